//! Finds how many fractal steps per pixel make "load 1" cost the band's centre at full
//! resolution on this GPU, so that the example runs the same experiment on a software
//! rasteriser and on a data-centre GPU.

use crate::gpu::Gpu;
use crate::load::{MAX_ITERATIONS, Sample, base_iterations as fit};
use anyhow::{Context, Result, bail};

/// Frames measured at each calibration step (their median is kept).
const FRAMES_PER_STEP: usize = 5;

/// The steps per pixel at which a full-resolution frame costs `target_ms`: measures the
/// frame's fixed cost (one step per pixel), then quadruples the steps until a frame costs at
/// least half the target, and fits the cost per pixel-step.
pub fn base_iterations(gpu: &mut Gpu, target_ms: f64) -> Result<f64> {
    let overhead = measure(gpu, 1)?;
    let mut iterations = 16u32;
    loop {
        let sample = measure(gpu, iterations)?;
        if sample.ms >= 0.5 * target_ms {
            let (w, h) = gpu.size();
            return fit(
                overhead.ms,
                &[sample],
                u64::from(w) * u64::from(h),
                target_ms,
            )
            .map_err(anyhow::Error::msg)
            .context("calibrating the load");
        }
        if iterations >= MAX_ITERATIONS {
            bail!(
                "even {MAX_ITERATIONS} steps per pixel cost only {:.3} ms a frame: use a larger \
                 window or a higher --refresh-hz",
                sample.ms
            );
        }
        iterations = iterations.saturating_mul(4).min(MAX_ITERATIONS);
    }
}

/// The median time of a few full-resolution frames at `iterations` steps per pixel.
fn measure(gpu: &mut Gpu, iterations: u32) -> Result<Sample> {
    let mut times = Vec::with_capacity(FRAMES_PER_STEP);
    let mut pixels = 0;
    let mut attempts = 0;
    while times.len() < FRAMES_PER_STEP {
        attempts += 1;
        if attempts > 20 * FRAMES_PER_STEP {
            bail!("the window gave no image to draw on for calibration");
        }
        if let Some(drawn) = gpu.frame(1.0, iterations, 0.0)? {
            times.push(drawn.ms);
            pixels = drawn.pixels;
        }
    }
    times.sort_by(f64::total_cmp);
    Ok(Sample {
        iterations,
        pixels,
        ms: times[times.len() / 2],
    })
}
