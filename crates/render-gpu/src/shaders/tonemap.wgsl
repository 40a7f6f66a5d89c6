// Mirrors steadyray_render::tonemap::linear_to_srgb8, for display without a host round trip.

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

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn tonemap(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.width || gid.y >= frame.height {
        return;
    }
    let i = gid.y * frame.width + gid.x;
    let c = image[i];
    srgb8[i] = linear_to_srgb8(c.x) | (linear_to_srgb8(c.y) << 8u)
        | (linear_to_srgb8(c.z) << 16u) | (255u << 24u);
}
