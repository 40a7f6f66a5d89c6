//! The GPU data layouts in one place: every struct the shaders read, `#[repr(C)]` and
//! [`bytemuck::Pod`], mirrored field for field by the WGSL structs of `shaders/layout.wgsl`.
//! The test `wgsl_layouts_match_rust` parses the WGSL with naga and compares each struct's
//! size, member names and offsets, and the shared constants, with the Rust side.

use bytemuck::{Pod, Zeroable};
use steadyray_render::MAX_DEPTH;
use steadyray_render::surface_motion::SurfaceMove;
use steadyray_scene::camera::CameraFrame;

/// A node of the triangle BVH (WGSL `BvhNode`): the 4-wide GPU layout of
/// `steadyray-accel`, uploaded as built.
pub use steadyray_accel::GpuNode as GpuBvhNode;

/// Entries of the WGSL BVH traversal stack: the most a tree the build accepts can push.
pub const BVH_STACK_SIZE: u32 = steadyray_accel::GPU_STACK_SIZE as u32;
/// Set in a BVH child entry for a leaf (`BVH_LEAF | count << 27 | first`).
pub const BVH_LEAF: u32 = steadyray_accel::GPU_LEAF;
/// The BVH child entry of an unused lane.
pub const BVH_EMPTY: u32 = steadyray_accel::GPU_EMPTY;

/// Workgroups are `WORKGROUP_SIZE` × `WORKGROUP_SIZE` threads, one thread per pixel.
pub const WORKGROUP_SIZE: u32 = 8;
/// Ray counters per workgroup of a frame of depth `max_depth`: depths 0..=max_depth, then
/// shadow rays, then the carries out of the shadow counter (a workgroup may trace more than
/// 2³² shadow rays with many lights), then the chains the depth limit stopped
/// (`RayCounts::stopped`).
pub const fn counter_stride(max_depth: u32) -> u32 {
    max_depth + 4
}
/// Ray counters per workgroup at most: [`counter_stride`] at MAX_DEPTH.
pub const COUNTER_SLOTS: u32 = counter_stride(MAX_DEPTH);
/// Threads of the ray-count reduction workgroup.
pub const REDUCE_SIZE: u32 = 256;

/// The ray caster's workgroups are `CAST_TILE` × `CAST_TILE` threads (one pixel tile of
/// primary rays, or `CAST_TILE`² rays of a list).
pub const CAST_TILE: u32 = 8;
/// [`GpuCastHit::id`] of a ray that hits nothing.
pub const CAST_MISS: u32 = u32::MAX;

/// Set in [`GpuTopLeaf::index`] when the leaf is an instance (the bits below index the
/// instance buffer); clear for a sphere or quad (they index the shape buffer).
pub const TOP_INSTANCE: u32 = 1 << 31;
/// The instance of a hit that is not on a mesh.
pub const NO_INSTANCE: u32 = u32::MAX;

/// [`GpuShape::kind`] of a sphere.
pub const SHAPE_SPHERE: u32 = 0;
/// [`GpuShape::kind`] of a quad.
pub const SHAPE_QUAD: u32 = 1;
/// [`GpuShape::kind`] of an infinite plane.
pub const SHAPE_PLANE: u32 = 2;

/// [`GpuMaterial::kind`] of a diffuse material.
pub const MAT_DIFFUSE: u32 = 0;
/// [`GpuMaterial::kind`] of a mirror.
pub const MAT_MIRROR: u32 = 1;
/// [`GpuMaterial::kind`] of a dielectric.
pub const MAT_DIELECTRIC: u32 = 2;
/// [`GpuMaterial::kind`] of an emitter.
pub const MAT_EMISSIVE: u32 = 3;

/// The per-frame uniform (WGSL `Frame`): camera frame, quality, scene-wide terms and the
/// dispatch geometry.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuFrame {
    /// The camera's eye, world space.
    pub eye: [f32; 3],
    /// tan(vfov / 2) · aspect.
    pub half_width: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// tan(vfov / 2).
    pub half_height: f32,
    /// Unit vector to the image's right.
    pub right: [f32; 3],
    /// S, fractional.
    pub spp: f32,
    /// Unit vector to the image's top.
    pub true_up: [f32; 3],
    /// Ambient term, a fraction of the albedo.
    pub ambient: f32,
    /// Radiance of rays that leave the scene, linear RGB.
    pub background: [f32; 3],
    /// R.
    pub max_depth: u32,
    /// The rendered image's width, pixels.
    pub width: u32,
    /// The rendered image's height, pixels.
    pub height: u32,
    /// Planes: the first `plane_count` shapes.
    pub plane_count: u32,
    /// Leaves of the top level (0: it is empty and not traversed).
    pub leaf_count: u32,
    /// Lights in the light buffer.
    pub light_count: u32,
    /// Workgroups along x.
    pub groups_x: u32,
    /// Counters per workgroup: R + 3 (depths 0..=R, shadow rays, shadow carries).
    pub counter_stride: u32,
    /// Workgroups in the dispatch.
    pub group_count: u32,
    /// The temporal mode's jitter J_k (zero outside it).
    pub jitter: [f32; 2],
    /// The temporal mode's first branch sample index (zero outside it).
    pub sample_base: u32,
    /// 1 in the temporal mode: sample 0 of each pixel records its geometry.
    pub temporal: u32,
    /// Shapes in the shape buffer: the planes, then the frame's spheres and quads.
    pub shape_count: u32,
    /// The frame's index in a still view (`TemporalFrame::still_frame`), else 0: its
    /// samples take new positions (`temporal::still_sample`).
    pub still_frame: u32,
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
    /// Padding for WGSL alignment (unused).
    pub pad2: u32,
}

/// The samples one dispatch of the integrator traces per pixel (WGSL `SampleRange`): those
/// with index i, `first <= i < end`, of the pixel's n (`sample_ranges`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSampleRange {
    /// The first sample index traced.
    pub first: u32,
    /// One past the last sample index traced.
    pub end: u32,
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
}

/// An analytic shape (WGSL `Shape`), with what its intersection test needs precomputed
/// exactly as the CPU reference precomputes it:
///
/// - Sphere: `p0` centre, `s0` = r², `s1` = 1 / r.
/// - Quad: `p0` corner, `p1` = normalize(w) with w = edge_u × edge_v, `p2` = (edge_v × w) / |w|²
///   and `p3` = (w × edge_u) / |w|² (the dual vectors giving the edge coordinates a, b),
///   `s0` = |edge_u|, `s1` = |edge_v|.
/// - Plane: `p0` point, `p1` normal, `p2` and `p3` the checker axes a and b.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuShape {
    /// Sphere centre, quad corner or plane point, world space.
    pub p0: [f32; 3],
    /// `SHAPE_*`.
    pub kind: u32,
    /// Quad: unit normal of edge_u × edge_v; plane: unit normal.
    pub p1: [f32; 3],
    /// Index into the material buffer.
    pub material: u32,
    /// Quad: the dual vector giving a; plane: checker axis a.
    pub p2: [f32; 3],
    /// Sphere: r²; quad: |edge_u|.
    pub s0: f32,
    /// Quad: the dual vector giving b; plane: checker axis b.
    pub p3: [f32; 3],
    /// Sphere: 1 / r; quad: |edge_v|.
    pub s1: f32,
}

/// A mesh triangle (WGSL `Triangle`) in its bottom level's space with its normal
/// normalize((v1 - v0) × (v2 - v0)). The buffer holds each mesh's triangles in its BVH's leaf
/// order, one mesh after another; `id` is the triangle's index in its mesh, which breaks ties
/// between hits at the same t as the CPU reference does (lowest index wins).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTriangle {
    /// First corner.
    pub v0: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Second corner.
    pub v1: [f32; 3],
    /// The triangle's index in its mesh (the tie-break).
    pub id: u32,
    /// Third corner.
    pub v2: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
    /// Unit normal, normalize((v1 - v0) × (v2 - v0)).
    pub normal: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad2: u32,
}

/// One leaf of the top level (WGSL `TopLeaf`), in its leaf order: a shape (`index` into the
/// shape buffer) or, with [`TOP_INSTANCE`] set, an instance; `key` breaks ties between hits
/// at the same t (lowest wins), as on the CPU.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTopLeaf {
    /// Index into the shape buffer, or into the instance buffer with [`TOP_INSTANCE`] set.
    pub index: u32,
    /// Tie-break between hits at the same t: the lowest key wins.
    pub key: u32,
}

/// A copy of a mesh (WGSL `Instance`): `to_mesh_*` are the rows (x, y, z, translation) of the
/// map from the world to the mesh's space, `normal_*` the rows of the cofactor matrix that
/// takes mesh normals to the world (`steadyray_render::two_level::Instance`); `baked` = 1
/// when the mesh is in world space already (no transform). The mesh's nodes and triangles
/// start at `node_base` and `tri_base` of their buffers.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuInstance {
    /// Row x of the world-to-mesh map (x, y, z, translation).
    pub to_mesh_x: [f32; 4],
    /// Row y of the world-to-mesh map.
    pub to_mesh_y: [f32; 4],
    /// Row z of the world-to-mesh map.
    pub to_mesh_z: [f32; 4],
    /// Row x of the cofactor matrix taking mesh normals to the world.
    pub normal_x: [f32; 3],
    /// The mesh's first node in the node buffer.
    pub node_base: u32,
    /// Row y of the normal matrix.
    pub normal_y: [f32; 3],
    /// The mesh's first triangle in the triangle buffer.
    pub tri_base: u32,
    /// Row z of the normal matrix.
    pub normal_z: [f32; 3],
    /// Index into the material buffer.
    pub material: u32,
    /// 1 when the mesh is in world space already (no transform), else 0.
    pub baked: u32,
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
    /// Padding for WGSL alignment (unused).
    pub pad2: u32,
}

/// A material (WGSL `Material`). `colour` is the albedo, reflectance, tint or radiance by
/// kind; a diffuse checker has `checker_size > 0` and its odd squares' albedo in `colour_b`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Albedo, reflectance, tint or radiance by `kind`, linear RGB.
    pub colour: [f32; 3],
    /// `MAT_*`.
    pub kind: u32,
    /// Albedo of a checker's odd squares.
    pub colour_b: [f32; 3],
    /// Side of a checker square, metres (0: no checker).
    pub checker_size: f32,
    /// Index of refraction (dielectrics).
    pub ior: f32,
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
    /// Padding for WGSL alignment (unused).
    pub pad2: u32,
}

/// A point light (WGSL `Light`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// World-space position.
    pub position: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad0: f32,
    /// Linear RGB intensity: the irradiance at 1 m, head on.
    pub intensity: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad1: f32,
}

/// The ray caster's uniform (WGSL `CastParams`): the camera frame of the primary rays
/// (`steadyray_scene::CameraFrame` for a `width` × `height` image), the image's
/// [`CAST_TILE`]-pixel tiles, the number of rays of a list and the mesh's triangle count.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCastParams {
    /// The camera's eye, world space.
    pub eye: [f32; 3],
    /// tan(vfov / 2) · aspect.
    pub half_width: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// tan(vfov / 2).
    pub half_height: f32,
    /// Unit vector to the image's right.
    pub right: [f32; 3],
    /// Image width, pixels.
    pub width: u32,
    /// Unit vector to the image's top.
    pub true_up: [f32; 3],
    /// Image height, pixels.
    pub height: u32,
    /// Tiles per image row.
    pub tiles_x: u32,
    /// Tiles in the image.
    pub tile_count: u32,
    /// Rays in the ray list.
    pub ray_count: u32,
    /// Triangles in the mesh.
    pub triangle_count: u32,
}

/// A camera frame (WGSL `CameraView`): `steadyray_scene::CameraFrame`, for the temporal
/// history's size.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCameraView {
    /// The camera's eye, world space.
    pub eye: [f32; 3],
    /// tan(vfov / 2) · aspect.
    pub half_width: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// tan(vfov / 2).
    pub half_height: f32,
    /// Unit vector to the image's right.
    pub right: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Unit vector to the image's top.
    pub true_up: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
}

impl From<&CameraFrame> for GpuCameraView {
    fn from(frame: &CameraFrame) -> Self {
        Self {
            eye: frame.eye.to_array(),
            half_width: frame.half_width,
            forward: frame.forward.to_array(),
            half_height: frame.half_height,
            right: frame.right.to_array(),
            true_up: frame.true_up.to_array(),
            ..Default::default()
        }
    }
}

/// The temporal resolve's uniform (WGSL `TemporalParams`, `shaders/temporal.wgsl`): the
/// camera frames of this frame and the previous one, the history's and the frame's sizes,
/// the landing anchor and the history's state (`steadyray_render::temporal::TemporalFrame`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTemporalParams {
    /// This frame's camera, for the history's size.
    pub current: GpuCameraView,
    /// The previous frame's camera, for the history's size.
    pub previous: GpuCameraView,
    /// The history's size.
    pub width: u32,
    /// The history's height, pixels.
    pub height: u32,
    /// The rendered frame's size.
    pub low_width: u32,
    /// The rendered frame's height, pixels.
    pub low_height: u32,
    /// Where a frame pixel's value lands inside it.
    pub anchor: [f32; 2],
    /// 1 when the previous camera frame and the history are valid.
    pub has_history: u32,
    /// 1 when the eye moved since the previous frame.
    pub eye_moved: u32,
    /// 1 when the camera frame is the previous one exactly and no object moved.
    pub still: u32,
    /// 1 when objects may have moved: `surface_count` entries of the motion table say how.
    pub world_moved: u32,
    /// Entries in the motion table.
    pub surface_count: u32,
    /// The frame's eye rays per pixel S (a frame pixel's sample count weighs its value).
    pub spp: f32,
    /// How strongly the history is sharpened for display
    /// (`steadyray_render::temporal::sharpen_strength`; 0: not at all).
    pub sharpen: f32,
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
    /// Padding for WGSL alignment (unused).
    pub pad2: u32,
}

/// The warped refresh's uniform (WGSL `WarpParams`, `shaders/warp.wgsl`): the camera frame of
/// the history's last frame and the refresh's, both for the history's size, and that size.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuWarpParams {
    /// The camera of the history's last frame.
    pub history_view: GpuCameraView,
    /// The camera at this refresh.
    pub refresh_view: GpuCameraView,
    /// The history's width, pixels.
    pub width: u32,
    /// The history's height, pixels.
    pub height: u32,
    /// How strongly the history's frame has it sharpened for display, and so the warp
    /// (`steadyray_render::temporal::sharpen_strength`; 0: not at all).
    pub sharpen: f32,
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
}

/// [`GpuSurfaceMotion::kind`] of a surface where it was.
pub const SURFACE_STILL: u32 = 0;
/// [`GpuSurfaceMotion::kind`] of a surface that moved.
pub const SURFACE_MOVED: u32 = 1;
/// [`GpuSurfaceMotion::kind`] of a surface that did not exist in the previous frame.
pub const SURFACE_NEW: u32 = 2;

/// How a surface moved since the previous frame (WGSL `SurfaceMotion`,
/// `steadyray_render::surface_motion::SurfaceMove`): its kind, and for a moved one the rows of
/// its point map (`p_*`) and normal map (`n_*`) back to the previous frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSurfaceMotion {
    /// Row x of the map from a point now to where it was in the previous frame.
    pub p_x: [f32; 4],
    /// Row y of the point map.
    pub p_y: [f32; 4],
    /// Row z of the point map.
    pub p_z: [f32; 4],
    /// Row x of the map taking normals back to the previous frame.
    pub n_x: [f32; 3],
    /// `SURFACE_*`.
    pub kind: u32,
    /// Row y of the normal map.
    pub n_y: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Row z of the normal map.
    pub n_z: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
}

impl From<&SurfaceMove> for GpuSurfaceMotion {
    fn from(m: &SurfaceMove) -> Self {
        match m {
            SurfaceMove::Still => Self::default(),
            SurfaceMove::New => Self {
                kind: SURFACE_NEW,
                ..Self::default()
            },
            SurfaceMove::Moved(map) => {
                let [p_x, p_y, p_z] = map.point_rows;
                let [n_x, n_y, n_z] = map.normal_rows;
                Self {
                    p_x,
                    p_y,
                    p_z,
                    n_x,
                    kind: SURFACE_MOVED,
                    n_y,
                    n_z,
                    ..Self::default()
                }
            }
        }
    }
}

/// A ray of a ray list (WGSL `CastRay`): origin + t·dir, hit on t in (T_MIN, ∞).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCastRay {
    /// Ray origin, world space.
    pub origin: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad0: u32,
    /// Ray direction.
    pub dir: [f32; 3],
    /// Padding for WGSL alignment (unused).
    pub pad1: u32,
}

/// A ray's closest hit (WGSL `CastHit`): t and the triangle's input index, or
/// `id == CAST_MISS` for a miss.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCastHit {
    /// Distance along the ray to the hit (in units of `dir`).
    pub t: f32,
    /// The hit triangle's input index, or [`CAST_MISS`].
    pub id: u32,
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::{offset_of, size_of};
    use wgpu::naga;

    /// A Rust struct's name, size and (member, offset) list, in declaration order.
    macro_rules! rust_layout {
        ($t:ident { $($field:ident),* $(,)? }) => {
            (
                size_of::<$t>(),
                vec![$((stringify!($field), offset_of!($t, $field))),*],
            )
        };
    }

    fn wgsl_module() -> naga::Module {
        parse(crate::pipeline::SHADER_SOURCE)
    }

    fn parse(source: &str) -> naga::Module {
        naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)))
    }

    /// Every module (the renderer's, the ray caster's, the temporal resolve's and the warp's)
    /// parses and validates without a GPU.
    #[test]
    fn wgsl_modules_validate() {
        for source in [
            crate::pipeline::SHADER_SOURCE,
            crate::pipeline::RAYCAST_SOURCE,
            crate::pipeline::TEMPORAL_SOURCE,
            crate::pipeline::WARP_SOURCE,
        ] {
            let module = parse(source);
            naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::default(),
            )
            .validate(&module)
            .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
        }
    }

    fn wgsl_struct(module: &naga::Module, name: &str) -> (usize, Vec<(String, usize)>) {
        let ty = module
            .types
            .iter()
            .find(|(_, ty)| ty.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("WGSL struct {name} not found"))
            .1;
        match &ty.inner {
            naga::TypeInner::Struct { members, span } => (
                *span as usize,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
                    .collect(),
            ),
            other => panic!("WGSL {name} is not a struct: {other:?}"),
        }
    }

    #[test]
    fn wgsl_layouts_match_rust() {
        let module = wgsl_module();
        let rust = [
            (
                "Frame",
                rust_layout!(GpuFrame {
                    eye,
                    half_width,
                    forward,
                    half_height,
                    right,
                    spp,
                    true_up,
                    ambient,
                    background,
                    max_depth,
                    width,
                    height,
                    plane_count,
                    leaf_count,
                    light_count,
                    groups_x,
                    counter_stride,
                    group_count,
                    jitter,
                    sample_base,
                    temporal,
                    shape_count,
                    still_frame,
                    pad1,
                    pad2,
                }),
            ),
            (
                "SampleRange",
                rust_layout!(GpuSampleRange {
                    first,
                    end,
                    pad0,
                    pad1
                }),
            ),
            (
                "Shape",
                rust_layout!(GpuShape {
                    p0,
                    kind,
                    p1,
                    material,
                    p2,
                    s0,
                    p3,
                    s1
                }),
            ),
            (
                "Triangle",
                rust_layout!(GpuTriangle {
                    v0,
                    pad0,
                    v1,
                    id,
                    v2,
                    pad1,
                    normal,
                    pad2
                }),
            ),
            (
                "BvhNode",
                rust_layout!(GpuBvhNode {
                    min_x,
                    min_y,
                    min_z,
                    max_x,
                    max_y,
                    max_z,
                    child,
                    pad
                }),
            ),
            ("TopLeaf", rust_layout!(GpuTopLeaf { index, key })),
            (
                "Instance",
                rust_layout!(GpuInstance {
                    to_mesh_x,
                    to_mesh_y,
                    to_mesh_z,
                    normal_x,
                    node_base,
                    normal_y,
                    tri_base,
                    normal_z,
                    material,
                    baked,
                    pad0,
                    pad1,
                    pad2,
                }),
            ),
            (
                "Material",
                rust_layout!(GpuMaterial {
                    colour,
                    kind,
                    colour_b,
                    checker_size,
                    ior,
                    pad0,
                    pad1,
                    pad2
                }),
            ),
            (
                "Light",
                rust_layout!(GpuLight {
                    position,
                    pad0,
                    intensity,
                    pad1
                }),
            ),
            (
                "CastParams",
                rust_layout!(GpuCastParams {
                    eye,
                    half_width,
                    forward,
                    half_height,
                    right,
                    width,
                    true_up,
                    height,
                    tiles_x,
                    tile_count,
                    ray_count,
                    triangle_count,
                }),
            ),
            (
                "CastRay",
                rust_layout!(GpuCastRay {
                    origin,
                    pad0,
                    dir,
                    pad1
                }),
            ),
            ("CastHit", rust_layout!(GpuCastHit { t, id })),
            (
                "CameraView",
                rust_layout!(GpuCameraView {
                    eye,
                    half_width,
                    forward,
                    half_height,
                    right,
                    pad0,
                    true_up,
                    pad1,
                }),
            ),
            (
                "TemporalParams",
                rust_layout!(GpuTemporalParams {
                    current,
                    previous,
                    width,
                    height,
                    low_width,
                    low_height,
                    anchor,
                    has_history,
                    eye_moved,
                    still,
                    world_moved,
                    surface_count,
                    spp,
                    sharpen,
                    pad0,
                    pad1,
                    pad2,
                }),
            ),
            (
                "WarpParams",
                rust_layout!(GpuWarpParams {
                    history_view,
                    refresh_view,
                    width,
                    height,
                    sharpen,
                    pad1,
                }),
            ),
            (
                "SurfaceMotion",
                rust_layout!(GpuSurfaceMotion {
                    p_x,
                    p_y,
                    p_z,
                    n_x,
                    kind,
                    n_y,
                    pad0,
                    n_z,
                    pad1,
                }),
            ),
        ];
        for (name, (size, fields)) in rust {
            let (wgsl_size, wgsl_fields) = wgsl_struct(&module, name);
            let fields: Vec<(String, usize)> = fields
                .into_iter()
                .map(|(f, o)| (f.to_string(), o))
                .collect();
            assert_eq!(wgsl_fields, fields, "member offsets of {name}");
            assert_eq!(wgsl_size, size, "size of {name}");
        }
    }

    /// The literal value of WGSL constant `name`.
    fn wgsl_constant(module: &naga::Module, name: &str) -> naga::Literal {
        let (_, c) = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("WGSL constant {name} not found"));
        match module.global_expressions[c.init] {
            naga::Expression::Literal(literal) => literal,
            ref other => panic!("WGSL constant {name} is not a literal: {other:?}"),
        }
    }

    #[test]
    fn wgsl_constants_match_rust() {
        use steadyray_render::temporal;
        let module = wgsl_module();
        let wgsl_u32 = |name: &str| -> u32 {
            match wgsl_constant(&module, name) {
                naga::Literal::U32(v) => v,
                other => panic!("WGSL constant {name} is not a u32: {other:?}"),
            }
        };
        let rust = [
            ("WORKGROUP_SIZE", WORKGROUP_SIZE),
            ("MAX_DEPTH", MAX_DEPTH),
            ("COUNTER_SLOTS", COUNTER_SLOTS),
            ("REDUCE_SIZE", REDUCE_SIZE),
            ("BVH_STACK_SIZE", BVH_STACK_SIZE),
            ("BVH_LEAF", BVH_LEAF),
            ("BVH_EMPTY", BVH_EMPTY),
            ("CAST_TILE", CAST_TILE),
            ("CAST_MISS", CAST_MISS),
            ("TOP_INSTANCE", TOP_INSTANCE),
            ("NO_INSTANCE", NO_INSTANCE),
            ("SHAPE_SPHERE", SHAPE_SPHERE),
            ("SHAPE_QUAD", SHAPE_QUAD),
            ("SHAPE_PLANE", SHAPE_PLANE),
            ("MAT_DIFFUSE", MAT_DIFFUSE),
            ("MAT_MIRROR", MAT_MIRROR),
            ("MAT_DIELECTRIC", MAT_DIELECTRIC),
            ("MAT_EMISSIVE", MAT_EMISSIVE),
            ("MISS_ID", temporal::MISS_ID),
            ("ID_MASK", temporal::ID_MASK),
            ("APPROX_FLAG", temporal::APPROX_FLAG),
            ("MIRROR_FLAG", temporal::MIRROR_FLAG),
            ("SURFACE_STILL", SURFACE_STILL),
            ("SURFACE_MOVED", SURFACE_MOVED),
            ("SURFACE_NEW", SURFACE_NEW),
        ];
        for (name, value) in rust {
            assert_eq!(wgsl_u32(name), value, "WGSL constant {name}");
        }
        let floats = [
            ("HISTORY_CAP", temporal::HISTORY_CAP),
            ("STILL_CAP", temporal::STILL_CAP),
            ("SPECULAR_CAP", temporal::SPECULAR_CAP),
            ("PLANE_TOLERANCE", temporal::PLANE_TOLERANCE),
            ("NORMAL_COS", temporal::NORMAL_COS),
        ];
        for (name, value) in floats {
            let wgsl = match wgsl_constant(&module, name) {
                naga::Literal::F32(v) => v,
                other => panic!("WGSL constant {name} is not an f32: {other:?}"),
            };
            assert_eq!(wgsl.to_bits(), value.to_bits(), "WGSL constant {name}");
        }
    }
}
