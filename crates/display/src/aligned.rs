//! A frame-time band aligned with the display: render times whose frames, handed over, make
//! every M-th refresh. On a 60 Hz display with vsync a frame that takes 17 ms misses its
//! refresh and waits for the next: the paper's 15–20 ms band straddles the refresh and shows
//! most frames every second refresh anyway, with the time between spent idle.

use crate::config::{DisplayConfig, SyncMode};
use crate::error::DisplayError;

/// The time kept free under the target refresh for timing noise, as a fraction of the frame
/// interval (5 %: the noise a controller holding its band still sees).
pub const ALIGNED_MARGIN: f64 = 0.05;
/// The band's width as a fraction of the frame interval (the paper's band is 5 ms of 20).
pub const ALIGNED_WIDTH: f64 = 0.2;

/// The band [Tmin, Tmax] of render times for frames shown every `multiple` refreshes: the
/// frame interval I = `multiple` · P (with variable refresh, P at the range's maximum),
/// Tmax = I · (1 − [`ALIGNED_MARGIN`]) − `hand_over_ms`, Tmin = Tmax − [`ALIGNED_WIDTH`] · I.
pub fn aligned_band(
    config: &DisplayConfig,
    multiple: u32,
    hand_over_ms: f64,
) -> Result<(f64, f64), DisplayError> {
    if !(hand_over_ms.is_finite() && hand_over_ms >= 0.0) {
        return Err(DisplayError::BadFrameTime {
            name: "hand-over",
            value: hand_over_ms,
            why: "it must be a finite number of ms, 0 or more",
        });
    }
    let period = match config.sync {
        SyncMode::Vrr(range) => range.min_interval_ms(),
        SyncMode::Vsync | SyncMode::Off => config.period_ms(),
    };
    let interval = f64::from(multiple.max(1)) * period;
    let tmax = interval * (1.0 - ALIGNED_MARGIN) - hand_over_ms;
    let tmin = tmax - ALIGNED_WIDTH * interval;
    if tmin <= 0.0 {
        return Err(DisplayError::BadFrameTime {
            name: "hand-over",
            value: hand_over_ms,
            why: "it leaves no render time in a frame interval of this display: take more refreshes per frame",
        });
    }
    Ok((tmin, tmax))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_under_one_and_two_refreshes_at_60_hz() {
        let display = DisplayConfig::new(60.0, SyncMode::Vsync).unwrap();
        let (tmin, tmax) = aligned_band(&display, 1, 1.6).unwrap();
        // 16.667 · 0.95 − 1.6 = 14.233; minus 3.333.
        assert!(
            (tmax - 14.2333).abs() < 1e-3 && (tmin - 10.9).abs() < 1e-3,
            "{tmin} {tmax}"
        );
        let (tmin, tmax) = aligned_band(&display, 2, 1.6).unwrap();
        assert!(
            (tmax - 30.0667).abs() < 1e-3 && (tmin - 23.4).abs() < 1e-3,
            "{tmin} {tmax}"
        );
        let err = aligned_band(&display, 1, 14.0).unwrap_err();
        assert!(err.to_string().contains("more refreshes"), "{err}");
        assert!(aligned_band(&display, 1, f64::NAN).is_err());
    }
}
