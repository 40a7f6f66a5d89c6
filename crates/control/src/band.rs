//! The reference band [Tmin, Tmax] a controller keeps the frame time in.

use crate::error::ConfigError;
use serde::{Deserialize, Serialize};
use std::fmt;

/// The band of acceptable frame times, in milliseconds (the paper: [15, 20]).
///
/// Always valid: both limits finite and positive, Tmin < Tmax (checked by [`Band::new`] and on
/// deserialization).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawBand")]
pub struct Band {
    tmin_ms: f64,
    tmax_ms: f64,
}

/// Where a frame time lies relative to the band.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Position {
    /// Tp < Tmin: time to spare.
    Under,
    /// Tmin <= Tp <= Tmax.
    In,
    /// Tp > Tmax: too slow.
    Over,
}

#[derive(Deserialize)]
struct RawBand {
    tmin_ms: f64,
    tmax_ms: f64,
}

impl TryFrom<RawBand> for Band {
    type Error = ConfigError;
    fn try_from(raw: RawBand) -> Result<Self, ConfigError> {
        Band::new(raw.tmin_ms, raw.tmax_ms)
    }
}

impl Band {
    /// The paper's band, [15, 20] ms.
    pub const PAPER: Band = Band {
        tmin_ms: 15.0,
        tmax_ms: 20.0,
    };

    /// A band; errors if a limit is NaN, infinite or not positive, or if Tmin >= Tmax.
    pub fn new(tmin_ms: f64, tmax_ms: f64) -> Result<Self, ConfigError> {
        for (name, value) in [("Tmin", tmin_ms), ("Tmax", tmax_ms)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ConfigError::BadBandLimit { name, value });
            }
        }
        if tmin_ms >= tmax_ms {
            return Err(ConfigError::EmptyBand { tmin_ms, tmax_ms });
        }
        Ok(Self { tmin_ms, tmax_ms })
    }

    /// Tmin, ms.
    pub fn tmin_ms(&self) -> f64 {
        self.tmin_ms
    }

    /// Tmax, ms.
    pub fn tmax_ms(&self) -> f64 {
        self.tmax_ms
    }

    /// Tmax - Tmin, ms.
    pub fn width_ms(&self) -> f64 {
        self.tmax_ms - self.tmin_ms
    }

    /// The time at fraction `f` of the way from Tmin to Tmax (0.5: the centre).
    pub fn at(&self, f: f64) -> f64 {
        self.tmin_ms + f * self.width_ms()
    }

    /// The band's centre, ms.
    pub fn centre_ms(&self) -> f64 {
        self.at(0.5)
    }

    /// Where `tp_ms` lies (limits inclusive: Tp = Tmax is in the band).
    pub fn position(&self, tp_ms: f64) -> Position {
        if tp_ms > self.tmax_ms {
            Position::Over
        } else if tp_ms < self.tmin_ms {
            Position::Under
        } else {
            Position::In
        }
    }

    /// Whether Tmin <= `tp_ms` <= Tmax.
    pub fn contains(&self, tp_ms: f64) -> bool {
        self.position(tp_ms) == Position::In
    }
}

impl fmt::Display for Band {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}, {}] ms", self.tmin_ms, self.tmax_ms)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_bands() {
        assert!(matches!(
            Band::new(20.0, 15.0),
            Err(ConfigError::EmptyBand { .. })
        ));
        assert!(matches!(
            Band::new(15.0, 15.0),
            Err(ConfigError::EmptyBand { .. })
        ));
        assert!(matches!(
            Band::new(-1.0, 15.0),
            Err(ConfigError::BadBandLimit { name: "Tmin", .. })
        ));
        assert!(matches!(
            Band::new(0.0, 15.0),
            Err(ConfigError::BadBandLimit { .. })
        ));
        assert!(matches!(
            Band::new(1.0, f64::NAN),
            Err(ConfigError::BadBandLimit { name: "Tmax", .. })
        ));
        assert!(Band::new(1.0, f64::INFINITY).is_err());
    }

    #[test]
    fn positions_are_inclusive() {
        let b = Band::PAPER;
        assert_eq!(b.position(15.0), Position::In);
        assert_eq!(b.position(20.0), Position::In);
        assert_eq!(b.position(20.01), Position::Over);
        assert_eq!(b.position(14.99), Position::Under);
        assert_eq!(b.centre_ms(), 17.5);
    }

    #[test]
    fn deserialization_validates() {
        let ok: Band = serde_json::from_str(r#"{"tmin_ms":15,"tmax_ms":20}"#).unwrap();
        assert_eq!(ok, Band::PAPER);
        assert!(serde_json::from_str::<Band>(r#"{"tmin_ms":20,"tmax_ms":15}"#).is_err());
    }
}
