//! Shared by the GPU integration tests: one renderer per test binary, skipped loudly when
//! no adapter exists, and image comparison.

#![allow(dead_code)] // each test binary uses a different subset

use std::sync::{Mutex, MutexGuard, OnceLock};
use steadyray_render::{Image, RayCounts};
use steadyray_render_gpu::{GpuOptions, GpuRenderer};

/// The test binary's GPU renderer (any adapter, software included; `STEADYRAY_ADAPTER`
/// narrows it). None, after printing "SKIPPED: no GPU adapter", when there is none; a panic
/// instead when `STEADYRAY_REQUIRE_GPU=1`.
pub fn gpu() -> Option<MutexGuard<'static, GpuRenderer>> {
    static GPU: OnceLock<Result<Mutex<GpuRenderer>, String>> = OnceLock::new();
    let renderer = GPU.get_or_init(|| {
        // wgpu's warnings (RUST_LOG=warn) in the test output.
        let _ = env_logger::builder().is_test(true).try_init();
        let options = GpuOptions {
            adapter_name: std::env::var("STEADYRAY_ADAPTER").ok(),
            allow_software: true,
        };
        match GpuRenderer::new(&options) {
            Ok(renderer) => Ok(Mutex::new(renderer)),
            Err(e) if std::env::var("STEADYRAY_REQUIRE_GPU").as_deref() == Ok("1") => {
                panic!("STEADYRAY_REQUIRE_GPU=1 but no GPU renderer could be created: {e}")
            }
            Err(e) => Err(e.to_string()),
        }
    });
    match renderer {
        Ok(m) => Some(m.lock().unwrap_or_else(|e| e.into_inner())),
        Err(e) => {
            eprintln!("SKIPPED: no GPU adapter ({e})");
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
    /// The largest difference of linear values, relative to max(1, |value|).
    pub max_linear: f32,
}

impl Diff {
    pub fn fraction_over_2(&self) -> f64 {
        self.pixels_over_2 as f64 / self.pixels as f64
    }

    /// The parity bar. On a software adapter (lavapipe, which rounds as the CPU does): at
    /// most 0.1% of pixels off by more than 2/255 and a mean error under 0.05 levels. On
    /// hardware, where the driver may fuse multiply-adds, a grazing ray can take another
    /// path and flip a whole pixel: on an H100 up to 8 pixels of 6,144 (0.13%) and a mean of
    /// 0.065 levels were seen on these small test images (and FLIP 7e-6 at 1920x1080), so
    /// there the bar is 0.25% and 0.15, still far under what a wrong object, material or
    /// light moves.
    pub fn assert_parity(&self, what: &str, exact: bool) {
        let (fraction, mean) = if exact { (0.001, 0.05) } else { (0.0025, 0.15) };
        assert!(
            self.fraction_over_2() <= fraction && self.mean <= mean,
            "{what}: GPU and CPU images differ too much: {self:?}"
        );
    }
}

/// Checks the GPU's ray counts against the CPU's. Eye rays always agree exactly. On lavapipe
/// (software) every count agrees exactly: the WGSL repeats the CPU's arithmetic operation
/// for operation and LLVM neither fuses nor approximates it. A hardware driver may fuse
/// multiply-adds or use its own sqrt and division rounding (Vulkan allows 2.5 ulp), which can
/// flip a grazing hit or a Fresnel choice and so change one sample's chain: each diverging
/// sample moves each per-depth count by at most 1 and the shadow count by at most
/// lights·(R + 1). There the bound is 0.1% of the samples diverging (as the image bar allows
/// 0.1% of pixels to differ).
pub fn assert_counts(gpu: &RayCounts, cpu: &RayCounts, exact: bool, lights: usize, what: &str) {
    assert_eq!(gpu.per_depth.len(), cpu.per_depth.len(), "{what}: depths");
    assert_eq!(gpu.per_depth[0], cpu.per_depth[0], "{what}: eye rays");
    if exact {
        assert_eq!(gpu, cpu, "{what}: ray counts");
        return;
    }
    let diverging = (cpu.per_depth[0] / 1000).max(1);
    for (k, (g, c)) in gpu.per_depth.iter().zip(&cpu.per_depth).enumerate() {
        assert!(g.abs_diff(*c) <= diverging, "{what}: depth {k}: {g} vs {c}");
    }
    assert!(
        gpu.stopped.abs_diff(cpu.stopped) <= diverging,
        "{what}: stopped chains {} vs {}",
        gpu.stopped,
        cpu.stopped
    );
    let shadow_bound = diverging * (lights * cpu.per_depth.len()) as u64;
    assert!(
        gpu.shadow.abs_diff(cpu.shadow) <= shadow_bound,
        "{what}: shadow rays {} vs {}",
        gpu.shadow,
        cpu.shadow
    );
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
    let max_linear = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(pa, pb)| pa.iter().zip(pb))
        .map(|(x, y)| (x - y).abs() / x.abs().max(1.0))
        .fold(0.0f32, f32::max);
    Diff {
        max_linear,
        max,
        mean: sum as f64 / (pixels * 3) as f64,
        pixels_over_2,
        pixels,
    }
}
