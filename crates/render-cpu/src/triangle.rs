//! A mesh's bottom level: its triangles' normals and the BVH of `steadyray-accel` (watertight
//! triangle test, 8-wide tree) that answers the closest-hit and any-hit queries over them,
//! shared by every copy of the mesh.

use glam::{Vec3, Vec3A};
use steadyray_accel::{Bvh, BvhError};
use steadyray_render::two_level::MeshGeometry;

/// One mesh's triangles (ids are positions in [`MeshGeometry::corners`]) and their BVH.
#[derive(Clone, Debug, Default)]
pub(crate) struct MeshBvh {
    normals: Vec<Vec3A>,
    bvh: Bvh,
}

impl MeshBvh {
    /// Builds the BVH over the mesh's triangles.
    pub fn new(mesh: &MeshGeometry) -> Result<Self, BvhError> {
        Self::from_corners(&mesh.corners, &mesh.normals)
    }

    fn from_corners(corners: &[[Vec3; 3]], normals: &[Vec3]) -> Result<Self, BvhError> {
        Ok(Self {
            normals: normals.iter().map(|&n| Vec3A::from(n)).collect(),
            bvh: Bvh::build(corners)?,
        })
    }

    /// The unit normal of triangle `i`, in the mesh's space.
    #[inline]
    pub fn normal(&self, i: u32) -> Vec3A {
        self.normals[i as usize]
    }

    /// The nearest hit of `origin + t·dir` in (T_MIN, t_max): its t and triangle id (the
    /// lowest id among hits at the same t).
    #[inline]
    pub fn closest(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<(f32, u32)> {
        self.bvh.closest(origin, dir, t_max)
    }

    /// Whether any triangle is hit by `origin + t·dir` on t in (T_MIN, t_max).
    #[inline]
    pub fn any_hit(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        self.bvh.any_hit(origin, dir, t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(tris: &[[Vec3; 3]]) -> MeshBvh {
        let normals: Vec<Vec3> = tris
            .iter()
            .map(|v| (v[1] - v[0]).cross(v[2] - v[0]).normalize())
            .collect();
        MeshBvh::from_corners(tris, &normals).unwrap()
    }

    fn v(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3::new(x, y, z)
    }

    #[test]
    fn hits_both_windings_and_reports_t() {
        let set = mesh(&[
            [v(-1.0, -1.0, -3.0), v(1.0, -1.0, -3.0), v(0.0, 1.0, -3.0)],
            [v(-1.0, -1.0, -4.0), v(0.0, 1.0, -4.0), v(1.0, -1.0, -4.0)],
        ]);
        assert_eq!(set.normal(0), Vec3A::Z);
        assert_eq!(set.normal(1), Vec3A::NEG_Z);
        assert_eq!(
            set.closest(Vec3A::ZERO, Vec3A::NEG_Z, f32::INFINITY),
            Some((3.0, 0))
        );
        assert_eq!(set.closest(Vec3A::ZERO, Vec3A::NEG_Z, 2.0), None);
        let back = Vec3A::new(0.0, 0.0, -5.0);
        assert_eq!(set.closest(back, Vec3A::Z, f32::INFINITY), Some((1.0, 1)));
        assert!(set.any_hit(Vec3A::ZERO, Vec3A::NEG_Z, 3.5));
        assert!(!set.any_hit(Vec3A::ZERO, Vec3A::NEG_Z, 3.0));
    }

    #[test]
    fn shared_edges_are_watertight() {
        // Two triangles sharing the diagonal of a skewed quad; rays sweep across it.
        let a = v(-1.3, -0.7, -4.1);
        let b = v(1.1, -0.9, -3.7);
        let c = v(1.2, 1.05, -4.4);
        let d = v(-0.8, 0.9, -4.0);
        let set = mesh(&[[a, b, c], [a, c, d]]);
        let origin = Vec3A::new(0.013, -0.021, 0.37);
        for i in 0..=2000 {
            let s = i as f32 / 2000.0;
            for off in [-1e-7f32, 0.0, 1e-7] {
                let target = Vec3A::from(a.lerp(c, 0.05 + 0.9 * s)) + Vec3A::splat(off);
                let dir = (target - origin).normalize();
                assert!(
                    set.closest(origin, dir, f32::INFINITY).is_some(),
                    "leak at s={s}"
                );
                assert!(set.any_hit(origin, dir, f32::INFINITY));
            }
        }
    }
}
