//! Warped refreshes on the GPU (`docs/temporal.md`, "Warped refreshes"): the last temporal
//! history shown again from a camera that moved since its frame, for a display refresh
//! that has no new frame. Three passes of `shaders/warp.wgsl`, the same arithmetic as the
//! CPU's `History::warped`: each history pixel's motion from its geometry record, then each
//! screen pixel's filtered history colour, then that colour shown as the history is
//! (sharpened when its frame resampled it), tone-mapped into the buffer the display reads.
//! The history stays on the device and is only read.

use crate::buffers::{FrameBuffers, GrowBuffer};
use crate::layout::{GpuWarpParams, WORKGROUP_SIZE};
use crate::pipeline::{WARP_SOURCE, buffer_entry, compute_pipeline, layout_entry, shader_module};
use crate::temporal::Resolved;
use steadyray_render::RenderError;
use steadyray_scene::camera::CameraFrame;

/// Bindings of the warp module's group 0, as declared in `shaders/warp.wgsl`.
mod binding {
    pub const PARAMS: u32 = 0;
    pub const HISTORY: u32 = 1;
    pub const GEOMETRY: u32 = 2;
    pub const MOTION: u32 = 3;
    pub const SRGB8: u32 = 4;
    pub const SRGB8_LEVELS: u32 = 5;
    pub const LINEAR: u32 = 6;
}

/// The warp's pipelines, its uniform, and the motion field and linear picture between its
/// passes.
pub(crate) struct WarpPass {
    layout: wgpu::BindGroupLayout,
    /// Per history pixel, its motion to the new camera (`warp_motion`).
    motion_pass: wgpu::ComputePipeline,
    /// Per screen pixel, the warped colour in linear radiance (`warp_colour`).
    colour_pass: wgpu::ComputePipeline,
    /// Per screen pixel, the colour as the display shows it, tone-mapped (`warp_display`).
    display_pass: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// One `vec2<f32>` motion per history pixel.
    motion: GrowBuffer,
    /// One `vec4<f32>` warped colour per screen pixel.
    linear: GrowBuffer,
}

impl WarpPass {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        use binding::*;
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let write = wgpu::BufferBindingType::Storage { read_only: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("warp bindings"),
            entries: &[
                layout_entry(PARAMS, wgpu::BufferBindingType::Uniform),
                layout_entry(HISTORY, read),
                layout_entry(GEOMETRY, read),
                layout_entry(MOTION, write),
                layout_entry(SRGB8, write),
                layout_entry(SRGB8_LEVELS, read),
                layout_entry(LINEAR, write),
            ],
        });
        let module = shader_module(device, WARP_SOURCE)?;
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("warp uniform"),
            size: size_of::<GpuWarpParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let motion = GrowBuffer::new(device, "warp motion", wgpu::BufferUsages::STORAGE, 0);
        let linear = GrowBuffer::new(device, "warp linear", wgpu::BufferUsages::STORAGE, 0);
        Ok(Self {
            motion_pass: compute_pipeline(device, &[&layout], &module, "warp_motion")?,
            colour_pass: compute_pipeline(device, &[&layout], &module, "warp_colour")?,
            display_pass: compute_pipeline(device, &[&layout], &module, "warp_display")?,
            layout,
            params,
            motion,
            linear,
        })
    }

    /// Writes the uniform and records the warp of `history` to camera frame `view` (made
    /// for the history's size), tone-mapped into the frame buffers' RGBA8 buffer (which has
    /// room for the history's pixels in the temporal mode).
    pub(crate) fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        history: &Resolved<'_>,
        view: &CameraFrame,
        frame_buffers: &FrameBuffers,
    ) {
        use binding::*;
        let (width, height) = (history.settings.width, history.settings.height);
        let uniform = GpuWarpParams {
            history_view: (&history.camera).into(),
            refresh_view: view.into(),
            width,
            height,
            sharpen: history.sharpen,
            ..Default::default()
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&uniform));
        self.motion
            .ensure(device, u64::from(width) * u64::from(height) * 8);
        self.linear
            .ensure(device, u64::from(width) * u64::from(height) * 16);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("warp bindings"),
            layout: &self.layout,
            entries: &[
                buffer_entry(PARAMS, &self.params),
                buffer_entry(HISTORY, history.colour),
                buffer_entry(GEOMETRY, history.geometry),
                buffer_entry(MOTION, self.motion.buffer()),
                buffer_entry(SRGB8, frame_buffers.srgb8.buffer()),
                buffer_entry(SRGB8_LEVELS, &frame_buffers.srgb8_levels),
                buffer_entry(LINEAR, self.linear.buffer()),
            ],
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("warped refresh"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, &bind_group, &[]);
        for pipeline in [&self.motion_pass, &self.colour_pass, &self.display_pass] {
            pass.set_pipeline(pipeline);
            pass.dispatch_workgroups(
                width.div_ceil(WORKGROUP_SIZE),
                height.div_ceil(WORKGROUP_SIZE),
                1,
            );
        }
    }
}
