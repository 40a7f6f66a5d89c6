// The temporal resolve of docs/temporal.md, one thread per history pixel, written operation
// for operation as the CPU's (render-cpu/src/temporal/resolve.rs) so both round alike: find
// the frame's sample that lands in the pixel, reproject the history by that sample's point,
// keep the taps whose surface is still seen around the pixel, filter them, clamp to the
// frame's local colour range and blend (a still camera keeps the history as it is). Then
// `tonemap_history` packs the new history for display.

@group(0) @binding(0) var<uniform> params: TemporalParams;
// The frame as rendered (low_width x low_height): radiance, and two geometry words per pixel
// (temporal_record.wgsl).
@group(0) @binding(1) var<storage, read> frame_image: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> frame_geometry: array<vec4<u32>>;
// The history before this frame (width x height): radiance and age, and its geometry.
@group(0) @binding(3) var<storage, read> history_in: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> geometry_in: array<vec4<u32>>;
// The history after it.
@group(0) @binding(5) var<storage, read_write> history_out: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> geometry_out: array<vec4<u32>>;
// The new history tone-mapped, one packed RGBA8 per pixel.
@group(0) @binding(7) var<storage, read_write> history_srgb8: array<u32>;
// How each surface moved since the previous frame, by surface id (read while the world
// moves).
@group(0) @binding(8) var<storage, read> surface_moves: array<SurfaceMotion>;
// The smallest radiance of each tone-map level 1..=255 (srgb.wgsl).
@group(0) @binding(9) var<storage, read> srgb8_levels: array<f32>;

fn finite3(c: vec3<f32>) -> bool {
    let exponent = bitcast<vec3<u32>>(c) & vec3<u32>(0x7f800000u);
    return all(exponent != vec3<u32>(0x7f800000u));
}

// A geometry record (temporal_record.wgsl).
struct Record {
    q: vec4<f32>,
    n: vec3<f32>,
    tag: u32,
}

fn frame_record(i: u32) -> Record {
    let b = frame_geometry[2u * i + 1u];
    return Record(bitcast<vec4<f32>>(frame_geometry[2u * i]), bitcast<vec3<f32>>(b.xyz), b.w);
}

fn history_record(i: u32) -> Record {
    let b = geometry_in[2u * i + 1u];
    return Record(bitcast<vec4<f32>>(geometry_in[2u * i]), bitcast<vec3<f32>>(b.xyz), b.w);
}

// A record's point and normal as they were in the previous frame, and whether its surface
// existed then.
struct Before {
    q: vec4<f32>,
    n: vec3<f32>,
    existed: bool,
}

// How record g's surface moved: a surface seen directly in a world that moved follows its
// object; anything else is taken as still (render-cpu's resolve::move_of).
fn before_of(g: Record) -> Before {
    let id = g.tag & ID_MASK;
    let direct = g.q.w != 0.0 && (g.tag & MIRROR_FLAG) == 0u;
    if params.world_moved == 0u || !direct || id >= params.surface_count {
        return Before(g.q, g.n, true);
    }
    let m = surface_moves[id];
    if m.kind == SURFACE_NEW {
        return Before(g.q, g.n, false);
    }
    if m.kind != SURFACE_MOVED {
        return Before(g.q, g.n, true);
    }
    let q = g.q.xyz;
    let p = vec3<f32>(
        m.p_x.x * q.x + m.p_x.y * q.y + m.p_x.z * q.z + m.p_x.w,
        m.p_y.x * q.x + m.p_y.y * q.y + m.p_y.z * q.z + m.p_y.w,
        m.p_z.x * q.x + m.p_z.y * q.y + m.p_z.z * q.z + m.p_z.w,
    );
    let n = vec3<f32>(dot3(m.n_x, g.n), dot3(m.n_y, g.n), dot3(m.n_z, g.n));
    let inv = 1.0 / sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    return Before(vec4<f32>(p, g.q.w), n * inv, true);
}

// floor((x + anchor) · full / low).
fn landing(x: u32, anchor: f32, full: u32, low: u32) -> u32 {
    return u32(floor((f32(x) + anchor) * f32(full) / f32(low)));
}

// floor((x + 0.5) · low / full), at most low - 1.
fn covering(x: u32, full: u32, low: u32) -> u32 {
    return min(u32(floor((f32(x) + 0.5) * f32(low) / f32(full))), low - 1u);
}

// The tent weight of low column c's centre at the centre of full column x (splat_weight).
fn splat_weight(x: u32, c: u32, full: u32, low: u32) -> f32 {
    let k = f32(full) / f32(low);
    let d = abs((f32(x) + 0.5) - (f32(c) + 0.5) * k) / k;
    return max(1.0 - d, 0.0);
}

// The first of covering - 1, covering, covering + 1 whose landing is x, or -1.
fn landed_from(x: u32, anchor: f32, full: u32, low: u32) -> i32 {
    let c = covering(x, full, low);
    if c >= 1u && landing(c - 1u, anchor, full, low) == x {
        return i32(c) - 1;
    }
    if landing(c, anchor, full, low) == x {
        return i32(c);
    }
    if c + 1u < low && landing(c + 1u, anchor, full, low) == x {
        return i32(c) + 1;
    }
    return -1;
}

// The tent weight, along one axis, at the centre of full column x of the samples of low
// column s whose centroid lies `at` past its left edge (centre_weight).
fn centre_weight(x: u32, s: u32, at: f32, full: u32, low: u32) -> f32 {
    let position = (f32(s) + at) * f32(full) / f32(low);
    return max(1.0 - abs(position - (f32(x) + 0.5)), 0.0);
}

// The frame at the centre of history pixel (x, y), where frame pixel (sx, sy) lands in a
// moving frame: the finite colours of the 3x3 frame pixels around it (inside the frame, row
// by row) weighted by the tent of their samples' centroid (the anchor for one sample, the
// centre for more), over the sum of the weights; `own` where no weight is left.
fn frame_at_centre(x: u32, y: u32, sx: u32, sy: u32, own: vec3<f32>) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    var total = 0.0;
    let y_end = min(sy + 1u, params.low_height - 1u);
    let x_end = min(sx + 1u, params.low_width - 1u);
    for (var ny = max(sy, 1u) - 1u; ny <= y_end; ny++) {
        for (var nx = max(sx, 1u) - 1u; nx <= x_end; nx++) {
            let cc = frame_image[ny * params.low_width + nx].xyz;
            if !finite3(cc) {
                continue;
            }
            var at = vec2<f32>(0.5, 0.5);
            if samples_for_pixel(nx, ny, params.spp) < 2u {
                at = params.anchor;
            }
            let w = centre_weight(x, nx, at.x, params.width, params.low_width)
                * centre_weight(y, ny, at.y, params.height, params.low_height);
            sum += w * cc;
            total += w;
        }
    }
    if total > 0.0 {
        return vec3<f32>(sum.x / total, sum.y / total, sum.z / total);
    }
    return own;
}

// The frame's 3x3 pixels around the covering one (those inside the frame, row by row): the
// range of their finite colours and their indices.
var<private> near_pixels: array<u32, 9>;
var<private> near_count: u32;
var<private> near_lo: vec3<f32>;
var<private> near_hi: vec3<f32>;
var<private> near_has_range: bool;

fn gather_neighbourhood(cx: u32, cy: u32) {
    near_count = 0u;
    near_has_range = false;
    let y_end = min(cy + 1u, params.low_height - 1u);
    let x_end = min(cx + 1u, params.low_width - 1u);
    for (var ny = max(cy, 1u) - 1u; ny <= y_end; ny++) {
        for (var nx = max(cx, 1u) - 1u; nx <= x_end; nx++) {
            let i = ny * params.low_width + nx;
            near_pixels[near_count] = i;
            near_count += 1u;
            let c = frame_image[i].xyz;
            if !finite3(c) {
                continue;
            }
            if near_has_range {
                near_lo = min(near_lo, c);
                near_hi = max(near_hi, c);
            } else {
                near_lo = c;
                near_hi = c;
                near_has_range = true;
            }
        }
    }
}

// Whether the history's surface `old` is one the neighbourhood sees: the same surface id and,
// for a point, within the tolerance of its tangent plane (PLANE_TOLERANCE times its distance
// from the previous eye) and facing alike.
fn seen_nearby(old: Record) -> bool {
    for (var k = 0u; k < near_count; k++) {
        let g = frame_record(near_pixels[k]);
        if (g.tag & ID_MASK) != (old.tag & ID_MASK) {
            continue;
        }
        let b = before_of(g);
        if !b.existed {
            continue;
        }
        if g.q.w == 0.0 {
            return true;
        }
        let e = b.q.xyz - params.previous.eye;
        let d = sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
        let off = old.q.xyz - b.q.xyz;
        if abs(dot3(off, b.n)) <= PLANE_TOLERANCE * d && dot3(b.n, old.n) >= NORMAL_COS {
            return true;
        }
    }
    return false;
}

// The history's Catmull-Rom filter over the 4x4 pixels from (ix - 1, iy - 1) at fractions
// (fx, fy) past (ix, iy): rows first, then the column.
fn history_catmull_rom(ix: i32, iy: i32, fx: f32, fy: f32) -> vec3<f32> {
    let wx = catmull_rom(fx);
    let wy = catmull_rom(fy);
    var sum = vec3<f32>(0.0);
    for (var b = 0; b < 4; b++) {
        let row = (iy - 1 + b) * i32(params.width);
        var line = vec3<f32>(0.0);
        for (var a = 0; a < 4; a++) {
            let h = history_in[row + ix - 1 + a].xyz;
            line = line + wx[a] * h;
        }
        sum = sum + wy[b] * line;
    }
    return sum;
}

// A pixel's reprojected history: valid, its filtered colour and its age.
struct Kept {
    valid: bool,
    colour: vec3<f32>,
    age: f32,
}

fn history_at(x: u32, y: u32, g: Record) -> Kept {
    let none = Kept(false, vec3<f32>(0.0), 0.0);
    let b = before_of(g);
    if !b.existed {
        return none;
    }
    let size = vec2<u32>(params.width, params.height);
    let before = project(params.previous, b.q, size);
    let now = project(params.current, g.q, size);
    if before.z == 0.0 || now.z == 0.0 {
        return none;
    }
    let bx = f32(x) + (before.x - now.x);
    let by = f32(y) + (before.y - now.y);
    let width = i32(params.width);
    let height = i32(params.height);
    if !(bx >= -1.0 && bx < f32(params.width) && by >= -1.0 && by < f32(params.height)) {
        return none;
    }
    let fx0 = floor(bx);
    let fy0 = floor(by);
    let fx = bx - fx0;
    let fy = by - fy0;
    let ix = i32(fx0);
    let iy = i32(fy0);
    let bilinear = vec4<f32>(
        (1.0 - fx) * (1.0 - fy),
        fx * (1.0 - fy),
        (1.0 - fx) * fy,
        fx * fy,
    );
    var all_valid = true;
    var weight = 0.0;
    var colour = vec3<f32>(0.0);
    var age = 0.0;
    for (var t = 0; t < 4; t++) {
        let tx = ix + (t & 1);
        let ty = iy + (t >> 1u);
        if tx < 0 || ty < 0 || tx >= width || ty >= height {
            all_valid = false;
            continue;
        }
        let i = u32(ty) * params.width + u32(tx);
        if !seen_nearby(history_record(i)) {
            all_valid = false;
            continue;
        }
        let w = bilinear[t];
        let h = history_in[i];
        weight += w;
        colour = colour + w * h.xyz;
        age += w * h.w;
    }
    if weight <= 0.0 {
        return none;
    }
    let inside = ix >= 1 && iy >= 1 && ix + 2 < width && iy + 2 < height;
    var filtered = colour / weight;
    if all_valid && inside {
        filtered = history_catmull_rom(ix, iy, fx, fy);
    }
    if !finite3(filtered) {
        return none;
    }
    return Kept(true, filtered, age / weight);
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn resolve(@builtin(global_invocation_id) gid: vec3<u32>) {
    let x = gid.x;
    let y = gid.y;
    if x >= params.width || y >= params.height {
        return;
    }
    let cx = covering(x, params.width, params.low_width);
    let cy = covering(y, params.height, params.low_height);
    let lx = landed_from(x, params.anchor.x, params.width, params.low_width);
    let ly = landed_from(y, params.anchor.y, params.height, params.low_height);
    let landed = lx >= 0 && ly >= 0;
    var sx = cx;
    var sy = cy;
    if landed {
        sx = u32(lx);
        sy = u32(ly);
    }
    let source = sy * params.low_width + sx;
    let g = frame_record(source);
    var c = frame_image[source].xyz;
    let current_ok = finite3(c);
    // Where it landed in a moving frame, the frame is read at the pixel's centre.
    if landed && params.still == 0u && current_ok {
        c = frame_at_centre(x, y, sx, sy, c);
    }
    let n = f32(samples_for_pixel(sx, sy, params.spp));
    // The frame's weight here: 1 where it landed; below scale 1 in a moving frame, a pixel
    // of two or more samples (centroid at its centre) reaches the pixels it covers by
    // the tent of its distance.
    var weight = 0.0;
    if landed {
        weight = 1.0;
    } else if params.still == 0u && n >= 2.0 {
        weight = splat_weight(x, cx, params.width, params.low_width)
            * splat_weight(y, cy, params.height, params.low_height);
    }
    let fresh = weight > 0.0 && current_ok;
    let m = n * weight;

    let pixel = y * params.width + x;
    var kept = Kept(false, vec3<f32>(0.0), 0.0);
    if params.still != 0u {
        let h = history_in[pixel];
        kept = Kept(true, h.xyz, h.w);
    } else if params.has_history != 0u {
        gather_neighbourhood(cx, cy);
        kept = history_at(x, y, g);
        if kept.valid && near_has_range {
            kept.colour = min(max(kept.colour, near_lo), near_hi);
        }
    }
    let approx = (g.tag & APPROX_FLAG) != 0u;
    let mirrored = (g.tag & MIRROR_FLAG) != 0u;
    let eye_moved = params.eye_moved != 0u;
    let world_moved = params.world_moved != 0u;
    var cap = HISTORY_CAP;
    if params.still != 0u {
        cap = STILL_CAP * n;
    } else if (approx && (eye_moved || world_moved)) || (mirrored && world_moved) {
        cap = SPECULAR_CAP;
    }
    var out = vec4<f32>(0.0);
    if kept.valid && fresh {
        let a = min(kept.age, cap);
        let alpha = m / (a + m);
        out = vec4<f32>(kept.colour + (c - kept.colour) * alpha, a + m);
    } else if kept.valid {
        out = vec4<f32>(kept.colour, min(kept.age, cap));
    } else if fresh {
        out = vec4<f32>(c, m);
    } else if current_ok {
        out = vec4<f32>(c, 0.0);
    }
    history_out[pixel] = out;
    geometry_out[2u * pixel] = frame_geometry[2u * source];
    geometry_out[2u * pixel + 1u] = frame_geometry[2u * source + 1u];
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn tonemap_history(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.width || gid.y >= params.height {
        return;
    }
    let i = gid.y * params.width + gid.x;
    var c = history_out[i];
    // A frame that resampled the history is sharpened for display (sharpen.wgsl), as
    // strongly as the host says.
    if params.sharpen > 0.0 {
        var n: array<vec4<f32>, 9>;
        for (var k = 0u; k < 9u; k++) {
            n[k] = history_out[neighbour_index(gid.x, gid.y, k, params.width, params.height)];
        }
        c = sharpened(n, params.sharpen);
    }
    history_srgb8[i] = pack_srgb8(c.xyz);
}
