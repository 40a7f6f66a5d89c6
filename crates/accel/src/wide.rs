//! The 4-wide BVH the CPU traverses: each node holds its four children's boxes as
//! structure-of-arrays lanes, so one step tests four boxes with the same few vector
//! instructions (the layout of Embree's BVH4). Traversal is single-ray, nearest child
//! first, with early exit for shadow rays.

use crate::watertight::{T_MIN, TriangleVerts, WatertightRay};
use glam::Vec3A;
use std::mem::MaybeUninit;

/// Set in [`Node4::child`] for a leaf: bits 27..31 hold the triangle count (1..=15), bits
/// 0..27 the leaf-order position of its first triangle.
pub(crate) const LEAF: u32 = 1 << 31;
/// Leaf-order positions must fit below this (2^27 triangles).
pub(crate) const MAX_LEAF_FIRST: u32 = 1 << 27;
/// Entries of the traversal stack; the build refuses trees that could overflow it.
pub(crate) const STACK_SIZE: usize = 192;

/// Box tests are widened by this relative margin on both ends, more than the rounding of
/// the slab arithmetic and of the triangle test's t (Ize, "Robust BVH Ray Traversal",
/// JCGT 2013), so that no box rejects a triangle hit the watertight test would report.
const NEAR_SCALE: f32 = 1.0 - 1.0 / (1 << 20) as f32;
const FAR_SCALE: f32 = 1.0 + 1.0 / (1 << 20) as f32;

/// A 4-wide node: per axis the four children's minima and maxima (`bounds[0..3]` minima
/// x, y, z; `bounds[3..6]` maxima), and per child an inner node index or a leaf (`LEAF`).
/// Unused lanes have an inverted (empty) box, which every ray misses.
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node4 {
    pub bounds: [[f32; 4]; 6],
    pub child: [u32; 4],
}

impl Node4 {
    /// A node whose four lanes are all empty.
    pub const EMPTY: Node4 = Node4 {
        bounds: [
            [f32::INFINITY; 4],
            [f32::INFINITY; 4],
            [f32::INFINITY; 4],
            [f32::NEG_INFINITY; 4],
            [f32::NEG_INFINITY; 4],
            [f32::NEG_INFINITY; 4],
        ],
        child: [0; 4],
    };
}

/// What one traversal needs of its box tests: the origin, the inverse direction and which
/// bound of each axis is met first. A zero direction component gives an infinite inverse;
/// a slab bound through the origin then gives 0·∞ = NaN, which the comparisons in
/// [`BoxRay::test`] ignore: the ray lies in that slab for every t, as it should.
struct BoxRay {
    origin: [f32; 3],
    inv: [f32; 3],
    near: [usize; 3],
    far: [usize; 3],
}

impl BoxRay {
    #[inline]
    fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let inv = dir.to_array().map(|d| 1.0 / d);
        let near = [0, 1, 2].map(|a| if inv[a] >= 0.0 { a } else { a + 3 });
        Self {
            origin: origin.to_array(),
            inv,
            far: near.map(|n| if n < 3 { n + 3 } else { n - 3 }),
            near,
        }
    }

    /// Per lane of `node`: the widened entry distance, and whether the ray meets the box
    /// on [0, t_max].
    #[inline(always)]
    fn test(&self, node: &Node4, t_max: f32) -> ([f32; 4], [bool; 4]) {
        let mut near = [0.0f32; 4];
        let mut far = [f32::INFINITY; 4];
        for axis in 0..3 {
            let lo = &node.bounds[self.near[axis]];
            let hi = &node.bounds[self.far[axis]];
            let (o, inv) = (self.origin[axis], self.inv[axis]);
            for lane in 0..4 {
                let n = (lo[lane] - o) * inv;
                let f = (hi[lane] - o) * inv;
                // Written as comparisons so that a NaN bound leaves the interval unchanged.
                near[lane] = if n > near[lane] { n } else { near[lane] };
                far[lane] = if f < far[lane] { f } else { far[lane] };
            }
        }
        let mut hit = [false; 4];
        for lane in 0..4 {
            near[lane] *= NEAR_SCALE;
            hit[lane] = near[lane] <= (far[lane] * FAR_SCALE).min(t_max);
        }
        (near, hit)
    }
}

/// The 4-wide tree and the triangles in leaf order, with their input indices.
#[derive(Clone, Debug, Default)]
pub(crate) struct Wide {
    pub nodes: Vec<Node4>,
    pub tris: Vec<TriangleVerts>,
    pub ids: Vec<u32>,
}

impl Wide {
    /// The nearest triangle hit on t in (T_MIN, t_max): its t and input index. Among hits at
    /// the same t the lowest input index wins, as in a brute-force loop in input order.
    #[inline]
    pub fn closest(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<(f32, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let wr = WatertightRay::new(origin, dir);
        let br = BoxRay::new(origin, dir);
        let mut best_t = t_max;
        // Ties with the incoming t_max are not hits (id < 0 never holds).
        let mut best_id = 0u32;
        let mut found = false;
        // Uninitialised: zeroing it would cost as much as a short traversal.
        let mut stack = [MaybeUninit::<(u32, f32)>::uninit(); STACK_SIZE];
        let mut sp = 0usize;
        let mut cur = 0u32;
        loop {
            if cur & LEAF == 0 {
                let node = &self.nodes[cur as usize];
                let (t_near, hit) = br.test(node, best_t);
                let mut order = [(0.0f32, 0u32); 4];
                let mut n = 0;
                for lane in 0..4 {
                    if hit[lane] {
                        order[n] = (t_near[lane], node.child[lane]);
                        n += 1;
                    }
                }
                if n > 0 {
                    // Nearest last: insertion sort by descending entry distance.
                    for i in 1..n {
                        let mut j = i;
                        while j > 0 && order[j - 1].0 < order[j].0 {
                            order.swap(j - 1, j);
                            j -= 1;
                        }
                    }
                    for &(d, c) in &order[..n - 1] {
                        stack[sp].write((c, d));
                        sp += 1;
                    }
                    cur = order[n - 1].1;
                    continue;
                }
            } else {
                let first = (cur & (MAX_LEAF_FIRST - 1)) as usize;
                let count = ((cur & !LEAF) >> 27) as usize;
                for k in first..first + count {
                    let t = wr.intersect_t(&self.tris[k]);
                    let id = self.ids[k];
                    if t > T_MIN && (t < best_t || (t == best_t && id < best_id)) {
                        best_t = t;
                        best_id = id;
                        found = true;
                    }
                }
            }
            // Pop the nearest pending child that can still hold a closer hit.
            loop {
                if sp == 0 {
                    return found.then_some((best_t, best_id));
                }
                sp -= 1;
                // SAFETY: entries below `sp` were all written by the pushes above.
                let (c, d) = unsafe { stack[sp].assume_init() };
                if d <= best_t {
                    cur = c;
                    break;
                }
            }
        }
    }

    /// Whether any triangle is hit on t in (T_MIN, t_max); stops at the first hit found.
    #[inline]
    pub fn any_hit(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let wr = WatertightRay::new(origin, dir);
        let br = BoxRay::new(origin, dir);
        let mut stack = [MaybeUninit::<u32>::uninit(); STACK_SIZE];
        let mut sp = 0usize;
        let mut cur = 0u32;
        loop {
            if cur & LEAF == 0 {
                let node = &self.nodes[cur as usize];
                let (_, hit) = br.test(node, t_max);
                for (&h, &child) in hit.iter().zip(&node.child) {
                    if h {
                        stack[sp].write(child);
                        sp += 1;
                    }
                }
            } else {
                let first = (cur & (MAX_LEAF_FIRST - 1)) as usize;
                let count = ((cur & !LEAF) >> 27) as usize;
                for tri in &self.tris[first..first + count] {
                    let t = wr.intersect_t(tri);
                    if t > T_MIN && t < t_max {
                        return true;
                    }
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            // SAFETY: entries below `sp` were all written by the pushes above.
            cur = unsafe { stack[sp].assume_init() };
        }
    }
}
