//! A frame's samples per pixel split over several dispatches of the integrator.
//!
//! Each invocation of the integrator traces one pixel's samples in a loop; at a high S that
//! is one long invocation. Lavapipe ends an invocation's loops after 65,535 iterations in all
//! (a guard against hangs in its shader compiler), and a glass pixel of the corridor at
//! R = 16 reaches that after about 124 samples: the rest came back black. Other drivers stop
//! a dispatch that runs for seconds (a reference at S = 1024 and 4K on a small GPU). So a
//! frame's samples go in dispatches of at most [`SampleRanges::per_dispatch`] samples a
//! pixel, each continuing the pixel's sum where the last one left it in the image buffer:
//! the sum is added in the same order as in one dispatch, and the picture keeps its bits.

use crate::layout::GpuSampleRange;
use steadyray_render::MAX_SPP;

/// Samples a pixel per dispatch on a software adapter: a glass pixel's bounces and BVH
/// walks for 16 samples stay far inside lavapipe's 65,535 loop iterations an invocation
/// (about 8,500 on the corridor at R = 16).
const SOFTWARE_SAMPLES_PER_DISPATCH: u32 = 16;

/// Samples a pixel per dispatch on a hardware adapter: above every S the controllers ran on
/// the GPUs measured (frames stay one dispatch), so only references are split.
const HARDWARE_SAMPLES_PER_DISPATCH: u32 = 256;

/// The bind group layout of the integrator's group 1: one [`GpuSampleRange`] at a dynamic
/// offset.
pub(crate) fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sample range"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(size_of::<GpuSampleRange>() as u64),
            },
            count: None,
        }],
    })
}

/// Every dispatch's [`GpuSampleRange`] up to [`MAX_SPP`], written once, one per aligned
/// slot of a uniform buffer, and the bind group that selects one by its offset.
pub(crate) struct SampleRanges {
    bind_group: wgpu::BindGroup,
    /// Bytes between two slots (the device's uniform offset alignment).
    stride: u32,
    per_dispatch: u32,
}

impl SampleRanges {
    /// The ranges for an adapter, software (`software`) or not.
    pub(crate) fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layout: &wgpu::BindGroupLayout,
        software: bool,
    ) -> Self {
        let per_dispatch = if software {
            SOFTWARE_SAMPLES_PER_DISPATCH
        } else {
            HARDWARE_SAMPLES_PER_DISPATCH
        };
        let range_size = size_of::<GpuSampleRange>() as u32;
        let stride = device
            .limits()
            .min_uniform_buffer_offset_alignment
            .max(range_size);
        let slots = (MAX_SPP as u32).div_ceil(per_dispatch);
        let mut bytes = vec![0u8; (slots * stride) as usize];
        for slot in 0..slots {
            let range = GpuSampleRange {
                first: slot * per_dispatch,
                end: (slot + 1) * per_dispatch,
                ..Default::default()
            };
            let at = (slot * stride) as usize;
            bytes[at..at + range_size as usize].copy_from_slice(bytemuck::bytes_of(&range));
        }
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sample ranges"),
            size: bytes.len() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&buffer, 0, &bytes);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sample ranges"),
            layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(u64::from(range_size)),
                }),
            }],
        });
        Self {
            bind_group,
            stride,
            per_dispatch,
        }
    }

    /// Records the integrator's dispatches of a frame at `spp` samples per pixel (at most
    /// ⌈S⌉ for a pixel) over `groups` workgroups, in `pass` with its pipeline and group 0
    /// set.
    pub(crate) fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>, spp: f32, groups: (u32, u32)) {
        for slot in 0..dispatches(spp, self.per_dispatch) {
            pass.set_bind_group(1, &self.bind_group, &[slot * self.stride]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        }
    }
}

/// Dispatches for a frame at `spp` (its pixels take at most ⌈S⌉ samples) with at most
/// `per_dispatch` samples a pixel in each.
fn dispatches(spp: f32, per_dispatch: u32) -> u32 {
    (spp.ceil() as u32).div_ceil(per_dispatch)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_takes_as_many_dispatches_as_its_most_samples_need() {
        assert_eq!(dispatches(1.0, 16), 1);
        assert_eq!(dispatches(16.0, 16), 1);
        assert_eq!(dispatches(16.5, 16), 2);
        assert_eq!(dispatches(32.0, 16), 2);
        assert_eq!(dispatches(MAX_SPP, 16), 256);
        assert_eq!(dispatches(MAX_SPP, 256), 16);
    }
}
