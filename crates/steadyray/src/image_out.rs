//! Writing rendered images to disk.

use anyhow::{Context, Result, bail};
use std::path::Path;
use steadyray_render::{Image, Picture};

/// The image file formats `render` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// Tone-mapped 8-bit sRGB.
    Png,
    /// Linear 32-bit float radiance.
    Exr,
}

/// The format a file name asks for, by its extension; checked before any rendering.
pub fn image_format(path: &Path) -> Result<ImageFormat> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(ImageFormat::Png),
        Some("exr") => Ok(ImageFormat::Exr),
        _ => bail!(
            "cannot tell the image format of {}: use a .png or .exr file name",
            path.display()
        ),
    }
}

/// Writes `image` as a tone-mapped 8-bit sRGB PNG, or as linear 32-bit float EXR, chosen by
/// the file extension.
pub fn save_image(image: &Image, path: &Path) -> Result<()> {
    match image_format(path)? {
        ImageFormat::Png => {
            let rgba = image.to_srgb8_rgba();
            image::save_buffer(
                path,
                &rgba,
                image.width,
                image.height,
                image::ExtendedColorType::Rgba8,
            )
            .with_context(|| format!("cannot write {}", path.display()))
        }
        ImageFormat::Exr => {
            let data: Vec<f32> = image.pixels.iter().flatten().copied().collect();
            let buffer = image::Rgb32FImage::from_raw(image.width, image.height, data)
                .context("image buffer has the wrong size")?;
            buffer
                .save(path)
                .with_context(|| format!("cannot write {}", path.display()))
        }
    }
}

/// Writes a display's 8-bit sRGB `picture` as a PNG (the only format that holds it as it
/// is; the caller checks the extension first).
pub fn save_picture(picture: &Picture, path: &Path) -> Result<()> {
    image::save_buffer(
        path,
        &picture.rgba,
        picture.width,
        picture.height,
        image::ExtendedColorType::Rgba8,
    )
    .with_context(|| format!("cannot write {}", path.display()))
}
