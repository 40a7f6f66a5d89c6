// Eye-ray directions of the pinhole camera, shared by the integrator and the ray caster:
// CameraFrame::ray_dir of docs/corridor.md, operation for operation, so that both backends
// round alike (exactly, where the driver does not fuse multiply-adds).

// glam's Vec3::normalize: v * (1 / sqrt(dot(v, v))), written out so both backends round alike.
fn unit(v: vec3<f32>) -> vec3<f32> {
    return v * (1.0 / sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
}

// The unit direction through pixel (px, py) of a size.x × size.y image at sub-pixel offset
// uv, py = 0 being the top row, for the camera frame (forward, right, true_up) with
// half_size = (half_width, half_height).
fn pixel_ray_dir(
    forward: vec3<f32>,
    right: vec3<f32>,
    true_up: vec3<f32>,
    half_size: vec2<f32>,
    size: vec2<u32>,
    px: u32,
    py: u32,
    uv: vec2<f32>,
) -> vec3<f32> {
    let sx = (2.0 * (f32(px) + uv.x) / f32(size.x) - 1.0) * half_size.x;
    let sy = (1.0 - 2.0 * (f32(py) + uv.y) / f32(size.y)) * half_size.y;
    return unit(forward + sx * right + sy * true_up);
}
