//! The scene as both renderers lay it out for their two-level BVH, computed here once so that
//! both get the same numbers bit for bit.
//!
//! - Bottom level ([`SceneLayout::meshes`]): one triangle list per mesh object, with its
//!   normals, built into a BVH once per scene and shared by all the mesh's copies. A mesh
//!   that never moves and has one copy is kept with its placement applied (world space, so
//!   rays need no transform); any other mesh in its own model space.
//! - Top level ([`SceneLayout::leaves_at`]): per frame, every object that exists at that time
//!   as leaves in object order (a sphere, a quad, or one [`Instance`] per mesh copy), each
//!   with its world box. A leaf's index in that list is its key: among hits at the same
//!   distance the lowest key wins (and within a mesh, the lowest triangle), as in a loop over
//!   the objects in order.
//! - Infinite planes stay outside both levels: every ray tests them after the tree, and a
//!   plane wins a tie only against nothing.

use crate::RenderError;
use crate::temporal::ID_MASK;
use glam::{DMat3, DVec3, Vec3, Vec3A};
use steadyray_accel::Bounds;
use steadyray_scene::{Pose, Scene, Shape};

/// The most surface ids a scene may take: the temporal mode's ids below its miss id.
const MAX_SURFACES: u32 = ID_MASK;

/// One mesh object's triangles as its bottom level holds them.
#[derive(Clone, Debug)]
pub struct MeshGeometry {
    /// The corners of its triangles with area (degenerate ones are left out), in world space
    /// when `baked`, else in the mesh's model space. A triangle's index here is its id.
    pub corners: Vec<[Vec3; 3]>,
    /// Per triangle, its unit normal normalize(cross(b - a, c - a)) in the same space.
    pub normals: Vec<Vec3>,
    /// The box around `corners`.
    pub bounds: Bounds,
    /// Whether the placement is applied: the mesh never moves and has one copy.
    pub baked: bool,
}

/// An infinite plane, its material and its surface id.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneLeaf {
    /// A point on the plane.
    pub point: Vec3,
    /// Its normal.
    pub normal: Vec3,
    /// Its material's index.
    pub material: u32,
    /// Its surface id ([`SceneLayout::surface_count`]).
    pub surface: u32,
}

/// One leaf of the top level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Leaf {
    /// A sphere at the frame's time.
    Sphere {
        /// Its centre.
        center: Vec3,
        /// Its radius.
        radius: f32,
        /// Its material's index.
        material: u32,
    },
    /// A two-sided parallelogram at the frame's time.
    Quad {
        /// One corner.
        corner: Vec3,
        /// The edge from it along u.
        edge_u: Vec3,
        /// The edge from it along v.
        edge_v: Vec3,
        /// Its material's index.
        material: u32,
    },
    /// A copy of a mesh.
    Instance(Instance),
}

/// One copy of a mesh: which mesh, and how rays and normals move between it and the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Index into [`SceneLayout::meshes`].
    pub mesh: u32,
    /// Its material's index.
    pub material: u32,
    /// World to mesh space as three rows (x, y, z, translation): a ray `o + t·d` becomes
    /// `o' + t·d'` with `o'_i = r_i.x·o.x + r_i.y·o.y + r_i.z·o.z + r_i.w` and
    /// `d'_i = r_i.x·d.x + r_i.y·d.y + r_i.z·d.z` (in that order, both backends), and the
    /// same t. `None` for a baked mesh: rays stay as they are.
    pub to_mesh: Option<[[f32; 4]; 3]>,
    /// Rows of the cofactor matrix of the mesh-to-world map's linear part: a mesh normal n
    /// becomes the world normal (r_0·n, r_1·n, r_2·n), normalised. It keeps the direction of
    /// cross(b - a, c - a) of the placed corners (as a baked mesh's normal does).
    pub normal_rows: [[f32; 3]; 3],
}

impl Instance {
    /// The ray `origin + t·dir` in the instance's mesh space (unchanged for a baked mesh).
    #[inline]
    pub fn ray_to_mesh(&self, origin: Vec3A, dir: Vec3A) -> (Vec3A, Vec3A) {
        let Some(rows) = &self.to_mesh else {
            return (origin, dir);
        };
        let point = |r: &[f32; 4]| r[0] * origin.x + r[1] * origin.y + r[2] * origin.z + r[3];
        let vector = |r: &[f32; 4]| r[0] * dir.x + r[1] * dir.y + r[2] * dir.z;
        (
            Vec3A::new(point(&rows[0]), point(&rows[1]), point(&rows[2])),
            Vec3A::new(vector(&rows[0]), vector(&rows[1]), vector(&rows[2])),
        )
    }

    /// The world normal of a triangle whose mesh normal is `n` (itself for a baked mesh):
    /// `m = (r_0·n, r_1·n, r_2·n)`, each dot product left to right, then
    /// `m · (1 / sqrt(m.x·m.x + m.y·m.y + m.z·m.z))`.
    #[inline]
    pub fn normal_to_world(&self, n: Vec3A) -> Vec3A {
        if self.to_mesh.is_none() {
            return n;
        }
        let row = |r: &[f32; 3]| r[0] * n.x + r[1] * n.y + r[2] * n.z;
        let rows = &self.normal_rows;
        let m = Vec3A::new(row(&rows[0]), row(&rows[1]), row(&rows[2]));
        let inv = 1.0 / (m.x * m.x + m.y * m.y + m.z * m.z).sqrt();
        m * inv
    }
}

/// A scene laid out for the two-level BVH: its meshes and planes, and what each object
/// becomes in the top level.
#[derive(Clone, Debug)]
pub struct SceneLayout {
    /// One per mesh object, in object order.
    pub meshes: Vec<MeshGeometry>,
    /// The infinite planes, in object order.
    pub planes: Vec<PlaneLeaf>,
    /// Per object, its index in `meshes` (mesh objects only).
    object_mesh: Vec<Option<u32>>,
    /// Per object, its first surface id: every object has one id per copy (a mesh with
    /// instances one per instance, any other object one), numbered in object order, so an
    /// id names the same surface in every frame (the temporal mode's surface id).
    surface_base: Vec<u32>,
    surface_count: u32,
    /// Whether any object moves, appears or disappears (else the leaves never change).
    pub animated: bool,
}

impl SceneLayout {
    /// Lays out `scene`, refusing what would make tracing panic or fill the image with NaN:
    /// material indices out of range, non-positive radii, quads with parallel edges, zero
    /// plane normals, vertex indices out of range.
    pub fn new(scene: &Scene) -> Result<Self, RenderError> {
        let bad = |name: &str, why: &str| RenderError::Scene(format!("object {name:?}: {why}"));
        let mut layout = SceneLayout {
            meshes: Vec::new(),
            planes: Vec::new(),
            object_mesh: Vec::with_capacity(scene.objects.len()),
            surface_base: Vec::with_capacity(scene.objects.len()),
            surface_count: 0,
            animated: scene.is_animated(),
        };
        let mut next_surface = 0u32;
        for obj in &scene.objects {
            if obj.material >= scene.materials.len() {
                return Err(bad(&obj.name, "material index out of range"));
            }
            let material = obj.material as u32;
            let copies = match &obj.shape {
                Shape::Mesh { instances, .. } => instances.len().max(1),
                _ => 1,
            };
            let surface = next_surface;
            next_surface = u32::try_from(copies)
                .ok()
                .and_then(|c| next_surface.checked_add(c))
                .filter(|&n| n <= MAX_SURFACES)
                .ok_or_else(|| bad(&obj.name, "too many objects and instances"))?;
            layout.surface_base.push(surface);
            let mut mesh_index = None;
            match &obj.shape {
                &Shape::Sphere { radius, .. } => {
                    if !(radius > 0.0 && radius.is_finite()) {
                        return Err(bad(&obj.name, "sphere radius must be positive"));
                    }
                }
                &Shape::Quad { edge_u, edge_v, .. } => {
                    if !quad_has_area(edge_u, edge_v) {
                        return Err(bad(&obj.name, "quad edges are parallel"));
                    }
                }
                &Shape::Plane { point, normal } => {
                    if normal.length_squared() == 0.0 || !normal.is_finite() {
                        return Err(bad(&obj.name, "plane normal must be a non-zero vector"));
                    }
                    layout.planes.push(PlaneLeaf {
                        point,
                        normal,
                        material,
                        surface,
                    });
                }
                Shape::Mesh {
                    mesh,
                    placement,
                    instances,
                } => {
                    let baked = obj.motion.is_none() && instances.is_empty();
                    let mut corners = Vec::with_capacity(mesh.triangles.len());
                    let mut normals = Vec::with_capacity(mesh.triangles.len());
                    for tri in &mesh.triangles {
                        let mut v = [Vec3::ZERO; 3];
                        for (corner, &vi) in v.iter_mut().zip(tri) {
                            let p = *mesh
                                .positions
                                .get(vi as usize)
                                .ok_or_else(|| bad(&obj.name, "vertex index out of range"))?;
                            *corner = if baked { placement.apply(p) } else { p };
                        }
                        // Degenerate (or non-finite) triangles cannot be hit: leave them out.
                        let n = (v[1] - v[0]).cross(v[2] - v[0]);
                        let len2 = n.length_squared();
                        if len2 > 0.0 && len2.is_finite() && v.iter().all(|c| c.is_finite()) {
                            corners.push(v);
                            normals.push(n.normalize());
                        }
                    }
                    mesh_index = Some(layout.meshes.len() as u32);
                    layout.meshes.push(MeshGeometry {
                        bounds: Bounds::around(corners.iter().flatten().copied()),
                        corners,
                        normals,
                        baked,
                    });
                }
            }
            layout.object_mesh.push(mesh_index);
        }
        layout.surface_count = next_surface;
        Ok(layout)
    }

    /// How many surface ids the scene's objects take.
    pub fn surface_count(&self) -> u32 {
        self.surface_count
    }

    /// The top level's leaves at scene time `t_s` (objects in order, those that do not exist
    /// then left out; planes never), each with its world box, its surface id and the index
    /// in `scene.objects` of its object (what a hit belongs to, to follow its motion), into
    /// `leaves`, `boxes`, `surfaces` and `objects` (cleared first). `scene` must be the scene
    /// this layout was made from.
    pub fn leaves_at(
        &self,
        scene: &Scene,
        t_s: f64,
        leaves: &mut Vec<Leaf>,
        boxes: &mut Vec<Bounds>,
        surfaces: &mut Vec<u32>,
        objects: &mut Vec<u32>,
    ) {
        leaves.clear();
        boxes.clear();
        surfaces.clear();
        objects.clear();
        for (index, ((obj, &mesh), &surface)) in scene
            .objects
            .iter()
            .zip(&self.object_mesh)
            .zip(&self.surface_base)
            .enumerate()
        {
            let material = obj.material as u32;
            match obj.pose_at(t_s) {
                None | Some(Pose::Plane { .. }) => {}
                Some(Pose::Sphere { center, radius }) => {
                    surfaces.push(surface);
                    leaves.push(Leaf::Sphere {
                        center,
                        radius,
                        material,
                    });
                    boxes.push(Bounds {
                        min: center - radius,
                        max: center + radius,
                    });
                }
                Some(Pose::Quad {
                    corner,
                    edge_u,
                    edge_v,
                }) => {
                    // A moving quad squashed flat for a moment has nothing to hit.
                    if quad_has_area(edge_u, edge_v) {
                        surfaces.push(surface);
                        leaves.push(Leaf::Quad {
                            corner,
                            edge_u,
                            edge_v,
                            material,
                        });
                        boxes.push(Bounds::around([
                            corner,
                            corner + edge_u,
                            corner + edge_v,
                            corner + edge_u + edge_v,
                        ]));
                    }
                }
                Some(Pose::Mesh { copies, .. }) => {
                    let Some(mesh) = mesh else { continue };
                    let geometry = &self.meshes[mesh as usize];
                    if geometry.corners.is_empty() {
                        continue;
                    }
                    for (copy_index, copy) in (0u32..).zip(copies) {
                        let (instance, bounds) = if geometry.baked {
                            (
                                Instance {
                                    mesh,
                                    material,
                                    to_mesh: None,
                                    normal_rows: [
                                        [1.0, 0.0, 0.0],
                                        [0.0, 1.0, 0.0],
                                        [0.0, 0.0, 1.0],
                                    ],
                                },
                                geometry.bounds,
                            )
                        } else {
                            let inverse = copy.inverse();
                            let cofactor =
                                copy.matrix3.inverse().transpose() * copy.matrix3.determinant();
                            let to_mesh = [0, 1, 2].map(|i| {
                                let r = inverse.matrix3.row(i).as_vec3();
                                [r.x, r.y, r.z, inverse.translation[i] as f32]
                            });
                            let normal_rows =
                                [0, 1, 2].map(|i| cofactor.row(i).as_vec3().to_array());
                            let b = geometry.bounds;
                            let corners = (0..8).map(|k| {
                                let pick = |bit: u32, lo: f32, hi: f32| {
                                    f64::from(if k & bit == 0 { lo } else { hi })
                                };
                                let p = DVec3::new(
                                    pick(1, b.min.x, b.max.x),
                                    pick(2, b.min.y, b.max.y),
                                    pick(4, b.min.z, b.max.z),
                                );
                                copy.transform_point3(p).as_vec3()
                            });
                            (
                                Instance {
                                    mesh,
                                    material,
                                    to_mesh: Some(to_mesh),
                                    normal_rows,
                                },
                                Bounds::around(corners),
                            )
                        };
                        // A copy squashed flat or sent to infinity has nothing to hit.
                        let finite = bounds.min.is_finite() && bounds.max.is_finite();
                        if finite && invertible(&copy.matrix3) {
                            surfaces.push(surface + copy_index);
                            leaves.push(Leaf::Instance(instance));
                            boxes.push(bounds);
                        }
                    }
                }
            }
            // Leaves pushed for this object (a `continue` above pushes none).
            objects.resize(leaves.len(), index as u32);
        }
    }
}

/// Whether a quad with these edges has area, by the test both backends prepare quads with.
fn quad_has_area(edge_u: Vec3, edge_v: Vec3) -> bool {
    let w2 = Vec3A::from(edge_u)
        .cross(Vec3A::from(edge_v))
        .length_squared();
    w2 > 0.0 && w2.is_finite()
}

/// Whether a copy's linear map can be inverted in `f32` terms (not squashed flat).
fn invertible(m: &DMat3) -> bool {
    let det = m.determinant();
    det.is_finite() && det.abs() > 1e-30
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_scene::scene_of as scene;
    use steadyray_scene::{Motion, MotionKey, Object, Transform, TriangleMesh};

    fn triangle() -> TriangleMesh {
        TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * 2.0],
            triangles: vec![[0, 1, 2], [0, 1, 3]],
        }
    }

    #[test]
    fn static_meshes_are_baked_and_moving_ones_transform_rays() {
        let placement = Transform {
            translate: Vec3::new(0.0, 0.0, -5.0),
            scale: Vec3::new(2.0, 1.0, 1.0),
            rotate_y_deg: 30.0,
        };
        let still = Object::fixed("still", Shape::mesh(triangle(), placement), 0);
        let moving = Object {
            motion: Some(Motion {
                keys: vec![MotionKey {
                    t: 0.0,
                    translate: Some(Vec3::new(1.0, 0.0, 0.0)),
                    rotate_y_deg: None,
                    scale: None,
                }],
                ..Default::default()
            }),
            ..Object::fixed("moving", Shape::mesh(triangle(), placement), 0)
        };
        let s = scene(vec![still, moving]);
        let layout = SceneLayout::new(&s).unwrap();
        assert!(layout.animated);
        assert_eq!(layout.meshes.len(), 2);
        // The degenerate triangle is left out.
        assert_eq!(layout.meshes[0].corners.len(), 1);
        assert!(layout.meshes[0].baked && !layout.meshes[1].baked);
        assert_eq!(layout.meshes[0].corners[0][1], placement.apply(Vec3::X));
        assert_eq!(layout.meshes[1].corners[0][1], Vec3::X);

        let (mut leaves, mut boxes, mut ids) = (Vec::new(), Vec::new(), Vec::new());
        layout.leaves_at(&s, 0.5, &mut leaves, &mut boxes, &mut ids, &mut Vec::new());
        assert_eq!(ids, [0, 1]);
        assert_eq!(leaves.len(), 2);
        let (Leaf::Instance(a), Leaf::Instance(b)) = (leaves[0], leaves[1]) else {
            panic!("two instances: {leaves:?}");
        };
        assert_eq!(a.to_mesh, None);
        // The moving copy: a world point of the baked copy, moved by +1 x, maps back to the
        // model-space corner.
        let world = Vec3A::from(placement.apply(Vec3::X)) + Vec3A::X;
        let (o, d) = b.ray_to_mesh(world, Vec3A::new(0.0, 0.0, 1.0));
        assert!((o - Vec3A::X).length() < 1e-5, "{o}");
        // The normal follows the placed triangle's winding: cross(b - a, c - a) of the
        // baked corners.
        let c = layout.meshes[0].corners[0];
        let baked_normal = Vec3A::from((c[1] - c[0]).cross(c[2] - c[0]).normalize());
        let n = b.normal_to_world(Vec3A::from(layout.meshes[1].normals[0]));
        assert!((n - baked_normal).length() < 1e-5, "{n} vs {baked_normal}");
        // The ray direction keeps t: mesh-space points at t match world points at t.
        let p_world = world + Vec3A::new(0.0, 0.0, 1.0) * 2.0;
        let (p_mesh, _) = b.ray_to_mesh(p_world, Vec3A::ZERO);
        assert!((o + d * 2.0 - p_mesh).length() < 1e-5);
        // Boxes hold their leaves.
        assert!(boxes[1].min.cmple(Vec3::from(world)).all());
        assert!(boxes[1].max.cmpge(Vec3::from(world)).all());
    }

    #[test]
    fn leaves_follow_object_order_and_skip_what_does_not_exist() {
        let ball = Object::fixed(
            "ball",
            Shape::Sphere {
                center: Vec3::new(0.0, 1.0, 0.0),
                radius: 0.5,
            },
            0,
        );
        let floor = Object::fixed(
            "floor",
            Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            0,
        );
        let later = Object {
            motion: Some(Motion {
                visible: Some(vec![[1.0, 2.0]]),
                ..Default::default()
            }),
            ..Object::fixed(
                "later",
                Shape::Quad {
                    corner: Vec3::ZERO,
                    edge_u: Vec3::X,
                    edge_v: Vec3::Z,
                },
                0,
            )
        };
        let s = scene(vec![later, floor, ball]);
        let layout = SceneLayout::new(&s).unwrap();
        assert_eq!(layout.planes.len(), 1);
        let (mut leaves, mut boxes, mut ids) = (Vec::new(), Vec::new(), Vec::new());
        layout.leaves_at(&s, 0.0, &mut leaves, &mut boxes, &mut ids, &mut Vec::new());
        assert_eq!(leaves.len(), 1);
        assert!(matches!(leaves[0], Leaf::Sphere { radius: 0.5, .. }));
        // Surface ids stay with their objects whatever exists: later 0, floor 1, ball 2.
        assert_eq!((ids.as_slice(), layout.planes[0].surface), (&[2][..], 1));
        assert_eq!(layout.surface_count(), 3);
        layout.leaves_at(&s, 1.5, &mut leaves, &mut boxes, &mut ids, &mut Vec::new());
        assert_eq!(ids, [0, 2]);
        assert!(matches!(leaves[0], Leaf::Quad { .. }));
        assert!(matches!(leaves[1], Leaf::Sphere { .. }));
        assert_eq!(boxes[1].min, Vec3::new(-0.5, 0.5, -0.5));
    }

    #[test]
    fn broken_objects_are_refused() {
        let mut s = scene(vec![Object::fixed(
            "q",
            Shape::Quad {
                corner: Vec3::ZERO,
                edge_u: Vec3::X,
                edge_v: Vec3::X * 2.0,
            },
            0,
        )]);
        let e = SceneLayout::new(&s).unwrap_err();
        assert!(e.to_string().contains("parallel"), "{e}");
        s.objects[0] = Object::fixed("m", Shape::mesh(triangle(), Transform::IDENTITY), 3);
        let e = SceneLayout::new(&s).unwrap_err();
        assert!(e.to_string().contains("material"), "{e}");
    }
}
