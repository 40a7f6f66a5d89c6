//! Fits a machine's timing-noise profile (`steadyray_control::noise`) from the `frames.csv`
//! of fixed-quality `steadyray bench` runs and prints it as JSON.
//!
//! ```text
//! cargo run --release -p steadyray-control --example fit_noise -- \
//!     FIRST/frames.csv [--second SECOND/frames.csv] [--controller NAME] \
//!     [--machine TEXT] [--recorded TEXT] > profile.json
//! ```
//!
//! Each file's rows of controller NAME (default: the file's first controller) give the frame
//! times in order; a second run of the same frames (`--second`) is needed to fit the spells.
//! The fit's measurements (frames against their neighbours, the two runs' ratio) go to stderr.

use std::collections::BTreeMap;
use std::process::ExitCode;
use steadyray_control::noise::{NoiseFit, fit_profile};

/// The frame times (ms) of one run, and the mean time between frames beyond them (ms): the
/// render call's wall time beyond Tp, the nearest the csv comes to it.
struct Run {
    tp_ms: Vec<f64>,
    gap_ms: f64,
}

fn main() -> ExitCode {
    match fit_from_args(std::env::args().skip(1).collect()) {
        Ok(fit) => {
            report(&fit);
            match serde_json::to_string_pretty(&fit.profile) {
                Ok(text) => {
                    println!("{text}");
                    ExitCode::SUCCESS
                }
                Err(e) => fail(&e.to_string()),
            }
        }
        Err(why) => fail(&why),
    }
}

fn fail(why: &str) -> ExitCode {
    eprintln!("fit_noise: {why}");
    ExitCode::FAILURE
}

/// Parses the arguments, reads the runs and fits.
fn fit_from_args(args: Vec<String>) -> Result<NoiseFit, String> {
    let mut options: BTreeMap<String, String> = BTreeMap::new();
    let mut first: Option<String> = None;
    let mut it = args.into_iter();
    while let Some(arg) = it.next() {
        match arg.strip_prefix("--") {
            Some(key @ ("second" | "controller" | "machine" | "recorded")) => {
                let value = it.next().ok_or_else(|| format!("--{key} needs a value"))?;
                options.insert(key.to_string(), value);
            }
            Some(other) => {
                return Err(format!(
                    "unknown option --{other}: expected --second, --controller, --machine, --recorded"
                ));
            }
            None if first.is_none() => first = Some(arg),
            None => return Err(format!("unexpected argument `{arg}`: give one frames.csv")),
        }
    }
    let first = first.ok_or("give the frames.csv of a fixed-quality bench run")?;
    let controller = options.get("controller").map(String::as_str);
    let a = read_run(&first, controller)?;
    let b = match options.get("second") {
        Some(path) => Some(read_run(path, controller)?),
        None => None,
    };
    let gap_ms = b.as_ref().map_or(a.gap_ms, |b| 0.5 * (a.gap_ms + b.gap_ms));
    let text = |key: &str| options.get(key).cloned().unwrap_or_default();
    fit_profile(
        &a.tp_ms,
        b.as_ref().map(|r| r.tp_ms.as_slice()),
        gap_ms,
        &text("machine"),
        &text("recorded"),
    )
    .map_err(|e| e.to_string())
}

/// The rows of `controller` (or the file's first controller) in `path`, in file order.
fn read_run(path: &str, controller: Option<&str>) -> Result<Run, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines
        .next()
        .ok_or_else(|| format!("{path} is empty"))?
        .split(',')
        .collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or_else(|| format!("{path} has no `{name}` column: is it a bench frames.csv?"))
    };
    let (name_col, tp_col, wall_col) =
        (column("controller")?, column("tp_ms")?, column("wall_ms")?);
    let mut wanted = controller.map(str::to_string);
    let (mut tp_ms, mut gaps) = (Vec::new(), Vec::new());
    for (i, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        let cell = |c: usize| {
            cells
                .get(c)
                .ok_or_else(|| format!("{path} line {}: too few columns", i + 2))
        };
        let name = cell(name_col)?.to_string();
        if *wanted.get_or_insert_with(|| name.clone()) != name {
            continue;
        }
        let number = |c: usize| -> Result<f64, String> {
            let v = cell(c)?;
            v.parse()
                .map_err(|_| format!("{path} line {}: `{v}` is not a number", i + 2))
        };
        let (tp, wall) = (number(tp_col)?, number(wall_col)?);
        tp_ms.push(tp);
        gaps.push((wall - tp).max(0.0));
    }
    if tp_ms.is_empty() {
        return Err(format!(
            "{path} has no rows of controller `{}`",
            wanted.unwrap_or_default()
        ));
    }
    let gap_ms = gaps.iter().sum::<f64>() / gaps.len() as f64;
    Ok(Run { tp_ms, gap_ms })
}

/// The fit's measurements, to stderr.
fn report(fit: &NoiseFit) {
    let [p5, p50, p95, p99] = fit.neighbour_ratio;
    eprintln!(
        "{} frames; a frame against the mean of its neighbours: p5 {p5:.3} p50 {p50:.3} \
         p95 {p95:.3} p99 {p99:.3}; {} spikes",
        fit.frames, fit.spikes
    );
    if let Some([p5, p50, p95]) = fit.run_ratio {
        eprintln!("the same frame in the two runs: p5 {p5:.3} p50 {p50:.3} p95 {p95:.3}");
    }
}
