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
    BadBandLimit {
        /// Which limit: `Tmin` or `Tmax`.
        name: &'static str,
        /// The value given, ms.
        value: f64,
    },
    /// Tmin is not below Tmax.
    #[error("band [{tmin_ms}, {tmax_ms}] ms is empty: Tmin must be below Tmax")]
    EmptyBand {
        /// The lower limit given, ms.
        tmin_ms: f64,
        /// The upper limit given, ms.
        tmax_ms: f64,
    },
    /// A quality knob's range has min > max, or is NaN, or leaves the knob's legal values.
    #[error("bounds for {knob} are invalid: [{min}, {max}] ({why})")]
    BadBounds {
        /// The knob's name (`spp`, `depth` or `scale`).
        knob: &'static str,
        /// The lower end given.
        min: f64,
        /// The upper end given.
        max: f64,
        /// What is wrong with the range.
        why: &'static str,
    },
    /// A ladder over a knob has no rung (e.g. S in [1.2, 1.8] holds no whole number).
    #[error("the ladder over {knob} is empty: no whole value lies in [{min}, {max}]")]
    EmptyLadder {
        /// The knob's name (`spp`, `depth` or `scale`).
        knob: &'static str,
        /// The lower end of the knob's range.
        min: f64,
        /// The upper end of the knob's range.
        max: f64,
    },
    /// The starting quality lies outside the bounds.
    #[error("start quality {quality} lies outside the bounds {bounds}")]
    StartOutOfBounds {
        /// The starting quality, as displayed.
        quality: String,
        /// The bounds, as displayed.
        bounds: String,
    },
    /// No controller has this name.
    #[error(
        "unknown controller `{0}`: expected one of fixed, step, hysteresis, predictive, perceptual"
    )]
    UnknownController(String),
    /// The controller has no option with this name.
    #[error("controller `{controller}` has no option `{key}`: it takes {expected}")]
    UnknownOption {
        /// The controller's name.
        controller: &'static str,
        /// The option given.
        key: String,
        /// The options it takes, for the message.
        expected: String,
    },
    /// An option's value could not be parsed or is out of range.
    #[error("option `{key}` = `{value}` is invalid: {why}")]
    BadOption {
        /// The option's name.
        key: String,
        /// The value given.
        value: String,
        /// Why it was refused.
        why: String,
    },
}

/// Any error of this crate, for a caller that wants one type to `?` into: each function
/// returns the precise error of its kind ([`ConfigError`] when building,
/// [`crate::ReportError`] when a report is refused, [`crate::SpecError`] when a list of
/// controllers cannot be read, [`crate::noise::NoiseError`] for a noise profile), and each
/// converts into this one.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A configuration mistake.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// A refused report.
    #[error(transparent)]
    Report(#[from] crate::report::ReportError),
    /// A list of controllers that cannot be read.
    #[error(transparent)]
    Spec(#[from] crate::spec::SpecError),
    /// A noise profile that cannot be read or is invalid.
    #[error(transparent)]
    Noise(#[from] crate::noise::NoiseError),
}
