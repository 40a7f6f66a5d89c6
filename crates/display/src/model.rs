//! The display model (`docs/display.md`): double-buffered presentation of frames whose render
//! and hand-over times were measured. Times in, display times out; nothing here renders or
//! waits, so a run on a fake clock gives the same answers as one on a real renderer.
//!
//! Frame j starts at s_j (s_0 = 0, then s_{j+1} = v_j: with two buffers the renderer draws
//! into the one the screen released when frame j replaced it), completes at
//! c_j = s_j + Tp_j + hand-over_j, and becomes visible at v_j:
//! - vsync on: the first refresh i·P at or after c_j, later than v_{j−1};
//! - vsync off: c_j;
//! - variable refresh: c_j, but no sooner than the shortest interval after the panel's
//!   previous refresh (the last new frame or a repeat the panel made after its longest
//!   interval without one).

use crate::config::{DisplayConfig, SyncMode, VrrRange};
use crate::error::DisplayError;
use serde::Serialize;

/// Times closer than this, ms, count as equal: refresh instants are computed as i·P, frame
/// times as sums, and a frame completing at a refresh (up to rounding) makes that refresh.
pub const TIME_EPS_MS: f64 = 1e-6;

/// One frame's way to the screen, ms of display time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FrameTimes {
    /// s_j: when rendering started.
    pub start_ms: f64,
    /// Tp_j: the render time.
    pub tp_ms: f64,
    /// The measured cost of handing the frame to the display (present or readback).
    pub hand_over_ms: f64,
    /// v_j: when the frame became visible.
    pub visible_ms: f64,
}

impl FrameTimes {
    /// c_j: when the frame was complete and handed over.
    pub fn complete_ms(&self) -> f64 {
        self.start_ms + self.tp_ms + self.hand_over_ms
    }

    /// v_j − s_j: from the start of rendering to the screen.
    pub fn latency_ms(&self) -> f64 {
        self.visible_ms - self.start_ms
    }
}

/// The index of the first refresh at or after `t_ms` (refreshes at i·`period_ms`).
pub fn refresh_at_or_after(t_ms: f64, period_ms: f64) -> u64 {
    ((t_ms - TIME_EPS_MS) / period_ms).ceil().max(0.0) as u64
}

/// When a variable-refresh panel whose last refresh was at `last_ms` shows a frame completed
/// at `complete_ms`; the repeats it makes meanwhile (each after its longest interval without
/// a new frame) are pushed onto `repeats`.
pub(crate) fn vrr_visible(
    last_ms: f64,
    complete_ms: f64,
    range: &VrrRange,
    repeats: &mut Vec<f64>,
) -> f64 {
    let mut last = last_ms;
    while complete_ms > last + range.max_interval_ms() + TIME_EPS_MS {
        last += range.max_interval_ms();
        repeats.push(last);
    }
    complete_ms.max(last + range.min_interval_ms())
}

/// The display, fed one frame at a time.
#[derive(Clone, Debug)]
pub struct Display {
    config: DisplayConfig,
    frames: Vec<FrameTimes>,
}

impl Display {
    /// A display that has shown nothing yet.
    pub fn new(config: DisplayConfig) -> Self {
        Self {
            config,
            frames: Vec::new(),
        }
    }

    /// The display's settings.
    pub fn config(&self) -> &DisplayConfig {
        &self.config
    }

    /// The frames presented so far, in order.
    pub fn frames(&self) -> &[FrameTimes] {
        &self.frames
    }

    /// When the next frame starts: 0, then when the frame before it became visible.
    pub fn next_start_ms(&self) -> f64 {
        self.frames.last().map_or(0.0, |f| f.visible_ms)
    }

    /// When the next frame would become visible if it completed `busy_ms` after its start
    /// (render and hand-over): the prediction a frame can render its world time from. A frame
    /// takes some time, so even `busy_ms` = 0 predicts a time after the start.
    pub fn visible_after(&self, busy_ms: f64) -> f64 {
        self.visible_at(self.next_start_ms() + busy_ms.max(2.0 * TIME_EPS_MS))
    }

    /// When the next frame becomes visible if it completes at `complete_ms`.
    fn visible_at(&self, complete_ms: f64) -> f64 {
        let previous = self.frames.last().map(|f| f.visible_ms);
        match self.config.sync {
            SyncMode::Vsync => {
                let p = self.config.period_ms();
                let mut i = refresh_at_or_after(complete_ms, p);
                if let Some(prev) = previous {
                    i = i.max((prev / p).round() as u64 + 1);
                }
                i as f64 * p
            }
            SyncMode::Off => complete_ms,
            SyncMode::Vrr(range) => vrr_visible(
                previous.unwrap_or(0.0),
                complete_ms,
                &range,
                &mut Vec::new(),
            ),
        }
    }

    /// Presents the next frame, which rendered for `tp_ms` and took `hand_over_ms` to hand
    /// over; returns its times. Refuses NaN, infinite or negative times, and a frame of no
    /// time at all (display time would stand still).
    pub fn present(&mut self, tp_ms: f64, hand_over_ms: f64) -> Result<FrameTimes, DisplayError> {
        for (name, value) in [("Tp", tp_ms), ("hand-over", hand_over_ms)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(DisplayError::BadFrameTime {
                    name,
                    value,
                    why: "it must be a finite number of ms, 0 or more",
                });
            }
        }
        if tp_ms + hand_over_ms <= 0.0 {
            return Err(DisplayError::BadFrameTime {
                name: "Tp + hand-over",
                value: tp_ms + hand_over_ms,
                why: "a frame must take some time, or display time stands still",
            });
        }
        let start_ms = self.next_start_ms();
        let frame = FrameTimes {
            start_ms,
            tp_ms,
            hand_over_ms,
            visible_ms: self.visible_at(start_ms + tp_ms + hand_over_ms),
        };
        self.frames.push(frame);
        Ok(frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_completing_on_a_refresh_makes_it() {
        let p = 1000.0 / 60.0;
        assert_eq!(refresh_at_or_after(0.0, p), 0);
        assert_eq!(refresh_at_or_after(2.0 * p, p), 2);
        assert_eq!(refresh_at_or_after(2.0 * p + 1e-9, p), 2, "rounding");
        assert_eq!(refresh_at_or_after(2.0 * p + 0.01, p), 3);
    }

    #[test]
    fn variable_refresh_repeats_after_its_longest_interval() {
        let range = VrrRange::new(40.0, 100.0).unwrap(); // 10 ms to 25 ms
        let mut repeats = Vec::new();
        assert_eq!(vrr_visible(0.0, 12.0, &range, &mut repeats), 12.0);
        assert_eq!(vrr_visible(0.0, 4.0, &range, &mut repeats), 10.0);
        assert!(repeats.is_empty());
        // Complete at 30: the panel repeats at 25 and can show the frame from 35 on.
        assert_eq!(vrr_visible(0.0, 30.0, &range, &mut repeats), 35.0);
        assert_eq!(repeats, [25.0]);
    }
}
