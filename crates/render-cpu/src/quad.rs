//! Two-sided parallelograms.

use crate::ray::{Ray, T_MIN};
use glam::{Vec3, Vec3A};

/// A quad `corner + a·edge_u + b·edge_v`, a, b in [0, 1], prepared for intersection.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Quad {
    corner: Vec3A,
    /// normalize(cross(edge_u, edge_v)).
    normal: Vec3A,
    /// Dual vectors: a = (p - corner)·dual_u, b = (p - corner)·dual_v for p in the plane.
    dual_u: Vec3A,
    dual_v: Vec3A,
    len_u: f32,
    len_v: f32,
    pub material: u32,
}

impl Quad {
    /// Prepares a quad; `None` when its edges are parallel or not finite (no plane).
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3, material: u32) -> Option<Self> {
        let (eu, ev) = (Vec3A::from(edge_u), Vec3A::from(edge_v));
        let w = eu.cross(ev);
        let w2 = w.length_squared();
        if !(w2 > 0.0 && w2.is_finite()) {
            return None;
        }
        Some(Self {
            corner: corner.into(),
            normal: w.normalize(),
            dual_u: ev.cross(w) / w2,
            dual_v: w.cross(eu) / w2,
            len_u: eu.length(),
            len_v: ev.length(),
            material,
        })
    }

    /// The t in (T_MIN, t_max) where `ray` meets the quad (either side).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let t = (self.corner - ray.origin).dot(self.normal) / ray.dir.dot(self.normal);
        if !(t > T_MIN && t < t_max) {
            return None;
        }
        let rel = ray.at(t) - self.corner;
        let a = rel.dot(self.dual_u);
        let b = rel.dot(self.dual_v);
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
    }

    /// The outward geometric normal, normalize(cross(edge_u, edge_v)).
    #[inline]
    pub fn normal(&self) -> Vec3A {
        self.normal
    }

    /// Checker coordinates of a point on the quad: metres along edge_u and edge_v from the
    /// corner.
    #[inline]
    pub fn surface_uv(&self, p: Vec3A) -> (f32, f32) {
        let rel = p - self.corner;
        (
            rel.dot(self.dual_u) * self.len_u,
            rel.dot(self.dual_v) * self.len_v,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn floor() -> Quad {
        Quad::new(
            Vec3::new(-2.0, 0.0, -12.0),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 10.0),
            0,
        )
        .unwrap()
    }

    #[test]
    fn hits_inside_misses_outside_both_sides() {
        let q = floor();
        let down = Ray::new(Vec3A::new(0.5, 1.0, -3.0), Vec3A::NEG_Y);
        assert_eq!(q.intersect(&down, f32::INFINITY), Some(1.0));
        let up = Ray::new(Vec3A::new(0.5, -2.0, -3.0), Vec3A::Y);
        assert_eq!(q.intersect(&up, f32::INFINITY), Some(2.0));
        let outside = Ray::new(Vec3A::new(2.5, 1.0, -3.0), Vec3A::NEG_Y);
        assert_eq!(q.intersect(&outside, f32::INFINITY), None);
        let parallel = Ray::new(Vec3A::new(0.0, 0.0, 0.0), Vec3A::NEG_Z);
        assert_eq!(q.intersect(&parallel, f32::INFINITY), None);
    }

    #[test]
    fn normal_and_uv() {
        let q = floor();
        // cross(+x, +z) = -y
        assert_eq!(q.normal(), Vec3A::NEG_Y);
        let (u, v) = q.surface_uv(Vec3A::new(-1.25, 0.0, -9.5));
        assert!((u - 0.75).abs() < 1e-6 && (v - 2.5).abs() < 1e-6, "{u} {v}");
    }

    #[test]
    fn degenerate_quads_are_refused() {
        assert!(Quad::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0, 0).is_none());
    }
}
