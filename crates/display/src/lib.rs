//! What the viewer sees of a real-time renderer's frames (`docs/display.md`): a display model
//! (refresh rate, vsync on or off, variable refresh within a range, double buffering, the
//! measured hand-over cost), the real clock that advances display time by it, the run's
//! figures (frames shown per second, repeated refreshes, pacing, latency) and the one viewing
//! set-up every perceptual metric assumes.
//!
//! Like the controllers it has no graphics dependency: times in, display times out. A run is
//! deterministic from its frames' measured render and hand-over times, so the simulated
//! renderer's fake clock drives it exactly as a real renderer does.
//!
//! ```
//! use steadyray_display::{DisplayConfig, DisplayFigures, RealClock, SyncMode};
//!
//! // 17 ms frames on a 60 Hz display with vsync: each misses a refresh and waits for the next.
//! let mut clock = RealClock::new(DisplayConfig::new(60.0, SyncMode::Vsync)?, 1.0)?;
//! while let Some(slot) = clock.next_frame() {
//!     // render the world at slot.world_s() here, measure Tp and the hand-over
//!     clock.present(17.0, 0.0)?;
//! }
//! let figures = DisplayFigures::of(&clock.finish());
//! // 30 frames start within the second; the first shows at refresh 2, the last would at 60.
//! assert_eq!((figures.frames_rendered, figures.frames_shown), (30, 29));
//! assert!((figures.latency_ms_mean.unwrap() - 2000.0 / 60.0).abs() < 1e-9);
//! # Ok::<(), steadyray_display::DisplayError>(())
//! ```

pub mod aligned;
pub mod clock;
pub mod config;
pub mod error;
pub mod figures;
pub mod model;
pub mod refresh_band;
pub mod stats;
pub mod timeline;
pub mod viewing;

pub use aligned::{BandShape, aligned_band, shaped_band};
pub use clock::{FrameSlot, MAX_DURATION_S, PREDICTION_FRAMES, RealClock};
pub use config::{DisplayConfig, MAX_REFRESH_HZ, SyncMode, VrrRange};
pub use error::DisplayError;
pub use figures::DisplayFigures;
pub use model::{Display, FrameTimes};
pub use refresh_band::RefreshBand;
pub use timeline::{Refresh, Timeline};
pub use viewing::ViewingSetup;
