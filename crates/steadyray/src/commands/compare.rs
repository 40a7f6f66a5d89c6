//! `steadyray compare REF.png TEST.png [--error-map map.png]`: FLIP, PSNR and SSIM of a test
//! image against a reference, as one JSON line.

use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use std::path::{Path, PathBuf};
use steadyray_quality::{Rgb8Image, compare, flip};

#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The reference image (any format the `image` crate reads; alpha is dropped).
    pub reference: PathBuf,
    /// The image to judge. A different size is brought to the reference's by a bilinear
    /// upscale (as a frame rendered at a reduced resolution scale is shown).
    pub test: PathBuf,
    /// Also write the FLIP error map (magma colours: black is no error) to this PNG.
    #[arg(long, value_name = "PNG")]
    pub error_map: Option<PathBuf>,
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
pub fn run(args: &CompareArgs) -> Result<()> {
    let reference = load_rgb8(&args.reference)?;
    let test = load_rgb8(&args.test)?;
    let upscaled = (test.width(), test.height()) != (reference.width(), reference.height());
    let test = test.resize_bilinear(reference.width(), reference.height());
    let m = compare(&reference, &test)?;
    if let Some(path) = &args.error_map {
        save_rgb8(&flip(&reference, &test)?.to_magma(), path)?;
    }
    // JSON has no infinity: identical images report a PSNR of null.
    let psnr = m.psnr.is_finite().then_some(m.psnr);
    let line = json!({
        "reference": args.reference.display().to_string(),
        "test": args.test.display().to_string(),
        "width": reference.width(),
        "height": reference.height(),
        "upscaled": upscaled,
        "flip": m.flip,
        "psnr": psnr,
        "ssim": m.ssim,
    });
    println!("{line}");
    Ok(())
}
