//! Camera paths: how the camera moves in `bench` and `view`.
//!
//! A path is a function of scene time t in seconds over its duration. The frame clock (the
//! paper's protocol) shows frame k of N at t = duration · k / N; the real clock shows the
//! path at display time.

use crate::camera::Camera;
use glam::Vec3;
use std::f32::consts::TAU;

/// A camera path over `frames` frames, lasting `frames / 60` seconds; the camera is a pure
/// function of the time t (or of k and N for frame k of N).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraPath {
    /// The paper's sweep: the scene camera's eye and pitch fixed, yaw θ = 2π·k/N.
    Sweep { frames: u32 },
    /// Circles `center` at `radius` and `height` (above the centre), looking at the centre;
    /// frame k of N is at angle 2π·k/N, starting on the +z side.
    Orbit {
        center: Vec3,
        radius: f32,
        height: f32,
        frames: u32,
    },
}

impl CameraPath {
    /// The default number of frames of the path.
    pub fn frames(&self) -> u32 {
        match *self {
            CameraPath::Sweep { frames } | CameraPath::Orbit { frames, .. } => frames,
        }
    }

    /// The path's length in seconds: its frames shown at 60 frames per second.
    pub fn duration_s(&self) -> f64 {
        self.frames() as f64 / 60.0
    }

    /// The time of frame `k` of `n` under the frame clock: t = duration · k / n.
    pub fn frame_time(&self, k: u32, n: u32) -> f64 {
        self.duration_s() * k as f64 / n.max(1) as f64
    }

    /// The camera for frame `k` of `n`; `base` supplies eye, pitch and field of view.
    pub fn camera(&self, base: &Camera, k: u32, n: u32) -> Camera {
        self.camera_at_phase(base, k as f32 / n.max(1) as f32)
    }

    /// The camera at time `t_s` seconds; the path repeats after its duration.
    pub fn camera_at_time(&self, base: &Camera, t_s: f64) -> Camera {
        let duration = self.duration_s();
        let phase = if duration > 0.0 {
            (t_s / duration).rem_euclid(1.0)
        } else {
            0.0
        };
        self.camera_at_phase(base, phase as f32)
    }

    /// The camera at `phase` in [0, 1) of one cycle of the path.
    fn camera_at_phase(&self, base: &Camera, phase: f32) -> Camera {
        let angle = TAU * phase;
        match *self {
            CameraPath::Sweep { .. } => {
                let pitch = base.forward.normalize().y.clamp(-1.0, 1.0).asin();
                Camera::yaw_pitch(base.eye, angle, pitch, base.vfov_deg)
            }
            CameraPath::Orbit {
                center,
                radius,
                height,
                ..
            } => {
                let eye = center + Vec3::new(radius * angle.sin(), height, radius * angle.cos());
                Camera::look_at(eye, center, Vec3::Y, base.vfov_deg)
            }
        }
    }
}
