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
    /// The sweep's eye and pitch with the yaw turning at the speeds of [`PANS`]: holds, slow
    /// pans and fast turns, one full turn in [`PANS_DURATION_S`] seconds whatever `frames`
    /// (the frame clock's count over it). A path whose speed on screen varies from stretch to
    /// stretch, for controllers that choose the frame rate from it.
    Pans { frames: u32 },
}

/// One stretch of the `pans` path: for `seconds`, the yaw turns at `deg_per_s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    pub seconds: f64,
    pub deg_per_s: f64,
}

const fn stretch(seconds: f64, deg_per_s: f64) -> Stretch {
    Stretch { seconds, deg_per_s }
}

/// The `pans` path's stretches, in order: a hold down the mirrors, a slow pan, a fast turn, a
/// hold, a slow pan, a fast turn, a hold and a medium pan back to the start: 360° in 12 s.
/// With the corridor's 60° vertical field of view at 16:9 on the standard viewing set-up (a
/// 24-inch display at 0.6 m), the picture moves at 0.54° of visual angle per degree of yaw on
/// average (0.43° at its centre, more toward its edges): 0, 6.5, 97, 0, 8, 81, 0 and 32 °/s
/// on average over the picture.
pub const PANS: [Stretch; 8] = [
    stretch(2.0, 0.0),
    stretch(2.5, 12.0),
    stretch(0.5, 180.0),
    stretch(2.0, 0.0),
    stretch(2.0, 15.0),
    stretch(1.0, 150.0),
    stretch(1.0, 0.0),
    stretch(1.0, 60.0),
];

/// The length of the `pans` path, s.
pub const PANS_DURATION_S: f64 = 12.0;

/// The `pans` path's yaw at `t_s` seconds into it, degrees (the path repeats after
/// [`PANS_DURATION_S`]).
pub fn pans_yaw_deg(t_s: f64) -> f64 {
    let mut t = t_s.rem_euclid(PANS_DURATION_S);
    let mut yaw = 0.0;
    for s in PANS {
        let spent = t.min(s.seconds);
        yaw += spent * s.deg_per_s;
        t -= spent;
        if t <= 0.0 {
            break;
        }
    }
    yaw
}

impl CameraPath {
    /// The default number of frames of the path.
    pub fn frames(&self) -> u32 {
        match *self {
            CameraPath::Sweep { frames }
            | CameraPath::Orbit { frames, .. }
            | CameraPath::Pans { frames } => frames,
        }
    }

    /// The path's length in seconds: its frames shown at 60 frames per second
    /// ([`PANS_DURATION_S`] for `pans`).
    pub fn duration_s(&self) -> f64 {
        match self {
            CameraPath::Pans { .. } => PANS_DURATION_S,
            _ => self.frames() as f64 / 60.0,
        }
    }

    /// The time of frame `k` of `n` under the frame clock: t = duration · k / n.
    pub fn frame_time(&self, k: u32, n: u32) -> f64 {
        self.duration_s() * k as f64 / n.max(1) as f64
    }

    /// The camera for frame `k` of `n`; `base` supplies eye, pitch and field of view.
    pub fn camera(&self, base: &Camera, k: u32, n: u32) -> Camera {
        match self {
            CameraPath::Pans { .. } => self.camera_at_time(base, self.frame_time(k, n)),
            _ => self.camera_at_phase(base, k as f32 / n.max(1) as f32),
        }
    }

    /// The camera at time `t_s` seconds; the path repeats after its duration.
    pub fn camera_at_time(&self, base: &Camera, t_s: f64) -> Camera {
        if let CameraPath::Pans { .. } = self {
            let yaw = pans_yaw_deg(t_s).to_radians() as f32;
            return Camera::yaw_pitch(base.eye, yaw, base_pitch(base), base.vfov_deg);
        }
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
                Camera::yaw_pitch(base.eye, angle, base_pitch(base), base.vfov_deg)
            }
            CameraPath::Pans { .. } => {
                let yaw = pans_yaw_deg(f64::from(phase) * PANS_DURATION_S).to_radians();
                Camera::yaw_pitch(base.eye, yaw as f32, base_pitch(base), base.vfov_deg)
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

/// The pitch of a base camera, radians: what the sweep and the pans keep.
fn base_pitch(base: &Camera) -> f32 {
    base.forward.normalize().y.clamp(-1.0, 1.0).asin()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pans_turn_once_at_their_stretches_speeds() {
        let total: f64 = PANS.iter().map(|s| s.seconds).sum();
        assert_eq!(total, PANS_DURATION_S);
        assert!((pans_yaw_deg(PANS_DURATION_S - 1e-9) - 360.0).abs() < 1e-6);
        assert_eq!(pans_yaw_deg(0.0), 0.0);
        assert_eq!(pans_yaw_deg(1.5), 0.0, "the first hold");
        assert!((pans_yaw_deg(3.0) - 12.0).abs() < 1e-9, "a slow pan");
        assert!(
            (pans_yaw_deg(4.75) - (30.0 + 45.0)).abs() < 1e-9,
            "a fast turn"
        );
        assert!(
            (pans_yaw_deg(PANS_DURATION_S + 3.0) - 12.0).abs() < 1e-9,
            "repeats"
        );
        let path = CameraPath::Pans { frames: 720 };
        assert_eq!(path.duration_s(), PANS_DURATION_S);
        let base = Camera::yaw_pitch(Vec3::new(0.0, 1.5, 0.0), 0.0, 0.1, 60.0);
        // Frame k of n and the time of that frame agree.
        let (by_frame, by_time) = (
            path.camera(&base, 180, 720),
            path.camera_at_time(&base, 3.0),
        );
        assert!((by_frame.forward - by_time.forward).length() < 1e-6);
        assert!(
            (by_time.forward.y - 0.1f32.sin()).abs() < 1e-6,
            "pitch kept"
        );
    }
}
