//! Structural similarity (SSIM) of the luma.

use crate::image::{Rgb8Image, SizeMismatch};

/// Gaussian window standard deviation (Wang et al. 2004).
const SIGMA: f64 = 1.5;
/// Window radius: an 11×11 window.
const RADIUS: usize = 5;
/// Stabilising constants for a dynamic range L = 255: (0.01 L)² and (0.03 L)².
const C1: f64 = (0.01 * 255.0) * (0.01 * 255.0);
const C2: f64 = (0.03 * 255.0) * (0.03 * 255.0);

/// Mean SSIM of `test` against `reference`, on the Rec. 601 luma of the 8-bit sRGB values,
/// with an 11×11 Gaussian window (σ = 1.5) normalised over the part of it inside the image
/// (so images smaller than the window still get a value). 1 for identical images; lower
/// for less similar ones (it can go below 0 for anti-correlated structure).
pub fn ssim(reference: &Rgb8Image, test: &Rgb8Image) -> Result<f64, SizeMismatch> {
    reference.check_same_size(test)?;
    let (w, h) = (reference.width() as usize, reference.height() as usize);
    let luma = |img: &Rgb8Image| -> Vec<f64> {
        img.as_bytes()
            .chunks_exact(3)
            .map(|p| 0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2]))
            .collect()
    };
    let (a, b) = (luma(reference), luma(test));
    let product =
        |u: &[f64], v: &[f64]| -> Vec<f64> { u.iter().zip(v).map(|(x, y)| x * y).collect() };
    let ones = vec![1.0; w * h];
    let norm = blur(&ones, w, h);
    let mean = |v: &[f64]| -> Vec<f64> {
        blur(v, w, h)
            .iter()
            .zip(&norm)
            .map(|(s, n)| s / n)
            .collect()
    };
    let (mu_a, mu_b) = (mean(&a), mean(&b));
    let (aa, bb, ab) = (
        mean(&product(&a, &a)),
        mean(&product(&b, &b)),
        mean(&product(&a, &b)),
    );
    let total: f64 = (0..w * h)
        .map(|i| {
            let (ma, mb) = (mu_a[i], mu_b[i]);
            let var_a = aa[i] - ma * ma;
            let var_b = bb[i] - mb * mb;
            let cov = ab[i] - ma * mb;
            ((2.0 * ma * mb + C1) * (2.0 * cov + C2))
                / ((ma * ma + mb * mb + C1) * (var_a + var_b + C2))
        })
        .sum();
    Ok(total / (w * h) as f64)
}

/// `v` filtered by the (unnormalised at the edges) separable Gaussian window: zero outside.
fn blur(v: &[f64], w: usize, h: usize) -> Vec<f64> {
    let kernel: Vec<f64> = (0..=2 * RADIUS)
        .map(|i| {
            let d = i as f64 - RADIUS as f64;
            (-d * d / (2.0 * SIGMA * SIGMA)).exp()
        })
        .collect();
    let sum: f64 = kernel.iter().sum();
    let kernel: Vec<f64> = kernel.iter().map(|k| k / sum).collect();
    let pass = |src: &[f64], stride: usize, len: usize, step: usize, lines: usize| {
        let mut out = vec![0.0; src.len()];
        for line in 0..lines {
            let base = line * stride;
            for i in 0..len {
                let mut acc = 0.0;
                for (j, k) in kernel.iter().enumerate() {
                    let p = i as isize + j as isize - RADIUS as isize;
                    if (0..len as isize).contains(&p) {
                        acc += k * src[base + p as usize * step];
                    }
                }
                out[base + i * step] = acc;
            }
        }
        out
    };
    let rows = pass(v, w, w, 1, h);
    pass(&rows, 1, h, w, w)
}
