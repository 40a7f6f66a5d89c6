//! The bench's costs measured before the runs: the hand-over (for a display-aligned band or
//! a `perceptual` controller choosing its frame time) and a warped refresh (for a band of
//! several refreshes with `--warp`, or such a controller).

use super::BenchConfig;
use super::plan::Plan;
use super::source::{FrameSource, PathPoint};
use anyhow::{Context, Result};
use steadyray_control::{ControllerSpec, Quality};

/// The costs measured before the runs, and the controllers told them.
pub struct Costs {
    /// The median hand-over at the start quality, ms, when measured.
    pub hand_over_ms: Option<f64>,
    /// The median warped refresh at the start quality, ms, when measured.
    pub warp_ms: Option<f64>,
    /// The controllers of the runs that warp: told the warp's cost where they lack it.
    pub warped_specs: Vec<ControllerSpec>,
}

/// Measures what the runs need measured at the plan's start quality and tells the
/// controllers that lack a cost: the hand-over to every run's, the warp to those of the runs
/// that warp (the runs without the history show no warps and are not told of any).
pub fn measure_costs(
    config: &BenchConfig,
    plan: &mut Plan,
    source: &mut dyn FrameSource,
) -> Result<Costs> {
    let frames = config.warmup.max(5);
    let needs_hand_over = plan.display.is_some()
        && (config.band.is_some() || plan.specs.iter().any(ControllerSpec::lacks_hand_over));
    let hand_over_ms = if needs_hand_over {
        Some(measure_hand_over(source, plan.start, frames)?)
    } else {
        None
    };
    if let Some(ms) = hand_over_ms {
        tell(&mut plan.specs, "hand_over", ms, "hand-over");
    }
    // Warped refreshes between frames run on the same machine as the frames.
    let needs_warp = config.warp
        && (config.band.is_some_and(|b| b.multiple > 1)
            || plan.specs.iter().any(ControllerSpec::lacks_warp));
    let mut warped_specs = plan.specs.clone();
    let warp_ms = match plan.display {
        Some(display) if needs_warp => {
            let period_s = display.period_ms() / 1000.0;
            let ms = measure_warp(source, plan.start, frames, period_s)?;
            tell(&mut warped_specs, "warp", ms, "warped refresh");
            Some(ms)
        }
        _ => None,
    };
    Ok(Costs {
        hand_over_ms,
        warp_ms,
        warped_specs,
    })
}

/// Tells every controller of `specs` lacking `key` the measured `ms`, saying so on stderr.
fn tell(specs: &mut [ControllerSpec], key: &str, ms: f64, what: &str) {
    for spec in specs.iter_mut() {
        if spec.tell_measured(key, ms) {
            eprintln!(
                "bench: {}: {what} {ms:.2} ms (median at the start quality)",
                spec.name
            );
        }
    }
}

/// The median of `measure(i)` over the calls i = `frames` to 2 · `frames` − 1, after as
/// many not kept (the first frames' buffers are still being allocated); `what` names it
/// in the error when nothing was measured.
fn median_after_warm_up(
    frames: u32,
    what: &str,
    mut measure: impl FnMut(u32) -> Result<f64>,
) -> Result<f64> {
    let mut times = Vec::new();
    for i in 0..2 * frames {
        let ms = measure(i)?;
        if i >= frames {
            times.push(ms);
        }
    }
    steadyray_display::stats::quantile(&times, 0.5)
        .with_context(|| format!("no frame to measure the {what}"))
}

/// The median hand-over cost of `frames` frames at the path's start at quality `q`, ms
/// (`median_after_warm_up`).
pub fn measure_hand_over(source: &mut dyn FrameSource, q: Quality, frames: u32) -> Result<f64> {
    median_after_warm_up(frames, "hand-over", |_| {
        source.frame(PathPoint::Time { index: 0, t_s: 0.0 }, q)?;
        Ok(source.hand_over()?.ms)
    })
}

/// The median cost of a warped refresh, ms (`median_after_warm_up`): frames at quality
/// `q` from the path's start, one refresh (`period_s`) apart, accumulated into a history
/// (moving, so that each resamples it, as in a run), each handed over and then warped to
/// the camera of the next refresh; the temporal mode is off again afterwards.
pub fn measure_warp(
    source: &mut dyn FrameSource,
    q: Quality,
    frames: u32,
    period_s: f64,
) -> Result<f64> {
    source.set_temporal(true)?;
    let ms = median_after_warm_up(frames, "warp", |i| {
        let t_s = f64::from(i) * period_s;
        let index = i as usize;
        source.frame(PathPoint::Time { index, t_s }, q)?;
        source.hand_over()?;
        Ok(source.warp(t_s + period_s, false)?.ms)
    })?;
    source.set_temporal(false)?;
    Ok(ms)
}
