//! Shared by the GPU integration tests: one renderer per test binary, skipped loudly when
//! no adapter exists, and image comparison.

#![allow(dead_code)] // each test binary uses a different subset

use std::sync::{Mutex, MutexGuard, OnceLock};
use steadyray_render::Image;
use steadyray_render_gpu::{GpuOptions, GpuRenderer};

/// The test binary's GPU renderer (any adapter, software included; `STEADYRAY_ADAPTER`
/// narrows it). None, after printing "SKIPPED: no GPU adapter", when there is none; a panic
/// instead when `STEADYRAY_REQUIRE_GPU=1`.
pub fn gpu() -> Option<MutexGuard<'static, GpuRenderer>> {
    static GPU: OnceLock<Option<Mutex<GpuRenderer>>> = OnceLock::new();
    let renderer = GPU.get_or_init(|| {
        // wgpu's warnings (RUST_LOG=warn) in the test output.
        let _ = env_logger::builder().is_test(true).try_init();
        let options = GpuOptions {
            adapter_name: std::env::var("STEADYRAY_ADAPTER").ok(),
            allow_software: true,
        };
        match GpuRenderer::new(&options) {
            Ok(renderer) => Some(Mutex::new(renderer)),
            Err(e) if std::env::var("STEADYRAY_REQUIRE_GPU").as_deref() == Ok("1") => {
                panic!("STEADYRAY_REQUIRE_GPU=1 but no GPU renderer could be created: {e}")
            }
            Err(e) => {
                eprintln!("SKIPPED: no GPU adapter ({e})");
                None
            }
        }
    });
    match renderer {
        Some(m) => Some(m.lock().unwrap_or_else(|e| e.into_inner())),
        None => {
            eprintln!("SKIPPED: no GPU adapter");
            None
        }
    }
}

/// How far two images are apart after the tone map, in 8-bit levels per channel.
#[derive(Clone, Debug)]
pub struct Diff {
    /// The largest channel difference.
    pub max: u8,
    /// Mean absolute channel difference.
    pub mean: f64,
    /// Pixels with some channel off by more than 2 levels.
    pub pixels_over_2: usize,
    pub pixels: usize,
}

impl Diff {
    pub fn fraction_over_2(&self) -> f64 {
        self.pixels_over_2 as f64 / self.pixels as f64
    }

    /// The parity bar: at most 0.1% of pixels off by more than 2/255, mean error tiny.
    pub fn assert_parity(&self, what: &str) {
        assert!(
            self.fraction_over_2() <= 0.001 && self.mean <= 0.05,
            "{what}: GPU and CPU images differ too much: {self:?}"
        );
    }
}

pub fn compare(a: &Image, b: &Image) -> Diff {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let (a8, b8) = (a.to_srgb8_rgba(), b.to_srgb8_rgba());
    let mut max = 0u8;
    let mut sum = 0u64;
    let mut pixels_over_2 = 0;
    for (pa, pb) in a8.chunks_exact(4).zip(b8.chunks_exact(4)) {
        let d = (0..3).map(|c| pa[c].abs_diff(pb[c])).max().unwrap_or(0);
        sum += (0..3)
            .map(|c| u64::from(pa[c].abs_diff(pb[c])))
            .sum::<u64>();
        max = max.max(d);
        pixels_over_2 += usize::from(d > 2);
    }
    let pixels = a.pixels.len();
    Diff {
        max,
        mean: sum as f64 / (pixels * 3) as f64,
        pixels_over_2,
        pixels,
    }
}
