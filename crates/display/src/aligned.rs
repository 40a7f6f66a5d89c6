//! A frame-time band aligned with the display: render times whose frames, handed over, make
//! every M-th refresh. On a 60 Hz display with vsync a frame that takes 17 ms misses its
//! refresh and waits for the next: the paper's 15–20 ms band straddles the refresh and shows
//! most frames every second refresh anyway, with the time between spent idle. Where the
//! refreshes between two frames show the last frame warped to their own camera, made on the
//! same machine as the frames, the band leaves room for those warps too.

use crate::config::{DisplayConfig, SyncMode};
use crate::error::DisplayError;

/// The time kept free under the target refresh for timing noise, as a fraction of the frame
/// interval (5 %: the noise a controller holding its band still sees).
pub const ALIGNED_MARGIN: f64 = 0.05;
/// The band's width as a fraction of the frame interval (the paper's band is 5 ms of 20).
pub const ALIGNED_WIDTH: f64 = 0.2;

/// What an aligned band keeps free under its refresh for timing noise (`margin`) and how
/// wide it is (`width`), as fractions of the frame interval: a controller that builds its own
/// bands (`perceptual`) chooses its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandShape {
    /// Kept free under the refresh, as a fraction of the frame interval.
    pub margin: f64,
    /// The band's width, as a fraction of the frame interval.
    pub width: f64,
}

impl BandShape {
    /// [`ALIGNED_MARGIN`] and [`ALIGNED_WIDTH`]: the band of `bench --band` and `view`.
    pub const ALIGNED: BandShape = BandShape {
        margin: ALIGNED_MARGIN,
        width: ALIGNED_WIDTH,
    };
}

/// The band [Tmin, Tmax] of render times for frames shown every `multiple` refreshes, each
/// frame handed over in `hand_over_ms` and followed, when the refreshes between frames are
/// warped (0 when they are not), by `multiple` − 1 warps of `warp_ms` each: the frame
/// interval I = `multiple` · P (with variable refresh, P at the range's maximum),
/// Tmax = I · (1 − [`ALIGNED_MARGIN`]) − `hand_over_ms` − (`multiple` − 1) · `warp_ms`,
/// Tmin = Tmax − [`ALIGNED_WIDTH`] · I, and with vsync on at least (`multiple` − 1) · P −
/// `hand_over_ms`: a frame done sooner makes the refresh before on its own and is shown a
/// refresh early (a warp is made only where it does not cost its frame a refresh, so the
/// refresh before it goes unwarped). That floor binds at three refreshes with warps (with
/// warps of 6.5 ms at 60 Hz it leaves a band about 1 ms wide) and, without warps, from five
/// refreshes a frame.
pub fn aligned_band(
    config: &DisplayConfig,
    multiple: u32,
    hand_over_ms: f64,
    warp_ms: f64,
) -> Result<(f64, f64), DisplayError> {
    shaped_band(config, multiple, hand_over_ms, warp_ms, BandShape::ALIGNED)
}

/// [`aligned_band`] with another margin and width (`shape`).
pub fn shaped_band(
    config: &DisplayConfig,
    multiple: u32,
    hand_over_ms: f64,
    warp_ms: f64,
    shape: BandShape,
) -> Result<(f64, f64), DisplayError> {
    for (name, value) in [("hand-over", hand_over_ms), ("warp", warp_ms)] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(DisplayError::BadFrameTime {
                name,
                value,
                why: "it must be a finite number of ms, 0 or more",
            });
        }
    }
    let period = match config.sync {
        SyncMode::Vrr(range) => range.min_interval_ms(),
        SyncMode::Vsync | SyncMode::Off => config.period_ms(),
    };
    let multiple = multiple.max(1);
    let interval = f64::from(multiple) * period;
    let warps_ms = f64::from(multiple - 1) * warp_ms;
    let tmax = interval * (1.0 - shape.margin) - hand_over_ms - warps_ms;
    let mut tmin = tmax - shape.width * interval;
    if tmin <= 0.0 {
        return Err(DisplayError::BadFrameTime {
            name: "hand-over and warps",
            value: hand_over_ms + warps_ms,
            why: "it leaves no render time in a frame interval of this display: take more refreshes per frame",
        });
    }
    if config.sync == SyncMode::Vsync && multiple > 1 {
        let early = f64::from(multiple - 1) * period - hand_over_ms;
        if early >= tmax {
            return Err(DisplayError::BadFrameTime {
                name: "warp",
                value: warp_ms,
                why: "a frame that leaves room for the warps between frames makes the refresh before on its own: take fewer refreshes per frame",
            });
        }
        tmin = tmin.max(early);
    }
    Ok((tmin, tmax))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_under_one_and_two_refreshes_at_60_hz() {
        let display = DisplayConfig::new(60.0, SyncMode::Vsync).unwrap();
        let (tmin, tmax) = aligned_band(&display, 1, 1.6, 0.0).unwrap();
        // 16.667 · 0.95 − 1.6 = 14.233; minus 3.333.
        assert!(
            (tmax - 14.2333).abs() < 1e-3 && (tmin - 10.9).abs() < 1e-3,
            "{tmin} {tmax}"
        );
        let (tmin, tmax) = aligned_band(&display, 2, 1.6, 0.0).unwrap();
        assert!(
            (tmax - 30.0667).abs() < 1e-3 && (tmin - 23.4).abs() < 1e-3,
            "{tmin} {tmax}"
        );
        let err = aligned_band(&display, 1, 14.0, 0.0).unwrap_err();
        assert!(err.to_string().contains("more refreshes"), "{err}");
        assert!(aligned_band(&display, 1, f64::NAN, 0.0).is_err());
    }

    #[test]
    fn warped_refreshes_between_frames_take_their_time_from_the_band() {
        let display = DisplayConfig::new(60.0, SyncMode::Vsync).unwrap();
        // One refresh a frame has no refresh between frames: the warp changes nothing.
        assert_eq!(
            aligned_band(&display, 1, 1.6, 6.5).unwrap(),
            aligned_band(&display, 1, 1.6, 0.0).unwrap()
        );
        // Two: one warp of 6.5 ms after each frame; three: two.
        let (tmin, tmax) = aligned_band(&display, 2, 1.6, 6.5).unwrap();
        assert!(
            (tmax - 23.5667).abs() < 1e-3 && (tmin - 16.9).abs() < 1e-3,
            "{tmin} {tmax}"
        );
        let (tmin, tmax) = aligned_band(&display, 3, 1.6, 6.5).unwrap();
        assert!((tmax - (50.0 * 0.95 - 1.6 - 13.0)).abs() < 1e-9, "{tmax}");
        // Not Tmax − 10 ms = 22.9: a frame of 30 ms and its hand-over make the second
        // refresh, and are shown there with the refresh before it unwarped.
        assert!((tmin - (2.0 * 50.0 / 3.0 - 1.6)).abs() < 1e-9, "{tmin}");
        // Warps of 7.5 ms leave three refreshes no band (a frame that leaves room for them
        // makes the second refresh); without warps five refreshes need the floor too.
        let err = aligned_band(&display, 3, 1.6, 7.5).unwrap_err();
        assert!(err.to_string().contains("fewer refreshes"), "{err}");
        let (tmin, _) = aligned_band(&display, 5, 1.6, 0.0).unwrap();
        assert!((tmin - (4.0 * 50.0 / 3.0 - 1.6)).abs() < 1e-9, "{tmin}");
        // Warps that fill the interval leave no band; a warp's cost must be a time.
        let err = aligned_band(&display, 2, 1.6, 25.0).unwrap_err();
        assert!(err.to_string().contains("hand-over and warps"), "{err}");
        let err = aligned_band(&display, 2, 1.6, -1.0).unwrap_err();
        assert!(err.to_string().contains("warp"), "{err}");
        assert!(aligned_band(&display, 2, 1.6, f64::INFINITY).is_err());
    }
}
