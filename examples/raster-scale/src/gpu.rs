//! The raster engine: a window surface, the heavy pass into an offscreen texture at the
//! render scale, and the upscale onto the window. [`Gpu::frame`] draws and presents one
//! frame and returns its measured time.

use crate::timer::{TimeSource, Timestamps, frame_ms};
use anyhow::{Context, Result, bail};
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;
use std::time::Instant;
use winit::window::Window;

/// The offscreen texture's format (the heavy pass writes linear colour).
const OFFSCREEN: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The uniform of `heavy.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct HeavyUniform {
    iterations: u32,
    time_s: f32,
    size: [f32; 2],
}

/// The uniform of `blit.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct BlitUniform {
    region: [f32; 2],
    limit: [f32; 2],
}

/// One frame as drawn: its time, where the time came from, and the heavy pass's pixels.
#[derive(Clone, Copy, Debug)]
pub struct Drawn {
    /// The frame's time, ms.
    pub ms: f64,
    /// Whether it came from timestamps or the wall clock.
    pub source: TimeSource,
    /// Pixels the heavy pass shaded (the scaled size).
    pub pixels: u64,
}

/// The device, the window's surface and the two passes.
pub struct Gpu {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    device: wgpu::Device,
    queue: wgpu::Queue,
    heavy: wgpu::RenderPipeline,
    heavy_uniform: wgpu::Buffer,
    heavy_group: wgpu::BindGroup,
    blit: wgpu::RenderPipeline,
    blit_uniform: wgpu::Buffer,
    blit_group: wgpu::BindGroup,
    offscreen: wgpu::TextureView,
    timestamps: Option<Timestamps>,
    /// The adapter, as the summary names it.
    pub adapter: String,
}

impl Gpu {
    /// Opens a device that can present to `window` and builds the passes for its size.
    pub fn new(instance: &wgpu::Instance, window: Arc<Window>) -> Result<Self> {
        let size = window.inner_size();
        let surface = instance
            .create_surface(window)
            .context("cannot create a GPU surface for the window")?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            compatible_surface: Some(&surface),
            force_fallback_adapter: false,
            apply_limit_buckets: false,
        }))
        .context("no GPU adapter can present to this window (install a Vulkan driver, e.g. mesa-vulkan-drivers)")?;
        let info = adapter.get_info();
        let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("raster-scale"),
            required_features: features,
            ..Default::default()
        }))
        .with_context(|| format!("cannot open a device on {}", info.name))?;
        let mut config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .context("the adapter cannot present to this window")?;
        config.present_mode = wgpu::PresentMode::AutoNoVsync;
        surface.configure(&device, &config);
        let timestamps = Timestamps::new(&device, &queue);
        let passes = Passes::new(&device, config.format, (config.width, config.height));
        Ok(Self {
            surface,
            config,
            adapter: format!("{} ({})", info.name, info.backend.to_str()),
            heavy: passes.heavy,
            heavy_uniform: passes.heavy_uniform,
            heavy_group: passes.heavy_group,
            blit: passes.blit,
            blit_uniform: passes.blit_uniform,
            blit_group: passes.blit_group,
            offscreen: passes.offscreen,
            timestamps,
            device,
            queue,
        })
    }

    /// The window's size in pixels (the full-resolution size of the heavy pass).
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Draws a frame at render scale `scale` with `iterations` fractal steps per pixel and
    /// presents it; None when the window had no image to give (the frame is not drawn).
    pub fn frame(&mut self, scale: f32, iterations: u32, time_s: f32) -> Result<Option<Drawn>> {
        let Some(target) = self.acquire()? else {
            return Ok(None);
        };
        let (width, height) = self.size();
        let scaled = scaled_size((width, height), scale);
        self.queue.write_buffer(
            &self.heavy_uniform,
            0,
            bytemuck::bytes_of(&HeavyUniform {
                iterations,
                time_s,
                size: [scaled.0 as f32, scaled.1 as f32],
            }),
        );
        let region = [
            scaled.0 as f32 / width as f32,
            scaled.1 as f32 / height as f32,
        ];
        self.queue.write_buffer(
            &self.blit_uniform,
            0,
            bytemuck::bytes_of(&BlitUniform {
                region,
                limit: [
                    region[0] - 0.5 / width as f32,
                    region[1] - 0.5 / height as f32,
                ],
            }),
        );
        let view = target.texture.create_view(&Default::default());
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        self.record_heavy(&mut encoder, scaled);
        self.record_blit(&mut encoder, &view);
        if let Some(t) = &self.timestamps {
            t.resolve(&mut encoder);
        }
        let start = Instant::now();
        self.queue.submit([encoder.finish()]);
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .context("waiting for the GPU failed")?;
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        self.queue.present(target);
        let gpu_ms = self
            .timestamps
            .as_ref()
            .and_then(|t| t.read_ms(&self.device));
        let (ms, source) = frame_ms(gpu_ms, wall_ms);
        Ok(Some(Drawn {
            ms,
            source,
            pixels: u64::from(scaled.0) * u64::from(scaled.1),
        }))
    }

    /// The window's next image, or None (after reconfiguring) when it has none to give.
    fn acquire(&mut self) -> Result<Option<wgpu::SurfaceTexture>> {
        Ok(match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) => Some(t),
            wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                drop(t);
                self.surface.configure(&self.device, &self.config);
                None
            }
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.surface.configure(&self.device, &self.config);
                None
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => None,
            wgpu::CurrentSurfaceTexture::Lost => bail!("the window's surface was lost"),
            wgpu::CurrentSurfaceTexture::Validation => {
                bail!("the window's surface refused to give an image (validation error)")
            }
        })
    }

    fn record_heavy(&self, encoder: &mut wgpu::CommandEncoder, scaled: (u32, u32)) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("heavy"),
            color_attachments: &[Some(attachment(&self.offscreen))],
            depth_stencil_attachment: None,
            timestamp_writes: self.timestamps.as_ref().map(Timestamps::begin),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_viewport(0.0, 0.0, scaled.0 as f32, scaled.1 as f32, 0.0, 1.0);
        pass.set_pipeline(&self.heavy);
        pass.set_bind_group(0, &self.heavy_group, &[]);
        pass.draw(0..3, 0..1);
    }

    fn record_blit(&self, encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("upscale"),
            color_attachments: &[Some(attachment(view))],
            depth_stencil_attachment: None,
            timestamp_writes: self.timestamps.as_ref().map(Timestamps::end),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.blit);
        pass.set_bind_group(0, &self.blit_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// The heavy pass's size at render scale `scale`: each side rounded, at least one pixel.
pub fn scaled_size((width, height): (u32, u32), scale: f32) -> (u32, u32) {
    let side = |n: u32| ((n as f32 * scale).round() as u32).clamp(1, n.max(1));
    (side(width), side(height))
}

fn attachment(view: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            store: wgpu::StoreOp::Store,
        },
    }
}

/// The pipelines, uniforms, bindings and offscreen texture, built once.
struct Passes {
    heavy: wgpu::RenderPipeline,
    heavy_uniform: wgpu::Buffer,
    heavy_group: wgpu::BindGroup,
    blit: wgpu::RenderPipeline,
    blit_uniform: wgpu::Buffer,
    blit_group: wgpu::BindGroup,
    offscreen: wgpu::TextureView,
}

impl Passes {
    fn new(device: &wgpu::Device, format: wgpu::TextureFormat, size: (u32, u32)) -> Self {
        let offscreen = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("offscreen"),
                size: wgpu::Extent3d {
                    width: size.0,
                    height: size.1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: OFFSCREEN,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default());
        let heavy_uniform = uniform_buffer(device, "heavy", size_of::<HeavyUniform>());
        let blit_uniform = uniform_buffer(device, "blit", size_of::<BlitUniform>());
        let heavy = pipeline(device, "heavy", include_str!("heavy.wgsl"), OFFSCREEN);
        let blit = pipeline(device, "blit", include_str!("blit.wgsl"), format);
        let heavy_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("heavy"),
            layout: &heavy.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: heavy_uniform.as_entire_binding(),
            }],
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("upscale"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let blit_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("blit"),
            layout: &blit.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: blit_uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&offscreen),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
            ],
        });
        Self {
            heavy,
            heavy_uniform,
            heavy_group,
            blit,
            blit_uniform,
            blit_group,
            offscreen,
        }
    }
}

fn uniform_buffer(device: &wgpu::Device, label: &str, size: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A full-screen-triangle pipeline from `source` (entry points `vs_main`, `fs_main`) with its
/// bind group layout taken from the shader.
fn pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        multiview_mask: None,
        cache: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_sizes_round_and_stay_inside_the_window() {
        assert_eq!(scaled_size((640, 360), 1.0), (640, 360));
        assert_eq!(scaled_size((640, 360), 0.5), (320, 180));
        assert_eq!(scaled_size((640, 360), 0.0), (1, 1));
        assert_eq!(scaled_size((640, 360), 2.0), (640, 360));
    }
}
