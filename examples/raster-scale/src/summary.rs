//! The run's one-line JSON summary: the share of frames in the band (the controller's
//! figure), and the mean render scale at each load level (the scale followed the load).

use crate::engine::Frame;
use crate::load::LEVELS;
use serde::Serialize;
use steadyray_control::{Action, Band, FrameRecord, Quality, metrics};

/// Frames at the start of each load phase left out of the per-level scale (the controller's
/// reaction to the step).
const SETTLE_FRAMES: usize = 10;

/// The mean scale the controller chose at one load level.
#[derive(Debug, Serialize)]
pub struct LevelScale {
    /// The load level.
    pub load: f64,
    /// Frames at that level after the settling frames.
    pub frames: usize,
    /// Their mean render scale.
    pub mean_scale: f64,
    /// Their share in the band, %.
    pub in_band_pct: f64,
}

/// How often the controller did what.
#[derive(Debug, Default, Serialize)]
pub struct Actions {
    /// Cuts of the scale.
    pub cuts: usize,
    /// Raises.
    pub raises: usize,
    /// Trades of one knob for another at the same cost (holds, every other frame, are not
    /// counted).
    pub trades: usize,
}

impl Actions {
    fn count(frames: &[Frame]) -> Self {
        let mut a = Self::default();
        for f in frames {
            match f.action {
                Some(Action::Cut) => a.cuts += 1,
                Some(Action::Raise) => a.raises += 1,
                Some(Action::Trade) => a.trades += 1,
                Some(Action::Hold) | None => {}
            }
        }
        a
    }
}

/// What `--frames N` prints.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// The controller spec.
    pub controller: String,
    /// The adapter.
    pub adapter: String,
    /// Where the frame times came from (timestamps, or the wall clock for some frames).
    pub timing: String,
    /// Frames summarised (after the warm-up).
    pub frames: usize,
    /// The band, ms.
    pub band_ms: [f64; 2],
    /// Fractal steps per pixel at load 1.
    pub base_iterations: f64,
    /// Frames in the band, %.
    pub in_band_pct: f64,
    /// Frames over the band, %.
    pub over_pct: f64,
    /// Median frame time, ms.
    pub tp_p50: f64,
    /// 95th percentile frame time, ms.
    pub tp_p95: f64,
    /// Quality reversals per 100 frames.
    pub reversals_per_100: f64,
    /// Mean render scale.
    pub mean_scale: f64,
    /// The controller's cuts, raises and trades (from its decisions; 0 where it gives none).
    pub actions: Actions,
    /// The scale at each load level.
    pub by_load: Vec<LevelScale>,
}

/// Summarises `frames` (the warm-up already left out) for `controller` in `band`.
pub fn summarize(
    controller: &str,
    adapter: &str,
    frames: &[Frame],
    band: Band,
    base_iterations: f64,
    phase_frames: u64,
) -> Summary {
    let records: Vec<FrameRecord> = frames.iter().map(|f| f.record).collect();
    let top = Quality::new(1.0, 0, 1.0);
    let s = metrics::summarize(&records, band, top, None);
    let by_load = LEVELS
        .iter()
        .map(|&load| {
            let settled: Vec<&Frame> = frames
                .iter()
                .filter(|f| f.level == load)
                .filter(|f| (f.record.frame as u64 % phase_frames.max(1)) as usize >= SETTLE_FRAMES)
                .collect();
            let n = settled.len().max(1) as f64;
            LevelScale {
                load,
                frames: settled.len(),
                mean_scale: settled
                    .iter()
                    .map(|f| f64::from(f.record.quality.scale))
                    .sum::<f64>()
                    / n,
                in_band_pct: 100.0
                    * settled
                        .iter()
                        .filter(|f| band.contains(f.record.tp_ms))
                        .count() as f64
                    / n,
            }
        })
        .collect();
    let walls = frames
        .iter()
        .filter(|f| f.source == crate::timer::TimeSource::WallClock)
        .count();
    let timing = match walls {
        0 => "gpu timestamps".to_string(),
        n if n == frames.len() => "wall clock".to_string(),
        n => format!("gpu timestamps ({n} frames on the wall clock)"),
    };
    Summary {
        controller: controller.to_string(),
        adapter: adapter.to_string(),
        timing,
        frames: s.frames,
        band_ms: [band.tmin_ms(), band.tmax_ms()],
        base_iterations,
        in_band_pct: s.in_band_pct,
        over_pct: s.over_pct,
        tp_p50: s.tp_p50,
        tp_p95: s.tp_p95,
        reversals_per_100: s.reversals_per_100,
        mean_scale: s.mean_scale,
        actions: Actions::count(frames),
        by_load,
    }
}
