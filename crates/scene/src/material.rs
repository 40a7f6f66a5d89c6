//! Surface materials of the Whitted model (see `docs/shading.md`).

use glam::Vec3;

/// How a surface responds to light. Colours are linear RGB.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// Lambert-like local shading from point lights plus the ambient term; optionally a
    /// checker pattern alternating between `albedo` and the checker's second albedo.
    Diffuse {
        albedo: Vec3,
        checker: Option<Checker>,
    },
    /// A perfect mirror: the reflected radiance scaled by `reflectance`.
    Mirror { reflectance: Vec3 },
    /// A clear dielectric (glass, water): reflects or refracts by the Fresnel equations,
    /// with total internal reflection. `tint` scales refracted light.
    Dielectric { ior: f32, tint: Vec3 },
    /// A surface that emits `radiance` and reflects nothing.
    Emissive { radiance: Vec3 },
}

/// A checker pattern of squares `size` metres wide in the surface's own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker {
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
