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
                    for (lane, tri) in tris.iter().enumerate() {
                        let want = if lane < n {
                            ray.intersect_t(tri)
                        } else {
                            f32::NAN
                        };
                        if want.is_nan() {
                            assert!(lanes[lane].is_nan(), "lane {lane} s {s}");
                        } else {
                            assert_eq!(lanes[lane].to_bits(), want.to_bits(), "lane {lane} s {s}");
                        }
                    }
                }
            }
        }
    }
}
