//! `steadyray suite`: the scene suite's command line (`docs/scene-suite.md`), and how a
//! method's bench flags become the library's configurations (the same parser as `bench`'s
//! and `calibrate`'s, so a flag means the same everywhere).

use super::experiment::{BenchArgs, CalibrateArgs};
use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use steadyray_experiment::bench::BenchConfig;
use steadyray_experiment::calibrate::CalibrateConfig;
use steadyray_experiment::calibrate_motion::JodTool;
use steadyray_experiment::suite::{SuiteCommands, SuiteConfig};
use steadyray_suite::{Plan, Shard};

/// `steadyray suite run` and `steadyray suite table`.
#[derive(Debug, Args)]
pub struct SuiteArgs {
    #[command(subcommand)]
    pub command: SuiteCommand,
}

/// The suite's two steps.
#[derive(Debug, Subcommand)]
pub enum SuiteCommand {
    /// Run the suite's cells (every method on every scene, --runs times) on the real clock,
    /// each a bench in a folder of its own: resumable (finished cells are not redone), and
    /// --shard I/N runs one slice for a batch system.
    Run(SuiteRunArgs),
    /// Join the finished cells of one or more suite folders into table.md, table.json and
    /// suite.png/svg: each method's median and range per scene, its rank and mean rank.
    Table(SuiteTableArgs),
}

/// `suite run`.
#[derive(Debug, Args)]
pub struct SuiteRunArgs {
    /// The suite's folder.
    #[arg(short = 'o', long = "out", default_value = "results/suite")]
    pub out: PathBuf,
    /// Runs of each method on each scene (K).
    #[arg(long, default_value_t = 3)]
    pub runs: u32,
    /// The slice of the cells to run, I/N (e.g. a Slurm array task's index and count).
    #[arg(long, default_value = "1/1")]
    pub shard: Shard,
    /// Only these scenes (comma separated; default: all six).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Only these methods (comma separated; default: all).
    #[arg(long, value_delimiter = ',')]
    pub methods: Vec<String>,
    /// Seconds of display time each cell shows: the default is the whole `pans` path (holds,
    /// slow pans and fast turns); a shorter span keeps JOD affordable but shows only the
    /// path's start (3 s: a hold and a slow pan, no fast turn).
    #[arg(long, default_value_t = 8.0)]
    pub duration: f64,
    /// The displayed quality scores the screen at one refresh in this many.
    #[arg(long, default_value_t = 2)]
    pub every: u32,
    /// Score each cell's video by JOD with this Python (one with scripts/jod/requirements.txt
    /// installed); without it the table ranks by displayed FLIP.
    #[arg(long, value_name = "PYTHON")]
    pub jod_python: Option<String>,
    /// With --jod-python: keep every cell's videos once scored.
    #[arg(long, requires = "jod_python")]
    pub keep_video: bool,
    /// Bench flags every cell shares, after `--`: e.g. `-- --backend cpu --width 640
    /// --height 360`.
    #[arg(last = true)]
    pub bench: Vec<String>,
}

/// `suite table`.
#[derive(Debug, Args)]
pub struct SuiteTableArgs {
    /// Suite folders (one per machine when the shards ran apart).
    #[arg(required = true)]
    pub folders: Vec<PathBuf>,
    /// Where to write the table (default: the first folder).
    #[arg(short = 'o', long = "out")]
    pub out: Option<PathBuf>,
}

impl SuiteRunArgs {
    /// The library's configuration: the standard plan narrowed by --scenes and --methods.
    pub fn config(&self) -> Result<SuiteConfig> {
        if !(self.duration.is_finite() && self.duration > 0.0) {
            anyhow::bail!(
                "--duration must be a positive number of seconds, got {}",
                self.duration
            );
        }
        if self.every == 0 {
            anyhow::bail!("--every must be at least 1");
        }
        let plan = Plan::standard(self.runs)
            .context("--runs")?
            .only_scenes(&self.scenes)
            .context("--scenes")?
            .only_methods(&self.methods)
            .context("--methods")?;
        Ok(SuiteConfig {
            plan,
            shard: self.shard,
            out: self.out.clone(),
            common: self.bench.clone(),
            duration_s: self.duration,
            every: self.every,
            jod: self.jod_python.as_ref().map(|python| JodTool {
                python: python.clone(),
                script: PathBuf::from("scripts/jod/jod.py"),
                keep_video: self.keep_video,
            }),
        })
    }
}

/// Parses flags with `bench`'s and `calibrate`'s own parsers.
pub struct CommandLine;

/// `bench`'s flags on their own.
#[derive(Parser)]
struct BenchLine {
    #[command(flatten)]
    bench: BenchArgs,
}

/// `calibrate`'s flags on their own.
#[derive(Parser)]
struct CalibrateLine {
    #[command(flatten)]
    calibrate: CalibrateArgs,
}

impl SuiteCommands for CommandLine {
    fn bench(&self, flags: &[String]) -> Result<BenchConfig> {
        let line = BenchLine::try_parse_from(
            std::iter::once("bench").chain(flags.iter().map(String::as_str)),
        )
        .map_err(|e| anyhow::anyhow!("bench {}: {e}", flags.join(" ")))?;
        Ok(line.bench.config())
    }

    fn calibrate(&self, flags: &[String]) -> Result<CalibrateConfig> {
        let line = CalibrateLine::try_parse_from(
            std::iter::once("calibrate").chain(flags.iter().map(String::as_str)),
        )
        .map_err(|e| anyhow::anyhow!("calibrate {}: {e}", flags.join(" ")))?;
        Ok((&line.calibrate).into())
    }
}
