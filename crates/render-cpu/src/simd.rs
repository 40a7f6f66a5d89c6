//! Per-pixel passes compiled again for the vector extensions of the CPU at hand. The
//! workspace builds for the x86-64 baseline (SSE2: 16 vector registers, several
//! instructions to turn a float into an index); the same code compiled for AVX2 or AVX-512
//! computes the same IEEE operations in the same order (Rust never fuses a multiply and an
//! add on its own), so every bit stays as it was and only the instructions differ. Used
//! where it measured a gain (`docs/temporal.md`, *Warps compiled for the CPU at hand*): a
//! warped refresh's passes, the display's sharpening and tone map, and the resolve's
//! preparation.

#[cfg(target_arch = "x86_64")]
use steadyray_accel::{X86Level, x86_level};

/// The [`X86Level`] the passes run at: the best this CPU has, or a lower one a test forces.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn level() -> X86Level {
    #[cfg(test)]
    if let Some(forced) = tests::forced().filter(|&forced| forced <= x86_level()) {
        return forced;
    }
    x86_level()
}

/// Runs `pass` compiled for the best vector extensions this CPU has. `pass` should be an
/// `#[inline(always)]` closure whose work is inlined into it (`#[inline]` or
/// `#[inline(always)]` functions): what it calls out of line keeps the baseline's code.
#[inline(always)]
pub(crate) fn best_compiled<R>(pass: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    match level() {
        // SAFETY: this CPU has AVX2, AVX-512 F and AVX-512 VL.
        X86Level::Avx512 => return unsafe { avx512(pass) },
        // SAFETY: this CPU has AVX2.
        X86Level::Avx2 => return unsafe { avx2(pass) },
        X86Level::Baseline => {}
    }
    pass()
}

/// `pass` compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn avx2<R>(pass: impl FnOnce() -> R) -> R {
    pass()
}

/// `pass` compiled for AVX-512 (32 vector registers, and a float converts to an unsigned
/// index in one instruction).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512vl")]
fn avx512<R>(pass: impl FnOnce() -> R) -> R {
    pass()
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::{X86Level, x86_level};
    use crate::CpuRenderer;
    use std::sync::atomic::{AtomicU8, Ordering};
    use steadyray_render::{Presented, RenderSettings, Renderer, TemporalSettings};
    use steadyray_scene::builtin;

    /// The level every pass runs at, while a test forces one (an index into LEVELS).
    static FORCED: AtomicU8 = AtomicU8::new(NOT_FORCED);
    const NOT_FORCED: u8 = u8::MAX;
    const LEVELS: [X86Level; 3] = [X86Level::Baseline, X86Level::Avx2, X86Level::Avx512];

    /// The level a test forces, if any.
    pub(super) fn forced() -> Option<X86Level> {
        LEVELS
            .get(usize::from(FORCED.load(Ordering::Relaxed)))
            .copied()
    }

    /// The bits of the temporal mode on the corridor's sweep: the history, its shown
    /// picture and a warp a refresh on, after each of a few moving frames at a scale below
    /// 1 (so the display sharpens).
    fn temporal_bits() -> Vec<u32> {
        let scene = builtin("corridor").expect("the corridor is built in");
        let mut renderer = CpuRenderer::with_threads(2);
        renderer.load_scene(&scene).expect("loads");
        renderer
            .set_temporal(Some(TemporalSettings {
                width: 96,
                height: 54,
            }))
            .expect("a valid history");
        let settings = RenderSettings {
            width: 68,
            height: 38,
            spp: 1.5,
            max_depth: 8,
        };
        let mut bits = Vec::new();
        for k in 0..6 {
            let t_s = f64::from(k) / 30.0;
            renderer
                .render(&scene.camera_at_time(t_s), t_s, &settings)
                .expect("renders");
            let image = renderer.read_image().expect("a history");
            bits.extend(image.pixels.iter().flatten().map(|v| v.to_bits()));
            let picture = renderer.read_picture().expect("a picture");
            bits.extend(picture.rgba.iter().map(|&v| u32::from(v)));
            match renderer
                .present_warped(&scene.camera_at_time(t_s + 1.0 / 60.0))
                .expect("warps")
            {
                Presented::Host(picture) => bits.extend(picture.rgba.iter().map(|&v| u32::from(v))),
                Presented::Device => panic!("the CPU presents on the host"),
            }
        }
        bits
    }

    /// Each level this CPU runs gives the baseline's bits. (While a level is forced, other
    /// tests of this crate run at it too: by this test's claim, to the same bits.)
    #[test]
    fn every_level_gives_the_same_bits() {
        let levels: Vec<usize> = (0..LEVELS.len())
            .filter(|&i| LEVELS[i] <= x86_level())
            .collect();
        let runs: Vec<(X86Level, Vec<u32>)> = levels
            .iter()
            .map(|&i| {
                FORCED.store(i as u8, Ordering::Relaxed);
                (LEVELS[i], temporal_bits())
            })
            .collect();
        FORCED.store(NOT_FORCED, Ordering::Relaxed);
        let (_, baseline) = &runs[0];
        for (level, bits) in &runs[1..] {
            assert!(bits == baseline, "{level:?} differs from the baseline");
        }
        eprintln!(
            "levels compared: {:?}",
            runs.iter().map(|(l, _)| l).collect::<Vec<_>>()
        );
    }
}
