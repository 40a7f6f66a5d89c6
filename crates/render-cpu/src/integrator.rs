//! The Whitted integrator of `docs/shading.md`: one chain of rays per eye sample.

use crate::material::Mat;
use crate::optics::{fresnel, reflect, refract_with, snell};
use crate::ray::{EPS, Ray, T_MIN};
use crate::world::{Prim, World};
use glam::Vec3A;
use steadyray_render::sampling::branch_random;

/// Where the integrator reports the rays it traces: counters when rendering, a recorder
/// when a single path is inspected.
pub(crate) trait PathSink {
    /// A ray traced at depth `depth` (0: the eye ray).
    fn ray(&mut self, depth: u32, ray: &Ray);
    /// A shadow ray traced toward a light.
    fn shadow_ray(&mut self);
    /// The depth limit ended the chain at a mirror or a dielectric (where a deeper limit
    /// would have traced one more ray).
    #[inline]
    fn stopped(&mut self) {}
    /// A ray of the chain hit a surface (the temporal mode records sample 0's path).
    #[inline]
    fn hit(&mut self, _hit: &PathHit) {}
    /// A ray of the chain left the scene.
    #[inline]
    fn miss(&mut self) {}
}

/// A surface a chain's ray reached, and what the chain does there.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PathHit {
    pub t: f32,
    pub prim: Prim,
    /// The geometric normal flipped to face the ray.
    pub normal: Vec3A,
    /// The chain goes on by a mirror reflection.
    pub reflects: bool,
    /// The chain goes on through a dielectric (reflected or refracted by Fresnel).
    pub dielectric: bool,
}

/// What identifies a sample for `branch_random`: pixel and sample index.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SampleId {
    pub px: u32,
    pub py: u32,
    pub sample: u32,
}

/// The radiance carried back along `ray` by one sample with reflection depth `max_depth`.
#[inline]
pub(crate) fn trace<S: PathSink>(
    world: &World,
    mut ray: Ray,
    id: SampleId,
    max_depth: u32,
    sink: &mut S,
) -> Vec3A {
    let mut w = Vec3A::ONE;
    let mut depth = 0;
    loop {
        sink.ray(depth, &ray);
        let Some(hit) = world.closest_hit(&ray) else {
            sink.miss();
            return w * world.background;
        };
        let p = ray.at(hit.t);
        let outward = world.normal(hit.prim, p);
        let entering = outward.dot(ray.dir) < 0.0;
        let n = if entering { outward } else { -outward };
        let last = depth == max_depth;
        let material = *world.material(hit.prim);
        sink.hit(&PathHit {
            t: hit.t,
            prim: hit.prim,
            normal: n,
            reflects: !last && matches!(material, Mat::Mirror { .. }),
            dielectric: !last && matches!(material, Mat::Dielectric { .. }),
        });
        match material {
            Mat::Emissive { radiance } => return w * radiance,
            Mat::Diffuse { albedo, checker } => {
                let albedo = match checker {
                    Some(c) if world.checker_is_odd(hit.prim, p, c.size) => c.albedo_b,
                    _ => albedo,
                };
                return w * local(world, p, n, albedo, sink);
            }
            Mat::Mirror { reflectance } => {
                if last {
                    sink.stopped();
                    return w * local(world, p, n, reflectance, sink);
                }
                w *= reflectance;
                ray = Ray::new(p + n * EPS, reflect(ray.dir, n));
            }
            Mat::Dielectric { ior, tint } => {
                if last {
                    sink.stopped();
                    return w * local(world, p, n, tint, sink);
                }
                let eta = if entering { 1.0 / ior } else { ior };
                let refracted = snell(ray.dir, n, eta).and_then(|(cos_i, cos_t)| {
                    let f = fresnel(cos_i, cos_t, eta);
                    let xi = branch_random(id.px, id.py, id.sample, depth);
                    (xi >= f).then(|| refract_with(ray.dir, n, eta, cos_i, cos_t))
                });
                ray = match refracted {
                    Some(dir) => {
                        w *= tint;
                        Ray::new(p - n * EPS, dir)
                    }
                    None => Ray::new(p + n * EPS, reflect(ray.dir, n)),
                };
            }
        }
        depth += 1;
    }
}

/// Local shading: albedo · (ambient + Σ V · I · max(0, n·l) / dist²), with a shadow ray
/// (counted) for each light that n faces.
#[inline]
fn local<S: PathSink>(world: &World, p: Vec3A, n: Vec3A, albedo: Vec3A, sink: &mut S) -> Vec3A {
    let mut irradiance = Vec3A::splat(world.ambient);
    let origin = p + n * EPS;
    for light in &world.lights {
        let to_light = light.position - p;
        let dist2 = to_light.length_squared();
        let dist = dist2.sqrt();
        let l = to_light / dist;
        let cos = n.dot(l);
        if cos > 0.0 {
            sink.shadow_ray();
            if !world.occluded(&Ray::new(origin, l), dist - T_MIN) {
                irradiance += light.intensity * cos / dist2;
            }
        }
    }
    albedo * irradiance
}
