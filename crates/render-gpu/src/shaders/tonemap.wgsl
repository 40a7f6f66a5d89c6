// The tone map of a rendered frame into packed RGBA8 (srgb.wgsl).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn tonemap(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.width || gid.y >= frame.height {
        return;
    }
    let i = gid.y * frame.width + gid.x;
    srgb8[i] = pack_srgb8(image[i].xyz);
}
