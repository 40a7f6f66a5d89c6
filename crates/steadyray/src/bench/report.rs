//! The terminal table and `summary.json`.

use super::machine::Machine;
use super::record::ControllerRun;
use anyhow::{Context, Result};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use steadyray_control::{Bounds, Quality, RunSummary};

/// The paper's reported figures, for comparison in every report.
pub const PAPER_IN_BAND_FIXED_PCT: f64 = 8.7;
pub const PAPER_IN_BAND_CONTROLLED_PCT: f64 = 93.9;

/// Everything `summary.json` holds besides the per-controller figures.
#[derive(Debug, Serialize)]
pub struct RunContext {
    pub scene: String,
    pub backend: String,
    pub device: String,
    pub machine: Machine,
    pub resolution: [u32; 2],
    pub band_ms: [f64; 2],
    pub frames: u32,
    pub warmup: u32,
    pub bounds: String,
    pub start: String,
    pub git_revision: String,
}

#[derive(Serialize)]
struct ControllerEntry<'a> {
    name: &'a str,
    #[serde(flatten)]
    summary: &'a RunSummary,
    /// Mean FLIP of the measured frames (`bench --quality`).
    #[serde(skip_serializing_if = "Option::is_none")]
    flip_mean: Option<f64>,
    /// 95th percentile of the measured frames' FLIP.
    #[serde(skip_serializing_if = "Option::is_none")]
    flip_p95: Option<f64>,
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

/// Writes `summary.json`.
pub fn write_summary(context: &RunContext, runs: &[ControllerRun], path: &Path) -> Result<()> {
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
                summary: &r.summary,
                flip_mean: r.flip.map(|f| f.0),
                flip_p95: r.flip.map(|f| f.1),
            })
            .collect(),
    };
    let text = serde_json::to_string_pretty(&summary)?;
    std::fs::write(path, text + "\n").with_context(|| format!("cannot write {}", path.display()))
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
        "{:<name_width$} {:>7} {:>6} {:>6} {:>8} {:>7} {:>6} {:>7} {:>7} {:>7} {:>7} {:>8} {:>8} {:>6} {:>5} {:>5} {:>8} {:>6} {:>6}",
        "controller",
        "in_band",
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
        let _ = writeln!(
            out,
            "{:<name_width$} {:>6.1}% {:>5.1}% {:>5.1}% {:>7.1}% {:>7.2} {:>6.2} {:>7.2} {:>7.2} {:>7.2} {:>7.2} {:>8.2} {:>8} {:>6} {:>5.2} {:>5.2} {:>8.1} {:>6} {:>6}",
            r.name,
            s.in_band_pct,
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
