//! LDR-FLIP through NVIDIA's reference implementation (the `nv-flip` crate's bindings).

use crate::image::{Rgb8Image, SizeMismatch};

/// Pixels per degree of visual angle the comparison assumes: FLIP's default (a 0.7 m
/// viewing distance from a 0.7 m wide 3840-pixel monitor, about 67).
pub const PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// The per-pixel FLIP error of a comparison, each value in [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct FlipMap {
    width: u32,
    height: u32,
    values: Vec<f32>,
}

impl FlipMap {
    /// The per-pixel errors, row-major.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The mean error: the single number the FLIP authors recommend reporting.
    pub fn mean(&self) -> f64 {
        self.values.iter().map(|&v| f64::from(v)).sum::<f64>() / self.values.len() as f64
    }

    /// The error map in FLIP's magma colour map (black: no error, yellow-white: largest).
    pub fn to_magma(&self) -> Rgb8Image {
        let map = nv_flip::FlipImageFloat::with_data(self.width, self.height, &self.values);
        let rgb = map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
        Rgb8Image::from_rgb(self.width, self.height, rgb)
            .expect("nv-flip returns a colour image of the map's size")
    }
}

/// The LDR-FLIP error map of `test` against `reference` (both sRGB 8-bit, same size), at
/// [`PIXELS_PER_DEGREE`]. Its [`FlipMap::mean`] is the figure steadyray reports.
pub fn flip(reference: &Rgb8Image, test: &Rgb8Image) -> Result<FlipMap, SizeMismatch> {
    flip_at(reference, test, PIXELS_PER_DEGREE)
}

/// [`flip`] under another viewing condition: `pixels_per_degree` of the images as shown (e.g.
/// a frame filling a given display at a given distance).
pub fn flip_at(
    reference: &Rgb8Image,
    test: &Rgb8Image,
    pixels_per_degree: f32,
) -> Result<FlipMap, SizeMismatch> {
    reference.check_same_size(test)?;
    let (w, h) = (reference.width(), reference.height());
    let r = nv_flip::FlipImageRgb8::with_data(w, h, reference.as_bytes());
    let t = nv_flip::FlipImageRgb8::with_data(w, h, test.as_bytes());
    let map = nv_flip::flip(r, t, pixels_per_degree);
    Ok(FlipMap {
        width: w,
        height: h,
        values: map.to_vec(),
    })
}
