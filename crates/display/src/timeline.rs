//! What the screen showed over a run: the panel's refreshes and the frame each one showed,
//! and the screen at any instant.

use crate::config::{DisplayConfig, SyncMode};
use crate::model::{FrameTimes, TIME_EPS_MS, refresh_at_or_after, vrr_visible};
use serde::Serialize;

/// One refresh of the panel.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Refresh {
    /// When it happened, ms of display time.
    pub time_ms: f64,
    /// The frame it showed (an index into the run's frames), `None` before the first frame.
    pub frame: Option<usize>,
}

/// A finished run as the display showed it.
#[derive(Clone, Debug, PartialEq)]
pub struct Timeline {
    config: DisplayConfig,
    duration_ms: f64,
    frames: Vec<FrameTimes>,
    refreshes: Vec<Refresh>,
}

impl Timeline {
    /// The timeline of `frames` (presented in order by [`crate::Display`] under `config`)
    /// over a run of `duration_ms`: the panel refreshes at i·P in [0, duration) with vsync on
    /// or off; with variable refresh, at 0, at each frame's v_j and at each repeat.
    pub fn new(config: DisplayConfig, frames: Vec<FrameTimes>, duration_ms: f64) -> Self {
        let refreshes = match config.sync {
            SyncMode::Vsync | SyncMode::Off => {
                let p = config.period_ms();
                let count = refresh_at_or_after(duration_ms, p);
                let mut shown = ScreenCursor::default();
                (0..count)
                    .map(|i| {
                        let time_ms = i as f64 * p;
                        Refresh {
                            time_ms,
                            frame: shown.at(&frames, time_ms),
                        }
                    })
                    .collect()
            }
            SyncMode::Vrr(range) => {
                let mut refreshes = vec![Refresh {
                    time_ms: 0.0,
                    frame: None,
                }];
                let mut repeats = Vec::new();
                let mut last = 0.0;
                for (j, f) in frames.iter().enumerate() {
                    repeats.clear();
                    vrr_visible(last, f.complete_ms(), &range, &mut repeats);
                    let previous = j.checked_sub(1);
                    refreshes.extend(repeats.iter().map(|&time_ms| Refresh {
                        time_ms,
                        frame: previous,
                    }));
                    refreshes.push(Refresh {
                        time_ms: f.visible_ms,
                        frame: Some(j),
                    });
                    last = f.visible_ms;
                }
                let tail = frames.len().checked_sub(1);
                loop {
                    last += range.max_interval_ms();
                    if last >= duration_ms - TIME_EPS_MS {
                        break;
                    }
                    refreshes.push(Refresh {
                        time_ms: last,
                        frame: tail,
                    });
                }
                refreshes.retain(|r| r.time_ms < duration_ms - TIME_EPS_MS);
                refreshes
            }
        };
        Self {
            config,
            duration_ms,
            frames,
            refreshes,
        }
    }

    /// The display the run was shown on.
    pub fn config(&self) -> &DisplayConfig {
        &self.config
    }

    /// The run's length, ms of display time.
    pub fn duration_ms(&self) -> f64 {
        self.duration_ms
    }

    /// Every frame rendered (started before the end), in order.
    pub fn frames(&self) -> &[FrameTimes] {
        &self.frames
    }

    /// The panel's refreshes in [0, duration), in order.
    pub fn refreshes(&self) -> &[Refresh] {
        &self.refreshes
    }

    /// The frame on screen at `t_ms`: the latest with v_j <= t (`None` before the first).
    pub fn shown_at(&self, t_ms: f64) -> Option<usize> {
        self.frames
            .partition_point(|f| f.visible_ms <= t_ms + TIME_EPS_MS)
            .checked_sub(1)
    }

    /// The screen sampled every `period_ms` from 0 to the end: what a video of the screen at
    /// that rate shows (with vsync on at the refresh period: exactly the panel's refreshes).
    pub fn sampled(&self, period_ms: f64) -> Vec<Refresh> {
        let count = refresh_at_or_after(self.duration_ms, period_ms);
        let mut shown = ScreenCursor::default();
        (0..count)
            .map(|i| {
                let time_ms = i as f64 * period_ms;
                Refresh {
                    time_ms,
                    frame: shown.at(&self.frames, time_ms),
                }
            })
            .collect()
    }
}

/// Walks the frames along increasing times (linear over a whole run, where a search per
/// refresh would be n log n).
#[derive(Default)]
struct ScreenCursor {
    next: usize,
}

impl ScreenCursor {
    fn at(&mut self, frames: &[FrameTimes], t_ms: f64) -> Option<usize> {
        while self.next < frames.len() && frames[self.next].visible_ms <= t_ms + TIME_EPS_MS {
            self.next += 1;
        }
        self.next.checked_sub(1)
    }
}
