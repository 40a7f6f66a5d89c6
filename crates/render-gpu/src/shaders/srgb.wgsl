// Mirrors steadyray_render::tonemap::linear_to_srgb8 to the bit, for display without a host
// round trip; shared by the renderer's tone map (tonemap.wgsl), the temporal history's
// (temporal.wgsl) and the warped refresh's (warp.wgsl). Each of their modules binds
// `srgb8_levels`, the smallest radiance of each level 1..=255 (steadyray_render::tonemap::srgb8_thresholds): the level is
// looked up there rather than computed with a pow() that may round unlike the host's.

fn linear_to_srgb8(value: f32) -> u32 {
    // NaN (exponent all ones, mantissa non-zero) maps to 0, tested on the bits so that no
    // compiler can fold it away.
    let is_nan = (bitcast<u32>(value) & 0x7fffffffu) > 0x7f800000u;
    let c = clamp(select(value, 0.0, is_nan), 0.0, 1.0);
    // The number of levels whose smallest radiance is at most c: the largest n <= 255 with
    // n = 0 or c >= srgb8_levels[n - 1], built bit by bit (the entries increase).
    var level = 0u;
    for (var step = 128u; step > 0u; step = step >> 1u) {
        let next = level + step;
        if next <= 255u && c >= srgb8_levels[next - 1u] {
            level = next;
        }
    }
    return level;
}

// A linear colour tone-mapped and packed as RGBA8 (R in the low byte, A = 255).
fn pack_srgb8(c: vec3<f32>) -> u32 {
    return linear_to_srgb8(c.x) | (linear_to_srgb8(c.y) << 8u)
        | (linear_to_srgb8(c.z) << 16u) | (255u << 24u);
}
