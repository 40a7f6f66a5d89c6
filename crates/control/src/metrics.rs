//! The benchmark's figures (docs/bench-protocol.md) computed from a run's per-frame records.

use crate::band::{Band, Position};
use crate::quality::Quality;
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// Frames a run must stay in the band to count as settled after a load change.
pub const SETTLE_HOLD: usize = 10;
/// A frame-to-frame time ratio at unchanged quality that counts as a large load change.
pub const LOAD_JUMP: f64 = 1.5;

/// One frame of a run, as the metrics need it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameRecord {
    /// The frame's index in the run.
    pub frame: usize,
    /// Tp, ms (also the render time for `rays_per_s`).
    pub tp_ms: f64,
    /// The quality the frame was rendered with.
    pub quality: Quality,
    /// All rays traced (every depth and shadow rays).
    pub rays: u64,
}

/// The figures of one run (one controller over one sweep). Percentages are of all frames
/// given; times in ms. Serializable for `summary.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Frames in the run.
    pub frames: usize,
    /// Frames with Tmin <= Tp <= Tmax.
    pub in_band_pct: f64,
    /// Frames with Tp > Tmax.
    pub over_pct: f64,
    /// Frames with Tp < Tmin.
    pub under_pct: f64,
    /// Frames with Tp < Tmin already at the highest quality (not the controller's fault).
    pub under_at_max_pct: f64,
    /// Frames where no controller could do better: in_band_pct + under_at_max_pct.
    pub ok_pct: f64,
    /// Mean Tp.
    pub tp_mean: f64,
    /// Population standard deviation.
    pub tp_std: f64,
    /// Median Tp.
    pub tp_p50: f64,
    /// 95th percentile of Tp.
    pub tp_p95: f64,
    /// 99th percentile of Tp.
    pub tp_p99: f64,
    /// Largest Tp.
    pub tp_max: f64,
    /// Frames whose quality differs from the previous frame's.
    pub quality_changes: usize,
    /// Flips of the direction of quality change (up then down, or down then up), directions
    /// taken from [`Quality::cmp_level`].
    pub reversals: usize,
    /// `reversals` per 100 frames.
    pub reversals_per_100: f64,
    /// The longest run of consecutive frames over Tmax.
    pub longest_over_run: usize,
    /// Large load changes found (from the load profile, or detected: see [`summarize`]).
    pub settle_events: usize,
    /// Mean and largest frames from a load change until Tp is back in the band (or under it
    /// at the highest quality) and stays there [`SETTLE_HOLD`] frames; over settled events.
    pub settle_mean: Option<f64>,
    /// `None` when no event settled.
    pub settle_max: Option<usize>,
    /// Events after which the run never settled before its end.
    pub unsettled: usize,
    /// Mean eye rays per pixel (S) over the frames.
    pub mean_spp: f64,
    /// Mean reflection depth (R) over the frames.
    pub mean_depth: f64,
    /// Mean resolution scale over the frames.
    pub mean_scale: f64,
    /// All rays traced in the run (every depth and shadow rays).
    pub rays_total: u64,
    /// Rays traced per second of render time.
    pub rays_per_s: f64,
}

/// The `p`-quantile (0..=1) of sorted values, interpolating linearly between ranks.
fn quantile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let pos = p * (sorted.len() - 1) as f64;
    let (i, frac) = (pos.floor() as usize, pos.fract());
    let next = sorted[(i + 1).min(sorted.len() - 1)];
    sorted[i] + frac * (next - sorted[i])
}

/// Frames where the load changed a lot without the controller's doing: Tp changed by a
/// factor >= [`LOAD_JUMP`] from the previous frame at the same quality, leaving the band from
/// a frame that was fine (in the band, or under it at the highest quality `top`).
pub fn detect_load_changes(records: &[FrameRecord], band: Band, top: Quality) -> Vec<usize> {
    (1..records.len())
        .filter(|&i| {
            let (a, b) = (&records[i - 1], &records[i]);
            let (lo, hi) = (a.tp_ms.min(b.tp_ms), a.tp_ms.max(b.tp_ms));
            a.quality == b.quality
                && hi >= LOAD_JUMP * lo
                && ok(a, band, top)
                && !band.contains(b.tp_ms)
        })
        .collect()
}

/// Whether a frame is where a controller should keep it: in the band, or under it at the
/// highest quality.
fn ok(r: &FrameRecord, band: Band, top: Quality) -> bool {
    match band.position(r.tp_ms) {
        Position::In => true,
        Position::Under => r.quality.at_least(&top),
        Position::Over => false,
    }
}

/// Computes the figures of a run. `top` is the highest quality (a frame at or above it on
/// every knob is "at max"). `load_changes` lists the frames (indices into `records`) where
/// the load changed suddenly, when known (e.g. [`crate::simulate::LoadProfile::changes`]);
/// `None` detects them with [`detect_load_changes`].
pub fn summarize(
    records: &[FrameRecord],
    band: Band,
    top: Quality,
    load_changes: Option<&[usize]>,
) -> RunSummary {
    let n = records.len();
    let pct = |count: usize| {
        if n == 0 {
            0.0
        } else {
            100.0 * count as f64 / n as f64
        }
    };
    let count = |f: &dyn Fn(&FrameRecord) -> bool| records.iter().filter(|r| f(r)).count();
    let at_max = |r: &FrameRecord| r.quality.at_least(&top);
    let position = |r: &FrameRecord| band.position(r.tp_ms);

    let mut tp: Vec<f64> = records.iter().map(|r| r.tp_ms).collect();
    let mean_of = |f: &dyn Fn(&FrameRecord) -> f64| {
        if n == 0 {
            0.0
        } else {
            records.iter().map(f).sum::<f64>() / n as f64
        }
    };
    let tp_mean = mean_of(&|r| r.tp_ms);
    let tp_std = mean_of(&|r| (r.tp_ms - tp_mean).powi(2)).sqrt();
    tp.sort_by(f64::total_cmp);

    let mut quality_changes = 0;
    let mut reversals = 0;
    let mut last_dir = Ordering::Equal;
    for w in records.windows(2) {
        let dir = w[1].quality.cmp_level(&w[0].quality);
        if w[1].quality != w[0].quality {
            quality_changes += 1;
        }
        if dir != Ordering::Equal {
            if last_dir != Ordering::Equal && dir != last_dir {
                reversals += 1;
            }
            last_dir = dir;
        }
    }

    let mut longest_over_run = 0;
    let mut run = 0;
    for r in records {
        run = if position(r) == Position::Over {
            run + 1
        } else {
            0
        };
        longest_over_run = longest_over_run.max(run);
    }

    let detected;
    let events = match load_changes {
        Some(e) => e,
        None => {
            detected = detect_load_changes(records, band, top);
            &detected[..]
        }
    };
    let mut settles = Vec::new();
    let mut unsettled = 0;
    for &e in events.iter().filter(|&&e| e < n) {
        let settled = (e..n.saturating_sub(SETTLE_HOLD - 1))
            .find(|&j| records[j..j + SETTLE_HOLD].iter().all(|r| ok(r, band, top)));
        match settled {
            Some(j) => settles.push(j - e),
            None => unsettled += 1,
        }
    }

    let in_band_pct = pct(count(&|r| position(r) == Position::In));
    let under_at_max_pct = pct(count(&|r| position(r) == Position::Under && at_max(r)));
    let rays_total: u64 = records.iter().map(|r| r.rays).sum();
    let render_s: f64 = records.iter().map(|r| r.tp_ms).sum::<f64>() * 1e-3;
    RunSummary {
        frames: n,
        in_band_pct,
        over_pct: pct(count(&|r| position(r) == Position::Over)),
        under_pct: pct(count(&|r| position(r) == Position::Under)),
        under_at_max_pct,
        ok_pct: in_band_pct + under_at_max_pct,
        tp_mean,
        tp_std,
        tp_p50: quantile(&tp, 0.5),
        tp_p95: quantile(&tp, 0.95),
        tp_p99: quantile(&tp, 0.99),
        tp_max: tp.last().copied().unwrap_or(0.0),
        quality_changes,
        reversals,
        reversals_per_100: pct(reversals),
        longest_over_run,
        settle_events: events.iter().filter(|&&e| e < n).count(),
        settle_mean: (!settles.is_empty())
            .then(|| settles.iter().sum::<usize>() as f64 / settles.len() as f64),
        settle_max: settles.iter().copied().max(),
        unsettled,
        mean_spp: mean_of(&|r| f64::from(r.quality.spp)),
        mean_depth: mean_of(&|r| f64::from(r.quality.depth)),
        mean_scale: mean_of(&|r| f64::from(r.quality.scale)),
        rays_total,
        rays_per_s: if render_s > 0.0 {
            rays_total as f64 / render_s
        } else {
            0.0
        },
    }
}

/// The most-in-band fixed quality: the index of the candidate with the most frames in band
/// (ties go to the higher quality by [`Quality::cmp_level`]); `None` if there are no
/// candidates. It is chosen by frame time alone, not by how it looks.
pub fn most_in_band_fixed(candidates: &[(Quality, RunSummary)]) -> Option<usize> {
    (0..candidates.len()).max_by(|&a, &b| {
        let (qa, sa) = &candidates[a];
        let (qb, sb) = &candidates[b];
        sa.in_band_pct
            .total_cmp(&sb.in_band_pct)
            .then(qa.cmp_level(qb))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(frame: usize, tp_ms: f64, depth: u32) -> FrameRecord {
        FrameRecord {
            frame,
            tp_ms,
            quality: Quality::new(1.0, depth, 1.0),
            rays: 1000,
        }
    }

    #[test]
    fn counts_positions_and_statistics() {
        let band = Band::PAPER;
        let top = Quality::new(1.0, 4, 1.0);
        let r = vec![
            rec(0, 10.0, 4),
            rec(1, 10.0, 3),
            rec(2, 17.0, 3),
            rec(3, 25.0, 3),
            rec(4, 26.0, 3),
        ];
        let s = summarize(&r, band, top, Some(&[]));
        assert_eq!(s.frames, 5);
        assert_eq!(s.in_band_pct, 20.0);
        assert_eq!(s.over_pct, 40.0);
        assert_eq!(s.under_pct, 40.0);
        assert_eq!(s.under_at_max_pct, 20.0);
        assert_eq!(s.longest_over_run, 2);
        assert_eq!(s.tp_p50, 17.0);
        assert_eq!(s.tp_max, 26.0);
        assert!((s.tp_mean - 17.6).abs() < 1e-12);
        assert!((s.rays_per_s - 5000.0 / 0.088).abs() < 1e-6);
        assert_eq!(s.quality_changes, 1);
        assert_eq!(s.reversals, 0);
    }

    #[test]
    fn reversals_count_direction_flips() {
        let depths = [4, 3, 3, 4, 5, 4, 4, 4, 3];
        let r: Vec<FrameRecord> = depths
            .iter()
            .enumerate()
            .map(|(i, &d)| rec(i, 17.0, d))
            .collect();
        let s = summarize(&r, Band::PAPER, Quality::new(1.0, 16, 1.0), None);
        // down, up, up, down, down: two flips.
        assert_eq!(s.reversals, 2);
        assert_eq!(s.quality_changes, 5);
        assert!((s.reversals_per_100 - 200.0 / 9.0).abs() < 1e-9);
    }

    #[test]
    fn settle_counts_frames_until_ten_in_band() {
        let mut r: Vec<FrameRecord> = (0..40).map(|i| rec(i, 17.0, 3)).collect();
        r[5].tp_ms = 34.0; // load doubles at frame 5 ...
        r[6].tp_ms = 21.0; // ... one more frame over, then back in band.
        let top = Quality::new(1.0, 16, 1.0);
        let s = summarize(&r, Band::PAPER, top, Some(&[5]));
        assert_eq!(
            (s.settle_events, s.settle_max, s.unsettled),
            (1, Some(2), 0)
        );
        // Detection finds the same event from the jump at unchanged quality.
        assert_eq!(detect_load_changes(&r, Band::PAPER, top), vec![5]);
        let late = summarize(&r, Band::PAPER, top, Some(&[35]));
        assert_eq!((late.settle_events, late.unsettled), (1, 1));
    }

    #[test]
    fn most_in_band_fixed_prefers_in_band_then_quality() {
        let band = Band::PAPER;
        let top = Quality::new(1.0, 16, 1.0);
        let run = |tp: f64| summarize(&[rec(0, tp, 1)], band, top, Some(&[]));
        let c = vec![
            (Quality::new(1.0, 1, 1.0), run(30.0)),
            (Quality::new(1.0, 2, 1.0), run(17.0)),
            (Quality::new(1.0, 3, 1.0), run(17.0)),
            (Quality::new(1.0, 4, 1.0), run(12.0)),
        ];
        assert_eq!(most_in_band_fixed(&c), Some(2));
        assert_eq!(most_in_band_fixed(&[]), None);
    }
}
