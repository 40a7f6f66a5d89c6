//! Measuring a frame's motion on screen: a grid of eye rays cast into the scene on the CPU
//! (whatever backend renders the frame), their primary hits reprojected into the previous
//! frame's camera ([`crate::speed`]).

use crate::speed::{ScreenSpeed, Seen, sample_speeds};
use steadyray_display::ViewingSetup;
use steadyray_render::{RenderError, Renderer};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{Camera, Scene};

/// Columns of the probe grid: 32 x 18 rays, about 0.25 % of a 640x360 frame's eye rays.
pub const GRID_COLUMNS: u32 = 32;

/// A camera at a time, s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    pub camera: Camera,
    pub time_s: f64,
}

/// Measures the motion on screen of a scene's frames.
pub struct MotionProbe {
    tracer: CpuRenderer,
    viewing: ViewingSetup,
    columns: u32,
    rows: u32,
    aspect: f64,
}

impl MotionProbe {
    /// A probe of `scene` for pictures `width` x `height` shown full screen on `viewing`: a
    /// grid of [`GRID_COLUMNS`] columns and as many rows as the aspect gives, traced on one
    /// CPU thread of its own.
    pub fn new(
        scene: &Scene,
        (width, height): (u32, u32),
        viewing: ViewingSetup,
    ) -> Result<Self, RenderError> {
        if width == 0 || height == 0 {
            return Err(RenderError::Scene(format!(
                "cannot measure motion on a {width}x{height} picture"
            )));
        }
        let mut tracer = CpuRenderer::with_threads(1);
        tracer.load_scene(scene)?;
        let aspect = f64::from(width) / f64::from(height);
        let rows = ((f64::from(GRID_COLUMNS) / aspect).round() as u32).max(1);
        Ok(Self {
            tracer,
            viewing,
            columns: GRID_COLUMNS,
            rows,
            aspect,
        })
    }

    /// The viewing set-up the speeds are measured under.
    pub fn viewing(&self) -> &ViewingSetup {
        &self.viewing
    }

    /// What each grid sample (the centres of the grid's cells) of a frame seen by `camera`
    /// shows.
    fn samples(&self, camera: &Camera) -> Result<Vec<Seen>, RenderError> {
        let frame = camera.frame(self.columns, self.rows);
        let mut out = Vec::with_capacity((self.columns * self.rows) as usize);
        for row in 0..self.rows {
            for column in 0..self.columns {
                let dir = frame.ray_dir(column, row, 0.5, 0.5, self.columns, self.rows);
                let seen = match self.tracer.first_hit(camera.eye, dir)? {
                    Some(t) => Seen::Point(camera.eye + t * dir),
                    None => Seen::Direction(dir),
                };
                out.push(seen);
            }
        }
        Ok(out)
    }

    /// The motion on screen of the frame `now`, the frame before it being `previous`.
    pub fn measure(&self, previous: &Shot, now: &Shot) -> Result<ScreenSpeed, RenderError> {
        let samples = self.samples(&now.camera)?;
        let speeds = sample_speeds(
            &previous.camera,
            &now.camera,
            now.time_s - previous.time_s,
            self.aspect,
            &self.viewing,
            &samples,
        );
        Ok(ScreenSpeed::of(&speeds))
    }
}

/// Follows a sequence of frames and gives each one's motion on screen since the frame before
/// it: a frame showing the same time as the one before (a repeated world time) moves as that
/// one did; a frame showing an earlier time (a new run, a cut) starts over at 0.
pub struct MotionTracker {
    probe: MotionProbe,
    last: Option<(Shot, ScreenSpeed)>,
}

impl MotionTracker {
    /// A tracker with no frame yet.
    pub fn new(probe: MotionProbe) -> Self {
        Self { probe, last: None }
    }

    /// The motion on screen of the frame `now`.
    pub fn next(&mut self, now: Shot) -> Result<ScreenSpeed, RenderError> {
        let speed = match self.last {
            Some((before, speed)) if now.time_s == before.time_s => speed,
            Some((before, _)) if now.time_s > before.time_s => self.probe.measure(&before, &now)?,
            _ => ScreenSpeed::default(),
        };
        self.last = Some((now, speed));
        Ok(speed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_scene::CameraPath;

    fn corridor_probe() -> (Scene, MotionProbe) {
        let scene = steadyray_scene::load_scene("corridor").unwrap();
        let probe = MotionProbe::new(&scene, (640, 360), ViewingSetup::standard_fhd()).unwrap();
        (scene, probe)
    }

    fn shot(scene: &Scene, time_s: f64) -> Shot {
        Shot {
            camera: scene.camera_at_time(time_s),
            time_s,
        }
    }

    #[test]
    fn the_sweep_turns_at_about_0_43_visual_degrees_per_degree_of_yaw() {
        let (scene, probe) = corridor_probe();
        // The corridor's sweep: 360° in 12 s, 30°/s of yaw, at every view of the turn.
        for t in [0.0, 3.0, 6.0, 9.0] {
            let s = probe
                .measure(&shot(&scene, t), &shot(&scene, t + 1.0 / 60.0))
                .unwrap();
            assert_eq!(s.samples, 32 * 18);
            // A pure turn: every point moves by its direction's change, near 0.43 · 30°/s at
            // the centre and faster toward the edges (perspective).
            assert!(
                s.mean_deg_s > 0.43 * 30.0 && s.mean_deg_s < 0.43 * 30.0 * 1.5,
                "{s:?}"
            );
            assert!(s.p95_deg_s > s.mean_deg_s, "{s:?}");
        }
        let still = probe
            .measure(&shot(&scene, 2.0), &shot(&scene, 2.0))
            .unwrap();
        assert_eq!(
            still,
            ScreenSpeed::default(),
            "no time passed: nothing measured"
        );
    }

    #[test]
    fn the_pans_path_is_still_then_slow_then_fast() {
        let (mut scene, probe) = corridor_probe();
        scene.path = CameraPath::pans(720);
        let at = |t: f64| {
            probe
                .measure(&shot(&scene, t - 1.0 / 60.0), &shot(&scene, t))
                .unwrap()
                .mean_deg_s
        };
        let (hold, slow, fast) = (at(1.0), at(2.5), at(3.25));
        assert!(hold < 1e-3, "{hold}");
        assert!(slow > 4.0 && slow < 9.0, "{slow}");
        assert!(fast > 70.0 && fast < 120.0, "{fast}");
    }

    #[test]
    fn a_tracker_keeps_the_motion_over_a_repeated_time_and_restarts_on_an_earlier_one() {
        let (scene, probe) = corridor_probe();
        let mut tracker = MotionTracker::new(probe);
        let first = tracker.next(shot(&scene, 1.0)).unwrap();
        assert_eq!(
            first,
            ScreenSpeed::default(),
            "nothing before the first frame"
        );
        let moving = tracker.next(shot(&scene, 1.05)).unwrap();
        assert!(moving.mean_deg_s > 10.0, "{moving:?}");
        assert_eq!(tracker.next(shot(&scene, 1.05)).unwrap(), moving);
        assert_eq!(
            tracker.next(shot(&scene, 0.0)).unwrap(),
            ScreenSpeed::default()
        );
    }

    #[test]
    fn a_picture_without_pixels_is_refused() {
        let scene = steadyray_scene::load_scene("corridor").unwrap();
        let err = MotionProbe::new(&scene, (0, 360), ViewingSetup::standard_fhd());
        assert!(err.err().unwrap().to_string().contains("0x360"));
    }
}
