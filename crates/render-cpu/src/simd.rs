//! Per-pixel passes compiled again for the vector extensions of the CPU at hand. The
//! workspace builds for the x86-64 baseline (SSE2), where converting a float to an index
//! takes half a dozen instructions and 16 vector registers hold the working set; the same
//! code compiled for AVX2 or AVX-512 computes the same IEEE operations in the same order
//! (Rust never fuses a multiply and an add on its own), so every bit stays as it was and
//! only the instructions differ. Used where it measured a gain (`docs/temporal.md`, *Warps
//! compiled for the CPU at hand*): a warped refresh's passes, the display's sharpening and
//! tone map, and the resolve's preparation.

/// The vector extensions a pass is compiled for.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Debug, PartialEq)]
enum Level {
    /// The workspace's build (SSE2).
    Baseline,
    Avx2,
    /// AVX2 with AVX-512 F and VL: 32 vector registers, and a float converts to an
    /// unsigned index in one instruction.
    Avx512,
}

/// The best [`Level`] this CPU runs (the feature checks are cached by the standard library).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn level() -> Level {
    use std::arch::is_x86_feature_detected as has;
    if !has!("avx2") {
        Level::Baseline
    } else if has!("avx512f") && has!("avx512vl") {
        Level::Avx512
    } else {
        Level::Avx2
    }
}

/// Runs `pass` compiled for the best vector extensions this CPU has. `pass` should be an
/// `#[inline(always)]` closure whose work is inlined into it (`#[inline]` or
/// `#[inline(always)]` functions): what it calls out of line keeps the baseline's code.
#[inline(always)]
pub(crate) fn best_compiled<R>(pass: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    match level() {
        // SAFETY: this CPU has AVX2, AVX-512 F and AVX-512 VL.
        Level::Avx512 => return unsafe { avx512(pass) },
        // SAFETY: this CPU has AVX2.
        Level::Avx2 => return unsafe { avx2(pass) },
        Level::Baseline => {}
    }
    pass()
}

/// `pass` compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn avx2<R>(pass: impl FnOnce() -> R) -> R {
    pass()
}

/// `pass` compiled for AVX-512 (see [`Level::Avx512`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512vl")]
fn avx512<R>(pass: impl FnOnce() -> R) -> R {
    pass()
}
