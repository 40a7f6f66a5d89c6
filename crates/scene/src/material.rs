//! Surface materials of the Whitted model (see `docs/shading.md`).

use glam::Vec3;

/// How a surface responds to light. Colours are linear RGB.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// Lambert-like local shading from point lights plus the ambient term; optionally a
    /// checker pattern alternating between `albedo` and the checker's second albedo.
    Diffuse {
        /// Diffuse reflectance, per channel (the even squares' when checkered).
        albedo: Vec3,
        /// `None`: one colour over the whole surface.
        checker: Option<Checker>,
    },
    /// A perfect mirror: the reflected radiance scaled by `reflectance`.
    Mirror {
        /// Factor on the reflected radiance, per channel; the albedo at the depth limit.
        reflectance: Vec3,
    },
    /// A clear dielectric (glass, water): reflects or refracts by the Fresnel equations,
    /// with total internal reflection. `tint` scales refracted light.
    Dielectric {
        /// Index of refraction η of the inside; outside is vacuum (1.5: glass).
        ior: f32,
        /// Factor on refracted light, per channel (1: clear); the albedo at the depth limit.
        tint: Vec3,
    },
    /// A surface that emits `radiance` and reflects nothing.
    Emissive {
        /// Emitted radiance, linear RGB.
        radiance: Vec3,
    },
}

/// A checker pattern of squares `size` metres wide in the surface's own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker {
    /// The side of a square, metres (> 0).
    pub size: f32,
    /// The albedo of the odd squares (the even squares use the material's `albedo`).
    pub albedo_b: Vec3,
}

impl Material {
    /// The colour used when the surface is shaded locally (diffuse lighting), which is also
    /// how mirrors and dielectrics look once the reflection depth R is used up.
    pub fn base_colour(&self) -> Vec3 {
        match *self {
            Material::Diffuse { albedo, .. } => albedo,
            Material::Mirror { reflectance } => reflectance,
            Material::Dielectric { tint, .. } => tint,
            Material::Emissive { radiance } => radiance,
        }
    }
}
