//! `fixed`: no control, the paper's baseline.

use crate::band::Band;
use crate::controller::{Controller, Setup, accept_time};
use crate::error::ConfigError;
use crate::quality::Quality;
use crate::report::{FrameReport, ReportError};

/// Renders every frame at the starting quality; reports are only checked.
#[derive(Clone, Debug)]
pub struct Fixed {
    quality: Quality,
}

impl Fixed {
    /// A fixed controller at `setup.start`.
    pub fn new(setup: Setup) -> Result<Self, ConfigError> {
        setup.validate()?;
        Ok(Self {
            quality: setup.start,
        })
    }
}

impl Controller for Fixed {
    fn name(&self) -> &'static str {
        "fixed"
    }

    fn quality(&self) -> Quality {
        self.quality
    }

    fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError> {
        accept_time(report)?;
        Ok(self.quality)
    }

    /// A fixed quality holds no band.
    fn set_band(&mut self, _band: Band) {}

    fn reset(&mut self) {}
}
