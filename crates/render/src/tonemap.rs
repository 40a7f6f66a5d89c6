//! The tone map from linear radiance to 8-bit sRGB, identical on every backend
//! (mirrored in `render-gpu/src/shaders/`).

/// Clamps linear radiance to [0, 1], applies the sRGB transfer function and rounds to 8 bits.
/// NaN maps to 0.
pub fn linear_to_srgb8(c: f32) -> u8 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5).floor().clamp(0.0, 255.0) as u8
}

/// [`linear_to_srgb8`], fast and to the bit: the tone map does not decrease with radiance, so
/// it is fixed by the smallest radiance of each level. A table over 4096 buckets of [0, 1]
/// gives a bucket's first level; the one threshold that may lie inside a bucket settles the
/// rest. About ten times faster than the transfer function's `powf`, which matters where every
/// pixel of every frame is converted on one thread (the CPU backend's way to a window).
#[inline]
pub fn linear_to_srgb8_fast(c: f32) -> u8 {
    let table = Srgb8Table::get();
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    let level = table.bucket_level[(c * BUCKETS as f32) as usize];
    // Levels lie more than a bucket apart, so at most one edge falls inside a bucket.
    level + u8::from(level < 255 && c >= table.threshold[usize::from(level)])
}

/// The smallest radiance of each level 1..=255 of [`linear_to_srgb8`] (entry k for level
/// k + 1): the tone map does not decrease with radiance, so a radiance's level is the number
/// of entries at or below it. The fast tone map and the GPU's (which looks levels up here
/// rather than trust a device's `pow` to round as the host's does) read this table.
pub fn srgb8_thresholds() -> &'static [f32; 255] {
    &Srgb8Table::get().threshold
}

/// Buckets of the fast tone map's table.
const BUCKETS: usize = 4096;

/// The fast tone map's tables.
struct Srgb8Table {
    /// `threshold[k]`: the smallest radiance that maps to level k + 1.
    threshold: [f32; 255],
    /// The level of each bucket's lower edge (one more entry for c = 1).
    bucket_level: [u8; BUCKETS + 1],
}

impl Srgb8Table {
    #[inline]
    fn get() -> &'static Self {
        static TABLE: std::sync::OnceLock<Srgb8Table> = std::sync::OnceLock::new();
        TABLE.get_or_init(|| {
            // Bisection over the bit patterns of [0, 1], which order as the values do.
            let smallest_at_least = |level: u8| -> f32 {
                let (mut lo, mut hi) = (0u32, 1f32.to_bits());
                while lo < hi {
                    let mid = lo + (hi - lo) / 2;
                    if linear_to_srgb8(f32::from_bits(mid)) >= level {
                        hi = mid;
                    } else {
                        lo = mid + 1;
                    }
                }
                f32::from_bits(lo)
            };
            let threshold = std::array::from_fn(|k| smallest_at_least(k as u8 + 1));
            let bucket_level = std::array::from_fn(|i| linear_to_srgb8(i as f32 / BUCKETS as f32));
            Srgb8Table {
                threshold,
                bucket_level,
            }
        })
    }
}

/// The inverse of the sRGB transfer function (8-bit to linear), for comparing images.
pub fn srgb8_to_linear(v: u8) -> f32 {
    let s = v as f32 / 255.0;
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each entry is its level's edge: it takes the level, and the radiance just below it
    /// the level before.
    #[test]
    fn thresholds_are_the_levels_edges() {
        let table = srgb8_thresholds();
        for (k, &t) in table.iter().enumerate() {
            let level = k as u8 + 1;
            assert_eq!(linear_to_srgb8(t), level, "entry {k}: {t:e}");
            let below = f32::from_bits(t.to_bits() - 1);
            assert_eq!(
                linear_to_srgb8(below),
                level - 1,
                "below entry {k}: {below:e}"
            );
        }
        assert!(table.is_sorted());
        assert!(table[254] <= 1.0);
    }

    #[test]
    fn round_trips_every_level() {
        for v in 0..=255u8 {
            assert_eq!(linear_to_srgb8(srgb8_to_linear(v)), v);
        }
    }

    /// No bucket holds two levels' edges: the fast tone map steps at most once past a
    /// bucket's first level.
    #[test]
    fn a_bucket_holds_at_most_one_edge() {
        let bucket = |t: f32| (t * BUCKETS as f32) as usize;
        for pair in Srgb8Table::get().threshold.windows(2) {
            assert!(bucket(pair[0]) < bucket(pair[1]), "{pair:?}");
        }
    }

    /// The fast tone map equals the exact one: on every level's threshold and the floats
    /// next to it, on one float in 61 of [0, 1], and outside it.
    #[test]
    fn the_fast_tone_map_is_exact() {
        let table = Srgb8Table::get();
        let check = |c: f32| assert_eq!(linear_to_srgb8_fast(c), linear_to_srgb8(c), "{c:e}");
        for &t in &table.threshold {
            for d in -3i32..=3 {
                check(f32::from_bits(t.to_bits().saturating_add_signed(d)));
            }
        }
        for bits in (0..=1f32.to_bits()).step_by(61) {
            check(f32::from_bits(bits));
        }
        for c in [
            -1.0,
            -0.0,
            1.0,
            1.5,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ] {
            check(c);
        }
    }

    #[test]
    fn clamps_and_rejects_nan() {
        assert_eq!(linear_to_srgb8(-1.0), 0);
        assert_eq!(linear_to_srgb8(7.0), 255);
        assert_eq!(linear_to_srgb8(f32::NAN), 0);
        assert_eq!(linear_to_srgb8(0.5), 188);
    }
}
