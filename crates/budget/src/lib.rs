//! A frame's time budget, for a renderer that takes its eye samples a small unit at a time
//! (a progressive renderer): when to stop adding units before the frame runs over, and how
//! long to go on adding them past the planned S when the frame would end early.
//!
//! A controller plans each frame's quality from the frames before it, so a frame that runs
//! slower than predicted (the machine's timing spikes and its spells of slower speed) ends
//! over the band, and one that runs faster ends under it; on a shared 2-core VM that noise
//! alone kept 6–15 % of frames out of a ±14 % band whatever the plan (`aim_ceiling`). A
//! renderer that honours a budget decides the last part of the frame's work inside the
//! frame, against its own clock: it always renders one sample in every pixel (the frame's
//! least), then adds units while the next one still ends by [`FrameBudget::stop_by_ms`],
//! and past the planned S while the frame has taken less than
//! [`FrameBudget::fill_until_ms`]. The frame then reports the S it reached, so the
//! controller learns from the work actually done.

use serde::{Deserialize, Serialize};
use std::ops::Range;
use thiserror::Error;

/// The groups of pixels a pass of units is split into: a unit adds samples to one group,
/// a sixteenth of the pixels spread evenly over the image (a pixel's group follows its
/// place in an ordered-dither matrix), so a frame stopped after any unit has its extra
/// samples spread as a fractional S would spread them.
pub const UNIT_GROUPS: u32 = 16;

/// The samples a unit adds to each pixel of its group: a pair mirrored about the pixel
/// centre, so a pixel's samples keep their centroid at the centre whatever unit the frame
/// stops after (its first sample is the centre).
pub const UNIT_SAMPLES: u32 = 2;

/// The units past the first sample of every pixel that make a frame's mean S = `spp`, to
/// the nearest unit (S moves in steps of [`UNIT_SAMPLES`] / [`UNIT_GROUPS`] = 1/8).
pub fn units_for_spp(spp: f32) -> u32 {
    (f64::from((spp - 1.0).max(0.0)) / f64::from(UNIT_SAMPLES) * f64::from(UNIT_GROUPS)).round()
        as u32
}

/// The mean S of a frame that took `units` units past its first sample.
pub fn spp_of_units(units: u32) -> f32 {
    1.0 + (UNIT_SAMPLES * units) as f32 / UNIT_GROUPS as f32
}

/// One frame's time budget (see the module documentation). Times are ms since the frame
/// began, on the renderer's clock (the one Tp is measured on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameBudget {
    /// The frame adds no unit that would end after this.
    pub stop_by_ms: f64,
    /// The frame goes on adding units past the planned S while it has taken less than this.
    pub fill_until_ms: f64,
    /// The most eye rays per pixel filling may reach.
    pub max_spp: f32,
}

impl FrameBudget {
    /// A budget that fills a frame up to `fill_until_ms`, stops it by `stop_by_ms` and fills
    /// up to `max_spp` eye rays per pixel. Errors unless 0 < fill_until ≤ stop_by (finite)
    /// and max_spp ≥ 1.
    pub fn new(fill_until_ms: f64, stop_by_ms: f64, max_spp: f32) -> Result<Self, BudgetError> {
        if !(fill_until_ms.is_finite() && stop_by_ms.is_finite() && fill_until_ms > 0.0) {
            return Err(BudgetError::BadTimes {
                fill_until_ms,
                stop_by_ms,
            });
        }
        if fill_until_ms > stop_by_ms {
            return Err(BudgetError::FillPastStop {
                fill_until_ms,
                stop_by_ms,
            });
        }
        if !max_spp.is_finite() || max_spp < 1.0 {
            return Err(BudgetError::BadSpp(max_spp));
        }
        Ok(Self {
            stop_by_ms,
            fill_until_ms,
            max_spp,
        })
    }

    /// Whether a frame that has taken `elapsed_ms`, whose last unit of samples took
    /// `unit_ms`, starts another: only if it would end by [`FrameBudget::stop_by_ms`], and,
    /// for a unit past the planned S (`planned` false), only while the frame has taken less
    /// than [`FrameBudget::fill_until_ms`]. The renderer itself stops at `max_spp`.
    pub fn another_unit(&self, elapsed_ms: f64, unit_ms: f64, planned: bool) -> bool {
        elapsed_ms + unit_ms <= self.stop_by_ms && (planned || elapsed_ms < self.fill_until_ms)
    }

    /// Runs a frame's units under this budget, the one schedule every renderer follows:
    /// `planned` units make the frame's planned S ([`units_for_spp`]); `elapsed_ms` reads
    /// the frame's clock (the first sample of every pixel already taken), `units(range)`
    /// renders the units of `range`, in order. A unit is expected to take as long as the
    /// last batch's took per unit (the first, as long as the frame so far per unit of
    /// work). Units go in batches of at most half the time left to the batch's limit (the
    /// stopping time for planned units, the fill time past them), so that a batch that ran
    /// twice as slow as expected still ends by it, and a renderer pays its per-batch cost
    /// (waking its threads) a few times a frame rather than once a unit. Stops at `max_spp`
    /// (or the plan, if higher). Returns the units rendered.
    pub fn run_units(
        &self,
        planned: u32,
        mut elapsed_ms: impl FnMut() -> f64,
        mut units: impl FnMut(Range<u32>),
    ) -> u32 {
        let most = units_for_spp(self.max_spp).max(planned);
        let mut now = elapsed_ms();
        let mut per_unit = now * f64::from(UNIT_SAMPLES) / f64::from(UNIT_GROUPS);
        let mut done = 0;
        while done < most {
            let planned_left = done < planned;
            if !self.another_unit(now, per_unit, planned_left) {
                break;
            }
            let (limit, cap) = if planned_left {
                (self.stop_by_ms, planned)
            } else {
                (self.fill_until_ms, most)
            };
            let room = ((limit - now) / 2.0 / per_unit.max(1e-6)).floor();
            let batch = (room.min(f64::from(cap - done)) as u32).max(1);
            units(done..done + batch);
            let then = now;
            now = elapsed_ms();
            per_unit = (now - then) / f64::from(batch);
            done += batch;
        }
        done
    }
}

/// The rays and time of a budgeted frame's first sample of every pixel
/// (the controller crate's `FrameReport::first_sample`): the part of the
/// frame its planned quality fixed, whose time still shows what a ray costs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FirstSample {
    /// Rays traced: eye rays, deeper levels and shadow rays.
    pub rays: u64,
    /// Time from the frame's start to the end of the first sample, ms.
    pub ms: f64,
}

/// Why a [`FrameBudget`] cannot be made.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BudgetError {
    /// Times that are not finite, or a fill time of 0 ms or less.
    #[error(
        "frame budget: fill until {fill_until_ms} ms, stop by {stop_by_ms} ms: its times must \
         be finite and above 0 ms"
    )]
    BadTimes {
        /// The fill time given, ms.
        fill_until_ms: f64,
        /// The stopping time given, ms.
        stop_by_ms: f64,
    },
    /// A fill time after the stopping time.
    #[error(
        "frame budget: fill until {fill_until_ms} ms, stop by {stop_by_ms} ms: a frame cannot \
         fill past the time it must stop by"
    )]
    FillPastStop {
        /// The fill time given, ms.
        fill_until_ms: f64,
        /// The stopping time given, ms.
        stop_by_ms: f64,
    },
    /// A most S under 1, infinite or NaN.
    #[error("frame budget: at most S = {0} eye rays per pixel: it must be a number, at least 1")]
    BadSpp(f32),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_go_on_while_they_fit_and_fill_only_before_the_fill_time() {
        let b = FrameBudget::new(17.5, 19.5, 8.0).unwrap();
        assert!(b.another_unit(18.0, 1.0, true), "planned, ends at 19.0");
        assert!(
            !b.another_unit(18.6, 1.0, true),
            "planned, would end at 19.6"
        );
        assert!(
            b.another_unit(17.0, 1.0, false),
            "fill before the fill time"
        );
        assert!(
            !b.another_unit(17.5, 0.5, false),
            "no fill from the fill time on"
        );
    }

    /// A frame on a clock where the first sample took `first` ms and each unit `unit` ms.
    fn units_run(budget: &FrameBudget, planned: u32, first: f64, unit: f64) -> u32 {
        let clock = std::cell::Cell::new(first);
        let mut next = 0;
        let done = budget.run_units(
            planned,
            || clock.get(),
            |batch| {
                assert_eq!(batch.start, next, "batches follow each other");
                next = batch.end;
                clock.set(clock.get() + unit * batch.len() as f64);
            },
        );
        assert_eq!(done, next);
        done
    }

    #[test]
    fn a_frame_runs_its_plan_cuts_it_when_slow_and_fills_it_when_fast() {
        let b = FrameBudget::new(17.5, 19.5, 8.0).unwrap();
        assert_eq!(units_for_spp(3.0), 16);
        assert_eq!(spp_of_units(16), 3.0);
        // 5 ms for the first sample, 2 x 5 / 16 for each unit: S = 3 ends at 15 ms, where
        // filling goes on to 17.5 ms and past (four more units, to 17.5 ms).
        assert_eq!(units_run(&b, 16, 5.0, 0.625), 20);
        // Twice as slow: the frame stops before 19.5 ms.
        let slow = units_run(&b, 16, 10.0, 1.25);
        assert_eq!(slow, 7, "10 + 7 x 1.25 = 18.75, one more would end at 20");
        // Filling stops at max_spp.
        assert_eq!(units_run(&b, 16, 1.0, 0.1), units_for_spp(8.0));
    }

    #[test]
    fn bad_budgets_are_refused_with_the_reason() {
        let err = |r: Result<FrameBudget, BudgetError>| r.unwrap_err().to_string();
        assert!(err(FrameBudget::new(0.0, 19.5, 8.0)).contains("above 0"));
        assert!(err(FrameBudget::new(f64::NAN, 19.5, 8.0)).contains("finite"));
        assert!(err(FrameBudget::new(20.0, 19.5, 8.0)).contains("fill past"));
        assert!(err(FrameBudget::new(17.5, 19.5, 0.5)).contains("at least 1"));
    }
}
