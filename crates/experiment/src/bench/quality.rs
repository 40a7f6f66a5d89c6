//! Measuring the delivered quality (`bench --quality`): FLIP of delivered frames against a
//! high-quality reference of the same view, rendered outside the timed loop.

use super::source::{FrameSource, PathPoint, render_reference};
use anyhow::{Context, Result, bail};
use std::collections::BTreeMap;
use steadyray_control::Quality;
use steadyray_quality::Rgb8Image;
use steadyray_render::Image;

/// The picture a viewer sees of a frame: tone-mapped 8-bit sRGB, brought to the full-scale
/// size `width`×`height` by a bilinear upscale when it was rendered at a reduced scale.
pub fn shown(image: &Image, width: u32, height: u32) -> Result<Rgb8Image> {
    let rgb = Rgb8Image::from_rgba(image.width, image.height, &image.to_srgb8_rgba())?;
    Ok(rgb.resize_bilinear(width, height))
}

/// Reference images of the sampled frames, rendered once and shared by every controller.
pub struct References {
    images: BTreeMap<u32, Rgb8Image>,
}

impl References {
    /// Renders the references of frames 0, `every`, 2·`every`, ... of an `n`-frame sweep at
    /// `quality` (before any controller runs, so no run is slowed by them). `progress` is
    /// told of each one.
    pub fn render(
        source: &mut dyn FrameSource,
        n: u32,
        every: u32,
        quality: Quality,
        mut progress: impl FnMut(),
    ) -> Result<Self> {
        if every == 0 {
            bail!("--every must be at least 1");
        }
        let (width, height) = source.resolution();
        let mut images = BTreeMap::new();
        for k in (0..n).step_by(every as usize) {
            let picture = render_reference(source, PathPoint::Frame { k, n }, quality)
                .with_context(|| format!("reference of frame {k} at {quality} failed"))?;
            let Some(picture) = picture else {
                bail!("--quality needs a renderer that produces images (not --simulate)");
            };
            images.insert(k, picture.resize_bilinear(width, height));
            progress();
        }
        Ok(Self { images })
    }

    /// The reference of frame `k`, if it is a sampled frame.
    pub fn get(&self, k: u32) -> Option<&Rgb8Image> {
        self.images.get(&k)
    }
}

/// Mean and 95th percentile (linear interpolation between ranks) of FLIP samples; `None`
/// when there are none.
pub fn flip_stats(samples: &[f64]) -> Option<(f64, f64)> {
    if samples.is_empty() {
        return None;
    }
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let mean = sorted.iter().sum::<f64>() / sorted.len() as f64;
    let pos = 0.95 * (sorted.len() - 1) as f64;
    let i = pos.floor() as usize;
    let next = sorted[(i + 1).min(sorted.len() - 1)];
    Some((mean, sorted[i] + pos.fract() * (next - sorted[i])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flip_statistics() {
        assert_eq!(flip_stats(&[]), None);
        let (mean, p95) = flip_stats(&[0.1, 0.3, 0.2]).unwrap();
        assert!((mean - 0.2).abs() < 1e-12);
        assert!((p95 - 0.29).abs() < 1e-12);
    }

    #[test]
    fn a_reduced_frame_is_shown_at_full_size() {
        let mut image = Image::new(4, 2);
        image.pixels.iter_mut().for_each(|p| *p = [1.0, 0.0, 0.0]);
        let rgb = shown(&image, 8, 4).unwrap();
        assert_eq!((rgb.width(), rgb.height()), (8, 4));
        assert_eq!(rgb.pixel(5, 3), [255, 0, 0]);
    }
}
