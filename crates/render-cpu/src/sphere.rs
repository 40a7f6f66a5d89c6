//! Spheres, with a numerically robust quadratic.

use crate::ray::{Ray, T_MIN};
use glam::{Vec3, Vec3A};

/// A sphere prepared for intersection.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sphere {
    center: Vec3A,
    radius2: f32,
    inv_radius: f32,
    pub material: u32,
}

impl Sphere {
    /// Prepares a sphere of `radius` > 0 around `center`.
    pub fn new(center: Vec3, radius: f32, material: u32) -> Self {
        Self {
            center: center.into(),
            radius2: radius * radius,
            inv_radius: 1.0 / radius,
            material,
        }
    }

    /// The nearest t in (T_MIN, t_max) where `ray` meets the sphere.
    ///
    /// The discriminant is computed from the distance between the centre and the ray's
    /// line, not as b² - ac, so small or far spheres do not lose it to cancellation
    /// ("Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems, ch. 7); the
    /// roots come from the stable pair q/a, c/q.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let f = ray.origin - self.center;
        let half_b = f.dot(ray.dir);
        let off_axis = f - (half_b * ray.inv_len2) * ray.dir;
        let disc = (self.radius2 - off_axis.length_squared()) / ray.inv_len2;
        if disc < 0.0 {
            return None;
        }
        let c = f.length_squared() - self.radius2;
        let q = -(half_b + disc.sqrt().copysign(half_b));
        let r0 = q * ray.inv_len2;
        let r1 = c / q;
        let (near, far) = if r0 <= r1 { (r0, r1) } else { (r1, r0) };
        if near > T_MIN && near < t_max {
            Some(near)
        } else if far > T_MIN && far < t_max {
            Some(far)
        } else {
            None
        }
    }

    /// The outward unit normal (p - c) / r at a point `p` on the sphere.
    #[inline]
    pub fn normal(&self, p: Vec3A) -> Vec3A {
        (p - self.center) * self.inv_radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_front_then_back_from_inside() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0, 0);
        let ray = Ray::new(Vec3A::ZERO, Vec3A::NEG_Z);
        assert_eq!(s.intersect(&ray, f32::INFINITY), Some(4.0));
        let inside = Ray::new(Vec3A::new(0.0, 0.0, -5.0), Vec3A::NEG_Z);
        assert_eq!(s.intersect(&inside, f32::INFINITY), Some(1.0));
        assert_eq!(s.intersect(&ray, 3.5), None);
        let behind = Ray::new(Vec3A::ZERO, Vec3A::Z);
        assert_eq!(s.intersect(&behind, f32::INFINITY), None);
    }

    #[test]
    fn small_far_sphere_keeps_its_discriminant() {
        // b² - ac would cancel catastrophically here (b² ~ 1e8, ac differs by 1e-6).
        let s = Sphere::new(Vec3::new(0.0, 0.0, -1.0e4), 1.0e-3, 0);
        let ray = Ray::new(Vec3A::ZERO, Vec3A::NEG_Z);
        let t = s.intersect(&ray, f32::INFINITY).expect("hit");
        assert!((t - (1.0e4 - 1.0e-3)).abs() < 2e-3, "t = {t}");
        let grazing = Ray::new(Vec3A::new(0.0, 0.9e-3, 0.0), Vec3A::NEG_Z);
        assert!(s.intersect(&grazing, f32::INFINITY).is_some());
        let missing = Ray::new(Vec3A::new(0.0, 1.1e-3, 0.0), Vec3A::NEG_Z);
        assert!(s.intersect(&missing, f32::INFINITY).is_none());
    }

    #[test]
    fn unnormalised_directions_give_the_same_point() {
        let s = Sphere::new(Vec3::new(0.3, -0.2, -4.0), 0.7, 0);
        let d = Vec3A::new(0.05, -0.04, -1.0).normalize();
        let a = Ray::new(Vec3A::ZERO, d);
        let b = Ray::new(Vec3A::ZERO, d * 3.0);
        let pa = a.at(s.intersect(&a, f32::INFINITY).unwrap());
        let pb = b.at(s.intersect(&b, f32::INFINITY).unwrap());
        assert!((pa - pb).length() < 1e-5);
        assert!((s.normal(pa).length() - 1.0).abs() < 1e-5);
    }
}
