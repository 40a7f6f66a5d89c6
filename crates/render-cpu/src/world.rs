//! The scene prepared for tracing: flat per-type primitive lists, materials, lights, and
//! the closest-hit and shadow queries over them.

use crate::material::{Mat, checker_is_odd};
use crate::plane::Plane;
use crate::quad::Quad;
use crate::ray::Ray;
use crate::sphere::Sphere;
use crate::triangle::{Triangle, Triangles};
use glam::Vec3A;
use steadyray_render::RenderError;
use steadyray_scene::{Scene, Shape};

/// Which primitive a ray hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Prim {
    Sphere(u32),
    Quad(u32),
    Plane(u32),
    Triangle(u32),
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

/// Everything the integrator reads, built once per `load_scene`.
#[derive(Clone, Debug)]
pub(crate) struct World {
    spheres: Vec<Sphere>,
    quads: Vec<Quad>,
    planes: Vec<Plane>,
    triangles: Triangles,
    materials: Vec<Mat>,
    pub lights: Vec<Light>,
    pub ambient: f32,
    pub background: Vec3A,
}

impl World {
    /// Prepares `scene`, refusing what would make tracing panic or produce NaNs everywhere:
    /// bad material or vertex indices, non-positive radii, degenerate quads.
    pub fn new(scene: &Scene) -> Result<Self, RenderError> {
        let bad = |name: &str, why: &str| RenderError::Scene(format!("object {name:?}: {why}"));
        let mut triangles = Vec::new();
        let mut world = World {
            spheres: Vec::new(),
            quads: Vec::new(),
            planes: Vec::new(),
            triangles: Triangles::default(),
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
        };
        for obj in &scene.objects {
            if obj.material >= world.materials.len() {
                return Err(bad(&obj.name, "material index out of range"));
            }
            let m = obj.material as u32;
            match &obj.shape {
                &Shape::Sphere { center, radius } => {
                    if !(radius > 0.0 && radius.is_finite()) {
                        return Err(bad(&obj.name, "sphere radius must be positive"));
                    }
                    world.spheres.push(Sphere::new(center, radius, m));
                }
                &Shape::Quad {
                    corner,
                    edge_u,
                    edge_v,
                } => {
                    let quad = Quad::new(corner, edge_u, edge_v, m)
                        .ok_or_else(|| bad(&obj.name, "quad edges are parallel"))?;
                    world.quads.push(quad);
                }
                &Shape::Plane { point, normal } => {
                    if normal.length_squared() == 0.0 || !normal.is_finite() {
                        return Err(bad(&obj.name, "plane normal must be a non-zero vector"));
                    }
                    world.planes.push(Plane::new(point, normal, m));
                }
                Shape::Mesh(mesh) => {
                    for tri in &mesh.triangles {
                        let mut v = [glam::Vec3::ZERO; 3];
                        for (corner, &vi) in v.iter_mut().zip(tri) {
                            *corner = *mesh
                                .positions
                                .get(vi as usize)
                                .ok_or_else(|| bad(&obj.name, "vertex index out of range"))?;
                        }
                        // Degenerate triangles cannot be hit; skip rather than refuse.
                        triangles.extend(Triangle::new(v, m));
                    }
                }
            }
        }
        world.triangles = Triangles::new(triangles)
            .map_err(|e| RenderError::Scene(format!("scene {:?}: meshes: {e}", scene.name)))?;
        Ok(world)
    }

    /// The nearest surface hit by `ray` on t in (T_MIN, ∞).
    #[inline]
    pub fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut t_max = f32::INFINITY;
        let mut take = |t: Option<f32>, prim: Prim, t_max: &mut f32| {
            if let Some(t) = t {
                *t_max = t;
                best = Some(Hit { t, prim });
            }
        };
        for (i, s) in self.spheres.iter().enumerate() {
            take(s.intersect(ray, t_max), Prim::Sphere(i as u32), &mut t_max);
        }
        for (i, q) in self.quads.iter().enumerate() {
            take(q.intersect(ray, t_max), Prim::Quad(i as u32), &mut t_max);
        }
        for (i, p) in self.planes.iter().enumerate() {
            take(p.intersect(ray, t_max), Prim::Plane(i as u32), &mut t_max);
        }
        if let Some((t, i)) = self.triangles.closest(ray, t_max) {
            take(Some(t), Prim::Triangle(i), &mut t_max);
        }
        best
    }

    /// Whether any surface is hit on t in (T_MIN, t_max) (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.spheres
            .iter()
            .any(|s| s.intersect(ray, t_max).is_some())
            || self.quads.iter().any(|q| q.intersect(ray, t_max).is_some())
            || self
                .planes
                .iter()
                .any(|p| p.intersect(ray, t_max).is_some())
            || self.triangles.any_hit(ray, t_max)
    }

    /// The outward (unflipped) geometric normal of `prim` at `p`.
    #[inline]
    pub fn normal(&self, prim: Prim, p: Vec3A) -> Vec3A {
        match prim {
            Prim::Sphere(i) => self.spheres[i as usize].normal(p),
            Prim::Quad(i) => self.quads[i as usize].normal(),
            Prim::Plane(i) => self.planes[i as usize].normal(),
            Prim::Triangle(i) => self.triangles.get(i).normal,
        }
    }

    /// The material of `prim`.
    #[inline]
    pub fn material(&self, prim: Prim) -> &Mat {
        let m = match prim {
            Prim::Sphere(i) => self.spheres[i as usize].material,
            Prim::Quad(i) => self.quads[i as usize].material,
            Prim::Plane(i) => self.planes[i as usize].material,
            Prim::Triangle(i) => self.triangles.get(i).material,
        };
        &self.materials[m as usize]
    }

    /// The temporal mode's surface id of `prim` (`docs/temporal.md`): spheres, quads and
    /// planes numbered in that order (each kind in object order), every mesh triangle one id
    /// after them.
    #[inline]
    pub fn surface_id(&self, prim: Prim) -> u32 {
        let (spheres, quads) = (self.spheres.len() as u32, self.quads.len() as u32);
        match prim {
            Prim::Sphere(i) => i,
            Prim::Quad(i) => spheres + i,
            Prim::Plane(i) => spheres + quads + i,
            Prim::Triangle(_) => spheres + quads + self.planes.len() as u32,
        }
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
            Prim::Sphere(_) | Prim::Triangle(_) => checker_is_odd(&p.to_array(), size),
        }
    }
}
