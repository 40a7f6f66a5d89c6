//! The scene prepared for tracing: materials, lights and planes, each mesh's bottom-level
//! BVH (built once per scene), and the frame's top level over its spheres, quads and mesh
//! copies (rebuilt or refitted when the scene time changes), with the closest-hit and
//! shadow queries over them.

use crate::material::{Mat, checker_is_odd};
use crate::plane::Plane;
use crate::quad::Quad;
use crate::ray::Ray;
use crate::sphere::Sphere;
use crate::triangle::MeshBvh;
use glam::Vec3A;
use std::time::Instant;
use steadyray_accel::{Bounds, TopLayout, TopLevel};
use steadyray_render::RenderError;
use steadyray_render::surface_motion::{SurfaceMove, surface_moves};
use steadyray_render::two_level::{Instance, Leaf, SceneLayout};
use steadyray_scene::{Scene, Shape};

/// Which primitive a ray hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Prim {
    Sphere(u32),
    Quad(u32),
    Plane(u32),
    /// Triangle `tri` of the mesh of the frame's instance `instance`.
    Triangle {
        instance: u32,
        tri: u32,
    },
}

/// The nearest intersection of a ray.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hit {
    pub t: f32,
    pub prim: Prim,
}

/// A point light in SIMD vectors.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Light {
    pub position: Vec3A,
    pub intensity: Vec3A,
}

/// What a top-level leaf is: an index into the frame's spheres, quads or instances.
#[derive(Clone, Copy, Debug)]
enum LeafRef {
    Sphere(u32),
    Quad(u32),
    Instance(u32),
}

/// Everything the integrator reads: built by `load_scene`, its top level brought to a
/// scene time by [`World::set_time`].
#[derive(Clone, Debug)]
pub(crate) struct World {
    scene: Scene,
    layout: SceneLayout,
    planes: Vec<Plane>,
    meshes: Vec<MeshBvh>,
    materials: Vec<Mat>,
    pub lights: Vec<Light>,
    pub ambient: f32,
    pub background: Vec3A,
    /// The frame's leaves: per leaf (its index is its key), what it is.
    leaf_refs: Vec<LeafRef>,
    spheres: Vec<Sphere>,
    quads: Vec<Quad>,
    /// The temporal mode's surface ids of the frame's spheres, quads and instances.
    sphere_ids: Vec<u32>,
    quad_ids: Vec<u32>,
    instance_ids: Vec<u32>,
    instances: Vec<Instance>,
    top: TopLevel,
    /// The time the leaves were placed at; `None` before the first placement.
    time_s: Option<f64>,
    /// Scratch for the frame's leaves, boxes and surface ids.
    leaves: Vec<Leaf>,
    boxes: Vec<Bounds>,
    leaf_ids: Vec<u32>,
    /// The object (index in the scene) of each leaf, and of each of the frame's spheres,
    /// quads and instances, and of each plane: what a hit belongs to.
    leaf_objects: Vec<u32>,
    sphere_objects: Vec<u32>,
    quad_objects: Vec<u32>,
    instance_objects: Vec<u32>,
    plane_objects: Vec<u32>,
}

impl World {
    /// Prepares `scene` at time 0, refusing what would make tracing panic or produce NaNs
    /// everywhere (see [`SceneLayout::new`]).
    pub fn new(scene: &Scene) -> Result<Self, RenderError> {
        let layout = SceneLayout::new(scene)?;
        let meshes = layout
            .meshes
            .iter()
            .map(MeshBvh::new)
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| RenderError::Scene(format!("scene {:?}: meshes: {e}", scene.name)))?;
        let mut world = World {
            planes: layout
                .planes
                .iter()
                .map(|p| Plane::new(p.point, p.normal, p.material))
                .collect(),
            meshes,
            materials: scene.materials.iter().map(|(_, m)| Mat::from(m)).collect(),
            lights: scene
                .lights
                .iter()
                .map(|l| Light {
                    position: l.position.into(),
                    intensity: l.intensity.into(),
                })
                .collect(),
            ambient: scene.ambient,
            background: scene.background.into(),
            scene: scene.clone(),
            layout,
            leaf_refs: Vec::new(),
            spheres: Vec::new(),
            quads: Vec::new(),
            sphere_ids: Vec::new(),
            quad_ids: Vec::new(),
            instance_ids: Vec::new(),
            instances: Vec::new(),
            top: TopLevel::build(&[], TopLayout::Cpu).map_err(top_error)?,
            time_s: None,
            leaves: Vec::new(),
            boxes: Vec::new(),
            leaf_ids: Vec::new(),
            leaf_objects: Vec::new(),
            sphere_objects: Vec::new(),
            quad_objects: Vec::new(),
            instance_objects: Vec::new(),
            plane_objects: scene
                .objects
                .iter()
                .enumerate()
                .filter(|(_, o)| matches!(o.shape, Shape::Plane { .. }))
                .map(|(i, _)| i as u32)
                .collect(),
        };
        world.set_time(0.0)?;
        Ok(world)
    }

    /// Places the scene's objects as they are at `time_s` and brings the top level up to
    /// date (refit or rebuild); returns the time this took, ms. A scene where nothing moves
    /// is placed once.
    pub fn set_time(&mut self, time_s: f64) -> Result<f64, RenderError> {
        if self.time_s.is_some() && !self.layout.animated {
            return Ok(0.0);
        }
        let start = Instant::now();
        self.layout.leaves_at(
            &self.scene,
            time_s,
            &mut self.leaves,
            &mut self.boxes,
            &mut self.leaf_ids,
            &mut self.leaf_objects,
        );
        self.leaf_refs.clear();
        self.spheres.clear();
        self.quads.clear();
        self.sphere_ids.clear();
        self.quad_ids.clear();
        self.instance_ids.clear();
        self.instances.clear();
        self.sphere_objects.clear();
        self.quad_objects.clear();
        self.instance_objects.clear();
        for ((leaf, &id), &object) in self
            .leaves
            .iter()
            .zip(&self.leaf_ids)
            .zip(&self.leaf_objects)
        {
            let leaf_ref = match *leaf {
                Leaf::Sphere {
                    center,
                    radius,
                    material,
                } => {
                    self.spheres.push(Sphere::new(center, radius, material));
                    self.sphere_ids.push(id);
                    self.sphere_objects.push(object);
                    LeafRef::Sphere(self.spheres.len() as u32 - 1)
                }
                Leaf::Quad {
                    corner,
                    edge_u,
                    edge_v,
                    material,
                } => {
                    // The layout gives only quads with area, by the same test.
                    let quad = Quad::new(corner, edge_u, edge_v, material).ok_or_else(|| {
                        RenderError::Scene(format!("a quad at {corner} has no area"))
                    })?;
                    self.quads.push(quad);
                    self.quad_ids.push(id);
                    self.quad_objects.push(object);
                    LeafRef::Quad(self.quads.len() as u32 - 1)
                }
                Leaf::Instance(instance) => {
                    self.instances.push(instance);
                    self.instance_ids.push(id);
                    self.instance_objects.push(object);
                    LeafRef::Instance(self.instances.len() as u32 - 1)
                }
            };
            self.leaf_refs.push(leaf_ref);
        }
        self.top.update(&self.boxes).map_err(top_error)?;
        self.time_s = Some(time_s);
        Ok(start.elapsed().as_secs_f64() * 1e3)
    }

    /// The nearest surface hit by `ray` on t in (T_MIN, ∞): the nearest leaf of the top
    /// level (ties to the lowest key, then the lowest triangle), then the planes, which win
    /// only when strictly nearer.
    #[inline]
    pub fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut best_key = u32::MAX;
        let t_leaf = self
            .top
            .closest(ray.origin, ray.dir, f32::INFINITY, |key, best_t| {
                let (t, prim) = match self.leaf_refs[key as usize] {
                    LeafRef::Sphere(i) => {
                        let Some(t) = self.spheres[i as usize].intersect(ray, f32::INFINITY) else {
                            return best_t;
                        };
                        (t, Prim::Sphere(i))
                    }
                    LeafRef::Quad(i) => {
                        let Some(t) = self.quads[i as usize].intersect(ray, f32::INFINITY) else {
                            return best_t;
                        };
                        (t, Prim::Quad(i))
                    }
                    LeafRef::Instance(i) => {
                        let instance = &self.instances[i as usize];
                        let (o, d) = instance.ray_to_mesh(ray.origin, ray.dir);
                        // Hits at best_t too, so that a lower key can take a tie.
                        let Some((t, tri)) =
                            self.meshes[instance.mesh as usize].closest(o, d, best_t.next_up())
                        else {
                            return best_t;
                        };
                        (t, Prim::Triangle { instance: i, tri })
                    }
                };
                if t < best_t || (t == best_t && key < best_key) {
                    best = Some(Hit { t, prim });
                    best_key = key;
                    t
                } else {
                    best_t
                }
            });
        let mut t_max = t_leaf;
        for (i, p) in self.planes.iter().enumerate() {
            if let Some(t) = p.intersect(ray, t_max) {
                t_max = t;
                best = Some(Hit {
                    t,
                    prim: Prim::Plane(i as u32),
                });
            }
        }
        best
    }

    /// Whether any surface is hit on t in (T_MIN, t_max) (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.planes
            .iter()
            .any(|p| p.intersect(ray, t_max).is_some())
            || self.top.any_hit(ray.origin, ray.dir, t_max, |key| {
                match self.leaf_refs[key as usize] {
                    LeafRef::Sphere(i) => self.spheres[i as usize].intersect(ray, t_max).is_some(),
                    LeafRef::Quad(i) => self.quads[i as usize].intersect(ray, t_max).is_some(),
                    LeafRef::Instance(i) => {
                        let instance = &self.instances[i as usize];
                        let (o, d) = instance.ray_to_mesh(ray.origin, ray.dir);
                        self.meshes[instance.mesh as usize].any_hit(o, d, t_max)
                    }
                }
            })
    }

    /// The outward (unflipped) geometric normal of `prim` at `p`.
    #[inline]
    pub fn normal(&self, prim: Prim, p: Vec3A) -> Vec3A {
        match prim {
            Prim::Sphere(i) => self.spheres[i as usize].normal(p),
            Prim::Quad(i) => self.quads[i as usize].normal(),
            Prim::Plane(i) => self.planes[i as usize].normal(),
            Prim::Triangle { instance, tri } => {
                let instance = &self.instances[instance as usize];
                instance.normal_to_world(self.meshes[instance.mesh as usize].normal(tri))
            }
        }
    }

    /// The material of `prim`.
    #[inline]
    pub fn material(&self, prim: Prim) -> &Mat {
        let m = match prim {
            Prim::Sphere(i) => self.spheres[i as usize].material,
            Prim::Quad(i) => self.quads[i as usize].material,
            Prim::Plane(i) => self.planes[i as usize].material,
            Prim::Triangle { instance, .. } => self.instances[instance as usize].material,
        };
        &self.materials[m as usize]
    }

    /// The index in the scene's objects of the object `prim` belongs to.
    pub fn object_of(&self, prim: Prim) -> u32 {
        match prim {
            Prim::Sphere(i) => self.sphere_objects[i as usize],
            Prim::Quad(i) => self.quad_objects[i as usize],
            Prim::Plane(i) => self.plane_objects[i as usize],
            Prim::Triangle { instance, .. } => self.instance_objects[instance as usize],
        }
    }

    /// The temporal mode's surface id of `prim` (`docs/temporal.md`): its object's (and
    /// copy's), the same in every frame.
    #[inline]
    pub fn surface_id(&self, prim: Prim) -> u32 {
        match prim {
            Prim::Sphere(i) => self.sphere_ids[i as usize],
            Prim::Quad(i) => self.quad_ids[i as usize],
            Prim::Plane(i) => self.layout.planes[i as usize].surface,
            Prim::Triangle { instance, .. } => self.instance_ids[instance as usize],
        }
    }

    /// Whether objects of the scene move, appear or disappear.
    pub fn is_animated(&self) -> bool {
        self.layout.animated
    }

    /// How every surface moved from scene time `before_s` to `now_s`, by surface id.
    pub fn surface_moves(&self, before_s: f64, now_s: f64, out: &mut Vec<SurfaceMove>) {
        surface_moves(&self.scene, &self.layout, before_s, now_s, out);
    }

    /// Whether `prim` is flat (a quad or a plane): a mirror image in it is a virtual scene
    /// that reprojects exactly.
    #[inline]
    pub fn is_flat(&self, prim: Prim) -> bool {
        matches!(prim, Prim::Quad(_) | Prim::Plane(_))
    }

    /// Whether `p` on `prim` lies on an odd checker square of `size`: surface (u, v) for
    /// quads and planes, the 3D checker for spheres and meshes.
    #[inline]
    pub fn checker_is_odd(&self, prim: Prim, p: Vec3A, size: f32) -> bool {
        match prim {
            Prim::Quad(i) => {
                let (u, v) = self.quads[i as usize].surface_uv(p);
                checker_is_odd(&[u, v], size)
            }
            Prim::Plane(i) => {
                let (u, v) = self.planes[i as usize].surface_uv(p);
                checker_is_odd(&[u, v], size)
            }
            Prim::Sphere(_) | Prim::Triangle { .. } => checker_is_odd(&p.to_array(), size),
        }
    }
}

fn top_error(e: steadyray_accel::BvhError) -> RenderError {
    RenderError::Scene(format!("top-level BVH: {e}"))
}
