//! What the experiment records: one row per frame, one run per controller.

use super::screen::DisplayRun;
use super::source::Measured;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;
use steadyray_control::metrics::RunSummary;
use steadyray_control::{Action, AimCeiling, Band, Decision, Reason, aim_ceiling};
use steadyray_display::FrameTimes;
use steadyray_quality::Rgb8Image;

/// One counted frame of one controller's sweep (a row of `frames.csv`).
#[derive(Clone, Debug, PartialEq)]
pub struct FrameRow {
    /// The frame's index in the run.
    pub frame: u32,
    /// Camera yaw in radians.
    pub angle: f32,
    /// The path's time the frame shows, s (frame clock: k/N of the path's length; real
    /// clock: the frame's predicted display time).
    pub t_s: f64,
    /// Eye rays per pixel S.
    pub spp: f32,
    /// Reflection depth R.
    pub depth: u32,
    /// Resolution scale.
    pub scale: f32,
    /// Tp, the render time, ms.
    pub tp_ms: f64,
    /// The warps of refreshes without a new frame made while the frame rendered (`bench
    /// --warp`), ms: the display model's time for the frame is `tp_ms + warp_ms`.
    pub warp_ms: f64,
    /// Host wall time of the render call, ms.
    pub wall_ms: f64,
    /// The part of Tp spent placing moving objects and updating the top-level BVH, ms.
    pub accel_ms: f64,
    /// Rays traced (every depth and shadow rays).
    pub rays: u64,
    /// Whether Tp lay in the band.
    pub in_band: bool,
    /// Mean FLIP against the reference, for the frames `bench --quality` measured.
    pub flip: Option<f64>,
    /// The frame's way to the screen (real clock only).
    pub display: Option<FrameTimes>,
    /// Its motion on screen, degrees of visual angle per second: mean and 95th percentile.
    pub speed_mean: f64,
    /// The 95th percentile of the motion on screen, deg/s.
    pub speed_p95: f64,
    /// The frame time the controller aimed this frame at, ms (`perceptual` only).
    pub target_ms: Option<f64>,
    /// The controller's prediction of this frame's Tp when it chose its quality, ms
    /// (controllers that predict, after their first frames).
    pub predicted_ms: Option<f64>,
    /// What the controller decided after this frame and why (written `action:reason`, e.g.
    /// `cut:drift`), for controllers that explain their decisions.
    pub decision: Option<(Action, Reason)>,
}

impl FrameRow {
    /// The row of frame `frame`, which showed the path at `t_s` and was measured as `m` at
    /// quality `m.report.quality`; no FLIP or display times yet.
    pub fn measured(frame: u32, t_s: f64, m: &Measured, band: Band) -> Self {
        let q = m.report.quality;
        Self {
            frame,
            angle: m.angle,
            t_s,
            spp: q.spp,
            depth: q.depth,
            scale: q.scale,
            tp_ms: m.report.tp_ms,
            warp_ms: 0.0,
            wall_ms: m.wall_ms,
            accel_ms: m.accel_ms,
            rays: m.report.total_rays(),
            in_band: band.contains(m.report.tp_ms),
            flip: None,
            display: None,
            speed_mean: m.speed.mean_deg_s,
            speed_p95: m.speed.p95_deg_s,
            target_ms: None,
            predicted_ms: None,
            decision: None,
        }
    }

    /// The row with the controller's side of the frame: the prediction it chose the
    /// frame's quality by (`predicted_ms`, from its decision before the frame) and what it
    /// decided after it (`after`).
    pub fn with_decision(self, predicted_ms: Option<f64>, after: Option<&Decision>) -> Self {
        Self {
            predicted_ms,
            decision: after.map(|d| (d.action, d.reason)),
            ..self
        }
    }
}

/// One controller's whole sweep and its figures.
#[derive(Clone, Debug)]
pub struct ControllerRun {
    /// The name in reports, e.g. `predictive` or `fixed(R=16)`.
    pub name: String,
    /// The band it ran in.
    pub band: Band,
    /// One row per counted frame.
    pub rows: Vec<FrameRow>,
    /// The run's figures.
    pub summary: RunSummary,
    /// Mean and 95th percentile of the measured frames' FLIP (`bench --quality`).
    pub flip: Option<(f64, f64)>,
    /// Every counted frame's picture at its rendered size (`bench --record`), in order.
    pub recorded: Vec<Rgb8Image>,
    /// What the viewer saw (real clock only).
    pub display: Option<DisplayRun>,
    /// Whether the controller handed its frames a time budget
    /// (`steadyray_control::FrameBudget`): their times were decided inside each frame.
    pub budgeted: bool,
}

impl ControllerRun {
    /// The most frames any one planned frame time could have kept in the run's band
    /// against the run's own prediction errors (each frame's Tp over the prediction its
    /// quality was chosen by; see [`aim_ceiling()`]): what separates the controller's misses
    /// from the machine's. `None` for a run without predictions, and for one whose
    /// controller chose a frame time of its own each frame (`perceptual`), which no single
    /// planned time describes, or whose frames ran within a time budget, whose times the
    /// renderer decided inside the frame and the plan no longer predicts.
    pub fn aim_ceiling(&self) -> Option<AimCeiling> {
        if self.budgeted || self.rows.iter().any(|r| r.target_ms.is_some()) {
            return None;
        }
        let ratios = self
            .rows
            .iter()
            .filter_map(|r| r.predicted_ms.map(|p| r.tp_ms / p));
        aim_ceiling(ratios, self.band)
    }
}

/// A run's name as a file name: letters, digits, `-`, `_`, `.`, `=` kept, others `_`.
pub fn safe_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.=".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes `frames.csv`: one row per frame and controller. The display columns (`start_ms`,
/// `hand_over_ms`, `visible_ms`: the frame's way to the screen, ms of display time) are empty
/// under the frame clock; `speed_mean` and `speed_p95` are the frame's motion on screen (deg/s),
/// `target_ms` the frame time `perceptual` aimed it at (empty for other controllers),
/// `warp_ms` the warps made while the frame rendered (`--warp`; the display's time for the
/// frame is `tp_ms + warp_ms`), `predicted_ms` the controller's prediction of the frame's Tp
/// and `decision` what it decided after the frame (`action:reason`; both empty for
/// controllers that do not say).
pub fn write_frames_csv(runs: &[ControllerRun], path: &Path) -> Result<()> {
    write_csv(
        path,
        "controller,frame,angle,spp,depth,scale,tp_ms,wall_ms,accel_ms,rays,in_band,flip,t_s,start_ms,hand_over_ms,visible_ms,speed_mean,speed_p95,target_ms,warp_ms,predicted_ms,decision",
        |out| write_frame_rows(runs, out),
    )
}

/// The rows of `frames.csv`.
fn write_frame_rows(runs: &[ControllerRun], out: &mut dyn Write) -> std::io::Result<()> {
    for run in runs {
        for r in &run.rows {
            let display = r.display.map_or_else(
                || ",,".to_string(),
                |d| {
                    format!(
                        "{:.4},{:.4},{:.4}",
                        d.start_ms, d.hand_over_ms, d.visible_ms
                    )
                },
            );
            writeln!(
                out,
                "{},{},{:.6},{},{},{},{:.4},{:.4},{:.4},{},{},{},{:.6},{},{:.3},{:.3},{},{:.4},{},{}",
                run.name,
                r.frame,
                r.angle,
                r.spp,
                r.depth,
                r.scale,
                r.tp_ms,
                r.wall_ms,
                r.accel_ms,
                r.rays,
                u8::from(r.in_band),
                r.flip.map_or_else(String::new, |f| format!("{f:.6}")),
                r.t_s,
                display,
                r.speed_mean,
                r.speed_p95,
                r.target_ms.map_or_else(String::new, |t| format!("{t:.4}")),
                r.warp_ms,
                r.predicted_ms
                    .map_or_else(String::new, |t| format!("{t:.4}")),
                r.decision.map_or_else(String::new, |(a, why)| format!(
                    "{}:{}",
                    a.name(),
                    why.name()
                )),
            )?;
        }
    }
    Ok(())
}

/// Writes `displayed.csv` (`bench --clock real --quality`): one row per sampled refresh and
/// controller, the scores whose means and p95 the summary gives, so that their distribution
/// over the run can be read. `refresh` is the refresh's number (at refresh · P), `frame` the
/// frame on screen (empty: the last warm-up frame), `warped` 1 where the refresh showed it
/// warped to its own time, `world_s` the world time the screen shows; `flip` is the screen
/// against the world at the refresh, `frame_flip` against the world at `world_s`, `age_flip`
/// the two worlds against each other.
pub fn write_displayed_csv(runs: &[ControllerRun], path: &Path) -> Result<()> {
    write_csv(
        path,
        "controller,refresh,time_s,frame,warped,world_s,flip,frame_flip,age_flip",
        |out| write_displayed_rows(runs, out),
    )
}

/// The rows of `displayed.csv`.
fn write_displayed_rows(runs: &[ControllerRun], out: &mut dyn Write) -> std::io::Result<()> {
    for run in runs {
        let Some(quality) = run.display.as_ref().and_then(|d| d.quality.as_ref()) else {
            continue;
        };
        for s in &quality.scored {
            let at = s.sample;
            writeln!(
                out,
                "{},{},{:.6},{},{},{:.6},{:.6},{:.6},{:.6}",
                run.name,
                at.index,
                at.time_s,
                at.frame.map_or_else(String::new, |f| f.to_string()),
                u8::from(at.warped),
                at.world_s,
                s.flip,
                s.frame_flip,
                s.age_flip,
            )?;
        }
    }
    Ok(())
}

/// Writes the CSV file `path`: its `header` line, then the rows `rows` writes.
fn write_csv(
    path: &Path,
    header: &str,
    rows: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let mut out = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?,
    );
    writeln!(out, "{header}")
        .and_then(|()| rows(&mut out))
        .and_then(|()| out.flush())
        .with_context(|| format!("cannot write {}", path.display()))
}
