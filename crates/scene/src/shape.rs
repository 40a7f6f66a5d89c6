//! Geometric primitives. All coordinates are world space, metres, right-handed, +y up.

use glam::Vec3;

/// One geometric primitive of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// A two-sided parallelogram: the points `corner + a·edge_u + b·edge_v`, a, b in [0, 1].
    /// Its surface coordinates (for checkers) are metres along the two edges.
    Quad {
        corner: Vec3,
        edge_u: Vec3,
        edge_v: Vec3,
    },
    /// A two-sided infinite plane through `point` with unit `normal`.
    Plane {
        point: Vec3,
        normal: Vec3,
    },
    /// Triangles already placed in world space.
    Mesh(TriangleMesh),
}

/// An indexed triangle mesh in world space. Degenerate triangles are removed on import.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// The three corners of triangle `i`.
    pub fn triangle(&self, i: usize) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[i];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }
}
