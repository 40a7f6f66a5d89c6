//! The online cost model Tp ≈ fixed_ms + ms_per_ray · rays, fitted from recent frames.
//!
//! A weighted least-squares line with exponential forgetting (old frames fade with factor
//! `forgetting` per frame) and a weak prior pulling the intercept toward 0, so the fit stays
//! defined when every recent frame traced about the same number of rays (the slope is then
//! Tp / rays). Robust to one-frame spikes: a frame whose residual exceeds `outlier_k` robust
//! standard deviations (1.4826 · MAD of recent relative residuals, floored) is not fitted.
//! If `confirm` outliers in a row lie on the same side, the cost really changed (a heavier
//! scene, another machine state): old frames are then forgotten and the model restarts from
//! the confirming ones (taking a rise as a cost per ray where their rays are too close to
//! split it: [`SLOPE_SPAN`]). So it does after [`DRIFT_RUN`] fitted frames in a row that all ran
//! slower (or all faster) than predicted by more than [`DRIFT_K`] robust standard
//! deviations: a cost that drifts a little each frame (a mesh filling more of the view) is
//! never an outlier, and a line fitted across the drift blames it on the fixed cost, which
//! then makes every cut far too deep.

use std::collections::VecDeque;

/// How many recent relative residuals the robust scale looks at.
const RESIDUAL_WINDOW: usize = 32;
/// How many recent prediction errors [`CostModel::recent_errors`] keeps: enough to tell
/// a machine's spikes (one frame in twenty on the idle 2-core VM) from its jitter with a
/// counting error of about 1 % (48 errors left it near 3 %, and the aim moved on it).
pub const ERROR_WINDOW: usize = 240;
/// Fitted frames in a row off their prediction on one side that confirm a drift of cost.
pub const DRIFT_RUN: usize = 3;
/// How far off (robust standard deviations) a fitted frame counts towards a drift. Three in
/// a row beyond 2 on one side happen by chance about once in 40,000 frames of Gaussian
/// noise; at 1.5 a coarse (1 ms) timer's rounding, which errs on one side for many frames
/// at a steady load, set off drifts that moved the quality for nothing.
pub const DRIFT_K: f64 = 2.0;
/// The confirming frames of a change of cost refit the whole line only if the most rays
/// among them are at least this many times the fewest; frames closer together cannot tell a
/// fixed cost from a cost per ray, and a line through two slow frames of a noisy machine
/// could then blame the fixed cost for all of it (on the 2-core VM, 15.7 ms at 380 k rays
/// and 19.4 ms at 277 k gave a fixed cost of 14 ms, and `predictive` cut a one-refresh band's
/// frames to R = 0 at scale 0.25). Where such a restart would raise the fixed cost, it takes
/// the change as a cost per ray instead: the reading that cuts less deep for the same
/// frames, and one that the next frames' other ray counts correct.
pub const SLOPE_SPAN: f64 = 2.0;

/// Parameters of [`CostModel`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct CostParams {
    /// Weight decay per frame, in (0, 1]: 0.95 remembers about the last 20 frames.
    pub forgetting: f64,
    /// Outlier threshold in robust standard deviations. Default 4.
    pub outlier_k: f64,
    /// Floor of the relative standard deviation (timer and scheduling noise). Default 0.03.
    pub min_sigma: f64,
    /// Floor of the absolute standard deviation, ms (timer resolution). Default 0.25.
    pub min_sigma_ms: f64,
    /// Outliers in a row, all on one side, that confirm a real change of cost. Default 2.
    pub confirm: u32,
    /// Weight of the prior "fixed_ms = 0", in frames. It decides the split between fixed and
    /// per-ray cost only when recent ray counts vary by less than about √(weight / frames
    /// remembered), ≈ 5 % with the defaults. Default 0.05.
    pub prior_weight: f64,
}

impl Default for CostParams {
    fn default() -> Self {
        Self {
            forgetting: 0.95,
            outlier_k: 4.0,
            min_sigma: 0.03,
            min_sigma_ms: 0.25,
            confirm: 2,
            prior_weight: 0.05,
        }
    }
}

/// What the model did with a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fit {
    /// The frame agreed with the model and was fitted.
    Accepted,
    /// The frame disagreed too much and was set aside (a hitch, or the first frame of a
    /// change not yet confirmed).
    Outlier,
    /// Enough outliers in a row confirmed a change of cost; the model was refitted to them.
    Shifted,
}

/// Tp ≈ fixed_ms + ms_per_ray · rays, fitted online (see the module documentation).
#[derive(Clone, Debug)]
pub struct CostModel {
    params: CostParams,
    /// Weighted sums over frames of 1, x, y, x², xy, with x in millions of rays, y in ms.
    sums: [f64; 5],
    fixed_ms: f64,
    ms_per_mray: f64,
    fitted: bool,
    residuals: VecDeque<f64>,
    errors: VecDeque<f64>,
    pending: Vec<(f64, f64)>,
    /// The current run of fitted frames off their prediction on one side (`drift_above`).
    drift: Vec<(f64, f64)>,
    drift_above: bool,
}

impl CostModel {
    /// An empty model: it predicts nothing until it has seen a frame.
    pub fn new(params: CostParams) -> Self {
        Self {
            params,
            sums: [0.0; 5],
            fixed_ms: 0.0,
            ms_per_mray: 0.0,
            fitted: false,
            residuals: VecDeque::with_capacity(RESIDUAL_WINDOW),
            errors: VecDeque::with_capacity(ERROR_WINDOW),
            pending: Vec::new(),
            drift: Vec::new(),
            drift_above: false,
        }
    }

    /// The fitted fixed cost per frame, ms.
    pub fn fixed_ms(&self) -> f64 {
        self.fixed_ms
    }

    /// The fitted cost per ray, ms.
    pub fn ms_per_ray(&self) -> f64 {
        self.ms_per_mray * 1e-6
    }

    /// The predicted frame time for `rays` rays, ms; `None` before the first frame.
    pub fn predict_ms(&self, rays: f64) -> Option<f64> {
        self.fitted
            .then_some(self.fixed_ms + self.ms_per_mray * rays * 1e-6)
    }

    /// The robust relative standard deviation of recent residuals (floored at `min_sigma`).
    pub fn sigma(&self) -> f64 {
        let mut r: Vec<f64> = self.residuals.iter().copied().collect();
        let med = median(&mut r);
        let mut dev: Vec<f64> = r.iter().map(|v| (v - med).abs()).collect();
        (1.4826 * median(&mut dev)).max(self.params.min_sigma)
    }

    /// The relative errors (Tp - predicted) / predicted of the last [`ERROR_WINDOW`]
    /// predictions, outliers included: the noise a planned frame time will meet, slow tail
    /// and all. A change of cost does not clear them: the noise is the machine's, not the
    /// line's.
    pub fn recent_errors(&self) -> impl Iterator<Item = f64> + '_ {
        self.errors.iter().copied()
    }

    /// Takes one frame: `rays` traced in `tp_ms` (both already checked finite and positive).
    pub fn observe(&mut self, rays: f64, tp_ms: f64) -> Fit {
        let x = rays * 1e-6;
        let Some(pred) = self.predict_ms(rays).filter(|p| *p > 0.0) else {
            self.add(x, tp_ms);
            return Fit::Accepted;
        };
        let rel = (tp_ms - pred) / pred;
        if self.errors.len() == ERROR_WINDOW {
            self.errors.pop_front();
        }
        self.errors.push_back(rel);
        let sigma = self.sigma().max(self.params.min_sigma_ms / pred);
        if rel.abs() <= self.params.outlier_k * sigma {
            self.pending.clear();
            if rel.abs() <= DRIFT_K * sigma || (rel > 0.0) != self.drift_above {
                self.drift.clear();
            }
            if rel.abs() > DRIFT_K * sigma {
                self.drift_above = rel > 0.0;
                self.drift.push((x, tp_ms));
            }
            if self.drift.len() >= DRIFT_RUN {
                let frames = std::mem::take(&mut self.drift);
                return self.restart_from(frames);
            }
            if self.residuals.len() == RESIDUAL_WINDOW {
                self.residuals.pop_front();
            }
            self.residuals.push_back(rel);
            self.add(x, tp_ms);
            return Fit::Accepted;
        }
        self.drift.clear();
        let same_side = self
            .pending
            .first()
            .is_none_or(|&(px, py)| (py > self.raw_predict(px)) == (rel > 0.0));
        if !same_side {
            self.pending.clear();
        }
        self.pending.push((x, tp_ms));
        if self.pending.len() < self.params.confirm as usize {
            return Fit::Outlier;
        }
        let frames = std::mem::take(&mut self.pending);
        self.restart_from(frames)
    }

    /// Forgets every frame and refits to `frames` (x, y) alone: the cost has changed.
    fn restart_from(&mut self, frames: Vec<(f64, f64)>) -> Fit {
        let (low, high) = frames
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &(x, _)| {
                (lo.min(x), hi.max(x))
            });
        let fixed_before = self.fixed_ms;
        self.refit_from(&frames, 0.0);
        if high < SLOPE_SPAN * low && self.fixed_ms > fixed_before {
            // Frames this close cannot tell a higher fixed cost from a higher cost per ray: a
            // frame of no rays at no time, weighing as much as they do, takes the rise as a
            // cost per ray until frames of other ray counts say otherwise.
            self.refit_from(&frames, frames.len() as f64);
        }
        self.residuals.clear();
        self.pending.clear();
        self.drift.clear();
        Fit::Shifted
    }

    /// Refits from `frames` alone, with `at_origin` frames of no rays at no time before them.
    fn refit_from(&mut self, frames: &[(f64, f64)], at_origin: f64) {
        self.sums = [at_origin, 0.0, 0.0, 0.0, 0.0];
        for &(x, y) in frames {
            self.add(x, y);
        }
    }

    fn raw_predict(&self, x: f64) -> f64 {
        self.fixed_ms + self.ms_per_mray * x
    }

    /// Forgets a little, adds (x, y) and refits.
    fn add(&mut self, x: f64, y: f64) {
        let lambda = self.params.forgetting;
        for s in &mut self.sums {
            *s *= lambda;
        }
        for (s, v) in self.sums.iter_mut().zip([1.0, x, y, x * x, x * y]) {
            *s += v;
        }
        self.refit();
    }

    /// Solves the 2×2 normal equations with the intercept prior; falls back to a line through
    /// the origin and the weighted mean if the fit is not physical (a non-positive slope, or a
    /// fixed cost below 0 or above 90 % of the mean frame time).
    fn refit(&mut self) {
        let [w, sx, sy, sxx, sxy] = self.sums;
        let mu = self.params.prior_weight;
        let det = (w + mu) * sxx - sx * sx;
        let (mut a, mut b) = if det > 1e-12 * (w + mu) * sxx.max(1e-300) {
            (
                (sy * sxx - sx * sxy) / det,
                ((w + mu) * sxy - sx * sy) / det,
            )
        } else {
            (0.0, 0.0)
        };
        let mean_y = if w > 0.0 { sy / w } else { 0.0 };
        if !(a >= 0.0 && a <= 0.9 * mean_y && b > 0.0 && b.is_finite()) {
            a = 0.0;
            b = if sx > 0.0 { sy / sx } else { 0.0 };
        }
        self.fixed_ms = a;
        self.ms_per_mray = b;
        self.fitted = b > 0.0;
    }
}

/// The median of `v` (sorted in place); 0 when empty.
fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_line_from_varied_frames() {
        let mut m = CostModel::new(CostParams::default());
        for i in 0..60 {
            let rays = 20e6 + 5e6 * f64::from(i % 7);
            m.observe(rays, 2.0 + 0.5e-6 * rays);
        }
        assert!((m.fixed_ms() - 2.0).abs() < 0.2, "fixed {}", m.fixed_ms());
        assert!((m.ms_per_ray() / 0.5e-6 - 1.0).abs() < 0.02);
    }

    #[test]
    fn a_single_spike_is_not_fitted_but_a_lasting_change_is() {
        let mut m = CostModel::new(CostParams::default());
        for _ in 0..20 {
            assert_eq!(m.observe(30e6, 16.0), Fit::Accepted);
        }
        let before = m.predict_ms(30e6).unwrap();
        assert_eq!(m.observe(30e6, 160.0), Fit::Outlier);
        assert_eq!(m.observe(30e6, 16.1), Fit::Accepted);
        assert!((m.predict_ms(30e6).unwrap() - before).abs() < 0.1);
        assert_eq!(m.observe(30e6, 32.0), Fit::Outlier);
        assert_eq!(m.observe(30e6, 32.0), Fit::Shifted);
        assert!((m.predict_ms(30e6).unwrap() - 32.0).abs() < 1.0);
    }

    /// Two slow frames of a noisy machine (`bench --band refresh` with the temporal mode on
    /// the 2-core VM: 15.7 ms at 380 k rays, then 19.4 ms at 277 k, after frames of about
    /// 6.5 ms + 16 ms per million rays) confirm a change, but a line through them puts
    /// 14 ms in the fixed cost, under which no quality fits a one-refresh band. Their rays are
    /// too close to split the cost, so the restart takes the rise as a cost per ray.
    #[test]
    fn two_slow_frames_close_in_rays_do_not_raise_the_fixed_cost() {
        let mut m = CostModel::new(CostParams::default());
        for i in 0..40 {
            let rays = 330e3 + 2e3 * f64::from(i % 30);
            let wobble = 1.0 + 0.02 * f64::from(i % 3) - 0.02;
            m.observe(rays, (6.5 + 16e-6 * rays) * wobble);
        }
        let fixed_before = m.fixed_ms();
        assert_eq!(m.observe(379_640.0, 15.745), Fit::Outlier);
        assert_eq!(m.observe(277_519.0, 19.437), Fit::Shifted);
        assert!(m.fixed_ms() <= fixed_before, "fixed {}", m.fixed_ms());
        // Both frames are explained on the whole, and a tenth of the rays is predicted to
        // take a tenth of the time, not the 14 ms of the line through them.
        let predicted = m.predict_ms(379_640.0).unwrap() + m.predict_ms(277_519.0).unwrap();
        assert!(
            (predicted / (15.745 + 19.437) - 1.0).abs() < 0.1,
            "{predicted}"
        );
        assert!(
            m.predict_ms(30e3).unwrap() < 3.0,
            "{:?}",
            m.predict_ms(30e3)
        );
        // Frames whose rays differ by SLOPE_SPAN or more refit the whole line as before.
        let mut wide = CostModel::new(CostParams::default());
        for i in 0..40 {
            let rays = 330e3 + 2e3 * f64::from(i % 30);
            wide.observe(rays, 6.5 + 16e-6 * rays);
        }
        wide.observe(400e3, 30.0);
        assert_eq!(wide.observe(100e3, 20.0), Fit::Shifted);
        assert!(wide.fixed_ms() > 10.0, "fixed {}", wide.fixed_ms());
    }

    #[test]
    fn a_steady_drift_restarts_the_fit_instead_of_bending_it() {
        let mut m = CostModel::new(CostParams::default());
        for i in 0..20 {
            let rays = 30e6 + 2e6 * f64::from(i % 5);
            m.observe(rays, 0.3 + 0.5e-6 * rays);
        }
        // The cost per ray grows 3 % a frame while a controller cuts the rays 2 % a frame:
        // no frame is an outlier, and a line through them all would put the growth in the
        // fixed cost.
        let (mut ms_per_ray, mut rays) = (0.5e-6, 34e6);
        let mut shifted = false;
        for _ in 0..30 {
            ms_per_ray *= 1.03;
            rays *= 0.98;
            shifted |= m.observe(rays, 0.3 + ms_per_ray * rays) == Fit::Shifted;
        }
        assert!(shifted);
        // Without the restarts: fixed 11.2 ms, and a cut to half the rays predicted at 16.1
        // ms for a true 11.6 (so the cut went twice as deep as it had to).
        assert!(m.fixed_ms() < 5.0, "fixed {}", m.fixed_ms());
        for r in [rays, 0.5 * rays] {
            let truth = 0.3 + ms_per_ray * r;
            let predicted = m.predict_ms(r).unwrap();
            assert!(
                (predicted / truth - 1.0).abs() < 0.15,
                "{r}: {predicted} vs {truth}"
            );
        }
    }

    #[test]
    fn constant_rays_give_a_proportional_model() {
        let mut m = CostModel::new(CostParams::default());
        for _ in 0..10 {
            m.observe(10e6, 10.0);
        }
        assert!((m.predict_ms(10e6).unwrap() - 10.0).abs() < 1e-9);
        assert!(m.predict_ms(20e6).unwrap() > 19.0);
    }
}
