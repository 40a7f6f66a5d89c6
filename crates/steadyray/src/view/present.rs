//! The present pass: a frame's packed RGBA8 image, read straight from its GPU buffer, drawn
//! over a target with nearest-pixel upscaling (`present.wgsl`). Built once; a new image
//! size, buffer or window size only rewrites a uniform or rebuilds a bind group.

use bytemuck::{Pod, Zeroable};
use steadyray_render_gpu::DisplayImage;

/// The uniform of `present.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
struct PresentUniform {
    image_size: [u32; 2],
    target_size: [u32; 2],
}

/// The pipeline and its bindings.
pub struct PresentPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    /// The bind group over the image buffer last drawn, rebuilt when the buffer changes.
    bound: Option<(wgpu::Buffer, wgpu::BindGroup)>,
}

impl PresentPass {
    /// Builds the pass for targets of `format` (a non-sRGB format).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("present"),
            source: wgpu::ShaderSource::Wgsl(include_str!("present.wgsl").into()),
        });
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("present"),
            entries: &[
                entry(0, wgpu::BufferBindingType::Uniform),
                entry(1, wgpu::BufferBindingType::Storage { read_only: true }),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("present"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("present"),
            layout: Some(&pipeline_layout),
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
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("present uniform"),
            size: size_of::<PresentUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            pipeline,
            layout,
            uniform,
            bound: None,
        }
    }

    /// Sets the image and target size of the next draws (before the encoder is submitted).
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        image: &DisplayImage<'_>,
        target_size: [u32; 2],
    ) {
        let uniform = PresentUniform {
            image_size: [image.width, image.height],
            target_size,
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        if self.bound.as_ref().is_none_or(|(b, _)| b != image.buffer) {
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("present"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.uniform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: image.buffer.as_entire_binding(),
                    },
                ],
            });
            self.bound = Some((image.buffer.clone(), bind_group));
        }
    }

    /// Draws the prepared image over all of `pass`'s target.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        if let Some((_, bind_group)) = &self.bound {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}
