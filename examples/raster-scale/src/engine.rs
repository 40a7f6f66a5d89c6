//! The engine's frame loop with `steadyray-control` in it: ask the controller for a render
//! scale, draw at it, tell the controller how long the frame took and how much it drew.

use crate::gpu::Gpu;
use crate::load::Schedule;
use crate::timer::TimeSource;
use anyhow::{Context, Result};
use std::time::Duration;
use steadyray_control::{Action, Band, Bounds, Controller, FrameRecord, Setup, from_name};

/// The knobs a raster engine has: one sample, no bounces, a render scale from a quarter of
/// the window's resolution to all of it.
pub fn raster_bounds() -> Result<Bounds> {
    Bounds::scale_only(0.25, 1.0).context("the raster bounds are invalid")
}

/// A controller from a spec such as `predictive` or `fixed:scale=0.6`, aiming at `band`,
/// starting at full resolution.
pub fn controller(spec: &str, band: Band) -> Result<Box<dyn Controller>> {
    let bounds = raster_bounds()?;
    let setup = Setup::new(band, bounds, bounds.max_quality())?;
    let (name, options) = spec.split_once(':').unwrap_or((spec, ""));
    from_name(name, setup, options).with_context(|| format!("controller `{spec}`"))
}

/// One frame of the run as the summary keeps it.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// The controller's view of the frame (time, quality, work).
    pub record: FrameRecord,
    /// The load level the frame ran at.
    pub level: f64,
    /// Where its time came from.
    pub source: TimeSource,
    /// What the controller did after it (None for controllers that do not say).
    pub action: Option<Action>,
}

/// Draws frame `index` at the controller's scale and reports its time and pixels; None when
/// the window had no image to draw on (nothing is reported). With `log`, each change of
/// scale is printed with the controller's reason.
pub fn step(
    gpu: &mut Gpu,
    controller: &mut dyn Controller,
    schedule: &Schedule,
    index: u64,
    time_s: f32,
    log: bool,
) -> Result<Option<Frame>> {
    let quality = controller.quality();
    let Some(drawn) = gpu.frame(quality.scale, schedule.iterations(index), time_s)? else {
        return Ok(None);
    };
    controller
        .frame_done(Duration::from_secs_f64(drawn.ms / 1e3), drawn.pixels)
        .context("the controller refused the frame's report")?;
    let decision = controller.decision();
    if let Some(d) = decision.filter(|d| log && d.action != Action::Hold) {
        eprintln!("frame {index}: {d}");
    }
    Ok(Some(Frame {
        record: FrameRecord {
            frame: index as usize,
            tp_ms: drawn.ms,
            quality,
            rays: drawn.pixels,
        },
        level: schedule.level(index),
        source: drawn.source,
        action: decision.map(|d| d.action),
    }))
}
