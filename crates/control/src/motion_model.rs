//! A quality model over (speed, frame time, setting): how good the displayed video looks when
//! what it shows moves on screen at a given speed, each frame stays on screen for a given
//! time, and frames are rendered at a given point of a calibrated [`Ladder`].
//!
//! `steadyray calibrate --motion` measures it (short stimuli at fixed speeds, frame times and
//! settings, scored against a reference video) and writes it as `motion.json`; the
//! `perceptual` controller reads it to choose the frame rate and the quality together
//! ([`crate::perceptual`]).
//!
//! # `motion.json`
//!
//! ```json
//! {
//!   "metric": "jod",
//!   "scene": "corridor",
//!   "resolution": [640, 360],
//!   "refresh_hz": 60.0,
//!   "stimulus_s": 1.0,
//!   "viewing": { "name": "standard_fhd", "diagonal_in": 24.0, "resolution": [1920, 1080], "distance_m": 0.6 },
//!   "ladder": { "scene": "corridor", "resolution": [640, 360], "reference": { "spp": 16.0, "depth": 16, "scale": 1.0 }, "views": 8, "points": [ ... ] },
//!   "speeds_deg_s": [0.0, 10.0, 40.0],
//!   "frame_times_ms": [16.667, 33.333, 50.0],
//!   "scores": [ [ [7.1, 8.0], [7.3, 8.4], [7.4, 8.6] ], ... ]
//! }
//! ```
//!
//! - `metric`: what the scores are. `jod`: ColorVideoVDP's just-objectionable-difference
//!   units of the displayed video against the reference video (10 = indistinguishable;
//!   higher is better): the figure claims rest on. `displayed_flip`: mean FLIP of the screen
//!   against the reference at each refresh (0 = identical; lower is better), the fill-in when
//!   Python is not available. The controller maximizes the score, or minimizes it for
//!   `displayed_flip`.
//! - `speeds_deg_s`: the stimuli's speeds on screen, degrees of visual angle per second
//!   under `viewing`, strictly rising from 0 or more.
//! - `frame_times_ms`: how long each frame stays on screen, strictly rising: the frame
//!   times a controller may choose (on a fixed-refresh display, whole numbers of refreshes).
//! - `ladder`: the settings scored, in the format of `ladder.json` ([`crate::ladder`]).
//! - `scores[i][j][k]`: the score at speed i, frame time j and ladder point k.
//! - `scene`, `resolution`, `refresh_hz`, `stimulus_s` (each stimulus's length) and `viewing`
//!   say what was measured.
//!
//! Between grid values the model interpolates linearly in speed and in the ladder position
//! (as the `predictive` controller moves between ladder points), and holds the end values
//! beyond the grid's speeds. Below the cheapest point, where the controller goes on at lower
//! resolution ([`crate::ladder::LADDER_FLOOR`]) and no stimulus was shown,
//! [`MotionModel::utility_below`] extrapolates by the rays saved.
//!
//! # The shipped default
//!
//! [`MotionModel::shipped`] is a model that comes with the crate
//! (`models/default-motion.json`), for `perceptual` without a model of its own scene: one
//! ladder, and scores that are the mean ([`MotionModel::mean`]) of models calibrated on that
//! ladder on several scenes. Any ladder works on any scene (the controller predicts each
//! point's cost on the current view from the measured rays), so what the mean gives up is
//! only each scene's own ordering of the frame times at each speed. How it was made, and how
//! to make it again: `docs/default-motion-model.md`.

use crate::ladder::Ladder;
use serde::{Deserialize, Serialize};
use std::fmt;

/// The text of the shipped default model (see [`MotionModel::shipped`]).
pub const SHIPPED_MODEL_JSON: &str = include_str!("../models/default-motion.json");

/// What a model's scores measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// ColorVideoVDP's JOD of the displayed video against the reference (higher is better).
    Jod,
    /// Mean FLIP of the screen against the reference at each refresh (lower is better).
    DisplayedFlip,
}

impl Metric {
    /// +1 when a higher score is better, −1 when a lower one is.
    pub fn sign(self) -> f64 {
        match self {
            Metric::Jod => 1.0,
            Metric::DisplayedFlip => -1.0,
        }
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Metric::Jod => "jod",
            Metric::DisplayedFlip => "displayed_flip",
        })
    }
}

/// A quality model over (speed, frame time, ladder point): see the module documentation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MotionModel {
    /// What the scores measure, and so whether higher or lower is better.
    pub metric: Metric,
    /// The scene the stimuli showed.
    pub scene: String,
    /// Full-scale image size of the stimuli.
    pub resolution: [u32; 2],
    /// The display's refresh rate the stimuli were shown at, Hz.
    pub refresh_hz: f64,
    /// Each stimulus's length, s.
    pub stimulus_s: f64,
    /// Whether the stimuli were shown by the temporal mode with each refresh between two
    /// frames warped to its own time (`calibrate --motion --warp`), or as plain frames held
    /// on screen (absent in older models: plain).
    #[serde(default)]
    pub warped: bool,
    /// The viewing set-up the scores assume (information only).
    pub viewing: serde_json::Value,
    /// The settings scored.
    pub ladder: Ladder,
    /// Speeds on screen, degrees of visual angle per second, strictly rising.
    pub speeds_deg_s: Vec<f64>,
    /// Frame times (time on screen per frame), ms, strictly rising.
    pub frame_times_ms: Vec<f64>,
    /// `scores[speed][frame time][ladder point]`.
    pub scores: Vec<Vec<Vec<f64>>>,
}

/// Checks that `values` are finite, at least `min` (and above it if `strict_min`), and
/// strictly rising.
fn check_axis(name: &str, values: &[f64], min: f64, strict_min: bool) -> Result<(), String> {
    if values.is_empty() {
        return Err(format!("{name} is empty"));
    }
    for (i, &v) in values.iter().enumerate() {
        let low = if strict_min { v <= min } else { v < min };
        if !v.is_finite() || low {
            let bound = if strict_min { "above" } else { "at least" };
            return Err(format!(
                "{name}[{i}] = {v} must be finite and {bound} {min}"
            ));
        }
        if i > 0 && v <= values[i - 1] {
            return Err(format!(
                "{name} must rise strictly: {} then {v}",
                values[i - 1]
            ));
        }
    }
    Ok(())
}

impl MotionModel {
    /// Checks the axes, the ladder and that `scores` has one finite score per cell.
    pub fn validate(&self) -> Result<(), String> {
        check_axis("speeds_deg_s", &self.speeds_deg_s, 0.0, false)?;
        check_axis("frame_times_ms", &self.frame_times_ms, 0.0, true)?;
        self.ladder.validate().map_err(|e| format!("ladder: {e}"))?;
        if !(self.refresh_hz.is_finite() && self.refresh_hz > 0.0) {
            return Err(format!("refresh_hz = {} must be above 0", self.refresh_hz));
        }
        let (s, f, p) = (
            self.speeds_deg_s.len(),
            self.frame_times_ms.len(),
            self.ladder.points.len(),
        );
        let shape_ok = self.scores.len() == s
            && self
                .scores
                .iter()
                .all(|row| row.len() == f && row.iter().all(|cells| cells.len() == p));
        if !shape_ok {
            return Err(format!(
                "scores must be {s} speeds x {f} frame times x {p} ladder points"
            ));
        }
        for (i, row) in self.scores.iter().enumerate() {
            for (j, cells) in row.iter().enumerate() {
                if let Some(k) = cells.iter().position(|v| !v.is_finite()) {
                    return Err(format!("scores[{i}][{j}][{k}] is not a finite number"));
                }
            }
        }
        Ok(())
    }

    /// Parses and checks a model from JSON.
    pub fn from_json(text: &str) -> Result<Self, String> {
        let model: MotionModel = serde_json::from_str(text).map_err(|e| e.to_string())?;
        model.validate()?;
        Ok(model)
    }

    /// The model that ships with the crate (`models/default-motion.json`): what
    /// `perceptual` uses when given no `model` (see the module documentation).
    pub fn shipped() -> Result<Self, String> {
        Self::from_json(SHIPPED_MODEL_JSON).map_err(|e| format!("the shipped default model: {e}"))
    }

    /// The mean of `models`, cell by cell: models of the same ladder, grids, metric, display
    /// and stimuli measured on different scenes (or views) become one that holds across
    /// them. Its `scene` lists theirs, joined by `+`. Refused, saying what differs, when
    /// they do not share all of these, or when there is no model.
    pub fn mean(models: &[MotionModel]) -> Result<Self, String> {
        let (first, rest) = models.split_first().ok_or("no model to take the mean of")?;
        first
            .validate()
            .map_err(|e| format!("model 0 ({}): {e}", first.scene))?;
        for (i, m) in rest.iter().enumerate() {
            let why = |e: String| format!("model {} ({}): {e}", i + 1, m.scene);
            m.validate().map_err(why)?;
            first.same_grids(m).map_err(why)?;
        }
        let n = models.len() as f64;
        let mut mean = first.clone();
        for (i, row) in mean.scores.iter_mut().enumerate() {
            for (j, cells) in row.iter_mut().enumerate() {
                for (k, cell) in cells.iter_mut().enumerate() {
                    *cell = models.iter().map(|m| m.scores[i][j][k]).sum::<f64>() / n;
                }
            }
        }
        let scenes: Vec<&str> = models.iter().map(|m| m.scene.as_str()).collect();
        mean.scene = scenes.join("+");
        Ok(mean)
    }

    /// Whether `other` scores the same cells as this model: the same metric, ladder points
    /// (their settings), speeds, frame times, display, image size, stimulus length and
    /// warping; else what differs.
    fn same_grids(&self, other: &MotionModel) -> Result<(), String> {
        let differs = |what: &str, a: String, b: String| {
            Err(format!("its {what} ({b}) differs from model 0's ({a})"))
        };
        if self.metric != other.metric {
            return differs("metric", self.metric.to_string(), other.metric.to_string());
        }
        if self.ladder.qualities() != other.ladder.qualities() {
            let show = |m: &MotionModel| {
                let q: Vec<String> = m.ladder.qualities().iter().map(|q| q.to_string()).collect();
                q.join(", ")
            };
            return differs("ladder points", show(self), show(other));
        }
        let grids = [
            ("speeds", &self.speeds_deg_s, &other.speeds_deg_s),
            ("frame times", &self.frame_times_ms, &other.frame_times_ms),
        ];
        for (what, a, b) in grids {
            if a != b {
                return differs(what, format!("{a:?}"), format!("{b:?}"));
            }
        }
        let settings = [
            ("refresh rate", self.refresh_hz, other.refresh_hz),
            ("stimulus length", self.stimulus_s, other.stimulus_s),
        ];
        for (what, a, b) in settings {
            if a != b {
                return differs(what, a.to_string(), b.to_string());
            }
        }
        if self.resolution != other.resolution {
            return differs(
                "resolution",
                format!("{:?}", self.resolution),
                format!("{:?}", other.resolution),
            );
        }
        if self.warped != other.warped {
            return differs("warping", self.warped.to_string(), other.warped.to_string());
        }
        Ok(())
    }

    /// The model without the ladder points that it scores no better than a cheaper point
    /// in every cell (at each speed and frame time): such a point costs more rays for a
    /// picture the viewer is not shown to prefer anywhere, yet `perceptual`'s inner
    /// controller would climb to it (and through the positions between it and its
    /// neighbours) whenever it fits. A ladder point ahead of cheaper ones on a still
    /// picture (its calibrated FLIP) can lose to them once the stimuli move: the shipped
    /// model's second point, S = 1.5 at half scale, scores worse than S = 1 at half scale in
    /// every cell. The cheapest point is always kept.
    pub fn without_dominated_points(mut self) -> Self {
        let sign = self.metric.sign();
        let no_better = |k: usize, c: usize| {
            self.scores
                .iter()
                .flatten()
                .all(|points| sign * points[k] <= sign * points[c])
        };
        let mut kept: Vec<usize> = Vec::new();
        for k in 0..self.ladder.points.len() {
            if !kept.iter().any(|&c| no_better(k, c)) {
                kept.push(k);
            }
        }
        self.ladder.points = kept.iter().map(|&k| self.ladder.points[k]).collect();
        for points in self.scores.iter_mut().flatten() {
            *points = kept.iter().map(|&k| points[k]).collect();
        }
        self
    }

    /// The score at grid speed `i`, frame time `j` and ladder position `u` (linear between
    /// points, clamped to the ladder).
    fn at_position(&self, i: usize, j: usize, u: f64) -> f64 {
        let cells = &self.scores[i][j];
        let last = cells.len() - 1;
        let u = u.clamp(0.0, last as f64);
        let k = (u.floor() as usize).min(last);
        let t = u - k as f64;
        cells[k] + t * (cells[(k + 1).min(last)] - cells[k])
    }

    /// The predicted score of frames shown for `frame_times_ms[j]` at ladder position `u`
    /// (point k at u = k) when the picture moves at `speed_deg_s`: linear in speed between
    /// the grid's speeds, the end values beyond them.
    pub fn score(&self, speed_deg_s: f64, j: usize, u: f64) -> f64 {
        let speeds = &self.speeds_deg_s;
        let i = speeds.partition_point(|&s| s <= speed_deg_s);
        if i == 0 {
            return self.at_position(0, j, u);
        }
        if i == speeds.len() {
            return self.at_position(i - 1, j, u);
        }
        let t = (speed_deg_s - speeds[i - 1]) / (speeds[i] - speeds[i - 1]);
        let (a, b) = (self.at_position(i - 1, j, u), self.at_position(i, j, u));
        a + t * (b - a)
    }

    /// The score as a utility: higher is better whatever the metric.
    pub fn utility(&self, speed_deg_s: f64, j: usize, u: f64) -> f64 {
        self.metric.sign() * self.score(speed_deg_s, j, u)
    }

    /// The utility of frames shown for `frame_times_ms[j]` at `speed_deg_s` at a setting
    /// below the ladder's cheapest point that traces `cost_ratio` (in (0, 1]) of its rays
    /// (the cheapest point at lower resolution), which no stimulus showed: point 0's utility
    /// less the ladder's mean gain per e-fold of rays (from its cheapest to its top point, by
    /// their calibrated rays; none when the row does not rise) for each e-fold saved. So a
    /// quarter of the pixels costs what the ladder gains over a fourfold rise in rays, and
    /// such a setting is never taken for better than the cheapest point measured.
    pub fn utility_below(&self, speed_deg_s: f64, j: usize, cost_ratio: f64) -> f64 {
        let at = |u: f64| self.utility(speed_deg_s, j, u);
        let points = &self.ladder.points;
        let top = points.len() - 1;
        let span = (points[top].rays / points[0].rays).ln();
        let gain = if span > 0.0 && span.is_finite() {
            ((at(top as f64) - at(0.0)) / span).max(0.0)
        } else {
            0.0
        };
        let saved = -cost_ratio.clamp(f64::MIN_POSITIVE, 1.0).ln();
        at(0.0) - gain * saved
    }

    /// The spread of the scores over the whole table (highest minus lowest): the scale
    /// against which the `perceptual` controller's hysteresis margin is set.
    pub fn spread(&self) -> f64 {
        let all = self.scores.iter().flatten().flatten().copied();
        let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        (hi - lo).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ladder::{LadderPoint, Reference};

    pub(crate) fn model() -> MotionModel {
        let point = |spp: f32, rays: f64, flip: f64| LadderPoint {
            spp,
            depth: 4,
            scale: 1.0,
            rays,
            ms: rays / 1e6,
            flip,
        };
        MotionModel {
            metric: Metric::Jod,
            scene: "test".into(),
            resolution: [64, 36],
            refresh_hz: 60.0,
            stimulus_s: 1.0,
            warped: false,
            viewing: serde_json::Value::Null,
            ladder: Ladder {
                scene: "test".into(),
                resolution: [64, 36],
                reference: Reference {
                    spp: 16.0,
                    depth: 4,
                    scale: 1.0,
                },
                views: 1,
                temporal_frames: None,
                points: vec![point(1.0, 1e6, 0.2), point(4.0, 4e6, 0.1)],
            },
            speeds_deg_s: vec![0.0, 20.0],
            frame_times_ms: vec![16.0, 32.0],
            scores: vec![
                vec![vec![6.0, 8.0], vec![6.0, 8.0]],
                vec![vec![5.0, 7.0], vec![3.0, 5.0]],
            ],
        }
    }

    #[test]
    fn interpolates_in_speed_and_ladder_position() {
        let m = model();
        m.validate().unwrap();
        assert_eq!(m.score(0.0, 0, 0.0), 6.0);
        assert_eq!(m.score(0.0, 0, 0.5), 7.0);
        assert_eq!(m.score(10.0, 1, 1.0), 6.5);
        assert_eq!(
            m.score(-5.0, 1, 0.0),
            6.0,
            "below the grid: the first speed"
        );
        assert_eq!(
            m.score(100.0, 1, 9.0),
            5.0,
            "beyond the grid and the ladder"
        );
        assert_eq!(m.spread(), 5.0);
        let flip = MotionModel {
            metric: Metric::DisplayedFlip,
            ..m
        };
        assert_eq!(flip.utility(0.0, 0, 0.0), -6.0);
    }

    #[test]
    fn below_the_cheapest_point_the_utility_falls_by_the_gain_per_e_fold_of_rays() {
        let m = model();
        // JOD rising 2 over the ladder's fourfold rays: half the rays cost 1, a quarter 2.
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        assert!(close(m.utility_below(0.0, 0, 1.0), 6.0));
        assert!(close(m.utility_below(0.0, 0, 0.5), 5.0));
        assert!(close(m.utility_below(0.0, 0, 0.25), 4.0));
        assert!(
            close(m.utility_below(10.0, 1, 0.25), 2.5),
            "at speed 10 the row runs 4.5 to 6.5"
        );
        // Displayed FLIP (lower is better) falling 0.02 over the ladder: a quarter of the
        // rays scores 0.02 worse than the cheapest point.
        let flip = MotionModel {
            metric: Metric::DisplayedFlip,
            scores: vec![vec![vec![0.06, 0.04]; 2]; 2],
            ..m.clone()
        };
        assert!(close(flip.utility_below(0.0, 0, 0.25), -0.08));
        // A row that does not rise (calibration noise) gives point 0's utility, never a
        // better one; the ladder's own positions below 0 are held at point 0.
        let flat = MotionModel {
            scores: vec![vec![vec![6.0, 5.5]; 2]; 2],
            ..m
        };
        assert!(close(flat.utility_below(0.0, 0, 0.25), 6.0));
        assert_eq!(flat.score(0.0, 0, -1.0), 6.0);
    }

    #[test]
    fn json_round_trips_and_bad_tables_are_named() {
        let m = model();
        let text = serde_json::to_string(&m).unwrap();
        assert_eq!(MotionModel::from_json(&text).unwrap(), m);
        let mut bad = m.clone();
        bad.scores[1][0].pop();
        assert!(
            bad.validate()
                .unwrap_err()
                .contains("2 speeds x 2 frame times")
        );
        let mut bad = m.clone();
        bad.scores[0][1][1] = f64::NAN;
        assert!(bad.validate().unwrap_err().contains("scores[0][1][1]"));
        let mut bad = m.clone();
        bad.frame_times_ms = vec![32.0, 16.0];
        assert!(bad.validate().unwrap_err().contains("rise strictly"));
        let mut bad = m.clone();
        bad.frame_times_ms[0] = 0.0;
        assert!(bad.validate().unwrap_err().contains("above 0"));
        let mut bad = m;
        bad.speeds_deg_s[0] = f64::NAN;
        assert!(bad.validate().unwrap_err().contains("speeds_deg_s[0]"));
        assert!(MotionModel::from_json(r#"{"metric": "psnr"}"#).is_err());
    }

    #[test]
    fn the_mean_averages_cells_and_refuses_models_of_other_grids() {
        let a = model();
        let mut b = model();
        b.scene = "other".into();
        b.scores[1][1] = vec![5.0, 7.0];
        let mean = MotionModel::mean(&[a.clone(), b.clone()]).unwrap();
        assert_eq!(mean.scene, "test+other");
        assert_eq!(mean.scores[1][1], vec![4.0, 6.0]);
        assert_eq!(mean.scores[0], a.scores[0]);
        assert_eq!(MotionModel::mean(std::slice::from_ref(&a)).unwrap(), a);
        assert!(MotionModel::mean(&[]).unwrap_err().contains("no model"));
        let refused = |other: MotionModel, what: &str| {
            let err = MotionModel::mean(&[a.clone(), other]).unwrap_err();
            assert!(err.contains(what) && err.contains("model 1"), "{err}");
        };
        let mut speeds = b.clone();
        speeds.speeds_deg_s = vec![0.0, 30.0];
        refused(speeds, "speeds");
        let mut times = b.clone();
        times.frame_times_ms = vec![16.0, 48.0];
        refused(times, "frame times");
        let mut ladder = b.clone();
        ladder.ladder.points[1].spp = 2.0;
        refused(ladder, "ladder points");
        let mut metric = b.clone();
        metric.metric = Metric::DisplayedFlip;
        refused(metric, "metric");
        let mut refresh = b.clone();
        refresh.refresh_hz = 120.0;
        refused(refresh, "refresh rate");
        let mut warped = b.clone();
        warped.warped = true;
        refused(warped, "warping");
        let mut bad = b;
        bad.scores[0][0].pop();
        refused(bad, "scores must be");
    }

    #[test]
    fn points_scored_no_better_than_a_cheaper_one_everywhere_are_dropped() {
        let mut m = model();
        let mut middle = m.ladder.points[0];
        middle.spp = 2.0;
        middle.rays = 2e6;
        middle.flip = 0.15;
        m.ladder.points.insert(1, middle);
        // JOD (higher is better): the middle point is never above the cheapest (ties
        // count as no better); the top point is above it in every cell.
        m.scores = vec![
            vec![vec![6.0, 6.0, 8.0], vec![6.0, 5.5, 8.0]],
            vec![vec![5.0, 4.0, 7.0], vec![3.0, 3.0, 5.0]],
        ];
        m.validate().unwrap();
        let pruned = m.clone().without_dominated_points();
        pruned.validate().unwrap();
        let spp: Vec<f32> = pruned.ladder.points.iter().map(|p| p.spp).collect();
        assert_eq!(spp, [1.0, 4.0]);
        assert_eq!(pruned.scores, model().scores);
        // Better than the cheapest in one cell is enough to stay.
        m.scores[1][1][1] = 3.5;
        assert_eq!(m.without_dominated_points().ladder.points.len(), 3);
    }

    #[test]
    fn the_shipped_models_second_point_is_dominated_once_the_stimuli_move() {
        let shipped = MotionModel::shipped().unwrap();
        let pruned = shipped.clone().without_dominated_points();
        let mut expected = shipped.ladder.points.clone();
        expected.remove(1);
        assert_eq!(pruned.ladder.points, expected);
    }

    #[test]
    fn the_shipped_model_is_valid() {
        let shipped = MotionModel::shipped().unwrap();
        assert!(shipped.frame_times_ms.len() >= 2 && shipped.speeds_deg_s.len() >= 2);
        assert!(shipped.spread() > 0.0);
    }
}
