//! Camera paths: how the camera moves from frame to frame in `bench` and `view`.

use crate::camera::Camera;
use glam::Vec3;
use std::f32::consts::TAU;

/// A camera path over `frames` frames; frame k of N is a pure function of k and N.
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

    /// The camera for frame `k` of `n`; `base` supplies eye, pitch and field of view.
    pub fn camera(&self, base: &Camera, k: u32, n: u32) -> Camera {
        let angle = TAU * k as f32 / n.max(1) as f32;
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
