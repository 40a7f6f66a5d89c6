// The heavy pass: a procedural picture whose cost per pixel is `iterations` steps of an
// orbit-trap fractal, so the pass costs pixels x iterations. It draws into the top-left
// `scale` part of the offscreen target (the viewport), which the blit pass stretches over
// the window.

struct Heavy {
    // Steps per pixel: the workload's knob (the load schedule times the calibrated base).
    iterations: u32,
    // Seconds since the start, to keep the picture moving.
    time_s: f32,
    // Size of the drawn region, pixels.
    size: vec2<f32>,
}

@group(0) @binding(0) var<uniform> heavy: Heavy;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    // The same picture at every scale: coordinates relative to the drawn region.
    let uv = position.xy / heavy.size;
    let c = vec2<f32>(-0.745 + 0.02 * sin(0.3 * heavy.time_s), 0.11) + (uv - 0.5) * 0.06;
    var z = vec2<f32>(0.0);
    var trap = 1e9;
    for (var i = 0u; i < heavy.iterations; i++) {
        z = vec2<f32>(z.x * z.x - z.y * z.y, 2.0 * z.x * z.y) + c;
        // Keep the orbit bounded so every pixel does every step (the cost is exact).
        if dot(z, z) > 4.0 {
            z = z * 0.25;
        }
        trap = min(trap, abs(z.x * z.y));
    }
    let shade = clamp(-0.15 * log(trap + 1e-6), 0.0, 1.0);
    return vec4<f32>(shade, shade * shade, 0.3 + 0.7 * shade * (1.0 - shade), 1.0);
}
