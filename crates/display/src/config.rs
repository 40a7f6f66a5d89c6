//! What the display is: its refresh rate and how a finished frame reaches the screen (vsync on
//! or off, or a variable refresh within a range).

use crate::error::DisplayError;
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

/// The highest refresh rate accepted, Hz (a bound on the timeline's size, not a display's).
pub const MAX_REFRESH_HZ: f64 = 1000.0;

/// A variable refresh rate's range (VRR: G-Sync, FreeSync, HDMI VRR).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct VrrRange {
    /// The slowest refresh: after `1000 / min_hz` ms without a new frame the panel shows the
    /// old one again.
    pub min_hz: f64,
    /// The fastest refresh: two refreshes are at least `1000 / max_hz` ms apart.
    pub max_hz: f64,
}

impl VrrRange {
    /// A checked range: 0 < `min_hz` < `max_hz` <= [`MAX_REFRESH_HZ`].
    pub fn new(min_hz: f64, max_hz: f64) -> Result<Self, DisplayError> {
        let ok = min_hz.is_finite()
            && max_hz.is_finite()
            && min_hz > 0.0
            && min_hz < max_hz
            && max_hz <= MAX_REFRESH_HZ;
        if ok {
            Ok(Self { min_hz, max_hz })
        } else {
            Err(DisplayError::BadVrr { min_hz, max_hz })
        }
    }

    /// The shortest interval between two refreshes, ms.
    pub fn min_interval_ms(&self) -> f64 {
        1000.0 / self.max_hz
    }

    /// The longest interval between two refreshes, ms.
    pub fn max_interval_ms(&self) -> f64 {
        1000.0 / self.min_hz
    }
}

impl FromStr for VrrRange {
    type Err = DisplayError;

    /// Reads `MIN-MAX` in Hz, e.g. `48-144`.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let syntax = || DisplayError::VrrSyntax(text.to_string());
        let (min, max) = text.split_once('-').ok_or_else(syntax)?;
        let min = min.trim().parse::<f64>().map_err(|_| syntax())?;
        let max = max.trim().parse::<f64>().map_err(|_| syntax())?;
        Self::new(min, max)
    }
}

impl fmt::Display for VrrRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}-{}", self.min_hz, self.max_hz)
    }
}

/// How a finished frame reaches the screen.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase", tag = "mode")]
pub enum SyncMode {
    /// Vsync on: a frame is shown at the first refresh at or after its completion (and after
    /// the refresh that showed the frame before it), whole, never in the middle of a scan.
    Vsync,
    /// Vsync off: a frame is shown at its completion, in the middle of the panel's scan. The
    /// tear line is not modelled: the screen at a refresh is the latest frame complete by then.
    Off,
    /// Variable refresh: the panel refreshes when a frame completes, no sooner than its
    /// shortest interval after its previous refresh; after its longest interval without a new
    /// frame it shows the old one again.
    Vrr(VrrRange),
}

/// A display: refresh rate and sync mode. The refresh rate is the fixed rate of the panel
/// with vsync on or off, and the rate at which the screen is sampled for videos and metrics
/// in every mode (with VRR, set it to the range's maximum to sample every refresh the panel
/// can make).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DisplayConfig {
    /// The refresh rate, Hz (with VRR, the range's maximum).
    pub refresh_hz: f64,
    /// Vsync on or off, or variable refresh.
    #[serde(flatten)]
    pub sync: SyncMode,
}

impl DisplayConfig {
    /// A checked display: 0 < `refresh_hz` <= [`MAX_REFRESH_HZ`].
    pub fn new(refresh_hz: f64, sync: SyncMode) -> Result<Self, DisplayError> {
        if !(refresh_hz.is_finite() && refresh_hz > 0.0 && refresh_hz <= MAX_REFRESH_HZ) {
            return Err(DisplayError::BadRefresh(refresh_hz));
        }
        Ok(Self { refresh_hz, sync })
    }

    /// The refresh period P, ms: refreshes (and screen samples) at i·P.
    pub fn period_ms(&self) -> f64 {
        1000.0 / self.refresh_hz
    }
}

impl fmt::Display for DisplayConfig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.sync {
            SyncMode::Vsync => write!(f, "{} Hz, vsync on", self.refresh_hz),
            SyncMode::Off => write!(f, "{} Hz, vsync off", self.refresh_hz),
            SyncMode::Vrr(range) => write!(
                f,
                "variable refresh {range} Hz, sampled at {} Hz",
                self.refresh_hz
            ),
        }
    }
}
