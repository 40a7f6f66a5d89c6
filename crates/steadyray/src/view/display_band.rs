//! `view --band refresh[:M]` (the view's default band): the band derived from the window's display, as `bench --band`
//! derives it from the display model. The refresh rate is the monitor's (60 Hz where it does
//! not say); the hand-over is what giving a frame to the window costs (the tone map and
//! upload of the CPU backend, the GPU's hand-over of its image), measured over the first
//! frames, after as many unmeasured ones. With `--warp` the M − 1 warped refreshes between
//! frames run on the same machine, and their cost, measured the same way, comes off the band
//! too while the window shows them (V turns them off and on: the band follows).

use anyhow::Result;
use steadyray_display::{DisplayConfig, SyncMode, aligned_band, stats::quantile};

/// Frames (and warped refreshes) measured, after as many unmeasured, before the band is set.
pub const HAND_OVER_FRAMES: usize = 10;

/// The refresh rate assumed when the monitor does not report one, Hz.
pub const FALLBACK_REFRESH_HZ: f64 = 60.0;

/// A display-aligned band: the costs measured so far, and the band once they are.
#[derive(Debug)]
pub struct DisplayBand {
    multiple: u32,
    display: DisplayConfig,
    hand_over: Costs,
    /// The warped refreshes' costs, when the window shows them.
    warp: Option<Costs>,
}

/// One cost measured over the first calls: [`HAND_OVER_FRAMES`] after as many unmeasured.
#[derive(Debug, Default)]
struct Costs {
    seen: usize,
    ms: Vec<f64>,
}

impl Costs {
    fn observe(&mut self, ms: f64) {
        self.seen += 1;
        if self.seen > HAND_OVER_FRAMES && ms.is_finite() && self.ms.len() < HAND_OVER_FRAMES {
            self.ms.push(ms);
        }
    }

    /// Whether more are needed before the median.
    fn wanted(&self) -> bool {
        self.ms.len() < HAND_OVER_FRAMES
    }

    /// The median, once enough are measured.
    fn median(&self) -> Option<f64> {
        if self.wanted() {
            return None;
        }
        quantile(&self.ms, 0.5)
    }
}

/// The band once measured, and what it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlignedBand {
    pub tmin_ms: f64,
    pub tmax_ms: f64,
    pub refresh_hz: f64,
    pub hand_over_ms: f64,
    /// A warped refresh's cost (0 when the window shows none).
    pub warp_ms: f64,
}

impl DisplayBand {
    /// Every `multiple`-th refresh of a display at `refresh_hz` (vsync on), or at
    /// [`FALLBACK_REFRESH_HZ`] when the monitor does not say; with `warps`, the refreshes
    /// between frames show warped ones, whose cost the band leaves room for.
    pub fn new(multiple: u32, refresh_hz: Option<f64>, warps: bool) -> Result<Self> {
        let hz = refresh_hz
            .filter(|hz| hz.is_finite() && *hz > 0.0)
            .unwrap_or(FALLBACK_REFRESH_HZ);
        Ok(Self {
            multiple: multiple.max(1),
            display: DisplayConfig::new(hz, SyncMode::Vsync)?,
            hand_over: Costs::default(),
            warp: warps.then(Costs::default),
        })
    }

    /// Takes one frame's hand-over.
    pub fn observe(&mut self, hand_over_ms: f64) {
        self.hand_over.observe(hand_over_ms);
    }

    /// Whether the band still waits for warped refreshes to be measured: a window whose
    /// controller shows none (`perceptual` at one refresh a frame) times unshown ones.
    pub fn wants_warp(&self) -> bool {
        self.warp.as_ref().is_some_and(Costs::wanted)
    }

    /// Takes one warped refresh's cost, as [`DisplayBand::observe`] a hand-over.
    pub fn observe_warp(&mut self, warp_ms: f64) {
        if let Some(warp) = &mut self.warp {
            warp.observe(warp_ms);
        }
    }

    /// The band (from the median costs) for frames followed by warped refreshes (`warps`,
    /// where the window was given them) or not, once what it needs is measured; or why the
    /// display leaves no band (costs longer than the frame interval).
    pub fn band(&self, warps: bool) -> Option<Result<AlignedBand>> {
        let hand_over_ms = self.hand_over.median()?;
        let warp_ms = match &self.warp {
            Some(warp) if warps => warp.median()?,
            _ => 0.0,
        };
        Some(
            aligned_band(&self.display, self.multiple, hand_over_ms, warp_ms)
                .map(|(tmin_ms, tmax_ms)| AlignedBand {
                    tmin_ms,
                    tmax_ms,
                    refresh_hz: self.display.refresh_hz,
                    hand_over_ms,
                    warp_ms,
                })
                .map_err(anyhow::Error::from),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measured(band: &mut DisplayBand, ms: f64) -> Option<Result<AlignedBand>> {
        (0..2 * HAND_OVER_FRAMES).find_map(|_| {
            band.observe(ms);
            band.band(true)
        })
    }

    #[test]
    fn the_band_comes_after_the_measured_frames_and_fits_the_refresh() {
        let mut band = DisplayBand::new(1, Some(60.0), false).unwrap();
        assert!(!band.wants_warp());
        for _ in 0..2 * HAND_OVER_FRAMES - 1 {
            band.observe(1.0);
            assert!(band.band(true).is_none());
        }
        band.observe(1.0);
        let b = band.band(true).unwrap().unwrap();
        // 16.67 ms · 0.95 − 1 ms and 0.2 · 16.67 ms below it.
        assert!((b.tmax_ms - (1000.0 / 60.0 * 0.95 - 1.0)).abs() < 1e-9);
        assert!((b.tmax_ms - b.tmin_ms - 1000.0 / 60.0 * 0.2).abs() < 1e-9);
        assert_eq!((b.refresh_hz, b.hand_over_ms, b.warp_ms), (60.0, 1.0, 0.0));
    }

    #[test]
    fn every_second_refresh_and_an_unknown_monitor() {
        let mut band = DisplayBand::new(2, None, false).unwrap();
        let b = measured(&mut band, 2.0).unwrap().unwrap();
        assert_eq!(b.refresh_hz, FALLBACK_REFRESH_HZ);
        assert!((b.tmax_ms - (2000.0 / 60.0 * 0.95 - 2.0)).abs() < 1e-9);
    }

    #[test]
    fn a_hand_over_longer_than_the_frame_is_an_error() {
        let mut band = DisplayBand::new(1, Some(144.0), false).unwrap();
        let err = measured(&mut band, 9.0).unwrap().unwrap_err();
        assert!(format!("{err:#}").contains("hand-over"), "{err:#}");
    }

    #[test]
    fn warped_refreshes_wait_for_their_own_measure_and_take_their_time_from_the_band() {
        let mut band = DisplayBand::new(2, Some(60.0), true).unwrap();
        // Every hand-over measured but no warp yet: no band with warps, one without.
        assert!(measured(&mut band, 2.0).is_none());
        assert!(band.wants_warp());
        let plain = band.band(false).unwrap().unwrap();
        assert_eq!((plain.hand_over_ms, plain.warp_ms), (2.0, 0.0));
        let b = (0..2 * HAND_OVER_FRAMES)
            .find_map(|_| {
                band.observe_warp(5.0);
                band.band(true)
            })
            .unwrap()
            .unwrap();
        assert_eq!((b.hand_over_ms, b.warp_ms), (2.0, 5.0));
        assert!(!band.wants_warp());
        // Warps turned off: the band without them, from the same measurements.
        assert_eq!(band.band(false).unwrap().unwrap(), plain);
        assert!((plain.tmax_ms - b.tmax_ms - 5.0).abs() < 1e-9);
        // 2 refreshes · 0.95 − the hand-over − one warp.
        assert!((b.tmax_ms - (2000.0 / 60.0 * 0.95 - 2.0 - 5.0)).abs() < 1e-9);
        assert!((b.tmax_ms - b.tmin_ms - 2000.0 / 60.0 * 0.2).abs() < 1e-9);
    }

    #[test]
    fn warps_that_leave_no_room_are_an_error() {
        let mut band = DisplayBand::new(2, Some(60.0), true).unwrap();
        for _ in 0..2 * HAND_OVER_FRAMES {
            band.observe_warp(40.0);
        }
        let err = measured(&mut band, 1.0).unwrap().unwrap_err();
        assert!(format!("{err:#}").contains("warp"), "{err:#}");
    }
}
