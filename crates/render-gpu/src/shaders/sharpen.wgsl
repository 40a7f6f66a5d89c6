// The display's sharpening of a resampled history, steadyray_render::temporal::sharpened to
// the bit (docs/temporal.md, "Sharpening for display"): c + k * (c - the mean of its four
// edge neighbours), clamped to its 3x3 range, at the strength k the host chose
// (steadyray_render::temporal::sharpen_strength). Shared by the history's tone map
// (temporal.wgsl) and the warped refresh's (warp.wgsl), each gathering the nine taps from
// its own buffer.

// The CPU's Vec4::min and Vec4::max (SSE's minps and maxps): the second operand unless the
// first is strictly smaller (larger), so that NaN and signed zeros come out alike.
fn cpu_min(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return select(b, a, a < b);
}

fn cpu_max(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return select(b, a, a > b);
}

// The index of tap k (rows top to bottom, each left to right; tap 4 is the pixel) of the
// 3x3 neighbourhood of pixel (x, y) of a width x height image, the edges repeated.
fn neighbour_index(x: u32, y: u32, k: u32, width: u32, height: u32) -> u32 {
    let dx = k % 3u;
    let dy = k / 3u;
    let column = min(max(x + dx, 1u) - 1u, width - 1u);
    let row = min(max(y + dy, 1u) - 1u, height - 1u);
    return row * width + column;
}

// The colour of the pixel whose neighbourhood is n (n[4] the pixel), sharpened at strength k.
fn sharpened(n: array<vec4<f32>, 9>, k: f32) -> vec4<f32> {
    let c = n[4];
    let cross = ((n[1] + n[7]) + (n[3] + n[5])) * 0.25;
    let s = c + k * (c - cross);
    var lo = n[0];
    var hi = n[0];
    for (var k = 1; k < 9; k++) {
        lo = cpu_min(lo, n[k]);
        hi = cpu_max(hi, n[k]);
    }
    return cpu_min(cpu_max(s, lo), hi);
}
