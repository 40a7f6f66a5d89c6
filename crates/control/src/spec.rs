//! Controllers as a list names them (`fixed,step:knob=both,predictive:order=depth,spp`):
//! each a name and its options, parsed here and built by [`from_name_with`]. The bench runs one
//! controller per entry; the window builds its controller from one too.

use crate::controller::{
    CONTROLLER_NAMES, Controller, OptionFiles, Setup, from_name_with, parse_options,
};
use crate::error::ConfigError;
use thiserror::Error;

/// Why a list of controllers cannot be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SpecError {
    /// A piece of the list names no controller.
    #[error("unknown controller {0:?} in --controllers (expected one of: {names})", names = CONTROLLER_NAMES.join(", "))]
    UnknownController(String),
    /// The list is empty.
    #[error("--controllers names no controller")]
    NoController,
}

/// One controller to run, as named on the command line (the window builds its controllers
/// from one too).
#[derive(Clone, Debug, PartialEq)]
pub struct ControllerSpec {
    /// The controller's name: one of [`CONTROLLER_NAMES`].
    pub name: String,
    /// Its options, as [`from_name_with`] takes them.
    pub options: String,
}

impl ControllerSpec {
    /// Builds the controller, with `files` giving the text of the files its options name
    /// (see [`from_name_with`]).
    pub fn build(
        &self,
        setup: Setup,
        files: &dyn OptionFiles,
    ) -> Result<Box<dyn Controller>, ConfigError> {
        from_name_with(&self.name, setup, &self.options, files)
    }

    /// A `perceptual` controller not told its hand-over: under the real clock the bench
    /// measures it and passes it on, so that its bands are `--band refresh`'s.
    pub fn lacks_hand_over(&self) -> bool {
        self.lacks("hand_over")
    }

    /// A `perceptual` controller not told what a warped refresh costs: under `--warp` the
    /// bench measures it and passes it on, so that its bands leave room for the warps.
    pub fn lacks_warp(&self) -> bool {
        self.lacks("warp")
    }

    /// A `perceptual` controller whose options do not give `key`.
    pub fn lacks(&self, key: &str) -> bool {
        self.name == "perceptual"
            && !parse_options(&self.options).is_ok_and(|o| o.iter().any(|(k, _)| k == key))
    }

    /// Tells a `perceptual` controller a measured cost (`hand_over`, `warp`) its options do
    /// not give, as `key=ms`; whether it was told.
    pub fn tell_measured(&mut self, key: &str, ms: f64) -> bool {
        let lacks = self.lacks(key);
        if lacks {
            self.add_option(&format!("{key}={ms:.3}"));
        }
        lacks
    }

    /// Appends `key=value` to the options.
    pub fn add_option(&mut self, option: &str) {
        if !self.options.is_empty() {
            self.options.push(' ');
        }
        self.options.push_str(option);
    }

    /// The run's name in reports (not for `fixed`, named by its quality): the controller and
    /// its options; for `perceptual`, its `model` file by its stem and the measured
    /// `hand_over` and `warp` left out.
    pub fn label(&self) -> String {
        if self.name != "perceptual" {
            return match self.options.is_empty() {
                true => self.name.clone(),
                false => format!("{} {}", self.name, self.options.replace(',', "+")),
            };
        }
        let options: Vec<String> = parse_options(&self.options)
            .unwrap_or_default()
            .into_iter()
            .filter(|(k, _)| k != "hand_over" && k != "warp")
            .map(|(k, v)| match k.as_str() {
                "model" => {
                    let stem = std::path::Path::new(&v)
                        .file_stem()
                        .map_or_else(|| v.clone(), |s| s.to_string_lossy().into_owned());
                    format!("{k}={stem}")
                }
                _ => format!("{k}={v}"),
            })
            .collect();
        if options.is_empty() {
            self.name.clone()
        } else {
            format!("{} {}", self.name, options.join("+"))
        }
    }
}

/// Splits `--controllers`: commas separate controllers, except inside an option value
/// (a piece that does not start with a controller name belongs to the one before).
pub fn parse_controllers(text: &str) -> Result<Vec<ControllerSpec>, SpecError> {
    let mut specs: Vec<ControllerSpec> = Vec::new();
    for piece in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (name, options) = piece.split_once(':').unwrap_or((piece, ""));
        if CONTROLLER_NAMES.contains(&name.trim()) {
            specs.push(ControllerSpec {
                name: name.trim().to_string(),
                options: options.trim().to_string(),
            });
        } else if let Some(last) = specs.last_mut().filter(|s| !s.options.is_empty()) {
            last.options.push(',');
            last.options.push_str(piece);
        } else {
            return Err(SpecError::UnknownController(name.to_string()));
        }
    }
    if specs.is_empty() {
        return Err(SpecError::NoController);
    }
    Ok(specs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controller_lists_keep_commas_inside_options() {
        let specs = parse_controllers("fixed, step:knob=both,predictive:order=depth,spp").unwrap();
        let names: Vec<_> = specs.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["fixed", "step", "predictive"]);
        assert_eq!(specs[1].options, "knob=both");
        assert_eq!(specs[2].options, "order=depth,spp");
    }

    #[test]
    fn perceptual_runs_are_told_the_hand_over_and_named_by_their_model() {
        let mut specs =
            parse_controllers("predictive:order=depth,spp,perceptual:model=out/motion.json")
                .unwrap();
        assert!(!specs[0].lacks_hand_over());
        assert!(specs[1].lacks_hand_over());
        specs[1].add_option("hand_over=1.600");
        assert!(!specs[1].lacks_hand_over());
        assert!(!specs[0].lacks_warp() && specs[1].lacks_warp());
        specs[1].add_option("warp=6.500");
        assert!(!specs[1].lacks_warp());
        assert_eq!(
            specs[1].options,
            "model=out/motion.json hand_over=1.600 warp=6.500"
        );
        assert_eq!(specs[1].label(), "perceptual model=motion");
        assert_eq!(specs[0].label(), "predictive order=depth+spp");
    }

    #[test]
    fn unknown_or_empty_controller_lists_are_errors() {
        let err = parse_controllers("fixed,bogus").unwrap_err().to_string();
        assert!(err.contains("bogus") && err.contains("predictive"), "{err}");
        assert!(parse_controllers(" , ").is_err());
    }
}
