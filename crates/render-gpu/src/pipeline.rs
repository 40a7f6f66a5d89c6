//! The compute pipelines, built once per renderer: frame settings live in a uniform buffer,
//! so neither a resize nor a quality change rebuilds them.

use crate::error::scoped;
use crate::sample_ranges;
use steadyray_render::RenderError;

/// The renderer's WGSL module: layouts and its bindings, sampling rules, eye rays, the
/// triangle BVH queries, geometry, the two-level scene queries, the temporal mode's geometry
/// record, integrator, count reduction and tone map.
pub(crate) const SHADER_SOURCE: &str = concat!(
    include_str!("shaders/layout.wgsl"),
    include_str!("shaders/render_bindings.wgsl"),
    include_str!("shaders/sampling.wgsl"),
    include_str!("shaders/camera.wgsl"),
    include_str!("shaders/traversal.wgsl"),
    include_str!("shaders/geometry.wgsl"),
    include_str!("shaders/top_level.wgsl"),
    include_str!("shaders/temporal_record.wgsl"),
    include_str!("shaders/integrator.wgsl"),
    include_str!("shaders/counts.wgsl"),
    include_str!("shaders/srgb.wgsl"),
    include_str!("shaders/tonemap.wgsl"),
);

/// The temporal resolve's WGSL module ([`crate::temporal`]): layouts, the sample counts, the
/// sRGB rule, the reprojection rules, the display's sharpening, and the resolve and history
/// tone map with their bindings.
pub(crate) const TEMPORAL_SOURCE: &str = concat!(
    include_str!("shaders/layout.wgsl"),
    include_str!("shaders/sampling.wgsl"),
    include_str!("shaders/srgb.wgsl"),
    include_str!("shaders/reprojection.wgsl"),
    include_str!("shaders/sharpen.wgsl"),
    include_str!("shaders/temporal.wgsl"),
);

/// The warped refresh's WGSL module ([`crate::warp`]): layouts, the sRGB rule, the
/// reprojection rules the resolve uses, the display's sharpening, and the motion, colour and
/// display passes with their bindings.
pub(crate) const WARP_SOURCE: &str = concat!(
    include_str!("shaders/layout.wgsl"),
    include_str!("shaders/srgb.wgsl"),
    include_str!("shaders/reprojection.wgsl"),
    include_str!("shaders/sharpen.wgsl"),
    include_str!("shaders/warp.wgsl"),
);

/// The ray caster's WGSL module ([`crate::GpuRayCaster`]): layouts, eye rays and the same
/// triangle BVH queries as [`SHADER_SOURCE`], with the casting kernels and their bindings.
pub(crate) const RAYCAST_SOURCE: &str = concat!(
    include_str!("shaders/layout.wgsl"),
    include_str!("shaders/camera.wgsl"),
    include_str!("shaders/traversal.wgsl"),
    include_str!("shaders/raycast.wgsl"),
);

/// Bindings of group 0, as declared in `shaders/render_bindings.wgsl`.
pub(crate) mod binding {
    pub const FRAME: u32 = 0;
    pub const SHAPES: u32 = 1;
    pub const TRIANGLES: u32 = 2;
    pub const MATERIALS: u32 = 3;
    pub const LIGHTS: u32 = 4;
    pub const IMAGE: u32 = 5;
    pub const GROUP_COUNTS: u32 = 6;
    pub const TOTALS: u32 = 7;
    pub const SRGB8: u32 = 8;
    pub const BVH_NODES: u32 = 9;
    pub const GEOMETRY: u32 = 10;
    pub const TOP_NODES: u32 = 11;
    pub const TOP_LEAVES: u32 = 12;
    pub const INSTANCES: u32 = 13;
    pub const SURFACE_IDS: u32 = 14;
    pub const SRGB8_LEVELS: u32 = 15;
}

/// The three entry points of [`SHADER_SOURCE`] over one bind group layout (group 0); the
/// integrator also binds its dispatch's sample range (group 1).
pub(crate) struct Pipelines {
    pub(crate) bind_group_layout: wgpu::BindGroupLayout,
    /// Group 1 of [`Pipelines::render`]: one [`crate::layout::GpuSampleRange`] at a dynamic
    /// offset.
    pub(crate) sample_range_layout: wgpu::BindGroupLayout,
    /// Traces the image and counts rays per workgroup.
    pub(crate) render: wgpu::ComputePipeline,
    /// Sums the per-workgroup counts into 64-bit totals.
    pub(crate) reduce_counts: wgpu::ComputePipeline,
    /// Tone-maps the linear image into packed RGBA8.
    pub(crate) tonemap: wgpu::ComputePipeline,
}

/// The whole of `buffer` bound at `binding` (the bind group side of [`layout_entry`]).
pub(crate) fn buffer_entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// A storage or uniform buffer binding visible to compute shaders.
pub(crate) fn layout_entry(
    binding: u32,
    ty: wgpu::BufferBindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

impl Pipelines {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        use binding::*;
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let write = wgpu::BufferBindingType::Storage { read_only: false };
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("steadyray bindings"),
            entries: &[
                layout_entry(FRAME, wgpu::BufferBindingType::Uniform),
                layout_entry(SHAPES, read),
                layout_entry(TRIANGLES, read),
                layout_entry(MATERIALS, read),
                layout_entry(LIGHTS, read),
                layout_entry(IMAGE, write),
                layout_entry(GROUP_COUNTS, write),
                layout_entry(TOTALS, write),
                layout_entry(SRGB8, write),
                layout_entry(BVH_NODES, read),
                layout_entry(GEOMETRY, write),
                layout_entry(TOP_NODES, read),
                layout_entry(TOP_LEAVES, read),
                layout_entry(INSTANCES, read),
                layout_entry(SURFACE_IDS, read),
                layout_entry(SRGB8_LEVELS, read),
            ],
        });
        let sample_range_layout = sample_ranges::layout(device);
        let module = shader_module(device, SHADER_SOURCE)?;
        let build = |entry| compute_pipeline(device, &[&bind_group_layout], &module, entry);
        Ok(Self {
            render: compute_pipeline(
                device,
                &[&bind_group_layout, &sample_range_layout],
                &module,
                "render",
            )?,
            reduce_counts: build("reduce_counts")?,
            tonemap: build("tonemap")?,
            bind_group_layout,
            sample_range_layout,
        })
    }
}

/// Compiles WGSL `source`; a parse or validation failure comes back with naga's message.
///
/// wgpu's loop bounding is off: by default it adds a counter to every loop so that a loop
/// that never ends cannot be assumed away by the driver's compiler, and on an H100 that
/// counter cost 5 % of primary and 8 % of bounce ray throughput in the BVH traversal.
/// Bounds checks stay on.
pub(crate) fn shader_module(
    device: &wgpu::Device,
    source: &str,
) -> Result<wgpu::ShaderModule, RenderError> {
    let checks = wgpu::ShaderRuntimeChecks {
        force_loop_bounding: false,
        ..wgpu::ShaderRuntimeChecks::checked()
    };
    scoped(device, "WGSL shader failed to compile", || {
        // SAFETY: wgpu asks that no loop of a module compiled without loop bounding runs
        // forever. Every loop of this crate's shaders ends: the per-light, per-shape,
        // per-sample and per-bounce loops count up to bounds the host validates (R at most
        // MAX_DEPTH), the reductions, the tone map's search and the warp's steps and taps
        // step over fixed or validated counts, the ray caster's block loops end when the
        // block counter passes the dispatch's blocks, and the BVH traversals visit each node
        // of a tree (built by steadyray-accel, each node with one parent) at most once.
        unsafe {
            device.create_shader_module_trusted(
                wgpu::ShaderModuleDescriptor {
                    label: Some("steadyray shaders"),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                },
                checks,
            )
        }
    })
}

/// The compute pipeline of `entry_point` in `module` over `layouts` (groups 0, 1, ...).
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    layouts: &[&wgpu::BindGroupLayout],
    module: &wgpu::ShaderModule,
    entry_point: &str,
) -> Result<wgpu::ComputePipeline, RenderError> {
    scoped(
        device,
        &format!("cannot create the compute pipeline {entry_point:?}"),
        || {
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(entry_point),
                bind_group_layouts: &layouts.iter().copied().map(Some).collect::<Vec<_>>(),
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            })
        },
    )
}
