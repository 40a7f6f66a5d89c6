//! A scene in GPU layout ([`PackedScene`]) and the storage buffers that hold it.

use crate::buffers::GrowBuffer;
use crate::layout::*;
use glam::{Vec3, Vec3A};
use steadyray_render::RenderError;
use steadyray_scene::{Material, Scene, Shape};

/// A scene flattened into the structs of [`crate::layout`]: spheres, quads and planes, each
/// kind in object order, and every mesh's triangles in the leaf order of their BVH (each
/// with its index in object order as `id`).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct PackedScene {
    pub(crate) shapes: Vec<GpuShape>,
    pub(crate) triangles: Vec<GpuTriangle>,
    pub(crate) bvh_nodes: Vec<GpuBvhNode>,
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

/// An analytic shape in GPU layout, precomputed as the CPU reference does (glam `Vec3A`
/// arithmetic, so the same f32 values); None for a mesh. Refuses what the CPU reference
/// refuses: non-positive radii, quads with parallel edges, zero plane normals.
fn pack_shape(shape: &Shape, material: u32) -> Result<Option<GpuShape>, &'static str> {
    let packed = match *shape {
        Shape::Sphere { center, radius } => {
            if !(radius > 0.0 && radius.is_finite()) {
                return Err("sphere radius must be positive");
            }
            GpuShape {
                p0: center.to_array(),
                kind: SHAPE_SPHERE,
                material,
                s0: radius * radius,
                s1: 1.0 / radius,
                ..Default::default()
            }
        }
        Shape::Quad {
            corner,
            edge_u,
            edge_v,
        } => {
            let (eu, ev) = (Vec3A::from(edge_u), Vec3A::from(edge_v));
            let w = eu.cross(ev);
            let w2 = w.length_squared();
            if !(w2 > 0.0 && w2.is_finite()) {
                return Err("quad edges are parallel");
            }
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
        Shape::Plane { point, normal } => {
            if normal.length_squared() == 0.0 || !normal.is_finite() {
                return Err("plane normal must be a non-zero vector");
            }
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
        Shape::Mesh(_) => return Ok(None),
    };
    Ok(Some(packed))
}

/// A mesh triangle in GPU layout, None when it has no area (it can never be hit).
fn pack_triangle(v: [Vec3; 3], material: u32) -> Option<GpuTriangle> {
    let n = (v[1] - v[0]).cross(v[2] - v[0]);
    let len2 = n.length_squared();
    (len2 > 0.0 && len2.is_finite()).then(|| GpuTriangle {
        v0: v[0].to_array(),
        material,
        v1: v[1].to_array(),
        v2: v[2].to_array(),
        normal: n.normalize().to_array(),
        ..Default::default()
    })
}

impl PackedScene {
    /// Flattens `scene`, checking the indices the shaders will follow.
    pub(crate) fn new(scene: &Scene) -> Result<Self, RenderError> {
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
            ..Default::default()
        };
        for object in &scene.objects {
            if object.material >= packed.materials.len() {
                return Err(bad(format!(
                    "object {:?} refers to material {} of {}",
                    object.name,
                    object.material,
                    packed.materials.len()
                )));
            }
            let material = object.material as u32;
            let shape = pack_shape(&object.shape, material)
                .map_err(|why| bad(format!("object {:?}: {why}", object.name)))?;
            packed.shapes.extend(shape);
            let Shape::Mesh(mesh) = &object.shape else {
                continue;
            };
            for (i, &[a, b, c]) in mesh.triangles.iter().enumerate() {
                if [a, b, c]
                    .iter()
                    .any(|&v| v as usize >= mesh.positions.len())
                {
                    return Err(bad(format!(
                        "mesh {:?} triangle {i} refers to a missing vertex",
                        object.name
                    )));
                }
                packed
                    .triangles
                    .extend(pack_triangle(mesh.triangle(i), material));
            }
        }
        // Closest-hit ties go to the first primitive tested: test spheres, quads, planes in
        // that order, as the CPU reference does.
        packed.shapes.sort_by_key(|s| s.kind);
        packed
            .order_triangles_for_bvh()
            .map_err(|e| bad(format!("meshes: {e}")))?;
        Ok(packed)
    }

    /// Builds the BVH over the triangles (in object order), numbers them by that order and
    /// puts them in the BVH's leaf order.
    fn order_triangles_for_bvh(&mut self) -> Result<(), steadyray_accel::BvhError> {
        let corners: Vec<[Vec3; 3]> = self
            .triangles
            .iter()
            .map(|t| [t.v0, t.v1, t.v2].map(Vec3::from))
            .collect();
        let bvh = steadyray_accel::Bvh::build(&corners)?;
        self.triangles = bvh
            .leaf_order()
            .iter()
            .map(|&i| GpuTriangle {
                id: i,
                ..self.triangles[i as usize]
            })
            .collect();
        self.bvh_nodes = bvh.gpu_nodes()?.to_vec();
        Ok(())
    }
}

/// The storage buffers of the loaded scene, reused (and only grown) across scenes.
pub(crate) struct SceneBuffers {
    pub(crate) shapes: GrowBuffer,
    pub(crate) triangles: GrowBuffer,
    pub(crate) bvh_nodes: GrowBuffer,
    pub(crate) materials: GrowBuffer,
    pub(crate) lights: GrowBuffer,
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
        }
    }

    /// Uploads `scene`; returns whether any buffer was replaced.
    pub(crate) fn upload(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PackedScene,
    ) -> bool {
        let grew = [
            self.shapes
                .write(device, queue, bytemuck::cast_slice(&scene.shapes)),
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_scene::{Camera, CameraPath, Checker, Object, PointLight, TriangleMesh};

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
            path: CameraPath::Sweep { frames: 1 },
        }
    }

    #[test]
    fn packs_shapes_then_triangles() {
        let mesh = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
        };
        let packed = PackedScene::new(&scene(vec![
            Object {
                name: "tri".into(),
                shape: Shape::Mesh(mesh),
                material: 1,
            },
            Object {
                name: "floor".into(),
                shape: Shape::Quad {
                    corner: Vec3::new(-2.0, 0.0, -2.0),
                    edge_u: Vec3::new(4.0, 0.0, 0.0),
                    edge_v: Vec3::new(0.0, 0.0, -10.0),
                },
                material: 0,
            },
        ]))
        .unwrap();
        assert_eq!(packed.shapes.len(), 1);
        let quad = packed.shapes[0];
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
        assert_eq!(packed.materials[0].checker_size, 0.5);
        assert_eq!(packed.materials[1].kind, MAT_DIELECTRIC);
    }

    #[test]
    fn rejects_bad_material_index() {
        let err = PackedScene::new(&scene(vec![Object {
            name: "ball".into(),
            shape: Shape::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            material: 7,
        }]))
        .unwrap_err();
        assert!(err.to_string().contains("material 7"), "{err}");
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
