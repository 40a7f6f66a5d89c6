//! The engine's frame loop with `steadyray-control` in it: ask the controller for a render
//! scale, draw at it, tell the controller how long the frame took and how much it drew.

use crate::gpu::{Drawn, Gpu};
use crate::load::Schedule;
use crate::timer::TimeSource;
use anyhow::{Context, Result};
use steadyray_control::{
    Band, Bounds, Controller, FrameRecord, FrameReport, Quality, Setup, from_name,
};

/// The knobs a raster engine has: one sample, no bounces, a render scale from a quarter of
/// the window's resolution to all of it.
pub fn raster_bounds() -> Result<Bounds> {
    Bounds::new((1.0, 1.0), (0, 0), (0.25, 1.0)).context("the raster bounds are invalid")
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
}

/// Draws frame `index` at the controller's scale and reports it; None when the window had
/// no image to draw on (nothing is reported).
pub fn step(
    gpu: &mut Gpu,
    controller: &mut dyn Controller,
    schedule: &Schedule,
    index: u64,
    time_s: f32,
) -> Result<Option<Frame>> {
    let quality = controller.quality();
    let Some(drawn) = gpu.frame(quality.scale, schedule.iterations(index), time_s)? else {
        return Ok(None);
    };
    controller
        .observe(&report(&drawn, quality))
        .context("the controller refused the frame's report")?;
    Ok(Some(Frame {
        record: FrameRecord {
            frame: index as usize,
            tp_ms: drawn.ms,
            quality,
            rays: drawn.pixels,
        },
        level: schedule.level(index),
        source: drawn.source,
    }))
}

/// What the controller is told: the frame time and the work done, as pixels shaded (one
/// sample each, no bounces: the only "rays" a raster pass has).
fn report(drawn: &Drawn, quality: Quality) -> FrameReport {
    FrameReport {
        tp_ms: drawn.ms,
        rays_per_depth: vec![drawn.pixels],
        shadow_rays: 0,
        rays_stopped: None,
        pixels: drawn.pixels,
        quality,
        speed_deg_s: 0.0,
    }
}
