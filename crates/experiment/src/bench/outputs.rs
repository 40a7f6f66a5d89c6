//! The bench's outputs: `frames.csv`, `displayed.csv` (real clock with `--quality`),
//! `summary.json`, the table (and `table.md` under the real clock) and the frame-time plots.

use super::BenchConfig;
use super::arms::Bands;
use super::machine;
use super::plan::Plan;
use super::plot;
use super::real_clock::RealSweep;
use super::record::{self, ControllerRun};
use super::report::{self, RealContext, RunContext};
use super::screen_quality::Described;
use anyhow::{Context, Result};
use steadyray_control::Quality;
use steadyray_display::ViewingSetup;

/// Everything `summary.json` says of the bench besides its runs.
pub fn run_context(
    config: &BenchConfig,
    plan: &Plan,
    bands: &Bands,
    real: Option<&RealSweep>,
    described: Described,
    reference_quality: Quality,
) -> RunContext {
    let band = bands.band;
    RunContext {
        scene: described.scene,
        backend: described.backend,
        device: described.device,
        machine: machine::Machine::detect(),
        resolution: [described.resolution.0, described.resolution.1],
        band_ms: [band.tmin_ms(), band.tmax_ms()],
        frames: config.frames,
        warmup: config.warmup,
        bounds: plan.bounds.to_string(),
        start: plan.start.to_string(),
        git_revision: machine::git_revision(),
        clock: if real.is_some() { "real" } else { "frames" },
        temporal: config.temporal,
        real: real.map(|r| RealContext {
            duration_s: r.duration_s,
            display: r.display,
            viewing: ViewingSetup::standard_fhd(),
            reference: (config.quality || config.video.is_some())
                .then(|| reference_quality.to_string()),
            every: config.quality.then_some(config.every),
            aligned_band: bands.aligned,
            warp: config.warp,
        }),
    }
}

/// Writes the bench's outputs into `config.out` and prints its table.
pub fn write_outputs(
    config: &BenchConfig,
    context: &RunContext,
    runs: &[ControllerRun],
    bands: &Bands,
) -> Result<()> {
    let out = &config.out;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let real = context.real.is_some();
    record::write_frames_csv(runs, &out.join("frames.csv"))?;
    let displayed_csv = real && config.quality;
    if displayed_csv {
        record::write_displayed_csv(runs, &out.join("displayed.csv"))?;
    }
    let summary = report::write_summary(context, runs, &out.join("summary.json"))?;
    if real {
        let controllers = summary["controllers"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let table = report::display_table(&controllers);
        print!("{table}");
        let path = out.join("table.md");
        std::fs::write(&path, &table)
            .with_context(|| format!("cannot write {}", path.display()))?;
    } else {
        print!("{}", report::table(runs));
        println!(
            "paper (GeForce 6800GT, 2005): {:.1} % in band without control, {:.1} % with step control",
            report::PAPER_IN_BAND_FIXED_PCT,
            report::PAPER_IN_BAND_CONTROLLED_PCT
        );
    }
    let band = bands.band;
    plot::write_plots(
        runs,
        (band.tmin_ms(), band.tmax_ms()),
        &out.join("frametime.png"),
        &out.join("frametime.svg"),
    )?;
    eprintln!(
        "bench: wrote frames.csv{}, summary.json{}, frametime.png and frametime.svg to {}",
        if displayed_csv { ", displayed.csv" } else { "" },
        if real { ", table.md" } else { "" },
        out.display()
    );
    Ok(())
}
