//! Geometric primitives. Coordinates are world space, metres, right-handed, +y up, except a
//! mesh's vertices, which its placement puts in the world.

use crate::Transform;
use glam::Vec3;

/// One geometric primitive of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere {
        /// Centre, world space.
        center: Vec3,
        /// Radius, metres (> 0).
        radius: f32,
    },
    /// A two-sided parallelogram: the points `corner + a·edge_u + b·edge_v`, a, b in [0, 1].
    /// Its surface coordinates (for checkers) are metres along the two edges.
    Quad {
        /// A corner, world space.
        corner: Vec3,
        /// The first edge from `corner`.
        edge_u: Vec3,
        /// The second edge from `corner`.
        edge_v: Vec3,
    },
    /// A two-sided infinite plane through `point` with unit `normal`.
    Plane {
        /// A point on the plane, world space.
        point: Vec3,
        /// Unit normal (either side: the plane is two-sided).
        normal: Vec3,
    },
    /// A triangle mesh, put in the world by `placement`, in one copy or in one copy per
    /// instance.
    Mesh {
        /// The mesh in its own (model) space.
        mesh: TriangleMesh,
        /// Model space to world: the shape's `scale`, `rotate_y_deg` and `translate`.
        placement: Transform,
        /// Copies of the mesh: each instance's transform is applied after the placement's
        /// scale and rotation and before its translation, i.e. in world units about the
        /// placement's origin. Empty: one copy at the placement.
        instances: Vec<Transform>,
    },
}

impl Shape {
    /// A single copy of `mesh` at `placement`.
    pub fn mesh(mesh: TriangleMesh, placement: Transform) -> Self {
        Shape::Mesh {
            mesh,
            placement,
            instances: Vec::new(),
        }
    }

    /// The point motion turns and scales the shape about: a mesh's translation, a sphere's
    /// centre, a quad's corner, a plane's point.
    pub fn origin(&self) -> Vec3 {
        match self {
            Shape::Sphere { center, .. } => *center,
            Shape::Quad { corner, .. } => *corner,
            Shape::Plane { point, .. } => *point,
            Shape::Mesh { placement, .. } => placement.translate,
        }
    }
}

/// An indexed triangle mesh in its own (model) space. Degenerate triangles are removed on
/// import.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct TriangleMesh {
    /// Corner positions.
    pub positions: Vec<Vec3>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// A closed axis-aligned box from `lo` to `hi`: 8 corners, 12 outward-facing triangles.
    pub fn cuboid(lo: Vec3, hi: Vec3) -> Self {
        let corner = |i: u32| {
            Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        };
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        Self {
            positions: (0..8).map(corner).collect(),
            triangles: quads
                .iter()
                .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
                .collect(),
        }
    }

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
