//! The speed of what a frame shows, on the display as the viewer sees it.
//!
//! A sample of the screen shows a world point P: the primary hit of the eye ray through it, or,
//! where the ray leaves the scene, the point at infinity along it (the background turns with
//! the camera but does not move with it). Projected into the frame's camera P lies at (x, y)
//! on the normalised screen [−1, 1]² (x right, y up); at the previous frame's time the point
//! was at P′ (P itself on a still object; where the object's motion had it then on a moving
//! one), and projected into the previous frame's camera P′ lay at (x′, y′). On the viewing
//! set-up's display (the picture shown full screen, `ViewingSetup`) both positions are points
//! on the panel, and the sample's speed is the visual angle between the eye's directions to
//! them, over the time between the two frames. Points that lay behind the previous camera
//! are left out.

use glam::{DVec3, Vec3};
use serde::Serialize;
use steadyray_display::ViewingSetup;
use steadyray_scene::Camera;

/// The motion on screen of one frame, degrees of visual angle per second.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ScreenSpeed {
    /// The mean over the samples.
    pub mean_deg_s: f64,
    /// The 95th percentile over the samples: how fast the fastest-moving parts move.
    pub p95_deg_s: f64,
    /// Samples measured (0: none could be reprojected, e.g. after a cut; both speeds 0).
    pub samples: usize,
}

/// What a sample of the screen shows: a point, or a direction for the background.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seen {
    /// The primary hit: its world position at the frame's time, and at the previous frame's
    /// (the same on a still object).
    Point {
        /// Where it is at the frame's time.
        now: Vec3,
        /// Where it was at the previous frame's.
        before: Vec3,
    },
    /// No hit: the background in this direction.
    Direction(Vec3),
}

impl Seen {
    /// A point on something that does not move.
    pub fn still(p: Vec3) -> Self {
        Seen::Point { now: p, before: p }
    }
}

/// A camera's projection onto the normalised screen [−1, 1]² of an image of a given aspect.
struct Projection {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    half_width: f64,
    half_height: f64,
}

impl Projection {
    fn new(camera: &Camera, aspect: f64) -> Self {
        // The renderers' ray frame; its horizontal extent follows the picture's aspect.
        let frame = camera.frame(1, 1);
        let d = |v: Vec3| v.as_dvec3();
        let half_height = f64::from(frame.half_height);
        Self {
            eye: d(frame.eye),
            forward: d(frame.forward),
            right: d(frame.right),
            up: d(frame.true_up),
            half_width: half_height * aspect,
            half_height,
        }
    }

    /// Where `seen` lies on the normalised screen (at the frame's time, or at the previous
    /// frame's when `before`), or `None` behind the camera.
    fn project(&self, seen: Seen, before: bool) -> Option<(f64, f64)> {
        let v = match seen {
            Seen::Point { now, .. } if !before => now.as_dvec3() - self.eye,
            Seen::Point { before, .. } => before.as_dvec3() - self.eye,
            Seen::Direction(d) => d.as_dvec3(),
        };
        let z = v.dot(self.forward);
        (z > 1e-9).then(|| {
            (
                v.dot(self.right) / (z * self.half_width),
                v.dot(self.up) / (z * self.half_height),
            )
        })
    }
}

/// The eye's direction to a normalised screen position on the viewing set-up's display.
fn eye_direction(viewing: &ViewingSetup, (x, y): (f64, f64)) -> DVec3 {
    let width = viewing.width_m();
    let [w, h] = viewing.resolution.map(f64::from);
    let height = width * h / w;
    DVec3::new(0.5 * x * width, 0.5 * y * height, viewing.distance_m)
}

/// The visual angle between two directions, degrees.
fn angle_deg(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

/// The speed of each sample that could be reprojected, deg/s: `samples` are what the frame
/// seen by `now` shows at its sample positions; `dt_s` is the time from the frame seen by
/// `previous` to it; `aspect` the picture's width over its height.
pub fn sample_speeds(
    previous: &Camera,
    now: &Camera,
    dt_s: f64,
    aspect: f64,
    viewing: &ViewingSetup,
    samples: &[Seen],
) -> Vec<f64> {
    if !(dt_s > 0.0 && dt_s.is_finite()) {
        return Vec::new();
    }
    let (before, after) = (
        Projection::new(previous, aspect),
        Projection::new(now, aspect),
    );
    samples
        .iter()
        .filter_map(|&seen| {
            let at = after.project(seen, false)?;
            let was = before.project(seen, true)?;
            let angle = angle_deg(eye_direction(viewing, at), eye_direction(viewing, was));
            Some(angle / dt_s)
        })
        .collect()
}

impl ScreenSpeed {
    /// The mean and 95th percentile of per-sample speeds (all 0 for none).
    pub fn of(speeds: &[f64]) -> Self {
        if speeds.is_empty() {
            return Self::default();
        }
        let mut sorted = speeds.to_vec();
        sorted.sort_by(f64::total_cmp);
        let pos = 0.95 * (sorted.len() - 1) as f64;
        let (i, frac) = (pos.floor() as usize, pos.fract());
        let next = sorted[(i + 1).min(sorted.len() - 1)];
        Self {
            mean_deg_s: sorted.iter().sum::<f64>() / sorted.len() as f64,
            p95_deg_s: sorted[i] + frac * (next - sorted[i]),
            samples: sorted.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASPECT: f64 = 16.0 / 9.0;

    #[test]
    fn a_turning_camera_moves_the_centre_by_the_display_s_angle() {
        let viewing = ViewingSetup::standard_fhd();
        let eye = Vec3::new(0.0, 1.5, 0.0);
        let (yaw, dt) = (1.0f32.to_radians(), 0.01);
        let now = Camera::yaw_pitch(eye, yaw, 0.0, 60.0);
        let before = Camera::yaw_pitch(eye, 0.0, 0.0, 60.0);
        // The centre now shows the direction the camera looks along; 1° of yaw earlier it was
        // at x = -tan(1°) / tan(hfov / 2) (the yaw turns left): on the display, at
        // 0.2656 m · that, seen from 0.6 m.
        let hfov_half = ((30f64).to_radians().tan() * ASPECT).atan();
        let x = 1f64.to_radians().tan() / hfov_half.tan();
        let half_width = 0.5 * viewing.width_m();
        let want = (x * half_width / viewing.distance_m).atan().to_degrees() / dt;
        for seen in [
            Seen::Direction(now.forward),
            Seen::still(eye + 3.0 * now.forward),
        ] {
            let got = sample_speeds(&before, &now, dt, ASPECT, &viewing, &[seen]);
            assert_eq!(got.len(), 1);
            assert!((got[0] / want - 1.0).abs() < 1e-4, "{} vs {want}", got[0]);
        }
        // About 0.43° of visual angle per degree of yaw at the centre (docs/scene-format.md).
        assert!((want * dt - 0.431).abs() < 0.005, "{}", want * dt);
    }

    #[test]
    fn a_sideways_step_moves_near_points_faster_and_the_background_not_at_all() {
        let viewing = ViewingSetup::standard_fhd();
        let look = |eye: Vec3| Camera::look_at(eye, eye + Vec3::NEG_Z, Vec3::Y, 60.0);
        let (before, now) = (look(Vec3::ZERO), look(Vec3::new(0.01, 0.0, 0.0)));
        let speed_at = |seen| sample_speeds(&before, &now, 0.01, ASPECT, &viewing, &[seen]);
        let near = speed_at(Seen::still(Vec3::new(0.01, 0.0, -1.0)))[0];
        let far = speed_at(Seen::still(Vec3::new(0.01, 0.0, -4.0)))[0];
        let sky = speed_at(Seen::Direction(Vec3::NEG_Z))[0];
        assert!((near / far - 4.0).abs() < 0.01, "{near} vs {far}");
        assert!(sky.abs() < 1e-9);
        // A point 1 m away moved 1 cm across: x = 0.01 / tan(hfov / 2) on the screen.
        let hfov_half = ((30f64).to_radians().tan() * ASPECT).atan();
        let x = 0.01 / hfov_half.tan();
        let want = (x * 0.5 * viewing.width_m() / viewing.distance_m)
            .atan()
            .to_degrees()
            / 0.01;
        assert!((near / want - 1.0).abs() < 1e-3, "{near} vs {want}");
    }

    #[test]
    fn still_cameras_behind_points_and_bad_times_give_no_motion() {
        let viewing = ViewingSetup::standard_fhd();
        let c = Camera::yaw_pitch(Vec3::ZERO, 0.3, 0.1, 60.0);
        let seen = Seen::still(Vec3::new(0.2, 0.1, -2.0));
        let still = sample_speeds(&c, &c, 0.02, ASPECT, &viewing, &[seen]);
        assert!(still[0].abs() < 1e-6, "{still:?}");
        let behind = Camera::yaw_pitch(Vec3::ZERO, std::f32::consts::PI, 0.0, 60.0);
        assert!(sample_speeds(&behind, &c, 0.02, ASPECT, &viewing, &[seen]).is_empty());
        for dt in [0.0, -1.0, f64::NAN] {
            assert!(sample_speeds(&c, &c, dt, ASPECT, &viewing, &[seen]).is_empty());
        }
    }

    #[test]
    fn a_moving_object_moves_on_screen_under_a_still_camera() {
        let viewing = ViewingSetup::standard_fhd();
        let c = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 60.0);
        let seen = Seen::Point {
            now: Vec3::new(0.01, 0.0, -1.0),
            before: Vec3::ZERO.with_z(-1.0),
        };
        let moving = sample_speeds(&c, &c, 0.01, ASPECT, &viewing, &[seen])[0];
        // As fast as the still point under the camera stepping 1 cm the other way.
        let stepped = Camera::look_at(
            Vec3::new(-0.01, 0.0, 0.0),
            Vec3::new(-0.01, 0.0, -1.0),
            Vec3::Y,
            60.0,
        );
        let still = Seen::still(Vec3::new(0.0, 0.0, -1.0));
        let shifted = sample_speeds(&c, &stepped, 0.01, ASPECT, &viewing, &[still])[0];
        assert!(
            moving > 10.0 && (moving / shifted - 1.0).abs() < 1e-3,
            "{moving} vs {shifted}"
        );
    }

    #[test]
    fn mean_and_percentile() {
        assert_eq!(ScreenSpeed::of(&[]), ScreenSpeed::default());
        let s = ScreenSpeed::of(&(0..=100).map(f64::from).collect::<Vec<_>>());
        assert_eq!((s.mean_deg_s, s.p95_deg_s, s.samples), (50.0, 95.0, 101));
    }
}
