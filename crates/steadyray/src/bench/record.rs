//! What the experiment records: one row per frame, one run per controller.

use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;
use steadyray_control::metrics::RunSummary;
use steadyray_quality::Rgb8Image;

/// One counted frame of one controller's sweep (a row of `frames.csv`).
#[derive(Clone, Debug, PartialEq)]
pub struct FrameRow {
    pub frame: u32,
    /// Camera yaw in radians.
    pub angle: f32,
    pub spp: f32,
    pub depth: u32,
    pub scale: f32,
    /// Tp, the render time, ms.
    pub tp_ms: f64,
    /// Host wall time of the render call, ms.
    pub wall_ms: f64,
    /// Rays traced (every depth and shadow rays).
    pub rays: u64,
    pub in_band: bool,
    /// Mean FLIP against the reference, for the frames `bench --quality` measured.
    pub flip: Option<f64>,
}

/// One controller's whole sweep and its figures.
#[derive(Clone, Debug)]
pub struct ControllerRun {
    /// The name in reports, e.g. `predictive` or `fixed(R=16)`.
    pub name: String,
    pub rows: Vec<FrameRow>,
    pub summary: RunSummary,
    /// Mean and 95th percentile of the measured frames' FLIP (`bench --quality`).
    pub flip: Option<(f64, f64)>,
    /// Every counted frame's picture at its rendered size (`bench --record`), in order.
    pub recorded: Vec<Rgb8Image>,
}

/// Writes `frames.csv`: one row per frame and controller.
pub fn write_frames_csv(runs: &[ControllerRun], path: &Path) -> Result<()> {
    let mut out = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?,
    );
    writeln!(
        out,
        "controller,frame,angle,spp,depth,scale,tp_ms,wall_ms,rays,in_band,flip"
    )?;
    for run in runs {
        for r in &run.rows {
            writeln!(
                out,
                "{},{},{:.6},{},{},{},{:.4},{:.4},{},{},{}",
                run.name,
                r.frame,
                r.angle,
                r.spp,
                r.depth,
                r.scale,
                r.tp_ms,
                r.wall_ms,
                r.rays,
                u8::from(r.in_band),
                r.flip.map_or_else(String::new, |f| format!("{f:.6}"))
            )?;
        }
    }
    out.flush()
        .with_context(|| format!("cannot write {}", path.display()))
}
