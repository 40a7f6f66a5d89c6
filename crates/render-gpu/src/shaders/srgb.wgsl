// Mirrors steadyray_render::tonemap::linear_to_srgb8, for display without a host round trip;
// shared by the renderer's tone map (tonemap.wgsl) and the temporal history's
// (temporal.wgsl).

fn linear_to_srgb8(value: f32) -> u32 {
    // NaN (exponent all ones, mantissa non-zero) maps to 0, tested on the bits so that no
    // compiler can fold it away.
    let is_nan = (bitcast<u32>(value) & 0x7fffffffu) > 0x7f800000u;
    let c = clamp(select(value, 0.0, is_nan), 0.0, 1.0);
    var s: f32;
    if c <= 0.0031308 {
        s = 12.92 * c;
    } else {
        s = 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    }
    return u32(clamp(floor(s * 255.0 + 0.5), 0.0, 255.0));
}

// A linear colour tone-mapped and packed as RGBA8 (R in the low byte, A = 255).
fn pack_srgb8(c: vec3<f32>) -> u32 {
    return linear_to_srgb8(c.x) | (linear_to_srgb8(c.y) << 8u)
        | (linear_to_srgb8(c.z) << 16u) | (255u << 24u);
}
