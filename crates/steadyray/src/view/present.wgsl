// The present pass: draws a frame's packed RGBA8 sRGB image (a storage buffer, one u32 per
// pixel, R in the low byte) over the whole target with nearest-pixel upscaling. The target is
// a non-sRGB (gamma-space) format, so the bytes land unchanged.

struct Present {
    // Size of the image in the buffer, pixels.
    image_size: vec2<u32>,
    // Size of the target, pixels.
    target_size: vec2<u32>,
}

@group(0) @binding(0) var<uniform> present: Present;
@group(0) @binding(1) var<storage, read> image: array<u32>;

// One triangle covering the target.
@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let scale = vec2<f32>(present.image_size) / vec2<f32>(present.target_size);
    let pixel = min(vec2<u32>(position.xy * scale), present.image_size - vec2<u32>(1u));
    return unpack4x8unorm(image[pixel.y * present.image_size.x + pixel.x]);
}
