//! What a controller decided after a frame, and why: what an engine shows in its HUD or log.

use crate::quality::{Knob, Quality};
use serde::Serialize;
use std::fmt;

/// What happened to the quality.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Action {
    /// The quality stays.
    Hold,
    /// The quality goes down: the next frame is to be cheaper.
    Cut,
    /// The quality goes up: there is time to spend.
    Raise,
    /// The quality changes at about the same cost (one knob traded for another).
    Trade,
}

/// Why the controller did what it did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reason {
    /// No prediction yet: the cost model has not seen enough frames.
    Learning,
    /// The frame was set aside as a hitch or as the first frame of a change the band
    /// tolerates; the quality waits for the next frame's word.
    SetAside,
    /// The next frame's predicted time lies inside the inner band.
    InInnerBand,
    /// Several frames in a row measured above the inner band: a drift the cost model lags.
    Drift,
    /// The predicted time lies above the inner band.
    OverInnerBand,
    /// The predicted time lies under the inner band: there is time to spend.
    UnderInnerBand,
    /// The band changed (e.g. `perceptual` chose another frame time).
    NewBand,
    /// The predicted time moved past the target the way the quality last moved (a view
    /// growing or shrinking in cost): the quality moves on the same way.
    Follow,
}

impl Action {
    /// Its name in logs and files (as serialized): `hold`, `cut`, `raise`, `trade`.
    pub fn name(self) -> &'static str {
        match self {
            Action::Hold => "hold",
            Action::Cut => "cut",
            Action::Raise => "raise",
            Action::Trade => "trade",
        }
    }
}

impl Reason {
    /// Its name in logs and files (as serialized), e.g. `in_inner_band`.
    pub fn name(self) -> &'static str {
        match self {
            Reason::Learning => "learning",
            Reason::SetAside => "set_aside",
            Reason::InInnerBand => "in_inner_band",
            Reason::Drift => "drift",
            Reason::OverInnerBand => "over_inner_band",
            Reason::UnderInnerBand => "under_inner_band",
            Reason::NewBand => "new_band",
            Reason::Follow => "follow",
        }
    }

    /// A few words for a HUD or a log.
    pub fn describe(self) -> &'static str {
        match self {
            Reason::Learning => "learning the cost model",
            Reason::SetAside => "frame set aside (a spike, or the first of a change)",
            Reason::InInnerBand => "prediction inside the inner band",
            Reason::Drift => "frames in a row above the inner band",
            Reason::OverInnerBand => "prediction above the inner band",
            Reason::UnderInnerBand => "prediction under the inner band",
            Reason::NewBand => "new band",
            Reason::Follow => "following the view's cost the way it last moved",
        }
    }
}

/// One frame's decision.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Decision {
    /// What happened to the quality.
    pub action: Action,
    /// Why.
    pub reason: Reason,
    /// The frame time just measured, ms (None for a decision no frame prompted, such as a
    /// new band).
    pub measured_ms: Option<f64>,
    /// The next frame's predicted time at the chosen quality, ms (None before the cost
    /// model predicts).
    pub predicted_ms: Option<f64>,
    /// The time aimed at, ms.
    pub target_ms: f64,
    /// The inner band: the quality is kept while its predicted time lies in it, ms (for
    /// `predictive` following a view's cost, narrowed on the side it follows).
    pub inner_ms: [f64; 2],
    /// The band, ms.
    pub band_ms: [f64; 2],
    /// The quality the frame was rendered with.
    pub from: Quality,
    /// The quality chosen for the next frame.
    pub to: Quality,
}

impl Decision {
    /// The knobs that moved, in the order S, R, scale.
    pub fn knobs_moved(&self) -> Vec<Knob> {
        let (a, b) = (&self.from, &self.to);
        [
            (Knob::Spp, a.spp != b.spp),
            (Knob::Depth, a.depth != b.depth),
            (Knob::Scale, a.scale != b.scale),
        ]
        .into_iter()
        .filter_map(|(k, moved)| moved.then_some(k))
        .collect()
    }
}

impl fmt::Display for Decision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.action.name())?;
        let moved: Vec<&str> = self.knobs_moved().iter().map(|k| k.name()).collect();
        if !moved.is_empty() {
            write!(f, " {}", moved.join("+"))?;
        }
        write!(f, " ({})", self.reason.describe())?;
        if let Some(t) = self.measured_ms {
            write!(f, ": measured {t:.2} ms")?;
        }
        if let Some(t) = self.predicted_ms {
            write!(f, ", next predicted {t:.2} ms")?;
        }
        write!(
            f,
            ", aiming at {:.2} ms in [{:.2}, {:.2}]",
            self.target_ms, self.inner_ms[0], self.inner_ms[1]
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names written to files are the serialized names, so a reader of `frames.csv` and
    /// of a JSON log sees one vocabulary.
    #[test]
    fn names_are_the_serialized_names() {
        for a in [Action::Hold, Action::Cut, Action::Raise, Action::Trade] {
            assert_eq!(
                serde_json::to_string(&a).unwrap(),
                format!("\"{}\"", a.name())
            );
        }
        for r in [
            Reason::Learning,
            Reason::SetAside,
            Reason::InInnerBand,
            Reason::Drift,
            Reason::OverInnerBand,
            Reason::UnderInnerBand,
            Reason::NewBand,
            Reason::Follow,
        ] {
            assert_eq!(
                serde_json::to_string(&r).unwrap(),
                format!("\"{}\"", r.name())
            );
        }
    }
}
