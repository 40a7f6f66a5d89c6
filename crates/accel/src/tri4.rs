//! Four triangles tested against one ray at once: a leaf of the CPU's wide tree stores its
//! (up to four) triangles as structure-of-arrays lanes, the layout of Embree's `Triangle4`,
//! and runs the watertight test of [`WatertightRay`] on all four with the same vector
//! instructions. Every lane computes exactly what [`WatertightRay::intersect_t`] computes
//! for that triangle (the same operations in the same order), so the CPU's hits stay
//! bit-identical to the GPU's and to a brute-force loop.

use crate::watertight::{TriangleVerts, WatertightRay};

/// Up to four triangles: `v[corner][axis][lane]`, and each lane's input index. Unused lanes
/// hold NaN corners, which no ray hits.
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri4 {
    v: [[[f32; 4]; 3]; 3],
    ids: [u32; 4],
}

impl Tri4 {
    /// The block of `tris` (at most four) with input indices `ids`.
    pub fn new(tris: &[TriangleVerts], ids: &[u32]) -> Self {
        debug_assert!(tris.len() <= 4 && tris.len() == ids.len());
        let mut block = Self {
            v: [[[f32::NAN; 4]; 3]; 3],
            ids: [u32::MAX; 4],
        };
        for (lane, (tri, &id)) in tris.iter().zip(ids).enumerate() {
            for (corner, point) in tri.iter().enumerate() {
                for (axis, &value) in point.iter().enumerate() {
                    block.v[corner][axis][lane] = value;
                }
            }
            block.ids[lane] = id;
        }
        block
    }

    /// The input index of lane `lane`.
    #[inline(always)]
    pub fn id(&self, lane: usize) -> u32 {
        self.ids[lane]
    }

    /// Per lane, the t where the ray's line meets that triangle, or NaN where it misses.
    #[inline(always)]
    pub fn intersect_t(&self, ray: &WatertightRay) -> [f32; 4] {
        #[cfg(target_arch = "x86_64")]
        {
            self.intersect_t_sse(ray)
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            self.intersect_t_lanes(ray)
        }
    }

    /// [`Tri4::intersect_t`] as lane loops, for targets other than x86-64 (and as the SSE form's
    /// reference in tests).
    #[cfg(any(test, not(target_arch = "x86_64")))]
    #[inline(always)]
    fn intersect_t_lanes(&self, ray: &WatertightRay) -> [f32; 4] {
        let (kx, ky, kz) = ray.axes();
        let (sx, sy, sz) = ray.shear();
        let o = ray.origin();
        // Per corner: the corner relative to the origin, sheared onto the ray's xy plane.
        let mut x = [[0.0f32; 4]; 3];
        let mut y = [[0.0f32; 4]; 3];
        let mut z = [[0.0f32; 4]; 3];
        for c in 0..3 {
            let (px, py, pz) = (&self.v[c][kx], &self.v[c][ky], &self.v[c][kz]);
            for l in 0..4 {
                let rz = pz[l] - o[kz];
                x[c][l] = (px[l] - o[kx]) - sx * rz;
                y[c][l] = (py[l] - o[ky]) - sy * rz;
                z[c][l] = rz;
            }
        }
        let [ax, bx, cx] = x;
        let [ay, by, cy] = y;
        let mut u = [0.0f32; 4];
        let mut v = [0.0f32; 4];
        let mut w = [0.0f32; 4];
        let mut on_edge = false;
        for l in 0..4 {
            u[l] = cx[l] * by[l] - cy[l] * bx[l];
            v[l] = ax[l] * cy[l] - ay[l] * cx[l];
            w[l] = bx[l] * ay[l] - by[l] * ax[l];
            on_edge |= (u[l] == 0.0) | (v[l] == 0.0) | (w[l] == 0.0);
        }
        if on_edge {
            edge_in_f64(&mut u, &mut v, &mut w, &x, &y);
        }
        let mut t = [0.0f32; 4];
        for l in 0..4 {
            let negative = (u[l] < 0.0) | (v[l] < 0.0) | (w[l] < 0.0);
            let positive = (u[l] > 0.0) | (v[l] > 0.0) | (w[l] > 0.0);
            let det = u[l] + v[l] + w[l];
            let t_scaled = u[l] * (sz * z[0][l]) + v[l] * (sz * z[1][l]) + w[l] * (sz * z[2][l]);
            let miss = (negative & positive) | (det == 0.0);
            t[l] = if miss { f32::NAN } else { t_scaled / det };
        }
        t
    }

    /// [`Tri4::intersect_t`] in SSE, which every x86-64 CPU has: the lane loops' operations
    /// in the same order, four lanes per instruction (compilers left parts of the loops
    /// scalar).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn intersect_t_sse(&self, ray: &WatertightRay) -> [f32; 4] {
        use std::arch::x86_64::*;
        let (kx, ky, kz) = ray.axes();
        let (sx, sy, sz) = ray.shear();
        let o = ray.origin();
        // SAFETY: SSE is part of every x86-64 CPU; the loads and stores move whole
        // four-lane rows.
        unsafe {
            let load = |row: &[f32; 4]| _mm_loadu_ps(row.as_ptr());
            let (okx, oky, okz) = (_mm_set1_ps(o[kx]), _mm_set1_ps(o[ky]), _mm_set1_ps(o[kz]));
            let (vsx, vsy, vsz) = (_mm_set1_ps(sx), _mm_set1_ps(sy), _mm_set1_ps(sz));
            // Per corner: the corner relative to the origin, sheared onto the ray's xy plane.
            let corner = |c: usize| {
                let rz = _mm_sub_ps(load(&self.v[c][kz]), okz);
                let x = _mm_sub_ps(_mm_sub_ps(load(&self.v[c][kx]), okx), _mm_mul_ps(vsx, rz));
                let y = _mm_sub_ps(_mm_sub_ps(load(&self.v[c][ky]), oky), _mm_mul_ps(vsy, rz));
                (x, y, rz)
            };
            let (ax, ay, az) = corner(0);
            let (bx, by, bz) = corner(1);
            let (cx, cy, cz) = corner(2);
            let mut u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
            let mut v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
            let mut w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
            let zero = _mm_setzero_ps();
            let on_edge = _mm_or_ps(
                _mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)),
                _mm_cmpeq_ps(w, zero),
            );
            if _mm_movemask_ps(on_edge) != 0 {
                let rows = |a: __m128, b: __m128, c: __m128| {
                    let mut out = [[0.0f32; 4]; 3];
                    for (row, value) in out.iter_mut().zip([a, b, c]) {
                        _mm_storeu_ps(row.as_mut_ptr(), value);
                    }
                    out
                };
                let ([mut us, mut vs, mut ws], x, y) =
                    (rows(u, v, w), rows(ax, bx, cx), rows(ay, by, cy));
                edge_in_f64(&mut us, &mut vs, &mut ws, &x, &y);
                (u, v, w) = (load(&us), load(&vs), load(&ws));
            }
            let negative = _mm_or_ps(
                _mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)),
                _mm_cmplt_ps(w, zero),
            );
            let positive = _mm_or_ps(
                _mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)),
                _mm_cmpgt_ps(w, zero),
            );
            let det = _mm_add_ps(_mm_add_ps(u, v), w);
            let t_scaled = _mm_add_ps(
                _mm_add_ps(
                    _mm_mul_ps(u, _mm_mul_ps(vsz, az)),
                    _mm_mul_ps(v, _mm_mul_ps(vsz, bz)),
                ),
                _mm_mul_ps(w, _mm_mul_ps(vsz, cz)),
            );
            let miss = _mm_or_ps(_mm_and_ps(negative, positive), _mm_cmpeq_ps(det, zero));
            let t = _mm_or_ps(
                _mm_and_ps(miss, _mm_set1_ps(f32::NAN)),
                _mm_andnot_ps(miss, _mm_div_ps(t_scaled, det)),
            );
            let mut out = [0.0f32; 4];
            _mm_storeu_ps(out.as_mut_ptr(), t);
            out
        }
    }

    /// The lanes (bit `lane`) whose t lies in (lo, hi]; NaN lies in none.
    #[inline(always)]
    pub fn lanes_in(t: &[f32; 4], lo: f32, hi: f32) -> u32 {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::*;
            // SAFETY: SSE is part of every x86-64 CPU; the load reads the four lanes.
            unsafe {
                let t = _mm_loadu_ps(t.as_ptr());
                let inside = _mm_and_ps(
                    _mm_cmpgt_ps(t, _mm_set1_ps(lo)),
                    _mm_cmple_ps(t, _mm_set1_ps(hi)),
                );
                _mm_movemask_ps(inside) as u32
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let mut mask = 0;
            for (lane, &tl) in t.iter().enumerate() {
                mask |= u32::from((tl > lo) & (tl <= hi)) << lane;
            }
            mask
        }
    }
}

/// The rare lanes where an edge function is exactly zero in f32: all three recomputed in
/// f64, as [`WatertightRay::intersect_t`] does.
#[cold]
#[inline(never)]
fn edge_in_f64(
    u: &mut [f32; 4],
    v: &mut [f32; 4],
    w: &mut [f32; 4],
    x: &[[f32; 4]; 3],
    y: &[[f32; 4]; 3],
) {
    let f = |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
    let [ax, bx, cx] = x;
    let [ay, by, cy] = y;
    for l in 0..4 {
        if u[l] == 0.0 || v[l] == 0.0 || w[l] == 0.0 {
            u[l] = f(cx[l], by[l], cy[l], bx[l]);
            v[l] = f(ax[l], cy[l], ay[l], cx[l]);
            w[l] = f(bx[l], ay[l], by[l], ax[l]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    /// Every lane agrees bit for bit with the single-triangle test, edges and misses included.
    #[test]
    fn lanes_match_the_single_triangle_test() {
        let tris: [TriangleVerts; 4] = [
            [[-1.0, -1.0, -3.0], [1.0, -1.0, -3.0], [0.0, 1.0, -3.0]],
            [[-1.0, -1.0, -3.0], [0.0, 1.0, -3.0], [1.0, -1.0, -3.0]],
            [[0.0, 0.0, -2.0], [2.0, 0.0, -2.0], [0.0, 2.0, -2.5]],
            [[0.0, 0.0, -1.0], [1.0, 0.0, -1.0], [3.0, 0.0, -1.0]],
        ];
        for n in 1..=4 {
            let block = Tri4::new(&tris[..n], &[7, 8, 9, 10][..n]);
            for i in 0..400 {
                let s = i as f32 / 400.0;
                let origin = Vec3A::new(0.0, 0.0, 0.5);
                for dir in [
                    Vec3A::new(s - 0.5, 0.0, -1.0),
                    Vec3A::new(0.0, s - 0.3, -1.0),
                    Vec3A::new(s, s * 0.5, -0.2),
                    Vec3A::new(-1.0, s, 0.3),
                ] {
                    let ray = WatertightRay::new(origin, dir);
                    let lanes = block.intersect_t(&ray);
                    let loops = block.intersect_t_lanes(&ray);
                    for (lane, tri) in tris.iter().enumerate() {
                        let want = if lane < n {
                            ray.intersect_t(tri)
                        } else {
                            f32::NAN
                        };
                        for got in [lanes[lane], loops[lane]] {
                            if want.is_nan() {
                                assert!(got.is_nan(), "lane {lane} s {s}");
                            } else {
                                assert_eq!(got.to_bits(), want.to_bits(), "lane {lane} s {s}");
                            }
                        }
                    }
                }
            }
        }
    }
}
