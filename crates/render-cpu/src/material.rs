//! Materials as the integrator reads them.

use glam::Vec3A;
use steadyray_scene::Material;

/// A scene material converted to SIMD-friendly vectors.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Mat {
    Diffuse {
        albedo: Vec3A,
        checker: Option<Checker>,
    },
    Mirror {
        reflectance: Vec3A,
    },
    Dielectric {
        ior: f32,
        tint: Vec3A,
    },
    Emissive {
        radiance: Vec3A,
    },
}

/// A checker's square size (metres) and its odd squares' albedo.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Checker {
    pub size: f32,
    pub albedo_b: Vec3A,
}

impl From<&Material> for Mat {
    fn from(m: &Material) -> Self {
        match *m {
            Material::Diffuse { albedo, checker } => Mat::Diffuse {
                albedo: albedo.into(),
                checker: checker.map(|c| Checker {
                    size: c.size,
                    albedo_b: c.albedo_b.into(),
                }),
            },
            Material::Mirror { reflectance } => Mat::Mirror {
                reflectance: reflectance.into(),
            },
            Material::Dielectric { ior, tint } => Mat::Dielectric {
                ior,
                tint: tint.into(),
            },
            Material::Emissive { radiance } => Mat::Emissive {
                radiance: radiance.into(),
            },
        }
    }
}

/// Whether the checker square containing surface coordinates `coords` is odd:
/// Σ floor(coord / size) is odd.
#[inline]
pub(crate) fn checker_is_odd(coords: &[f32], size: f32) -> bool {
    let sum = coords
        .iter()
        .fold(0i64, |acc, &c| acc + (c / size).floor() as i64);
    sum & 1 == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parity_handles_negative_coordinates() {
        assert!(!checker_is_odd(&[0.1, 0.2], 0.5));
        assert!(checker_is_odd(&[0.6, 0.2], 0.5));
        assert!(checker_is_odd(&[-0.1, 0.2], 0.5));
        assert!(!checker_is_odd(&[-0.1, -0.2], 0.5));
        assert!(checker_is_odd(&[-0.1, -0.2, 0.6], 0.5));
        assert!(!checker_is_odd(&[-0.1, -0.2, 1.1], 0.5));
    }
}
