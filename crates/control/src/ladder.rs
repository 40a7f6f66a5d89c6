//! A calibrated quality ladder: the Pareto front of (S, R, scale) settings, cheapest first,
//! each one looking better (lower FLIP) than every cheaper one.
//!
//! `steadyray calibrate` measures it (rays, time and FLIP against a high-quality reference
//! over sampled views of the camera path) and writes it as `ladder.json`; `predictive` with
//! the option `ladder=PATH` moves along it instead of raising knobs in a fixed order. The
//! controller never trusts the calibrated cost: it predicts each point's time on the current
//! view from the measured rays (its ray and cost models), so a ladder calibrated on one
//! machine or at one view still works on another. The calibrated FLIP only orders the points.
//!
//! # `ladder.json`
//!
//! ```json
//! {
//!   "scene": "corridor",
//!   "resolution": [320, 180],
//!   "reference": { "spp": 256.0, "depth": 16, "scale": 1.0 },
//!   "views": 8,
//!   "temporal_frames": 8,
//!   "points": [
//!     { "spp": 1.0, "depth": 0, "scale": 0.5, "rays": 51000.0, "ms": 1.9, "flip": 0.31 },
//!     { "spp": 1.0, "depth": 2, "scale": 1.0, "rays": 260000.0, "ms": 7.5, "flip": 0.12 }
//!   ]
//! }
//! ```
//!
//! `points` is the front, in order of rising cost: `rays` (mean rays per frame over the
//! views, shadow rays included) strictly rises and `flip` (mean FLIP against the reference)
//! strictly falls. `ms` is the mean frame time measured while calibrating (information only).
//! The other fields say what the ladder was calibrated on; `temporal_frames` (optional) that
//! the FLIP is that of the temporal mode's history after so many frames leading up to each
//! view.

use crate::quality::Quality;
use serde::{Deserialize, Serialize};

/// The lowest position along a ladder (point k at position k): the ladder's cheapest point
/// at the controller's lowest resolution scale. Between it and position 0 (the cheapest
/// point itself) the scale falls linearly and S and R stay the cheapest point's, so a view
/// dearer than the calibration's still has a setting that fits the band: a ladder
/// calibrated on another scene or machine often starts too high for it.
pub const LADDER_FLOOR: f64 = -1.0;

/// One setting on the ladder, with what calibration measured for it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LadderPoint {
    /// Eye rays per pixel S.
    pub spp: f32,
    /// Reflection/refraction depth R.
    pub depth: u32,
    /// Resolution scale.
    pub scale: f32,
    /// Mean rays per frame over the calibration views.
    pub rays: f64,
    /// Mean frame time over the calibration views, ms.
    pub ms: f64,
    /// Mean FLIP against the reference over the calibration views.
    pub flip: f64,
}

impl LadderPoint {
    /// The point's quality.
    pub fn quality(&self) -> Quality {
        Quality::new(self.spp, self.depth, self.scale)
    }
}

/// The reference a ladder was calibrated against.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Reference {
    /// Eye rays per pixel of the reference.
    pub spp: f32,
    /// Reflection depth of the reference.
    pub depth: u32,
    /// Resolution scale of the reference, in (0, 1].
    pub scale: f32,
}

/// A calibrated ladder (see the module documentation for the file format).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ladder {
    /// The scene calibrated.
    pub scene: String,
    /// Full-scale image size calibrated at.
    pub resolution: [u32; 2],
    /// The reference quality FLIP was measured against.
    pub reference: Reference,
    /// Views of the camera path measured.
    pub views: u32,
    /// With the temporal mode: the frames accumulated before each view was measured (the
    /// points' FLIP is the history's; `calibrate --temporal`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temporal_frames: Option<u32>,
    /// The Pareto front, cheapest first.
    pub points: Vec<LadderPoint>,
}

impl Ladder {
    /// Checks the front: at least one point, valid knobs (S >= 1, 0 < scale <= 1), rays
    /// strictly rising and FLIP strictly falling.
    pub fn validate(&self) -> Result<(), String> {
        if self.points.is_empty() {
            return Err("the ladder has no points".into());
        }
        if self.resolution.contains(&0) {
            return Err(format!(
                "the ladder was measured at an empty image ({}x{})",
                self.resolution[0], self.resolution[1]
            ));
        }
        for (i, p) in self.points.iter().enumerate() {
            if !(p.spp >= 1.0 && p.spp.is_finite() && p.scale > 0.0 && p.scale <= 1.0) {
                return Err(format!(
                    "point {i} ({}) is not a valid quality (S >= 1, 0 < scale <= 1)",
                    p.quality()
                ));
            }
            if !(p.rays.is_finite() && p.flip.is_finite()) {
                return Err(format!("point {i} has a non-finite rays or flip"));
            }
            if i > 0 {
                let q = &self.points[i - 1];
                if !(p.rays > q.rays && p.flip < q.flip) {
                    return Err(format!(
                        "point {i} does not continue the front: rays must rise ({} -> {}) and \
                         flip fall ({} -> {})",
                        q.rays, p.rays, q.flip, p.flip
                    ));
                }
            }
        }
        Ok(())
    }

    /// Parses and checks a ladder from JSON.
    pub fn from_json(text: &str) -> Result<Self, String> {
        let ladder: Ladder = serde_json::from_str(text).map_err(|e| e.to_string())?;
        ladder.validate()?;
        Ok(ladder)
    }

    /// The qualities along the ladder, cheapest first.
    pub fn qualities(&self) -> Vec<Quality> {
        self.points.iter().map(LadderPoint::quality).collect()
    }
}

/// Settings that differ only in R and measure within this fraction of each other in both
/// rays and FLIP are a tie.
const DEPTH_TIE: f64 = 0.01;

/// The Pareto front of measured settings: sorted by rays (ties: lower FLIP first), keeping
/// each setting whose FLIP is below that of every cheaper one. Non-finite measurements are
/// dropped.
///
/// Among settings that differ only in R and tie on average (within 1 % in rays and FLIP),
/// only the deepest competes: the average over views dilutes the views dominated by mirrors,
/// which are where R shows and costs, so a shallower setting's edge of a few rays or a FLIP
/// ulp is noise, and taking it would give up reflections where they matter.
pub fn pareto_front(mut measured: Vec<LadderPoint>) -> Vec<LadderPoint> {
    measured.retain(|p| p.rays.is_finite() && p.flip.is_finite());
    let ties = |shallow: &LadderPoint, deep: &LadderPoint| {
        let near = |a: f64, b: f64| b <= a * (1.0 + DEPTH_TIE) && a <= b * (1.0 + DEPTH_TIE);
        deep.depth > shallow.depth
            && deep.spp == shallow.spp
            && deep.scale == shallow.scale
            && near(shallow.rays, deep.rays)
            && near(shallow.flip, deep.flip)
    };
    let all = measured.clone();
    measured.retain(|p| !all.iter().any(|q| ties(p, q)));
    measured.sort_by(|a, b| a.rays.total_cmp(&b.rays).then(a.flip.total_cmp(&b.flip)));
    let mut front: Vec<LadderPoint> = Vec::new();
    for p in measured {
        let better = front.last().is_none_or(|last| p.flip < last.flip);
        let dearer = front.last().is_none_or(|last| p.rays > last.rays);
        if better && dearer {
            front.push(p);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(spp: f32, depth: u32, rays: f64, flip: f64) -> LadderPoint {
        LadderPoint {
            spp,
            depth,
            scale: 1.0,
            rays,
            ms: rays / 1e6,
            flip,
        }
    }

    #[test]
    fn depths_that_tie_on_average_give_way_to_the_deepest() {
        let front = pareto_front(vec![
            pt(1.0, 6, 1000.0, 0.0500),
            pt(1.0, 16, 1002.0, 0.0501),
            pt(1.0, 12, 1001.0, 0.0502),
            pt(2.0, 4, 1500.0, 0.0300), // 20 % cheaper than R = 16: not a tie, kept
            pt(2.0, 16, 1800.0, 0.0290),
        ]);
        let kept: Vec<(f32, u32)> = front.iter().map(|p| (p.spp, p.depth)).collect();
        assert_eq!(kept, vec![(1.0, 16), (2.0, 4), (2.0, 16)]);
    }

    #[test]
    fn the_front_keeps_only_settings_better_than_all_cheaper_ones() {
        let front = pareto_front(vec![
            pt(4.0, 0, 400.0, 0.30), // dominated by (1, 2)
            pt(1.0, 0, 100.0, 0.40),
            pt(1.0, 2, 250.0, 0.20),
            pt(2.0, 2, 500.0, 0.15),
            pt(1.0, 1, 180.0, 0.40), // no better than the cheaper (1, 0)
            pt(8.0, 8, 900.0, f64::NAN),
        ]);
        let kept: Vec<(f32, u32)> = front.iter().map(|p| (p.spp, p.depth)).collect();
        assert_eq!(kept, [(1.0, 0), (1.0, 2), (2.0, 2)]);
        assert!(
            front
                .windows(2)
                .all(|w| w[1].rays > w[0].rays && w[1].flip < w[0].flip)
        );
    }

    #[test]
    fn json_round_trips_and_is_checked() {
        let ladder = Ladder {
            scene: "corridor".into(),
            resolution: [32, 18],
            reference: Reference {
                spp: 256.0,
                depth: 16,
                scale: 1.0,
            },
            views: 2,
            temporal_frames: None,
            points: vec![pt(1.0, 0, 100.0, 0.4), pt(1.0, 2, 250.0, 0.2)],
        };
        let text = serde_json::to_string(&ladder).unwrap();
        assert_eq!(Ladder::from_json(&text).unwrap(), ladder);
        let mut bad = ladder.clone();
        bad.points.reverse();
        assert!(bad.validate().unwrap_err().contains("front"));
        bad.points.clear();
        assert!(bad.validate().is_err());
        let mut empty = ladder.clone();
        empty.resolution = [0, 360];
        assert!(empty.validate().unwrap_err().contains("0x360"));
        assert!(Ladder::from_json("{").is_err());
    }
}
