//! `step`: the paper's rule, exactly.
//!
//! Tp > Tmax: one step down; Tp < Tmin: one step up; inside the band: no change. Steps are ±1
//! on whole numbers, so with a coarse knob and a 1 ms timer the time oscillates across a
//! narrow band: the defect the paper reports, reproduced on purpose.

use crate::band::{Band, Position};
use crate::controller::{Controller, Setup, accept_time, parse_option};
use crate::error::ConfigError;
use crate::quality::{Bounds, Knob, Quality};
use crate::report::{FrameReport, ReportError};
use std::fmt;
use std::str::FromStr;

/// Which knob `step` turns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum StepKnob {
    /// R only (the paper's experiment).
    #[default]
    Depth,
    /// S only (in whole samples).
    Spp,
    /// Both: cuts S first down to its minimum, then R; raises R first up to its maximum,
    /// then S.
    Both,
}

impl FromStr for StepKnob {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "depth" => Ok(Self::Depth),
            "spp" => Ok(Self::Spp),
            "both" => Ok(Self::Both),
            other => Err(format!(
                "unknown knob `{other}`: expected depth, spp or both"
            )),
        }
    }
}

impl fmt::Display for StepKnob {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Depth => "depth",
            Self::Spp => "spp",
            Self::Both => "both",
        })
    }
}

/// Parameters of [`Step`]. Option: `knob=depth|spp|both` (default `depth`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub struct StepParams {
    /// Which knob each step turns.
    pub knob: StepKnob,
}

impl StepParams {
    /// Sets one option by name (used by [`crate::from_name`]).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        match key {
            "knob" => self.knob = parse_option(key, value, |_| Ok(()))?,
            _ => {
                return Err(ConfigError::UnknownOption {
                    controller: "step",
                    key: key.to_string(),
                    expected: crate::options::expected_keys("step"),
                });
            }
        }
        Ok(())
    }
}

/// The paper's controller: ±1 on R or S when Tp leaves the band.
#[derive(Clone, Debug)]
pub struct Step {
    setup: Setup,
    params: StepParams,
    quality: Quality,
}

impl Step {
    /// A step controller; errors if the bounds hold no whole S while S is a knob.
    pub fn new(setup: Setup, params: StepParams) -> Result<Self, ConfigError> {
        setup.validate()?;
        if params.knob != StepKnob::Depth {
            setup.bounds.ladder(Knob::Spp, setup.start)?;
        }
        Ok(Self {
            setup,
            params,
            quality: setup.start,
        })
    }
}

/// S one whole sample down (or to the next whole number below a fractional S).
fn spp_down(s: f32, b: &Bounds) -> f32 {
    (s.ceil() - 1.0).max(b.spp_min)
}

/// S one whole sample up (or to the next whole number above a fractional S).
fn spp_up(s: f32, b: &Bounds) -> f32 {
    (s.floor() + 1.0).min(b.spp_max)
}

impl Controller for Step {
    fn name(&self) -> &'static str {
        "step"
    }

    fn quality(&self) -> Quality {
        self.quality
    }

    fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError> {
        let tp = accept_time(report)?;
        let b = self.setup.bounds;
        let q = &mut self.quality;
        match (self.setup.band.position(tp), self.params.knob) {
            (Position::In, _) => {}
            (Position::Over, StepKnob::Depth) => {
                q.depth = q.depth.saturating_sub(1).max(b.depth_min)
            }
            (Position::Over, StepKnob::Spp) => q.spp = spp_down(q.spp, &b),
            (Position::Over, StepKnob::Both) => {
                if q.spp > b.spp_min {
                    q.spp = spp_down(q.spp, &b);
                } else {
                    q.depth = q.depth.saturating_sub(1).max(b.depth_min);
                }
            }
            (Position::Under, StepKnob::Depth) => q.depth = (q.depth + 1).min(b.depth_max),
            (Position::Under, StepKnob::Spp) => q.spp = spp_up(q.spp, &b),
            (Position::Under, StepKnob::Both) => {
                if q.depth < b.depth_max {
                    q.depth += 1;
                } else {
                    q.spp = spp_up(q.spp, &b);
                }
            }
        }
        Ok(*q)
    }

    fn reset(&mut self) {
        self.quality = self.setup.start;
    }

    fn set_band(&mut self, band: Band) {
        self.setup.band = band;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(tp_ms: f64, q: Quality) -> FrameReport {
        FrameReport {
            tp_ms,
            rays_per_depth: vec![1],
            rays_stopped: None,
            shadow_rays: 0,
            pixels: 1,
            quality: q,
            speed_deg_s: 0.0,
            first_sample: None,
        }
    }

    fn step(knob: StepKnob, start: Quality) -> Step {
        let setup = Setup::new(Band::PAPER, Bounds::default(), start).unwrap();
        Step::new(setup, StepParams { knob }).unwrap()
    }

    #[test]
    fn follows_the_paper_rule() {
        let start = Quality::new(4.0, 8, 1.0);
        let mut c = step(StepKnob::Depth, start);
        assert_eq!(c.observe(&report(25.0, start)).unwrap().depth, 7);
        assert_eq!(c.observe(&report(17.0, start)).unwrap().depth, 7);
        assert_eq!(c.observe(&report(10.0, start)).unwrap().depth, 8);
        assert_eq!(c.observe(&report(20.0, start)).unwrap().depth, 8);
        assert_eq!(c.observe(&report(15.0, start)).unwrap().depth, 8);
        assert_eq!(c.quality().spp, 4.0);
    }

    #[test]
    fn both_cuts_spp_first_and_raises_depth_first() {
        let start = Quality::new(2.0, 15, 1.0);
        let mut c = step(StepKnob::Both, start);
        assert_eq!(
            c.observe(&report(30.0, start)).unwrap(),
            Quality::new(1.0, 15, 1.0)
        );
        assert_eq!(
            c.observe(&report(30.0, start)).unwrap(),
            Quality::new(1.0, 14, 1.0)
        );
        assert_eq!(
            c.observe(&report(5.0, start)).unwrap(),
            Quality::new(1.0, 15, 1.0)
        );
        assert_eq!(
            c.observe(&report(5.0, start)).unwrap(),
            Quality::new(1.0, 16, 1.0)
        );
        assert_eq!(
            c.observe(&report(5.0, start)).unwrap(),
            Quality::new(2.0, 16, 1.0)
        );
    }

    #[test]
    fn stays_inside_bounds_and_rounds_fractional_spp() {
        let start = Quality::new(2.5, 0, 1.0);
        let mut c = step(StepKnob::Spp, start);
        assert_eq!(c.observe(&report(30.0, start)).unwrap().spp, 2.0);
        assert_eq!(c.observe(&report(30.0, start)).unwrap().spp, 1.0);
        assert_eq!(c.observe(&report(30.0, start)).unwrap().spp, 1.0);
        let mut d = step(StepKnob::Depth, Quality::new(1.0, 16, 1.0));
        assert_eq!(d.observe(&report(1.0, start)).unwrap().depth, 16);
    }
}
