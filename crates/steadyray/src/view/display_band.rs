//! `view --band refresh[:M]` (the view's default band): the band derived from the window's display, as `bench --band`
//! derives it from the display model. The refresh rate is the monitor's (60 Hz where it does
//! not say); the hand-over is what giving a frame to the window costs (the tone map and
//! upload of the CPU backend, the GPU's hand-over of its image), measured over the first
//! frames, after as many unmeasured ones.

use anyhow::Result;
use steadyray_display::{DisplayConfig, SyncMode, aligned_band, stats::quantile};

/// Frames measured (after as many unmeasured) before the band is set.
pub const HAND_OVER_FRAMES: usize = 10;

/// The refresh rate assumed when the monitor does not report one, Hz.
pub const FALLBACK_REFRESH_HZ: f64 = 60.0;

/// A display-aligned band waiting for its hand-over to be measured.
#[derive(Debug)]
pub struct DisplayBand {
    multiple: u32,
    display: DisplayConfig,
    seen: usize,
    hand_over_ms: Vec<f64>,
}

/// The band once measured, and what it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlignedBand {
    pub tmin_ms: f64,
    pub tmax_ms: f64,
    pub refresh_hz: f64,
    pub hand_over_ms: f64,
}

impl DisplayBand {
    /// Every `multiple`-th refresh of a display at `refresh_hz` (vsync on), or at
    /// [`FALLBACK_REFRESH_HZ`] when the monitor does not say.
    pub fn new(multiple: u32, refresh_hz: Option<f64>) -> Result<Self> {
        let hz = refresh_hz
            .filter(|hz| hz.is_finite() && *hz > 0.0)
            .unwrap_or(FALLBACK_REFRESH_HZ);
        Ok(Self {
            multiple: multiple.max(1),
            display: DisplayConfig::new(hz, SyncMode::Vsync)?,
            seen: 0,
            hand_over_ms: Vec::with_capacity(HAND_OVER_FRAMES),
        })
    }

    /// Takes one frame's hand-over; once enough are measured, the band (median hand-over),
    /// or why the display leaves no band (a hand-over longer than the frame interval).
    pub fn observe(&mut self, hand_over_ms: f64) -> Option<Result<AlignedBand>> {
        self.seen += 1;
        if self.seen <= HAND_OVER_FRAMES || !hand_over_ms.is_finite() {
            return None;
        }
        self.hand_over_ms.push(hand_over_ms);
        if self.hand_over_ms.len() < HAND_OVER_FRAMES {
            return None;
        }
        let median = quantile(&self.hand_over_ms, 0.5)?;
        // The window shows no warped refreshes: nothing else shares the frame interval.
        Some(
            aligned_band(&self.display, self.multiple, median, 0.0)
                .map(|(tmin_ms, tmax_ms)| AlignedBand {
                    tmin_ms,
                    tmax_ms,
                    refresh_hz: self.display.refresh_hz,
                    hand_over_ms: median,
                })
                .map_err(anyhow::Error::from),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measured(band: &mut DisplayBand, ms: f64) -> Option<Result<AlignedBand>> {
        (0..2 * HAND_OVER_FRAMES).find_map(|_| band.observe(ms))
    }

    #[test]
    fn the_band_comes_after_the_measured_frames_and_fits_the_refresh() {
        let mut band = DisplayBand::new(1, Some(60.0)).unwrap();
        for _ in 0..2 * HAND_OVER_FRAMES - 1 {
            assert!(band.observe(1.0).is_none());
        }
        let b = band.observe(1.0).unwrap().unwrap();
        // 16.67 ms · 0.95 − 1 ms and 0.2 · 16.67 ms below it.
        assert!((b.tmax_ms - (1000.0 / 60.0 * 0.95 - 1.0)).abs() < 1e-9);
        assert!((b.tmax_ms - b.tmin_ms - 1000.0 / 60.0 * 0.2).abs() < 1e-9);
        assert_eq!((b.refresh_hz, b.hand_over_ms), (60.0, 1.0));
    }

    #[test]
    fn every_second_refresh_and_an_unknown_monitor() {
        let mut band = DisplayBand::new(2, None).unwrap();
        let b = measured(&mut band, 2.0).unwrap().unwrap();
        assert_eq!(b.refresh_hz, FALLBACK_REFRESH_HZ);
        assert!((b.tmax_ms - (2000.0 / 60.0 * 0.95 - 2.0)).abs() < 1e-9);
    }

    #[test]
    fn a_hand_over_longer_than_the_frame_is_an_error() {
        let mut band = DisplayBand::new(1, Some(144.0)).unwrap();
        let err = measured(&mut band, 9.0).unwrap().unwrap_err();
        assert!(format!("{err:#}").contains("hand-over"), "{err:#}");
    }
}
