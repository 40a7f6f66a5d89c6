//! Camera paths: how the camera moves in `bench` and `view`.
//!
//! A path is a function of scene time t in seconds over its duration (by default its frames
//! at 60 per second). The frame clock (the paper's protocol) shows frame k of N at
//! t = duration · k / N; the real clock shows the path at display time. After its duration a
//! path starts over.

use crate::camera::Camera;
use crate::spline::{Curve, Ends, interpolate};
use glam::{DVec3, Vec3};
use std::f32::consts::TAU;

/// A camera path: its motion, its default number of frames and its duration.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraPath {
    /// How the camera moves.
    pub motion: PathMotion,
    /// The number of frames `bench` shows of it by default.
    pub frames: u32,
    /// Its length in seconds; `None`: `frames / 60`.
    pub duration_s: Option<f64>,
}

/// How a [`CameraPath`] moves the camera.
#[derive(Clone, Debug, PartialEq)]
pub enum PathMotion {
    /// The paper's sweep: the scene camera's eye and pitch fixed, yaw θ = 2π·k/N (one turn
    /// over the duration).
    Sweep,
    /// Circles `center` at `radius` and `height` (above the centre), looking at the centre;
    /// frame k of N is at angle 2π·k/N, starting on the +z side.
    Orbit {
        /// The point circled and looked at, world space.
        center: Vec3,
        /// The circle's radius, metres.
        radius: f32,
        /// The eye's height above `center`, metres.
        height: f32,
    },
    /// The sweep's eye and pitch with the yaw turning at the speeds of [`PANS`]: holds, slow
    /// pans and fast turns, one full turn over the path's duration (by default
    /// [`PANS_DURATION_S`], the stretches' own lengths; another duration plays them faster or
    /// slower). A path whose speed on screen varies from stretch to stretch, for controllers
    /// that choose the frame rate from it.
    Pans,
    /// Through keyed cameras (see [`KeyedPath`]).
    Keys(KeyedPath),
}

/// One stretch of the `pans` path: for `seconds`, the yaw turns at `deg_per_s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    /// The stretch's length, s.
    pub seconds: f64,
    /// Yaw speed over the stretch, degrees per second (0: a hold).
    pub deg_per_s: f64,
}

const fn stretch(seconds: f64, deg_per_s: f64) -> Stretch {
    Stretch { seconds, deg_per_s }
}

/// The `pans` path's stretches, in order: a hold down the mirrors, a slow pan, a fast turn, a
/// hold, a slow pan, a fast turn and a medium turn back to the start: 360° in 8 s. With the
/// corridor's 60° vertical field of view at 16:9 on the standard viewing set-up (a 24-inch
/// display at 0.6 m), the picture moves at 0.54° of visual angle per degree of yaw on average
/// (0.43° at its centre, more toward its edges): 0, 6.5, 97, 0, 8, 81 and 47 °/s on average
/// over the picture.
pub const PANS: [Stretch; 7] = [
    stretch(1.5, 0.0),
    stretch(1.5, 12.0),
    stretch(0.5, 180.0),
    stretch(1.5, 0.0),
    stretch(1.0, 15.0),
    stretch(1.0, 150.0),
    stretch(1.0, 87.0),
];

/// The length of the `pans` path's stretches, s: its default duration.
pub const PANS_DURATION_S: f64 = 8.0;

/// The `pans` path's yaw at `t_s` seconds into its stretches, degrees (the path repeats
/// after [`PANS_DURATION_S`]).
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

/// A camera moving through keys: eye and target (or yaw and pitch) follow the C1 spline of
/// `crate::spline` (a Catmull–Rom spline with the key times as knots), the field of view
/// straight segments between the keys that give one. Open, it holds the last key after it;
/// looped, it runs from the last key back to the first, arriving at the path's duration.
#[derive(Clone, Debug, PartialEq)]
pub struct KeyedPath {
    /// At least two, times strictly increasing from 0, all looking the same way (all with
    /// a target or all with yaw and pitch).
    pub keys: Vec<CameraKey>,
    /// Whether the path runs from the last key back to the first (see above).
    pub looped: bool,
}

/// One key of a [`KeyedPath`].
#[derive(Clone, Debug, PartialEq)]
pub struct CameraKey {
    /// Seconds.
    pub t: f64,
    /// The camera's position, world space.
    pub eye: Vec3,
    /// Where the camera looks.
    pub look: KeyLook,
    /// Vertical field of view in degrees; `None`: interpolated from the keys that give one,
    /// or the scene camera's when none does.
    pub vfov_deg: Option<f32>,
}

/// Where a [`CameraKey`] looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KeyLook {
    /// At a point.
    Target(Vec3),
    /// Along yaw and pitch in degrees, as the scene camera's `yaw_deg` and `pitch_deg`.
    YawPitch {
        /// Yaw, degrees.
        yaw_deg: f32,
        /// Pitch, degrees.
        pitch_deg: f32,
    },
}

impl CameraPath {
    /// A sweep of `frames` frames lasting `frames / 60` seconds.
    pub fn sweep(frames: u32) -> Self {
        Self {
            motion: PathMotion::Sweep,
            frames,
            duration_s: None,
        }
    }

    /// The pans of [`PANS`] over `frames` frames, lasting [`PANS_DURATION_S`].
    pub fn pans(frames: u32) -> Self {
        Self {
            motion: PathMotion::Pans,
            frames,
            duration_s: None,
        }
    }

    /// The default number of frames of the path.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// The path's length in seconds: `duration_s`, or its frames shown at 60 per second
    /// ([`PANS_DURATION_S`] for `pans`).
    pub fn duration_s(&self) -> f64 {
        let default = match self.motion {
            PathMotion::Pans => PANS_DURATION_S,
            _ => self.frames as f64 / 60.0,
        };
        self.duration_s.unwrap_or(default)
    }

    /// The time of frame `k` of `n` under the frame clock: t = duration · k / n.
    pub fn frame_time(&self, k: u32, n: u32) -> f64 {
        self.duration_s() * k as f64 / n.max(1) as f64
    }

    /// The camera for frame `k` of `n`; `base` supplies eye, pitch and field of view where
    /// the path does not.
    pub fn camera(&self, base: &Camera, k: u32, n: u32) -> Camera {
        match &self.motion {
            PathMotion::Keys(_) | PathMotion::Pans => {
                self.camera_at_time(base, self.frame_time(k, n))
            }
            _ => self.camera_at_phase(base, k as f32 / n.max(1) as f32),
        }
    }

    /// The camera at time `t_s` seconds; the path starts over after its duration.
    pub fn camera_at_time(&self, base: &Camera, t_s: f64) -> Camera {
        let duration = self.duration_s();
        let t = if duration > 0.0 {
            t_s.rem_euclid(duration)
        } else {
            0.0
        };
        match &self.motion {
            PathMotion::Keys(keys) => keys.camera_at(base, t, self),
            PathMotion::Pans => {
                let stretches_t = if duration > 0.0 {
                    t / duration * PANS_DURATION_S
                } else {
                    0.0
                };
                let yaw = pans_yaw_deg(stretches_t).to_radians() as f32;
                Camera::yaw_pitch(base.eye, yaw, base_pitch(base), base.vfov_deg)
            }
            _ => {
                let phase = if duration > 0.0 { t / duration } else { 0.0 };
                self.camera_at_phase(base, phase as f32)
            }
        }
    }

    /// The camera of a sweep or orbit at `phase` in [0, 1) of one turn.
    fn camera_at_phase(&self, base: &Camera, phase: f32) -> Camera {
        let angle = TAU * phase;
        match self.motion {
            PathMotion::Orbit {
                center,
                radius,
                height,
            } => {
                let eye = center + Vec3::new(radius * angle.sin(), height, radius * angle.cos());
                Camera::look_at(eye, center, Vec3::Y, base.vfov_deg)
            }
            _ => Camera::yaw_pitch(base.eye, angle, base_pitch(base), base.vfov_deg),
        }
    }
}

/// The pitch of a base camera, radians: what the sweep and the pans keep.
fn base_pitch(base: &Camera) -> f32 {
    base.forward.normalize().y.clamp(-1.0, 1.0).asin()
}

impl KeyedPath {
    /// The camera at time `t` in [0, duration) of `path`.
    fn camera_at(&self, base: &Camera, t: f64, path: &CameraPath) -> Camera {
        let ends = if self.looped {
            Ends::Cyclic(path.duration_s())
        } else {
            Ends::Open
        };
        let track = |value: &dyn Fn(&CameraKey) -> Option<DVec3>, curve| {
            let keys: Vec<(f64, DVec3)> = self
                .keys
                .iter()
                .filter_map(|k| value(k).map(|v| (k.t, v)))
                .collect();
            (!keys.is_empty()).then(|| interpolate(&keys, ends, curve, t))
        };
        let eye = track(&|k| Some(k.eye.into()), Curve::Smooth)
            .unwrap_or(base.eye.into())
            .as_vec3();
        let vfov_deg = track(
            &|k| k.vfov_deg.map(|f| DVec3::splat(f.into())),
            Curve::Linear,
        )
        .map_or(base.vfov_deg, |f| f.x as f32);
        let target = track(
            &|k| match k.look {
                KeyLook::Target(p) => Some(p.into()),
                KeyLook::YawPitch { .. } => None,
            },
            Curve::Smooth,
        );
        let forward = match target {
            Some(target) => target.as_vec3() - eye,
            None => {
                let angles = track(
                    &|k| match k.look {
                        KeyLook::YawPitch { yaw_deg, pitch_deg } => {
                            Some(DVec3::new(yaw_deg.into(), pitch_deg.into(), 0.0))
                        }
                        KeyLook::Target(_) => None,
                    },
                    Curve::Smooth,
                )
                .unwrap_or_default();
                let (yaw, pitch) = (angles.x.to_radians() as f32, angles.y.to_radians() as f32);
                Camera::yaw_pitch(eye, yaw, pitch, vfov_deg).forward
            }
        };
        Camera {
            eye,
            // Between keys the eye may pass through the target: keep the scene camera's view.
            forward: forward.try_normalize().unwrap_or(base.forward),
            up: base.up,
            vfov_deg,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keyed(looped: bool, duration_s: Option<f64>) -> CameraPath {
        let key = |t: f64, eye: [f32; 3], target: [f32; 3]| CameraKey {
            t,
            eye: Vec3::from(eye),
            look: KeyLook::Target(Vec3::from(target)),
            vfov_deg: None,
        };
        CameraPath {
            motion: PathMotion::Keys(KeyedPath {
                keys: vec![
                    key(0.0, [0.0, 1.0, 5.0], [0.0, 1.0, 0.0]),
                    key(2.0, [4.0, 1.0, 0.0], [0.0, 1.0, 0.0]),
                    key(5.0, [0.0, 2.0, -5.0], [0.0, 0.0, 0.0]),
                ],
                looped,
            }),
            frames: 600,
            duration_s,
        }
    }

    #[test]
    fn keyed_path_passes_through_its_keys() {
        let base = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 50.0);
        let path = keyed(false, Some(8.0));
        let at2 = path.camera_at_time(&base, 2.0);
        assert!((at2.eye - Vec3::new(4.0, 1.0, 0.0)).length() < 1e-5);
        assert!((at2.forward - Vec3::NEG_X).length() < 1e-5, "{at2:?}");
        assert_eq!(at2.vfov_deg, 50.0);
        // Open: holds the last key until the duration, then starts over.
        let late = path.camera_at_time(&base, 7.0);
        assert!((late.eye - Vec3::new(0.0, 2.0, -5.0)).length() < 1e-5);
        let again = path.camera_at_time(&base, 8.0 + 2.0);
        assert!((again.eye - at2.eye).length() < 1e-5);
        // Frame k of n is at duration · k / n.
        assert_eq!(path.camera(&base, 1, 4), path.camera_at_time(&base, 2.0));
    }

    #[test]
    fn looped_keyed_path_returns_to_its_first_key() {
        let base = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 50.0);
        let path = keyed(true, Some(8.0));
        let near_end = path.camera_at_time(&base, 7.999_999);
        assert!((near_end.eye - Vec3::new(0.0, 1.0, 5.0)).length() < 1e-4);
        let mid = path.camera_at_time(&base, 6.5);
        assert!(
            mid.eye.z < 0.0 && mid.eye.z > -5.0 || mid.eye.x.abs() > 0.1,
            "{mid:?}"
        );
    }

    #[test]
    fn the_pans_turn_once_at_their_stretches_speeds() {
        let total: f64 = PANS.iter().map(|s| s.seconds).sum();
        assert_eq!(total, PANS_DURATION_S);
        assert!((pans_yaw_deg(PANS_DURATION_S - 1e-9) - 360.0).abs() < 1e-6);
        assert_eq!(pans_yaw_deg(0.0), 0.0);
        assert_eq!(pans_yaw_deg(1.0), 0.0, "the first hold");
        assert!((pans_yaw_deg(2.25) - 9.0).abs() < 1e-9, "a slow pan");
        assert!((pans_yaw_deg(3.25) - 63.0).abs() < 1e-9, "a fast turn");
        assert!(
            (pans_yaw_deg(PANS_DURATION_S + 2.25) - 9.0).abs() < 1e-9,
            "repeats"
        );
        let path = CameraPath::pans(720);
        assert_eq!(path.duration_s(), PANS_DURATION_S);
        let base = Camera::yaw_pitch(Vec3::new(0.0, 1.5, 0.0), 0.0, 0.1, 60.0);
        // Frame k of n and the time of that frame agree.
        let (by_frame, by_time) = (
            path.camera(&base, 180, 720),
            path.camera_at_time(&base, 2.0),
        );
        assert!((by_frame.forward - by_time.forward).length() < 1e-6);
        assert!(
            (by_time.forward.y - 0.1f32.sin()).abs() < 1e-6,
            "pitch kept"
        );
        // Twice the duration plays the stretches at half speed.
        let slow = CameraPath {
            duration_s: Some(2.0 * PANS_DURATION_S),
            ..path.clone()
        };
        let (a, b) = (
            slow.camera_at_time(&base, 6.0),
            path.camera_at_time(&base, 3.0),
        );
        assert!((a.forward - b.forward).length() < 1e-6);
    }

    #[test]
    fn default_duration_is_frames_at_60() {
        assert_eq!(CameraPath::sweep(720).duration_s(), 12.0);
        assert_eq!(keyed(false, Some(8.0)).duration_s(), 8.0);
        assert_eq!(keyed(false, None).duration_s(), 10.0);
    }
}
