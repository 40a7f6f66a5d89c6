//! The window's surface and what draws on it: the present pass (the frame) and egui (the
//! HUD), on the device the frames were made on. A resize reconfigures the surface only.

use super::capture::{PendingCapture, Screenshot, capture_texture};
use super::present::PresentPass;
use anyhow::{Context, Result, bail};
use steadyray_render_gpu::DisplayImage;

/// How frames are presented (`--present`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PresentChoice {
    /// Wait for vertical blank (vsync), never tear.
    Fifo,
    /// Replace the queued frame with the newest, no tearing (where supported).
    Mailbox,
    /// Present at once, may tear (where supported).
    Immediate,
}

impl PresentChoice {
    fn mode(self) -> wgpu::PresentMode {
        match self {
            PresentChoice::Fifo => wgpu::PresentMode::Fifo,
            PresentChoice::Mailbox => wgpu::PresentMode::Mailbox,
            PresentChoice::Immediate => wgpu::PresentMode::Immediate,
        }
    }
}

/// The HUD of one frame, tessellated by egui.
pub struct UiFrame {
    pub paint_jobs: Vec<egui::ClippedPrimitive>,
    pub textures: egui::TexturesDelta,
    pub pixels_per_point: f32,
}

/// What drawing a frame came to.
pub enum Drawn {
    /// On screen; with the screenshot when one was asked for.
    Presented(Option<Screenshot>),
    /// The surface had no image to give (minimised, occluded, outdated): nothing drawn.
    Skipped,
}

/// The surface, configured for the window, and the passes that draw on it.
pub struct Screen {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The non-sRGB format the passes render in (the surface's format or a view of it).
    format: wgpu::TextureFormat,
    device: wgpu::Device,
    queue: wgpu::Queue,
    present: PresentPass,
    egui: egui_wgpu::Renderer,
    /// egui's texture changes not applied yet (kept over skipped frames).
    textures: egui::TexturesDelta,
}

impl Screen {
    /// Configures `surface` for a `width × height` window on `device`.
    pub fn new(
        surface: wgpu::Surface<'static>,
        adapter: &wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
        (width, height): (u32, u32),
        present: PresentChoice,
    ) -> Result<Self> {
        let caps = surface.get_capabilities(adapter);
        let mut config = surface
            .get_default_config(adapter, width.max(1), height.max(1))
            .context("the GPU adapter cannot present to this window")?;
        // egui and the present pass write gamma-space bytes: prefer a non-sRGB format, else
        // render through a non-sRGB view of an sRGB one.
        config.format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .unwrap_or(config.format);
        let format = config.format.remove_srgb_suffix();
        if !matches!(
            format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
        ) {
            bail!(
                "the window offers no 8-bit RGBA format (it offers {:?})",
                caps.formats
            );
        }
        if format != config.format {
            config.view_formats = vec![format];
        }
        let wanted = present.mode();
        config.present_mode = if caps.present_modes.contains(&wanted) {
            wanted
        } else {
            log::warn!(
                "present mode {wanted:?} is not supported here (supported: {:?}); using Fifo",
                caps.present_modes
            );
            wgpu::PresentMode::Fifo
        };
        let present = PresentPass::new(&device, format);
        let egui = egui_wgpu::Renderer::new(&device, format, egui_wgpu::RendererOptions::default());
        let screen = Self {
            surface,
            config,
            format,
            device,
            queue,
            present,
            egui,
            textures: egui::TexturesDelta::default(),
        };
        screen.configure();
        Ok(screen)
    }

    /// The window's size in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// The present mode in use.
    pub fn present_mode(&self) -> wgpu::PresentMode {
        self.config.present_mode
    }

    /// Follows a window resize (a zero size, when minimised, is remembered but not applied).
    pub fn resize(&mut self, width: u32, height: u32) {
        if (width, height) != self.size() {
            self.config.width = width;
            self.config.height = height;
            self.configure();
        }
    }

    fn configure(&self) {
        if self.config.width > 0 && self.config.height > 0 {
            self.surface.configure(&self.device, &self.config);
        }
    }

    /// Draws `image` under the HUD `ui` and presents it; also draws it offscreen and reads
    /// it back when `capture` is set.
    pub fn draw(
        &mut self,
        image: &DisplayImage<'_>,
        mut ui: UiFrame,
        capture: bool,
    ) -> Result<Drawn> {
        self.textures.append(std::mem::take(&mut ui.textures));
        let (width, height) = self.size();
        if width == 0 || height == 0 {
            return Ok(Drawn::Skipped);
        }
        let texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) => t,
            wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                drop(t);
                self.configure();
                return Ok(Drawn::Skipped);
            }
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.configure();
                return Ok(Drawn::Skipped);
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(Drawn::Skipped);
            }
            wgpu::CurrentSurfaceTexture::Lost => {
                bail!("the window's surface was lost (the display went away?)")
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                bail!("the window's surface refused to give an image (validation error)")
            }
        };
        let view = texture.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.format),
            ..Default::default()
        });
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [width, height],
            pixels_per_point: ui.pixels_per_point,
        };
        for (id, deltas) in self.textures.set.drain() {
            for delta in &deltas {
                self.egui
                    .update_texture(&self.device, &self.queue, id, delta);
            }
        }
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("present"),
            });
        let egui_commands = self.egui.update_buffers(
            &self.device,
            &self.queue,
            &mut encoder,
            &ui.paint_jobs,
            &screen,
        );
        self.present
            .prepare(&self.device, &self.queue, image, [width, height]);
        self.compose(&mut encoder, &view, &ui.paint_jobs, &screen);
        let pending = if capture {
            let offscreen = capture_texture(&self.device, self.format, width, height);
            let offscreen_view = offscreen.create_view(&Default::default());
            self.compose(&mut encoder, &offscreen_view, &ui.paint_jobs, &screen);
            Some(PendingCapture::record(
                &self.device,
                &mut encoder,
                &offscreen,
            )?)
        } else {
            None
        };
        self.queue
            .submit(egui_commands.into_iter().chain([encoder.finish()]));
        self.queue.present(texture);
        for id in self.textures.free.drain() {
            self.egui.free_texture(&id);
        }
        if let Some(error) = pollster::block_on(scope.pop()) {
            bail!("drawing the window failed: {error}");
        }
        let shot = pending.map(|p| p.finish(&self.device)).transpose()?;
        Ok(Drawn::Presented(shot))
    }

    /// Records the frame and the HUD over `target`.
    fn compose(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        paint_jobs: &[egui::ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
    ) {
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("frame and HUD"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            })
            .forget_lifetime();
        self.present.draw(&mut pass);
        self.egui.render(&mut pass, paint_jobs, screen);
    }
}
