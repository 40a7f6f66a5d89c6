//! [`GpuRenderer`]: the Whitted integrator of `docs/shading.md` as wgpu compute passes.

use crate::adapter::{AdapterSummary, GpuOptions};
use crate::buffers::{FrameBuffers, TOTALS_BYTES};
use crate::device::GpuContext;
use crate::error::{gpu_error, scoped};
use crate::layout::{GpuFrame, WORKGROUP_SIZE, counter_stride};
use crate::pipeline::{Pipelines, binding, buffer_entry};
use crate::sample_ranges::SampleRanges;
use crate::scene_buffers::{GpuWorld, PackedScene, SceneBuffers};
use crate::temporal::TemporalPass;
use crate::timing::{GpuTimer, TIMESTAMP_BYTES};
use crate::warp::WarpPass;
use std::time::Instant;
use steadyray_render::temporal::sample_base;
use steadyray_render::two_level::SceneLayout;
use steadyray_render::{
    BackendInfo, FrameBudget, FrameStats, Image, Picture, Presented, RayCounts, RenderError,
    RenderSettings, Renderer, SampleStream, TemporalSettings, TimingSource, check_camera,
    check_time,
};
use steadyray_scene::{Camera, Scene};

pub(crate) mod display;

/// The loaded scene: what is fixed, and its frame at the last time rendered.
struct LoadedScene {
    packed: PackedScene,
    world: GpuWorld,
}

/// The image the last frame left: its size, whether it is the temporal history, and what
/// the RGBA8 buffer holds of it (so that a presented frame read back as a picture is not
/// tone-mapped twice, and a warped refresh stays on display until the frame is presented
/// again).
#[derive(Clone, Copy, Debug)]
struct LastFrame {
    width: u32,
    height: u32,
    temporal: bool,
    shown: Shown,
}

/// What the RGBA8 buffer holds of the last frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shown {
    /// Nothing of it: showing or reading its picture needs its tone map first.
    Nothing,
    /// Its tone map.
    Frame,
    /// A warped refresh of it ([`Renderer::present_warped`]): the display's picture until
    /// the next frame or [`Renderer::present`].
    Warp,
}

/// The GPU backend. It owns its device (create one per process) and keeps pipelines and
/// buffers across frames and scenes: a new image size or quality only rewrites the frame
/// uniform and, when the image grows, reallocates the frame buffers.
///
/// [`Renderer::render`] waits for the frame and reads back only the ray counts and
/// timestamps; [`Renderer::read_image`] (linear) and [`GpuRenderer::read_srgb8`]
/// (tone-mapped) read the image. In the temporal mode the history stays on the device and
/// the resolve pass runs inside the frame's timestamps; a warped refresh
/// ([`Renderer::present_warped`]) reads it there.
pub struct GpuRenderer {
    ctx: GpuContext,
    pipelines: Pipelines,
    /// The integrator's dispatches of a frame, each with its share of the samples.
    sample_ranges: SampleRanges,
    timer: Option<GpuTimer>,
    frame_uniform: wgpu::Buffer,
    scene_buffers: SceneBuffers,
    frame_buffers: FrameBuffers,
    /// Refers to the buffers above; dropped whenever one of them is replaced.
    bind_group: Option<wgpu::BindGroup>,
    scene: Option<LoadedScene>,
    temporal: TemporalPass,
    warp: WarpPass,
    /// The samples plain frames draw.
    stream: SampleStream,
    last_frame: Option<LastFrame>,
}

impl GpuRenderer {
    /// Opens the adapter `options` choose and builds the pipelines. Fails with
    /// [`RenderError::Gpu`] ("no GPU adapter found (...)") when no adapter qualifies.
    pub fn new(options: &GpuOptions) -> Result<Self, RenderError> {
        Self::from_context(GpuContext::new(options)?)
    }

    /// Builds the pipelines and buffers on an opened device.
    fn from_context(ctx: GpuContext) -> Result<Self, RenderError> {
        let pipelines = Pipelines::new(&ctx.device)?;
        let sample_ranges = SampleRanges::new(
            &ctx.device,
            &ctx.queue,
            &pipelines.sample_range_layout,
            ctx.adapter.is_software,
        );
        let timer = ctx
            .timestamps
            .then(|| GpuTimer::new(&ctx.device, &ctx.queue))
            .flatten();
        let frame_uniform = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame uniform"),
            size: size_of::<GpuFrame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let scene_buffers = SceneBuffers::new(&ctx.device);
        let frame_buffers = FrameBuffers::new(&ctx.device);
        let temporal = TemporalPass::new(&ctx.device)?;
        let warp = WarpPass::new(&ctx.device)?;
        ctx.errors.check()?;
        Ok(Self {
            ctx,
            pipelines,
            sample_ranges,
            timer,
            frame_uniform,
            scene_buffers,
            frame_buffers,
            bind_group: None,
            scene: None,
            temporal,
            warp,
            stream: SampleStream::Frames,
            last_frame: None,
        })
    }

    /// The adapter this renderer runs on.
    pub fn adapter(&self) -> &AdapterSummary {
        &self.ctx.adapter
    }

    /// Whether frame times come from GPU timestamps ([`TimingSource::GpuTimestamps`]).
    pub fn has_timestamps(&self) -> bool {
        self.timer.is_some()
    }

    /// The last frame tone-mapped on the GPU (`linear_to_srgb8` per channel, to the bit: the
    /// shaders look each level up in a table of the host's) as RGBA bytes, row-major, top row
    /// first: the same bytes as `read_image()?.to_srgb8_rgba()`. After [`Renderer::present_warped`] it is the warped
    /// picture on display instead, until the next frame or [`Renderer::present`].
    pub fn read_srgb8(&mut self) -> Result<Vec<u8>, RenderError> {
        let last = self.last_frame.ok_or(RenderError::NoFrame)?;
        let size = u64::from(last.width) * u64::from(last.height) * 4;
        let mut encoder = self.ctx.encoder("tonemap");
        self.encode_tonemap(&mut encoder, last);
        let bytes = self.read_back(encoder, Source::Srgb8, size)?;
        self.mark_tone_mapped();
        Ok(bytes)
    }

    /// The bind group over the current buffers, rebuilt if one was replaced.
    fn bind_group(&mut self) -> wgpu::BindGroup {
        let bind_group = self.bind_group.get_or_insert_with(|| {
            let (s, f) = (&self.scene_buffers, &self.frame_buffers);
            self.ctx
                .device
                .create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("steadyray bindings"),
                    layout: &self.pipelines.bind_group_layout,
                    entries: &[
                        buffer_entry(binding::FRAME, &self.frame_uniform),
                        buffer_entry(binding::SHAPES, s.shapes.buffer()),
                        buffer_entry(binding::TRIANGLES, s.triangles.buffer()),
                        buffer_entry(binding::MATERIALS, s.materials.buffer()),
                        buffer_entry(binding::LIGHTS, s.lights.buffer()),
                        buffer_entry(binding::IMAGE, f.image.buffer()),
                        buffer_entry(binding::GROUP_COUNTS, f.group_counts.buffer()),
                        buffer_entry(binding::TOTALS, &f.totals),
                        buffer_entry(binding::SRGB8, f.srgb8.buffer()),
                        buffer_entry(binding::BVH_NODES, s.bvh_nodes.buffer()),
                        buffer_entry(binding::GEOMETRY, f.geometry.buffer()),
                        buffer_entry(binding::TOP_NODES, s.top_nodes.buffer()),
                        buffer_entry(binding::TOP_LEAVES, s.top_leaves.buffer()),
                        buffer_entry(binding::INSTANCES, s.instances.buffer()),
                        buffer_entry(binding::SURFACE_IDS, s.surface_ids.buffer()),
                        buffer_entry(binding::SRGB8_LEVELS, &f.srgb8_levels),
                    ],
                })
        });
        bind_group.clone()
    }

    /// Appends a copy of the first `size` bytes of `source` to the readback buffer, submits,
    /// waits and returns the bytes.
    fn read_back(
        &mut self,
        mut encoder: wgpu::CommandEncoder,
        source: Source,
        size: u64,
    ) -> Result<Vec<u8>, RenderError> {
        let f = &mut self.frame_buffers;
        f.image_readback.ensure(&self.ctx.device, size);
        let from = match source {
            Source::Linear => f.image.buffer(),
            Source::Srgb8 => f.srgb8.buffer(),
            Source::History => self.temporal.output().ok_or(RenderError::NoFrame)?,
        };
        encoder.copy_buffer_to_buffer(from, 0, f.image_readback.buffer(), 0, size);
        let commands = scoped(&self.ctx.device, "cannot record the readback", || {
            encoder.finish()
        })?;
        self.ctx.submit_and_wait(commands)?;
        self.ctx.read_buffer(f.image_readback.buffer(), size)
    }

    /// Records the reduction of the per-workgroup counters into 64-bit totals and their copy
    /// to the start of the stats readback buffer.
    fn encode_totals(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        counter_stride: u32,
    ) {
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("reduce ray counts"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipelines.reduce_counts);
            pass.set_bind_group(0, bind_group, &[]);
            pass.dispatch_workgroups(counter_stride, 1, 1);
        }
        let f = &self.frame_buffers;
        let bytes = u64::from(counter_stride) * 8;
        encoder.copy_buffer_to_buffer(&f.totals, 0, &f.stats_readback, 0, bytes);
    }

    /// Checks that a frame of `settings` (accumulated into a history of `history` pixels in
    /// the temporal mode) fits the device's buffer and dispatch limits.
    fn check_limits(
        &self,
        settings: &RenderSettings,
        counters: u64,
        history: Option<u64>,
    ) -> Result<(), RenderError> {
        let limits = self.ctx.device.limits();
        let max = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size);
        let history = history.unwrap_or(0);
        let needs = [
            ("image", settings.pixels() * 16),
            ("ray counter", counters * 4),
            ("history geometry", history * 32),
            ("pixel geometry", history.min(1) * settings.pixels() * 32),
        ];
        match needs.into_iter().find(|&(_, bytes)| bytes > max) {
            Some((what, bytes)) => Err(gpu_error(
                "frame too large for this GPU",
                format!(
                    "{}x{} at R={} needs a {bytes}-byte {what} buffer; the device allows {max}",
                    settings.width, settings.height, settings.max_depth
                ),
            )),
            None => Ok(()),
        }
    }
}

/// Which image [`GpuRenderer::read_back`] copies.
enum Source {
    Linear,
    Srgb8,
    /// The temporal history (radiance and age per pixel).
    History,
}

/// The 64-bit (low, high) totals in `bytes`.
fn parse_totals(bytes: &[u8]) -> Vec<u64> {
    bytes
        .chunks_exact(8)
        .map(|pair| {
            let [low, high]: [u32; 2] = bytemuck::pod_read_unaligned(pair);
            u64::from(low) | (u64::from(high) << 32)
        })
        .collect()
}

impl Renderer for GpuRenderer {
    fn info(&self) -> BackendInfo {
        BackendInfo {
            backend: "gpu".to_string(),
            device: self.ctx.description(),
        }
    }

    fn load_scene(&mut self, scene: &Scene) -> Result<(), RenderError> {
        self.scene = None;
        let layout = SceneLayout::new(scene)?;
        let packed = PackedScene::new(scene, &layout)?;
        let count = |n: usize, what: &str| {
            u32::try_from(n).map_err(|_| RenderError::Scene(format!("too many {what}: {n}")))
        };
        count(packed.lights.len(), "lights")?;
        count(packed.triangles.len(), "triangles")?;
        let world = GpuWorld::new(scene, layout)?;
        let device = &self.ctx.device;
        let grew = scoped(device, "cannot upload the scene", || {
            self.scene_buffers
                .upload_scene(device, &self.ctx.queue, &packed)
        })?;
        if grew {
            self.bind_group = None;
        }
        self.scene = Some(LoadedScene { packed, world });
        self.temporal.reset();
        Ok(())
    }

    fn render(
        &mut self,
        camera: &Camera,
        time_s: f64,
        settings: &RenderSettings,
    ) -> Result<FrameStats, RenderError> {
        settings.validate()?;
        check_time(time_s)?;
        check_camera(camera)?;
        let scene = self.scene.as_mut().ok_or(RenderError::NoScene)?;
        self.ctx.errors.check()?;
        let wall_start = Instant::now();
        // The frame's objects and top level, placed and uploaded: part of Tp.
        if scene.world.place(time_s, &scene.packed)? {
            let device = &self.ctx.device;
            let world = &scene.world;
            let grew = scoped(device, "cannot upload the frame's objects", || {
                self.scene_buffers
                    .upload_frame(device, &self.ctx.queue, world)
            })??;
            if grew {
                self.bind_group = None;
            }
        }
        let accel_ms = wall_start.elapsed().as_secs_f64() * 1e3;
        let count = |n: usize, what: &str| {
            u32::try_from(n).map_err(|_| RenderError::Scene(format!("too many {what}: {n}")))
        };
        let plane_count = count(scene.packed.planes.len(), "planes")?;
        let leaf_count = count(scene.world.top_leaves.len(), "objects")?;
        let shape_count = count(scene.world.shapes.len(), "shapes")?;
        let light_count = scene.packed.lights.len() as u32;
        let (ambient, background) = (scene.packed.ambient, scene.packed.background);
        let animated = scene.world.is_animated();
        let (width, height) = (settings.width, settings.height);
        let groups_x = width.div_ceil(WORKGROUP_SIZE);
        let groups_y = height.div_ceil(WORKGROUP_SIZE);
        let group_count = groups_x * groups_y;
        let counter_stride = counter_stride(settings.max_depth);
        let counters = u64::from(group_count) * u64::from(counter_stride);
        let history = self.temporal.settings();
        if let Some(history) = history {
            history.check(settings)?;
        }
        let history_pixels = history.map(|h| u64::from(h.width) * u64::from(h.height));
        self.check_limits(settings, counters, history_pixels)?;

        // In the temporal mode rays follow the history's aspect, so every sample lies where
        // it lands.
        let (frame_width, frame_height) = history.map_or((width, height), |h| (h.width, h.height));
        let cam = camera.frame(frame_width, frame_height);
        let step = self.temporal.advance(cam, time_s, animated, settings.spp);
        if let (Some(step), Some(scene)) = (step.filter(|s| s.world_moved), &self.scene) {
            self.temporal
                .upload_moves(&self.ctx.device, &self.ctx.queue, |out| {
                    scene.world.surface_moves(step.previous_time_s, time_s, out);
                });
        }
        let (plain_jitter, plain_base) = self.stream.pattern();
        let frame = GpuFrame {
            eye: cam.eye.to_array(),
            half_width: cam.half_width,
            forward: cam.forward.to_array(),
            half_height: cam.half_height,
            right: cam.right.to_array(),
            spp: settings.spp,
            true_up: cam.true_up.to_array(),
            ambient,
            background,
            max_depth: settings.max_depth,
            width,
            height,
            plane_count,
            leaf_count,
            light_count,
            groups_x,
            counter_stride,
            group_count,
            jitter: step.map_or(plain_jitter, |s| s.jitter),
            sample_base: step.map_or(plain_base, |s| sample_base(s.index)),
            temporal: u32::from(step.is_some()),
            shape_count,
            still_frame: step.map_or(0, |s| s.still_frame()),
            ..Default::default()
        };
        let shown = history_pixels.unwrap_or(settings.pixels());
        if self.frame_buffers.ensure(
            &self.ctx.device,
            settings.pixels(),
            counters,
            step.is_some(),
            shown,
        ) {
            self.bind_group = None;
            self.temporal.invalidate();
        }
        // The image buffer is about to be overwritten: no frame to read until this one is.
        self.last_frame = None;
        self.ctx
            .queue
            .write_buffer(&self.frame_uniform, 0, bytemuck::bytes_of(&frame));

        let mut encoder = self.ctx.encoder("frame");
        let bind_group = self.bind_group();
        {
            // The temporal resolve ends the timed span when there is one.
            let writes = match step {
                Some(_) => GpuTimer::begin_writes,
                None => GpuTimer::pass_writes,
            };
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render"),
                timestamp_writes: self.timer.as_ref().map(writes),
            });
            pass.set_pipeline(&self.pipelines.render);
            pass.set_bind_group(0, &bind_group, &[]);
            self.sample_ranges
                .dispatch(&mut pass, settings.spp, (groups_x, groups_y));
        }
        if let Some(step) = &step {
            self.temporal.encode_resolve(
                &self.ctx.device,
                &self.ctx.queue,
                &mut encoder,
                &self.frame_buffers,
                (&cam, step, (width, height)),
                self.timer.as_ref(),
            );
        }
        self.encode_totals(&mut encoder, &bind_group, counter_stride);
        let f = &self.frame_buffers;
        let totals_bytes = u64::from(counter_stride) * 8;
        if let Some(timer) = &self.timer {
            timer.resolve(&mut encoder, &f.stats_readback, TOTALS_BYTES);
        }
        let commands = scoped(&self.ctx.device, "cannot record the frame", || {
            encoder.finish()
        })?;
        let gpu_start = Instant::now();
        self.ctx.submit_and_wait(commands)?;
        let submit_and_wait_ms = gpu_start.elapsed().as_secs_f64() * 1e3;
        let stats = self
            .ctx
            .read_buffer(&f.stats_readback, TOTALS_BYTES + TIMESTAMP_BYTES)?;

        let totals = parse_totals(&stats[..totals_bytes as usize]);
        let depth = settings.max_depth as usize;
        let rays = RayCounts {
            per_depth: totals[..=depth].to_vec(),
            shadow: totals[depth + 1] + (totals[depth + 2] << 32),
            stopped: totals[depth + 3],
        };
        let gpu_ms = self
            .timer
            .as_ref()
            .and_then(|t| t.elapsed_ms(&stats[TOTALS_BYTES as usize..]));
        let (render_ms, timing) = match gpu_ms {
            Some(ms) => (accel_ms + ms, TimingSource::GpuTimestamps),
            None => (accel_ms + submit_and_wait_ms, TimingSource::WallClock),
        };
        self.last_frame = Some(LastFrame {
            width: frame_width,
            height: frame_height,
            temporal: step.is_some(),
            shown: Shown::Nothing,
        });
        Ok(FrameStats {
            render_ms,
            accel_ms,
            wall_ms: wall_start.elapsed().as_secs_f64() * 1e3,
            timing,
            samples: rays.per_depth[0],
            spp: settings.spp,
            rays,
            width,
            height,
        })
    }

    fn read_image(&mut self) -> Result<Image, RenderError> {
        let LastFrame {
            width,
            height,
            temporal,
            ..
        } = self.last_frame.ok_or(RenderError::NoFrame)?;
        let size = u64::from(width) * u64::from(height) * 16;
        let encoder = self.ctx.encoder("read image");
        let source = if temporal {
            Source::History
        } else {
            Source::Linear
        };
        let bytes = self.read_back(encoder, source, size)?;
        let pixels = bytes
            .chunks_exact(16)
            .map(|texel| {
                let [r, g, b, _]: [f32; 4] = bytemuck::pod_read_unaligned(texel);
                [r, g, b]
            })
            .collect();
        Ok(Image {
            width,
            height,
            pixels,
        })
    }

    fn present(&mut self) -> Result<Presented, RenderError> {
        // The frame itself goes on display again, replacing any warped refresh of it.
        if let Some(last) = &mut self.last_frame
            && last.shown == Shown::Warp
        {
            last.shown = Shown::Nothing;
        }
        self.display_image()?;
        self.ctx.wait()?;
        Ok(Presented::Device)
    }

    fn read_picture(&mut self) -> Result<Picture, RenderError> {
        let rgba = self.read_srgb8()?;
        let last = self.last_frame.ok_or(RenderError::NoFrame)?;
        Ok(Picture {
            width: last.width,
            height: last.height,
            rgba,
        })
    }

    fn present_warped(&mut self, camera: &Camera) -> Result<Presented, RenderError> {
        check_camera(camera)?;
        let settings = self.temporal.settings().ok_or_else(|| {
            RenderError::Unavailable(
                "a warped refresh needs the temporal mode (its history and geometry)".into(),
            )
        })?;
        if !self.last_frame.is_some_and(|last| last.temporal) {
            return Err(RenderError::NoFrame);
        }
        let history = self.temporal.resolved().ok_or(RenderError::NoFrame)?;
        self.ctx.errors.check()?;
        let view = camera.frame(settings.width, settings.height);
        let mut encoder = self.ctx.encoder("warped refresh");
        let device = &self.ctx.device;
        let commands = scoped(device, "cannot record the warped refresh", || {
            self.warp.encode(
                device,
                &self.ctx.queue,
                &mut encoder,
                &history,
                &view,
                &self.frame_buffers,
            );
            encoder.finish()
        })?;
        self.ctx.submit_and_wait(commands)?;
        if let Some(last) = &mut self.last_frame {
            last.shown = Shown::Warp;
        }
        Ok(Presented::Device)
    }

    fn set_temporal(&mut self, temporal: Option<TemporalSettings>) -> Result<(), RenderError> {
        if let Some(settings) = &temporal {
            settings.validate()?;
        }
        let device = &self.ctx.device;
        scoped(device, "cannot allocate the temporal history", || {
            self.temporal.set(device, temporal);
        })?;
        self.last_frame = None;
        Ok(())
    }

    fn reset_history(&mut self) {
        self.temporal.reset();
    }

    fn set_sample_stream(&mut self, stream: SampleStream) {
        self.stream = stream;
    }

    fn set_frame_budget(&mut self, budget: Option<FrameBudget>) -> Result<(), RenderError> {
        match budget {
            None => Ok(()),
            Some(_) => Err(RenderError::Unavailable(
                "a frame budget needs the CPU renderer: the GPU renders a frame's samples \
                 in one submission and cannot stop it part-way"
                    .into(),
            )),
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::pipeline::{compute_pipeline, layout_entry, shader_module};

    /// A renderer on any adapter (software included), or None after a loud skip message;
    /// panics instead when STEADYRAY_REQUIRE_GPU=1.
    pub(crate) fn test_renderer() -> Option<GpuRenderer> {
        let options = GpuOptions {
            adapter_name: std::env::var("STEADYRAY_ADAPTER").ok(),
            allow_software: true,
        };
        match GpuRenderer::new(&options) {
            Ok(renderer) => Some(renderer),
            Err(e) if std::env::var("STEADYRAY_REQUIRE_GPU").as_deref() == Ok("1") => {
                panic!("STEADYRAY_REQUIRE_GPU=1 but no GPU renderer: {e}")
            }
            Err(e) => {
                eprintln!("SKIPPED: no GPU adapter ({e})");
                None
            }
        }
    }

    #[test]
    fn broken_wgsl_surfaces_the_compiler_message() {
        let Some(renderer) = test_renderer() else {
            return;
        };
        let device = &renderer.ctx.device;
        let err = shader_module(device, "@compute @workgroup_size(1) fn main( {")
            .expect_err("a syntax error must not compile");
        let message = err.to_string();
        assert!(
            message.contains("WGSL shader failed to compile"),
            "{message}"
        );
        assert!(
            message.contains("expected"),
            "no parser message in: {message}"
        );

        // Parses, but fails validation: a type error.
        let module = shader_module(
            device,
            "@compute @workgroup_size(1) fn main() { let x: u32 = 1.5; }",
        );
        let message = match module {
            Err(e) => e.to_string(),
            Ok(module) => compute_pipeline(
                device,
                &[&renderer.pipelines.bind_group_layout],
                &module,
                "main",
            )
            .expect_err("a type error must not build")
            .to_string(),
        };
        assert!(
            message.contains("main") || message.contains("u32"),
            "{message}"
        );
        // Caught by the scopes: nothing left over for the device's uncaptured handler.
        renderer.ctx.errors.check().unwrap();
    }

    /// The per-workgroup counters are summed with carries: totals far beyond u32 come out
    /// exact (a real GPU passes 4.29e9 rays per frame).
    #[test]
    fn count_reduction_carries_past_32_bits() {
        let Some(mut renderer) = test_renderer() else {
            return;
        };
        let scene = steadyray_scene::builtin("corridor").unwrap();
        renderer.load_scene(&scene).unwrap();
        // 64x64 pixels: 64 workgroups, R = 0: 3 counters each.
        let settings = RenderSettings {
            width: 64,
            height: 64,
            spp: 1.0,
            max_depth: 0,
        };
        renderer.render(&scene.camera, 0.0, &settings).unwrap();
        // Four counters per workgroup at R = 0: eye rays, shadow rays, their carries and the
        // stopped chains.
        let counts: Vec<u32> = (0..64u32)
            .flat_map(|g| [u32::MAX - g, 3_000_000_000 + g, g % 3, g % 5])
            .collect();
        let ctx = &renderer.ctx;
        ctx.queue.write_buffer(
            renderer.frame_buffers.group_counts.buffer(),
            0,
            bytemuck::cast_slice(&counts),
        );
        let bind_group = renderer.bind_group();
        let mut encoder = renderer.ctx.encoder("reduce test");
        renderer.encode_totals(&mut encoder, &bind_group, 4);
        renderer.ctx.submit_and_wait(encoder.finish()).unwrap();
        let bytes = renderer
            .ctx
            .read_buffer(&renderer.frame_buffers.stats_readback, 32)
            .unwrap();
        let expected = [0, 1, 2, 3].map(|c| {
            counts
                .iter()
                .skip(c)
                .step_by(4)
                .map(|&v| u64::from(v))
                .sum::<u64>()
        });
        assert_eq!(parse_totals(&bytes), expected);
        assert!(expected[..2].iter().all(|&t| t > u64::from(u32::MAX)));
    }

    /// The GPU's tone map (`shaders/srgb.wgsl`, the renderer's level table) is the host's
    /// to the bit at every level's edge, where a `pow` that rounds unlike the host's moves a
    /// radiance to the next level, across [0, 1], and for NaN, signed zeros, infinities and
    /// radiances past 1.
    #[test]
    fn tone_map_is_the_hosts_at_every_levels_edge() {
        use steadyray_render::tonemap::linear_to_srgb8;
        use wgpu::util::DeviceExt;
        let Some(renderer) = test_renderer() else {
            return;
        };
        let mut values: Vec<f32> = steadyray_render::tonemap::srgb8_thresholds()
            .iter()
            .flat_map(|t| [f32::from_bits(t.to_bits() - 1), *t])
            .collect();
        values.extend((0..1f32.to_bits()).step_by(65_537).map(f32::from_bits));
        values.extend([
            f32::NAN,
            -0.0,
            0.0,
            -1.0,
            f32::NEG_INFINITY,
            f32::INFINITY,
            1.0,
            2.0,
        ]);
        let source = concat!(
            include_str!("shaders/srgb.wgsl"),
            "
            @group(0) @binding(0) var<storage, read> values: array<f32>;
            @group(0) @binding(1) var<storage, read_write> levels: array<u32>;
            @group(0) @binding(2) var<storage, read> srgb8_levels: array<f32>;

            @compute @workgroup_size(64)
            fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
                if gid.x < arrayLength(&values) {
                    levels[gid.x] = linear_to_srgb8(values[gid.x]);
                }
            }
            "
        );
        let ctx = &renderer.ctx;
        let device = &ctx.device;
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let write = wgpu::BufferBindingType::Storage { read_only: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tone map test"),
            entries: &[
                layout_entry(0, read),
                layout_entry(1, write),
                layout_entry(2, read),
            ],
        });
        let module = shader_module(device, source).unwrap();
        let pipeline = compute_pipeline(device, &[&layout], &module, "main").unwrap();
        let bytes = (values.len() * 4) as u64;
        let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("tone map test values"),
            contents: bytemuck::cast_slice(&values),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        let output = buffer("tone map test levels", U::STORAGE | U::COPY_SRC);
        let readback = buffer("tone map test readback", U::MAP_READ | U::COPY_DST);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tone map test"),
            layout: &layout,
            entries: &[
                buffer_entry(0, &input),
                buffer_entry(1, &output),
                buffer_entry(2, &renderer.frame_buffers.srgb8_levels),
            ],
        });
        let mut encoder = ctx.encoder("tone map test");
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(values.len().div_ceil(64) as u32, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, bytes);
        ctx.submit_and_wait(encoder.finish()).unwrap();
        let on_gpu = ctx.read_buffer(&readback, bytes).unwrap();
        let off: Vec<(f32, u32, u8)> = on_gpu
            .chunks_exact(4)
            .zip(&values)
            .map(|(level, &v)| (v, bytemuck::pod_read_unaligned(level), linear_to_srgb8(v)))
            .filter(|&(_, gpu, host)| gpu != u32::from(host))
            .collect();
        assert!(off.is_empty(), "(radiance, GPU level, host level): {off:?}");
    }

    #[test]
    fn totals_are_64_bit() {
        let bytes: Vec<u8> = bytemuck::cast_slice(&[7u32, 0, u32::MAX, 2]).to_vec();
        assert_eq!(
            parse_totals(&bytes),
            vec![7, u64::from(u32::MAX) | (2 << 32)]
        );
    }
}
