//! The real clock: a run lasts a given span of display time, each frame starts when the
//! display model lets it (see [`crate::model`]), and each frame renders the world at the time
//! it is predicted to be shown. Display time advances by the measured render and hand-over
//! times only, so a run is deterministic from them (and runs on a fake clock as it does on a
//! real renderer); a faster controller renders more frames in the same span.
//!
//! Why the predicted display time and not the frame's start: the viewer sees a frame at v_j,
//! so the world it shows should be the world at v_j. Rendered at its start s_j instead, every
//! frame is at least one refresh old when it appears, and the step of the world between two
//! frames shown (s_{j+1} − s_j = v_j − v_{j−1}) is the interval *before* the one the viewer
//! sees (v_{j+1} − v_j): each change of the frame rate shows as a jump in the motion. With the
//! prediction (the median render and hand-over time of the last [`PREDICTION_FRAMES`]
//! frames, rounded up to the refresh that would show it) the steps match whenever the
//! prediction holds, which a controller holding its band makes the common case; VR runtimes
//! render at a predicted display time for the same reason.
//!
//! Why the median of several frames and not the last frame's time: a controller answers a
//! slow frame with a cut, so the frame after it is fast, and a prediction from the slow frame
//! is then a refresh or more too late: that frame shows the world ahead of its refresh, and
//! the next one, predicted from a fast frame, renders the same world time again (a stop, then
//! a jump). On the corridor at one 60 Hz refresh a frame, one frame in seven or eight did so.
//! The median lets one slow frame pass and still follows a lasting change within a few frames.

use crate::config::DisplayConfig;
use crate::error::DisplayError;
use crate::model::{Display, FrameTimes};
use crate::stats::quantile;
use crate::timeline::Timeline;

/// The longest run accepted, s (a bound on the timeline's size).
pub const MAX_DURATION_S: f64 = 3600.0;

/// The frames whose median render and hand-over time predicts the next frame's.
pub const PREDICTION_FRAMES: usize = 5;

/// The next frame to render under the real clock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameSlot {
    /// The frame's index in the run.
    pub index: usize,
    /// When it starts, ms of display time.
    pub start_ms: f64,
    /// When it is predicted to be shown, ms: the world time to render.
    pub show_ms: f64,
}

impl FrameSlot {
    /// The world time to render, s.
    pub fn world_s(&self) -> f64 {
        self.show_ms / 1000.0
    }
}

/// A run of `duration` seconds of display time on a display model.
#[derive(Clone, Debug)]
pub struct RealClock {
    display: Display,
    duration_ms: f64,
    /// The render and hand-over times of the last frames (at most [`PREDICTION_FRAMES`]).
    recent_busy_ms: Vec<f64>,
}

impl RealClock {
    /// A run of `duration_s` seconds (0 < duration <= [`MAX_DURATION_S`]) on `config`.
    pub fn new(config: DisplayConfig, duration_s: f64) -> Result<Self, DisplayError> {
        if !(duration_s.is_finite() && duration_s > 0.0 && duration_s <= MAX_DURATION_S) {
            return Err(DisplayError::BadDuration(duration_s));
        }
        Ok(Self {
            display: Display::new(config),
            duration_ms: duration_s * 1000.0,
            recent_busy_ms: Vec::with_capacity(PREDICTION_FRAMES + 1),
        })
    }

    /// Adds the render and hand-over time of a frame rendered outside the run (a warm-up
    /// frame) to those the prediction takes its median from; each presented frame adds its
    /// own. A NaN, infinite or negative time is ignored.
    pub fn expect(&mut self, busy_ms: f64) {
        if busy_ms.is_finite() && busy_ms >= 0.0 {
            self.recent_busy_ms.push(busy_ms);
            if self.recent_busy_ms.len() > PREDICTION_FRAMES {
                self.recent_busy_ms.remove(0);
            }
        }
    }

    /// The render and hand-over time the next frame is predicted to take: the median of the
    /// recent frames' (the mean of the middle two of an even count), 0 before any.
    pub fn predicted_busy_ms(&self) -> f64 {
        quantile(&self.recent_busy_ms, 0.5).unwrap_or(0.0)
    }

    /// The run's length, ms.
    pub fn duration_ms(&self) -> f64 {
        self.duration_ms
    }

    /// The next frame, or `None` when it would start at or after the run's end.
    pub fn next_frame(&self) -> Option<FrameSlot> {
        let start_ms = self.display.next_start_ms();
        (start_ms < self.duration_ms).then(|| FrameSlot {
            index: self.display.frames().len(),
            start_ms,
            show_ms: self.display.visible_after(self.predicted_busy_ms()),
        })
    }

    /// Presents the frame of the current slot, which rendered for `tp_ms` and took
    /// `hand_over_ms` to hand over.
    pub fn present(&mut self, tp_ms: f64, hand_over_ms: f64) -> Result<FrameTimes, DisplayError> {
        if self.next_frame().is_none() {
            return Err(DisplayError::RunOver {
                duration_ms: self.duration_ms,
            });
        }
        let frame = self.display.present(tp_ms, hand_over_ms)?;
        self.expect(tp_ms + hand_over_ms);
        Ok(frame)
    }

    /// The run as the screen showed it.
    pub fn finish(self) -> Timeline {
        let config = *self.display.config();
        Timeline::new(config, self.display.frames().to_vec(), self.duration_ms)
    }
}
