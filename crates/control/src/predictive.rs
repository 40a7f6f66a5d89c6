//! `predictive`: predicts the next frame's time for candidate qualities and picks the best
//! one that fits.
//!
//! Each frame:
//! 1. The [`CostModel`] (Tp ≈ fixed_ms + ms_per_ray · rays, fitted online, robust to
//!    spikes) takes the frame. A frame it sets aside as an outlier changes nothing,
//!    over Tmax or not: on a real machine one slow frame is far more often a spike than a
//!    change of cost (the 2-core VM, idle: about one frame in twenty runs 1.1 to 1.4 times
//!    its neighbours' time, alone), and a cut on its word landed the next frames under the
//!    band and made a reversal with the raise after it. `confirm` outliers in a row on one
//!    side (default 2) confirm a real change of cost and the model refits at once, as do
//!    three fitted frames in a row well off their prediction on one side (a cost drifting a
//!    little each frame).
//! 2. The [`RayModel`] of the frame gives the rays any candidate quality would trace. The
//!    load's trend (the camera moves smoothly) is extrapolated one frame ahead: an
//!    exponential average of the frame-to-frame growth of the load, weight `trend`, each
//!    growth clamped to ±10 %.
//! 3. Deadband: if the current quality's predicted time lies inside the inner band, nothing
//!    changes, except a trade (`trades`, default on): when the knob order's own plan for the
//!    target, raised from the lowest quality, has an earlier knob higher and a later one
//!    lower than the current quality, it moves there (R cut on a shallow view comes back on
//!    a deep one; raises and cuts never trade). This is what keeps it still in steady state:
//!    the prediction uses the measured rays, which carry no timer noise. The inner band starts as
//!    [Tmin + `deadband`·w, Tmax − `deadband`·w] (w = Tmax − Tmin) around the target
//!    Tmin + `target`·w; once the recent prediction errors are known, the target follows
//!    them and the inner band narrows to what their scatter allows, [`INNER_HALF`] of the
//!    band on each side of the target on a quiet machine ([`Predictive::aim`]): on a
//!    machine whose noise only ever slows frames down it aims below the centre, as far as
//!    that noise asks and no further, and holds the planned time close to that aim.
//!    While the view's cost keeps moving the way the last change went (a cut, then more
//!    load), the side it moves towards is as narrow as on a quiet machine: the quality
//!    follows the view close to the target, each move the same way as the last, which is
//!    no reversal; turning back still needs the prediction past the noise-wide inner band.
//! 4. Otherwise it takes the highest quality whose predicted time is at most the target,
//!    raising at most `max_raise` times the current rays per change
//!    (cuts are not limited). Quality order (`order`, default `depth,scale,spp`): R first,
//!    while at least `min_reach` of the eye rays reach the deeper level (all of R at once
//!    when the deeper levels together carry no more than that: nearly free); then the scale
//!    (continuous); then S (continuous); then any remaining R. Cuts go in reverse. Continuous
//!    knobs let it land on the target instead of oscillating across the band.
//!
//! With a calibrated [`Ladder`] (option `ladder=PATH`, see [`crate::ladder`]) step 4 moves
//! along the ladder's Pareto front instead of the knob order: a raise takes the best point
//! above the current one (lowest calibrated FLIP) predicted to fit the target, a cut the best
//! point below it that fits. Below the cheapest point the ladder goes on at lower resolution
//! ([`LADDER_FLOOR`]): its cheapest point with the scale falling to the bounds' lowest, so
//! a view dearer than the calibration's still gets a frame in the band (a ladder calibrated
//! on another scene or machine often starts too high; a cut then stayed at its cheapest point
//! over the band). Each point's time is still predicted from the measured rays of the current
//! view, so S, R and scale are chosen together by what looks best for the time the frame may
//! take.

use crate::band::{Band, Position};
use crate::budget::{self, BASE_SHARE, FrameBudget};
use crate::controller::{Controller, Setup, parse_option, within};
use crate::cost_model::{CostModel, CostParams, Fit};
use crate::decision::{Action, Decision, Reason};
use crate::error::ConfigError;
use crate::ladder::{LADDER_FLOOR, Ladder};
use crate::quality::{Knob, KnobOrder, Quality};
use crate::ray_model::{DEFAULT_DECAY, RayModel};
use crate::report::{FrameReport, ReportError};

/// The largest frame-to-frame load growth the trend extrapolates (±10 %).
const MAX_GROWTH: f64 = 1.1;
/// The load's trend (ln of its growth per frame, ±0.05 %) past which a held quality
/// follows the view's cost the way it last moved (see `Predictive::holding_range`).
pub const FOLLOW_TREND: f64 = 5e-4;
/// Frames in a row measured above the inner band that `measured_cut` takes for a drift
/// (fewer are too often noise, or a coarse timer's rounding).
pub const DRIFT_FRAMES: u32 = 3;
/// The most frames in a row above the inner band a drift may need on a noisy machine.
pub const MAX_DRIFT_FRAMES: u32 = 8;
/// A drift needs so many frames above the inner band that the measured noise alone puts a
/// frame planned at the target above it that many times in a row with at most this chance.
pub const DRIFT_CHANCE: f64 = 1e-3;
/// Fitted frames needed before the aim follows the measured noise.
pub const MIN_NOISE_FRAMES: usize = 8;
/// Planned times scored across the band by [`Predictive::aim`].
const AIM_GRID: u32 = 50;
/// Once the noise is measured, the inner band spans at least this fraction of the band on
/// either side of the target (this much on a quiet machine, more on a noisy one:
/// [`NOISE_HALF`]). Frames planned anywhere in a wider inner band met the noise far from the
/// aim: on the 2-core VM the old inner band (the times scoring within 5 % of the best,
/// 16 to 19 ms in [15, 20]) let a tenth of the frames be planned above 18.2 ms, where a
/// spike of 1.1 already ends over the band. Narrower, the quality moves more often with the
/// view, and reversals grow.
pub const INNER_HALF: f64 = 0.12;
/// On a noisy machine the inner band is at least this many robust standard deviations of
/// the prediction errors on either side of the target ([`Predictive::aim`]).
pub const NOISE_HALF: f64 = 2.0;
/// With a frame budget, a raise leaves the first sample of every pixel this share of
/// [`BASE_SHARE`]'s limit, which a held quality may fill: a quality raised to the limit
/// itself was cut again on the next frame whose prediction came out a little higher.
pub const BASE_RAISE: f64 = 0.9;
/// Continuous knobs are found to this relative precision.
const SEARCH_STEPS: u32 = 40;
/// A trade ([`PredictiveParams::trades`]) counts S and scale as unchanged within this fraction.
pub const TRADE_MARGIN: f64 = 0.02;

/// Parameters of [`Predictive`], with their option names and defaults.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
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
    /// `measured_cut`: [`DRIFT_FRAMES`] frames in a row (more on a noisy machine, see
    /// `Predictive::drift_frames`) measured above the inner band trigger
    /// a cut even when the model still predicts the quality fits (the model lags a cost that
    /// drifts with the view). Without it only frames over Tmax do. Default true.
    pub measured_cut: bool,
    /// `trades`: inside the inner band, move to where the knob order would settle for the
    /// target from the lowest quality when that is a trade with the current quality (an
    /// earlier knob higher, a later one lower), so the quality held follows the view and not
    /// the way the run came there: raises and cuts never trade, so without it an R cut on
    /// a view that needed little stays cut on views that need more. Default true.
    pub trades: bool,
    /// The cost model's parameters (options `forgetting`, `outlier_k`, `confirm`).
    pub cost: CostParams,
    /// `ladder`: a calibrated ladder file (`ladder.json`) to move along instead of `order`.
    /// Default none.
    pub ladder: Option<Ladder>,
    /// `budget`: hand each frame a [`FrameBudget`] for the band
    /// ([`budget::for_band`], filled up to the aim's target), so that a renderer
    /// that takes its samples a unit at a time ends the frame in the band against its own
    /// clock ([`crate::budget`]). Default false: the paper's per-frame control alone.
    pub budget: bool,
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
            measured_cut: true,
            trades: true,
            cost: CostParams::default(),
            ladder: None,
            budget: false,
        }
    }
}

impl PredictiveParams {
    /// Sets one option by name (used by [`crate::from_name`]); `ladder`, which names a file,
    /// is [`crate::from_name_with`]'s.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        match key {
            "order" => self.order = parse_option(key, value, |_| Ok(()))?,
            "target" => self.target = parse_option(key, value, within(0.0, 1.0))?,
            "deadband" => self.deadband = parse_option(key, value, within(0.0, 0.5))?,
            "min_reach" => self.min_reach = parse_option(key, value, within(0.0, 1.0))?,
            "max_raise" => self.max_raise = parse_option(key, value, within(1.01, 1e6))?,
            "trend" => self.trend = parse_option(key, value, within(0.0, 1.0))?,
            "measured_cut" => self.measured_cut = parse_option(key, value, |_| Ok(()))?,
            "trades" => self.trades = parse_option(key, value, |_| Ok(()))?,
            "budget" => self.budget = parse_option(key, value, |_| Ok(()))?,
            "forgetting" => self.cost.forgetting = parse_option(key, value, within(0.01, 1.0))?,
            "outlier_k" => self.cost.outlier_k = parse_option(key, value, within(1.0, 1e6))?,
            "confirm" => self.cost.confirm = parse_option(key, value, within(1, 100))?,
            "ladder" => {
                return Err(ConfigError::BadOption {
                    key: key.to_string(),
                    value: value.to_string(),
                    why: "names a file: set `ladder` to a parsed Ladder, or build the \
                          controller with from_name_with"
                        .into(),
                });
            }
            _ => {
                return Err(ConfigError::UnknownOption {
                    controller: "predictive",
                    key: key.to_string(),
                    expected: crate::options::expected_keys("predictive"),
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

/// Where the predictive controller aims: a target time and the inner band around it, ms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aim {
    /// The Tp, ms, a new quality's predicted time is aimed at.
    pub target_ms: f64,
    /// The quality is kept while its predicted time lies in [low_ms, high_ms].
    pub low_ms: f64,
    /// Top of the inner band, ms (`low_ms` is its bottom).
    pub high_ms: f64,
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
    /// How much slower than predicted the last frame ran, when it completed a drift (1
    /// otherwise): scales the predictions of the decision it triggers.
    surprise: f64,
    /// Frames in a row measured above the inner band at the current quality.
    above_run: u32,
    /// The way the quality last moved ([`Action::Raise`] or [`Action::Cut`]), if it has.
    last_move: Option<Action>,
    /// Where on the ladder the current quality lies (see [`Predictive::ladder_quality`]);
    /// `None` off the ladder (the starting quality) or without one.
    ladder_pos: Option<f64>,
    /// The last decision, for [`Controller::decision`].
    decision: Option<Decision>,
}

/// What [`Predictive::decide`] chose: the next quality, its ladder position when it moved
/// along a ladder, and why.
struct Choice {
    quality: Quality,
    ladder_pos: Option<f64>,
    reason: Reason,
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
            surprise: 1.0,
            above_run: 0,
            last_move: None,
            ladder_pos: None,
            decision: None,
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
        self.cost
            .predict_ms(load.rays(q) * self.trend.exp())
            .map(|t| t * self.surprise)
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

    /// Where to aim under the measured noise: the target time and the inner band.
    ///
    /// Until [`MIN_NOISE_FRAMES`] frames have measured the noise, the target is `target`
    /// and the inner band `deadband` in from each side of the band. Then each planned time
    /// t on a grid over the band is scored by how many recent relative prediction errors r
    /// keep t·(1 + r) inside the band, averaged over the times within the inner band's
    /// half-width of t ([`NOISE_HALF`] robust deviations of the errors, at least
    /// [`INNER_HALF`] of the band, at most the nominal inner band's half: a quality is held
    /// while its prediction wanders that far from where it was planned, so a time next to a
    /// cliff of the count, where the errors that make frames fast drop them under Tmin, is
    /// not as good as it looks alone). The target is the middle of the best-scoring times,
    /// and the inner band that half-width on each side of it. Real frame-time noise is
    /// one-sided (other work only makes frames slower), so this aims below the centre
    /// exactly as far as the noise asks.
    pub fn aim(&self) -> Aim {
        self.aim_in(self.setup.band)
    }

    /// Where [`Predictive::aim`] would aim in `band` under the same measured noise.
    pub fn aim_in(&self, band: Band) -> Aim {
        let p = &self.params;
        let nominal = Aim {
            target_ms: band.at(p.target),
            low_ms: band.at(p.deadband),
            high_ms: band.at(1.0 - p.deadband),
        };
        let mut errors: Vec<f64> = self.cost.recent_errors().collect();
        if errors.len() < MIN_NOISE_FRAMES {
            return nominal;
        }
        // Sorted, the errors that keep t·(1 + r) in the band are one run of them, found by
        // two binary searches per planned time (t·(1 + r) grows with r).
        errors.sort_by(f64::total_cmp);
        let step = |i: i32| band.at(f64::from(i) / f64::from(AIM_GRID));
        let count_at = |i: i32| {
            let t = step(i);
            let under =
                errors.partition_point(|&r| band.position(t * (1.0 + r)) == Position::Under);
            let in_or_under =
                errors.partition_point(|&r| band.position(t * (1.0 + r)) != Position::Over);
            (in_or_under - under) as f64
        };
        let half = self.inner_half_ms(band, &errors);
        let reach = (half / band.width_ms() * f64::from(AIM_GRID)).round() as i32;
        let grid = AIM_GRID as i32;
        let counts: Vec<f64> = (-reach..=grid + reach).map(count_at).collect();
        let window = counts.len() - grid as usize;
        let scores: Vec<f64> = counts
            .windows(window)
            .map(|w| w.iter().sum::<f64>() / window as f64)
            .collect();
        let best = scores.iter().copied().fold(0.0, f64::max);
        let first = scores.iter().position(|&s| s >= best).unwrap_or(0);
        let last = scores.iter().rposition(|&s| s >= best).unwrap_or(0);
        let target_ms = 0.5 * (step(first as i32) + step(last as i32));
        Aim {
            target_ms,
            low_ms: target_ms - half,
            high_ms: target_ms + half,
        }
    }

    /// Half the inner band's width once the noise is measured, ms: [`NOISE_HALF`] robust
    /// standard deviations of the prediction errors (spikes aside) at the band's centre,
    /// at least [`INNER_HALF`] of the band and at most the nominal inner band's half. On a
    /// quiet machine the quality is held close to its aim; on a noisy one a band that
    /// narrow moved the quality on the noise (the shared 2-core VM's recording: 9.6
    /// reversals per 100 frames on a steady view). `sorted`: the errors, in order.
    fn inner_half_ms(&self, band: Band, sorted: &[f64]) -> f64 {
        let median = sorted[sorted.len() / 2];
        let mut deviations: Vec<f64> = sorted.iter().map(|r| (r - median).abs()).collect();
        let middle = deviations.len() / 2;
        let sigma = 1.4826 * *deviations.select_nth_unstable_by(middle, f64::total_cmp).1;
        let nominal = (0.5 - self.params.deadband) * band.width_ms();
        (NOISE_HALF * sigma * band.centre_ms())
            .min(nominal)
            .max(INNER_HALF * band.width_ms())
    }

    /// The next quality (and its ladder position when it moved along a ladder): unchanged
    /// inside `aim`'s inner band, else the best that fits its target; with the reason.
    fn decide(&self, aim: &Aim) -> Choice {
        let p = &self.params;
        let keep = |reason| Choice {
            quality: self.quality,
            ladder_pos: None,
            reason,
        };
        let (Some(now), Some(load)) = (self.predict_ms(&self.quality), &self.load) else {
            return keep(Reason::Learning);
        };
        let (low_ms, high_ms) = self.holding_range(aim);
        let raising = now < low_ms;
        if !raising && now <= high_ms && self.base_fits(&self.quality, 1.0) {
            let trade = (p.trades && p.ladder.is_none())
                .then(|| self.order_trade(load, aim.target_ms))
                .flatten();
            return Choice {
                quality: trade.unwrap_or(self.quality),
                ladder_pos: None,
                reason: Reason::InInnerBand,
            };
        }
        let reason = if (aim.low_ms..=aim.high_ms).contains(&now) {
            Reason::Follow
        } else if raising {
            Reason::UnderInnerBand
        } else if self.surprise > 1.0 {
            Reason::Drift
        } else {
            Reason::OverInnerBand
        };
        let target = aim.target_ms;
        let ray_cap = if raising {
            p.max_raise * load.rays(&self.quality)
        } else {
            f64::INFINITY
        };
        let fits = |q: &Quality| {
            load.rays(q) <= ray_cap
                && self.predict_ms(q).is_some_and(|t| t <= target)
                && self.base_fits(q, if raising { BASE_RAISE } else { 1.0 })
        };
        let (quality, ladder_pos) = match &self.params.ladder {
            Some(ladder) => {
                let u = self.best_on_ladder(ladder, fits, raising);
                (self.ladder_quality(ladder, u), Some(u))
            }
            None => (self.best_fitting(load, fits, raising), None),
        };
        Choice {
            quality,
            ladder_pos,
            reason,
        }
    }

    /// Whether `q` leaves its frame's budget room to work in: without a budget always;
    /// with one, when the first sample of every pixel at `q`'s depth and scale is predicted
    /// to take at most `share` × [`BASE_SHARE`] of the time the frame must stop by (the
    /// rest of `q`'s S is what the budget cuts or fills).
    fn base_fits(&self, q: &Quality, share: f64) -> bool {
        if !self.params.budget {
            return true;
        }
        let stop_by = budget::stop_by_ms(self.setup.band);
        let base = Quality { spp: 1.0, ..*q };
        self.predict_ms(&base)
            .is_some_and(|t| t <= share * BASE_SHARE * stop_by)
    }

    /// The predicted times the current quality is held for: `aim`'s inner band, but only
    /// [`INNER_HALF`] of the band past the target (as on a quiet machine) on the side the
    /// quality last moved towards while the view's load keeps going the way that moved it
    /// (growing after a cut, shrinking after a raise, by [`FOLLOW_TREND`] a frame or more).
    /// Such a view is followed closely, each move the same way as the last, which is no
    /// reversal; turning back still needs the prediction past the inner band, as far as
    /// the noise asks. On a steady view the inner band stays whole: there the prediction
    /// moves only with the cost model's noise, and following it one way only held the
    /// quality off-centre.
    fn holding_range(&self, aim: &Aim) -> (f64, f64) {
        let follow = INNER_HALF * self.setup.band.width_ms();
        match self.last_move {
            Some(Action::Cut) if self.trend > FOLLOW_TREND => {
                (aim.low_ms, aim.high_ms.min(aim.target_ms + follow))
            }
            Some(Action::Raise) if self.trend < -FOLLOW_TREND => {
                (aim.low_ms.max(aim.target_ms - follow), aim.high_ms)
            }
            _ => (aim.low_ms, aim.high_ms),
        }
    }

    /// Takes `choice` as the next quality and records the decision made under `aim`
    /// (`measured_ms`: the frame that prompted it, if one did).
    fn apply(&mut self, choice: Choice, measured_ms: Option<f64>, aim: &Aim) -> Quality {
        let from = self.quality;
        if choice.quality != from {
            self.above_run = 0;
        }
        self.quality = choice.quality;
        if choice.ladder_pos.is_some() {
            self.ladder_pos = choice.ladder_pos;
        }
        self.record(choice.reason, from, measured_ms, aim);
        self.quality
    }

    /// Records the decision that took the quality from `from` to the current one under
    /// `aim`.
    fn record(&mut self, reason: Reason, from: Quality, measured_ms: Option<f64>, aim: &Aim) {
        let to = self.quality;
        let held_ms = self.holding_range(aim);
        let action = if to == from {
            Action::Hold
        } else {
            match reason {
                Reason::InInnerBand => Action::Trade,
                Reason::UnderInnerBand => Action::Raise,
                Reason::NewBand | Reason::Follow => {
                    if to.at_least(&from) {
                        Action::Raise
                    } else {
                        Action::Cut
                    }
                }
                _ => Action::Cut,
            }
        };
        if matches!(action, Action::Raise | Action::Cut) {
            self.last_move = Some(action);
        }
        let band = self.setup.band;
        self.decision = Some(Decision {
            action,
            reason,
            measured_ms,
            predicted_ms: self.predict_ms(&to),
            target_ms: aim.target_ms,
            inner_ms: [held_ms.0, held_ms.1],
            band_ms: [band.tmin_ms(), band.tmax_ms()],
            from,
            to,
        });
    }

    /// Frames in a row measured above the inner band that make a drift (`measured_cut`):
    /// [`DRIFT_FRAMES`], or more where the recent prediction errors' scatter around their
    /// median lifts a frame planned at the target above the inner band often (a share p of
    /// them): the fewest n with
    /// p^n ≤ [`DRIFT_CHANCE`], at most [`MAX_DRIFT_FRAMES`]. On a machine whose frames
    /// scatter by 10 % or more, three frames above the inner band happen by chance every
    /// few dozen frames, and each such cut and the raise after it was a reversal.
    fn drift_frames(&self, aim: &Aim) -> u32 {
        let mut errors: Vec<f64> = self.cost.recent_errors().collect();
        if errors.len() < MIN_NOISE_FRAMES {
            return DRIFT_FRAMES;
        }
        // The scatter around the errors' median: a drift's errors all lean one way, which is
        // the drift to answer, not noise to wait out.
        errors.sort_by(f64::total_cmp);
        let median = errors[errors.len() / 2];
        let above = errors
            .iter()
            .filter(|&&r| aim.target_ms * (1.0 + r - median) > aim.high_ms)
            .count();
        if above == 0 {
            return DRIFT_FRAMES;
        }
        let share = above as f64 / errors.len() as f64;
        let needed = (DRIFT_CHANCE.ln() / share.ln()).ceil();
        if needed.is_finite() {
            (needed as u32).clamp(DRIFT_FRAMES, MAX_DRIFT_FRAMES)
        } else {
            MAX_DRIFT_FRAMES
        }
    }

    /// The quality at position `u` along the ladder: point `i` at `u = i`, and between
    /// points i and i + 1 each knob interpolated linearly (R rounded), so the controller can
    /// land on the target between two calibrated points; below point 0, down to
    /// [`LADDER_FLOOR`], point 0 at a resolution scale falling linearly to the bounds'
    /// lowest. Clamped into the bounds.
    pub fn ladder_quality(&self, ladder: &Ladder, u: f64) -> Quality {
        let last = ladder.points.len() - 1;
        let u = u.clamp(LADDER_FLOOR, last as f64);
        if u < 0.0 {
            let cheapest = ladder.points[0].quality();
            let scale = cheapest.get(Knob::Scale);
            let lowest = self.setup.bounds.range(Knob::Scale).0.min(scale);
            let t = u / LADDER_FLOOR;
            let q = cheapest.with(Knob::Scale, scale + t * (lowest - scale));
            return self.setup.bounds.clamp(q);
        }
        let i = (u.floor() as usize).min(last);
        let (a, b) = (ladder.points[i], ladder.points[(i + 1).min(last)]);
        let t = u - i as f64;
        let lerp = |x: f64, y: f64| x + t * (y - x);
        let q = Quality::new(
            lerp(f64::from(a.spp), f64::from(b.spp)) as f32,
            lerp(f64::from(a.depth), f64::from(b.depth)).round() as u32,
            lerp(f64::from(a.scale), f64::from(b.scale)) as f32,
        );
        self.setup.bounds.clamp(q)
    }

    /// The highest ladder position for which `fits` holds, moving one way only: a raise
    /// searches above the current position (staying put if nothing there fits), a cut below
    /// it, down to [`LADDER_FLOOR`] (there if nothing fits). Off the ladder (the starting
    /// quality), the whole ladder is searched. Whole positions are tried from the top down;
    /// the segment above the best one is then bisected.
    fn best_on_ladder(
        &self,
        ladder: &Ladder,
        fits: impl Fn(&Quality) -> bool,
        raising: bool,
    ) -> f64 {
        let top = (ladder.points.len() - 1) as f64;
        let (lo, hi) = match (self.ladder_pos, raising) {
            (None, _) => (LADDER_FLOOR, top),
            (Some(u), true) => (u, top),
            (Some(u), false) => (LADDER_FLOOR, u),
        };
        self.search_ladder(ladder, fits, (lo, hi), raising)
    }

    /// The highest position in `lo..=hi` for which `fits` holds: whole positions from the
    /// top down, then the segment above the best one bisected. When nothing fits: `lo`.
    fn search_ladder(
        &self,
        ladder: &Ladder,
        fits: impl Fn(&Quality) -> bool,
        (lo, hi): (f64, f64),
        raising: bool,
    ) -> f64 {
        let at = |u: f64| fits(&self.ladder_quality(ladder, u));
        let whole = (lo.ceil() as i64..=hi.floor() as i64)
            .rev()
            .map(|i| i as f64)
            .find(|&u| at(u));
        let (mut ok, mut bad) = match whole {
            Some(u) => (u, (u + 1.0).min(hi)),
            None if raising => (lo, (lo.floor() + 1.0).min(hi)),
            None => return lo,
        };
        if bad > ok && at(bad) {
            return bad;
        }
        for _ in 0..SEARCH_STEPS {
            let mid = 0.5 * (ok + bad);
            if at(mid) {
                ok = mid;
            } else {
                bad = mid;
            }
        }
        ok
    }

    /// The highest position on the ladder predicted to take at most `target_ms` on the current
    /// view (no limit on the raise), or `None` before the first frame, without a ladder, or
    /// when even its lowest position ([`LADDER_FLOOR`]) is predicted to take longer: where
    /// this controller would settle if `target_ms` were its target. The `perceptual`
    /// controller asks it for every frame time it considers.
    pub fn ladder_position_within(&self, target_ms: f64) -> Option<f64> {
        let ladder = self.params.ladder.as_ref()?;
        let fits = |q: &Quality| self.predict_ms(q).is_some_and(|t| t <= target_ms);
        if !fits(&self.ladder_quality(ladder, LADDER_FLOOR)) {
            return None;
        }
        let top = (ladder.points.len() - 1) as f64;
        Some(self.search_ladder(ladder, fits, (LADDER_FLOOR, top), true))
    }

    /// The band in use.
    pub fn band(&self) -> Band {
        self.setup.band
    }

    /// Moves the band to `band` and re-plans the quality at once from the last frame's
    /// measurements (as if that frame had been observed under the new band), so a new target
    /// frame time takes effect with the next frame. Returns the next quality.
    pub fn retarget(&mut self, band: Band) -> Quality {
        self.setup.band = band;
        self.above_run = 0;
        let aim = self.aim();
        let mut choice = self.decide(&aim);
        choice.reason = Reason::NewBand;
        self.apply(choice, None, &aim)
    }

    /// Where the knob order would settle for `target_ms` on the current view, raised from
    /// [`Predictive::lowest`], when that is a trade with the current quality: the first knob of the
    /// order on which they differ is higher in the plan and a later one lower (S and scale
    /// count as equal within [`TRADE_MARGIN`]). None otherwise, so inside the inner band the
    /// quality only moves to follow the view, never to creep.
    fn order_trade(&self, load: &RayModel, target_ms: f64) -> Option<Quality> {
        let fits = |q: &Quality| self.predict_ms(q).is_some_and(|t| t <= target_ms);
        let plan = self.climb(self.lowest(), &self.raise_stages(load), fits);
        let compare = |knob: Knob| {
            let (planned, now) = (plan.get(knob), self.quality.get(knob));
            if knob != Knob::Depth && (planned - now).abs() <= TRADE_MARGIN * now {
                std::cmp::Ordering::Equal
            } else {
                planned.total_cmp(&now)
            }
        };
        let order = self.params.order.knobs();
        let first = order.iter().position(|&k| compare(k).is_ne())?;
        let later_lower = order[first + 1..].iter().any(|&k| compare(k).is_lt());
        (compare(order[first]).is_gt() && later_lower).then_some(plan)
    }

    /// The knobs a raise goes through, each with its top: R up to the useful depth on the
    /// current view, then the others in order, then the rest of R. When the levels beyond
    /// the useful depth together carry no more rays than one level at `min_reach` would, R
    /// goes to its top at once: that costs about nothing, and it puts back the reflections
    /// of the few pixels that show a mirror or glass (a run cut to R = 0 on a view where 1 %
    /// of the eye rays met a mirror otherwise kept R = 0 for good, S taking all the room).
    fn raise_stages(&self, load: &RayModel) -> Vec<(Knob, f64)> {
        let b = &self.setup.bounds;
        let order = self.params.order.knobs();
        let mut useful = load.useful_depth(self.params.min_reach, b.depth_min, b.depth_max);
        let tail: f64 = (useful + 1..=b.depth_max).map(|k| load.reach(k)).sum();
        if tail <= self.params.min_reach {
            useful = b.depth_max;
        }
        let mut stages: Vec<(Knob, f64)> = order
            .iter()
            .map(|&k| {
                let top = if k == Knob::Depth {
                    f64::from(useful)
                } else {
                    b.range(k).1
                };
                (k, top)
            })
            .collect();
        if order.contains(&Knob::Depth) {
            stages.push((Knob::Depth, f64::from(b.depth_max)));
        }
        stages
    }

    /// The highest quality along the knob order for which `fits` holds. A raise starts from
    /// the current quality and only raises knobs ([`Predictive::raise_stages`]). A cut only
    /// lowers knobs: the highest quality below the current one in the order, so the last
    /// knob in the order goes first (the lowest quality if nothing fits). Neither trades one
    /// knob for another; [`Predictive::order_trade`] does, inside the inner band.
    fn best_fitting(
        &self,
        load: &RayModel,
        fits: impl Fn(&Quality) -> bool,
        raising: bool,
    ) -> Quality {
        if raising {
            return self.climb(self.quality, &self.raise_stages(load), fits);
        }
        let order = self.params.order.knobs();
        let stages: Vec<(Knob, f64)> = order.iter().map(|&k| (k, self.quality.get(k))).collect();
        self.climb(self.cut_floor(), &stages, fits)
    }

    /// The lowest quality a cut may reach: [`Predictive::lowest`], but keeping R on a drift
    /// (predictions scaled by its surprise): reflections that vanish are the most visible cut
    /// and the slowest to come back, and a few slow frames are often the machine's, not the
    /// view's. A lasting change of cost refits the cost model at its `confirm`-th outlier,
    /// and that cut may take R.
    fn cut_floor(&self) -> Quality {
        let lowest = self.lowest();
        if self.surprise > 1.0 {
            lowest.with(Knob::Depth, self.quality.get(Knob::Depth))
        } else {
            lowest
        }
    }

    /// The current quality with every knob of the order at its lowest.
    fn lowest(&self) -> Quality {
        let b = &self.setup.bounds;
        self.params
            .order
            .knobs()
            .iter()
            .fold(self.quality, |q, &knob| q.with(knob, b.range(knob).0))
    }

    /// From `q`, each knob of `stages` raised in turn to its top while `fits` holds; the
    /// first that cannot reach its top is raised as far as fits (R level by level, S and
    /// scale by bisection), and that is the answer.
    fn climb(
        &self,
        mut q: Quality,
        stages: &[(Knob, f64)],
        fits: impl Fn(&Quality) -> bool,
    ) -> Quality {
        let b = &self.setup.bounds;
        for &(knob, top) in stages {
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
        let (rays, tp_ms) = (report.total_rays() as f64, report.tp_ms);
        let expected = self.cost.predict_ms(rays);
        self.surprise = 1.0;
        // A budgeted frame's time is held by its budget and its rays vary instead; its
        // first sample, at the same speed of the machine, pins the fixed cost the frame's
        // time alone would let drift.
        if let Some(first) = report.first_sample {
            self.cost.observe(first.rays as f64, first.ms);
        }
        let fit = self.cost.observe(rays, tp_ms);
        // The aim follows the prediction errors, which only the cost model's `observe` moves:
        // one aim serves the whole decision.
        let aim = self.aim();
        if fit == Fit::Outlier {
            // Set aside by the cost model: a spike or a hitch, or the first frames of a change
            // of cost that its next outliers will confirm.
            self.record(Reason::SetAside, self.quality, Some(report.tp_ms), &aim);
            return Ok(self.quality);
        }
        // With `measured_cut`, frames in a row measured above the inner band are a drift the
        // model lags: predictions are then scaled by how much slower the frame ran than
        // predicted.
        self.above_run = if report.tp_ms > aim.high_ms {
            self.above_run + 1
        } else {
            0
        };
        let drift = self.params.measured_cut && self.above_run >= self.drift_frames(&aim);
        // A model just refitted to the latest frames already explains them.
        let refitted = fit == Fit::Shifted;
        if let Some(e) = expected.filter(|_| !refitted && drift) {
            self.surprise = (tp_ms / e).max(1.0);
        }
        self.update_load(report);
        // A surprise under which not even the lowest quality a cut may reach would fit is not
        // one a cut can answer (a fixed cost such as the temporal pass, scaled by it, fills
        // the band alone): cutting to that floor would only flash a poor frame. The
        // predictions stay as fitted; a lasting change of cost is refitted at its
        // `confirm`-th outlier.
        if self.surprise > 1.0
            && self
                .predict_ms(&self.cut_floor())
                .is_some_and(|t| t > aim.target_ms)
        {
            self.surprise = 1.0;
        }
        let choice = self.decide(&aim);
        Ok(self.apply(choice, Some(report.tp_ms), &aim))
    }

    fn decision(&self) -> Option<&Decision> {
        self.decision.as_ref()
    }

    fn set_band(&mut self, band: Band) {
        self.retarget(band);
    }

    fn frame_budget(&self) -> Option<FrameBudget> {
        self.params.budget.then(|| {
            budget::for_band(
                self.setup.band,
                self.aim().target_ms,
                self.setup.bounds.spp_max,
            )
        })
    }

    fn reset(&mut self) {
        self.quality = self.setup.start;
        self.cost = CostModel::new(self.params.cost.clone());
        self.load = None;
        self.trend = 0.0;
        self.surprise = 1.0;
        self.above_run = 0;
        self.last_move = None;
        self.ladder_pos = None;
        self.decision = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
            rays_stopped: None,
            pixels,
            quality: q,
            speed_deg_s: 0.0,
            first_sample: None,
        }
    }

    /// A new band (a live view's, once measured) keeps the fitted cost model: the next
    /// frame is already planned for it, where a controller built anew at the same quality
    /// would still hold that quality.
    #[test]
    fn a_new_band_keeps_the_cost_model_and_plans_for_it_at_once() {
        let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
        let mut c = Predictive::new(setup, PredictiveParams::default()).unwrap();
        for _ in 0..30 {
            let r = frame(c.quality(), 1e6);
            c.observe(&r).unwrap();
        }
        let settled = c.quality();
        assert!(Band::PAPER.contains(frame(settled, 1e6).tp_ms), "{settled}");
        let longer = Band::new(30.0, 40.0).unwrap();
        c.set_band(longer);
        let next = c.quality();
        assert!(next.level() > settled.level(), "{settled} -> {next}");
        assert!(longer.contains(frame(next, 1e6).tp_ms), "{next}");
        let rebuilt = Predictive::new(
            Setup {
                band: longer,
                start: settled,
                ..setup
            },
            PredictiveParams::default(),
        )
        .unwrap();
        assert_eq!(rebuilt.quality(), settled);
    }

    #[test]
    fn aims_below_the_centre_when_noise_only_slows_frames() {
        let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
        // The aim alone: on a constant load, cutting on measured frames only chases noise.
        let params = PredictiveParams {
            measured_cut: false,
            ..PredictiveParams::default()
        };
        let mut c = Predictive::new(setup, params).unwrap();
        let mut rng = crate::simulate::Pcg32::new(7);
        let mut in_band = 0;
        let frames = 600;
        for i in 0..frames {
            let mut r = frame(c.quality(), 1e6);
            // Half-normal noise, σ = 15 %: other work on the machine only ever adds time.
            r.tp_ms *= 1.0 + 0.15 * rng.normal().abs();
            if i >= 100 && Band::PAPER.contains(r.tp_ms) {
                in_band += 1;
            }
            c.observe(&r).unwrap();
        }
        let aim = c.aim();
        let pct = 100.0 * f64::from(in_band) / f64::from(frames - 100);
        // Aiming at the centre with the nominal inner band keeps 89 % of these frames, a
        // perfect aim 97.4 %. The aim's score is averaged over the inner band, here 1.5 ms
        // on each side under this heavy noise, as if the planned time wandered across it as
        // it does on a moving view: on this steady one that costs about two points.
        assert!(pct >= 95.0, "{pct:.1} % in band, aim {aim:?}");
        assert!(aim.target_ms < Band::PAPER.centre_ms(), "{aim:?}");
    }

    #[test]
    fn follows_a_view_growing_in_cost_close_to_the_target() {
        let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(4.0, 4, 1.0)).unwrap();
        let mut c = Predictive::new(setup, PredictiveParams::default()).unwrap();
        let mut rng = crate::simulate::Pcg32::new(3);
        let follow = INNER_HALF * Band::PAPER.width_ms();
        let mut pixels = 3e5;
        let mut follows = 0;
        for i in 0..200 {
            let mut r = frame(c.quality(), pixels);
            // Symmetric noise, σ = 6 %: enough to widen the inner band past `follow`.
            r.tp_ms *= 1.0 + 0.06 * rng.normal();
            c.observe(&r).unwrap();
            pixels *= 1.004;
            let d = c.decision().unwrap();
            if i < 50 {
                continue;
            }
            assert!(c.aim().high_ms - d.target_ms > follow + 0.5, "{d}");
            if d.reason == Reason::Follow {
                assert_eq!(d.action, Action::Cut, "{d}");
                follows += 1;
            }
            // Held after a cut, on a view whose cost grows, the planned time stays within
            // `follow` of the target, not anywhere in the noise-wide inner band.
            if d.action == Action::Hold && c.last_move == Some(Action::Cut) {
                let planned = d.predicted_ms.unwrap();
                assert!(planned <= d.target_ms + follow + 1e-9, "{d}");
                assert!((d.inner_ms[1] - (d.target_ms + follow)).abs() < 1e-9, "{d}");
            }
        }
        assert!(follows >= 5, "{follows} follow cuts");
    }

    #[test]
    fn frames_measured_above_the_inner_band_cut_deeper_with_measured_cut() {
        let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
        let after_slow_frames = |measured_cut: bool| {
            let params = PredictiveParams {
                measured_cut,
                ..PredictiveParams::default()
            };
            let mut c = Predictive::new(setup, params).unwrap();
            for _ in 0..30 {
                let r = frame(c.quality(), 1e6);
                c.observe(&r).unwrap();
            }
            let settled = c.quality();
            let high = c.aim().high_ms;
            // Frames slower than the model expects, above the inner band yet inside
            // the band and inside the cost model's tolerance.
            for _ in 0..DRIFT_FRAMES {
                let mut r = frame(c.quality(), 1e6);
                r.tp_ms = (high + 0.2).min(Band::PAPER.tmax_ms() - 0.1);
                c.observe(&r).unwrap();
            }
            (settled, c.quality())
        };
        // Without it the model moves only as far as three fitted frames pull it.
        let (settled, with) = after_slow_frames(true);
        let (_, without) = after_slow_frames(false);
        assert!(with.cmp_level(&settled).is_lt(), "{settled} -> {with}");
        assert!(with.cmp_level(&without).is_lt(), "{with} vs {without}");
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
