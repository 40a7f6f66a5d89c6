//! The GPU's tone map, to the bit the host's (`steadyray_render::tonemap::linear_to_srgb8`):
//! a GPU's `pow` may round unlike the host's `powf` (lavapipe's did, by one ulp), which
//! moves a radiance that lies within a rounding of a level's edge to the next level. So the
//! shaders (`shaders/srgb.wgsl`) do not evaluate the transfer function: they look the level
//! up among the smallest radiances of levels 1 to 255, found here from the host's own
//! function, and every picture the GPU shows is the host's tone map of its image.

use steadyray_render::tonemap::linear_to_srgb8;

/// The levels above 0 of the 8-bit tone map: entries of the table.
pub(crate) const LEVELS: usize = 255;

/// The smallest radiance of each level 1..=255 (entry k for level k + 1), by bisection over
/// the bit patterns of [0, 1], which order as the values do: the tone map does not decrease
/// with radiance, so a radiance's level is the number of entries at or below it.
pub(crate) fn level_thresholds() -> [f32; LEVELS] {
    std::array::from_fn(|k| {
        let level = k as u8 + 1;
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
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each entry is its level's edge: it takes the level, and the radiance just below it
    /// the level before.
    #[test]
    fn thresholds_are_the_levels_edges() {
        let table = level_thresholds();
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
        assert!(table[LEVELS - 1] <= 1.0);
    }
}
