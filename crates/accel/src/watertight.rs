//! The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1), 2013: edges shared by two triangles are hit by at least one of
//! them, never neither, whatever the rounding.

use glam::Vec3A;

/// Rays hit on t in (T_MIN, t_max) (`docs/shading.md`).
pub const T_MIN: f32 = 1e-4;

/// A triangle's three corners as plain arrays, so that the test can pick coordinates by a
/// per-ray axis index without a branch.
pub type TriangleVerts = [[f32; 3]; 3];

/// A ray transformed for the watertight test: its dominant axis becomes z and the shear
/// (sx, sy, sz) maps its direction to +z. Computed once per ray, shared by all its tests.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    origin: [f32; 3],
    kx: usize,
    ky: usize,
    kz: usize,
    sx: f32,
    sy: f32,
    sz: f32,
}

impl WatertightRay {
    /// The shear for the ray `origin + t·dir` (`dir` need not be unit length, not zero).
    #[inline]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let kz = dir.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Components picked from an array by index: loads, where indexing the vector
        // compiles to branches on the axes, which bounce rays mispredict.
        let d = dir.to_array();
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        // The three divisions in one vector instruction.
        let [sx, sy, sz] = (Vec3A::new(d[kx], d[ky], 1.0) / d[kz]).to_array();
        Self {
            origin: origin.to_array(),
            kx,
            ky,
            kz,
            sx,
            sy,
            sz,
        }
    }

    /// The ray's origin.
    #[inline(always)]
    pub(crate) fn origin(&self) -> &[f32; 3] {
        &self.origin
    }

    /// The axes (kx, ky, kz) the test maps to x, y and z.
    #[inline(always)]
    pub(crate) fn axes(&self) -> (usize, usize, usize) {
        (self.kx, self.ky, self.kz)
    }

    /// The shear (sx, sy, sz).
    #[inline(always)]
    pub(crate) fn shear(&self) -> (f32, f32, f32) {
        (self.sx, self.sy, self.sz)
    }

    /// The t in (T_MIN, t_max) where the ray meets triangle `v`, if it does. Zero-area
    /// triangles are never hit.
    #[inline]
    pub fn intersect(&self, v: &TriangleVerts, t_max: f32) -> Option<f32> {
        let t = self.intersect_t(v);
        (t > T_MIN && t < t_max).then_some(t)
    }

    /// The t where the ray's line meets triangle `v`, or NaN where it misses (NaN fails
    /// every range test, so callers compare without a separate flag).
    /// The BVH's leaves run this test four triangles at a time (`tri4.rs`); this single
    /// triangle form is the reference they are checked against, bit for bit.
    #[inline]
    pub fn intersect_t(&self, v: &TriangleVerts) -> f32 {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let o = &self.origin;
        let rel = |p: &[f32; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
        let (a, b, c) = (rel(&v[0]), rel(&v[1]), rel(&v[2]));
        let ax = a[kx] - self.sx * a[kz];
        let ay = a[ky] - self.sy * a[kz];
        let bx = b[kx] - self.sx * b[kz];
        let by = b[ky] - self.sy * b[kz];
        let cx = c[kx] - self.sx * c[kz];
        let cy = c[ky] - self.sy * c[kz];
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // On an edge in f32: decide in f64, as the paper does.
            let f =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            u = f(cx, by, cy, bx);
            v = f(ax, cy, ay, cx);
            w = f(bx, ay, by, ax);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return f32::NAN;
        }
        let det = u + v + w;
        if det == 0.0 {
            return f32::NAN;
        }
        let t_scaled = u * (self.sz * a[kz]) + v * (self.sz * b[kz]) + w * (self.sz * c[kz]);
        t_scaled / det
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn verts(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> TriangleVerts {
        [a, b, c]
    }

    #[test]
    fn hits_both_windings_and_reports_t() {
        let t1 = verts([-1.0, -1.0, -3.0], [1.0, -1.0, -3.0], [0.0, 1.0, -3.0]);
        let t2 = verts([-1.0, -1.0, -3.0], [0.0, 1.0, -3.0], [1.0, -1.0, -3.0]);
        let wr = WatertightRay::new(Vec3A::ZERO, Vec3A::NEG_Z);
        assert_eq!(wr.intersect(&t1, f32::INFINITY), Some(3.0));
        assert_eq!(wr.intersect(&t2, f32::INFINITY), Some(3.0));
        assert_eq!(wr.intersect(&t1, 2.0), None);
        let miss = WatertightRay::new(Vec3A::new(2.0, 0.0, 0.0), Vec3A::NEG_Z);
        assert_eq!(miss.intersect(&t1, f32::INFINITY), None);
    }

    #[test]
    fn shared_edges_are_watertight() {
        // Two triangles sharing the diagonal of a skewed quad; rays sweep across it.
        let a = Vec3A::new(-1.3, -0.7, -4.1);
        let b = Vec3A::new(1.1, -0.9, -3.7);
        let c = Vec3A::new(1.2, 1.05, -4.4);
        let d = Vec3A::new(-0.8, 0.9, -4.0);
        let tris = [
            [a.to_array(), b.to_array(), c.to_array()],
            [a.to_array(), c.to_array(), d.to_array()],
        ];
        let origin = Vec3A::new(0.013, -0.021, 0.37);
        for i in 0..=2000 {
            let s = i as f32 / 2000.0;
            for off in [-1e-7f32, 0.0, 1e-7] {
                let target = a.lerp(c, 0.05 + 0.9 * s) + Vec3A::splat(off);
                let wr = WatertightRay::new(origin, (target - origin).normalize());
                assert!(
                    tris.iter()
                        .any(|t| wr.intersect(t, f32::INFINITY).is_some()),
                    "leak at s={s}"
                );
            }
        }
    }

    #[test]
    fn zero_area_triangles_are_never_hit() {
        let wr = WatertightRay::new(Vec3A::new(0.5, 0.0, 1.0), Vec3A::NEG_Z);
        let flat = verts([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]);
        assert_eq!(wr.intersect(&flat, f32::INFINITY), None);
    }
}
