//! Mesh triangles: their normals and materials, and the BVH of `steadyray-accel` (watertight
//! triangle test, 8-wide tree) that answers the closest-hit and any-hit queries over them.

use crate::ray::Ray;
use glam::{Vec3, Vec3A};
use steadyray_accel::{Bvh, BvhError};

/// One triangle with its outward normal normalize(cross(b - a, c - a)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Triangle {
    pub v: [Vec3; 3],
    pub normal: Vec3A,
    pub material: u32,
}

impl Triangle {
    /// Prepares triangle (a, b, c); `None` when it has no area.
    pub fn new(v: [Vec3; 3], material: u32) -> Option<Self> {
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let len2 = n.length_squared();
        (len2 > 0.0 && len2.is_finite()).then(|| Self {
            v,
            normal: Vec3A::from(n.normalize()),
            material,
        })
    }
}

/// All triangles of the scene and their BVH; triangle indices are positions in the list
/// given to [`Triangles::new`].
#[derive(Clone, Debug, Default)]
pub(crate) struct Triangles {
    tris: Vec<Triangle>,
    bvh: Bvh,
}

impl Triangles {
    /// Builds the BVH over `tris`.
    pub fn new(tris: Vec<Triangle>) -> Result<Self, BvhError> {
        let corners: Vec<[Vec3; 3]> = tris.iter().map(|t| t.v).collect();
        let bvh = Bvh::build(&corners)?;
        Ok(Self { tris, bvh })
    }

    /// Triangle `i`.
    #[inline]
    pub fn get(&self, i: u32) -> &Triangle {
        &self.tris[i as usize]
    }

    /// The nearest hit in (T_MIN, t_max): its t and triangle index (the lowest index among
    /// hits at the same t).
    #[inline]
    pub fn closest(&self, ray: &Ray, t_max: f32) -> Option<(f32, u32)> {
        self.bvh.closest(ray.origin, ray.dir, t_max)
    }

    /// Whether any triangle is hit on t in (T_MIN, t_max).
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        self.bvh.any_hit(ray.origin, ray.dir, t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle::new([a.into(), b.into(), c.into()], 0).unwrap()
    }

    #[test]
    fn hits_both_windings_and_reports_t() {
        let t1 = tri([-1.0, -1.0, -3.0], [1.0, -1.0, -3.0], [0.0, 1.0, -3.0]);
        let t2 = tri([-1.0, -1.0, -4.0], [0.0, 1.0, -4.0], [1.0, -1.0, -4.0]);
        assert_eq!(t1.normal, Vec3A::Z);
        assert_eq!(t2.normal, Vec3A::NEG_Z);
        let set = Triangles::new(vec![t1, t2]).unwrap();
        let ray = Ray::new(Vec3A::ZERO, Vec3A::NEG_Z);
        assert_eq!(set.closest(&ray, f32::INFINITY), Some((3.0, 0)));
        assert_eq!(set.closest(&ray, 2.0), None);
        let back = Ray::new(Vec3A::new(0.0, 0.0, -5.0), Vec3A::Z);
        assert_eq!(set.closest(&back, f32::INFINITY), Some((1.0, 1)));
        assert!(set.any_hit(&ray, 3.5));
        assert!(!set.any_hit(&ray, 3.0));
    }

    #[test]
    fn shared_edges_are_watertight() {
        // Two triangles sharing the diagonal of a skewed quad; rays sweep across it.
        let a = Vec3::new(-1.3, -0.7, -4.1);
        let b = Vec3::new(1.1, -0.9, -3.7);
        let c = Vec3::new(1.2, 1.05, -4.4);
        let d = Vec3::new(-0.8, 0.9, -4.0);
        let set = Triangles::new(vec![
            Triangle::new([a, b, c], 0).unwrap(),
            Triangle::new([a, c, d], 0).unwrap(),
        ])
        .unwrap();
        let origin = Vec3A::new(0.013, -0.021, 0.37);
        for i in 0..=2000 {
            let s = i as f32 / 2000.0;
            for off in [-1e-7f32, 0.0, 1e-7] {
                let target = Vec3A::from(a.lerp(c, 0.05 + 0.9 * s)) + Vec3A::splat(off);
                let ray = Ray::new(origin, (target - origin).normalize());
                assert!(set.closest(&ray, f32::INFINITY).is_some(), "leak at s={s}");
                assert!(set.any_hit(&ray, f32::INFINITY));
            }
        }
    }

    #[test]
    fn degenerate_triangles_are_refused() {
        assert!(Triangle::new([Vec3::ZERO, Vec3::X, Vec3::X * 3.0], 0).is_none());
    }
}
