//! `hysteresis`: cut fast, raise slowly; the standard fix for oscillation in games' dynamic
//! resolution (Unreal's budget with headroom and minimum change interval, HDRP's "step down
//! fast, step up slowly").
//!
//! It needs no cost model, only Tp. Quality moves along the knob order (raised in order,
//! cut in reverse) by a *work factor*: nominal work is proportional to S, to scale² and to
//! R + 1, so a factor f multiplies S by f, or scale by √f, or R + 1 by f (whole steps, at
//! least one), spilling over to the next knob when one reaches its bound.
//!
//! - Cut: when Tp > Tmax (at once, the panic path), or when `cut_after` frames in a row are
//!   above the soft limit Tmin + `cut_above`·(Tmax − Tmin) and `min_interval` frames have
//!   passed since the last change. The factor is target / Tp: proportional to the overshoot.
//! - Raise: after `up_after` frames in a row below Tmin + `raise_below`·(Tmax − Tmin), by
//!   target / mean(Tp) but at most 1 + `max_up` (no limit when their mean is under Tmin:
//!   frames out of the band are as wrong as frames over it).
//! - Spike: a first frame over Tmax after frames under the soft limit cuts no further than
//!   would land the frame before it at the target (nothing when that frame was at or under
//!   it): on a real machine one slow frame is more often a spike than a change of load, and
//!   a full cut on its word lands the next frame under the band. A second frame over
//!   confirms the change and cuts in full.
//! - Hitch: a frame over Tmax and more than `hitch_ratio` times the previous frame is held
//!   (no change) unless the next frame confirms it, so a one-frame spike costs no quality.

use crate::band::Band;
use crate::controller::{Controller, Setup, accept_time, parse_option, within};
use crate::error::ConfigError;
use crate::quality::{Bounds, Knob, KnobOrder, Quality};
use crate::report::{FrameReport, ReportError};

/// Parameters of [`Hysteresis`], with their option names and defaults.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct HysteresisParams {
    /// `order`: knobs in raising order; cut in reverse. Default `depth,scale,spp`.
    pub order: KnobOrder,
    /// `target`: where in the band a change aims, as a fraction (0 = Tmin, 1 = Tmax).
    /// Default 0.4 (17 ms in [15, 20]): below the centre, a budget with headroom, so that a
    /// rising load takes a few frames to reach the soft limit.
    pub target: f64,
    /// `cut_above`: the soft upper limit as a fraction of the band. Default 0.8 (19 ms in
    /// [15, 20]): cutting before Tmax keeps frames in the band while the load rises.
    pub cut_above: f64,
    /// `cut_after`: frames in a row above the soft limit before a soft cut. Default 1.
    pub cut_after: u32,
    /// `raise_below`: headroom limit as a fraction of the band. Default 0.3 (16.5 ms).
    pub raise_below: f64,
    /// `up_after`: frames in a row with headroom before a raise. Default 3.
    pub up_after: u32,
    /// `max_up`: the largest relative increase of nominal work per raise. Default 0.3.
    pub max_up: f64,
    /// `min_interval`: frames between changes (a frame over Tmax cuts regardless). Default 3.
    pub min_interval: u32,
    /// `hitch_ratio`: a frame over Tmax and this many times slower than the previous frame
    /// is held as a possible hitch. Default 3.
    pub hitch_ratio: f64,
}

impl Default for HysteresisParams {
    fn default() -> Self {
        Self {
            order: KnobOrder::default(),
            target: 0.4,
            cut_above: 0.8,
            cut_after: 1,
            raise_below: 0.3,
            up_after: 3,
            max_up: 0.3,
            min_interval: 3,
            hitch_ratio: 3.0,
        }
    }
}

impl HysteresisParams {
    /// Sets one option by name (used by [`crate::from_name`]).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        match key {
            "order" => self.order = parse_option(key, value, |_| Ok(()))?,
            "target" => self.target = parse_option(key, value, within(0.0, 1.0))?,
            "cut_above" => self.cut_above = parse_option(key, value, within(0.0, 1.0))?,
            "cut_after" => self.cut_after = parse_option(key, value, within(1, 1000))?,
            "raise_below" => self.raise_below = parse_option(key, value, within(0.0, 1.0))?,
            "up_after" => self.up_after = parse_option(key, value, within(1, 10_000))?,
            "max_up" => self.max_up = parse_option(key, value, within(0.001, 10.0))?,
            "min_interval" => self.min_interval = parse_option(key, value, within(0, 10_000))?,
            "hitch_ratio" => self.hitch_ratio = parse_option(key, value, within(1.0, 1e6))?,
            _ => {
                return Err(ConfigError::UnknownOption {
                    controller: "hysteresis",
                    key: key.to_string(),
                    expected: crate::options::expected_keys("hysteresis"),
                });
            }
        }
        Ok(())
    }

    /// Checks that the limits are ordered: raise_below < target < cut_above.
    fn validate(&self) -> Result<(), ConfigError> {
        if !(self.raise_below < self.target && self.target < self.cut_above) {
            return Err(ConfigError::BadOption {
                key: "target".into(),
                value: self.target.to_string(),
                why: format!(
                    "must lie strictly between raise_below ({}) and cut_above ({})",
                    self.raise_below, self.cut_above
                ),
            });
        }
        Ok(())
    }
}

/// The hysteresis controller (see the module documentation).
#[derive(Clone, Debug)]
pub struct Hysteresis {
    setup: Setup,
    params: HysteresisParams,
    quality: Quality,
    /// Frames observed since the last change.
    since_change: u32,
    /// Frames in a row above the soft limit.
    over_run: u32,
    /// Frames in a row with headroom, and the sum of their times.
    headroom_run: u32,
    headroom_sum: f64,
    /// The last frame time that was not held as a hitch.
    last_tp: Option<f64>,
    /// Whether the previous frame was held as a possible hitch.
    held: bool,
}

impl Hysteresis {
    /// A hysteresis controller; errors on a bad setup or disordered limits.
    pub fn new(setup: Setup, params: HysteresisParams) -> Result<Self, ConfigError> {
        setup.validate()?;
        params.validate()?;
        Ok(Self::fresh(setup, params))
    }

    /// A controller at the starting quality with an empty history.
    fn fresh(setup: Setup, params: HysteresisParams) -> Self {
        Self {
            setup,
            params,
            quality: setup.start,
            since_change: 0,
            over_run: 0,
            headroom_run: 0,
            headroom_sum: 0.0,
            last_tp: None,
            held: false,
        }
    }

    /// The parameters in use.
    pub fn params(&self) -> &HysteresisParams {
        &self.params
    }

    /// The quality change this frame calls for, if any.
    fn decide(&mut self, tp: f64, before: Option<f64>) -> Option<Quality> {
        let band = self.setup.band;
        let p = &self.params;
        let target = band.at(p.target);
        if tp > band.at(p.cut_above) {
            self.over_run += 1;
        } else {
            self.over_run = 0;
        }
        if tp < band.at(p.raise_below) {
            self.headroom_run += 1;
            self.headroom_sum += tp;
        } else {
            self.headroom_run = 0;
            self.headroom_sum = 0.0;
        }
        let settled = self.since_change >= p.min_interval;
        let overload = tp > band.tmax_ms();
        let factor = if overload
            && self.over_run == 1
            && let Some(before) = before
        {
            // One frame over Tmax after frames under the soft limit: on a real machine more
            // often a spike than a change of load. Cut only as far as lands the next frame at
            // the target should it have been one (none when the frame before was already
            // there); a second frame over confirms it and cuts in full.
            let spike_safe = target / before;
            if spike_safe >= 1.0 {
                return None;
            }
            (target / tp).max(spike_safe).min(0.97)
        } else if overload || (self.over_run >= p.cut_after && settled) {
            (target / tp).min(0.97)
        } else if self.headroom_run >= p.up_after && settled {
            let mean = self.headroom_sum / f64::from(self.headroom_run);
            if mean < band.tmin_ms() {
                target / mean
            } else {
                (target / mean).min(1.0 + p.max_up)
            }
        } else {
            return None;
        };
        let next = scale_work(self.quality, factor, &p.order, &self.setup.bounds);
        (next != self.quality).then_some(next)
    }
}

/// `q` with its nominal work multiplied by about `factor`, moving knobs in `order` (raising)
/// or in reverse (cutting); each knob absorbs what it can before the next one moves.
fn scale_work(mut q: Quality, mut factor: f64, order: &KnobOrder, b: &Bounds) -> Quality {
    let cutting = factor < 1.0;
    let knobs: Vec<Knob> = if cutting {
        order.knobs().iter().rev().copied().collect()
    } else {
        order.knobs().to_vec()
    };
    for knob in knobs {
        let (lo, hi) = b.range(knob);
        let v = q.get(knob);
        let work = |v: f64| match knob {
            Knob::Spp => v,
            Knob::Scale => v * v,
            Knob::Depth => v + 1.0,
        };
        let wanted = work(v) * factor;
        let nv = match knob {
            Knob::Spp => wanted,
            Knob::Scale => wanted.sqrt(),
            // Whole steps, at least one in the asked direction.
            Knob::Depth if cutting => (wanted - 1.0).floor().min(v - 1.0),
            Knob::Depth => (wanted - 1.0).floor().max(v + 1.0),
        }
        .clamp(lo, hi);
        factor *= work(v) / work(nv);
        q = q.with(knob, nv);
        let at_bound = if cutting { nv <= lo } else { nv >= hi };
        if !at_bound {
            break;
        }
    }
    q
}

impl Controller for Hysteresis {
    fn name(&self) -> &'static str {
        "hysteresis"
    }

    fn quality(&self) -> Quality {
        self.quality
    }

    fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError> {
        let tp = accept_time(report)?;
        let hitch = self.last_tp.is_some_and(|last| {
            tp > self.setup.band.tmax_ms() && tp > self.params.hitch_ratio * last
        });
        if hitch && !self.held {
            self.held = true;
            return Ok(self.quality);
        }
        self.held = false;
        let before = self.last_tp.replace(tp);
        self.since_change = self.since_change.saturating_add(1);
        if let Some(next) = self.decide(tp, before) {
            self.quality = next;
            self.since_change = 0;
            self.over_run = 0;
            self.headroom_run = 0;
            self.headroom_sum = 0.0;
        }
        Ok(self.quality)
    }

    fn reset(&mut self) {
        *self = Self::fresh(self.setup, self.params.clone());
    }

    /// The runs over and under the band's edges start again: they were counted against
    /// the old band.
    fn set_band(&mut self, band: Band) {
        self.setup.band = band;
        self.over_run = 0;
        self.headroom_run = 0;
        self.headroom_sum = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_scaling_spills_over_in_cut_order() {
        let b = Bounds::default();
        let order = KnobOrder::default();
        let q = Quality::new(8.0, 16, 1.0);
        // Cut: S first.
        let c = scale_work(q, 0.25, &order, &b);
        assert_eq!(c, Quality::new(2.0, 16, 1.0));
        // A deep cut spills from S (down to 1, factor 1/8) into scale (work ∝ scale²).
        let d = scale_work(q, 1.0 / 32.0, &order, &b);
        assert_eq!((d.scale, d.spp, d.depth), (0.5, 1.0, 16));
        // Raise: depth first (at max already), then scale, then S.
        let r = scale_work(Quality::new(1.0, 16, 0.5), 1.21, &order, &b);
        assert!((r.scale - 0.55).abs() < 1e-5 && r.depth == 16 && r.spp == 1.0);
        let r = scale_work(Quality::new(8.0, 16, 1.0), 1.1, &order, &b);
        assert!((r.spp - 8.8).abs() < 1e-5 && r.depth == 16 && r.scale == 1.0);
        // Depth moves by whole steps, at least one.
        let only_depth: KnobOrder = "depth".parse().unwrap();
        assert_eq!(scale_work(q, 0.99, &only_depth, &b).depth, 15);
        assert_eq!(
            scale_work(Quality::new(8.0, 2, 1.0), 1.01, &only_depth, &b).depth,
            3
        );
    }

    #[test]
    fn disordered_limits_are_rejected() {
        let setup = Setup::new(
            crate::Band::PAPER,
            Bounds::default(),
            Quality::new(1.0, 0, 1.0),
        )
        .unwrap();
        let p = HysteresisParams {
            target: 0.9,
            ..HysteresisParams::default()
        };
        assert!(matches!(
            Hysteresis::new(setup, p),
            Err(ConfigError::BadOption { .. })
        ));
    }
}
