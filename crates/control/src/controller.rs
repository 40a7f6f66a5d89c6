//! The controller interface and the constructor that builds one by name.

use crate::band::Band;
use crate::budget::FrameBudget;
use crate::decision::Decision;
use crate::error::ConfigError;
use crate::fixed::Fixed;
use crate::hysteresis::{Hysteresis, HysteresisParams};
use crate::ladder::Ladder;
use crate::motion_model::MotionModel;
use crate::perceptual::{Perceptual, PerceptualParams};
use crate::predictive::{Predictive, PredictiveParams};
use crate::quality::{Bounds, Quality};
use crate::report::{FrameReport, ReportError};
use crate::step::{Step, StepParams};
use std::fmt;
use std::str::FromStr;
use std::time::Duration;

/// A frame-time controller: it sees each frame's report and decides the next frame's quality.
///
/// The loop: `q = c.quality()`, render with `q`, then `c.observe(&report)` (which returns the
/// next quality, the same value `c.quality()` gives afterwards).
pub trait Controller: Send + fmt::Debug {
    /// The controller's name: one of [`CONTROLLER_NAMES`].
    fn name(&self) -> &'static str;

    /// The quality to render the next frame with. Always inside the controller's bounds.
    fn quality(&self) -> Quality;

    /// Takes the report of the frame just rendered and returns the next frame's quality.
    ///
    /// A report with a NaN, infinite, zero, negative or absurd (> [`crate::MAX_FRAME_MS`]) Tp
    /// is refused with an error and changes nothing: quality, history and model stay as they
    /// were, so the run continues exactly as if the frame had not been reported.
    fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError>;

    /// The simple case in one call, for an engine that knows only how long its frame took
    /// and how many pixels it shaded: the frame just rendered at [`Controller::quality`]
    /// took `frame_time` and shaded `pixels` pixels (after the render scale), each with the
    /// quality's samples and no bounces ([`FrameReport::from_pixels`]). Returns the next
    /// quality, as [`Controller::observe`] does.
    fn frame_done(&mut self, frame_time: Duration, pixels: u64) -> Result<Quality, ReportError> {
        let report = FrameReport::from_pixels(frame_time, pixels, self.quality());
        self.observe(&report)
    }

    /// What the last frame's report made the controller decide, and why (the predicted time,
    /// the band aimed at, the knobs moved): for an engine's HUD or log. `None` before the
    /// first frame, and for controllers that explain nothing (`fixed`, `step`, `hysteresis`).
    fn decision(&self) -> Option<&Decision> {
        None
    }

    /// Back to the starting quality with an empty history (e.g. between benchmark runs).
    fn reset(&mut self);

    /// Holds `band` from the next frame on, keeping what the controller has learned (a live
    /// view's band, measured from its display or edited, should not cost the cost model it
    /// fitted); the next quality is the one in use, or (`predictive`) already planned for
    /// the new band from the last frame's measurements. A controller that derives its bands
    /// from elsewhere (`perceptual`: its model's frame times) keeps its own.
    fn set_band(&mut self, band: Band);

    /// Takes costs measured around each frame on its display, for a controller whose bands
    /// leave room for them (`perceptual`: its options `hand_over` and `warp`), keeping what
    /// it has learned; `None` keeps the cost it has. The others have no use for them. On an
    /// error (costs that leave a frame time no band) nothing changes.
    fn set_display_costs(&mut self, _costs: DisplayCosts) -> Result<(), ConfigError> {
        Ok(())
    }

    /// The frame time the controller has chosen to deliver, ms, for a controller that
    /// chooses the frame rate itself (`perceptual`); `None` for one that holds the band it
    /// was given.
    fn target_frame_ms(&self) -> Option<f64> {
        None
    }

    /// The time budget the next frame should be rendered within, for a renderer that takes
    /// its eye samples a unit at a time ([`FrameBudget`]); `None` (every controller unless
    /// asked: `predictive`'s and `perceptual`'s option `budget`) renders the planned
    /// quality whole.
    fn frame_budget(&self) -> Option<FrameBudget> {
        None
    }
}

/// Costs around a frame on its display, as a live view measures them (`None`: not told).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DisplayCosts {
    /// Handing a finished frame to the display, ms.
    pub hand_over_ms: Option<f64>,
    /// A warped refresh between two frames, ms.
    pub warp_ms: Option<f64>,
}

/// What every controller needs: the band, the knobs' bounds and the starting quality.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setup {
    /// The frame-time band the controller keeps Tp in.
    pub band: Band,
    /// The range each knob may take; the controller never leaves it.
    pub bounds: Bounds,
    /// The quality of the first frame, inside `bounds`.
    pub start: Quality,
}

impl Setup {
    /// A checked setup: valid bounds and a start inside them.
    pub fn new(band: Band, bounds: Bounds, start: Quality) -> Result<Self, ConfigError> {
        let setup = Self {
            band,
            bounds,
            start,
        };
        setup.validate()?;
        Ok(setup)
    }

    /// Checks the bounds and that the start lies inside them.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.bounds.validate()?;
        if !self.bounds.contains(&self.start) {
            return Err(ConfigError::StartOutOfBounds {
                quality: self.start.to_string(),
                bounds: self.bounds.to_string(),
            });
        }
        Ok(())
    }
}

/// The names [`from_name`] accepts.
pub const CONTROLLER_NAMES: [&str; 5] = ["fixed", "step", "hysteresis", "predictive", "perceptual"];

/// Where the options that name a file (`predictive`'s `ladder=PATH`, `perceptual`'s
/// `model=PATH`) get its text. The library reads no files itself: the caller says how (the
/// steadyray binary reads them from disk; an engine may ship them in its assets).
pub trait OptionFiles {
    /// The text of the file `path` names, or why it cannot be had.
    fn read(&self, path: &str) -> Result<String, String>;
}

/// No files: an option that names one is refused, saying how to give it.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoFiles;

impl OptionFiles for NoFiles {
    fn read(&self, path: &str) -> Result<String, String> {
        Err(format!(
            "{path} is a file, and this controller was built without a way to read files: \
             build it with from_name_with and an OptionFiles (or pass the parsed ladder or \
             model in its parameters)"
        ))
    }
}

/// Builds a controller by name (`fixed`, `step`, `hysteresis`, `predictive`, `perceptual`) with options
/// written `key=value`, separated by spaces or `;` (e.g. `"knob=depth"`,
/// `"up_after=10; order=depth,spp"`). An empty string gives the defaults. Unknown names,
/// unknown keys, unparsable values and bad setups are errors that say what is accepted.
/// Options that name a file are refused: see [`from_name_with`].
pub fn from_name(
    name: &str,
    setup: Setup,
    options: &str,
) -> Result<Box<dyn Controller>, ConfigError> {
    from_name_with(name, setup, options, &NoFiles)
}

/// [`from_name`], with `files` giving the text of the files that options name (`ladder=`,
/// `model=`).
pub fn from_name_with(
    name: &str,
    setup: Setup,
    options: &str,
    files: &dyn OptionFiles,
) -> Result<Box<dyn Controller>, ConfigError> {
    let options = parse_options(options)?;
    let name = name.trim();
    Ok(match name {
        "fixed" => {
            let mut start = setup.start;
            for (key, value) in &options {
                match key.as_str() {
                    "spp" => start.spp = parse_option(key, value, |_| Ok(()))?,
                    "depth" => start.depth = parse_option(key, value, |_| Ok(()))?,
                    "scale" => start.scale = parse_option(key, value, |_| Ok(()))?,
                    _ => {
                        return Err(ConfigError::UnknownOption {
                            controller: "fixed",
                            key: key.clone(),
                            expected: crate::options::expected_keys("fixed"),
                        });
                    }
                }
            }
            Box::new(Fixed::new(Setup::new(setup.band, setup.bounds, start)?)?)
        }
        "step" => {
            let mut p = StepParams::default();
            for (k, v) in &options {
                p.set(k, v)?;
            }
            Box::new(Step::new(setup, p)?)
        }
        "hysteresis" => {
            let mut p = HysteresisParams::default();
            for (k, v) in &options {
                p.set(k, v)?;
            }
            Box::new(Hysteresis::new(setup, p)?)
        }
        "predictive" => {
            let mut p = PredictiveParams::default();
            for (k, v) in &options {
                match k.as_str() {
                    "ladder" => p.ladder = Some(read_option(k, v, files, Ladder::from_json)?),
                    _ => p.set(k, v)?,
                }
            }
            Box::new(Predictive::new(setup, p)?)
        }
        "perceptual" => {
            let mut p = PerceptualParams::default();
            for (k, v) in &options {
                match k.as_str() {
                    "model" => p.model = Some(read_option(k, v, files, MotionModel::from_json)?),
                    _ => p.set(k, v)?,
                }
            }
            Box::new(Perceptual::new(setup, p)?)
        }
        other => return Err(ConfigError::UnknownController(other.to_string())),
    })
}

/// Reads the file option `key`=`path` through `files` and parses it with `parse`; an error
/// names the option and the file.
fn read_option<T>(
    key: &str,
    path: &str,
    files: &dyn OptionFiles,
    parse: fn(&str) -> Result<T, String>,
) -> Result<T, ConfigError> {
    let bad = |why: String| ConfigError::BadOption {
        key: key.to_string(),
        value: path.to_string(),
        why,
    };
    let text = files.read(path.trim()).map_err(bad)?;
    parse(&text).map_err(|why| bad(format!("{}: {why}", path.trim())))
}

/// Splits `key=value` items separated by whitespace or `;`.
pub fn parse_options(text: &str) -> Result<Vec<(String, String)>, ConfigError> {
    text.split(|c: char| c == ';' || c.is_whitespace())
        .filter(|item| !item.is_empty())
        .map(|item| match item.split_once('=') {
            Some((k, v)) if !k.is_empty() => Ok((k.to_string(), v.to_string())),
            _ => Err(ConfigError::BadOption {
                key: item.to_string(),
                value: String::new(),
                why: "options are written key=value".into(),
            }),
        })
        .collect()
}

/// Parses one option value and checks it with `ok`, whose message says what is accepted.
pub(crate) fn parse_option<T: FromStr>(
    key: &str,
    value: &str,
    ok: impl Fn(&T) -> Result<(), String>,
) -> Result<T, ConfigError>
where
    T::Err: fmt::Display,
{
    let bad = |why: String| ConfigError::BadOption {
        key: key.to_string(),
        value: value.to_string(),
        why,
    };
    let parsed = value.trim().parse::<T>().map_err(|e| bad(e.to_string()))?;
    ok(&parsed).map_err(bad)?;
    Ok(parsed)
}

/// A range check for [`parse_option`]: `lo <= v <= hi`.
pub(crate) fn within<T: PartialOrd + fmt::Display + Copy>(
    lo: T,
    hi: T,
) -> impl Fn(&T) -> Result<(), String> {
    move |v| {
        if *v >= lo && *v <= hi {
            Ok(())
        } else {
            Err(format!("must lie in [{lo}, {hi}]"))
        }
    }
}

/// The check shared by all controllers' `observe`: refuses bad times before anything changes.
pub(crate) fn accept_time(report: &FrameReport) -> Result<f64, ReportError> {
    report.check_time().map(|()| report.tp_ms)
}
