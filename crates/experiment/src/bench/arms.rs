//! The bench's bands and arms: the band of the runs that warp and of those that do not (the
//! same band unless a display-aligned band leaves room for warps), and one set of
//! controllers per temporal mode.

use super::BenchConfig;
use super::costs::Costs;
use super::plan::Plan;
use super::report::AlignedBand;
use anyhow::{Result, bail};
use steadyray_control::{Band, Controller, Setup};
use steadyray_display::{DisplayConfig, RefreshBand, aligned_band};

/// The bands of a bench's runs.
#[derive(Clone, Copy, Debug)]
pub struct Bands {
    /// The band of the runs that warp (and of every run without `--warp`).
    pub band: Band,
    /// The band of the runs without the history, which show no warps.
    pub plain: Band,
    /// How `--band refresh[:M]` derived them, when it did.
    pub aligned: Option<AlignedBand>,
}

/// The runs of one temporal mode: with the history (and, with `--warp`, its warped
/// refreshes) or without, their band and their controllers (one per `--controllers` entry,
/// in order).
pub struct Arm {
    /// Whether the runs accumulate a temporal history.
    pub temporal: bool,
    /// Their band.
    pub band: Band,
    /// Their controllers' set-up.
    pub setup: Setup,
    /// Their controllers.
    pub controllers: Vec<Box<dyn Controller>>,
}

impl Bands {
    /// The bands: `--tmin`/`--tmax`, or derived from the display and the measured costs
    /// (`--band refresh[:M]`, said on stderr).
    pub fn derive(config: &BenchConfig, plan: &Plan, costs: &Costs) -> Result<Self> {
        match (&config.band, &plan.display, costs.hand_over_ms) {
            (None, _, _) => {
                let band = Band::new(config.tmin, config.tmax)?;
                Ok(Self {
                    band,
                    plain: band,
                    aligned: None,
                })
            }
            (Some(_), None, _) => bail!("--band refresh needs --clock real"),
            (Some(_), Some(_), None) => bail!("the hand-over was not measured"),
            (Some(choice), Some(display), Some(hand_over_ms)) => {
                let warp_ms = match costs.warp_ms {
                    Some(ms) if choice.multiple > 1 => ms,
                    _ => 0.0,
                };
                let plain_runs = config.temporal.modes().contains(&false);
                aligned(display, *choice, (hand_over_ms, warp_ms), plain_runs)
            }
        }
    }
}

/// The bands aligned with `display` for frames every `choice.multiple`-th refresh, leaving
/// room for the hand-over and (in the runs that warp) the warps; said on stderr.
fn aligned(
    display: &DisplayConfig,
    choice: RefreshBand,
    (hand_over_ms, warp_ms): (f64, f64),
    plain_runs: bool,
) -> Result<Bands> {
    let band_with = |warp_ms| -> Result<Band> {
        let (tmin, tmax) = aligned_band(display, choice.multiple, hand_over_ms, warp_ms)?;
        Ok(Band::new(tmin, tmax)?)
    };
    let band = band_with(warp_ms)?;
    let plain = band_with(0.0)?;
    let (tmin, tmax) = (band.tmin_ms(), band.tmax_ms());
    let costs = if warp_ms > 0.0 {
        let warps = choice.multiple - 1;
        format!("hand-over {hand_over_ms:.2} ms, {warps} warp(s) of {warp_ms:.2} ms (medians")
    } else {
        format!("hand-over {hand_over_ms:.2} ms (median")
    };
    // Runs without the history in a band of their own.
    let plain_runs = plain != band && plain_runs;
    let plain_text = if plain_runs {
        format!(
            "; runs without the history (no warps): [{:.2}, {:.2}] ms",
            plain.tmin_ms(),
            plain.tmax_ms()
        )
    } else {
        String::new()
    };
    eprintln!(
        "bench: --band {choice}: {costs} at the start quality), band [{tmin:.2}, {tmax:.2}] ms{plain_text}"
    );
    Ok(Bands {
        band,
        plain,
        aligned: Some(AlignedBand {
            refreshes: choice.multiple,
            hand_over_ms,
            warp_ms,
            plain_band_ms: plain_runs.then(|| [plain.tmin_ms(), plain.tmax_ms()]),
        }),
    })
}

/// One set of controllers per temporal mode: a run with the history and its warps (in the
/// band and with the controllers told of warps), or without.
pub fn build_arms(
    config: &BenchConfig,
    plan: &Plan,
    costs: &Costs,
    bands: &Bands,
) -> Result<Vec<Arm>> {
    let mut arms = Vec::new();
    for &temporal in config.temporal.modes() {
        let (band, specs) = match temporal && config.warp {
            true => (bands.band, &costs.warped_specs),
            false => (bands.plain, &plan.specs),
        };
        let (setup, controllers) = plan.build(band, specs)?;
        arms.push(Arm {
            temporal,
            band,
            setup,
            controllers,
        });
    }
    Ok(arms)
}
