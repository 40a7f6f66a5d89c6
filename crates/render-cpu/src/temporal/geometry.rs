//! The geometry record of a pixel (`docs/temporal.md`, "What sample 0 records"): the point
//! its history is reprojected by, the surface seen there and its normal, recorded along the
//! path of the pixel's sample 0 while it is traced. Seen through mirrors, the point and the
//! normal are those of the mirror image (the virtual scene behind the mirrors).

use crate::integrator::{PathHit, PathSink};
use crate::ray::Ray;
use crate::world::World;
use glam::Vec3A;
use steadyray_render::temporal::{APPROX_FLAG, MIRROR_FLAG, MISS_ID, dot3};

/// One pixel's geometry, laid out as the GPU's two `vec4`s.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Geometry {
    /// The reprojected point (`q[3]` = 1), or the eye ray's direction (`q[3]` = 0) when the
    /// path leaves the scene.
    pub q: [f32; 4],
    /// The surface's normal, flipped to face the ray that hit it and carried back through
    /// the mirrors (zero for a miss).
    pub n: [f32; 3],
    /// The surface id (`MISS_ID` for a miss), with `APPROX_FLAG` set when a dielectric or a
    /// curved mirror makes the reprojection approximate and `MIRROR_FLAG` when the surface is
    /// seen through a mirror.
    pub tag: u32,
}

/// A [`PathSink`] that passes rays on to `inner` (the frame's counters) and records the
/// geometry of the path: its run of mirror reflections is followed, and the first event
/// that is not one ends the record.
pub(crate) struct GeometrySink<'a, S> {
    inner: &'a mut S,
    world: &'a World,
    eye: Vec3A,
    dir: Vec3A,
    /// Distance travelled through the mirrors so far.
    length: f32,
    /// Rows of the product of the mirrors' reflections so far, which takes a normal seen
    /// through them back to the mirror image.
    mirrors: [[f32; 3]; 3],
    mirrored: bool,
    approx: bool,
    record: Option<Geometry>,
}

/// v − 2·(v·m)·m, the reflection of `v` about unit normal `m`.
#[inline]
fn reflect(v: [f32; 3], m: [f32; 3]) -> [f32; 3] {
    let k = 2.0 * dot3(v, m);
    [v[0] - k * m[0], v[1] - k * m[1], v[2] - k * m[2]]
}

impl<'a, S: PathSink> GeometrySink<'a, S> {
    /// A recorder for the eye ray from `eye` along unit `dir`.
    pub fn new(inner: &'a mut S, world: &'a World, eye: Vec3A, dir: Vec3A) -> Self {
        Self {
            inner,
            world,
            eye,
            dir,
            length: 0.0,
            mirrors: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            mirrored: false,
            approx: false,
            record: None,
        }
    }

    /// The record of the traced path.
    pub fn finish(self) -> Geometry {
        self.record.unwrap_or_default()
    }

    fn tag(&self, id: u32) -> u32 {
        let approx = if self.approx { APPROX_FLAG } else { 0 };
        let mirrored = if self.mirrored { MIRROR_FLAG } else { 0 };
        id | approx | mirrored
    }
}

impl<S: PathSink> PathSink for GeometrySink<'_, S> {
    #[inline]
    fn ray(&mut self, depth: u32, ray: &Ray) {
        self.inner.ray(depth, ray);
    }

    #[inline]
    fn shadow_ray(&mut self) {
        self.inner.shadow_ray();
    }

    #[inline]
    fn stopped(&mut self) {
        self.inner.stopped();
    }

    fn hit(&mut self, hit: &PathHit) {
        if self.record.is_some() {
            return;
        }
        self.length += hit.t;
        let n = hit.normal.to_array();
        if hit.reflects {
            self.mirrored = true;
            self.approx |= !self.world.is_flat(hit.prim);
            self.mirrors = self.mirrors.map(|row| reflect(row, n));
            return;
        }
        self.approx |= hit.dielectric;
        let q = self.eye + self.dir * self.length;
        self.record = Some(Geometry {
            q: q.extend(1.0).to_array(),
            n: self.mirrors.map(|row| dot3(row, n)),
            tag: self.tag(self.world.surface_id(hit.prim)),
        });
    }

    fn miss(&mut self) {
        if self.record.is_none() {
            self.record = Some(Geometry {
                q: self.dir.extend(0.0).to_array(),
                n: [0.0; 3],
                tag: self.tag(MISS_ID),
            });
        }
    }
}
