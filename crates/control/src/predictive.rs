//! `predictive`: predicts the next frame's time for candidate qualities and picks the best
//! one that fits.
//!
//! Each frame:
//! 1. The [`CostModel`] (Tp ≈ fixed_ms + ms_per_ray · rays, fitted online, robust to
//!    spikes) takes the frame. A frame it sets aside as an outlier changes nothing: a
//!    one-frame hitch costs no quality; a second outlier on the same side confirms a real
//!    change of cost and the model refits at once.
//! 2. The [`RayModel`] of the frame gives the rays any candidate quality would trace. The
//!    load's trend (the camera moves smoothly) is extrapolated one frame ahead: an
//!    exponential average of the frame-to-frame growth of the load, weight `trend`, each
//!    growth clamped to ±10 %.
//! 3. Deadband: if the current quality's predicted time lies inside the inner band
//!    [Tmin + `deadband`·w, Tmax − `deadband`·w] (w = Tmax − Tmin), nothing changes. This is
//!    what keeps it still in steady state: the prediction uses the measured rays, which
//!    carry no timer noise. With noisy frame times the inner band narrows (keeping at least
//!    ±12 % of the band around the target) so that two robust deviations of the noise still stay inside the band.
//! 4. Otherwise it takes the highest quality whose predicted time is at most the target
//!    Tmin + `target`·w, raising at most `max_raise` times the current rays per change
//!    (cuts are not limited). Quality order (`order`, default `depth,scale,spp`): R first,
//!    while at least `min_reach` of the eye rays reach the deeper level; then the scale
//!    (continuous); then S (continuous); then any remaining R. Cuts go in reverse. Continuous
//!    knobs let it land on the target instead of oscillating across the band.

use crate::controller::{Controller, Setup, parse_option, within};
use crate::cost_model::{CostModel, CostParams, Fit};
use crate::error::ConfigError;
use crate::quality::{Knob, KnobOrder, Quality};
use crate::ray_model::{DEFAULT_DECAY, RayModel};
use crate::report::{FrameReport, ReportError};

/// The largest frame-to-frame load growth the trend extrapolates (±10 %).
const MAX_GROWTH: f64 = 1.1;
/// Noise deviations a frame predicted inside the inner band may deviate and stay in the band.
pub const NOISE_MARGIN: f64 = 2.0;
/// The inner band never narrows to less than this fraction of the band on either side of
/// the target.
pub const MIN_INNER: f64 = 0.12;
/// Continuous knobs are found to this relative precision.
const SEARCH_STEPS: u32 = 40;

/// Parameters of [`Predictive`], with their option names and defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct PredictiveParams {
    /// `order`: knobs in raising order; cut in reverse. Default `depth,scale,spp`.
    pub order: KnobOrder,
    /// `target`: the time a change aims for, as a fraction of the band. Default 0.5.
    pub target: f64,
    /// `deadband`: the inner band's margin, as a fraction of the band. Default 0.2
    /// (inner band [16, 19] ms in [15, 20]).
    pub deadband: f64,
    /// `min_reach`: R is raised first only while this fraction of eye rays reaches the
    /// deeper level. Default 0.02.
    pub min_reach: f64,
    /// `max_raise`: the largest factor on predicted rays per raise. Default 2.
    pub max_raise: f64,
    /// `trend`: weight of the newest growth in the load trend, 0 to disable. Default 0.5.
    pub trend: f64,
    /// The cost model's parameters (options `forgetting`, `outlier_k`, `confirm`).
    pub cost: CostParams,
}

impl Default for PredictiveParams {
    fn default() -> Self {
        Self {
            order: KnobOrder::default(),
            target: 0.5,
            deadband: 0.2,
            min_reach: 0.02,
            max_raise: 2.0,
            trend: 0.5,
            cost: CostParams::default(),
        }
    }
}

const PREDICTIVE_KEYS: &str = "order, target, deadband, min_reach, max_raise, trend, \
                               forgetting, outlier_k, confirm";

impl PredictiveParams {
    /// Sets one option by name (used by [`crate::from_name`]).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        match key {
            "order" => self.order = parse_option(key, value, |_| Ok(()))?,
            "target" => self.target = parse_option(key, value, within(0.0, 1.0))?,
            "deadband" => self.deadband = parse_option(key, value, within(0.0, 0.5))?,
            "min_reach" => self.min_reach = parse_option(key, value, within(0.0, 1.0))?,
            "max_raise" => self.max_raise = parse_option(key, value, within(1.01, 1e6))?,
            "trend" => self.trend = parse_option(key, value, within(0.0, 1.0))?,
            "forgetting" => self.cost.forgetting = parse_option(key, value, within(0.01, 1.0))?,
            "outlier_k" => self.cost.outlier_k = parse_option(key, value, within(1.0, 1e6))?,
            "confirm" => self.cost.confirm = parse_option(key, value, within(1, 100))?,
            _ => {
                return Err(ConfigError::UnknownOption {
                    controller: "predictive",
                    key: key.to_string(),
                    expected: PREDICTIVE_KEYS,
                });
            }
        }
        Ok(())
    }

    /// Checks that the target lies inside the inner band.
    fn validate(&self) -> Result<(), ConfigError> {
        if !(self.target >= self.deadband && self.target <= 1.0 - self.deadband) {
            return Err(ConfigError::BadOption {
                key: "target".into(),
                value: self.target.to_string(),
                why: format!(
                    "must lie inside the inner band [{}, {}] set by deadband",
                    self.deadband,
                    1.0 - self.deadband
                ),
            });
        }
        Ok(())
    }
}

/// The predictive controller (see the module documentation).
#[derive(Clone, Debug)]
pub struct Predictive {
    setup: Setup,
    params: PredictiveParams,
    quality: Quality,
    cost: CostModel,
    load: Option<RayModel>,
    /// Exponential average of ln(load growth per frame).
    trend: f64,
}

impl Predictive {
    /// A predictive controller; errors on a bad setup or a target outside the inner band.
    pub fn new(setup: Setup, params: PredictiveParams) -> Result<Self, ConfigError> {
        setup.validate()?;
        params.validate()?;
        Ok(Self {
            quality: setup.start,
            cost: CostModel::new(params.cost.clone()),
            setup,
            params,
            load: None,
            trend: 0.0,
        })
    }

    /// The parameters in use.
    pub fn params(&self) -> &PredictiveParams {
        &self.params
    }

    /// The fitted cost model.
    pub fn cost_model(&self) -> &CostModel {
        &self.cost
    }

    /// The predicted time of the next frame at quality `q`, ms (`None` before any frame).
    pub fn predict_ms(&self, q: &Quality) -> Option<f64> {
        let load = self.load.as_ref()?;
        self.cost.predict_ms(load.rays(q) * self.trend.exp())
    }

    /// Updates the load and its trend from an accepted frame.
    fn update_load(&mut self, report: &FrameReport) {
        let last_decay = self.load.as_ref().map_or(DEFAULT_DECAY, RayModel::decay);
        let load = RayModel::from_report(report, last_decay);
        if let Some(old) = &self.load {
            // Growth over the levels both frames measured, at the frame's own quality.
            let mut q = report.quality;
            q.depth = q.depth.min(old.measured_depth()).min(load.measured_depth());
            let (before, now) = (old.rays(&q), load.rays(&q));
            if before > 0.0 && now > 0.0 {
                let growth = (now / before).clamp(1.0 / MAX_GROWTH, MAX_GROWTH).ln();
                let w = self.params.trend;
                self.trend = (1.0 - w) * self.trend + w * growth;
            }
        }
        self.load = Some(load);
    }

    /// The inner band: `deadband` in from each side, narrowed (to no less than [`MIN_INNER`] of the band around the target) so that
    /// a frame predicted inside it stays in the band within [`NOISE_MARGIN`] times the
    /// measured relative noise.
    pub fn inner_band(&self) -> (f64, f64) {
        let band = self.setup.band;
        let p = &self.params;
        let target = band.at(p.target);
        let spread = NOISE_MARGIN * self.cost.sigma();
        let low = band
            .at(p.deadband)
            .max(band.tmin_ms() / (1.0 - spread).max(0.1));
        let high = band
            .at(1.0 - p.deadband)
            .min(band.tmax_ms() / (1.0 + spread));
        let half = MIN_INNER * band.width_ms();
        (low.min(target - half), high.max(target + half))
    }

    /// The next quality: unchanged inside the inner band, else the best that fits the target.
    fn decide(&self) -> Quality {
        let band = self.setup.band;
        let p = &self.params;
        let (Some(now), Some(load)) = (self.predict_ms(&self.quality), &self.load) else {
            return self.quality;
        };
        let (low, high) = self.inner_band();
        let raising = now < low;
        if !raising && now <= high {
            return self.quality;
        }
        let target = band.at(p.target);
        let ray_cap = if raising {
            p.max_raise * load.rays(&self.quality)
        } else {
            f64::INFINITY
        };
        let fits = |q: &Quality| {
            load.rays(q) <= ray_cap && self.predict_ms(q).is_some_and(|t| t <= target)
        };
        self.best_fitting(load, fits, raising)
    }

    /// The highest quality along the knob order for which `fits` holds. A raise starts from
    /// the current quality and only raises knobs: R up to the useful depth, then the others
    /// in order, then the rest of R. A cut only lowers knobs: the highest quality below the
    /// current one in the order, so the last knob in the order goes first (the lowest quality
    /// if nothing fits). Moves are never trades (one knob up, another down).
    fn best_fitting(
        &self,
        load: &RayModel,
        fits: impl Fn(&Quality) -> bool,
        raising: bool,
    ) -> Quality {
        let b = &self.setup.bounds;
        let order = self.params.order.knobs();
        let current = self.quality;
        let mut q = current;
        let stages: Vec<(Knob, f64)> = if raising {
            let useful = load.useful_depth(self.params.min_reach, b.depth_min, b.depth_max);
            let mut stages: Vec<(Knob, f64)> = order
                .iter()
                .map(|&k| {
                    (
                        k,
                        if k == Knob::Depth {
                            f64::from(useful)
                        } else {
                            b.range(k).1
                        },
                    )
                })
                .collect();
            if order.contains(&Knob::Depth) {
                stages.push((Knob::Depth, f64::from(b.depth_max)));
            }
            stages
        } else {
            for &knob in order {
                q = q.with(knob, b.range(knob).0);
            }
            order.iter().map(|&k| (k, current.get(k))).collect()
        };
        for (knob, top) in stages {
            let from = q.get(knob);
            if top <= from {
                continue;
            }
            if fits(&q.with(knob, top)) {
                q = q.with(knob, top);
                continue;
            }
            q = match knob {
                Knob::Depth => {
                    let mut d = q;
                    while f64::from(d.depth) < top && fits(&d.with(knob, f64::from(d.depth + 1))) {
                        d.depth += 1;
                    }
                    d
                }
                Knob::Spp | Knob::Scale => {
                    let (mut lo, mut hi) = (from, top);
                    for _ in 0..SEARCH_STEPS {
                        let mid = 0.5 * (lo + hi);
                        if fits(&q.with(knob, mid)) {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    q.with(knob, lo)
                }
            };
            break;
        }
        b.clamp(q)
    }
}

impl Controller for Predictive {
    fn name(&self) -> &'static str {
        "predictive"
    }

    fn quality(&self) -> Quality {
        self.quality
    }

    fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError> {
        report.check_rays()?;
        if self.cost.observe(report.total_rays() as f64, report.tp_ms) == Fit::Outlier {
            return Ok(self.quality);
        }
        self.update_load(report);
        self.quality = self.decide();
        Ok(self.quality)
    }

    fn reset(&mut self) {
        self.quality = self.setup.start;
        self.cost = CostModel::new(self.params.cost.clone());
        self.load = None;
        self.trend = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::band::Band;
    use crate::quality::Bounds;

    /// A frame of a simple scene: half the rays go one level deeper; 1 ms + 1 ns per ray.
    fn frame(q: Quality, full_pixels: f64) -> FrameReport {
        let pixels = (full_pixels * f64::from(q.scale * q.scale)).round() as u64;
        let eye = pixels as f64 * f64::from(q.spp);
        let rays: Vec<u64> = (0..=q.depth)
            .map(|k| (eye * 0.5f64.powi(k as i32)) as u64)
            .collect();
        let total: u64 = rays.iter().sum();
        FrameReport {
            tp_ms: 1.0 + total as f64 * 1e-6,
            rays_per_depth: rays,
            shadow_rays: 0,
            pixels,
            quality: q,
        }
    }

    #[test]
    fn lands_in_the_inner_band_and_stays() {
        let setup = Setup::new(
            Band::PAPER,
            Bounds::default(),
            Bounds::default().max_quality(),
        )
        .unwrap();
        let mut c = Predictive::new(setup, PredictiveParams::default()).unwrap();
        let mut tp = Vec::new();
        for _ in 0..20 {
            let r = frame(c.quality(), 1e6);
            tp.push(r.tp_ms);
            c.observe(&r).unwrap();
        }
        assert!(tp[0] > 100.0);
        assert!(tp[2..].iter().all(|t| (16.0..=19.0).contains(t)), "{tp:?}");
        let q = c.quality();
        assert_eq!(c.observe(&frame(q, 1e6)).unwrap(), q);
    }

    #[test]
    fn raises_depth_only_while_rays_reach_it() {
        let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 2, 1.0)).unwrap();
        let mut c = Predictive::new(setup, PredictiveParams::default()).unwrap();
        for _ in 0..10 {
            let r = frame(c.quality(), 2e6);
            c.observe(&r).unwrap();
        }
        // Reach 0.5^k >= 0.02 up to k = 5: depth 5 first, then S (then more depth, cheap).
        let q = c.quality();
        assert!(q.depth >= 5 && q.spp > 1.0, "{q}");
    }
}
