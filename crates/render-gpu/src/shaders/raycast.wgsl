// The ray caster of `steadyray raybench` (src/raycast.rs): each ray's closest triangle hit
// through the BVH (traversal.wgsl) and nothing else, written to `hits`.
//
// The workgroups are persistent: each of CAST_TILE × CAST_TILE threads takes the next block
// of CAST_TILE² rays from a shared counter until none is left. A block's cost varies widely
// (empty sky against the mesh's silhouette), and taking blocks as they finish keeps every
// workgroup busy to the end of the dispatch; launching only as many workgroups as the GPU
// holds means the zeroing of the private traversal stack that WGSL requires is paid once
// per thread, not once per ray. Primary rays are generated here from the camera, one per
// pixel centre: a block is a CAST_TILE × CAST_TILE pixel tile, so each subgroup's rays are
// neighbours and traverse the same nodes.

@group(0) @binding(0) var<uniform> params: CastParams;
@group(0) @binding(1) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(2) var<storage, read> bvh_nodes: array<BvhNode>;
// The rays of cast_rays (unused by cast_primary).
@group(0) @binding(3) var<storage, read> rays: array<CastRay>;
// One hit per ray: row-major pixels for cast_primary, the order of `rays` for cast_rays.
@group(0) @binding(4) var<storage, read_write> hits: array<CastHit>;
// The next block to take; zero at the start of each dispatch.
@group(0) @binding(5) var<storage, read_write> next_block: atomic<u32>;

// The block the workgroup works on, as taken by its first thread.
var<workgroup> taken_block: u32;

const CAST_GROUP_SIZE: u32 = CAST_TILE * CAST_TILE;

// The workgroup's next block (the same for all its threads); blocks past the last mean
// there is no more work.
fn take_block(lid: u32) -> u32 {
    // Every thread has read the previous block before the first thread takes the next.
    workgroupBarrier();
    if lid == 0u {
        taken_block = atomicAdd(&next_block, 1u);
    }
    return workgroupUniformLoad(&taken_block);
}

// The closest hit of the ray origin + t·dir, t in (T_MIN, ∞).
fn cast_ray(origin: vec3<f32>, dir: vec3<f32>) -> CastHit {
    if params.triangle_count == 0u {
        return CastHit(NO_HIT, CAST_MISS);
    }
    let hit = closest_triangle(make_ray(origin, dir), NO_HIT, 0u, 0u);
    if hit.t < NO_HIT {
        return CastHit(hit.t, hit.id);
    }
    return CastHit(NO_HIT, CAST_MISS);
}

// One ray through the centre of each pixel of the width × height image.
@compute @workgroup_size(CAST_TILE, CAST_TILE, 1)
fn cast_primary(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    loop {
        let tile = take_block(index);
        if tile >= params.tile_count {
            break;
        }
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
fn cast_rays(@builtin(local_invocation_index) lid: u32) {
    let blocks = (params.ray_count + CAST_GROUP_SIZE - 1u) / CAST_GROUP_SIZE;
    loop {
        let block = take_block(lid);
        if block >= blocks {
            break;
        }
        let i = block * CAST_GROUP_SIZE + lid;
        if i < params.ray_count {
            let ray = rays[i];
            hits[i] = cast_ray(ray.origin, ray.dir);
        }
    }
}
