// GPU data layouts, mirrored field for field by the `#[repr(C)]` structs of `src/layout.rs`
// (the test `layout::tests::wgsl_layouts_match_rust` checks sizes, offsets and constants).
// Every module includes this file first; the bindings are declared per module
// (render_bindings.wgsl, raycast.wgsl).

const WORKGROUP_SIZE: u32 = 8u;
// The largest depth R (steadyray_render::MAX_DEPTH).
const MAX_DEPTH: u32 = 64u;
// Ray counters per workgroup: one per depth 0..=MAX_DEPTH, then shadow rays (low word, then
// the carries out of it), then the chains the depth limit stopped at a mirror or dielectric.
const COUNTER_SLOTS: u32 = 68u;
// Threads of the ray-count reduction.
const REDUCE_SIZE: u32 = 256u;
// Entries of the BVH traversal stack (steadyray_accel::GPU_STACK_SIZE).
const BVH_STACK_SIZE: u32 = 64u;
// A BVH child entry: an inner node's index, a leaf BVH_LEAF | count << 27 | first, or
// BVH_EMPTY for an unused lane (node 0 is the root, nobody's child).
const BVH_LEAF: u32 = 0x80000000u;
const BVH_EMPTY: u32 = 0u;

// The ray caster (raycast.wgsl): CAST_TILE × CAST_TILE threads per workgroup, one pixel
// each; CAST_MISS is the triangle id of a ray that hits nothing.
const CAST_TILE: u32 = 8u;
const CAST_MISS: u32 = 0xffffffffu;

// A top-level leaf's index has TOP_INSTANCE set for an instance; a hit on no mesh has
// instance NO_INSTANCE.
const TOP_INSTANCE: u32 = 0x80000000u;
const NO_INSTANCE: u32 = 0xffffffffu;

const SHAPE_SPHERE: u32 = 0u;
const SHAPE_QUAD: u32 = 1u;
const SHAPE_PLANE: u32 = 2u;

// The temporal mode (steadyray_render::temporal, docs/temporal.md).
const HISTORY_CAP: f32 = 4.0;
const STILL_CAP: f32 = 64.0;
const SPECULAR_CAP: f32 = 4.0;
const PLANE_TOLERANCE: f32 = 0.02;
const NORMAL_COS: f32 = 0.5;
const MISS_ID: u32 = 0x3fffffffu;
const ID_MASK: u32 = 0x3fffffffu;
const APPROX_FLAG: u32 = 0x80000000u;
const MIRROR_FLAG: u32 = 0x40000000u;
// SurfaceMotion.kind.
const SURFACE_STILL: u32 = 0u;
const SURFACE_MOVED: u32 = 1u;
const SURFACE_NEW: u32 = 2u;

const MAT_DIFFUSE: u32 = 0u;
const MAT_MIRROR: u32 = 1u;
const MAT_DIELECTRIC: u32 = 2u;
const MAT_EMISSIVE: u32 = 3u;

// Per-frame settings: camera frame, quality, scene-wide terms and dispatch geometry.
struct Frame {
    eye: vec3<f32>,
    half_width: f32,
    forward: vec3<f32>,
    half_height: f32,
    right: vec3<f32>,
    spp: f32,
    true_up: vec3<f32>,
    ambient: f32,
    background: vec3<f32>,
    max_depth: u32,
    width: u32,
    height: u32,
    // The first plane_count shapes are the infinite planes.
    plane_count: u32,
    // Leaves of the top level; 0: it is empty.
    leaf_count: u32,
    light_count: u32,
    groups_x: u32,
    counter_stride: u32,
    group_count: u32,
    // The temporal mode's jitter and first branch sample index (zero outside it), and 1 when
    // sample 0 records its geometry.
    jitter: vec2<f32>,
    sample_base: u32,
    temporal: u32,
    // Shapes in `shapes`: the planes, then the frame's spheres and quads (the surface id of
    // every mesh triangle in the temporal record).
    shape_count: u32,
    // The frame's index in a still view, else 0: its samples take new positions
    // (sampling.wgsl, still_sample).
    still_frame: u32,
    pad1: u32,
    pad2: u32,
}

// The samples one dispatch of the integrator traces per pixel (GpuSampleRange): those with
// index i, first <= i < end, of the pixel's n.
struct SampleRange {
    first: u32,
    end: u32,
    pad0: u32,
    pad1: u32,
}

// A camera frame (GpuCameraView; CameraFrame of docs/corridor.md) for the temporal history's
// size.
struct CameraView {
    eye: vec3<f32>,
    half_width: f32,
    forward: vec3<f32>,
    half_height: f32,
    right: vec3<f32>,
    pad0: u32,
    true_up: vec3<f32>,
    pad1: u32,
}

// The temporal resolve's settings (GpuTemporalParams): this frame's and the previous frame's
// camera frames, the history's size (width x height) and the rendered frame's, the landing
// anchor and the history's state.
struct TemporalParams {
    current: CameraView,
    previous: CameraView,
    width: u32,
    height: u32,
    low_width: u32,
    low_height: u32,
    anchor: vec2<f32>,
    has_history: u32,
    eye_moved: u32,
    still: u32,
    world_moved: u32,
    surface_count: u32,
    spp: f32,
    // How strongly the history is sharpened for display (sharpen.wgsl; 0: not at all).
    sharpen: f32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// The warped refresh's settings (GpuWarpParams): the camera frames of the history's frame
// and of the refresh, both for the history's size (width x height).
struct WarpParams {
    history_view: CameraView,
    refresh_view: CameraView,
    width: u32,
    height: u32,
    // How strongly the history's frame has it sharpened for display, and so the warp.
    sharpen: f32,
    pad1: u32,
}

// How a surface moved since the previous frame (GpuSurfaceMotion,
// steadyray_render::surface_motion): kind SURFACE_STILL, SURFACE_MOVED (the point rows p_*
// and the normal rows n_* map it back) or SURFACE_NEW.
struct SurfaceMotion {
    p_x: vec4<f32>,
    p_y: vec4<f32>,
    p_z: vec4<f32>,
    n_x: vec3<f32>,
    kind: u32,
    n_y: vec3<f32>,
    pad0: u32,
    n_z: vec3<f32>,
    pad1: u32,
}

// An analytic shape (see GpuShape in src/layout.rs). Sphere: p0 centre, s0 = r²,
// s1 = 1 / r. Quad: p0 corner, p1 unit normal, p2 and p3 the dual edge vectors,
// s0 = |edge_u|, s1 = |edge_v|. Plane: p0 point, p1 normal, p2 and p3 the checker axes.
struct Shape {
    p0: vec3<f32>,
    kind: u32,
    p1: vec3<f32>,
    material: u32,
    p2: vec3<f32>,
    s0: f32,
    p3: vec3<f32>,
    s1: f32,
}

// A mesh triangle in its bottom level's space with its normal normalize((v1 - v0) ×
// (v2 - v0)), in its mesh BVH's leaf order; id is its index in its mesh (the tie-break among
// hits at the same t).
struct Triangle {
    v0: vec3<f32>,
    pad0: u32,
    v1: vec3<f32>,
    id: u32,
    v2: vec3<f32>,
    pad1: u32,
    normal: vec3<f32>,
    pad2: u32,
}

// A node of the 4-wide triangle BVH (GpuBvhNode, steadyray_accel::GpuNode): per lane a
// child's box and the child entry. Node 0 is the root. 128 bytes, one cache line.
struct BvhNode {
    min_x: vec4<f32>,
    min_y: vec4<f32>,
    min_z: vec4<f32>,
    max_x: vec4<f32>,
    max_y: vec4<f32>,
    max_z: vec4<f32>,
    child: vec4<u32>,
    pad: vec4<u32>,
}

// A top-level leaf (GpuTopLeaf): a shape, or with TOP_INSTANCE an instance; key breaks ties.
struct TopLeaf {
    index: u32,
    key: u32,
}

// A copy of a mesh (GpuInstance): rows of the world-to-mesh map, rows of the cofactor matrix
// taking mesh normals to the world, where its nodes and triangles start, its material, and
// baked = 1 when the mesh is in world space already.
struct Instance {
    to_mesh_x: vec4<f32>,
    to_mesh_y: vec4<f32>,
    to_mesh_z: vec4<f32>,
    normal_x: vec3<f32>,
    node_base: u32,
    normal_y: vec3<f32>,
    tri_base: u32,
    normal_z: vec3<f32>,
    material: u32,
    baked: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// colour: albedo, reflectance, tint or radiance by kind; colour_b and checker_size > 0 for a
// diffuse checker; ior for dielectrics.
struct Material {
    colour: vec3<f32>,
    kind: u32,
    colour_b: vec3<f32>,
    checker_size: f32,
    ior: f32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

struct Light {
    position: vec3<f32>,
    pad0: f32,
    intensity: vec3<f32>,
    pad1: f32,
}

// The ray caster's settings (GpuCastParams): the camera frame of the primary rays
// (CameraFrame of docs/corridor.md), the image size in pixels and CAST_TILE tiles, and the
// number of rays of a cast_rays dispatch.
struct CastParams {
    eye: vec3<f32>,
    half_width: f32,
    forward: vec3<f32>,
    half_height: f32,
    right: vec3<f32>,
    width: u32,
    true_up: vec3<f32>,
    height: u32,
    tiles_x: u32,
    tile_count: u32,
    ray_count: u32,
    triangle_count: u32,
}

// A ray for cast_rays (GpuCastRay): origin + t·dir, t in (T_MIN, ∞).
struct CastRay {
    origin: vec3<f32>,
    pad0: u32,
    dir: vec3<f32>,
    pad1: u32,
}

// A ray's closest hit (GpuCastHit): its t and the triangle's input index, or CAST_MISS.
struct CastHit {
    t: f32,
    id: u32,
}
