//! Image quality metrics: how far a delivered frame is from a high-quality reference of the
//! same view.
//!
//! - [`flip()`]: mean LDR-FLIP (Andersson et al., HPG 2020), NVIDIA's perceptual difference
//!   metric for rendered images, computed by NVIDIA's C++ implementation through the `nv-flip`
//!   crate at 67 pixels per degree. 0 means identical; 1 is the largest error. Lower is better.
//! - [`psnr()`]: peak signal-to-noise ratio in dB over the 8-bit RGB channels (higher is better).
//! - [`ssim()`]: mean structural similarity of the luma (Wang et al. 2004; Gaussian window
//!   σ = 1.5, 11×11; higher is better, 1 for identical images).
//!
//! Every metric takes two [`Rgb8Image`]s of the same size: sRGB-encoded 8-bit pixels, the
//! picture that is actually shown. A frame rendered at a reduced resolution scale is first
//! brought to the reference's size with [`Rgb8Image::resize_bilinear`], as a display's scaler
//! would.
//!
//! ```
//! use steadyray_quality::{Rgb8Image, compare};
//! let a = Rgb8Image::from_fn(32, 32, |x, y| [(x * 8) as u8, (y * 8) as u8, 128]);
//! let m = compare(&a, &a)?;
//! assert_eq!(m.flip, 0.0);
//! assert!(m.psnr.is_infinite() && (m.ssim - 1.0).abs() < 1e-12);
//! # Ok::<(), steadyray_quality::SizeMismatch>(())
//! ```

pub mod flip;
pub mod image;
pub mod psnr;
pub mod ssim;

pub use flip::{FlipMap, PIXELS_PER_DEGREE, flip, flip_at};
pub use image::{Rgb8Image, SizeMismatch};
pub use psnr::psnr;
pub use ssim::ssim;

/// The three metrics of one comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metrics {
    /// Mean FLIP error in [0, 1] (lower is better).
    pub flip: f64,
    /// PSNR in dB (infinite for identical images).
    pub psnr: f64,
    /// Mean SSIM of the luma, at most 1.
    pub ssim: f64,
}

/// FLIP, PSNR and SSIM of `test` against `reference` (same size).
pub fn compare(reference: &Rgb8Image, test: &Rgb8Image) -> Result<Metrics, SizeMismatch> {
    Ok(Metrics {
        flip: flip(reference, test)?.mean(),
        psnr: psnr(reference, test)?,
        ssim: ssim(reference, test)?,
    })
}
