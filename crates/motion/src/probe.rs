//! Measuring a frame's motion on screen: a grid of eye rays cast into the world of the frame's
//! time on the CPU (whatever backend renders the frame), each primary hit carried back by its
//! object's motion to where it was at the previous frame's time and reprojected into the
//! previous frame's camera ([`crate::speed`]).

use crate::speed::{ScreenSpeed, Seen, sample_speeds};
use glam::DVec3;
use steadyray_display::ViewingSetup;
use steadyray_render::{RenderError, Renderer};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{Camera, Scene};

/// Columns of the probe grid: 32 x 18 rays, about 0.25 % of a 640x360 frame's eye rays.
pub const GRID_COLUMNS: u32 = 32;

/// A frame's camera and times, s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    /// The frame's camera.
    pub camera: Camera,
    /// When the frame is shown: the clock speeds are per.
    pub time_s: f64,
    /// The scene time it renders: where its objects are (the bench renders the world at
    /// the display time; a window's scene clock may stop or start over).
    pub world_s: f64,
}

impl Shot {
    /// A frame rendering the world at the time it is shown.
    pub fn at(camera: Camera, time_s: f64) -> Self {
        Self {
            camera,
            time_s,
            world_s: time_s,
        }
    }
}

/// Measures the motion on screen of a scene's frames.
pub struct MotionProbe {
    scene: Scene,
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
            scene: scene.clone(),
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

    /// What each grid sample (the centres of the grid's cells) of the frame `now` shows, a
    /// hit point with where its object had it at scene time `before_s`; a point on an
    /// object that did not exist then is left out.
    fn samples(&mut self, now: &Shot, before_s: f64) -> Result<Vec<Seen>, RenderError> {
        let frame = now.camera.frame(self.columns, self.rows);
        let dirs: Vec<_> = (0..self.rows)
            .flat_map(|row| (0..self.columns).map(move |column| (column, row)))
            .map(|(column, row)| frame.ray_dir(column, row, 0.5, 0.5, self.columns, self.rows))
            .collect();
        let hits = self.tracer.first_hits(now.world_s, now.camera.eye, &dirs)?;
        Ok(dirs
            .iter()
            .zip(hits)
            .filter_map(|(&dir, hit)| match hit {
                None => Some(Seen::Direction(dir)),
                Some((t, object)) => {
                    let p = now.camera.eye + t * dir;
                    let before = self.moved(object, p, now.world_s, before_s)?;
                    Some(Seen::Point { now: p, before })
                }
            })
            .collect())
    }

    /// Where the point `p` of object `object` at time `now_s` was at `before_s` (itself on a
    /// still object), or `None` when the object did not exist then.
    fn moved(&self, object: usize, p: glam::Vec3, now_s: f64, before_s: f64) -> Option<glam::Vec3> {
        let obj = &self.scene.objects[object];
        if obj.motion.is_none() {
            return Some(p);
        }
        let (now, before) = (obj.placement_at(now_s)?, obj.placement_at(before_s)?);
        let was = before.transform_point3(now.inverse().transform_point3(DVec3::from(p)));
        was.is_finite().then(|| was.as_vec3())
    }

    /// The motion on screen of the frame `now`, the frame before it being `previous`. When
    /// the scene clock started over between them, objects count as still.
    pub fn measure(&mut self, previous: &Shot, now: &Shot) -> Result<ScreenSpeed, RenderError> {
        let before_s = if previous.world_s <= now.world_s {
            previous.world_s
        } else {
            now.world_s
        };
        let samples = self.samples(now, before_s)?;
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
        Shot::at(scene.camera_at_time(time_s), time_s)
    }

    #[test]
    fn the_sweep_turns_at_about_0_43_visual_degrees_per_degree_of_yaw() {
        let (scene, mut probe) = corridor_probe();
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
        let (mut scene, mut probe) = corridor_probe();
        scene.path = CameraPath::pans(720);
        let mut at = |t: f64| {
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
    fn a_ball_flying_past_a_still_camera_moves_on_screen() {
        let toml = r#"
            [camera]
            eye = [0, 0, 0]
            target = [0, 0, -1]
            vfov_deg = 60
            [[materials]]
            name = "white"
            type = "diffuse"
            albedo = 0.8
            [[shapes]]
            name = "ball"
            type = "sphere"
            material = "white"
            center = [0, 0, -4]
            radius = 1.5
            [shapes.motion]
            [[shapes.motion.keys]]
            t = 0.0
            translate = [-1, 0, 0]
            [[shapes.motion.keys]]
            t = 1.0
            translate = [1, 0, 0]
        "#;
        let scene = steadyray_scene::parse_scene(toml, "ball.toml", None).unwrap();
        let mut probe = MotionProbe::new(&scene, (640, 360), ViewingSetup::standard_fhd()).unwrap();
        let camera = scene.camera;
        let s = probe
            .measure(&Shot::at(camera, 0.49), &Shot::at(camera, 0.51))
            .unwrap();
        // The ball covers part of the picture and moves; the background does not.
        assert!(s.p95_deg_s > 5.0, "{s:?}");
        assert!(s.mean_deg_s > 0.5 && s.mean_deg_s < s.p95_deg_s, "{s:?}");
        // Its world frozen (a window's paused scene clock), the same camera sees nothing move.
        let frozen = |time_s| Shot {
            camera,
            time_s,
            world_s: 0.5,
        };
        let still = probe.measure(&frozen(0.49), &frozen(0.51)).unwrap();
        assert!(still.p95_deg_s < 1e-6, "{still:?}");
    }

    #[test]
    fn a_picture_without_pixels_is_refused() {
        let scene = steadyray_scene::load_scene("corridor").unwrap();
        let err = MotionProbe::new(&scene, (0, 360), ViewingSetup::standard_fhd());
        assert!(err.err().unwrap().to_string().contains("0x360"));
    }
}
