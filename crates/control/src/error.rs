//! Why a controller, band or set of bounds cannot be built.
//!
//! Every error names the offending value and what would be accepted, so a command-line user
//! can fix the call without reading the code.

use thiserror::Error;

/// A configuration mistake: a bad band, empty bounds, an unknown controller or option.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ConfigError {
    /// Tmin or Tmax is NaN, infinite or not positive.
    #[error("band limit {name} = {value} ms is invalid: it must be a finite number above 0")]
    BadBandLimit { name: &'static str, value: f64 },
    /// Tmin is not below Tmax.
    #[error("band [{tmin_ms}, {tmax_ms}] ms is empty: Tmin must be below Tmax")]
    EmptyBand { tmin_ms: f64, tmax_ms: f64 },
    /// A quality knob's range has min > max, or is NaN, or leaves the knob's legal values.
    #[error("bounds for {knob} are invalid: [{min}, {max}] ({why})")]
    BadBounds {
        knob: &'static str,
        min: f64,
        max: f64,
        why: &'static str,
    },
    /// A ladder over a knob has no rung (e.g. S in [1.2, 1.8] holds no whole number).
    #[error("the ladder over {knob} is empty: no whole value lies in [{min}, {max}]")]
    EmptyLadder {
        knob: &'static str,
        min: f64,
        max: f64,
    },
    /// The starting quality lies outside the bounds.
    #[error("start quality {quality} lies outside the bounds {bounds}")]
    StartOutOfBounds { quality: String, bounds: String },
    /// No controller has this name.
    #[error(
        "unknown controller `{0}`: expected one of fixed, step, hysteresis, predictive, perceptual"
    )]
    UnknownController(String),
    /// The controller has no option with this name.
    #[error("controller `{controller}` has no option `{key}`: it takes {expected}")]
    UnknownOption {
        controller: &'static str,
        key: String,
        expected: String,
    },
    /// An option's value could not be parsed or is out of range.
    #[error("option `{key}` = `{value}` is invalid: {why}")]
    BadOption {
        key: String,
        value: String,
        why: String,
    },
}
