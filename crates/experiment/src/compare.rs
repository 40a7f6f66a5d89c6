//! `steadyray compare REF.png TEST.png [--error-map map.png]`: FLIP, PSNR and SSIM of a test
//! image against a reference, as one JSON line.

use anyhow::{Context, Result, bail};
use serde_json::json;
use std::path::{Path, PathBuf};
use steadyray_quality::{Rgb8Image, flip_at, psnr, ssim};

/// Two images to compare and where to write the comparison's pictures.
#[derive(Clone, Debug)]
pub struct CompareConfig {
    /// The reference image (any format the `image` crate reads; alpha is dropped).
    pub reference: PathBuf,
    /// The image to judge. A different size is brought to the reference's by a bilinear
    /// upscale (as a frame rendered at a reduced resolution scale is shown).
    pub test: PathBuf,
    /// Also write the FLIP error map (magma colours: black is no error) to this PNG.
    pub error_map: Option<PathBuf>,
    /// Also write the test image (upscaled), the reference and the FLIP error map side by
    /// side, in that order, to this PNG.
    pub side_by_side: Option<PathBuf>,
    /// FLIP's viewing condition: pixels of the reference per degree of visual angle as
    /// shown (the bench's displayed FLIP uses the standard FHD set-up's, 12.6 for a
    /// 640-pixel-wide frame filling the display).
    pub ppd: f32,
}

/// `images` (all of the same height) next to each other, left to right, 4 white pixels apart.
pub fn side_by_side(images: &[&Rgb8Image]) -> Rgb8Image {
    const GAP: u32 = 4;
    let height = images.iter().map(|i| i.height()).max().unwrap_or(1);
    let width = images.iter().map(|i| i.width() + GAP).sum::<u32>() - GAP;
    let mut starts = Vec::new();
    let mut x0 = 0;
    for img in images {
        starts.push(x0);
        x0 += img.width() + GAP;
    }
    Rgb8Image::from_fn(width.max(1), height, |x, y| {
        images
            .iter()
            .zip(&starts)
            .find(|(img, s)| x >= **s && x < **s + img.width() && y < img.height())
            .map_or([255; 3], |(img, s)| img.pixel(x - *s, y))
    })
}

/// Reads an image file as 8-bit sRGB.
pub fn load_rgb8(path: &Path) -> Result<Rgb8Image> {
    let img = image::open(path)
        .with_context(|| format!("cannot read {}", path.display()))?
        .into_rgb8();
    let (w, h) = img.dimensions();
    Ok(Rgb8Image::from_rgb(w, h, img.into_raw())?)
}

/// Writes an 8-bit sRGB image as PNG.
pub fn save_rgb8(image: &Rgb8Image, path: &Path) -> Result<()> {
    image::save_buffer(
        path,
        image.as_bytes(),
        image.width(),
        image.height(),
        image::ExtendedColorType::Rgb8,
    )
    .with_context(|| format!("cannot write {}", path.display()))
}

/// Compares the two images and prints `{"flip":..,"psnr":..,"ssim":..,...}`.
pub fn run(args: &CompareConfig) -> Result<()> {
    if !(args.ppd.is_finite() && args.ppd > 0.0) {
        bail!(
            "--ppd must be a positive number of pixels per degree, not {}",
            args.ppd
        );
    }
    let reference = load_rgb8(&args.reference)?;
    let test = load_rgb8(&args.test)?;
    let upscaled = (test.width(), test.height()) != (reference.width(), reference.height());
    let test = test.resize_bilinear(reference.width(), reference.height());
    let flip_map = flip_at(&reference, &test, args.ppd)?;
    if args.error_map.is_some() || args.side_by_side.is_some() {
        let map = flip_map.to_magma();
        if let Some(path) = &args.error_map {
            save_rgb8(&map, path)?;
        }
        if let Some(path) = &args.side_by_side {
            save_rgb8(&side_by_side(&[&test, &reference, &map]), path)?;
        }
    }
    // JSON has no infinity: identical images report a PSNR of null.
    let psnr = Some(psnr(&reference, &test)?).filter(|p| p.is_finite());
    let line = json!({
        "reference": args.reference.display().to_string(),
        "test": args.test.display().to_string(),
        "width": reference.width(),
        "height": reference.height(),
        "upscaled": upscaled,
        "flip": flip_map.mean(),
        "ppd": args.ppd,
        "psnr": psnr,
        "ssim": ssim(&reference, &test)?,
    });
    println!("{line}");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_by_side_places_images_left_to_right() {
        let a = Rgb8Image::from_fn(2, 2, |_, _| [1; 3]);
        let b = Rgb8Image::from_fn(3, 1, |_, _| [2; 3]);
        let both = side_by_side(&[&a, &b]);
        assert_eq!((both.width(), both.height()), (9, 2));
        assert_eq!(both.pixel(1, 1), [1; 3]);
        assert_eq!(both.pixel(3, 0), [255; 3]);
        assert_eq!(both.pixel(6, 0), [2; 3]);
        assert_eq!(both.pixel(6, 1), [255; 3]);
    }
}
