//! Tracing a single ray the way an eye sample is traced, recording its path: for tests,
//! debugging and comparing backends ray by ray.

use crate::integrator::PathSink;
use crate::ray::Ray;
use glam::Vec3;

/// One ray of a recorded path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracedRay {
    /// 0 for the first ray, +1 per reflection or refraction.
    pub depth: u32,
    /// Where the ray starts.
    pub origin: Vec3,
    /// The direction as traced (not renormalised).
    pub dir: Vec3,
}

/// The path of one sample: every ray of its chain, its shadow-ray count and its radiance.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathTrace {
    /// Every ray of the chain, the eye ray first.
    pub rays: Vec<TracedRay>,
    /// Shadow rays traced along it.
    pub shadow_rays: u64,
    /// Linear radiance carried back to the first ray's origin.
    pub radiance: Vec3,
}

impl PathSink for PathTrace {
    fn ray(&mut self, depth: u32, ray: &Ray) {
        self.rays.push(TracedRay {
            depth,
            origin: ray.origin.into(),
            dir: ray.dir.into(),
        });
    }

    fn shadow_ray(&mut self) {
        self.shadow_rays += 1;
    }
}
