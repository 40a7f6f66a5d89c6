//! What a real-clock run's screen showed: the run as the viewer saw it (its timeline, the
//! pictures kept, its warped refreshes) and, once measured, its displayed quality sample by
//! sample. The real clock fills these in, the displayed quality measures them, the records
//! and reports write them.

use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use steadyray_display::{DisplayFigures, Timeline};
use steadyray_quality::Rgb8Image;

/// A real-clock run as the viewer saw it.
#[derive(Clone, Debug)]
pub struct DisplayRun {
    /// When each frame was shown, refresh by refresh.
    pub timeline: Timeline,
    /// What the viewer saw, in figures.
    pub figures: DisplayFigures,
    /// The pictures (tone-mapped, at their rendered size) of the frames on screen at the kept
    /// samples, by frame; `None` is the last warm-up frame, on screen before the first.
    pub pictures: BTreeMap<Option<usize>, Rgb8Image>,
    /// The refreshes that showed the frame on screen warped to their own time (`--warp`),
    /// with the pictures of those at kept samples.
    pub warps: Warps,
    /// World time of each frame, s.
    pub world_s: Vec<f64>,
    /// World time of the frame on screen before the first (`None`), s: the last warm-up
    /// frame's, a refresh before the path's start in the bench.
    pub lead_in_world_s: f64,
    /// The screen against the references (`bench --quality`), measured after the runs.
    pub quality: Option<DisplayedQuality>,
    /// The frames' share (rendering and hand-over) of the run's wall time, %: the rest is
    /// the bench's own work between frames. A GPU's clocks follow how busy it is, so a low
    /// share slows its frames; `None` where the frames were not timed in wall time.
    pub busy_pct: Option<f64>,
}

impl DisplayRun {
    /// The world time a frame on screen shows, s.
    pub fn world_of(&self, frame: Option<usize>) -> f64 {
        frame.map_or(self.lead_in_world_s, |j| self.world_s[j])
    }
}

/// The warped refreshes of a run (`--warp`).
#[derive(Clone, Debug, Default)]
pub struct Warps {
    /// The refreshes (by index: refresh i is at i·P) that showed a warp.
    pub shown: BTreeSet<usize>,
    /// The warps' pictures at the kept samples, by refresh.
    pub pictures: BTreeMap<usize, Rgb8Image>,
    /// What each warp shown cost, ms.
    pub ms: Vec<f64>,
    /// Refreshes shown unwarped that should have been warped: without a new frame, beyond
    /// the warps made ahead for them (`warps_to_make`) or whose warp would have cost the next frame its
    /// refresh, or a frame's first showing whose warp did not fit before its refresh.
    pub missed: usize,
}

/// The warps' figures in `summary.json`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct WarpFigures {
    /// Refreshes that showed a warp.
    pub warps_shown: usize,
    /// Their mean cost, ms.
    pub warp_ms_mean: f64,
    /// Refreshes shown unwarped that should have been warped (no time left for the warp).
    pub warps_missed: usize,
}

impl Warps {
    /// Records a warp shown at refresh `refresh` that cost `ms`, with its picture if kept.
    pub fn record(&mut self, refresh: usize, ms: f64, picture: Option<Rgb8Image>) {
        self.shown.insert(refresh);
        self.ms.push(ms);
        if let Some(picture) = picture {
            self.pictures.insert(refresh, picture);
        }
    }

    /// The figures of a run that warped.
    pub fn figures(&self) -> WarpFigures {
        WarpFigures {
            warps_shown: self.shown.len(),
            warp_ms_mean: steadyray_display::stats::mean(&self.ms).unwrap_or(0.0),
            warps_missed: self.missed,
        }
    }
}

/// The screen at one sample: its time, what it showed and that frame's world time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenSample {
    /// The sample's number: it is at `index`·P.
    pub index: usize,
    /// The refresh's time on the display, s.
    pub time_s: f64,
    /// The frame on screen; `None`: the last warm-up frame.
    pub frame: Option<usize>,
    /// Whether the refresh showed that frame warped to its own time (`--warp`).
    pub warped: bool,
    /// The world time the screen shows, s: its frame's, or the refresh's own for a warp (what
    /// a warp gets wrong, objects that moved since the frame and what it uncovers, is its
    /// picture's error, not its age).
    pub world_s: f64,
}

/// One sampled refresh against the references (a row of `displayed.csv`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScoredSample {
    /// Where and when the screen was sampled.
    pub sample: ScreenSample,
    /// FLIP of the screen against the world at the refresh.
    pub flip: f64,
    /// FLIP of the screen against the world at the time its frame shows.
    pub frame_flip: f64,
    /// FLIP of the world at the frame's time against the world at the refresh.
    pub age_flip: f64,
}

/// What one run's screen looked like against the references.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayedQuality {
    /// Mean and 95th percentile of FLIP of the screen against the world at the refresh.
    pub flip_mean: f64,
    /// The 95th percentile of the samples' FLIP.
    pub flip_p95: f64,
    /// Mean FLIP of the screen against the world at the time its frame shows: the picture's
    /// own error, without its age.
    pub frame_flip_mean: f64,
    /// Mean FLIP of the world at the time its frame shows against the world at the refresh
    /// (two references): what the screen's age costs a perfect picture, the part of
    /// `flip_mean` no better picture at the same frame times can remove.
    pub age_flip_mean: f64,
    /// Mean age of the world on screen, ms (refresh time − the frame's world time).
    pub age_ms_mean: f64,
    /// Every sampled refresh's scores, in time order: the distribution behind the means.
    pub scored: Vec<ScoredSample>,
}
