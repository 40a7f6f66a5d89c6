//! Deterministic sampling rules shared bit for bit by the CPU and GPU backends
//! (mirrored in `render-gpu/src/shaders/`): integer hashing only, so both agree exactly.

use glam::Vec3A;

/// The PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", 2020).
pub fn pcg_hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// A uniform number in [0, 1) from the top 24 bits of a hash: exact in f32.
pub fn unit_from_hash(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The random number that chooses a dielectric branch (reflect or refract) for sample
/// `sample` of pixel (px, py) at depth `depth`.
pub fn branch_random(px: u32, py: u32, sample: u32, depth: u32) -> f32 {
    let mut h = pcg_hash(px);
    h = pcg_hash(h ^ py);
    h = pcg_hash(h ^ sample);
    h = pcg_hash(h ^ depth);
    unit_from_hash(h)
}

/// The R2 low-discrepancy sequence's generators (Roberts 2018): 1/φ₂ and 1/φ₂².
const R2_A: f32 = 0.754_877_7;
const R2_B: f32 = 0.569_840_3;

/// Sub-pixel position (u, v) in [0, 1)² of sample `i` of a pixel that takes `n` samples:
/// points of the R2 sequence paired with their mirror images about the pixel centre (and the
/// centre itself when n is odd), so that every sample count has its centroid at the centre.
/// The plain R2 sequence started at the centre put the two samples of S = 2 around (0.38,
/// 0.28): the whole image moved by a fifth of a pixel, which FLIP scored worse than S = 1.
pub fn sample_offset(i: u32, n: u32) -> (f32, f32) {
    let odd = n & 1;
    if i < odd || n <= 1 {
        return (0.5, 0.5);
    }
    let j = i - odd;
    let k = (j / 2 + 1) as f32;
    let (u, v) = (0.5 + k * R2_A, 0.5 + k * R2_B);
    let (u, v) = (u - u.floor(), v - v.floor());
    if j & 1 == 0 {
        (u, v)
    } else {
        let (u, v) = (1.0 - u, 1.0 - v);
        (u - u.floor(), v - v.floor())
    }
}

/// The 8×8 Bayer ordered-dither matrix.
const BAYER8: [[u8; 8]; 8] = [
    [0, 32, 8, 40, 2, 34, 10, 42],
    [48, 16, 56, 24, 50, 18, 58, 26],
    [12, 44, 4, 36, 14, 46, 6, 38],
    [60, 28, 52, 20, 62, 30, 54, 22],
    [3, 35, 11, 43, 1, 33, 9, 41],
    [51, 19, 59, 27, 49, 17, 57, 25],
    [15, 47, 7, 39, 13, 45, 5, 37],
    [63, 31, 55, 23, 61, 29, 53, 21],
];

/// Where pixel (px, py) stands in the 8×8 ordered-dither matrix, 0 to 63: at fractional S
/// the pixels of lower rank take their extra sample first ([`samples_for_pixel`]), and a
/// frame rendered within a time budget adds its units of samples to them first.
pub fn dither_rank(px: u32, py: u32) -> u32 {
    u32::from(BAYER8[(py & 7) as usize][(px & 7) as usize])
}

/// Eye rays for pixel (px, py) at fractional S: floor(S), plus one where the fractional part
/// exceeds the pixel's Bayer threshold, so the mean over any 8×8 block is S to within 1/64.
pub fn samples_for_pixel(px: u32, py: u32, spp: f32) -> u32 {
    let whole = spp.floor();
    let frac = spp - whole;
    let threshold = (dither_rank(px, py) as f32 + 0.5) / 64.0;
    whole as u32 + u32::from(frac > threshold)
}

/// A cosine-weighted direction about unit normal `n` from two uniform numbers in [0, 1)
/// (Malley's method, with the branchless orthonormal basis of Duff et al., JCGT 2017): the
/// diffuse bounce rays of `steadyray raybench` and of the BVH benchmarks. Not used by the
/// Whitted integrator, which has no diffuse bounces.
pub fn cosine_direction(n: Vec3A, u1: f32, u2: f32) -> Vec3A {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3A::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let s = Vec3A::new(b, sign + n.y * n.y * a, -n.y);
    let r = u1.sqrt();
    let phi = std::f32::consts::TAU * u2;
    (t * (r * phi.cos()) + s * (r * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt()).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_spp_is_exact_everywhere() {
        for s in 1..5u32 {
            for y in 0..8 {
                for x in 0..8 {
                    assert_eq!(samples_for_pixel(x, y, s as f32), s);
                }
            }
        }
    }

    #[test]
    fn fractional_spp_averages_to_s_over_a_block() {
        for k in 0..=64 {
            let s = 2.0 + k as f32 / 64.0;
            let total: u32 = (0..8)
                .flat_map(|y| (0..8).map(move |x| samples_for_pixel(x, y, s)))
                .sum();
            let mean = total as f32 / 64.0;
            assert!((mean - s).abs() <= 1.0 / 64.0 + 1e-6, "S={s} mean={mean}");
        }
    }

    #[test]
    fn offsets_stay_inside_the_pixel_and_are_distinct() {
        let n = 64;
        let pts: Vec<_> = (0..n).map(|i| sample_offset(i, n)).collect();
        for &(u, v) in &pts {
            assert!((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v));
        }
        for i in 0..pts.len() {
            for j in i + 1..pts.len() {
                assert_ne!(pts[i], pts[j]);
            }
        }
        assert_eq!(sample_offset(0, 1), (0.5, 0.5));
    }

    #[test]
    fn every_sample_count_is_centred_on_the_pixel() {
        for n in 1..=64u32 {
            let (su, sv) = (0..n).fold((0.0f64, 0.0f64), |(a, b), i| {
                let (u, v) = sample_offset(i, n);
                (a + f64::from(u), b + f64::from(v))
            });
            let (cu, cv) = (su / f64::from(n), sv / f64::from(n));
            assert!(
                (cu - 0.5).abs() < 1e-6 && (cv - 0.5).abs() < 1e-6,
                "n={n}: ({cu}, {cv})"
            );
        }
    }

    #[test]
    fn branch_random_is_uniform_enough() {
        let n = 100_000;
        let mean: f64 = (0..n)
            .map(|i| branch_random(i % 317, i / 317, i % 7, 3) as f64)
            .sum::<f64>()
            / n as f64;
        assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
    }
}
