//! A run's figures as the viewer saw it (`docs/display.md`): frames shown per second,
//! repeated refreshes, pacing and latency.

use crate::stats::{mean, quantile, std_dev};
use crate::timeline::Timeline;
use serde::Serialize;

/// What the screen showed over one run. Times in ms.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DisplayFigures {
    /// Frames started before the run's end.
    pub frames_rendered: usize,
    /// Distinct frames that some refresh of the panel showed.
    pub frames_shown: usize,
    /// Frames shown per second of display time.
    pub displayed_fps: f64,
    /// Refreshes of the panel showing the same frame as the refresh before, in % of the
    /// refreshes that follow one showing a frame.
    pub repeated_pct: f64,
    /// Standard deviation of the intervals between the frames shown (v_{j+1} − v_j); `None`
    /// with fewer than two frames shown.
    pub pacing_std_ms: Option<f64>,
    /// Mean of v_j − s_j over the frames shown; `None` when none was shown.
    pub latency_ms_mean: Option<f64>,
    /// 95th percentile of v_j − s_j over the frames shown.
    pub latency_ms_p95: Option<f64>,
}

impl DisplayFigures {
    /// The figures of a finished run.
    pub fn of(timeline: &Timeline) -> Self {
        let refreshes = timeline.refreshes();
        let mut shown: Vec<usize> = refreshes.iter().filter_map(|r| r.frame).collect();
        shown.dedup();
        let (mut pairs, mut repeated) = (0usize, 0usize);
        for w in refreshes.windows(2) {
            if let (Some(a), Some(b)) = (w[0].frame, w[1].frame) {
                pairs += 1;
                repeated += usize::from(a == b);
            }
        }
        let frames = timeline.frames();
        let visible: Vec<f64> = shown.iter().map(|&j| frames[j].visible_ms).collect();
        let intervals: Vec<f64> = visible.windows(2).map(|w| w[1] - w[0]).collect();
        let latency: Vec<f64> = shown.iter().map(|&j| frames[j].latency_ms()).collect();
        Self {
            frames_rendered: frames.len(),
            frames_shown: shown.len(),
            displayed_fps: shown.len() as f64 / (timeline.duration_ms() / 1000.0),
            repeated_pct: if pairs == 0 {
                0.0
            } else {
                100.0 * repeated as f64 / pairs as f64
            },
            pacing_std_ms: std_dev(&intervals),
            latency_ms_mean: mean(&latency),
            latency_ms_p95: quantile(&latency, 0.95),
        }
    }
}
