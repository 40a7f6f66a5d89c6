//! Runs the suite's cells: each a real-clock bench of one method on one scene, in the cell's
//! own folder.

use crate::bench::{self, BenchConfig};
use crate::calibrate::{self, CalibrateConfig};
use crate::calibrate_motion::{JodTool, prune_video, score_with_jod};
use anyhow::{Context, Result, anyhow, bail};
use serde_json::Value;
use std::path::{Path, PathBuf};
use steadyray_suite::run::CellEvent;
use steadyray_suite::{Cell, CellResult, CellRunner, Plan, Shard, SuiteScene, run_cells};

/// How the suite turns command-line flags into the library's configurations: the binary
/// parses them with the same parser as `steadyray bench` and `steadyray calibrate`, so a
/// method's flags mean exactly what they mean on the command line, defaults included.
pub trait SuiteCommands {
    /// The bench configuration of `bench` with `flags`.
    fn bench(&self, flags: &[String]) -> Result<BenchConfig>;
    /// The calibration configuration of `calibrate` with `flags`.
    fn calibrate(&self, flags: &[String]) -> Result<CalibrateConfig>;
}

/// What `suite run` runs, and how.
#[derive(Clone, Debug)]
pub struct SuiteConfig {
    /// The plan (scenes, methods, runs).
    pub plan: Plan,
    /// Which slice of the cells this process runs.
    pub shard: Shard,
    /// The suite's folder: cells, models, table.
    pub out: PathBuf,
    /// Bench flags every cell shares (backend, size, display, …), after the suite's own.
    pub common: Vec<String>,
    /// Seconds of display time each cell shows.
    pub duration_s: f64,
    /// The displayed quality scores the screen at one refresh in this many (`--every`).
    pub every: u32,
    /// The JOD tool, where it is installed: cells then write videos and are scored by JOD.
    pub jod: Option<JodTool>,
}

/// Runs the cells of `config.plan` that `config.shard` takes and that have not finished,
/// printing a line per cell; a killed run resumes where it stopped.
pub fn run(config: &SuiteConfig, commands: &dyn SuiteCommands) -> Result<()> {
    let mut runner = BenchCells { config, commands };
    let start = std::time::Instant::now();
    let mut progress = |cell: &Cell, i: usize, n: usize, event: &CellEvent| match event {
        CellEvent::AlreadyDone => eprintln!("suite: [{}/{n}] {} done before", i + 1, cell.id()),
        CellEvent::Starting => eprintln!("suite: [{}/{n}] {} ...", i + 1, cell.id()),
        CellEvent::Done(s) => eprintln!("suite: [{}/{n}] {} took {s:.0} s", i + 1, cell.id()),
    };
    let report = run_cells(
        &config.plan,
        config.shard,
        &config.out,
        &mut runner,
        &mut progress,
    )?;
    eprintln!(
        "suite: shard {} ran {} cells in {:.0} s ({} were done before; {:.0} s in all with \
         calibration); `steadyray suite table {}` joins the results",
        config.shard,
        report.ran.len(),
        report.seconds,
        report.already_done,
        start.elapsed().as_secs_f64(),
        config.out.display()
    );
    Ok(())
}

/// The suite's cell runner: a bench of the cell's method on its scene.
struct BenchCells<'a> {
    config: &'a SuiteConfig,
    commands: &'a dyn SuiteCommands,
}

impl CellRunner for BenchCells<'_> {
    fn run(&mut self, plan: &Plan, cell: &Cell, dir: &Path) -> Result<CellResult, String> {
        self.run_cell(plan, cell, dir).map_err(|e| format!("{e:#}"))
    }
}

impl BenchCells<'_> {
    fn run_cell(&self, plan: &Plan, cell: &Cell, dir: &Path) -> Result<CellResult> {
        let scene = plan
            .scene(&cell.scene)
            .context("the cell's scene is not in the plan")?;
        let method = plan
            .method(&cell.method)
            .context("the cell's method is not in the plan")?;
        let mut flags = scene_flags(scene);
        flags.extend(self.cell_flags(dir));
        flags.extend(self.config.common.iter().cloned());
        if method.needs_motion_model() {
            let model = self.motion_model(scene)?;
            flags.extend(method.flags_with_model(&model.display().to_string()));
        } else {
            flags.extend(method.flags.iter().cloned());
        }
        let bench_config = self.commands.bench(&flags)?;
        bench::run(&bench_config).with_context(|| format!("bench {}", flags.join(" ")))?;
        if let Some(tool) = &self.config.jod {
            self.score(tool, dir)?;
        }
        read_result(cell, &dir.join("summary.json"))
    }

    /// The suite's own bench flags: the real clock, the displayed quality at one refresh in
    /// `every`, the references shared by every cell (`<suite>/references`: each rendered
    /// once), the cell's folder and, with the JOD tool, the videos.
    fn cell_flags(&self, dir: &Path) -> Vec<String> {
        let mut flags: Vec<String> = [
            "--clock",
            "real",
            "--duration",
            &self.config.duration_s.to_string(),
            "--quality",
            "--every",
            &self.config.every.to_string(),
            "--references",
            &self.config.out.join("references").display().to_string(),
            "--out",
            &dir.display().to_string(),
        ]
        .map(str::to_string)
        .to_vec();
        if self.config.jod.is_some() {
            flags.push("--video".into());
            flags.push(dir.join("video").display().to_string());
        }
        flags
    }

    /// Scores the cell's video by JOD and merges the score into its summary.
    fn score(&self, tool: &JodTool, dir: &Path) -> Result<()> {
        let video = dir.join("video");
        let summary = read_json(&dir.join("summary.json"))?;
        let runs: Vec<String> = summary["controllers"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|c| c["name"].as_str().map(str::to_string))
            .collect();
        let scores = score_with_jod(tool, &video, &runs)?;
        crate::jod::merge(&video.join("jod.json"), &dir.join("summary.json"))?;
        if !tool.keep_video {
            prune_video(&video)?;
        }
        eprintln!("suite: JOD {scores:?}");
        Ok(())
    }

    /// The scene's calibrated `perceptual` model, for the methods that need one
    /// (`perceptual-scene`; `perceptual` uses its shipped model): calibrated once and kept
    /// under `models/<scene>/` (a ladder, then the motion model on its points).
    fn motion_model(&self, scene: &SuiteScene) -> Result<PathBuf> {
        let dir = self.config.out.join("models").join(&scene.name);
        let (ladder, model) = (dir.join("ladder.json"), dir.join("motion.json"));
        if model.exists() {
            return Ok(model);
        }
        std::fs::create_dir_all(&dir).with_context(|| dir.display().to_string())?;
        let size = size_flags(&self.config.common);
        let path = |p: &Path| p.display().to_string();
        if !ladder.exists() {
            let mut flags = scene_flags(scene);
            flags.extend(size.clone());
            flags.extend(["-o".into(), path(&ladder)]);
            eprintln!("suite: calibrating {}'s ladder", scene.name);
            calibrate::run(&self.commands.calibrate(&flags)?)?;
        }
        let mut flags = scene_flags(scene);
        flags.extend(size);
        flags.extend(["--motion".into(), "--ladder".into(), path(&ladder)]);
        flags.extend(["-o".into(), path(&model)]);
        eprintln!("suite: calibrating {}'s motion model", scene.name);
        calibrate::run(&self.commands.calibrate(&flags)?)?;
        Ok(model)
    }
}

/// `--scene` and `--path` of a suite scene.
fn scene_flags(scene: &SuiteScene) -> Vec<String> {
    let mut flags = vec!["--scene".to_string(), scene.scene.clone()];
    if let Some(path) = &scene.path {
        flags.extend(["--path".to_string(), path.clone()]);
    }
    flags
}

/// The `--backend`, `--width` and `--height` flags (with their values) of `common`, which
/// the calibrations must share with the cells.
fn size_flags(common: &[String]) -> Vec<String> {
    let mut flags = Vec::new();
    let mut items = common.iter();
    while let Some(flag) = items.next() {
        if ["--backend", "--width", "--height"].contains(&flag.as_str()) {
            flags.push(flag.clone());
            flags.extend(items.next().cloned());
        }
    }
    flags
}

fn read_json(path: &Path) -> Result<Value> {
    let text = std::fs::read_to_string(path).with_context(|| path.display().to_string())?;
    serde_json::from_str(&text).with_context(|| format!("{} is not JSON", path.display()))
}

/// The cell's result from its bench's `summary.json`: its one run's displayed FLIP, frames
/// shown per second, share in the band and (once merged) JOD.
fn read_result(cell: &Cell, summary: &Path) -> Result<CellResult> {
    let value = read_json(summary)?;
    let runs = value["controllers"]
        .as_array()
        .filter(|r| !r.is_empty())
        .ok_or_else(|| anyhow!("{} has no runs", summary.display()))?;
    if runs.len() != 1 {
        bail!(
            "{} has {} runs: a suite method runs one controller",
            summary.display(),
            runs.len()
        );
    }
    let run = &runs[0];
    let number = |key: &str| {
        run[key]
            .as_f64()
            .ok_or_else(|| anyhow!("{} lacks `{key}`", summary.display()))
    };
    Ok(CellResult {
        cell: cell.clone(),
        displayed_flip: number("displayed_flip_mean")?,
        jod: run["jod"].as_f64(),
        displayed_fps: number("displayed_fps")?,
        in_band_pct: number("in_band_pct")?,
        seconds: 0.0,
    })
}
