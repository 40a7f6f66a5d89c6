//! The ray-box test of the CPU's wide tree: one ray against all [`WIDTH`] child boxes of a
//! node at once. [`Portable`] is plain lane loops for any CPU; [`Avx`] is the same arithmetic
//! in 256-bit AVX instructions, which the traversal uses where the CPU has them (compilers
//! do not reliably turn the lane loops into those instructions by themselves). Both give
//! the same bits.

use crate::wide::{WIDTH, WideNode};
use glam::Vec3A;

/// Box tests are widened by this relative margin on both ends, more than the rounding of
/// the slab arithmetic and of the triangle test's t (Ize, "Robust BVH Ray Traversal",
/// JCGT 2013), so that no box rejects a triangle hit the watertight test would report.
const NEAR_SCALE: f32 = 1.0 - 1.0 / (1 << 20) as f32;
const FAR_SCALE: f32 = 1.0 + 1.0 / (1 << 20) as f32;

/// What one traversal needs of its box tests: the origin and the inverse direction, in
/// two copies with the widening folded in (one for entry distances, one for exit
/// distances), so that the widening costs no instruction per node. The relative error this
/// adds (one rounding) is far inside the margin.
///
/// The sign of the inverse direction says which bound of an axis is met first: the minimum
/// where it is positive (+∞ for a +0 component), the maximum where it is negative. A zero
/// direction component gives an infinite inverse; a slab bound through the origin then
/// gives 0·∞ = NaN, which the tests ignore: the ray lies in that slab for every t, as it
/// should.
pub(crate) struct BoxRay {
    origin: [f32; 3],
    inv_near: [f32; 3],
    inv_far: [f32; 3],
}

impl BoxRay {
    #[inline(always)]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let inv = (Vec3A::ONE / dir).to_array();
        Self {
            origin: origin.to_array(),
            inv_near: inv.map(|i| i * NEAR_SCALE),
            inv_far: inv.map(|i| i * FAR_SCALE),
        }
    }
}

/// A way to run the box test: per lane of `node`, the widened entry distance, and as bit
/// `lane` of a mask whether the ray meets that box on [0, t_max].
pub(crate) trait BoxTest {
    fn test(ray: &BoxRay, node: &WideNode, t_max: f32) -> ([f32; WIDTH], u32);
}

/// Lane loops, for any CPU.
pub(crate) struct Portable;

impl BoxTest for Portable {
    #[inline(always)]
    fn test(ray: &BoxRay, node: &WideNode, t_max: f32) -> ([f32; WIDTH], u32) {
        let mut near = [0.0f32; WIDTH];
        let mut far = [t_max; WIDTH];
        for axis in 0..3 {
            let (min, max) = (&node.bounds[axis], &node.bounds[axis + 3]);
            let (lo, hi) = if ray.inv_near[axis].is_sign_negative() {
                (max, min)
            } else {
                (min, max)
            };
            let o = ray.origin[axis];
            let (inv_near, inv_far) = (ray.inv_near[axis], ray.inv_far[axis]);
            for lane in 0..WIDTH {
                let n = (lo[lane] - o) * inv_near;
                let f = (hi[lane] - o) * inv_far;
                // Comparisons, so that a NaN bound leaves the interval unchanged.
                near[lane] = if n > near[lane] { n } else { near[lane] };
                far[lane] = if f < far[lane] { f } else { far[lane] };
            }
        }
        let mut hit = 0u32;
        for lane in 0..WIDTH {
            hit |= u32::from(near[lane] <= far[lane]) << lane;
        }
        (near, hit)
    }
}

/// 256-bit AVX: all eight lanes in each instruction. Only for code compiled with AVX
/// enabled on a CPU that has it (the traversal's AVX2 entry points).
#[cfg(target_arch = "x86_64")]
pub(crate) struct Avx;

#[cfg(target_arch = "x86_64")]
impl BoxTest for Avx {
    #[inline(always)]
    fn test(ray: &BoxRay, node: &WideNode, t_max: f32) -> ([f32; WIDTH], u32) {
        use std::arch::x86_64::*;
        const { assert!(WIDTH == 8) };
        // SAFETY: only instantiated inside functions compiled with AVX2 enabled, which run
        // only after the CPU was found to have it; the loads read whole 8-lane rows.
        unsafe {
            let mut near = _mm256_setzero_ps();
            let mut far = _mm256_set1_ps(t_max);
            for axis in 0..3 {
                let min = _mm256_loadu_ps(node.bounds[axis].as_ptr());
                let max = _mm256_loadu_ps(node.bounds[axis + 3].as_ptr());
                let (inv_near, inv_far) = (
                    _mm256_set1_ps(ray.inv_near[axis]),
                    _mm256_set1_ps(ray.inv_far[axis]),
                );
                // Rows at fixed offsets, swapped by the sign bit of the inverse direction:
                // no per-ray row offsets held in registers or reloaded per node.
                let lo = _mm256_blendv_ps(min, max, inv_near);
                let hi = _mm256_blendv_ps(max, min, inv_near);
                let o = _mm256_set1_ps(ray.origin[axis]);
                let n = _mm256_mul_ps(_mm256_sub_ps(lo, o), inv_near);
                let f = _mm256_mul_ps(_mm256_sub_ps(hi, o), inv_far);
                // max(a, b) is `a > b ? a : b` and min(a, b) `a < b ? a : b`: a NaN `n` or
                // `f` leaves the interval unchanged, as in the portable loop.
                near = _mm256_max_ps(n, near);
                far = _mm256_min_ps(f, far);
            }
            let hit = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
            let mut out = [0.0f32; WIDTH];
            _mm256_storeu_ps(out.as_mut_ptr(), near);
            (out, hit)
        }
    }
}
