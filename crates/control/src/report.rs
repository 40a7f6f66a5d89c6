//! What a rendered frame tells the controller, and which reports are refused.

use crate::quality::Quality;
use serde::{Deserialize, Serialize};
use std::time::Duration;
use steadyray_budget::FirstSample;
use thiserror::Error;

/// The longest frame time a report may claim, ms (one minute). Longer times are refused as
/// absurd: a broken timer or a suspended process, not information about the renderer.
pub const MAX_FRAME_MS: f64 = 60_000.0;

/// The measurements of one rendered frame, as a controller sees them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameReport {
    /// Tp: the image-generation time, ms.
    pub tp_ms: f64,
    /// `rays_per_depth[k]`: rays traced after k reflection/refraction events (k = 0: eye
    /// rays). Length R + 1 for a frame rendered with depth R.
    pub rays_per_depth: Vec<u64>,
    /// Shadow rays toward the lights.
    pub shadow_rays: u64,
    /// Chains the depth limit ended at a mirror or a dielectric: the rays level R + 1 would
    /// trace, not traced (`None` when the renderer does not count them). With it the
    /// `predictive` controller knows how far the next level reaches instead of guessing.
    #[serde(default)]
    pub rays_stopped: Option<u64>,
    /// Pixels rendered (after the resolution scale).
    pub pixels: u64,
    /// The quality this frame was rendered with.
    pub quality: Quality,
    /// How fast what the frame shows moves on screen, degrees of visual angle per second
    /// (the renderer's measure of motion; 0 for a still view or when nobody measured it).
    /// Only the `perceptual` controller reads it: it picks the frame rate from it.
    #[serde(default)]
    pub speed_deg_s: f64,
    /// For a frame rendered within a time budget ([`crate::FrameBudget`]): its first
    /// sample of every pixel, the part its quality fixed (`None` for a frame rendered
    /// whole). The budget holds the whole frame's time and lets its rays vary instead, so
    /// the frame's (rays, Tp) no longer show the cost of a ray; this part's still do, and
    /// `predictive` fits its cost model on it.
    #[serde(default)]
    pub first_sample: Option<FirstSample>,
}

/// Why a report was refused. A refused report changes nothing: every controller returns the
/// error, keeps its quality and leaves its history and model untouched.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ReportError {
    /// Tp is NaN or infinite.
    #[error("frame time {0} ms is not a finite number")]
    NotFinite(f64),
    /// Tp is zero or negative (a timer that did not tick or ran backwards).
    #[error("frame time {0} ms is not positive")]
    NotPositive(f64),
    /// Tp is longer than [`MAX_FRAME_MS`].
    #[error("frame time {0} ms is absurd (over {MAX_FRAME_MS} ms)")]
    Absurd(f64),
    /// The predictive controller needs ray counts and a pixel count; this report has none.
    #[error("the report has no rays or no pixels: the predictive controller needs both")]
    NoRays,
    /// A first sample ([`FrameReport::first_sample`]) without rays, or whose time is not
    /// a number above 0 ms and at most the frame's.
    #[error(
        "the first sample's time {0} ms is not above 0 and at most the frame's, or it has no rays"
    )]
    BadFirstSample(f64),
    /// The screen speed is NaN, infinite or negative (the `perceptual` controller reads it).
    #[error("screen speed {0} deg/s is invalid: it must be a finite number, 0 or more")]
    BadSpeed(f64),
}

impl FrameReport {
    /// The report of an engine that counts no rays, only the pixels it shaded (after the
    /// render scale): a frame of `pixels` pixels at `quality`, which took `frame_time`. Its
    /// work is `pixels` × S eye samples and nothing deeper, so `predictive` predicts the
    /// render scale's and S's costs exactly and leaves the depth where it is (a renderer
    /// that bounces should report its rays per depth instead).
    pub fn from_pixels(frame_time: Duration, pixels: u64, quality: Quality) -> Self {
        let samples = (pixels as f64 * f64::from(quality.spp.max(1.0))).round() as u64;
        let mut rays_per_depth = vec![0; quality.depth as usize + 1];
        rays_per_depth[0] = samples;
        Self {
            tp_ms: frame_time.as_secs_f64() * 1e3,
            rays_per_depth,
            shadow_rays: 0,
            rays_stopped: None,
            pixels,
            quality,
            speed_deg_s: 0.0,
            first_sample: None,
        }
    }

    /// All rays: every depth and the shadow rays.
    pub fn total_rays(&self) -> u64 {
        self.rays_per_depth.iter().sum::<u64>() + self.shadow_rays
    }

    /// Checks Tp: finite, positive and at most [`MAX_FRAME_MS`].
    pub fn check_time(&self) -> Result<(), ReportError> {
        let t = self.tp_ms;
        if !t.is_finite() {
            Err(ReportError::NotFinite(t))
        } else if t <= 0.0 {
            Err(ReportError::NotPositive(t))
        } else if t > MAX_FRAME_MS {
            Err(ReportError::Absurd(t))
        } else {
            Ok(())
        }
    }

    /// Checks Tp and that the frame has pixels and eye rays (what a cost model needs).
    pub fn check_rays(&self) -> Result<(), ReportError> {
        self.check_time()?;
        if self.pixels == 0 || self.rays_per_depth.first().copied().unwrap_or(0) == 0 {
            return Err(ReportError::NoRays);
        }
        match self.first_sample {
            Some(first)
                if !(first.ms.is_finite() && first.ms > 0.0 && first.ms <= self.tp_ms)
                    || first.rays == 0 =>
            {
                Err(ReportError::BadFirstSample(first.ms))
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(tp_ms: f64) -> FrameReport {
        FrameReport {
            tp_ms,
            rays_per_depth: vec![100, 50],
            rays_stopped: None,
            shadow_rays: 30,
            pixels: 100,
            quality: Quality::new(1.0, 1, 1.0),
            speed_deg_s: 0.0,
            first_sample: None,
        }
    }

    #[test]
    fn time_checks() {
        assert!(report(16.0).check_time().is_ok());
        assert!(matches!(
            report(f64::NAN).check_time(),
            Err(ReportError::NotFinite(_))
        ));
        assert!(matches!(
            report(f64::INFINITY).check_time(),
            Err(ReportError::NotFinite(_))
        ));
        assert_eq!(report(0.0).check_time(), Err(ReportError::NotPositive(0.0)));
        assert_eq!(
            report(-3.0).check_time(),
            Err(ReportError::NotPositive(-3.0))
        );
        assert_eq!(
            report(61_000.0).check_time(),
            Err(ReportError::Absurd(61_000.0))
        );
        assert_eq!(report(16.0).total_rays(), 180);
    }

    #[test]
    fn ray_checks() {
        let mut r = report(16.0);
        assert!(r.check_rays().is_ok());
        r.pixels = 0;
        assert_eq!(r.check_rays(), Err(ReportError::NoRays));
        r.pixels = 100;
        r.rays_per_depth.clear();
        assert_eq!(r.check_rays(), Err(ReportError::NoRays));
    }
}
