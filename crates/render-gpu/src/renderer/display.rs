//! Showing frames in a window without readback: the renderer opens its device on an adapter
//! the window chose (so both share one device), and tone-maps each frame into its packed
//! RGBA8 buffer, which a present pass on the same device reads directly.

use super::{GpuRenderer, LastFrame, Shown};
use crate::device::GpuContext;
use crate::error::scoped;
use crate::layout::WORKGROUP_SIZE;
use steadyray_render::RenderError;

/// The last frame (or a warped refresh of it), tone-mapped on the GPU and left there.
#[derive(Clone, Copy, Debug)]
pub struct DisplayImage<'a> {
    /// `width × height` packed RGBA8 texels (`u32`, R in the low byte, A = 255), row-major,
    /// top row first, in sRGB: the bytes [`GpuRenderer::read_srgb8`] returns. Usable as a
    /// read-only storage buffer; it may be larger than the image and is replaced when a
    /// larger frame is rendered.
    pub buffer: &'a wgpu::Buffer,
    /// The image's width, pixels.
    pub width: u32,
    /// The image's height, pixels.
    pub height: u32,
}

impl GpuRenderer {
    /// Notes that the last frame's tone map was submitted without error (or skipped, a
    /// warped refresh of it being on display, which stays): until the next frame, showing
    /// or reading it needs no pass.
    pub(super) fn mark_tone_mapped(&mut self) {
        if let Some(last) = &mut self.last_frame
            && last.shown == Shown::Nothing
        {
            last.shown = Shown::Frame;
        }
    }

    /// Opens the renderer on `adapter`, e.g. the one [`crate::surface_adapter`] chose for a
    /// window, so that the window's present pass can share [`Self::device`].
    pub fn with_adapter(adapter: &wgpu::Adapter) -> Result<Self, RenderError> {
        Self::from_context(GpuContext::open(adapter)?)
    }

    /// The device the renderer runs on.
    pub fn device(&self) -> &wgpu::Device {
        &self.ctx.device
    }

    /// The queue the renderer submits to; work submitted to it later sees its frames.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.ctx.queue
    }

    /// Tone-maps the last frame into its RGBA8 buffer on the GPU and returns that buffer,
    /// without waiting: passes submitted afterwards to [`Self::queue`] read the finished
    /// image. After [`steadyray_render::Renderer::present_warped`] the buffer holds the
    /// warped picture, which is returned as it is until the next frame or
    /// [`steadyray_render::Renderer::present`].
    pub fn display_image(&mut self) -> Result<DisplayImage<'_>, RenderError> {
        let last = self.last_frame.ok_or(RenderError::NoFrame)?;
        let mut encoder = self.ctx.encoder("tonemap for display");
        self.encode_tonemap(&mut encoder, last);
        let device = &self.ctx.device;
        let commands = scoped(device, "cannot record the tone map", || encoder.finish())?;
        scoped(device, "GPU submission failed", || {
            self.ctx.queue.submit([commands]);
        })?;
        self.ctx.errors.check()?;
        self.mark_tone_mapped();
        Ok(DisplayImage {
            buffer: self.frame_buffers.srgb8.buffer(),
            width: last.width,
            height: last.height,
        })
    }

    /// Records the tone-map pass of the last frame (linear image, or the temporal history,
    /// to packed RGBA8), unless the buffer already holds its picture or a warp of it.
    pub(super) fn encode_tonemap(&mut self, encoder: &mut wgpu::CommandEncoder, last: LastFrame) {
        if last.shown != Shown::Nothing {
            return;
        }
        if last.temporal {
            self.temporal.encode_tonemap(encoder);
            return;
        }
        let (width, height) = (last.width, last.height);
        let bind_group = self.bind_group();
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("tonemap"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipelines.tonemap);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(
            width.div_ceil(WORKGROUP_SIZE),
            height.div_ceil(WORKGROUP_SIZE),
            1,
        );
    }
}
