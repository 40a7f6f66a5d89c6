// The temporal mode's reprojection rules (steadyray_render::temporal), shared by the resolve
// (temporal.wgsl) and the warped refresh (warp.wgsl) so that both round as the CPU does: a
// dot product summed left to right, where a camera sees a point or a direction, and the
// history filter's Catmull-Rom weights.

// a · b summed left to right, as the CPU's dot3.
fn dot3(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Where camera frame `view` sees point q (q.w != 0) or direction q (q.w = 0), in pixels of an
// image of `size` (project4's arithmetic, one lane): x, y and z = 1, or z = 0 when q lies
// behind the camera or on its plane.
fn project(view: CameraView, q: vec4<f32>, size: vec2<u32>) -> vec3<f32> {
    var v = q.xyz;
    if q.w != 0.0 {
        v = q.xyz - view.eye;
    }
    let z = dot3(v, view.forward);
    if !(z > 0.0) {
        return vec3<f32>(0.0);
    }
    let sx = dot3(v, view.right) / z;
    let sy = dot3(v, view.true_up) / z;
    return vec3<f32>(
        (sx / view.half_width + 1.0) * 0.5 * f32(size.x),
        (1.0 - sy / view.half_height) * 0.5 * f32(size.y),
        1.0,
    );
}

// The Catmull-Rom weights of the four taps at offsets -1, 0, 1, 2 from a sample at fraction
// f past tap 0.
fn catmull_rom(f: f32) -> vec4<f32> {
    return vec4<f32>(
        f * (-0.5 + f * (1.0 - 0.5 * f)),
        1.0 + f * f * (-2.5 + 1.5 * f),
        f * (0.5 + f * (2.0 - 1.5 * f)),
        f * f * (-0.5 + 0.5 * f),
    );
}
