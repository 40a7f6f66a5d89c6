// The integrator's bind group (src/pipeline.rs, `binding`): the frame, the scene, the image,
// the ray counters, the tone map's levels and, in the temporal mode, the pixels' geometry
// records. Group 1: the samples this dispatch traces (src/sample_ranges.rs).

@group(0) @binding(0) var<uniform> frame: Frame;
// The planes, then the frame's spheres and quads.
@group(0) @binding(1) var<storage, read> shapes: array<Shape>;
@group(0) @binding(2) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(3) var<storage, read> materials: array<Material>;
@group(0) @binding(4) var<storage, read> lights: array<Light>;
// Linear RGBA radiance, row-major, top row first.
@group(0) @binding(5) var<storage, read_write> image: array<vec4<f32>>;
// counter_stride counters per workgroup: rays at depth 0..=R, shadow rays, shadow carries,
// chains stopped by the depth limit.
@group(0) @binding(6) var<storage, read_write> group_counts: array<u32>;
// The frame's totals per counter as 64-bit (low, high) pairs.
@group(0) @binding(7) var<storage, read_write> totals: array<vec2<u32>>;
// The tone-mapped image, one packed RGBA8 (R in the low byte) per pixel.
@group(0) @binding(8) var<storage, read_write> srgb8: array<u32>;
// Every mesh's triangle BVH (bottom levels), one after another (empty when there are none).
@group(0) @binding(9) var<storage, read> bvh_nodes: array<BvhNode>;
// In the temporal mode, two per pixel: the record's point (bits of a vec4<f32>), then its
// normal's bits and its tag (temporal_record.wgsl).
@group(0) @binding(10) var<storage, read_write> geometry: array<vec4<u32>>;
// The frame's top level over its spheres, quads and instances, and its leaves in leaf order.
@group(0) @binding(11) var<storage, read> top_nodes: array<BvhNode>;
@group(0) @binding(12) var<storage, read> top_leaves: array<TopLeaf>;
@group(0) @binding(13) var<storage, read> instances: array<Instance>;
// The temporal mode's surface ids of the frame's shapes, then of its instances.
@group(0) @binding(14) var<storage, read> surface_ids: array<u32>;
// The smallest radiance of each tone-map level 1..=255 (srgb.wgsl).
@group(0) @binding(15) var<storage, read> srgb8_levels: array<f32>;
// The samples of each pixel this dispatch of the integrator traces.
@group(1) @binding(0) var<uniform> sample_range: SampleRange;
