//! Rays and the two epsilons of `docs/shading.md`.

use glam::Vec3A;

/// Rays hit on t in (T_MIN, ∞); shadow rays stop T_MIN short of the light.
pub const T_MIN: f32 = 1e-4;
/// Secondary and shadow rays start this far off the surface, along the facing normal.
pub const EPS: f32 = 1e-4;

/// A ray `origin + t · dir`. `dir` is close to unit length but never renormalised, as in the
/// shading contract; `inv_len2` = 1 / |dir|² lets intersectors stay exact anyway.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ray {
    pub origin: Vec3A,
    pub dir: Vec3A,
    pub inv_len2: f32,
}

impl Ray {
    /// A ray from `origin` along `dir`.
    #[inline]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        Self {
            origin,
            dir,
            inv_len2: 1.0 / dir.length_squared(),
        }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + t * self.dir
    }
}
