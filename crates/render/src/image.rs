//! A rendered image in linear radiance.

use crate::tonemap::linear_to_srgb8_fast;

/// A linear-RGB radiance image, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB radiance per pixel, `width × height` of them.
    pub pixels: Vec<[f32; 3]>,
}

impl Image {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![[0.0; 3]; width as usize * height as usize],
        }
    }

    /// The pixel at (x, y).
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// The tone-mapped 8-bit sRGB image as RGBA bytes (alpha 255), the picture both backends
    /// must agree on.
    pub fn to_srgb8_rgba(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.pixels.len() * 4);
        for p in &self.pixels {
            out.extend(p.iter().map(|&c| linear_to_srgb8_fast(c)));
            out.push(255);
        }
        out
    }
}
