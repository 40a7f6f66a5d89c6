//! Peak signal-to-noise ratio.

use crate::image::{Rgb8Image, SizeMismatch};

/// PSNR of `test` against `reference` in dB: 10 · log10(255² / MSE), the mean squared error
/// taken over every 8-bit R, G and B value. Infinite when the images are identical.
pub fn psnr(reference: &Rgb8Image, test: &Rgb8Image) -> Result<f64, SizeMismatch> {
    reference.check_same_size(test)?;
    let sum: f64 = reference
        .as_bytes()
        .iter()
        .zip(test.as_bytes())
        .map(|(&a, &b)| (f64::from(a) - f64::from(b)).powi(2))
        .sum();
    let mse = sum / reference.as_bytes().len() as f64;
    Ok(if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    })
}
