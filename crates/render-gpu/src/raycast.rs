//! [`GpuRayCaster`]: closest-hit ray casting through a mesh's BVH on the GPU and nothing
//! else (no shading), timed by GPU timestamps: the GPU side of `steadyray raybench`.
//!
//! The kernels (`shaders/raycast.wgsl`) share the watertight triangle test and the BVH
//! traversal with the renderer (`shaders/traversal.wgsl`), so they find exactly the hits of
//! [`Bvh::closest`] where the driver rounds as the CPU does (lavapipe; the tests check it).
//!
//! Primary rays are generated in the kernel from the camera frame, by the renderer's
//! `pixel_ray_dir` (`shaders/camera.wgsl`), which repeats
//! `CameraFrame::ray_dir(px, py, 0.5, 0.5, w, h)` operation for operation: the same
//! directions, bit for bit, unless the driver fuses a multiply and an add into one rounding
//! (hardware drivers may, WGSL allows it), in which case a direction may differ in its last
//! bit and a grazing ray may hit differently. Uploading the primary rays instead would cost a
//! 32-byte read per ray in the timed kernel and is what [`GpuRayCaster::cast_rays`] does for
//! callers that need the CPU's exact rays.

use crate::adapter::{AdapterSummary, GpuOptions};
use crate::buffers::GrowBuffer;
use crate::device::GpuContext;
use crate::error::{gpu_error, scoped};
use crate::layout::{CAST_MISS, CAST_TILE, GpuCastHit, GpuCastParams, GpuCastRay, GpuTriangle};
use crate::pipeline::{
    RAYCAST_SOURCE, buffer_entry, compute_pipeline, layout_entry, shader_module,
};
use crate::timing::{GpuTimer, TIMESTAMP_BYTES};
use glam::Vec3;
use std::time::{Duration, Instant};
use steadyray_accel::Bvh;
use steadyray_render::{RenderError, TimingSource};
use steadyray_scene::camera::CameraFrame;

/// Bindings of the ray caster's group 0, as declared in `shaders/raycast.wgsl`.
mod binding {
    pub const PARAMS: u32 = 0;
    pub const TRIANGLES: u32 = 1;
    pub const BVH_NODES: u32 = 2;
    pub const RAYS: u32 = 3;
    pub const HITS: u32 = 4;
    pub const NEXT_BLOCK: u32 = 5;
}

/// The persistent workgroups launched per dispatch (fewer when there are fewer blocks of
/// `CAST_TILE`² rays): 262,144 threads, about as many as the largest GPUs hold at once (an
/// H100 holds 270,336), so that each thread pays WGSL's zeroing of its traversal stack once
/// and then casts ray after ray, its workgroup taking the next block as it finishes one.
const PERSISTENT_GROUPS: u32 = 4096;

/// Untimed dispatches run before the timed ones until this much time has passed (at least
/// one): pipeline and cache warm-up, and GPU clocks ramping up.
const WARM_UP: Duration = Duration::from_millis(50);

impl GpuCastRay {
    /// The ray `origin + t·dir`.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin: origin.to_array(),
            dir: dir.to_array(),
            ..Default::default()
        }
    }
}

/// What one batch of casts found and measured.
#[derive(Clone, Debug, PartialEq)]
pub struct CastOutcome {
    /// Per ray (row-major pixels for [`GpuRayCaster::cast_primary`], the order given for
    /// [`GpuRayCaster::cast_rays`]): its closest hit as (t, input triangle index), as
    /// [`Bvh::closest`] returns it, or None for a miss.
    pub hits: Vec<Option<(f32, u32)>>,
    /// The time of each timed dispatch in milliseconds: the kernel alone (no upload or
    /// readback) by GPU timestamps, or submit-to-finish host time (see `timing`).
    pub times_ms: Vec<f64>,
    /// [`TimingSource::GpuTimestamps`] when every timed dispatch had plausible timestamps,
    /// else [`TimingSource::WallClock`] for all of them.
    pub timing: TimingSource,
}

/// Which kernel a batch runs.
#[derive(Clone, Copy, Debug)]
enum Kernel {
    Primary,
    List,
}

/// One mesh and its BVH on the GPU, uploaded once, and the two casting kernels: rays from a
/// camera through every pixel centre ([`GpuRayCaster::cast_primary`]) and rays from a list
/// ([`GpuRayCaster::cast_rays`]). Each batch runs untimed warm-up dispatches, then `reps`
/// dispatches, each timed on its own, then reads the hits back once.
pub struct GpuRayCaster {
    ctx: GpuContext,
    bind_group_layout: wgpu::BindGroupLayout,
    primary: wgpu::ComputePipeline,
    list: wgpu::ComputePipeline,
    timer: Option<GpuTimer>,
    params: wgpu::Buffer,
    /// The triangles in BVH leaf order, each with its input index as `id`.
    triangles: GrowBuffer,
    bvh_nodes: GrowBuffer,
    rays: GrowBuffer,
    hits: GrowBuffer,
    hits_readback: GrowBuffer,
    /// The kernels' block counter, zeroed before each dispatch.
    next_block: wgpu::Buffer,
    /// The two timestamps of the last timed dispatch.
    stamps_readback: wgpu::Buffer,
    /// Refers to the buffers above; dropped whenever one of them is replaced.
    bind_group: Option<wgpu::BindGroup>,
    triangle_count: u32,
}

impl GpuRayCaster {
    /// Opens the adapter `options` choose and uploads `triangles` (corners in world space,
    /// in input order) in the leaf order of `bvh`, built over the same triangles, with its
    /// nodes. Fails with [`RenderError::Gpu`] ("no GPU adapter found (...)") when no adapter
    /// qualifies, and with [`RenderError::Scene`] when `bvh` is not over `triangles` or is too
    /// deep for the GPU traversal's stack.
    pub fn new(
        options: &GpuOptions,
        triangles: &[[Vec3; 3]],
        bvh: &Bvh,
    ) -> Result<Self, RenderError> {
        if bvh.triangle_count() != triangles.len() {
            return Err(RenderError::Scene(format!(
                "the BVH holds {} triangles, the mesh {}",
                bvh.triangle_count(),
                triangles.len()
            )));
        }
        let triangle_count = u32::try_from(triangles.len())
            .map_err(|_| RenderError::Scene(format!("too many triangles: {}", triangles.len())))?;
        let nodes = bvh
            .gpu_nodes()
            .map_err(|e| RenderError::Scene(e.to_string()))?;
        let packed: Vec<GpuTriangle> = bvh
            .leaf_order()
            .iter()
            .map(|&id| {
                let [v0, v1, v2] = triangles[id as usize].map(|v| v.to_array());
                GpuTriangle {
                    v0,
                    v1,
                    v2,
                    id,
                    ..Default::default()
                }
            })
            .collect();
        let ctx = GpuContext::new(options)?;
        let device = &ctx.device;
        check_binding_size(&ctx, "triangle", packed.len() as u64 * 64)?;
        check_binding_size(&ctx, "BVH node", size_of_val(nodes) as u64)?;

        let module = shader_module(device, RAYCAST_SOURCE)?;
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let write = wgpu::BufferBindingType::Storage { read_only: false };
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ray caster bindings"),
            entries: &[
                layout_entry(binding::PARAMS, wgpu::BufferBindingType::Uniform),
                layout_entry(binding::TRIANGLES, read),
                layout_entry(binding::BVH_NODES, read),
                layout_entry(binding::RAYS, read),
                layout_entry(binding::HITS, write),
                layout_entry(binding::NEXT_BLOCK, write),
            ],
        });
        let primary = compute_pipeline(device, &[&bind_group_layout], &module, "cast_primary")?;
        let list = compute_pipeline(device, &[&bind_group_layout], &module, "cast_rays")?;

        use wgpu::BufferUsages as U;
        let storage = U::STORAGE | U::COPY_DST;
        let mut triangles = GrowBuffer::new(device, "cast triangles", storage, 0);
        let mut bvh_nodes = GrowBuffer::new(device, "cast bvh nodes", storage, 0);
        scoped(device, "cannot upload the mesh", || {
            triangles.write(device, &ctx.queue, bytemuck::cast_slice(&packed));
            bvh_nodes.write(device, &ctx.queue, bytemuck::cast_slice(nodes));
        })?;
        let caster = Self {
            bind_group_layout,
            primary,
            list,
            timer: ctx
                .timestamps
                .then(|| GpuTimer::new(device, &ctx.queue))
                .flatten(),
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("cast params"),
                size: size_of::<GpuCastParams>() as u64,
                usage: U::UNIFORM | U::COPY_DST,
                mapped_at_creation: false,
            }),
            triangles,
            bvh_nodes,
            rays: GrowBuffer::new(device, "cast rays", storage, 0),
            hits: GrowBuffer::new(device, "cast hits", U::STORAGE | U::COPY_SRC, 0),
            hits_readback: GrowBuffer::new(
                device,
                "cast hits readback",
                U::MAP_READ | U::COPY_DST,
                0,
            ),
            next_block: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("cast block counter"),
                size: 4,
                usage: U::STORAGE | U::COPY_DST,
                mapped_at_creation: false,
            }),
            stamps_readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("cast timestamps readback"),
                size: TIMESTAMP_BYTES,
                usage: U::MAP_READ | U::COPY_DST,
                mapped_at_creation: false,
            }),
            bind_group: None,
            triangle_count,
            ctx,
        };
        caster.ctx.wait()?;
        Ok(caster)
    }

    /// The adapter the caster runs on.
    pub fn adapter(&self) -> &AdapterSummary {
        &self.ctx.adapter
    }

    /// The device as the renderer describes it: adapter name, graphics API and driver.
    pub fn device_description(&self) -> String {
        self.ctx.description()
    }

    /// Casts one ray through the centre of each pixel of a `width` × `height` image from
    /// camera `frame` (made for that size: `Camera::frame(width, height)`), `reps` timed
    /// times after the warm-up. The hits are row-major, top row first.
    pub fn cast_primary(
        &mut self,
        frame: &CameraFrame,
        width: u32,
        height: u32,
        reps: u32,
    ) -> Result<CastOutcome, RenderError> {
        if width == 0 || height == 0 || reps == 0 {
            return Err(RenderError::Gpu(
                "cast_primary needs at least one pixel and one repetition".to_string(),
            ));
        }
        let rays = u64::from(width) * u64::from(height);
        let (tiles_x, tiles_y) = (width.div_ceil(CAST_TILE), height.div_ceil(CAST_TILE));
        let params = GpuCastParams {
            eye: frame.eye.to_array(),
            half_width: frame.half_width,
            forward: frame.forward.to_array(),
            half_height: frame.half_height,
            right: frame.right.to_array(),
            width,
            true_up: frame.true_up.to_array(),
            height,
            tiles_x,
            tile_count: tiles_x * tiles_y,
            ray_count: 0,
            triangle_count: self.triangle_count,
        };
        self.run(Kernel::Primary, &params, rays, reps)
    }

    /// Casts `rays` for their closest hits, `reps` timed times after the warm-up; the hits
    /// come in the order of `rays`.
    pub fn cast_rays(
        &mut self,
        rays: &[GpuCastRay],
        reps: u32,
    ) -> Result<CastOutcome, RenderError> {
        if reps == 0 {
            return Err(RenderError::Gpu(
                "cast_rays needs at least one repetition".to_string(),
            ));
        }
        let ray_count = u32::try_from(rays.len())
            .map_err(|_| gpu_error("too many rays for one batch", rays.len()))?;
        check_binding_size(&self.ctx, "ray", rays.len() as u64 * 32)?;
        let device = &self.ctx.device;
        let grew = scoped(device, "cannot upload the rays", || {
            self.rays
                .write(device, &self.ctx.queue, bytemuck::cast_slice(rays))
        })?;
        if grew {
            self.bind_group = None;
        }
        let params = GpuCastParams {
            ray_count,
            triangle_count: self.triangle_count,
            ..Default::default()
        };
        self.run(Kernel::List, &params, u64::from(ray_count), reps)
    }

    /// Runs `kernel` over `rays` rays with `params`: warm-up, `reps` timed dispatches, then
    /// the readback of the hits.
    fn run(
        &mut self,
        kernel: Kernel,
        params: &GpuCastParams,
        rays: u64,
        reps: u32,
    ) -> Result<CastOutcome, RenderError> {
        self.ctx.errors.check()?;
        let hit_bytes = rays * size_of::<GpuCastHit>() as u64;
        check_binding_size(&self.ctx, "hit", hit_bytes)?;
        let device = &self.ctx.device;
        if self.hits.ensure(device, hit_bytes) {
            self.bind_group = None;
        }
        self.hits_readback.ensure(device, hit_bytes);
        self.ctx
            .queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(params));
        let blocks = match kernel {
            Kernel::Primary => params.tile_count,
            Kernel::List => params.ray_count.div_ceil(CAST_TILE * CAST_TILE),
        };
        let groups = blocks.clamp(1, PERSISTENT_GROUPS);
        let bind_group = self.bind_group();
        let pipeline = match kernel {
            Kernel::Primary => &self.primary,
            Kernel::List => &self.list,
        };

        let warm_up = Instant::now();
        loop {
            let commands = self.encode_dispatch(pipeline, &bind_group, groups, false)?;
            self.ctx.submit_and_wait(commands)?;
            if warm_up.elapsed() >= WARM_UP {
                break;
            }
        }
        let mut stamped = Vec::with_capacity(reps as usize);
        let mut wall = Vec::with_capacity(reps as usize);
        for _ in 0..reps {
            let commands = self.encode_dispatch(pipeline, &bind_group, groups, true)?;
            let start = Instant::now();
            self.ctx.submit_and_wait(commands)?;
            let wall_ms = start.elapsed().as_secs_f64() * 1e3;
            wall.push(wall_ms);
            stamped.push(match &self.timer {
                Some(timer) => {
                    let bytes = self
                        .ctx
                        .read_buffer(&self.stamps_readback, TIMESTAMP_BYTES)?;
                    // A kernel cannot take longer than its submission took on the host.
                    timer.elapsed_ms(&bytes).filter(|&ms| ms <= wall_ms)
                }
                None => None,
            });
        }
        let (times_ms, timing) = match stamped.into_iter().collect::<Option<Vec<f64>>>() {
            Some(times) => (times, TimingSource::GpuTimestamps),
            None => (wall, TimingSource::WallClock),
        };
        Ok(CastOutcome {
            hits: self.read_hits(hit_bytes)?,
            times_ms,
            timing,
        })
    }

    /// One dispatch of `pipeline` over `groups` workgroups, with the timestamps around its
    /// pass copied to the readback buffer when `timed` and the device has them.
    fn encode_dispatch(
        &self,
        pipeline: &wgpu::ComputePipeline,
        bind_group: &wgpu::BindGroup,
        groups: u32,
        timed: bool,
    ) -> Result<wgpu::CommandBuffer, RenderError> {
        let timer = self.timer.as_ref().filter(|_| timed);
        let mut encoder = self.ctx.encoder("cast");
        encoder.clear_buffer(&self.next_block, 0, None);
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("cast"),
                timestamp_writes: timer.map(GpuTimer::pass_writes),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.dispatch_workgroups(groups, 1, 1);
        }
        if let Some(timer) = timer {
            timer.resolve(&mut encoder, &self.stamps_readback, 0);
        }
        scoped(&self.ctx.device, "cannot record the cast", || {
            encoder.finish()
        })
    }

    /// Copies the first `bytes` of the hits out and decodes them.
    fn read_hits(&self, bytes: u64) -> Result<Vec<Option<(f32, u32)>>, RenderError> {
        if bytes == 0 {
            return Ok(Vec::new());
        }
        let mut encoder = self.ctx.encoder("read hits");
        encoder.copy_buffer_to_buffer(self.hits.buffer(), 0, self.hits_readback.buffer(), 0, bytes);
        let commands = scoped(&self.ctx.device, "cannot record the hit readback", || {
            encoder.finish()
        })?;
        self.ctx.submit_and_wait(commands)?;
        let raw = self.ctx.read_buffer(self.hits_readback.buffer(), bytes)?;
        Ok(raw
            .chunks_exact(size_of::<GpuCastHit>())
            .map(|chunk| {
                let hit: GpuCastHit = bytemuck::pod_read_unaligned(chunk);
                (hit.id != CAST_MISS).then_some((hit.t, hit.id))
            })
            .collect())
    }

    /// The bind group over the current buffers, rebuilt if one was replaced.
    fn bind_group(&mut self) -> wgpu::BindGroup {
        let bind_group = self.bind_group.get_or_insert_with(|| {
            self.ctx
                .device
                .create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("ray caster bindings"),
                    layout: &self.bind_group_layout,
                    entries: &[
                        buffer_entry(binding::PARAMS, &self.params),
                        buffer_entry(binding::TRIANGLES, self.triangles.buffer()),
                        buffer_entry(binding::BVH_NODES, self.bvh_nodes.buffer()),
                        buffer_entry(binding::RAYS, self.rays.buffer()),
                        buffer_entry(binding::HITS, self.hits.buffer()),
                        buffer_entry(binding::NEXT_BLOCK, &self.next_block),
                    ],
                })
        });
        bind_group.clone()
    }
}

/// Fails when a `bytes`-byte storage buffer of `what`s exceeds the device's binding limits.
fn check_binding_size(ctx: &GpuContext, what: &str, bytes: u64) -> Result<(), RenderError> {
    let limits = ctx.device.limits();
    let max = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    if bytes > max {
        return Err(gpu_error(
            "too large for this GPU",
            format!("the {what} buffer needs {bytes} bytes; the device binds at most {max}"),
        ));
    }
    Ok(())
}
