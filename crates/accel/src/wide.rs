//! The 8-wide BVH the CPU traverses: each node holds its eight children's boxes as
//! structure-of-arrays lanes, so one step tests eight boxes with a few AVX instructions (the
//! layout of Embree's BVH8), and each leaf is one [`Tri4`] block tested in one go.
//! Traversal is single-ray, nearest child first, with early exit for shadow rays. CPUs
//! with AVX-512 run the AVX2 code compiled for their wider register file; CPUs without
//! AVX2 traverse the same tree with portable lane loops. All get the same hits.

#[cfg(target_arch = "x86_64")]
use crate::box_test::Avx;
use crate::box_test::{BoxRay, BoxTest, Portable};
use crate::child_order::Pending;
use crate::tri4::Tri4;
use crate::watertight::{T_MIN, WatertightRay};
use glam::Vec3A;
use std::mem::MaybeUninit;

/// Children per node. Eight with AVX2 box tests measured faster than the earlier 4-wide
/// tree with scalar leaves on both ray sets of `steadyray raybench` (bunny, 2 threads:
/// primary 28.7 vs 25.5 M rays/s, bounce 7.9 vs 6.2); without AVX, eight lanes of portable
/// loops traced primary rays slower than four (9.4 vs 11.3 M rays/s, 1 thread).
pub(crate) const WIDTH: usize = 8;
/// Set in [`WideNode::child`] for a leaf; the bits below hold the index of its [`Tri4`] block.
pub(crate) const LEAF: u32 = 1 << 31;
/// Entries of the traversal stack; the build refuses trees that could overflow it.
pub(crate) const STACK_SIZE: usize = 192;

/// A wide node: per axis the children's minima and maxima (`bounds[0..3]` minima
/// x, y, z; `bounds[3..6]` maxima), and per child an inner node index or a leaf (`LEAF`).
/// Unused lanes have an inverted (empty) box, which every ray misses.
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug)]
pub(crate) struct WideNode {
    pub bounds: [[f32; WIDTH]; 6],
    pub child: [u32; WIDTH],
}

impl WideNode {
    /// A node whose eight lanes are all empty.
    pub const EMPTY: WideNode = WideNode {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [0; WIDTH],
    };

    /// Sets lane `lane`'s box.
    pub fn set_box(&mut self, lane: usize, min: [f32; 3], max: [f32; 3]) {
        for axis in 0..3 {
            self.bounds[axis][lane] = min[axis];
            self.bounds[axis + 3][lane] = max[axis];
        }
    }
}

/// Whether a ray can be traversed: with a NaN or infinite origin or direction its box tests,
/// which leave an interval unchanged at a NaN, would enter every box, the empty lanes too,
/// and overflow the stack. The top level ([`crate::TopLevel`]) lets such a ray meet nothing;
/// a mesh's tree takes only finite rays (the top level's callers pass them on), and checks
/// that in debug builds only: the check cost 4 % of the primary rays per second of
/// `steadyray raybench` on the bunny.
#[inline(always)]
pub(crate) fn finite_ray(origin: Vec3A, dir: Vec3A) -> bool {
    (origin.is_finite_mask() & dir.is_finite_mask()).all()
}

/// The vector extensions a CPU pass is compiled for: the traversal's box tests here, and the
/// CPU renderer's per-pixel passes (`steadyray-render-cpu`).
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub enum X86Level {
    /// The workspace's build (SSE2): the portable lane loops.
    Baseline,
    /// AVX2: the AVX2 box tests.
    Avx2,
    /// The same AVX2 code compiled with AVX-512 F and VL enabled. Its 32 vector registers
    /// hold all of the ray's constants, where with 16 the box test reloaded two of them
    /// from memory at every node: 5 % more bounce rays per second on the bunny (Zen 4).
    Avx512,
}

/// The best [`X86Level`] this CPU runs (the feature checks are cached by the standard
/// library).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub fn x86_level() -> X86Level {
    use std::arch::is_x86_feature_detected as has;
    if !has!("avx2") {
        X86Level::Baseline
    } else if has!("avx512f") && has!("avx512vl") {
        X86Level::Avx512
    } else {
        X86Level::Avx2
    }
}

/// The name of the traversal's compiled form this CPU runs: "avx512", "avx2" or
/// "portable".
pub(crate) fn simd_name() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    match x86_level() {
        X86Level::Avx512 => return "avx512",
        X86Level::Avx2 => return "avx2",
        X86Level::Baseline => {}
    }
    "portable"
}

/// The wide tree, its leaves' triangle blocks, and the input indices in leaf order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Wide {
    pub nodes: Vec<WideNode>,
    pub leaves: Vec<Tri4>,
    pub ids: Vec<u32>,
}

impl Wide {
    /// The nearest triangle hit on t in (T_MIN, t_max): its t and input index. Among hits at
    /// the same t the lowest input index wins, as in a brute-force loop in input order.
    #[inline]
    pub fn closest(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<(f32, u32)> {
        #[cfg(target_arch = "x86_64")]
        match x86_level() {
            // SAFETY: this CPU has AVX2, AVX-512 F and AVX-512 VL.
            X86Level::Avx512 => return unsafe { self.closest_avx512(origin, dir, t_max) },
            // SAFETY: this CPU has AVX2.
            X86Level::Avx2 => return unsafe { self.closest_avx2(origin, dir, t_max) },
            X86Level::Baseline => {}
        }
        self.closest_with::<Portable>(origin, dir, t_max)
    }

    /// [`Wide::any_hit`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn any_hit_avx2(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        self.any_hit_with::<Avx>(origin, dir, t_max)
    }

    /// [`Wide::any_hit`] compiled for AVX-512 (see [`X86Level::Avx512`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    fn any_hit_avx512(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        self.any_hit_with::<Avx>(origin, dir, t_max)
    }

    /// [`Wide::closest`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn closest_avx2(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<(f32, u32)> {
        self.closest_with::<Avx>(origin, dir, t_max)
    }

    /// [`Wide::closest`] compiled for AVX-512 (see [`X86Level::Avx512`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    fn closest_avx512(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<(f32, u32)> {
        self.closest_with::<Avx>(origin, dir, t_max)
    }

    /// [`Wide::closest`] with box tests by `B`.
    #[inline(always)]
    pub(crate) fn closest_with<B: BoxTest>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
    ) -> Option<(f32, u32)> {
        debug_assert!(
            finite_ray(origin, dir),
            "a ray that is not finite: {origin} {dir}"
        );
        if self.nodes.is_empty() {
            return None;
        }
        let wr = WatertightRay::new(origin, dir);
        let br = BoxRay::new(origin, dir);
        let mut best_t = t_max;
        // Ties with the incoming t_max are not hits (id < 0 never holds).
        let mut best_id = 0u32;
        let mut found = false;
        let mut stack = [MaybeUninit::uninit(); STACK_SIZE];
        let mut pending = Pending::new(&mut stack);
        let mut cur = 0u32;
        loop {
            if cur & LEAF == 0 {
                let node = &self.nodes[cur as usize];
                let (near, lanes) = B::test(&br, node, best_t);
                if lanes != 0 {
                    cur = pending.enter(&near, &node.child, lanes);
                    continue;
                }
            } else {
                let block = &self.leaves[(cur & !LEAF) as usize];
                let t = block.intersect_t(&wr);
                let mut hits = Tri4::lanes_in(&t, T_MIN, best_t);
                while hits != 0 {
                    let lane = hits.trailing_zeros() as usize;
                    hits &= hits - 1;
                    let (tl, id) = (t[lane], block.id(lane));
                    // An earlier lane may have lowered best_t since the mask was taken.
                    if tl < best_t || (tl == best_t && id < best_id) {
                        best_t = tl;
                        best_id = id;
                        found = true;
                    }
                }
            }
            // The nearest pending child that can still hold a closer hit.
            match pending.pop_within(best_t) {
                Some(next) => cur = next,
                None => return found.then_some((best_t, best_id)),
            }
        }
    }

    /// Whether any triangle is hit on t in (T_MIN, t_max); stops at the first hit found.
    #[inline]
    pub fn any_hit(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        #[cfg(target_arch = "x86_64")]
        match x86_level() {
            // SAFETY: this CPU has AVX2, AVX-512 F and AVX-512 VL.
            X86Level::Avx512 => return unsafe { self.any_hit_avx512(origin, dir, t_max) },
            // SAFETY: this CPU has AVX2.
            X86Level::Avx2 => return unsafe { self.any_hit_avx2(origin, dir, t_max) },
            X86Level::Baseline => {}
        }
        self.any_hit_with::<Portable>(origin, dir, t_max)
    }

    /// [`Wide::any_hit`] with box tests by `B`.
    #[inline(always)]
    pub(crate) fn any_hit_with<B: BoxTest>(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        debug_assert!(
            finite_ray(origin, dir),
            "a ray that is not finite: {origin} {dir}"
        );
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
                let (_, mut mask) = B::test(&br, node, t_max);
                while mask != 0 {
                    stack[sp].write(node.child[mask.trailing_zeros() as usize]);
                    sp += 1;
                    mask &= mask - 1;
                }
            } else {
                let t = self.leaves[(cur & !LEAF) as usize].intersect_t(&wr);
                // t < t_max is t <= the float below t_max.
                if Tri4::lanes_in(&t, T_MIN, t_max.next_down()) != 0 {
                    return true;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Bvh;
    use glam::Vec3;

    /// The portable lane loops and every compiled form this CPU runs (AVX2 and AVX-512
    /// where present, and the dispatched one) agree on every ray, hit or miss, nearest or
    /// any.
    #[test]
    fn portable_and_vector_traversals_agree() {
        let mut state = 0x2545_f491u32;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        };
        let mut point = || Vec3::new(next(), next(), next()) * 4.0 - 2.0;
        let tris: Vec<[Vec3; 3]> = (0..3000)
            .map(|_| {
                let c = point();
                [c, c + point() * 0.1, c + point() * 0.1]
            })
            .collect();
        let bvh = Bvh::build(&tris).unwrap();
        let wide = &bvh.wide;
        #[cfg(target_arch = "x86_64")]
        let level = x86_level();
        let mut hits = 0;
        for _ in 0..4000 {
            let origin = Vec3A::from(point() * 1.5);
            let dir = Vec3A::from(point()).normalize_or(Vec3A::X);
            let t_max = if hits % 3 == 0 { f32::INFINITY } else { 2.0 };
            let want = wide.closest_with::<Portable>(origin, dir, t_max);
            let want_any = wide.any_hit_with::<Portable>(origin, dir, t_max);
            assert_eq!(bvh.closest(origin, dir, t_max), want);
            assert_eq!(bvh.any_hit(origin, dir, t_max), want_any);
            #[cfg(target_arch = "x86_64")]
            {
                if level != X86Level::Baseline {
                    // SAFETY: this CPU has AVX2.
                    unsafe {
                        assert_eq!(wide.closest_avx2(origin, dir, t_max), want);
                        assert_eq!(wide.any_hit_avx2(origin, dir, t_max), want_any);
                    }
                }
                if level == X86Level::Avx512 {
                    // SAFETY: this CPU has AVX2, AVX-512 F and AVX-512 VL.
                    unsafe {
                        assert_eq!(wide.closest_avx512(origin, dir, t_max), want);
                        assert_eq!(wide.any_hit_avx512(origin, dir, t_max), want_any);
                    }
                }
            }
            hits += usize::from(want.is_some());
        }
        assert!(hits > 500, "too few hits ({hits}) to compare");
    }
}
