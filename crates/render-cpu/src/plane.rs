//! Two-sided infinite planes.

use crate::ray::{Ray, T_MIN};
use glam::{Vec3, Vec3A};

/// An infinite plane through `point` with unit `normal`, prepared for intersection.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plane {
    point: Vec3A,
    normal: Vec3A,
    /// The checker axes of `docs/shading.md`: a = normalize(cross(normal, X or Y)),
    /// b = cross(normal, a).
    axis_a: Vec3A,
    axis_b: Vec3A,
    pub material: u32,
}

impl Plane {
    /// Prepares a plane; `normal` is used as given (the scene keeps it unit length).
    pub fn new(point: Vec3, normal: Vec3, material: u32) -> Self {
        let normal = Vec3A::from(normal);
        let other = if normal.x.abs() < 0.9 {
            Vec3A::X
        } else {
            Vec3A::Y
        };
        let axis_a = normal.cross(other).normalize();
        Self {
            point: point.into(),
            normal,
            axis_a,
            axis_b: normal.cross(axis_a),
            material,
        }
    }

    /// The t in (T_MIN, t_max) where `ray` meets the plane (either side).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let t = (self.point - ray.origin).dot(self.normal) / ray.dir.dot(self.normal);
        (t > T_MIN && t < t_max).then_some(t)
    }

    /// The plane's normal.
    #[inline]
    pub fn normal(&self) -> Vec3A {
        self.normal
    }

    /// Checker coordinates: u = (p - point)·a, v = (p - point)·b.
    #[inline]
    pub fn surface_uv(&self, p: Vec3A) -> (f32, f32) {
        let rel = p - self.point;
        (rel.dot(self.axis_a), rel.dot(self.axis_b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_both_sides_and_not_behind() {
        let p = Plane::new(Vec3::new(0.0, 0.0, -2.0), Vec3::Z, 0);
        let front = Ray::new(Vec3A::ZERO, Vec3A::NEG_Z);
        assert_eq!(p.intersect(&front, f32::INFINITY), Some(2.0));
        let back = Ray::new(Vec3A::new(0.0, 0.0, -5.0), Vec3A::Z);
        assert_eq!(p.intersect(&back, f32::INFINITY), Some(3.0));
        let away = Ray::new(Vec3A::ZERO, Vec3A::Z);
        assert_eq!(p.intersect(&away, f32::INFINITY), None);
    }

    #[test]
    fn checker_axes_follow_the_contract() {
        // normal +y: a = normalize(cross(Y, X)) = -Z, b = cross(Y, -Z) = -X.
        let p = Plane::new(Vec3::ZERO, Vec3::Y, 0);
        assert_eq!(p.surface_uv(Vec3A::new(1.0, 0.0, 2.0)), (-2.0, -1.0));
        // normal +x uses Y: a = normalize(cross(X, Y)) = Z, b = cross(X, Z) = -Y.
        let p = Plane::new(Vec3::ZERO, Vec3::X, 0);
        assert_eq!(p.surface_uv(Vec3A::new(0.0, 3.0, 2.0)), (2.0, -3.0));
    }
}
