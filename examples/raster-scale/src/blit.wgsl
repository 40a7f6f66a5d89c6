// The upscale: the heavy pass's region of the offscreen texture, stretched bilinearly over
// the whole window.

struct Blit {
    // The drawn region's share of the offscreen texture (the render scale, per axis).
    region: vec2<f32>,
    // The farthest texture coordinate a bilinear read may centre on without reaching texels
    // outside the drawn region (region less half a texel).
    limit: vec2<f32>,
}

@group(0) @binding(0) var<uniform> blit: Blit;
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var linear: sampler;

struct Varyings {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> Varyings {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: Varyings;
    out.position = vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
    out.uv = vec2<f32>(corner.x, 1.0 - corner.y);
    return out;
}

@fragment
fn fs_main(in: Varyings) -> @location(0) vec4<f32> {
    return textureSample(source, linear, min(in.uv * blit.region, blit.limit));
}
