// The warped refresh of docs/temporal.md ("Warped refreshes"), written operation for operation
// as the CPU's (render-cpu/src/temporal/warp.rs) so that both round alike: the last history
// shown again from a camera that moved since its frame. `warp_motion` says, per history
// pixel, where its record's surface moves on screen between the history's camera and the
// new one; `warp_colour` then looks, from each screen pixel, for the history pixel that
// lands on it (WARP_STEPS fixed-point steps on that motion field), takes the history's
// Catmull-Rom filter there, clamped to the four nearest pixels' range; `warp_display` then
// shows it as the history is shown (sharpened when its frame resampled it, and tone-mapped,
// srgb.wgsl). The history is only read.

@group(0) @binding(0) var<uniform> warp: WarpParams;
// The last history (width x height): radiance and age, and its geometry records
// (temporal_record.wgsl, two words per pixel).
@group(0) @binding(1) var<storage, read> history: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> history_geometry: array<vec4<u32>>;
// Per history pixel, its motion in pixels, or NO_MOTION.
@group(0) @binding(3) var<storage, read_write> motion: array<vec2<f32>>;
// The warped picture, one packed RGBA8 per pixel.
@group(0) @binding(4) var<storage, read_write> warp_srgb8: array<u32>;
// The smallest radiance of each tone-map level 1..=255 (srgb.wgsl).
@group(0) @binding(5) var<storage, read> srgb8_levels: array<f32>;
// The warped picture in linear radiance, before it is shown as the history is.
@group(0) @binding(6) var<storage, read_write> warp_linear: array<vec4<f32>>;

// Fixed-point steps from a screen pixel to the history pixel that lands on it.
const WARP_STEPS: u32 = 3u;
// The motion of a record whose point is behind one of the cameras (a quiet NaN, as the
// CPU's NO_MOTION): no step follows it.
const NO_MOTION: u32 = 0x7fc00000u;

// Whether v is NaN, tested on the bits so that no compiler can fold it away.
fn is_nan(v: f32) -> bool {
    return (bitcast<u32>(v) & 0x7fffffffu) > 0x7f800000u;
}

// steadyray_render::temporal::floor for every input: WGSL's floor where |t| <= 2^31; past
// that the CPU's truncation saturates at ±2^31, and NaN truncates to 0.
fn cpu_floor(t: f32) -> f32 {
    if is_nan(t) {
        return 0.0;
    }
    return clamp(floor(t), -2147483648.0, 2147483648.0);
}

// The pixel column (or row) of an image `size` wide that holds t: floor(t) clamped to it.
fn pixel_of(t: f32, size: u32) -> u32 {
    return u32(clamp(cpu_floor(t), 0.0, f32(size - 1u)));
}

// Tap k (offset k - 1) of the filter from whole number f (a cpu_floor), clamped to
// [0, last]. f is clamped first to where an offset can still matter, so that it converts.
fn tap(f: f32, k: i32, last: u32) -> u32 {
    let i = i32(clamp(f, -2.0, f32(last) + 2.0));
    return u32(clamp(i + k - 1, 0, i32(last)));
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn warp_motion(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= warp.width || gid.y >= warp.height {
        return;
    }
    let i = gid.y * warp.width + gid.x;
    let q = bitcast<vec4<f32>>(history_geometry[2u * i]);
    let size = vec2<u32>(warp.width, warp.height);
    let a = project(warp.history_view, q, size);
    let b = project(warp.refresh_view, q, size);
    var m = vec2<f32>(bitcast<f32>(NO_MOTION));
    if a.z != 0.0 && b.z != 0.0 {
        m = vec2<f32>(b.x - a.x, b.y - a.y);
    }
    motion[i] = m;
}

// The history's Catmull-Rom filter at `at` (pixel centres at i + 0.5, taps past the edges
// clamped to them), clamped to the range of the four pixels around `at`.
fn filtered_at(at: vec2<f32>) -> vec3<f32> {
    let u = at.x - 0.5;
    let v = at.y - 0.5;
    let fu = cpu_floor(u);
    let fv = cpu_floor(v);
    let wx = catmull_rom(u - fu);
    let wy = catmull_rom(v - fv);
    var columns: array<u32, 4>;
    var rows: array<u32, 4>;
    for (var k = 0; k < 4; k++) {
        columns[k] = tap(fu, k, warp.width - 1u);
        rows[k] = tap(fv, k, warp.height - 1u);
    }
    var sum = vec4<f32>(0.0);
    for (var b = 0; b < 4; b++) {
        let row = rows[b] * warp.width;
        var line = vec4<f32>(0.0);
        for (var a = 0; a < 4; a++) {
            line = line + wx[a] * history[row + columns[a]];
        }
        sum = sum + wy[b] * line;
    }
    let n0 = history[rows[1] * warp.width + columns[1]];
    let n1 = history[rows[1] * warp.width + columns[2]];
    let n2 = history[rows[2] * warp.width + columns[1]];
    let n3 = history[rows[2] * warp.width + columns[2]];
    let lo = cpu_min(cpu_min(cpu_min(n0, n1), n2), n3);
    let hi = cpu_max(cpu_max(cpu_max(n0, n1), n2), n3);
    return cpu_min(cpu_max(sum, lo), hi).xyz;
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn warp_colour(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= warp.width || gid.y >= warp.height {
        return;
    }
    let centre = vec2<f32>(f32(gid.x) + 0.5, f32(gid.y) + 0.5);
    var at = centre;
    for (var s = 0u; s < WARP_STEPS; s++) {
        let px = pixel_of(at.x, warp.width);
        let py = pixel_of(at.y, warp.height);
        let m = motion[py * warp.width + px];
        if is_nan(m.x) {
            break;
        }
        at = centre - m;
    }
    warp_linear[gid.y * warp.width + gid.x] = vec4<f32>(filtered_at(at), 0.0);
}

// The warped picture shown as the history is: sharpened (sharpen.wgsl) when the history's
// frame resampled it, then tone-mapped.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn warp_display(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= warp.width || gid.y >= warp.height {
        return;
    }
    let i = gid.y * warp.width + gid.x;
    var c = warp_linear[i];
    if warp.sharpen > 0.0 {
        var n: array<vec4<f32>, 9>;
        for (var k = 0u; k < 9u; k++) {
            n[k] = warp_linear[neighbour_index(gid.x, gid.y, k, warp.width, warp.height)];
        }
        c = sharpened(n, warp.sharpen);
    }
    warp_srgb8[i] = pack_srgb8(c.xyz);
}
