//! The quality and size of one frame.

use crate::sample_stream::MIN_REFERENCE_SPP;
use thiserror::Error;

/// The largest reflection/refraction depth R a renderer accepts.
pub const MAX_DEPTH: u32 = 64;
/// The largest number of eye rays per pixel S a renderer accepts.
pub const MAX_SPP: f32 = 4096.0;

/// Checks an image size any renderer can render: 1 to 16384 pixels on a side (a command's
/// full-scale size, checked before it renders anything at it or a scale of it).
pub fn check_image_size(width: u32, height: u32) -> Result<(), SettingsError> {
    if width == 0 || height == 0 {
        return Err(SettingsError::EmptyImage { width, height });
    }
    if width > 16384 || height > 16384 {
        return Err(SettingsError::ImageTooLarge { width, height });
    }
    Ok(())
}

/// What to render: image size, eye rays per pixel S (fractional: see
/// [`crate::sampling::samples_for_pixel`]) and the largest reflection/refraction depth R.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Eye rays per pixel S.
    pub spp: f32,
    /// The largest reflection/refraction depth R.
    pub max_depth: u32,
}

/// Why a [`RenderSettings`] cannot be rendered.
#[derive(Debug, Error, PartialEq)]
pub enum SettingsError {
    /// An image without pixels.
    #[error("image size {width}x{height} is empty: width and height must be at least 1")]
    EmptyImage {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// An image larger than 16384 pixels on a side.
    #[error("image size {width}x{height} is too large (at most 16384 on a side)")]
    ImageTooLarge {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// S outside [1, `MAX_SPP`] or NaN.
    #[error("samples per pixel S = {0} is out of range: it must be a number in [1, {MAX_SPP}]")]
    BadSpp(f32),
    /// R above `MAX_DEPTH`.
    #[error("reflection depth R = {0} is out of range: at most {MAX_DEPTH}")]
    BadDepth(u32),
    /// A reference of fewer samples than it needs.
    #[error(
        "a reference needs S >= {MIN_REFERENCE_SPP} (got {0}): with one sample a pixel, the \
         reference's sample sits off the pixel centre, and its image is shifted"
    )]
    BadReferenceSpp(f32),
    #[error(
        "a {width}x{height} frame cannot be accumulated into a {history_width}x{history_height} \
         history: temporal frames are at most the history's size"
    )]
    /// A temporal frame larger than its history.
    LargerThanHistory {
        /// The frame's width.
        width: u32,
        /// The frame's height.
        height: u32,
        /// The history's width.
        history_width: u32,
        /// The history's height.
        history_height: u32,
    },
}

impl RenderSettings {
    /// Checks the settings, so renderers never see an empty image or a NaN sample count.
    pub fn validate(&self) -> Result<(), SettingsError> {
        check_image_size(self.width, self.height)?;
        if !(self.spp >= 1.0 && self.spp <= MAX_SPP) {
            return Err(SettingsError::BadSpp(self.spp));
        }
        if self.max_depth > MAX_DEPTH {
            return Err(SettingsError::BadDepth(self.max_depth));
        }
        Ok(())
    }

    /// The settings of a frame at resolution scale `scale` of a `full`-size image (see
    /// [`RenderSettings::scaled_size`]), `spp` eye rays per pixel and depth `max_depth`: the
    /// one way every command and the window size a frame of a quality.
    pub fn scaled(full: (u32, u32), scale: f32, spp: f32, max_depth: u32) -> Self {
        let (width, height) = Self::scaled_size(full, scale);
        Self {
            width,
            height,
            spp,
            max_depth,
        }
    }

    /// The image size at resolution scale `scale` of a `full`-size image: each side scaled
    /// and rounded to the nearest pixel, at least 1 pixel.
    pub fn scaled_size((width, height): (u32, u32), scale: f32) -> (u32, u32) {
        let side = |v: u32| ((v as f32 * scale).round() as u32).max(1);
        (side(width), side(height))
    }

    /// Number of pixels.
    pub fn pixels(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}
