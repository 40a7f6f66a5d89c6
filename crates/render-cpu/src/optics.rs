//! Reflection, refraction and the Fresnel equations exactly as `docs/shading.md` writes
//! them. `n` is always the normal flipped to face the incoming direction `d` (dot(n, d) < 0).

use glam::Vec3A;

/// The mirror direction d - 2·dot(d, n)·n.
#[inline]
pub fn reflect(d: Vec3A, n: Vec3A) -> Vec3A {
    d - 2.0 * d.dot(n) * n
}

/// The cosines (cos_i, cos_t) of a ray `d` crossing an interface with relative index
/// `eta` = η_i/η_t, or `None` on total internal reflection (sin²_t > 1).
#[inline]
pub fn snell(d: Vec3A, n: Vec3A, eta: f32) -> Option<(f32, f32)> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    (sin2_t <= 1.0).then(|| (cos_i, (1.0 - sin2_t).sqrt()))
}

/// The exact unpolarised Fresnel reflectance F = (r_s² + r_p²) / 2 with the ratios written
/// in `eta` = η_i/η_t.
#[inline]
pub fn fresnel(cos_i: f32, cos_t: f32, eta: f32) -> f32 {
    let r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (r_s * r_s + r_p * r_p) * 0.5
}

/// The refracted direction eta·d + (eta·cos_i - cos_t)·n for cosines from [`snell`].
#[inline]
pub fn refract_with(d: Vec3A, n: Vec3A, eta: f32, cos_i: f32, cos_t: f32) -> Vec3A {
    eta * d + (eta * cos_i - cos_t) * n
}

/// The refracted direction of `d` through an interface with relative index `eta`, or
/// `None` on total internal reflection.
pub fn refract(d: Vec3A, n: Vec3A, eta: f32) -> Option<Vec3A> {
    snell(d, n, eta).map(|(cos_i, cos_t)| refract_with(d, n, eta, cos_i, cos_t))
}
