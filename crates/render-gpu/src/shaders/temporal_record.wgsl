// The temporal mode's geometry record of a pixel's sample 0 (docs/temporal.md), as
// render-cpu/src/temporal/geometry.rs records it: the path's run of mirror reflections is
// followed, and its first other event (a hit that is not a mirror reflection, or a miss)
// ends the record, with the point and normal of the mirror image.

var<private> record_on: bool;
var<private> record_done: bool;
var<private> record_eye: vec3<f32>;
var<private> record_dir: vec3<f32>;
// Distance travelled through the mirrors so far.
var<private> record_length: f32;
var<private> record_approx: bool;
var<private> record_mirrored: bool;
// Rows of the product of the mirrors' reflections so far.
var<private> record_row0: vec3<f32>;
var<private> record_row1: vec3<f32>;
var<private> record_row2: vec3<f32>;
var<private> record_q: vec4<f32>;
var<private> record_n: vec3<f32>;
var<private> record_tag: u32;

// a · b summed left to right, as the CPU's dot3.
fn dot3(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Starts recording the path of the eye ray from `eye` along `dir` when `on`.
fn record_begin(on: bool, eye: vec3<f32>, dir: vec3<f32>) {
    record_on = on;
    if on {
        record_done = false;
        record_eye = eye;
        record_dir = dir;
        record_length = 0.0;
        record_approx = false;
        record_mirrored = false;
        record_row0 = vec3<f32>(1.0, 0.0, 0.0);
        record_row1 = vec3<f32>(0.0, 1.0, 0.0);
        record_row2 = vec3<f32>(0.0, 0.0, 1.0);
    }
}

// v - 2·(v·m)·m.
fn reflect_about(v: vec3<f32>, m: vec3<f32>) -> vec3<f32> {
    let k = 2.0 * dot3(v, m);
    return v - k * m;
}

// The surface id of the object (or copy) of `hit`, the same in every frame.
fn surface_id(hit: Hit) -> u32 {
    return surface_ids[select(frame.shape_count + hit.inst, hit.prim, hit.inst == NO_INSTANCE)];
}

fn tag_of(id: u32) -> u32 {
    return id | select(0u, APPROX_FLAG, record_approx) | select(0u, MIRROR_FLAG, record_mirrored);
}

// A ray of the path made `hit` with facing normal n; the path goes on by a mirror
// reflection (`reflects`) or through a dielectric.
fn record_hit(hit: Hit, n: vec3<f32>, reflects: bool, dielectric: bool) {
    if !record_on || record_done {
        return;
    }
    record_length += hit.t;
    if reflects {
        record_mirrored = true;
        let flat = hit.inst == NO_INSTANCE && shapes[hit.prim].kind != SHAPE_SPHERE;
        record_approx = record_approx || !flat;
        record_row0 = reflect_about(record_row0, n);
        record_row1 = reflect_about(record_row1, n);
        record_row2 = reflect_about(record_row2, n);
        return;
    }
    record_approx = record_approx || dielectric;
    record_q = vec4<f32>(record_eye + record_dir * record_length, 1.0);
    record_n = vec3<f32>(dot3(record_row0, n), dot3(record_row1, n), dot3(record_row2, n));
    record_tag = tag_of(surface_id(hit));
    record_done = true;
}

// A ray of the path left the scene.
fn record_miss() {
    if !record_on || record_done {
        return;
    }
    record_q = vec4<f32>(record_dir, 0.0);
    record_n = vec3<f32>(0.0);
    record_tag = tag_of(MISS_ID);
    record_done = true;
}

// Writes the record of pixel `index`.
fn record_store(index: u32) {
    geometry[2u * index] = bitcast<vec4<u32>>(record_q);
    geometry[2u * index + 1u] = vec4<u32>(bitcast<vec3<u32>>(record_n), record_tag);
}
