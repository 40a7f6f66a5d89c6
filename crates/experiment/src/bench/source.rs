//! Where the experiment's frames come from: a real renderer over the scene's camera path, or
//! the control crate's simulated renderer on a fake clock (`bench --simulate`).

use super::reference_store::digest;
use crate::frame_loop::{FrameLoop, LoopFrame};
use anyhow::{Result, bail};
use std::f64::consts::TAU;
use std::time::Instant;
use steadyray_control::simulate::{RendererModel, SimRenderer, corridor_load};
use steadyray_control::{FrameReport, Quality};
use steadyray_motion::{MotionTracker, ScreenSpeed, Shot};
use steadyray_quality::Rgb8Image;
use steadyray_render::{FrameBudget, Picture, Presented, Renderer, SampleStream, TemporalSettings};
use steadyray_scene::{Camera, Scene};

/// One rendered (or simulated) frame as the experiment sees it.
pub struct Measured {
    /// What the controller is shown.
    pub report: FrameReport,
    /// Host wall time of the render call, ms.
    pub wall_ms: f64,
    /// The part of Tp spent on moving objects' top-level BVH, ms.
    pub accel_ms: f64,
    /// Camera yaw of the frame, radians.
    pub angle: f32,
    /// The frame's motion on screen since the frame rendered before it (0 from a source
    /// that does not measure it: the simulated renderer).
    pub speed: ScreenSpeed,
}

/// A frame handed to the display: its cost and, from a renderer, the picture.
pub struct HandOver {
    /// What handing the frame over cost, ms (see [`FrameSource::hand_over`]).
    pub ms: f64,
    /// The tone-mapped 8-bit frame at its rendered size, or `None` from a source without
    /// images (the simulated renderer).
    pub image: Option<Rgb8Image>,
}

/// Where on the camera path a frame is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathPoint {
    /// Frame `k` of an `n`-frame sweep (the frame clock, the paper's protocol).
    Frame {
        /// The frame's index.
        k: u32,
        /// Frames in the sweep.
        n: u32,
    },
    /// The path at `t_s` seconds (the real clock); `index` numbers the frame in its run.
    Time {
        /// The frame's index in its run.
        index: usize,
        /// The path's time, s.
        t_s: f64,
    },
}

/// A source of frames at any quality along a fixed camera path.
pub trait FrameSource {
    /// The backend and device, for reports.
    fn describe(&self) -> (String, String);
    /// A digest of the world drawn (the whole scene), naming it for references kept between
    /// benches (`--references`); `None` for a source without images.
    fn world_digest(&self) -> Option<String> {
        None
    }
    /// Full-scale image size.
    fn resolution(&self) -> (u32, u32);
    /// The camera path's length in seconds (its default frames at 60 per second).
    fn path_duration_s(&self) -> f64;
    /// Renders the frame at `at` at quality `q`.
    fn frame(&mut self, at: PathPoint, q: Quality) -> Result<Measured> {
        self.frame_within(at, q, None)
    }
    /// Renders the frame at `at` at quality `q` within a time `budget` when given (a
    /// controller's [`steadyray_control::Controller::frame_budget`]): the report carries
    /// the S the frame reached. A source that cannot honour a budget fails.
    fn frame_within(
        &mut self,
        at: PathPoint,
        q: Quality,
        budget: Option<FrameBudget>,
    ) -> Result<Measured>;
    /// Hands the last frame to the display and measures what that costs: a renderer's own
    /// way to a window (`Renderer::present`), with its picture read back for the scores
    /// outside that time; the simulated renderer takes [`SIM_HAND_OVER_MS`].
    fn hand_over(&mut self) -> Result<HandOver>;
    /// Hands the last frame to the display again as the camera at path time `t_s` sees it,
    /// for a refresh that has no new frame (`Renderer::present_warped`), and measures what
    /// that costs, with its picture (when `picture`) read back outside that time; the
    /// simulated renderer takes [`SIM_WARP_MS`].
    fn warp(&mut self, t_s: f64, picture: bool) -> Result<HandOver>;
    /// Whether a frame's Tp and hand-over are wall time spent in these calls (a renderer),
    /// not a simulated time: only then is their share of a run's wall time a measurement.
    fn takes_wall_time(&self) -> bool;
    /// Frames where the load changes suddenly by construction, when known.
    fn load_changes(&self, n: u32) -> Option<Vec<usize>>;
    /// The last frame's 8-bit picture at its rendered size, as the backend's display shows it
    /// ([`read_picture`], outside any timing), or `None` for a source without images (the
    /// simulated renderer).
    fn last_picture(&mut self) -> Result<Option<Rgb8Image>>;
    /// Turns the temporal mode on (a new history at the full-scale size: every frame is
    /// accumulated into it) or off.
    fn set_temporal(&mut self, on: bool) -> Result<()>;
    /// Chooses the samples plain frames draw (`Renderer::set_sample_stream`); a source
    /// without samples (the simulated renderer) ignores it.
    fn set_sample_stream(&mut self, stream: SampleStream);
}

/// Renders the reference of the world at `at` at quality `q` and returns its picture at its
/// rendered size (`None` for a source without images). It draws the samples reserved for
/// references ([`SampleStream::Reference`]), so that no frame it judges shares its noise;
/// the source draws the frames' samples again afterwards.
pub fn render_reference(
    source: &mut dyn FrameSource,
    at: PathPoint,
    q: Quality,
) -> Result<Option<Rgb8Image>> {
    source.set_sample_stream(SampleStream::Reference);
    let picture = source.frame(at, q).and_then(|_| source.last_picture());
    source.set_sample_stream(SampleStream::Frames);
    picture
}

/// The simulated renderer's hand-over cost, ms.
pub const SIM_HAND_OVER_MS: f64 = 1.0;

/// The simulated renderer's cost of a warped refresh, ms.
pub const SIM_WARP_MS: f64 = 0.5;

/// Frames from a real renderer.
pub struct RendererSource {
    /// The renderer drawing the frames.
    pub renderer: Box<dyn Renderer>,
    /// The scene, with its camera path.
    pub scene: Scene,
    /// Renders the frames at the full-scale size and says which time the controller sees.
    pub frame_loop: FrameLoop,
    /// Measures each frame's motion on screen since the frame rendered before it (outside
    /// the render's time).
    pub motion: MotionTracker,
}

impl FrameSource for RendererSource {
    fn describe(&self) -> (String, String) {
        let info = self.renderer.info();
        (info.backend, info.device)
    }

    fn resolution(&self) -> (u32, u32) {
        self.frame_loop.full_size()
    }

    fn world_digest(&self) -> Option<String> {
        Some(digest(&format!("{:?}", self.scene)))
    }

    fn path_duration_s(&self) -> f64 {
        self.scene.path.duration_s()
    }

    fn frame_within(
        &mut self,
        at: PathPoint,
        q: Quality,
        budget: Option<FrameBudget>,
    ) -> Result<Measured> {
        let (camera, time_s) = match at {
            PathPoint::Frame { k, n } => {
                (self.scene.camera_at(k, n), self.scene.path.frame_time(k, n))
            }
            PathPoint::Time { t_s, .. } => (self.scene.camera_at_time(t_s), t_s),
        };
        let mut measured = render_measured(
            &mut self.frame_loop,
            self.renderer.as_mut(),
            &camera,
            time_s,
            (q, budget),
        )?;
        measured.speed = self.motion.next(Shot::at(camera, time_s))?;
        measured.report.speed_deg_s = measured.speed.mean_deg_s;
        Ok(measured)
    }

    fn hand_over(&mut self) -> Result<HandOver> {
        let start = Instant::now();
        let presented = self.renderer.present()?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        // The picture the bench keeps for its scores: the one presented when it reached the
        // host, else the device's picture read back now (outside the hand-over's time).
        let picture = match presented {
            Presented::Host(picture) => rgb8(picture)?,
            Presented::Device => read_picture(self.renderer.as_mut())?,
        };
        Ok(HandOver {
            ms,
            image: Some(picture),
        })
    }

    fn warp(&mut self, t_s: f64, picture: bool) -> Result<HandOver> {
        let camera = self.scene.camera_at_time(t_s);
        warp_measured(self.renderer.as_mut(), &camera, picture)
    }

    fn takes_wall_time(&self) -> bool {
        true
    }

    fn load_changes(&self, _n: u32) -> Option<Vec<usize>> {
        None
    }

    fn last_picture(&mut self) -> Result<Option<Rgb8Image>> {
        Ok(Some(read_picture(self.renderer.as_mut())?))
    }

    fn set_temporal(&mut self, on: bool) -> Result<()> {
        set_history(self.renderer.as_mut(), self.frame_loop.full_size(), on)
    }

    fn set_sample_stream(&mut self, stream: SampleStream) {
        self.renderer.set_sample_stream(stream);
    }
}

/// `renderer`'s last frame handed to the display again as `camera` sees it
/// (`Renderer::present_warped`): what that cost, ms, and, when `picture`, the picture, read
/// back outside that time when it stayed on the device (a warp whose picture no score or
/// video keeps is not read back).
pub fn warp_measured(
    renderer: &mut dyn Renderer,
    camera: &Camera,
    picture: bool,
) -> Result<HandOver> {
    let start = Instant::now();
    let presented = renderer.present_warped(camera)?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let image = match (picture, presented) {
        (false, _) => None,
        (true, Presented::Host(picture)) => Some(rgb8(picture)?),
        (true, Presented::Device) => Some(read_picture(renderer)?),
    };
    Ok(HandOver { ms, image })
}

/// The last frame's picture as `renderer`'s display shows it (`Renderer::read_picture`), as
/// the RGB image the scores and videos take.
pub fn read_picture(renderer: &mut dyn Renderer) -> Result<Rgb8Image> {
    rgb8(renderer.read_picture()?)
}

/// A renderer's picture as the RGB image the scores and videos take.
fn rgb8(picture: Picture) -> Result<Rgb8Image> {
    Ok(Rgb8Image::from_rgba(
        picture.width,
        picture.height,
        &picture.rgba,
    )?)
}

/// Renders `camera` at scene time `time_s` at quality `q` within `budget`, if any, through
/// `frame_loop` (its full-scale size scaled by `q.scale`, the controller's time by its
/// rule) and measures it: no motion on screen yet (the caller measures it).
pub fn render_measured(
    frame_loop: &mut FrameLoop,
    renderer: &mut dyn Renderer,
    camera: &Camera,
    time_s: f64,
    (q, budget): (Quality, Option<FrameBudget>),
) -> Result<Measured> {
    let frame = frame_loop.render_within(renderer, camera, time_s, q, budget)?;
    Ok(Measured::of(frame, camera))
}

impl Measured {
    /// The bench's measurement of a frame of the loop, which showed `camera`: the report
    /// the controller sees, the render call's wall time and the BVH's share of Tp.
    pub fn of(frame: LoopFrame, camera: &Camera) -> Self {
        let f = camera.forward;
        Self {
            report: frame.report,
            wall_ms: frame.stats.wall_ms,
            accel_ms: frame.stats.accel_ms,
            angle: (-f.x).atan2(-f.z).rem_euclid(std::f32::consts::TAU),
            speed: ScreenSpeed::default(),
        }
    }
}

/// Turns the temporal mode of `renderer` on (a new history of `full` pixels) or off.
pub fn set_history(
    renderer: &mut dyn Renderer,
    (width, height): (u32, u32),
    on: bool,
) -> Result<()> {
    let history = TemporalSettings { width, height };
    Ok(renderer.set_temporal(on.then_some(history))?)
}

/// Frames from the simulated renderer: a cost model driven by the corridor-shaped load.
pub struct SimulatedSource {
    /// The simulated renderer.
    pub renderer: SimRenderer,
    /// Frames of the sweep: the path lasts frames / 60 s.
    pub frames: u32,
}

impl FrameSource for SimulatedSource {
    fn describe(&self) -> (String, String) {
        let m = self.renderer.model();
        (
            "simulated".into(),
            format!(
                "cost model: {} ms + {} ns/ray, noise {}, timer {} ms",
                m.fixed_ms, m.ns_per_ray, m.noise, m.timer_ms
            ),
        )
    }

    fn resolution(&self) -> (u32, u32) {
        let pixels = self.renderer.model().full_pixels;
        let height = ((pixels as f64 * 9.0 / 16.0).sqrt().round() as u32).max(1);
        ((pixels / height as u64) as u32, height)
    }

    fn path_duration_s(&self) -> f64 {
        f64::from(self.frames) / 60.0
    }

    fn frame_within(
        &mut self,
        at: PathPoint,
        q: Quality,
        budget: Option<FrameBudget>,
    ) -> Result<Measured> {
        let (index, load, turn) = match at {
            PathPoint::Frame { k, n } => (
                k as usize,
                self.renderer.model().profile.load(k as usize),
                f64::from(k) / f64::from(n.max(1)),
            ),
            PathPoint::Time { index, t_s } => {
                let turn = (t_s / self.path_duration_s()).rem_euclid(1.0);
                (index, corridor_load(TAU * turn), turn)
            }
        };
        let report = self
            .renderer
            .render_within(index, &load, q, budget.as_ref());
        Ok(Measured {
            wall_ms: report.tp_ms,
            accel_ms: 0.0,
            report,
            angle: (TAU * turn) as f32,
            speed: ScreenSpeed::default(),
        })
    }

    fn hand_over(&mut self) -> Result<HandOver> {
        Ok(HandOver {
            ms: SIM_HAND_OVER_MS,
            image: None,
        })
    }

    fn warp(&mut self, _t_s: f64, _picture: bool) -> Result<HandOver> {
        Ok(HandOver {
            ms: SIM_WARP_MS,
            image: None,
        })
    }

    fn takes_wall_time(&self) -> bool {
        false
    }

    fn load_changes(&self, n: u32) -> Option<Vec<usize>> {
        Some(self.renderer.model().profile.changes(n as usize))
    }

    fn last_picture(&mut self) -> Result<Option<Rgb8Image>> {
        Ok(None)
    }

    fn set_temporal(&mut self, on: bool) -> Result<()> {
        if on {
            bail!("the simulated renderer has no temporal mode (--temporal needs a renderer)");
        }
        Ok(())
    }

    fn set_sample_stream(&mut self, _stream: SampleStream) {}
}

/// A simulated source for an `n`-frame corridor sweep.
pub fn simulated(n: u32) -> SimulatedSource {
    SimulatedSource {
        renderer: SimRenderer::new(RendererModel::corridor(n as usize)),
        frames: n,
    }
}

/// [`simulated`] with its noise drawn from `seed` (the corridor model's own seed is 1).
pub fn simulated_seeded(n: u32, seed: u64) -> SimulatedSource {
    let model = RendererModel {
        seed,
        ..RendererModel::corridor(n as usize)
    };
    SimulatedSource {
        renderer: SimRenderer::new(model),
        frames: n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_display::ViewingSetup;
    use steadyray_motion::MotionProbe;
    use steadyray_render_cpu::CpuRenderer;
    use steadyray_scene::builtin;

    /// A CPU source of the corridor at 64x36.
    fn corridor() -> RendererSource {
        let scene = builtin("corridor").unwrap();
        let mut renderer = CpuRenderer::with_threads(2);
        renderer.load_scene(&scene).unwrap();
        let probe = MotionProbe::new(&scene, (64, 36), ViewingSetup::standard_fhd()).unwrap();
        RendererSource {
            renderer: Box::new(renderer),
            scene,
            frame_loop: FrameLoop::new((64, 36)),
            motion: MotionTracker::new(probe),
        }
    }

    #[test]
    fn a_reference_draws_its_own_samples_and_frames_theirs_again() {
        let mut source = corridor();
        let at = PathPoint::Time { index: 0, t_s: 0.5 };
        let q = Quality::new(4.0, 8, 1.0);
        let frame = |source: &mut RendererSource| {
            source.frame(at, q).unwrap();
            source.last_picture().unwrap().unwrap()
        };
        let before = frame(&mut source);
        let reference = render_reference(&mut source, at, q).unwrap().unwrap();
        // Compared with `==`: a failing assert_eq! would print every pixel.
        assert!(
            reference != before,
            "the reference drew the frames' samples"
        );
        assert!(
            frame(&mut source) == before,
            "frames must draw their own samples again"
        );
        source.renderer.set_sample_stream(SampleStream::Reference);
        assert!(frame(&mut source) == reference, "not the reserved samples");
    }

    /// The window renders through [`FrameLoop::render`] and shows its controller the loop's
    /// report; the bench measures the same frame as [`Measured::of`] it. Over the same frame
    /// stats, implausible GPU timestamps included, both give the controller the same Tp.
    #[test]
    fn the_window_and_the_bench_give_a_controller_the_same_tp() {
        use steadyray_render::{FrameStats, TimingSource};
        let stats = |render_ms, wall_ms, timing| FrameStats {
            render_ms,
            accel_ms: 0.0,
            wall_ms,
            timing,
            rays: Default::default(),
            width: 64,
            height: 36,
            samples: 1,
            spp: 1.0,
        };
        let gpu = TimingSource::GpuTimestamps;
        let readings = [
            stats(16.0, 17.5, gpu),
            stats(0.3, 72.0, gpu),
            stats(16.0, 17.5, gpu),
            stats(40.0, 41.0, TimingSource::WallClock),
        ];
        let camera = builtin("corridor").unwrap().camera;
        let q = Quality::new(1.0, 4, 1.0);
        let (mut window, mut bench) = (FrameLoop::new((64, 36)), FrameLoop::new((64, 36)));
        let mut seen = Vec::new();
        for s in readings {
            let settings = window.settings(q);
            let window_tp = window.frame(s.clone(), settings, q).report.tp_ms;
            let bench_tp = Measured::of(bench.frame(s, settings, q), &camera)
                .report
                .tp_ms;
            assert_eq!(window_tp, bench_tp);
            seen.push(bench_tp);
        }
        // The lavapipe reading and every GPU reading after it give the wall time.
        assert_eq!(seen, [16.0, 72.0, 17.5, 40.0]);
    }
}
