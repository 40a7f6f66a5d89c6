// The ray caster of `steadyray raybench` (src/raycast.rs): each ray's closest triangle hit
// through the BVH (traversal.wgsl) and nothing else, written to `hits`.
//
// A workgroup of CAST_TILE × CAST_TILE threads works through several CAST_TILE² blocks of
// rays (grid-stride over the dispatch), so that the zeroing of the private traversal stack
// that WGSL requires happens once per thread, not once per ray. Primary rays are generated
// here from the camera, one per pixel centre: a block is a CAST_TILE × CAST_TILE pixel tile,
// so each subgroup's rays are neighbours and traverse the same nodes.

@group(0) @binding(0) var<uniform> params: CastParams;
@group(0) @binding(1) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(2) var<storage, read> bvh_nodes: array<BvhNode>;
// The rays of cast_rays (unused by cast_primary).
@group(0) @binding(3) var<storage, read> rays: array<CastRay>;
// One hit per ray: row-major pixels for cast_primary, the order of `rays` for cast_rays.
@group(0) @binding(4) var<storage, read_write> hits: array<CastHit>;

const CAST_GROUP_SIZE: u32 = CAST_TILE * CAST_TILE;

// The closest hit of the ray origin + t·dir, t in (T_MIN, ∞).
fn cast_ray(origin: vec3<f32>, dir: vec3<f32>) -> CastHit {
    if params.triangle_count == 0u {
        return CastHit(NO_HIT, CAST_MISS);
    }
    let hit = closest_triangle(make_ray(origin, dir), NO_HIT);
    if hit.t < NO_HIT {
        return CastHit(hit.t, hit.id);
    }
    return CastHit(NO_HIT, CAST_MISS);
}

// One ray through the centre of each pixel of the width × height image.
@compute @workgroup_size(CAST_TILE, CAST_TILE, 1)
fn cast_primary(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_id) lid: vec3<u32>,
) {
    for (var tile = wid.x; tile < params.tile_count; tile += groups.x) {
        let px = (tile % params.tiles_x) * CAST_TILE + lid.x;
        let py = (tile / params.tiles_x) * CAST_TILE + lid.y;
        if px < params.width && py < params.height {
            let dir = pixel_ray_dir(
                params.forward,
                params.right,
                params.true_up,
                vec2<f32>(params.half_width, params.half_height),
                vec2<u32>(params.width, params.height),
                px,
                py,
                vec2<f32>(0.5, 0.5),
            );
            hits[py * params.width + px] = cast_ray(params.eye, dir);
        }
    }
}

// The ray_count rays of `rays`.
@compute @workgroup_size(CAST_GROUP_SIZE, 1, 1)
fn cast_rays(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let blocks = (params.ray_count + CAST_GROUP_SIZE - 1u) / CAST_GROUP_SIZE;
    for (var block = wid.x; block < blocks; block += groups.x) {
        let i = block * CAST_GROUP_SIZE + lid;
        if i < params.ray_count {
            let ray = rays[i];
            hits[i] = cast_ray(ray.origin, ray.dir);
        }
    }
}
