//! `bench --repeat N`: the experiment run N times, each repetition a fresh run written as a
//! single run writes it into `OUT/repeat-K/`, and the repetitions' figures summarised per
//! controller as their median and range ([`repeat_summary`]) in
//! `OUT/summary.json`, `OUT/table.md` and the table printed at the end.
//!
//! Every repetition opens its renderer afresh and measures again what the runs need
//! measured before them (the hand-over, the warped refresh, the fixed baselines' searches), so the
//! spread is that of fresh runs on the machine; on the simulated renderer repetition K draws
//! its noise from seed K (repetition 1 is the single run's).

use super::BenchConfig;
use super::repeat_summary::{self, repeated_table};
use super::report::{self, write_json};
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};

/// The folder of repetition `k` (from 1) inside the output folder `out`.
pub fn repetition_dir(out: &Path, k: u32) -> PathBuf {
    out.join(format!("repeat-{k}"))
}

/// Runs the experiment `config.repeat` times into `OUT/repeat-K/` and writes the summary
/// of the repetitions into `OUT`.
pub fn run_repeated(config: &BenchConfig) -> Result<()> {
    check(config)?;
    let mut summaries = Vec::new();
    for k in 1..=config.repeat {
        eprintln!("bench: repetition {k} of {}", config.repeat);
        let repetition = BenchConfig {
            out: repetition_dir(&config.out, k),
            repeat: 1,
            ..config.clone()
        };
        super::run_once(&repetition, k)?;
        summaries.push(read_summary(&repetition.out.join("summary.json"))?);
    }
    let summary = repeat_summary::summarise(&summaries)?;
    let out = &config.out;
    write_json(&summary, &out.join("summary.json"))?;
    let table = repeated_table(&summary);
    print!("{table}");
    if summary["clock"] == "frames" {
        println!(
            "paper (GeForce 6800GT, 2005): {:.1} % in band without control, {:.1} % with step control",
            report::PAPER_IN_BAND_FIXED_PCT,
            report::PAPER_IN_BAND_CONTROLLED_PCT
        );
    }
    let path = out.join("table.md");
    std::fs::write(&path, &table).with_context(|| format!("cannot write {}", path.display()))?;
    eprintln!(
        "bench: wrote summary.json and table.md (median [min–max] over {} runs) to {}, each repetition's outputs to repeat-1/ ... repeat-{}/",
        config.repeat,
        out.display(),
        config.repeat
    );
    Ok(())
}

/// Refuses a repetition count the bench cannot run, before anything renders.
fn check(config: &BenchConfig) -> Result<()> {
    if config.repeat == 0 {
        bail!("--repeat must be at least 1 (the number of times the experiment runs)");
    }
    if config.record.is_some() || config.video.is_some() {
        bail!(
            "--record and --video keep the frames of one run: use them without --repeat (or with --repeat 1)"
        );
    }
    Ok(())
}

/// A repetition's `summary.json`.
fn read_summary(path: &Path) -> Result<serde_json::Value> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{} is not JSON", path.display()))
}
