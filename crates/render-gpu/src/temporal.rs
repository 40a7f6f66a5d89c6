//! The GPU's temporal mode (`docs/temporal.md`): the history lives on the device in two
//! buffers of radiance and age and two of geometry, read and written alternately by the
//! resolve pass of `shaders/temporal.wgsl`, which runs after the render pass inside the
//! frame's timestamps. Nothing of it is read back in the loop.

use crate::buffers::{FrameBuffers, GrowBuffer};
use crate::layout::{GpuSurfaceMotion, GpuTemporalParams, WORKGROUP_SIZE};
use crate::pipeline::{
    TEMPORAL_SOURCE, buffer_entry, compute_pipeline, layout_entry, shader_module,
};
use crate::timing::GpuTimer;
use steadyray_render::surface_motion::SurfaceMove;
use steadyray_render::temporal::{HistoryClock, TemporalFrame, sharpen_strength};
use steadyray_render::{RenderError, TemporalSettings};
use steadyray_scene::camera::CameraFrame;

/// Bindings of the temporal module's group 0, as declared in `shaders/temporal.wgsl`.
mod binding {
    pub const PARAMS: u32 = 0;
    pub const FRAME_IMAGE: u32 = 1;
    pub const FRAME_GEOMETRY: u32 = 2;
    pub const HISTORY_IN: u32 = 3;
    pub const GEOMETRY_IN: u32 = 4;
    pub const HISTORY_OUT: u32 = 5;
    pub const GEOMETRY_OUT: u32 = 6;
    pub const HISTORY_SRGB8: u32 = 7;
    pub const SURFACE_MOVES: u32 = 8;
    pub const SRGB8_LEVELS: u32 = 9;
}

/// The history's buffers and bookkeeping, while the temporal mode is on.
struct History {
    clock: HistoryClock,
    /// Radiance and age (`vec4<f32>`) per pixel, twice.
    colour: [GrowBuffer; 2],
    /// Two geometry words (`vec4<u32>`) per pixel, twice.
    geometry: [GrowBuffer; 2],
    /// Bind group i reads history i and writes the other; dropped when a buffer it names
    /// is replaced.
    bind_groups: Option<[wgpu::BindGroup; 2]>,
    /// The history the next frame reads (the last frame wrote it).
    read: usize,
    /// The camera frame (for the history's size) of the last frame resolved into the
    /// history, which a warped refresh reprojects from; None before the first.
    resolved: Option<CameraFrame>,
    /// How strongly that frame has the history sharpened for display (0: not at all).
    sharpen: f32,
}

/// The last resolved history, as a warped refresh ([`crate::warp`]) reads it.
pub(crate) struct Resolved<'a> {
    /// Radiance and age (`vec4<f32>`) per pixel.
    pub(crate) colour: &'a wgpu::Buffer,
    /// Two geometry words (`vec4<u32>`) per pixel: the record of the frame pixel each
    /// history pixel was resolved from.
    pub(crate) geometry: &'a wgpu::Buffer,
    /// How strongly its frame has it sharpened for display (0: not at all).
    pub(crate) sharpen: f32,
    /// The camera frame of its frame, for the history's size.
    pub(crate) camera: CameraFrame,
    /// The history's size.
    pub(crate) settings: TemporalSettings,
}

/// The resolve and history tone-map pipelines, their uniform, the surfaces' motion table and
/// the history.
pub(crate) struct TemporalPass {
    layout: wgpu::BindGroupLayout,
    resolve: wgpu::ComputePipeline,
    tonemap: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// How each surface moved since the previous frame (`GpuSurfaceMotion` per surface id).
    moves: GrowBuffer,
    /// Scratch for the host's table of moves.
    host_moves: Vec<SurfaceMove>,
    history: Option<History>,
}

/// The uniform of a frame: `current` and the previous camera frame, the sizes, `frame` and
/// the number of surfaces in the motion table.
fn params(
    settings: TemporalSettings,
    low: (u32, u32),
    current: &CameraFrame,
    frame: &TemporalFrame,
    surfaces: u32,
) -> GpuTemporalParams {
    GpuTemporalParams {
        current: current.into(),
        previous: frame.previous.as_ref().unwrap_or(current).into(),
        width: settings.width,
        height: settings.height,
        low_width: low.0,
        low_height: low.1,
        anchor: frame.anchor,
        has_history: u32::from(frame.previous.is_some()),
        eye_moved: u32::from(frame.eye_moved),
        still: u32::from(frame.still),
        world_moved: u32::from(frame.world_moved),
        surface_count: surfaces,
        spp: frame.spp,
        sharpen: sharpen_strength(frame, low, (settings.width, settings.height)),
        ..Default::default()
    }
}

impl TemporalPass {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        use binding::*;
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let write = wgpu::BufferBindingType::Storage { read_only: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("temporal bindings"),
            entries: &[
                layout_entry(PARAMS, wgpu::BufferBindingType::Uniform),
                layout_entry(FRAME_IMAGE, read),
                layout_entry(FRAME_GEOMETRY, read),
                layout_entry(HISTORY_IN, read),
                layout_entry(GEOMETRY_IN, read),
                layout_entry(HISTORY_OUT, write),
                layout_entry(GEOMETRY_OUT, write),
                layout_entry(HISTORY_SRGB8, write),
                layout_entry(SURFACE_MOVES, read),
                layout_entry(SRGB8_LEVELS, read),
            ],
        });
        let module = shader_module(device, TEMPORAL_SOURCE)?;
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("temporal uniform"),
            size: size_of::<GpuTemporalParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let moves = GrowBuffer::new(
            device,
            "surface moves",
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            0,
        );
        Ok(Self {
            resolve: compute_pipeline(device, &[&layout], &module, "resolve")?,
            tonemap: compute_pipeline(device, &[&layout], &module, "tonemap_history")?,
            layout,
            params,
            moves,
            host_moves: Vec::new(),
            history: None,
        })
    }

    /// Turns the mode on with an empty history of `settings`' size, or off.
    pub(crate) fn set(&mut self, device: &wgpu::Device, settings: Option<TemporalSettings>) {
        self.history = settings.map(|s| {
            let pixels = u64::from(s.width) * u64::from(s.height);
            let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
            let buffer = |label, bytes| GrowBuffer::new(device, label, usage, pixels * bytes);
            History {
                clock: HistoryClock::new(s),
                colour: [buffer("history a", 16), buffer("history b", 16)],
                geometry: [
                    buffer("history geometry a", 32),
                    buffer("history geometry b", 32),
                ],
                bind_groups: None,
                read: 0,
                resolved: None,
                sharpen: 0.0,
            }
        });
    }

    /// The history's size, when the mode is on.
    pub(crate) fn settings(&self) -> Option<TemporalSettings> {
        self.history.as_ref().map(|h| h.clock.settings())
    }

    /// Forgets the history: the next frame starts a new one.
    pub(crate) fn reset(&mut self) {
        if let Some(history) = &mut self.history {
            history.clock.reset();
        }
    }

    /// Forgets the bind groups (a frame buffer they name was replaced).
    pub(crate) fn invalidate(&mut self) {
        if let Some(history) = &mut self.history {
            history.bind_groups = None;
        }
    }

    /// Counts the next frame, seen from camera frame `current` (for the history's size) at
    /// scene time `time_s` of a scene that is `animated` or not, and returns what its render
    /// pass needs; None when the mode is off.
    pub(crate) fn advance(
        &mut self,
        current: CameraFrame,
        time_s: f64,
        animated: bool,
        spp: f32,
    ) -> Option<TemporalFrame> {
        self.history
            .as_mut()
            .map(|h| h.clock.advance(current, time_s, animated, spp))
    }

    /// Uploads how the surfaces moved for the next resolve: `fill` writes the table into the
    /// scratch it is given. Returns whether the table's buffer was replaced.
    pub(crate) fn upload_moves(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        fill: impl FnOnce(&mut Vec<SurfaceMove>),
    ) -> bool {
        fill(&mut self.host_moves);
        let table: Vec<GpuSurfaceMotion> = self.host_moves.iter().map(Into::into).collect();
        let grew = self
            .moves
            .write(device, queue, bytemuck::cast_slice(&table));
        if grew {
            self.invalidate();
        }
        grew
    }

    /// Writes the frame's uniform and records the resolve of a `low`-sized frame into the
    /// history, its end timestamp the frame's. The mode must be on.
    pub(crate) fn encode_resolve(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame_buffers: &FrameBuffers,
        step: (&CameraFrame, &TemporalFrame, (u32, u32)),
        timer: Option<&GpuTimer>,
    ) {
        let Some(history) = &mut self.history else {
            return;
        };
        let settings = history.clock.settings();
        let (current, frame, low) = step;
        let surfaces = if frame.world_moved {
            self.host_moves.len() as u32
        } else {
            0
        };
        let uniform = params(settings, low, current, frame, surfaces);
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&uniform));
        let groups = history.bind_groups.get_or_insert_with(|| {
            let buffers = TemporalBuffers {
                params: &self.params,
                moves: &self.moves,
                colour: &history.colour,
                geometry: &history.geometry,
            };
            bind_groups(device, &self.layout, frame_buffers, &buffers)
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("temporal resolve"),
            timestamp_writes: timer.map(GpuTimer::end_writes),
        });
        pass.set_pipeline(&self.resolve);
        pass.set_bind_group(0, &groups[history.read], &[]);
        pass.dispatch_workgroups(
            settings.width.div_ceil(WORKGROUP_SIZE),
            settings.height.div_ceil(WORKGROUP_SIZE),
            1,
        );
        history.read = 1 - history.read;
        history.resolved = Some(*current);
        history.sharpen = uniform.sharpen;
    }

    /// Records the tone map of the last resolved history into the frame buffers' RGBA8
    /// buffer. The mode must be on and a frame resolved.
    pub(crate) fn encode_tonemap(&self, encoder: &mut wgpu::CommandEncoder) {
        let Some(history) = &self.history else {
            return;
        };
        let Some(groups) = &history.bind_groups else {
            return;
        };
        let settings = history.clock.settings();
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("tonemap history"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.tonemap);
        // The group that wrote the last history: it reads the other one.
        pass.set_bind_group(0, &groups[1 - history.read], &[]);
        pass.dispatch_workgroups(
            settings.width.div_ceil(WORKGROUP_SIZE),
            settings.height.div_ceil(WORKGROUP_SIZE),
            1,
        );
    }

    /// The buffer holding the last resolved history (radiance and age per pixel).
    pub(crate) fn output(&self) -> Option<&wgpu::Buffer> {
        self.history.as_ref().map(|h| h.colour[h.read].buffer())
    }

    /// The last resolved history with its geometry and camera, if a frame was resolved
    /// since the mode was set (a reset keeps it, as it keeps the frame on display).
    pub(crate) fn resolved(&self) -> Option<Resolved<'_>> {
        let history = self.history.as_ref()?;
        Some(Resolved {
            colour: history.colour[history.read].buffer(),
            geometry: history.geometry[history.read].buffer(),
            sharpen: history.sharpen,
            camera: history.resolved?,
            settings: history.clock.settings(),
        })
    }
}

/// The temporal pass's own buffers a bind group names.
struct TemporalBuffers<'a> {
    params: &'a wgpu::Buffer,
    moves: &'a GrowBuffer,
    colour: &'a [GrowBuffer; 2],
    geometry: &'a [GrowBuffer; 2],
}

/// The two bind groups of a history: group i reads history i and writes the other.
fn bind_groups(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    frame_buffers: &FrameBuffers,
    b: &TemporalBuffers<'_>,
) -> [wgpu::BindGroup; 2] {
    use binding::*;
    let (params, colour, geometry) = (b.params, b.colour, b.geometry);
    [0, 1].map(|i| {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("temporal bindings"),
            layout,
            entries: &[
                buffer_entry(PARAMS, params),
                buffer_entry(FRAME_IMAGE, frame_buffers.image.buffer()),
                buffer_entry(FRAME_GEOMETRY, frame_buffers.geometry.buffer()),
                buffer_entry(HISTORY_IN, colour[i].buffer()),
                buffer_entry(GEOMETRY_IN, geometry[i].buffer()),
                buffer_entry(HISTORY_OUT, colour[1 - i].buffer()),
                buffer_entry(GEOMETRY_OUT, geometry[1 - i].buffer()),
                buffer_entry(HISTORY_SRGB8, frame_buffers.srgb8.buffer()),
                buffer_entry(SURFACE_MOVES, b.moves.buffer()),
                buffer_entry(SRGB8_LEVELS, &frame_buffers.srgb8_levels),
            ],
        })
    })
}
