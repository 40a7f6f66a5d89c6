//! Fits a [`NoiseProfile`] to the frame times of fixed-quality runs.
//!
//! - **Jitter and spikes**: each frame against the mean of its two neighbours,
//!   l = ln(t_i) − ln((t_(i−1) + t_(i+1)) / 2). Over a smooth sweep the neighbours share the
//!   frame's view and the machine's spell, so l holds the jitter (variance 1.5·σ² for
//!   independent jitter of σ) and the spikes. σ comes from the median absolute deviation of l
//!   (robust to the spikes); frames more than [`SPIKE_K`] of l's deviations above its median
//!   are spikes, and their l the log of their factor.
//! - **Spells**: two runs of the same frames (same sweep, same quality) differ only in the
//!   machine's noise: d = ln(a_i) − ln(b_i) holds two independent spell processes and two
//!   jitters. The jitter is independent from frame to frame, so the autocovariance of d at
//!   lags k ≥ 1 is 2·σ_s²·ρ^k for spells of spread σ_s and per-frame correlation ρ: a line
//!   fitted to its logarithm over lags 1 to [`MAX_LAG`] gives both; ρ becomes a correlation
//!   time through the runs' mean frame time. Spikes are clipped out of d first.

use super::profile::{NoiseError, NoiseProfile};

/// A frame whose log ratio to its neighbours lies this many robust deviations above the
/// median is a spike.
pub const SPIKE_K: f64 = 4.0;
/// The largest lag of the spells' autocovariance fit.
pub const MAX_LAG: usize = 24;
/// The fewest frames a fit accepts.
pub const MIN_FIT_FRAMES: usize = 50;
/// The smallest spell spread reported; below it the two runs show no spells.
const MIN_SPELL_SIGMA: f64 = 1e-3;

/// A fitted profile with the measurements it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct NoiseFit {
    /// The fitted profile.
    pub profile: NoiseProfile,
    /// Frames against the mean of their neighbours: the ratio's 5th, 50th, 95th and 99th
    /// percentiles (all runs together).
    pub neighbour_ratio: [f64; 4],
    /// The same frame in the two runs, first over second: 5th, 50th and 95th percentiles
    /// (`None` from one run).
    pub run_ratio: Option<[f64; 3]>,
    /// Frames counted as spikes, and frames looked at.
    pub spikes: usize,
    /// Frames looked at (all runs together).
    pub frames: usize,
}

/// A description of the spikes found, for reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpikeFit {
    /// Fraction of frames that are spikes.
    pub prob: f64,
    /// Mean and standard deviation of their log factor.
    pub log_mean: f64,
    /// Standard deviation of the spikes' log factor.
    pub log_sd: f64,
}

/// Fits a profile to `first`, the frame times (ms) of a fixed-quality run over a smooth
/// sweep, and, when given, `second`, a second run of the same frames (needed for the spells:
/// from one run they stay 0). `mean_gap_ms` is the time from one frame's start to the next's
/// beyond its own time (presenting, the bench's bookkeeping), 0 if unknown. `machine` and
/// `recorded` describe the recording. Errors on too few frames, a bad time or runs of
/// different lengths.
pub fn fit_profile(
    first: &[f64],
    second: Option<&[f64]>,
    mean_gap_ms: f64,
    machine: &str,
    recorded: &str,
) -> Result<NoiseFit, NoiseError> {
    check_frames(first)?;
    let runs: Vec<&[f64]> = match second {
        Some(b) => {
            check_frames(b)?;
            if b.len() != first.len() {
                return Err(NoiseError::RunsDiffer {
                    first: first.len(),
                    second: b.len(),
                });
            }
            vec![first, b]
        }
        None => vec![first],
    };
    let logs: Vec<f64> = runs.iter().flat_map(|r| neighbour_logs(r)).collect();
    let (centre, spread) = robust_centre_spread(&logs);
    let threshold = centre + SPIKE_K * spread;
    let spike_logs: Vec<f64> = logs
        .iter()
        .filter(|&&l| l > threshold)
        .map(|l| l - centre)
        .collect();
    let spikes = fit_spikes(&spike_logs, logs.len());
    let mean_ms = runs.iter().flat_map(|r| r.iter()).sum::<f64>()
        / runs.iter().map(|r| r.len()).sum::<usize>() as f64
        + mean_gap_ms.max(0.0);
    let (spell_sigma, spell_ms, run_ratio) = match second {
        Some(b) => {
            let (sigma, ms) = fit_spells(first, b, mean_ms);
            let mut ratios: Vec<f64> = first.iter().zip(b).map(|(a, b)| a / b).collect();
            let q = percentiles(&mut ratios, &[0.05, 0.5, 0.95]);
            (sigma, ms, Some([q[0], q[1], q[2]]))
        }
        None => (0.0, 1000.0, None),
    };
    let mut ratios: Vec<f64> = logs.iter().map(|l| l.exp()).collect();
    let q = percentiles(&mut ratios, &[0.05, 0.5, 0.95, 0.99]);
    let profile = NoiseProfile {
        machine: machine.to_string(),
        recorded: recorded.to_string(),
        jitter_sigma: (spread / 1.5f64.sqrt()).min(1.0),
        spike_prob: spikes.prob,
        spike_log_mean: spikes.log_mean.min(5.0),
        spike_log_sd: spikes.log_sd.min(1.0),
        spell_sigma: spell_sigma.min(1.0),
        spell_ms,
    };
    profile.validate()?;
    Ok(NoiseFit {
        profile,
        neighbour_ratio: [q[0], q[1], q[2], q[3]],
        run_ratio,
        spikes: spike_logs.len(),
        frames: logs.len(),
    })
}

/// Every frame time finite and positive, and enough of them.
fn check_frames(frames: &[f64]) -> Result<(), NoiseError> {
    if frames.len() < MIN_FIT_FRAMES {
        return Err(NoiseError::TooFewFrames {
            got: frames.len(),
            needed: MIN_FIT_FRAMES,
        });
    }
    match frames.iter().position(|t| !(t.is_finite() && *t > 0.0)) {
        Some(index) => Err(NoiseError::BadFrameTime {
            index,
            value: frames[index],
        }),
        None => Ok(()),
    }
}

/// ln of each inner frame's time over the mean of its two neighbours'.
fn neighbour_logs(frames: &[f64]) -> Vec<f64> {
    frames
        .windows(3)
        .map(|w| (w[1] / (0.5 * (w[0] + w[2]))).ln())
        .collect()
}

/// The spike probability and log factor's mean and spread from the spikes' logs.
fn fit_spikes(spike_logs: &[f64], frames: usize) -> SpikeFit {
    if spike_logs.is_empty() {
        return SpikeFit {
            prob: 0.0,
            log_mean: 0.0,
            log_sd: 0.0,
        };
    }
    let n = spike_logs.len() as f64;
    let log_mean = spike_logs.iter().sum::<f64>() / n;
    let var = spike_logs
        .iter()
        .map(|l| (l - log_mean).powi(2))
        .sum::<f64>()
        / n;
    SpikeFit {
        prob: n / frames as f64,
        log_mean,
        log_sd: var.sqrt(),
    }
}

/// Spell spread and correlation time (ms) from two runs of the same frames, frames
/// `mean_ms` apart; (0, 1000) when the runs show none.
fn fit_spells(a: &[f64], b: &[f64], mean_ms: f64) -> (f64, f64) {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| (x / y).ln()).collect();
    let (centre, spread) = robust_centre_spread(&d);
    let clip = SPIKE_K * spread.max(1e-9);
    let clipped: Vec<f64> = d.iter().map(|v| (v - centre).clamp(-clip, clip)).collect();
    let mean = clipped.iter().sum::<f64>() / clipped.len() as f64;
    let centred: Vec<f64> = clipped.iter().map(|v| v - mean).collect();
    let acov = |k: usize| {
        centred
            .iter()
            .zip(&centred[k..])
            .map(|(x, y)| x * y)
            .sum::<f64>()
            / (centred.len() - k) as f64
    };
    let points: Vec<(f64, f64)> = (1..=MAX_LAG.min(centred.len() / 4))
        .map(|k| (k as f64, acov(k)))
        .take_while(|&(_, c)| c > 0.0)
        .map(|(k, c)| (k, c.ln()))
        .collect();
    if points.len() < 2 {
        return (0.0, 1000.0);
    }
    let (slope, intercept) = line_fit(&points);
    let rho = slope.exp().clamp(1e-3, 0.999);
    // The intercept is ln(2·σ_s²) (two runs' spells).
    let sigma = (0.5 * intercept.exp()).sqrt();
    if sigma < MIN_SPELL_SIGMA {
        return (0.0, 1000.0);
    }
    (sigma, -mean_ms.max(1e-3) / rho.ln())
}

/// Least-squares slope and intercept of y on x.
fn line_fit(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (slope, my - slope * mx)
}

/// Median and robust standard deviation (1.4826 · median absolute deviation).
fn robust_centre_spread(values: &[f64]) -> (f64, f64) {
    let mut v = values.to_vec();
    let centre = percentiles(&mut v, &[0.5])[0];
    let mut dev: Vec<f64> = values.iter().map(|x| (x - centre).abs()).collect();
    (centre, 1.4826 * percentiles(&mut dev, &[0.5])[0])
}

/// The given quantiles of `values` (sorted in place; nearest rank).
fn percentiles(values: &mut [f64], quantiles: &[f64]) -> Vec<f64> {
    values.sort_by(f64::total_cmp);
    let last = values.len().saturating_sub(1);
    quantiles
        .iter()
        .map(|q| {
            values
                .get((q * last as f64).round() as usize)
                .copied()
                .unwrap_or(f64::NAN)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::noise::NoiseProcess;

    /// A smooth sweep's noise-free frame times (a slow swing between 12 and 28 ms).
    fn sweep(frames: usize) -> Vec<f64> {
        (0..frames)
            .map(|i| 20.0 + 8.0 * (std::f64::consts::TAU * i as f64 / frames as f64).sin())
            .collect()
    }

    fn noisy(profile: &NoiseProfile, seed: u64, ideal: &[f64]) -> Vec<f64> {
        let mut noise = NoiseProcess::new(profile.clone(), seed);
        ideal.iter().map(|t| t * noise.factor(t + 3.0)).collect()
    }

    #[test]
    fn a_fit_recovers_the_noise_it_was_drawn_from() {
        let truth = NoiseProfile {
            jitter_sigma: 0.04,
            spike_prob: 0.02,
            spike_log_mean: 0.4,
            spike_log_sd: 0.1,
            spell_sigma: 0.08,
            spell_ms: 1500.0,
            ..NoiseProfile::quiet("truth")
        };
        let ideal = sweep(6000);
        let (a, b) = (noisy(&truth, 1, &ideal), noisy(&truth, 2, &ideal));
        let fit = fit_profile(&a, Some(&b), 3.0, "m", "r").unwrap().profile;
        let near = |got: f64, want: f64, tol: f64| (got - want).abs() <= tol * want;
        assert!(near(fit.jitter_sigma, 0.04, 0.2), "{fit:?}");
        assert!(near(fit.spike_prob, 0.02, 0.35), "{fit:?}");
        assert!(near(fit.spike_log_mean, 0.4, 0.25), "{fit:?}");
        assert!(near(fit.spell_sigma, 0.08, 0.35), "{fit:?}");
        assert!(near(fit.spell_ms, 1500.0, 0.6), "{fit:?}");
    }

    #[test]
    fn one_run_fits_no_spells_and_bad_frames_are_named() {
        let fit = fit_profile(&sweep(200), None, 0.0, "m", "r").unwrap();
        assert_eq!(fit.profile.spell_sigma, 0.0);
        assert!(fit.run_ratio.is_none());
        assert!(fit.profile.jitter_sigma < 1e-3);
        let mut bad = sweep(200);
        bad[7] = f64::NAN;
        let err = fit_profile(&bad, None, 0.0, "m", "r").unwrap_err();
        assert!(
            matches!(err, NoiseError::BadFrameTime { index: 7, .. }),
            "{err}"
        );
        assert!(matches!(
            fit_profile(&sweep(10), None, 0.0, "m", "r"),
            Err(NoiseError::TooFewFrames { got: 10, .. })
        ));
        assert!(matches!(
            fit_profile(&sweep(200), Some(&sweep(100)), 0.0, "m", "r"),
            Err(NoiseError::RunsDiffer { .. })
        ));
    }
}
