//! Why a display, a viewing set-up, a run or a frame's times cannot be used. Every error names
//! the offending value and what would be accepted.

use thiserror::Error;

/// A bad display setting or frame time.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DisplayError {
    /// The refresh rate is NaN, infinite, not positive or above [`crate::MAX_REFRESH_HZ`].
    #[error("refresh rate {0} Hz is invalid: it must be a number above 0 and at most 1000")]
    BadRefresh(f64),
    /// A variable refresh range that is empty or leaves (0, 1000] Hz.
    #[error(
        "variable refresh range {min_hz}-{max_hz} Hz is invalid: it must be MIN-MAX with 0 < MIN < MAX <= 1000"
    )]
    BadVrr {
        /// The range's minimum, Hz.
        min_hz: f64,
        /// Its maximum, Hz.
        max_hz: f64,
    },
    /// Text that does not read as a variable refresh range.
    #[error("cannot read a variable refresh range from `{0}`: write MIN-MAX in Hz, e.g. 48-144")]
    VrrSyntax(String),
    /// A run duration that is NaN, infinite, not positive or above [`crate::MAX_DURATION_S`].
    #[error("duration {0} s is invalid: it must be a number of seconds above 0 and at most 3600")]
    BadDuration(f64),
    /// A frame's render or hand-over time is NaN, infinite or negative, or the frame takes no
    /// time at all (display time would not advance).
    #[error("frame time {name} = {value} ms is invalid: {why}")]
    BadFrameTime {
        /// Which time.
        name: &'static str,
        /// Its value, ms.
        value: f64,
        /// What is wrong with it.
        why: &'static str,
    },
    /// A frame was presented after the run's last frame slot.
    #[error("the run is over: no frame starts at or after its end ({duration_ms} ms)")]
    RunOver {
        /// The run's length, ms.
        duration_ms: f64,
    },
    /// A viewing set-up with a size, distance or resolution that is not positive.
    #[error("viewing set-up is invalid: {0}")]
    BadViewing(String),
}
