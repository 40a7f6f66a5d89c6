//! The pinhole camera and the pixel-to-ray convention of `docs/corridor.md`.

use glam::Vec3;

/// A pinhole camera looking from `eye` along `forward`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The centre of projection, world space.
    pub eye: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// The world's up direction (need not be orthogonal to `forward`).
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub vfov_deg: f32,
}

/// The orthonormal frame and scale factors derived from a camera for one image size;
/// computed once per frame and shared by every ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraFrame {
    /// The centre of projection, world space.
    pub eye: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit vector to the image's right (`forward` × `up`, normalized).
    pub right: Vec3,
    /// Unit vector to the image's top, orthogonal to `forward` and `right`.
    pub true_up: Vec3,
    /// tan(vfov / 2) · aspect
    pub half_width: f32,
    /// tan(vfov / 2)
    pub half_height: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target`.
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3, vfov_deg: f32) -> Self {
        Self {
            eye,
            forward: (target - eye).normalize(),
            up,
            vfov_deg,
        }
    }

    /// A camera at `eye` with yaw θ and pitch φ (radians). At yaw 0, pitch 0 it looks along
    /// -z; the view direction is (-sin θ cos φ, sin φ, -cos θ cos φ), as in the paper's sweep.
    pub fn yaw_pitch(eye: Vec3, yaw: f32, pitch: f32, vfov_deg: f32) -> Self {
        let forward = Vec3::new(
            -yaw.sin() * pitch.cos(),
            pitch.sin(),
            -yaw.cos() * pitch.cos(),
        );
        Self {
            eye,
            forward,
            up: Vec3::Y,
            vfov_deg,
        }
    }

    /// Why no image can be rendered from this camera: a position or direction that is not
    /// finite (a NaN yaw, say), no view direction, or a field of view outside (0°, 180°).
    pub fn check(&self) -> Result<(), String> {
        let finite = self.eye.is_finite() && self.forward.is_finite() && self.up.is_finite();
        if !finite {
            return Err(format!(
                "its position and directions must be finite (eye {}, forward {}, up {})",
                self.eye, self.forward, self.up
            ));
        }
        if self.forward.length_squared() == 0.0 {
            return Err("it has no view direction".into());
        }
        if !(self.vfov_deg > 0.0 && self.vfov_deg < 180.0) {
            return Err(format!(
                "its field of view {}° is not in (0°, 180°)",
                self.vfov_deg
            ));
        }
        Ok(())
    }

    /// The ray frame for an image of `width` × `height` pixels.
    pub fn frame(&self, width: u32, height: u32) -> CameraFrame {
        let forward = self.forward.normalize();
        // Looking straight along `up` leaves `right` undefined: fall back to another axis.
        let right = forward
            .cross(self.up)
            .try_normalize()
            .or_else(|| forward.cross(Vec3::Z).try_normalize())
            .unwrap_or(Vec3::X);
        let true_up = right.cross(forward);
        let half_height = (self.vfov_deg.to_radians() * 0.5).tan();
        let aspect = width as f32 / height as f32;
        CameraFrame {
            eye: self.eye,
            forward,
            right,
            true_up,
            half_width: half_height * aspect,
            half_height,
        }
    }
}

impl CameraFrame {
    /// The unit direction of the eye ray through pixel (px, py) at sub-pixel offset (u, v)
    /// in [0, 1)², py = 0 being the top row (`docs/corridor.md`).
    pub fn ray_dir(&self, px: u32, py: u32, u: f32, v: f32, width: u32, height: u32) -> Vec3 {
        let sx = (2.0 * (px as f32 + u) / width as f32 - 1.0) * self.half_width;
        let sy = (1.0 - 2.0 * (py as f32 + v) / height as f32) * self.half_height;
        (self.forward + sx * self.right + sy * self.true_up).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_camera_renders_only_when_finite_with_a_direction_and_a_field_of_view() {
        let good = Camera::yaw_pitch(Vec3::new(0.0, 1.5, 0.0), 0.3, 0.1, 60.0);
        assert_eq!(good.check(), Ok(()));
        let bad = [
            Camera::yaw_pitch(good.eye, f32::NAN, 0.0, 60.0),
            Camera {
                eye: Vec3::new(f32::INFINITY, 0.0, 0.0),
                ..good
            },
            Camera {
                forward: Vec3::ZERO,
                ..good
            },
            Camera {
                vfov_deg: 0.0,
                ..good
            },
            Camera {
                vfov_deg: 180.0,
                ..good
            },
            Camera {
                vfov_deg: f32::NAN,
                ..good
            },
        ];
        for camera in bad {
            assert!(camera.check().is_err(), "{camera:?}");
        }
    }
}
