//! Predicts the rays a candidate quality would trace, from the last frame's rays per depth.
//!
//! Rays scale with pixels · S (pixels ∝ scale²). Per eye sample, level k carries
//! n_k / (pixels · S) rays; levels up to the frame's depth R are measured, and level R + 1
//! too when the renderer counts the chains its depth limit stopped at a mirror or dielectric
//! ([`FrameReport::rays_stopped`]: exactly the rays level R + 1 would trace); deeper levels
//! are extrapolated with the decay ratio ρ = (n_1 + … + n_R) / (n_0 + … + n_(R−1)): the measured
//! levels' ratio to the level before, averaged with their rays as weights (fewer rays reach
//! each deeper level; ρ is clamped to [0, 1] because one branch per sample never multiplies
//! rays). Not the ratio of the two deepest levels alone: on a view whose rays die out before
//! R those are a handful of rays or none (one ray, then none, reads as ρ = 0), and a frame at
//! R = 0, which measures no ratio, carries the last one; carried as 0, no level beyond 0
//! looked reached, and R was never raised again (`predictive` at a one-refresh band with
//! the temporal mode, cut to R = 0 by one slow frame, held it for the rest of the run).
//! Shadow rays are taken proportional to the other rays.

use crate::quality::Quality;
use crate::report::FrameReport;

/// The decay ratio assumed before any frame with R >= 1 was seen.
pub const DEFAULT_DECAY: f64 = 0.5;

/// The scene's load as seen in one frame, independent of the quality it was rendered at.
#[derive(Clone, Debug, PartialEq)]
pub struct RayModel {
    /// Rays at level k per eye sample, for the measured levels 0..=R.
    per_sample: Vec<f64>,
    /// Shadow rays per eye or secondary ray.
    shadow_ratio: f64,
    /// Pixels at scale 1.
    full_pixels: f64,
    /// Ratio between successive levels beyond the measured ones.
    decay: f64,
}

impl RayModel {
    /// The load measured by `report` (which must pass [`FrameReport::check_rays`]).
    /// `last_decay` is used when the frame has no two levels to measure the decay from.
    pub fn from_report(report: &FrameReport, last_decay: f64) -> Self {
        let q = report.quality;
        let pixels = report.pixels as f64;
        let samples = pixels * f64::from(q.spp.max(1.0));
        // The measured levels, and the next one when the renderer counted it.
        let levels: Vec<u64> = report
            .rays_per_depth
            .iter()
            .copied()
            .chain(report.rays_stopped)
            .collect();
        let per_sample: Vec<f64> = levels.iter().map(|&n| n as f64 / samples).collect();
        let path_rays: u64 = report.rays_per_depth.iter().sum();
        let n = levels.len();
        let shallow: u64 = levels[..n.saturating_sub(1)].iter().sum();
        let decay = if n >= 2 && shallow > 0 {
            let deep: u64 = levels[1..].iter().sum();
            (deep as f64 / shallow as f64).clamp(0.0, 1.0)
        } else {
            last_decay
        };
        let scale = f64::from(q.scale).max(1e-3);
        Self {
            per_sample,
            shadow_ratio: report.shadow_rays as f64 / path_rays.max(1) as f64,
            full_pixels: pixels / (scale * scale),
            decay,
        }
    }

    /// The decay ratio between successive deep levels.
    pub fn decay(&self) -> f64 {
        self.decay
    }

    /// The deepest measured level (R, or R + 1 when the frame counted the stopped chains).
    pub fn measured_depth(&self) -> u32 {
        self.per_sample.len().saturating_sub(1) as u32
    }

    /// Rays at level k per eye sample (measured, or extrapolated beyond the measured depth).
    fn level(&self, k: u32) -> f64 {
        let top = self.measured_depth();
        match self.per_sample.get(k as usize) {
            Some(v) => *v,
            None => {
                self.per_sample.last().copied().unwrap_or(0.0) * self.decay.powi((k - top) as i32)
            }
        }
    }

    /// The fraction of eye rays that reach level k.
    pub fn reach(&self, k: u32) -> f64 {
        let eye = self.level(0);
        if eye > 0.0 { self.level(k) / eye } else { 0.0 }
    }

    /// The deepest level in [lo, hi] up to which every level is reached by at least
    /// `min_reach` of the eye rays (at least `lo`).
    pub fn useful_depth(&self, min_reach: f64, lo: u32, hi: u32) -> u32 {
        (lo + 1..=hi)
            .take_while(|&k| self.reach(k) >= min_reach)
            .last()
            .unwrap_or(lo)
    }

    /// Predicted rays (all levels and shadow rays) for a frame at quality `q`.
    pub fn rays(&self, q: &Quality) -> f64 {
        let scale = f64::from(q.scale);
        let samples = self.full_pixels * scale * scale * f64::from(q.spp);
        let per_sample: f64 = (0..=q.depth).map(|k| self.level(k)).sum();
        samples * per_sample * (1.0 + self.shadow_ratio)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report() -> FrameReport {
        FrameReport {
            tp_ms: 10.0,
            // 1000 pixels at scale 0.5, S = 2: 2000 eye rays, half go one level deeper.
            rays_per_depth: vec![2000, 1000, 500],
            rays_stopped: None,
            shadow_rays: 350,
            pixels: 1000,
            quality: Quality::new(2.0, 2, 0.5),
            speed_deg_s: 0.0,
            first_sample: None,
        }
    }

    #[test]
    fn reproduces_the_measured_frame() {
        let m = RayModel::from_report(&report(), DEFAULT_DECAY);
        assert!((m.rays(&report().quality) - 3850.0).abs() < 1e-6);
        assert_eq!(m.decay(), 0.5);
    }

    #[test]
    fn scales_with_pixels_and_samples_and_extrapolates_depth() {
        let m = RayModel::from_report(&report(), DEFAULT_DECAY);
        // Scale 1 has 4x the pixels; S = 1 halves the samples.
        assert!((m.rays(&Quality::new(1.0, 2, 1.0)) - 2.0 * 3850.0).abs() < 1e-6);
        // Depth 3 adds 250 rays per 2000 eye rays, plus shadows in proportion.
        let deeper = m.rays(&Quality::new(2.0, 3, 0.5));
        assert!((deeper - 3750.0 * 1.1).abs() < 1e-6);
        assert!((m.reach(4) - 0.0625).abs() < 1e-12);
        assert_eq!(m.useful_depth(0.1, 0, 16), 3);
        assert_eq!(m.useful_depth(0.9, 1, 16), 1);
    }

    #[test]
    fn rays_that_die_out_before_the_depth_do_not_read_as_no_decay() {
        // Eye rays 10000; 3000, 900 and 270 reach levels 1 to 3, one ray level 4, none 5.
        let mut r = report();
        r.rays_per_depth = vec![10_000, 3000, 900, 270, 1, 0];
        r.quality = Quality::new(1.0, 5, 1.0);
        r.pixels = 10_000;
        let m = RayModel::from_report(&r, DEFAULT_DECAY);
        assert!(
            (m.decay() - 4171.0 / 14171.0).abs() < 1e-12,
            "{}",
            m.decay()
        );
        // A frame at R = 0 carries it, so levels beyond 0 still look reached.
        let mut flat = report();
        flat.rays_per_depth = vec![10_000];
        flat.quality = Quality::new(1.0, 0, 1.0);
        flat.pixels = 10_000;
        let at_zero = RayModel::from_report(&flat, m.decay());
        assert_eq!(at_zero.decay(), m.decay());
        assert_eq!(at_zero.useful_depth(0.02, 0, 16), 3);
    }
}
