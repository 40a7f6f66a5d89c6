//! A machine's timing noise as a few numbers: what [`super::fit_profile`] estimates and
//! [`super::NoiseProcess`] replays.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Why a noise profile or the frames to fit one from are unusable.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum NoiseError {
    /// A parameter is NaN, infinite or outside its range.
    #[error("noise parameter {name} = {value} is invalid: it must be {expected}")]
    BadParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The accepted range, for the message.
        expected: &'static str,
    },
    /// Too few frames to estimate anything.
    #[error("{got} frames are too few to fit a noise profile: at least {needed} are needed")]
    TooFewFrames {
        /// Frames given.
        got: usize,
        /// The fewest frames a fit accepts.
        needed: usize,
    },
    /// A frame time is NaN, infinite, zero or negative.
    #[error("frame {index} has time {value} ms: frame times must be finite and above 0")]
    BadFrameTime {
        /// The frame's index in its run.
        index: usize,
        /// Its time, ms.
        value: f64,
    },
    /// The two runs of a spell fit do not hold the same frames.
    #[error("the two runs hold {first} and {second} frames: a spell fit needs the same frames")]
    RunsDiffer {
        /// Frames in the first run.
        first: usize,
        /// Frames in the second run.
        second: usize,
    },
}

/// The parameters of a machine's timing noise (see the module documentation of
/// [`crate::noise`]), with where they come from. Serialised as JSON in the repository's
/// recorded profiles (`crates/control/noise/*.json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NoiseProfile {
    /// The machine the profile was recorded on, e.g. "2-core AMD EPYC VM".
    pub machine: String,
    /// How it was recorded (command, quality, frames), for whoever records the next one.
    pub recorded: String,
    /// Standard deviation of ln(jitter factor), frame to frame: 0.04 is about 4 %.
    pub jitter_sigma: f64,
    /// Probability that a frame is a spike.
    pub spike_prob: f64,
    /// Mean of ln(spike factor): a spike multiplies the frame's time by about e^this.
    pub spike_log_mean: f64,
    /// Standard deviation of ln(spike factor).
    pub spike_log_sd: f64,
    /// Stationary standard deviation of ln(machine speed) over spells.
    pub spell_sigma: f64,
    /// Correlation time of the spells, ms: the speed's log keeps e^(−Δt/spell_ms) of its
    /// deviation over Δt.
    pub spell_ms: f64,
}

impl NoiseProfile {
    /// A profile without noise (every factor 1).
    pub fn quiet(machine: &str) -> Self {
        Self {
            machine: machine.to_string(),
            recorded: String::new(),
            jitter_sigma: 0.0,
            spike_prob: 0.0,
            spike_log_mean: 0.0,
            spike_log_sd: 0.0,
            spell_sigma: 0.0,
            spell_ms: 1000.0,
        }
    }

    /// Checks every parameter: spreads finite and in [0, 1], the spike probability in
    /// [0, 1], the spike's mean log factor in [0, 5] and the correlation time above 0.
    pub fn validate(&self) -> Result<(), NoiseError> {
        let check = |name: &'static str, value: f64, lo: f64, hi: f64, expected| {
            if value.is_finite() && (lo..=hi).contains(&value) {
                Ok(())
            } else {
                Err(NoiseError::BadParameter {
                    name,
                    value,
                    expected,
                })
            }
        };
        let spread = "finite and in [0, 1]";
        check("jitter_sigma", self.jitter_sigma, 0.0, 1.0, spread)?;
        check(
            "spike_prob",
            self.spike_prob,
            0.0,
            1.0,
            "a probability in [0, 1]",
        )?;
        check(
            "spike_log_mean",
            self.spike_log_mean,
            0.0,
            5.0,
            "finite and in [0, 5]",
        )?;
        check("spike_log_sd", self.spike_log_sd, 0.0, 1.0, spread)?;
        check("spell_sigma", self.spell_sigma, 0.0, 1.0, spread)?;
        if !(self.spell_ms.is_finite() && self.spell_ms > 0.0) {
            return Err(NoiseError::BadParameter {
                name: "spell_ms",
                value: self.spell_ms,
                expected: "a finite time above 0 ms",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_profile_round_trips_through_json_and_bad_values_are_named() {
        let mut p = NoiseProfile::quiet("test");
        p.jitter_sigma = 0.05;
        let text = serde_json::to_string(&p).unwrap();
        let back: NoiseProfile = serde_json::from_str(&text).unwrap();
        assert_eq!(back, p);
        assert!(back.validate().is_ok());
        p.spell_ms = 0.0;
        let err = p.validate().unwrap_err().to_string();
        assert!(err.contains("spell_ms"), "{err}");
        p.spell_ms = 10.0;
        p.spike_prob = f64::NAN;
        assert!(p.validate().unwrap_err().to_string().contains("spike_prob"));
    }
}
