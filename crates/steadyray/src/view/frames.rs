//! Where the window's frames come from and how they reach the GPU: the GPU renderer leaves
//! its tone-mapped frame in a GPU buffer (no readback); the CPU renderer's frame and
//! playback's PNGs are uploaded into one each frame.

use anyhow::Result;
use steadyray_render::{Presented, Renderer, TemporalSettings};
use steadyray_render_cpu::CpuRenderer;
use steadyray_render_gpu::{DisplayImage, GpuRenderer};
use steadyray_scene::{Camera, Scene};

/// A storage buffer that RGBA8 images are written into from the host; grows as needed.
pub struct Upload {
    buffer: wgpu::Buffer,
    size: (u32, u32),
}

impl Upload {
    /// An empty upload buffer on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            buffer: Self::allocate(device, 4),
            size: (1, 1),
        }
    }

    fn allocate(device: &wgpu::Device, bytes: u64) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("uploaded frame"),
            size: bytes.next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Uploads a `width × height` RGBA8 sRGB image.
    pub fn write(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        width: u32,
        height: u32,
        rgba: &[u8],
    ) {
        let bytes = rgba.len() as u64;
        if bytes > self.buffer.size() {
            self.buffer = Self::allocate(device, bytes);
        }
        queue.write_buffer(&self.buffer, 0, rgba);
        self.size = (width, height);
    }

    /// Uploads the picture the CPU renderer handed over.
    fn presented(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        presented: Presented,
    ) -> DisplayImage<'_> {
        if let Presented::Host(picture) = presented {
            self.write(device, queue, picture.width, picture.height, &picture.rgba);
        }
        self.image()
    }

    /// The last uploaded image.
    pub fn image(&self) -> DisplayImage<'_> {
        DisplayImage {
            buffer: &self.buffer,
            width: self.size.0,
            height: self.size.1,
        }
    }
}

/// The live renderer of the view.
pub enum LiveRenderer {
    /// Renders on the window's device; frames stay on the GPU.
    Gpu(Box<GpuRenderer>),
    /// Renders on the CPU; frames are uploaded.
    Cpu {
        renderer: Box<CpuRenderer>,
        upload: Upload,
    },
}

impl LiveRenderer {
    /// The renderer as the [`Renderer`] trait.
    pub fn renderer(&mut self) -> &mut dyn Renderer {
        match self {
            LiveRenderer::Gpu(r) => r.as_mut(),
            LiveRenderer::Cpu { renderer, .. } => renderer.as_mut(),
        }
    }

    /// "gpu on ..." or "cpu on ...", for the HUD.
    pub fn describe(&mut self) -> String {
        let info = self.renderer().info();
        format!("{} on {}", info.backend, info.device)
    }

    /// Prepares `scene`.
    pub fn load_scene(&mut self, scene: &Scene) -> Result<()> {
        Ok(self.renderer().load_scene(scene)?)
    }

    /// Turns the temporal mode on with a new history, or off.
    pub fn set_temporal(&mut self, temporal: Option<TemporalSettings>) -> Result<()> {
        Ok(self.renderer().set_temporal(temporal)?)
    }

    /// The last frame as the display shows it (`Renderer::present`: the temporal history
    /// sharpened where it was resampled, then tone-mapped), where the present pass can read
    /// it.
    pub fn image(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<DisplayImage<'_>> {
        match self {
            LiveRenderer::Gpu(r) => Ok(r.display_image()?),
            LiveRenderer::Cpu { renderer, upload } => {
                let presented = renderer.present()?;
                Ok(upload.presented(device, queue, presented))
            }
        }
    }

    /// The last frame shown again as `camera` sees it, for a refresh without a new frame
    /// (`Renderer::present_warped`), where the present pass can read it.
    pub fn warped(
        &mut self,
        camera: &Camera,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<DisplayImage<'_>> {
        match self {
            LiveRenderer::Gpu(r) => {
                r.present_warped(camera)?;
                Ok(r.display_image()?)
            }
            LiveRenderer::Cpu { renderer, upload } => {
                let presented = renderer.present_warped(camera)?;
                Ok(upload.presented(device, queue, presented))
            }
        }
    }
}
