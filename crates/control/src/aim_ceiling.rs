//! The aim ceiling: how many frames of a run any controller that plans its frames at one
//! time could have kept in the band, against the run's own prediction errors.
//!
//! A controller that predicts its frames plans each at some time and meets an error: the
//! frame takes `ratio` times its prediction (the machine's noise, spikes included, and the
//! prediction's own lag). Planned at time c, a frame lands in the band when
//! Tmin ≤ c · ratio ≤ Tmax. Over a run's measured ratios, the best single c keeps some share
//! of the frames in the band and no aim can keep more: what is missing below that share is
//! the controller's to win, what is missing above it the machine's (or the predictor's).
//! `bench` reports it beside each predicting controller's share in the band.

use crate::band::Band;
use serde::{Deserialize, Serialize};

/// The best one planned frame time could do against a run's prediction errors.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AimCeiling {
    /// A planned time that keeps the most frames in the band, ms (the middle of the first
    /// stretch of such times).
    pub planned_ms: f64,
    /// The share of the frames (%) that time keeps in the band.
    pub in_band_pct: f64,
    /// Frames measured (the ratios taken).
    pub frames: usize,
}

/// The aim ceiling of the frames whose measured time was `ratio` times their prediction
/// (ratios that are not finite and positive are left out); `None` without any.
///
/// Each frame is kept by the planned times in [Tmin / ratio, Tmax / ratio]; the most such
/// intervals overlapping at one time is found by a sweep over their ends.
pub fn aim_ceiling(ratios: impl IntoIterator<Item = f64>, band: Band) -> Option<AimCeiling> {
    // (planned time, +1 where a frame's interval opens, -1 where it closes); opens sort
    // before closes at one time because the band's ends are inclusive.
    let mut ends: Vec<(f64, i32)> = ratios
        .into_iter()
        .filter(|r| r.is_finite() && *r > 0.0)
        .flat_map(|r| [(band.tmin_ms() / r, 1), (band.tmax_ms() / r, -1)])
        .collect();
    if ends.is_empty() {
        return None;
    }
    ends.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
    let frames = ends.len() / 2;
    let (mut open, mut best, mut best_from, mut best_to) = (0, 0, 0.0, 0.0);
    for (i, &(at, step)) in ends.iter().enumerate() {
        open += step;
        if open > best {
            best = open;
            best_from = at;
            best_to = ends.get(i + 1).map_or(at, |next| next.0);
        }
    }
    Some(AimCeiling {
        planned_ms: 0.5 * (best_from + best_to),
        in_band_pct: 100.0 * f64::from(best) / frames as f64,
        frames,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(ratios: &[f64], planned: f64) -> usize {
        ratios
            .iter()
            .filter(|&&r| Band::PAPER.contains(planned * r))
            .count()
    }

    #[test]
    fn a_spike_the_band_can_absorb_is_kept_by_aiming_low() {
        // [15, 20] holds 1.0 and 1.3 together from 15 to 15.38 ms.
        let c = aim_ceiling([1.0, 1.0, 1.3], Band::PAPER).unwrap();
        assert_eq!(c.in_band_pct, 100.0);
        assert_eq!(c.frames, 3);
        assert!((15.0..=20.0 / 1.3).contains(&c.planned_ms), "{c:?}");
    }

    #[test]
    fn errors_wider_than_the_band_cost_frames() {
        let ratios = [0.7, 1.0, 1.0, 1.0, 1.6];
        let c = aim_ceiling(ratios, Band::PAPER).unwrap();
        assert_eq!(c.in_band_pct, 60.0);
        assert_eq!(kept(&ratios, c.planned_ms), 3);
    }

    #[test]
    fn no_planned_time_on_a_grid_beats_the_ceiling() {
        let ratios: Vec<f64> = (0..200)
            .map(|i| 0.9 + 0.4 * ((f64::from(i) * 0.618_034).fract()).powi(3))
            .collect();
        let c = aim_ceiling(ratios.iter().copied(), Band::PAPER).unwrap();
        assert_eq!(kept(&ratios, c.planned_ms) as f64 / 2.0, c.in_band_pct);
        for i in 0..=1000 {
            let planned = 10.0 + 0.012 * f64::from(i);
            assert!(kept(&ratios, planned) as f64 / 2.0 <= c.in_band_pct);
        }
    }

    #[test]
    fn frames_without_a_usable_ratio_are_left_out() {
        assert_eq!(aim_ceiling([], Band::PAPER), None);
        assert_eq!(aim_ceiling([f64::NAN, 0.0, -1.0], Band::PAPER), None);
        let c = aim_ceiling([f64::INFINITY, 1.0], Band::PAPER).unwrap();
        assert_eq!((c.frames, c.in_band_pct), (1, 100.0));
    }
}
