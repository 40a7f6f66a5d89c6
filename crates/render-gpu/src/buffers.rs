//! GPU buffers that are reused from frame to frame and only grow.

use crate::layout::COUNTER_SLOTS;
use crate::timing::TIMESTAMP_BYTES;
use steadyray_render::tonemap::srgb8_thresholds;
use wgpu::util::DeviceExt;

/// The smallest buffer allocated: one element of any GPU struct of [`crate::layout`].
const MIN_BUFFER_BYTES: u64 = 256;

/// A buffer of fixed usage that is reallocated only when asked to hold more than it can.
pub(crate) struct GrowBuffer {
    label: &'static str,
    usage: wgpu::BufferUsages,
    buffer: wgpu::Buffer,
}

impl GrowBuffer {
    /// A buffer of at least `size` bytes, and at least [`MIN_BUFFER_BYTES`] so that an
    /// empty array can still be bound as an array of the largest element.
    pub(crate) fn new(
        device: &wgpu::Device,
        label: &'static str,
        usage: wgpu::BufferUsages,
        size: u64,
    ) -> Self {
        Self {
            label,
            usage,
            buffer: Self::allocate(device, label, usage, size),
        }
    }

    fn allocate(
        device: &wgpu::Device,
        label: &'static str,
        usage: wgpu::BufferUsages,
        size: u64,
    ) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: size
                .max(MIN_BUFFER_BYTES)
                .next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
            usage,
            mapped_at_creation: false,
        })
    }

    /// Makes room for `size` bytes; returns whether the buffer was replaced (so bind groups
    /// that refer to it must be rebuilt). Contents are not kept.
    pub(crate) fn ensure(&mut self, device: &wgpu::Device, size: u64) -> bool {
        if size <= self.buffer.size() {
            return false;
        }
        self.buffer = Self::allocate(device, self.label, self.usage, size);
        true
    }

    pub(crate) fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Writes `data` at the start, growing first if needed; returns whether it grew.
    pub(crate) fn write(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        data: &[u8],
    ) -> bool {
        let grew = self.ensure(device, data.len() as u64);
        if !data.is_empty() {
            queue.write_buffer(&self.buffer, 0, data);
        }
        grew
    }
}

/// Bytes of the 64-bit ray totals (the most counters a frame can have).
pub(crate) const TOTALS_BYTES: u64 = COUNTER_SLOTS as u64 * 8;

/// The per-frame buffers: outputs, counters and readback staging, grown with the image, and
/// the tone map's table.
pub(crate) struct FrameBuffers {
    /// Linear RGBA f32 per pixel.
    pub(crate) image: GrowBuffer,
    /// Packed RGBA8 per pixel, written by the tone-map pass.
    pub(crate) srgb8: GrowBuffer,
    /// The smallest radiance of each tone-map level 1..=255 ([`srgb8_thresholds`], the
    /// host's own: a device's `pow` may round unlike the host's `powf`), which
    /// the tone-map passes look levels up in.
    pub(crate) srgb8_levels: wgpu::Buffer,
    /// `counter_stride` u32 counters per workgroup.
    pub(crate) group_counts: GrowBuffer,
    /// 64-bit totals per counter.
    pub(crate) totals: wgpu::Buffer,
    /// Readback of the totals, then the two timestamps.
    pub(crate) stats_readback: wgpu::Buffer,
    /// Readback of an image (linear or RGBA8).
    pub(crate) image_readback: GrowBuffer,
    /// In the temporal mode, two `vec4<u32>` geometry words per pixel.
    pub(crate) geometry: GrowBuffer,
}

impl FrameBuffers {
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        use wgpu::BufferUsages as U;
        Self {
            image: GrowBuffer::new(device, "image", U::STORAGE | U::COPY_SRC, 0),
            srgb8: GrowBuffer::new(device, "srgb8 image", U::STORAGE | U::COPY_SRC, 0),
            srgb8_levels: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("srgb8 levels"),
                contents: bytemuck::cast_slice(srgb8_thresholds()),
                usage: U::STORAGE,
            }),
            group_counts: GrowBuffer::new(
                device,
                "workgroup ray counts",
                U::STORAGE | U::COPY_DST,
                0,
            ),
            totals: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ray totals"),
                size: TOTALS_BYTES,
                usage: U::STORAGE | U::COPY_SRC,
                mapped_at_creation: false,
            }),
            stats_readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame stats readback"),
                size: TOTALS_BYTES + TIMESTAMP_BYTES,
                usage: U::MAP_READ | U::COPY_DST,
                mapped_at_creation: false,
            }),
            image_readback: GrowBuffer::new(device, "image readback", U::MAP_READ | U::COPY_DST, 0),
            geometry: GrowBuffer::new(device, "pixel geometry", U::STORAGE, 0),
        }
    }

    /// Makes room for a frame of `pixels` pixels and `counters` workgroup counters, with
    /// geometry records when `temporal`, and for tone-mapping `shown` pixels; returns whether
    /// a bound buffer was replaced.
    pub(crate) fn ensure(
        &mut self,
        device: &wgpu::Device,
        pixels: u64,
        counters: u64,
        temporal: bool,
        shown: u64,
    ) -> bool {
        let grew = [
            self.image.ensure(device, pixels * 16),
            self.srgb8.ensure(device, shown * 4),
            self.group_counts.ensure(device, counters * 4),
            temporal && self.geometry.ensure(device, pixels * 32),
        ];
        grew.contains(&true)
    }
}
