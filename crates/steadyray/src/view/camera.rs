//! The view's camera: a fly camera (yaw, pitch, position) moved by the keys and the mouse,
//! and the paper's automatic sweep (the yaw turning at a constant rate around the eye).

use glam::Vec3;
use std::f32::consts::{FRAC_PI_2, TAU};
use steadyray_scene::Camera;

/// How far the pitch may go from the horizon: just short of straight up or down.
const MAX_PITCH: f32 = FRAC_PI_2 - 0.01;

/// A camera at `eye` with yaw and pitch as [`Camera::yaw_pitch`] defines them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub eye: Vec3,
    /// Radians; 0 looks along -z, increasing turns left (towards -x).
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    pub vfov_deg: f32,
}

impl FlyCamera {
    /// The fly camera looking where `camera` looks.
    pub fn from_camera(camera: &Camera) -> Self {
        let f = camera.forward.normalize();
        Self {
            eye: camera.eye,
            yaw: (-f.x).atan2(-f.z),
            pitch: f.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH),
            vfov_deg: camera.vfov_deg,
        }
    }

    /// The camera to render with.
    pub fn camera(&self) -> Camera {
        Camera::yaw_pitch(self.eye, self.yaw, self.pitch, self.vfov_deg)
    }

    /// Turns by `(yaw, pitch)` radians as the mouse gives them (positive yaw turns right).
    pub fn look(&mut self, (yaw, pitch): (f32, f32)) {
        self.yaw = (self.yaw - yaw).rem_euclid(TAU);
        self.pitch = (self.pitch + pitch).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves `distance` along `direction` given in camera space (x right, y up, z forward):
    /// forward and right stay in the horizontal plane, up is the world's up.
    pub fn translate(&mut self, direction: Vec3, distance: f32) {
        let forward = Vec3::new(-self.yaw.sin(), 0.0, -self.yaw.cos());
        let right = Vec3::new(self.yaw.cos(), 0.0, -self.yaw.sin());
        let world = right * direction.x + Vec3::Y * direction.y + forward * direction.z;
        self.eye += world * distance;
    }
}

/// The paper's automatic sweep: while on, the yaw turns a full circle every `period_s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    pub on: bool,
    /// Seconds per full turn.
    pub period_s: f32,
}

impl Sweep {
    /// Advances `camera` by `dt_s` seconds of sweep (nothing when off).
    pub fn advance(&self, camera: &mut FlyCamera, dt_s: f32) {
        if self.on && self.period_s > 0.0 {
            camera.yaw = (camera.yaw + TAU * dt_s / self.period_s).rem_euclid(TAU);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn round_trips_a_scene_camera() {
        let scene = steadyray_scene::builtin("corridor").unwrap();
        let fly = FlyCamera::from_camera(&scene.camera);
        let cam = fly.camera();
        assert!(close(cam.forward, scene.camera.forward.normalize()));
        assert_eq!(cam.eye, scene.camera.eye);
        let tilted = Camera::yaw_pitch(Vec3::ONE, 1.0, 0.3, 45.0);
        let back = FlyCamera::from_camera(&tilted).camera();
        assert!(close(back.forward, tilted.forward), "{back:?}");
    }

    #[test]
    fn keys_move_in_the_view_plane() {
        let mut fly = FlyCamera::from_camera(&Camera::yaw_pitch(Vec3::ZERO, 0.0, 0.5, 60.0));
        fly.translate(Vec3::Z, 2.0);
        assert!(
            close(fly.eye, Vec3::new(0.0, 0.0, -2.0)),
            "forward is -z, level"
        );
        fly.translate(Vec3::X, 1.0);
        assert!(close(fly.eye, Vec3::new(1.0, 0.0, -2.0)), "right is +x");
        fly.translate(Vec3::Y, 1.0);
        assert!(close(fly.eye, Vec3::new(1.0, 1.0, -2.0)));
    }

    #[test]
    fn mouse_turns_and_pitch_is_clamped() {
        let mut fly = FlyCamera::from_camera(&Camera::yaw_pitch(Vec3::ZERO, 0.0, 0.0, 60.0));
        fly.look((0.1, 0.0));
        assert!(fly.camera().forward.x > 0.0, "positive yaw turns right");
        fly.look((0.0, 10.0));
        assert!(fly.pitch <= MAX_PITCH && fly.camera().forward.y > 0.99);
        fly.look((0.0, -20.0));
        assert!(fly.pitch >= -MAX_PITCH);
    }

    #[test]
    fn sweep_turns_a_circle_per_period_only_when_on() {
        let mut fly = FlyCamera::from_camera(&Camera::yaw_pitch(Vec3::ZERO, 0.0, 0.0, 60.0));
        let mut sweep = Sweep {
            on: false,
            period_s: 8.0,
        };
        sweep.advance(&mut fly, 2.0);
        assert_eq!(fly.yaw, 0.0);
        sweep.on = true;
        sweep.advance(&mut fly, 2.0);
        assert!((fly.yaw - TAU / 4.0).abs() < 1e-5);
        sweep.advance(&mut fly, 8.0);
        assert!((fly.yaw - TAU / 4.0).abs() < 1e-4, "wraps");
    }
}
