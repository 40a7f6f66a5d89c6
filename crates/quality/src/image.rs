//! An 8-bit sRGB image as the metrics see it, and the bilinear resize.

use std::fmt;

/// An sRGB-encoded 8-bit RGB image, row-major, top row first, 3 bytes per pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb8Image {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

/// Two images that should have the same size do not (or a buffer does not fit its size).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SizeMismatch {
    /// The expected size (or buffer length as `[len, 0]`).
    pub expected: [u32; 2],
    /// The size found.
    pub found: [u32; 2],
}

impl fmt::Display for SizeMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "image sizes differ: expected {}x{}, found {}x{}",
            self.expected[0], self.expected[1], self.found[0], self.found[1]
        )
    }
}

impl std::error::Error for SizeMismatch {}

impl Rgb8Image {
    /// An image from RGB bytes (`3 · width · height` of them); at least 1×1.
    pub fn from_rgb(width: u32, height: u32, data: Vec<u8>) -> Result<Self, SizeMismatch> {
        let len = width as usize * height as usize * 3;
        if width == 0 || height == 0 || data.len() != len {
            return Err(SizeMismatch {
                expected: [width.max(1), height.max(1)],
                found: [(data.len() / 3 / height.max(1) as usize) as u32, height],
            });
        }
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// An image from RGBA bytes (alpha dropped), e.g. `steadyray_render::Image::to_srgb8_rgba`.
    pub fn from_rgba(width: u32, height: u32, rgba: &[u8]) -> Result<Self, SizeMismatch> {
        let data: Vec<u8> = rgba
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        Self::from_rgb(width, height, data)
    }

    /// An image whose pixel (x, y) is `f(x, y)` (panics on an empty size).
    pub fn from_fn(width: u32, height: u32, f: impl Fn(u32, u32) -> [u8; 3]) -> Self {
        assert!(width > 0 && height > 0, "an image is at least 1x1");
        let data = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .flat_map(|(x, y)| f(x, y))
            .collect();
        Self {
            width,
            height,
            data,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The RGB bytes.
    pub fn as_bytes(&self) -> &[u8] {
        &self.data
    }

    /// The RGB bytes, by value.
    pub fn into_bytes(self) -> Vec<u8> {
        self.data
    }

    /// The pixel at (x, y).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    /// Errors unless `other` has this image's size.
    pub fn check_same_size(&self, other: &Rgb8Image) -> Result<(), SizeMismatch> {
        if (self.width, self.height) == (other.width, other.height) {
            Ok(())
        } else {
            Err(SizeMismatch {
                expected: [self.width, self.height],
                found: [other.width, other.height],
            })
        }
    }

    /// This image resized to `width`×`height` by bilinear interpolation of the sRGB values
    /// (pixel centres aligned, edges clamped), as a display scaler shows a frame rendered at
    /// a reduced resolution. The same size returns a copy.
    pub fn resize_bilinear(&self, width: u32, height: u32) -> Rgb8Image {
        if (width, height) == (self.width, self.height) {
            return self.clone();
        }
        let axis = |out: u32, src: u32| -> Vec<(usize, usize, f32)> {
            let ratio = src as f32 / out as f32;
            (0..out)
                .map(|i| {
                    let s = ((i as f32 + 0.5) * ratio - 0.5).clamp(0.0, (src - 1) as f32);
                    let i0 = s.floor() as usize;
                    let i1 = (i0 + 1).min(src as usize - 1);
                    (i0, i1, s - i0 as f32)
                })
                .collect()
        };
        let xs = axis(width, self.width);
        let ys = axis(height, self.height);
        let w = self.width as usize;
        let at = |x: usize, y: usize, c: usize| f32::from(self.data[3 * (y * w + x) + c]);
        let mut data = Vec::with_capacity(width as usize * height as usize * 3);
        for &(y0, y1, fy) in &ys {
            for &(x0, x1, fx) in &xs {
                for c in 0..3 {
                    let top = at(x0, y0, c) * (1.0 - fx) + at(x1, y0, c) * fx;
                    let bottom = at(x0, y1, c) * (1.0 - fx) + at(x1, y1, c) * fx;
                    let v = top * (1.0 - fy) + bottom * fy;
                    data.push(v.round().clamp(0.0, 255.0) as u8);
                }
            }
        }
        Rgb8Image {
            width,
            height,
            data,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resize_keeps_flat_images_flat_and_interpolates() {
        let flat = Rgb8Image::from_fn(4, 3, |_, _| [10, 20, 30]);
        let big = flat.resize_bilinear(9, 7);
        assert!(big.as_bytes().chunks(3).all(|p| p == [10, 20, 30]));
        let ramp = Rgb8Image::from_fn(2, 1, |x, _| [(x * 200) as u8, 0, 0]);
        let wide = ramp.resize_bilinear(4, 1);
        let reds: Vec<u8> = (0..4).map(|x| wide.pixel(x, 0)[0]).collect();
        assert_eq!(reds, [0, 50, 150, 200]);
    }

    #[test]
    fn buffers_must_fit_their_size() {
        assert!(Rgb8Image::from_rgb(2, 2, vec![0; 11]).is_err());
        assert!(Rgb8Image::from_rgb(0, 2, vec![]).is_err());
        let rgba = [1, 2, 3, 255, 4, 5, 6, 255];
        let img = Rgb8Image::from_rgba(2, 1, &rgba).unwrap();
        assert_eq!(img.pixel(1, 0), [4, 5, 6]);
    }
}
