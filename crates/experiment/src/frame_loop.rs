//! The one frame loop: quality → render → observe. A frame is rendered at the quality a
//! controller asks for (its resolution scale applied by [`RenderSettings::scaled`]), the
//! renderer's stats become the controller's [`FrameReport`], and one rule,
//! [`ControllerClock`], decides which time the controller sees. The bench, both
//! calibrations and the window (`steadyray view`) all render their frames through a
//! [`FrameLoop`]; each adds only where its camera and world time come from and what it does
//! with the frame.

use anyhow::Result;
use steadyray_control::{Controller, FrameReport, Quality, ReportError};
use steadyray_render::{FrameBudget, FrameStats, RenderSettings, Renderer, TimingSource};
use steadyray_scene::Camera;

/// GPU timestamps this far (ms) below the render call's wall time, and under a quarter of
/// it, are implausible.
const IMPLAUSIBLE_GAP_MS: f64 = 5.0;

/// Which time the controller sees for a frame: the renderer's own Tp (GPU timestamps, or the
/// wall clock around the render of the CPU renderer and of GPUs without timestamps), unless
/// GPU timestamps prove implausible: implausibly far below the render call's wall time
/// (lavapipe's, once frames are also presented on its queue, read about 0.3 ms for a 70 ms
/// frame). From the first implausible reading on, the controller sees the render call's
/// wall time for good: a timer that lied once is not trusted again.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ControllerClock {
    wall_clock: bool,
}

/// The time a controller sees for one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControllerTime {
    /// Tp as the controller sees it, ms.
    pub tp_ms: f64,
    /// Where it came from.
    pub source: TimingSource,
    /// Whether this frame's reading turned the clock to the wall time (for good).
    pub switched: bool,
}

impl ControllerClock {
    /// Whether GPU timestamps were found implausible: the controller sees wall time since.
    pub fn on_wall_clock(&self) -> bool {
        self.wall_clock
    }

    /// The time the controller sees for a frame of `stats` (see [`ControllerClock`]).
    pub fn time(&mut self, stats: &FrameStats) -> ControllerTime {
        let gpu = stats.timing == TimingSource::GpuTimestamps;
        let switched = gpu && !self.wall_clock && implausible(stats);
        self.wall_clock |= switched;
        if gpu && self.wall_clock {
            ControllerTime {
                tp_ms: stats.wall_ms,
                source: TimingSource::WallClock,
                switched,
            }
        } else {
            ControllerTime {
                tp_ms: stats.render_ms,
                source: stats.timing,
                switched,
            }
        }
    }
}

/// Whether `stats`'s GPU timestamps are implausibly far below the render call's wall time.
fn implausible(stats: &FrameStats) -> bool {
    stats.timing == TimingSource::GpuTimestamps
        && stats.wall_ms - stats.render_ms > IMPLAUSIBLE_GAP_MS
        && stats.render_ms < stats.wall_ms / 4.0
}

/// One frame rendered by the loop.
#[derive(Clone, Debug)]
pub struct LoopFrame {
    /// What the controller is shown (Tp by [`ControllerClock`]; no motion on screen: the
    /// caller measures it and fills `speed_deg_s` in).
    pub report: FrameReport,
    /// The renderer's own measurements.
    pub stats: FrameStats,
    /// The size and quality the frame was rendered at.
    pub settings: RenderSettings,
    /// Which time the controller sees, and whether this frame changed it.
    pub time: ControllerTime,
}

/// Renders frames of a full-scale size at the qualities a controller asks for and reports
/// them to it (see the module's documentation).
#[derive(Clone, Copy, Debug)]
pub struct FrameLoop {
    full: (u32, u32),
    clock: ControllerClock,
}

impl FrameLoop {
    /// A loop rendering frames of `full` pixels at resolution scale 1.
    pub fn new(full: (u32, u32)) -> Self {
        Self {
            full,
            clock: ControllerClock::default(),
        }
    }

    /// The full-scale size.
    pub fn full_size(&self) -> (u32, u32) {
        self.full
    }

    /// Changes the full-scale size (the window's, when it is resized).
    pub fn set_full_size(&mut self, full: (u32, u32)) {
        self.full = full;
    }

    /// The rule that decides which time the controller sees.
    pub fn clock(&self) -> &ControllerClock {
        &self.clock
    }

    /// The settings of a frame at quality `q`.
    pub fn settings(&self, q: Quality) -> RenderSettings {
        RenderSettings::scaled(self.full, q.scale, q.spp, q.depth)
    }

    /// Renders `camera` at world time `world_s` at quality `q` and builds the controller's
    /// report of it.
    pub fn render(
        &mut self,
        renderer: &mut dyn Renderer,
        camera: &Camera,
        world_s: f64,
        q: Quality,
    ) -> Result<LoopFrame> {
        self.render_within(renderer, camera, world_s, q, None)
    }

    /// [`FrameLoop::render`] within a frame's time `budget` when given
    /// ([`Renderer::set_frame_budget`]; the renderer is left without one after the frame):
    /// the report carries the S the frame reached.
    pub fn render_within(
        &mut self,
        renderer: &mut dyn Renderer,
        camera: &Camera,
        world_s: f64,
        q: Quality,
        budget: Option<FrameBudget>,
    ) -> Result<LoopFrame> {
        let settings = self.settings(q);
        let stats = match budget {
            None => renderer.render(camera, world_s, &settings)?,
            Some(budget) => {
                renderer.set_frame_budget(Some(budget))?;
                let stats = renderer.render(camera, world_s, &settings);
                renderer.set_frame_budget(None)?;
                stats?
            }
        };
        Ok(self.frame(stats, settings, q))
    }

    /// The loop's frame of a render's `stats` at `settings` (quality `q`): the report the
    /// controller sees, its Tp by [`ControllerClock`], its S the one the frame reached.
    pub fn frame(&mut self, stats: FrameStats, settings: RenderSettings, q: Quality) -> LoopFrame {
        let time = self.clock.time(&stats);
        let report = FrameReport {
            tp_ms: time.tp_ms,
            rays_per_depth: stats.rays.per_depth.clone(),
            shadow_rays: stats.rays.shadow,
            rays_stopped: Some(stats.rays.stopped),
            pixels: settings.pixels(),
            quality: Quality {
                spp: stats.spp,
                ..q
            },
            speed_deg_s: 0.0,
            first_sample: None,
        };
        LoopFrame {
            report,
            stats,
            settings,
            time,
        }
    }

    /// One turn of the loop: renders `camera` at world time `world_s` at the quality
    /// `controller` asks for, with `speed_deg_s` the frame's motion on screen (measured by
    /// the caller, outside the render's time), and shows the controller the report. The
    /// frame is returned with the controller's verdict on the report (a refused report
    /// leaves it as it was).
    pub fn step(
        &mut self,
        renderer: &mut dyn Renderer,
        controller: &mut dyn Controller,
        (camera, world_s): (&Camera, f64),
        speed_deg_s: impl FnOnce(&LoopFrame) -> Result<f64>,
    ) -> Result<(LoopFrame, Result<Quality, ReportError>)> {
        let q = controller.quality();
        let budget = controller.frame_budget();
        let mut frame = self.render_within(renderer, camera, world_s, q, budget)?;
        frame.report.speed_deg_s = speed_deg_s(&frame)?;
        let verdict = controller.observe(&frame.report);
        Ok((frame, verdict))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats(render_ms: f64, wall_ms: f64, timing: TimingSource) -> FrameStats {
        FrameStats {
            render_ms,
            accel_ms: 0.0,
            wall_ms,
            timing,
            rays: Default::default(),
            width: 1,
            height: 1,
            samples: 1,
            spp: 2.0,
        }
    }

    #[test]
    fn implausible_timestamps_give_way_to_the_wall_clock_for_good() {
        let gpu = TimingSource::GpuTimestamps;
        let wall = TimingSource::WallClock;
        let mut clock = ControllerClock::default();
        let seen = |clock: &mut ControllerClock, s| {
            let t = clock.time(&s);
            (t.tp_ms, t.source)
        };
        assert_eq!(seen(&mut clock, stats(16.0, 17.5, gpu)), (16.0, gpu));
        assert_eq!(
            seen(&mut clock, stats(0.4, 1.9, gpu)),
            (0.4, gpu),
            "small overhead"
        );
        assert!(!clock.on_wall_clock());
        let lavapipe = clock.time(&stats(0.3, 72.0, gpu));
        assert_eq!((lavapipe.tp_ms, lavapipe.source), (72.0, wall));
        assert!(lavapipe.switched && clock.on_wall_clock());
        // Plausible readings afterwards still give the wall time.
        let after = clock.time(&stats(16.0, 17.5, gpu));
        assert_eq!(
            (after.tp_ms, after.source, after.switched),
            (17.5, wall, false)
        );
    }

    #[test]
    fn the_cpu_renderers_time_is_its_own() {
        let wall = TimingSource::WallClock;
        let mut clock = ControllerClock::default();
        // The CPU renderer's Tp is its own wall clock around the render, whatever the call's.
        assert_eq!(clock.time(&stats(40.0, 41.0, wall)).tp_ms, 40.0);
        assert_eq!(clock.time(&stats(0.3, 72.0, wall)).tp_ms, 0.3);
        assert!(!clock.on_wall_clock());
    }

    #[test]
    fn reports_carry_the_rays_pixels_and_quality_of_the_frame() {
        let mut frame_loop = FrameLoop::new((160, 90));
        let q = Quality::new(2.0, 4, 0.5);
        let settings = frame_loop.settings(q);
        assert_eq!((settings.width, settings.height), (80, 45));
        let mut s = stats(12.0, 13.0, TimingSource::GpuTimestamps);
        s.rays.per_depth = vec![100, 40];
        s.rays.shadow = 7;
        let frame = frame_loop.frame(s, settings, q);
        assert_eq!(frame.report.tp_ms, 12.0);
        assert_eq!(frame.report.rays_per_depth, vec![100, 40]);
        assert_eq!(frame.report.shadow_rays, 7);
        assert_eq!(frame.report.pixels, 80 * 45);
        assert_eq!(frame.report.quality, q);
    }
}
