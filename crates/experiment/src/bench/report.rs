//! The terminal table and `summary.json`.

use super::machine::Machine;
use super::record::ControllerRun;
use super::screen::WarpFigures;
use anyhow::{Context, Result};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use steadyray_control::{Bounds, Quality, RunSummary};
use steadyray_display::{DisplayConfig, DisplayFigures, ViewingSetup};

/// The paper's reported figures, for comparison in every report.
pub const PAPER_IN_BAND_FIXED_PCT: f64 = 8.7;
/// The paper's in-band share with step control, %.
pub const PAPER_IN_BAND_CONTROLLED_PCT: f64 = 93.9;

/// Everything `summary.json` holds besides the per-controller figures.
#[derive(Debug, Serialize)]
pub struct RunContext {
    /// The scene's name.
    pub scene: String,
    /// The backend.
    pub backend: String,
    /// The device.
    pub device: String,
    /// The machine the bench ran on.
    pub machine: Machine,
    /// Full-scale image size.
    pub resolution: [u32; 2],
    /// The band, ms.
    pub band_ms: [f64; 2],
    /// Frames in the sweep.
    pub frames: u32,
    /// Warm-up frames per run.
    pub warmup: u32,
    /// The quality bounds, as text.
    pub bounds: String,
    /// The start quality, as text.
    pub start: String,
    /// The source revision.
    pub git_revision: String,
    /// `frames` or `real`.
    pub clock: &'static str,
    /// Which runs used the temporal mode (`off`, `on` or `both`; those that did are
    /// labelled "+temporal").
    pub temporal: crate::config::TemporalChoice,
    /// The real clock's display and viewing set-up.
    #[serde(flatten)]
    pub real: Option<RealContext>,
}

/// What a real-clock run adds to `summary.json`'s context.
#[derive(Debug, Serialize)]
pub struct RealContext {
    /// Display time per run, s.
    pub duration_s: f64,
    /// The display model.
    pub display: DisplayConfig,
    /// The viewing set-up of displayed FLIP and JOD.
    pub viewing: ViewingSetup,
    /// The references' quality, when there are references.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<String>,
    /// Displayed FLIP measures refreshes 0, K, 2K, ...
    #[serde(skip_serializing_if = "Option::is_none")]
    pub every: Option<u32>,
    /// How `--band refresh` derived the band.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aligned_band: Option<AlignedBand>,
    /// Whether the temporal runs warped their refreshes without a new frame (`--warp`).
    pub warp: bool,
}

/// A band derived from the display (`--band refresh[:M]`).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct AlignedBand {
    /// Frames shown every this many refreshes.
    pub refreshes: u32,
    /// The measured hand-over the band leaves room for, ms.
    pub hand_over_ms: f64,
    /// The measured warped refresh the band leaves room for after each frame, once per
    /// refresh between two frames, ms (0 without --warp or at one refresh a frame).
    pub warp_ms: f64,
    /// The band of the runs without the history (`--temporal both`), which show no warps
    /// and so leave no room for them; absent where it is `band_ms`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plain_band_ms: Option<[f64; 2]>,
}

#[derive(Serialize)]
struct ControllerEntry<'a> {
    name: &'a str,
    /// The band the run held, ms.
    band_ms: [f64; 2],
    #[serde(flatten)]
    summary: &'a RunSummary,
    /// Mean FLIP of the measured frames (`bench --quality`).
    #[serde(skip_serializing_if = "Option::is_none")]
    flip_mean: Option<f64>,
    /// 95th percentile of the measured frames' FLIP.
    #[serde(skip_serializing_if = "Option::is_none")]
    flip_p95: Option<f64>,
    /// The most frames any one planned frame time could have kept in the band against
    /// the run's prediction errors, % (controllers that predict; `ControllerRun::aim_ceiling`).
    #[serde(skip_serializing_if = "Option::is_none")]
    aim_ceiling_pct: Option<f64>,
    /// What the viewer saw (real clock).
    #[serde(flatten)]
    display: Option<&'a DisplayFigures>,
    /// The frames' share of the run's wall time, % (real clock): how busy the bench kept
    /// the renderer.
    #[serde(skip_serializing_if = "Option::is_none")]
    busy_pct: Option<f64>,
    /// The refreshes warped (real clock, `--warp`, the runs that warped).
    #[serde(flatten)]
    warps: Option<WarpFigures>,
    /// The screen against the world at each sampled refresh (real clock, `--quality`).
    #[serde(flatten)]
    displayed: Option<DisplayedEntry>,
    /// The motion on screen and the frame times a controller chose.
    #[serde(flatten)]
    motion: MotionEntry,
}

/// The motion on screen over a run, and the targets of a controller that chooses its frame
/// time (`perceptual`).
#[derive(Serialize)]
struct MotionEntry {
    /// Mean over the frames of their mean motion on screen, deg/s.
    speed_mean_deg_s: f64,
    /// Mean target frame time over the frames, ms.
    #[serde(skip_serializing_if = "Option::is_none")]
    target_ms_mean: Option<f64>,
    /// How often the target changed.
    #[serde(skip_serializing_if = "Option::is_none")]
    target_changes: Option<usize>,
}

impl MotionEntry {
    fn of(run: &ControllerRun) -> Self {
        let rows = &run.rows;
        let n = rows.len().max(1) as f64;
        let targets: Vec<f64> = rows.iter().filter_map(|r| r.target_ms).collect();
        let targeted = !targets.is_empty();
        Self {
            speed_mean_deg_s: rows.iter().map(|r| r.speed_mean).sum::<f64>() / n,
            target_ms_mean: targeted.then(|| targets.iter().sum::<f64>() / targets.len() as f64),
            target_changes: targeted.then(|| targets.windows(2).filter(|w| w[0] != w[1]).count()),
        }
    }
}

/// The displayed quality's figures in `summary.json`.
#[derive(Serialize)]
struct DisplayedEntry {
    /// Mean FLIP of the screen against the world at the refresh.
    displayed_flip_mean: f64,
    displayed_flip_p95: f64,
    /// Mean FLIP of the screen against the world at its frame's own time.
    frame_flip_mean: f64,
    /// Mean FLIP of the world at its frame's time against the world at the refresh: what
    /// the screen's age alone costs.
    age_flip_mean: f64,
    /// Mean age of the world on screen at the sampled refreshes, ms.
    screen_age_ms_mean: f64,
    /// Refreshes measured.
    displayed_samples: usize,
}

#[derive(Serialize)]
struct Summary<'a> {
    #[serde(flatten)]
    context: &'a RunContext,
    paper_in_band_pct: PaperFigures,
    controllers: Vec<ControllerEntry<'a>>,
}

#[derive(Serialize)]
struct PaperFigures {
    without_control: f64,
    with_control: f64,
}

/// Writes `summary.json` and returns what it wrote.
pub fn write_summary(
    context: &RunContext,
    runs: &[ControllerRun],
    path: &Path,
) -> Result<serde_json::Value> {
    let summary = Summary {
        context,
        paper_in_band_pct: PaperFigures {
            without_control: PAPER_IN_BAND_FIXED_PCT,
            with_control: PAPER_IN_BAND_CONTROLLED_PCT,
        },
        controllers: runs
            .iter()
            .map(|r| ControllerEntry {
                name: &r.name,
                band_ms: [r.band.tmin_ms(), r.band.tmax_ms()],
                summary: &r.summary,
                flip_mean: r.flip.map(|f| f.0),
                flip_p95: r.flip.map(|f| f.1),
                aim_ceiling_pct: r.aim_ceiling().map(|c| c.in_band_pct),
                display: r.display.as_ref().map(|d| &d.figures),
                busy_pct: r.display.as_ref().and_then(|d| d.busy_pct),
                warps: r
                    .display
                    .as_ref()
                    .filter(|d| !d.warps.shown.is_empty() || d.warps.missed > 0)
                    .map(|d| d.warps.figures()),
                displayed: r
                    .display
                    .as_ref()
                    .and_then(|d| d.quality.as_ref())
                    .map(|q| DisplayedEntry {
                        displayed_flip_mean: q.flip_mean,
                        displayed_flip_p95: q.flip_p95,
                        frame_flip_mean: q.frame_flip_mean,
                        age_flip_mean: q.age_flip_mean,
                        screen_age_ms_mean: q.age_ms_mean,
                        displayed_samples: q.scored.len(),
                    }),
                motion: MotionEntry::of(r),
            })
            .collect(),
    };
    let value = serde_json::to_value(&summary)?;
    write_json(&value, path)?;
    Ok(value)
}

/// Writes `value` as pretty JSON under a temporary name, then renames it over `path`.
pub fn write_json(value: &serde_json::Value, path: &Path) -> Result<()> {
    let temp = path.with_extension("json.partial");
    let text = serde_json::to_string_pretty(value)? + "\n";
    std::fs::write(&temp, text).with_context(|| format!("cannot write {}", temp.display()))?;
    std::fs::rename(&temp, path).with_context(|| format!("cannot write {}", path.display()))
}

/// The real clock's table, one column per figure: header, `summary.json` key, decimals.
pub const DISPLAY_COLUMNS: [(&str, &str, usize); 13] = [
    ("frames", "frames_rendered", 0),
    ("shown fps", "displayed_fps", 1),
    ("repeated %", "repeated_pct", 1),
    ("pacing std ms", "pacing_std_ms", 2),
    ("latency ms", "latency_ms_mean", 1),
    ("latency p95", "latency_ms_p95", 1),
    ("Tp in band %", "in_band_pct", 1),
    ("S", "mean_spp", 2),
    ("R", "mean_depth", 1),
    ("scale", "mean_scale", 2),
    ("displayed FLIP", "displayed_flip_mean", 4),
    ("FLIP p95", "displayed_flip_p95", 4),
    ("JOD", "jod", 2),
];

/// The real clock's table (Markdown) from `summary.json`'s controllers: what the viewer saw,
/// with JOD once `steadyray jod merge` has added it; a missing figure shows as `-`.
pub fn display_table(controllers: &[serde_json::Value]) -> String {
    let mut out = String::from("| controller |");
    for (header, _, _) in DISPLAY_COLUMNS {
        let _ = write!(out, " {header} |");
    }
    out.push_str("\n|---|");
    out.push_str(&"---|".repeat(DISPLAY_COLUMNS.len()));
    out.push('\n');
    for c in controllers {
        let name = c.get("name").and_then(|n| n.as_str()).unwrap_or("?");
        let _ = write!(out, "| {name} |");
        for (_, key, decimals) in DISPLAY_COLUMNS {
            match c.get(key).and_then(serde_json::Value::as_f64) {
                Some(v) => {
                    let _ = write!(out, " {v:.decimals$} |");
                }
                None => out.push_str(" - |"),
            }
        }
        out.push('\n');
    }
    out
}

/// The table printed on the terminal: one row per controller.
pub fn table(runs: &[ControllerRun]) -> String {
    let name_width = runs
        .iter()
        .map(|r| r.name.len())
        .max()
        .unwrap_or(10)
        .max(10);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<name_width$} {:>7} {:>7} {:>6} {:>6} {:>8} {:>7} {:>6} {:>7} {:>7} {:>7} {:>7} {:>8} {:>8} {:>6} {:>5} {:>5} {:>8} {:>6} {:>6}",
        "controller",
        "in_band",
        "ceiling",
        "over",
        "under",
        "u@max",
        "tp_mean",
        "tp_std",
        "tp_p50",
        "tp_p95",
        "tp_p99",
        "tp_max",
        "rev/100",
        "max_over",
        "settle",
        "S",
        "R",
        "Mrays/s",
        "flip",
        "flip95",
    );
    for r in runs {
        let s = &r.summary;
        let settle = s
            .settle_max
            .map_or_else(|| "-".to_string(), |m| m.to_string());
        let (flip, flip95) = r.flip.map_or_else(
            || ("-".to_string(), "-".to_string()),
            |(mean, p95)| (format!("{mean:.4}"), format!("{p95:.4}")),
        );
        let ceiling = r
            .aim_ceiling()
            .map_or_else(|| "-".to_string(), |c| format!("{:.1}%", c.in_band_pct));
        let _ = writeln!(
            out,
            "{:<name_width$} {:>6.1}% {:>7} {:>5.1}% {:>5.1}% {:>7.1}% {:>7.2} {:>6.2} {:>7.2} {:>7.2} {:>7.2} {:>7.2} {:>8.2} {:>8} {:>6} {:>5.2} {:>5.2} {:>8.1} {:>6} {:>6}",
            r.name,
            s.in_band_pct,
            ceiling,
            s.over_pct,
            s.under_pct,
            s.under_at_max_pct,
            s.tp_mean,
            s.tp_std,
            s.tp_p50,
            s.tp_p95,
            s.tp_p99,
            s.tp_max,
            s.reversals_per_100,
            s.longest_over_run,
            settle,
            s.mean_spp,
            s.mean_depth,
            s.rays_per_s / 1e6,
            flip,
            flip95,
        );
    }
    out
}

/// A short label for a fixed quality, e.g. `S=2 R=5` (with the scale when not full).
pub fn quality_label(q: &Quality, bounds: &Bounds) -> String {
    let mut label = format!("S={} R={}", q.spp, q.depth);
    if q.scale != bounds.scale_max {
        let _ = write!(label, " x{}", q.scale);
    }
    label
}
