//! A scene in GPU layout: what is fixed per scene ([`PackedScene`]: materials, lights,
//! planes, every mesh's triangles and bottom-level BVH), what changes per frame
//! ([`GpuWorld`]: the frame's spheres and quads, instances and top level), and the storage
//! buffers that hold them.

use crate::buffers::GrowBuffer;
use crate::layout::*;
use glam::{Vec3, Vec3A};
use steadyray_accel::{Bounds, BvhError, TopLayout, TopLevel};
use steadyray_render::RenderError;
use steadyray_render::surface_motion::{SurfaceMove, surface_moves};
use steadyray_render::two_level::{Leaf, SceneLayout};
use steadyray_scene::{Material, Scene};

/// The parts of a scene that stay the same from frame to frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct PackedScene {
    /// The infinite planes, in object order: the first shapes of every frame.
    pub(crate) planes: Vec<GpuShape>,
    /// Every mesh's triangles in its BVH's leaf order, one mesh after another.
    pub(crate) triangles: Vec<GpuTriangle>,
    /// Every mesh's 4-wide BVH, one after another (child indices within the mesh's own).
    pub(crate) bvh_nodes: Vec<GpuBvhNode>,
    /// Per mesh, where its nodes and triangles start.
    pub(crate) mesh_bases: Vec<(u32, u32)>,
    pub(crate) materials: Vec<GpuMaterial>,
    pub(crate) lights: Vec<GpuLight>,
    pub(crate) ambient: f32,
    pub(crate) background: [f32; 3],
}

/// The checker axes a, b of a plane with unit `normal` (docs/shading.md, Checker).
fn plane_axes(normal: Vec3A) -> (Vec3A, Vec3A) {
    let other = if normal.x.abs() < 0.9 {
        Vec3A::X
    } else {
        Vec3A::Y
    };
    let a = normal.cross(other).normalize();
    (a, normal.cross(a))
}

fn pack_material(material: &Material) -> Result<GpuMaterial, String> {
    let mut packed = GpuMaterial {
        colour: material.base_colour().to_array(),
        ..Default::default()
    };
    match *material {
        Material::Diffuse { checker, .. } => {
            packed.kind = MAT_DIFFUSE;
            if let Some(checker) = checker {
                if checker.size.is_nan() || checker.size <= 0.0 {
                    return Err(format!("checker size {} is not positive", checker.size));
                }
                packed.checker_size = checker.size;
                packed.colour_b = checker.albedo_b.to_array();
            }
        }
        Material::Mirror { .. } => packed.kind = MAT_MIRROR,
        Material::Dielectric { ior, .. } => {
            if ior.is_nan() || ior <= 0.0 {
                return Err(format!("index of refraction {ior} is not positive"));
            }
            packed.kind = MAT_DIELECTRIC;
            packed.ior = ior;
        }
        Material::Emissive { .. } => packed.kind = MAT_EMISSIVE,
    }
    Ok(packed)
}

/// A sphere in GPU layout, precomputed as the CPU reference's `Sphere::new` does.
fn pack_sphere(center: Vec3, radius: f32, material: u32) -> GpuShape {
    GpuShape {
        p0: center.to_array(),
        kind: SHAPE_SPHERE,
        material,
        s0: radius * radius,
        s1: 1.0 / radius,
        ..Default::default()
    }
}

/// A quad in GPU layout, precomputed as the CPU reference's `Quad::new` does (glam `Vec3A`
/// arithmetic, so the same f32 values). The layout gives only quads with area.
fn pack_quad(corner: Vec3, edge_u: Vec3, edge_v: Vec3, material: u32) -> GpuShape {
    let (eu, ev) = (Vec3A::from(edge_u), Vec3A::from(edge_v));
    let w = eu.cross(ev);
    let w2 = w.length_squared();
    GpuShape {
        p0: corner.to_array(),
        kind: SHAPE_QUAD,
        p1: w.normalize().to_array(),
        material,
        p2: (ev.cross(w) / w2).to_array(),
        s0: eu.length(),
        p3: (w.cross(eu) / w2).to_array(),
        s1: ev.length(),
    }
}

/// A plane in GPU layout, with its checker axes as the CPU reference computes them.
fn pack_plane(point: Vec3, normal: Vec3, material: u32) -> GpuShape {
    let (a, b) = plane_axes(normal.into());
    GpuShape {
        p0: point.to_array(),
        kind: SHAPE_PLANE,
        p1: normal.to_array(),
        material,
        p2: a.to_array(),
        p3: b.to_array(),
        ..Default::default()
    }
}

impl PackedScene {
    /// Packs what `layout` (of `scene`) keeps for every frame, building each mesh's BVH.
    pub(crate) fn new(scene: &Scene, layout: &SceneLayout) -> Result<Self, RenderError> {
        let bad = |what: String| RenderError::Scene(format!("scene {:?}: {what}", scene.name));
        let materials = scene
            .materials
            .iter()
            .map(|(name, m)| pack_material(m).map_err(|e| bad(format!("material {name:?}: {e}"))))
            .collect::<Result<Vec<_>, _>>()?;
        let mut packed = Self {
            materials,
            ambient: scene.ambient,
            background: scene.background.to_array(),
            lights: scene
                .lights
                .iter()
                .map(|l| GpuLight {
                    position: l.position.to_array(),
                    intensity: l.intensity.to_array(),
                    ..Default::default()
                })
                .collect(),
            planes: layout
                .planes
                .iter()
                .map(|p| pack_plane(p.point, p.normal, p.material))
                .collect(),
            ..Default::default()
        };
        for mesh in &layout.meshes {
            packed
                .add_mesh(&mesh.corners, &mesh.normals)
                .map_err(|e| bad(format!("meshes: {e}")))?;
        }
        Ok(packed)
    }

    /// Builds the BVH over one mesh's triangles and appends its nodes and its triangles (in
    /// the BVH's leaf order, each with its index in the mesh as `id`).
    fn add_mesh(&mut self, corners: &[[Vec3; 3]], normals: &[Vec3]) -> Result<(), BvhError> {
        let count = |n: usize| u32::try_from(n).map_err(|_| BvhError::TooManyTriangles(n));
        self.mesh_bases
            .push((count(self.bvh_nodes.len())?, count(self.triangles.len())?));
        let bvh = steadyray_accel::Bvh::build(corners)?;
        self.triangles.extend(bvh.leaf_order().iter().map(|&i| {
            let [v0, v1, v2] = corners[i as usize].map(|v| v.to_array());
            GpuTriangle {
                v0,
                v1,
                v2,
                id: i,
                normal: normals[i as usize].to_array(),
                ..Default::default()
            }
        }));
        self.bvh_nodes.extend_from_slice(bvh.gpu_nodes()?);
        Ok(())
    }
}

/// The per-frame part of a loaded scene: its layout, its frame in GPU layout and the
/// top level they came from.
pub(crate) struct GpuWorld {
    scene: Scene,
    layout: SceneLayout,
    top: TopLevel,
    /// The time the frame was placed at; `None` before the first placement.
    time_s: Option<f64>,
    /// Scratch of each placement: the frame's leaves, boxes, surface ids and objects (as
    /// `SceneLayout::leaves_at` gives them), each leaf's index among the shapes or
    /// instances, and the instances' surface ids.
    leaves: Vec<Leaf>,
    boxes: Vec<Bounds>,
    leaf_ids: Vec<u32>,
    leaf_objects: Vec<u32>,
    leaf_index: Vec<u32>,
    instance_ids: Vec<u32>,
    /// The planes, then the frame's spheres and quads.
    pub(crate) shapes: Vec<GpuShape>,
    /// The temporal mode's surface ids of `shapes`, then of `instances`.
    pub(crate) surface_ids: Vec<u32>,
    /// The frame's leaves in the top level's leaf order.
    pub(crate) top_leaves: Vec<GpuTopLeaf>,
    pub(crate) instances: Vec<GpuInstance>,
}

impl GpuWorld {
    /// The world of `scene`, not yet placed at any time.
    pub(crate) fn new(scene: &Scene, layout: SceneLayout) -> Result<Self, RenderError> {
        Ok(Self {
            scene: scene.clone(),
            layout,
            top: TopLevel::build(&[], TopLayout::Gpu).map_err(top_error)?,
            time_s: None,
            leaves: Vec::new(),
            boxes: Vec::new(),
            leaf_ids: Vec::new(),
            leaf_objects: Vec::new(),
            leaf_index: Vec::new(),
            instance_ids: Vec::new(),
            shapes: Vec::new(),
            surface_ids: Vec::new(),
            top_leaves: Vec::new(),
            instances: Vec::new(),
        })
    }

    /// Whether objects of the scene move, appear or disappear.
    pub(crate) fn is_animated(&self) -> bool {
        self.layout.animated
    }

    /// How every surface moved from scene time `before_s` to `now_s`, by surface id.
    pub(crate) fn surface_moves(&self, before_s: f64, now_s: f64, out: &mut Vec<SurfaceMove>) {
        surface_moves(&self.scene, &self.layout, before_s, now_s, out);
    }

    /// The top level's nodes.
    pub(crate) fn top_nodes(&self) -> Result<&[GpuBvhNode], RenderError> {
        self.top.gpu_nodes().map_err(top_error)
    }

    /// Places the frame at `time_s`: its shapes, instances and top level (refitted or
    /// rebuilt). Returns whether anything changed (a scene where nothing moves is placed
    /// once). `packed` gives the meshes' positions in the buffers.
    pub(crate) fn place(&mut self, time_s: f64, packed: &PackedScene) -> Result<bool, RenderError> {
        if self.time_s.is_some() && !self.layout.animated {
            return Ok(false);
        }
        self.layout.leaves_at(
            &self.scene,
            time_s,
            &mut self.leaves,
            &mut self.boxes,
            &mut self.leaf_ids,
            &mut self.leaf_objects,
        );
        self.top.update(&self.boxes).map_err(top_error)?;
        self.shapes.clear();
        self.shapes.extend_from_slice(&packed.planes);
        self.surface_ids.clear();
        self.surface_ids
            .extend(self.layout.planes.iter().map(|p| p.surface));
        self.instance_ids.clear();
        self.instances.clear();
        // Each leaf as a shape or instance, by its index (its key).
        self.leaf_index.clear();
        for (leaf, &id) in self.leaves.iter().zip(&self.leaf_ids) {
            self.leaf_index.push(match *leaf {
                Leaf::Sphere {
                    center,
                    radius,
                    material,
                } => {
                    self.shapes.push(pack_sphere(center, radius, material));
                    self.surface_ids.push(id);
                    self.shapes.len() as u32 - 1
                }
                Leaf::Quad {
                    corner,
                    edge_u,
                    edge_v,
                    material,
                } => {
                    self.shapes
                        .push(pack_quad(corner, edge_u, edge_v, material));
                    self.surface_ids.push(id);
                    self.shapes.len() as u32 - 1
                }
                Leaf::Instance(inst) => {
                    let (node_base, tri_base) = packed.mesh_bases[inst.mesh as usize];
                    let rows = inst.to_mesh.unwrap_or_default();
                    let [nx, ny, nz] = inst.normal_rows;
                    self.instances.push(GpuInstance {
                        to_mesh_x: rows[0],
                        to_mesh_y: rows[1],
                        to_mesh_z: rows[2],
                        normal_x: nx,
                        node_base,
                        normal_y: ny,
                        tri_base,
                        normal_z: nz,
                        material: inst.material,
                        baked: u32::from(inst.to_mesh.is_none()),
                        ..Default::default()
                    });
                    self.instance_ids.push(id);
                    TOP_INSTANCE | (self.instances.len() as u32 - 1)
                }
            });
        }
        self.surface_ids.extend_from_slice(&self.instance_ids);
        self.top_leaves.clear();
        self.top_leaves
            .extend(self.top.leaf_order().iter().map(|&key| GpuTopLeaf {
                index: self.leaf_index[key as usize],
                key,
            }));
        self.time_s = Some(time_s);
        Ok(true)
    }
}

fn top_error(e: BvhError) -> RenderError {
    RenderError::Scene(format!("top-level BVH: {e}"))
}

/// The storage buffers of the loaded scene and its frame, reused (and only grown).
pub(crate) struct SceneBuffers {
    pub(crate) shapes: GrowBuffer,
    pub(crate) triangles: GrowBuffer,
    pub(crate) bvh_nodes: GrowBuffer,
    pub(crate) materials: GrowBuffer,
    pub(crate) lights: GrowBuffer,
    pub(crate) top_nodes: GrowBuffer,
    pub(crate) top_leaves: GrowBuffer,
    pub(crate) instances: GrowBuffer,
    pub(crate) surface_ids: GrowBuffer,
}

impl SceneBuffers {
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let buffer = |label| GrowBuffer::new(device, label, usage, 0);
        Self {
            shapes: buffer("shapes"),
            triangles: buffer("triangles"),
            bvh_nodes: buffer("bvh nodes"),
            materials: buffer("materials"),
            lights: buffer("lights"),
            top_nodes: buffer("top-level nodes"),
            top_leaves: buffer("top-level leaves"),
            instances: buffer("instances"),
            surface_ids: buffer("surface ids"),
        }
    }

    /// Uploads what stays the same over the scene's frames; returns whether any buffer was
    /// replaced.
    pub(crate) fn upload_scene(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PackedScene,
    ) -> bool {
        let grew = [
            self.triangles
                .write(device, queue, bytemuck::cast_slice(&scene.triangles)),
            self.bvh_nodes
                .write(device, queue, bytemuck::cast_slice(&scene.bvh_nodes)),
            self.materials
                .write(device, queue, bytemuck::cast_slice(&scene.materials)),
            self.lights
                .write(device, queue, bytemuck::cast_slice(&scene.lights)),
        ];
        grew.contains(&true)
    }

    /// Uploads the frame's shapes, instances and top level; returns whether any buffer was
    /// replaced.
    pub(crate) fn upload_frame(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        world: &GpuWorld,
    ) -> Result<bool, RenderError> {
        let grew = [
            self.shapes
                .write(device, queue, bytemuck::cast_slice(&world.shapes)),
            self.top_nodes
                .write(device, queue, bytemuck::cast_slice(world.top_nodes()?)),
            self.top_leaves
                .write(device, queue, bytemuck::cast_slice(&world.top_leaves)),
            self.instances
                .write(device, queue, bytemuck::cast_slice(&world.instances)),
            self.surface_ids
                .write(device, queue, bytemuck::cast_slice(&world.surface_ids)),
        ];
        Ok(grew.contains(&true))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_scene::{
        Camera, CameraPath, Checker, Object, PointLight, Shape, Transform, TriangleMesh,
    };

    fn scene(objects: Vec<Object>) -> Scene {
        Scene {
            name: "test".into(),
            materials: vec![
                (
                    "floor".into(),
                    Material::Diffuse {
                        albedo: Vec3::splat(0.8),
                        checker: Some(Checker {
                            size: 0.5,
                            albedo_b: Vec3::splat(0.25),
                        }),
                    },
                ),
                (
                    "glass".into(),
                    Material::Dielectric {
                        ior: 1.5,
                        tint: Vec3::ONE,
                    },
                ),
            ],
            objects,
            lights: vec![PointLight {
                position: Vec3::new(0.0, 3.0, 0.0),
                intensity: Vec3::splat(2.0),
            }],
            ambient: 0.05,
            background: Vec3::new(0.05, 0.07, 0.12),
            camera: Camera::yaw_pitch(Vec3::new(0.0, 1.5, 0.0), 0.0, 0.0, 60.0),
            path: CameraPath::sweep(1),
        }
    }

    /// The scene packed and placed at time 0.
    fn packed(scene: &Scene) -> Result<(PackedScene, GpuWorld), RenderError> {
        let layout = SceneLayout::new(scene)?;
        let packed = PackedScene::new(scene, &layout)?;
        let mut world = GpuWorld::new(scene, layout)?;
        world.place(0.0, &packed)?;
        Ok((packed, world))
    }

    #[test]
    fn packs_shapes_then_triangles() {
        let mesh = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
        };
        let (packed, world) = packed(&scene(vec![
            Object {
                name: "tri".into(),
                shape: Shape::mesh(mesh, Transform::IDENTITY),
                material: 1,
                motion: None,
            },
            Object {
                name: "floor".into(),
                shape: Shape::Quad {
                    corner: Vec3::new(-2.0, 0.0, -2.0),
                    edge_u: Vec3::new(4.0, 0.0, 0.0),
                    edge_v: Vec3::new(0.0, 0.0, -10.0),
                },
                material: 0,
                motion: None,
            },
        ]))
        .unwrap();
        assert_eq!(world.shapes.len(), 1);
        let quad = world.shapes[0];
        assert_eq!(
            (quad.kind, quad.material, quad.s0, quad.s1),
            (SHAPE_QUAD, 0, 4.0, 10.0)
        );
        // cross(+x, -z) = +y
        assert_eq!(quad.p1, [0.0, 1.0, 0.0]);
        // the dual vectors give the edge fractions of a point: (1, 0, -2.5) is a = 0.75,
        // b = 0.05 from the corner.
        let rel = Vec3A::new(3.0, 0.0, -0.5);
        let (a, b) = (rel.dot(quad.p2.into()), rel.dot(quad.p3.into()));
        assert!(
            (a - 0.75).abs() < 1e-6 && (b - 0.05).abs() < 1e-6,
            "{a} {b}"
        );
        assert_eq!(packed.triangles.len(), 1);
        assert_eq!(packed.triangles[0].normal, [0.0, 0.0, 1.0]);
        // The mesh is the first leaf (key 0), the quad the second.
        assert_eq!(world.instances.len(), 1);
        assert_eq!(world.instances[0].material, 1);
        assert_eq!(world.instances[0].baked, 1);
        let mut leaves = world.top_leaves.clone();
        leaves.sort_by_key(|l| l.key);
        assert_eq!(
            leaves,
            [
                GpuTopLeaf {
                    index: TOP_INSTANCE,
                    key: 0
                },
                GpuTopLeaf { index: 0, key: 1 }
            ]
        );
        assert_eq!(packed.materials[0].checker_size, 0.5);
        assert_eq!(packed.materials[1].kind, MAT_DIELECTRIC);
    }

    #[test]
    fn rejects_bad_material_index() {
        let err = packed(&scene(vec![Object {
            name: "ball".into(),
            shape: Shape::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            material: 7,
            motion: None,
        }]))
        .err()
        .unwrap();
        assert!(err.to_string().contains("material index"), "{err}");
    }

    #[test]
    fn plane_axes_are_orthonormal() {
        for n in [Vec3A::Y, Vec3A::X, Vec3A::new(0.6, 0.8, 0.0)] {
            let (a, b) = plane_axes(n);
            assert!(a.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6 && a.dot(b).abs() < 1e-6);
            assert!((a.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
        }
    }
}
