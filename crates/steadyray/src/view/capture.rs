//! Screenshots of the composited window (scene and HUD): the frame is drawn a second time
//! into an offscreen texture, copied to a buffer and written as an 8-bit sRGB PNG.

use anyhow::{Context, Result, bail};
use std::path::Path;
use std::sync::mpsc;

/// An RGBA8 sRGB image, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Screenshot {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

impl Screenshot {
    /// Writes the screenshot as a PNG.
    pub fn save(&self, path: &Path) -> Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
        }
        image::save_buffer(
            path,
            &self.rgba,
            self.width,
            self.height,
            image::ExtendedColorType::Rgba8,
        )
        .with_context(|| format!("cannot write the screenshot {}", path.display()))
    }
}

/// Bytes per row of a texture copy: 4 per pixel, padded as wgpu requires.
pub fn padded_row_bytes(width: u32) -> u32 {
    (width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
}

/// The image in `data` (rows of `padded_row_bytes(width)`) as tight RGBA rows; `bgra` swaps
/// the red and blue channels of a BGRA texture.
pub fn unpad_rows(data: &[u8], width: u32, height: u32, bgra: bool) -> Vec<u8> {
    let padded = padded_row_bytes(width) as usize;
    let tight = width as usize * 4;
    let mut out = Vec::with_capacity(tight * height as usize);
    for row in data.chunks(padded).take(height as usize) {
        out.extend_from_slice(&row[..tight]);
    }
    if bgra {
        for px in out.chunks_exact_mut(4) {
            px.swap(0, 2);
        }
    }
    out
}

/// An offscreen copy of one frame, recorded beside the frame's draw to the window.
pub struct PendingCapture {
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    bgra: bool,
}

/// A texture to draw a frame into for a screenshot.
pub fn capture_texture(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("screenshot"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

impl PendingCapture {
    /// Records the copy of `texture` (drawn by the same encoder) into a readable buffer.
    pub fn record(
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
    ) -> Result<Self> {
        let (width, height) = (texture.width(), texture.height());
        let bgra = match texture.format() {
            wgpu::TextureFormat::Bgra8Unorm => true,
            wgpu::TextureFormat::Rgba8Unorm => false,
            other => bail!("cannot take a screenshot of a {other:?} window"),
        };
        let row = padded_row_bytes(width);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("screenshot readback"),
            size: u64::from(row) * u64::from(height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(height),
                },
            },
            texture.size(),
        );
        Ok(Self {
            buffer,
            width,
            height,
            bgra,
        })
    }

    /// Waits for the submitted copy and returns the image.
    pub fn finish(self, device: &wgpu::Device) -> Result<Screenshot> {
        let slice = self.buffer.slice(..);
        let (sender, receiver) = mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            // The receiver waits below; a failed send means nobody listens any more.
            let _ = sender.send(result);
        });
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .context("waiting for the screenshot failed")?;
        receiver
            .recv()
            .context("the screenshot's map callback never ran")?
            .context("cannot map the screenshot buffer")?;
        let rgba = {
            let data = slice
                .get_mapped_range()
                .context("cannot read the screenshot buffer")?;
            unpad_rows(&data, self.width, self.height, self.bgra)
        };
        self.buffer.unmap();
        Ok(Screenshot {
            width: self.width,
            height: self.height,
            rgba,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_unpadded_and_bgra_swapped() {
        let (width, height) = (3u32, 2u32);
        let row = padded_row_bytes(width) as usize;
        assert_eq!(row, 256);
        let mut data = vec![0xEEu8; row * 2];
        for y in 0..2 {
            for x in 0..3 {
                let i = y * row + x * 4;
                data[i..i + 4].copy_from_slice(&[10 * x as u8, y as u8, 200, 255]);
            }
        }
        let rgba = unpad_rows(&data, width, height, false);
        assert_eq!(rgba.len(), 24);
        assert_eq!(&rgba[12..16], &[0, 1, 200, 255]);
        let swapped = unpad_rows(&data, width, height, true);
        assert_eq!(&swapped[4..8], &[200, 0, 10, 255]);
    }

    #[test]
    fn saves_a_png() {
        let dir = tempfile::Builder::new()
            .prefix("steadyray-capture-")
            .tempdir()
            .unwrap();
        let path = dir.path().join("shots").join("shot.png");
        let shot = Screenshot {
            width: 2,
            height: 1,
            rgba: vec![1, 2, 3, 255, 4, 5, 6, 255],
        };
        shot.save(&path).unwrap();
        let back = image::open(&path).unwrap().into_rgba8();
        assert_eq!(back.into_raw(), shot.rgba);
    }
}
