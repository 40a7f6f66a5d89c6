//! The one kind of transform the scene format writes: a per-axis scale, then a rotation about
//! +y, then a translation. Mesh placements, instances and motion keys are all of this kind.

use glam::{DAffine3, DMat3, DVec3, Vec3};

/// Scale (per axis) first, then a right-handed rotation of `rotate_y_deg` degrees about +y,
/// then a translation. The identity transform leaves positions bit-for-bit unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Translation, applied last.
    pub translate: Vec3,
    /// Per-axis scale, applied first.
    pub scale: Vec3,
    /// Right-handed rotation about the +y axis, in degrees.
    pub rotate_y_deg: f32,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    /// The transform that changes nothing.
    pub const IDENTITY: Transform = Transform {
        translate: Vec3::ZERO,
        scale: Vec3::ONE,
        rotate_y_deg: 0.0,
    };

    /// Whether this transform changes nothing (it is then not applied at all).
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// The transformed position of point `p`, in `f32` (how a placed mesh's vertices are
    /// computed, so that a static mesh keeps the positions it always had).
    pub fn apply(&self, p: Vec3) -> Vec3 {
        let s = p * self.scale;
        let (sin, cos) = self.rotate_y_deg.to_radians().sin_cos();
        let r = Vec3::new(cos * s.x + sin * s.z, s.y, -sin * s.x + cos * s.z);
        r + self.translate
    }

    /// The transform as an affine map in `f64`, for composing with others.
    pub fn to_affine(&self) -> DAffine3 {
        DAffine3 {
            matrix3: rotation_y(f64::from(self.rotate_y_deg))
                * DMat3::from_diagonal(self.scale.into()),
            translation: self.translate.into(),
        }
    }

    /// The linear part (scale, then rotation) alone, as an affine map in `f64`.
    pub fn linear(&self) -> DAffine3 {
        DAffine3 {
            translation: DVec3::ZERO,
            ..self.to_affine()
        }
    }
}

/// The right-handed rotation by `deg` degrees about +y: it takes +x toward -z.
pub fn rotation_y(deg: f64) -> DMat3 {
    let (sin, cos) = deg.to_radians().sin_cos();
    DMat3::from_cols(
        DVec3::new(cos, 0.0, -sin),
        DVec3::Y,
        DVec3::new(sin, 0.0, cos),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_is_scale_rotate_translate() {
        let t = Transform {
            translate: Vec3::new(10.0, 0.0, 0.0),
            scale: Vec3::splat(2.0),
            rotate_y_deg: 90.0,
        };
        // (1,0,0) scaled to (2,0,0), rotated +90° about y to (0,0,-2), moved to (10,0,-2).
        let p = t.apply(Vec3::X);
        assert!((p - Vec3::new(10.0, 0.0, -2.0)).length() < 1e-5, "{p}");
        let q = t.to_affine().transform_point3(DVec3::X);
        assert!((q - DVec3::new(10.0, 0.0, -2.0)).length() < 1e-12, "{q}");
        assert!(Transform::default().is_identity());
        assert!(!t.is_identity());
        let v = t.linear().transform_point3(DVec3::X);
        assert!((v - DVec3::new(0.0, 0.0, -2.0)).length() < 1e-12, "{v}");
    }
}
