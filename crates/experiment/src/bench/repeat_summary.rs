//! The summary of a repeated bench (`bench --repeat N`): the repetitions' `summary.json`
//! files merged into one whose every controller figure is its median and range over the
//! repetitions with each repetition's value (`{median, min, max, runs}`), and the table of
//! those medians and ranges.

use super::report::DISPLAY_COLUMNS;
use anyhow::{Result, bail};
use serde_json::{Map, Value, json};
use std::fmt::Write as _;
use steadyray_display::stats::quantile;

/// The frame clock's table of a repeated bench: header, `summary.json` key, decimals, and
/// the factor the figure is shown multiplied by (the columns of the single run's table).
const FRAME_COLUMNS: [(&str, &str, usize, f64); 19] = [
    ("in band %", "in_band_pct", 1, 1.0),
    ("aim ceiling %", "aim_ceiling_pct", 1, 1.0),
    ("over %", "over_pct", 1, 1.0),
    ("under %", "under_pct", 1, 1.0),
    ("u@max %", "under_at_max_pct", 1, 1.0),
    ("tp_mean", "tp_mean", 2, 1.0),
    ("tp_std", "tp_std", 2, 1.0),
    ("tp_p50", "tp_p50", 2, 1.0),
    ("tp_p95", "tp_p95", 2, 1.0),
    ("tp_p99", "tp_p99", 2, 1.0),
    ("tp_max", "tp_max", 2, 1.0),
    ("rev/100", "reversals_per_100", 2, 1.0),
    ("max_over", "longest_over_run", 0, 1.0),
    ("settle", "settle_max", 0, 1.0),
    ("S", "mean_spp", 2, 1.0),
    ("R", "mean_depth", 2, 1.0),
    ("Mrays/s", "rays_per_s", 1, 1e-6),
    ("flip", "flip_mean", 4, 1.0),
    ("flip95", "flip_p95", 4, 1.0),
];

/// One summary of the repetitions' `summary.json` values, in order: their context (each
/// field kept where the repetitions agree, else `{runs: [...]}`), `repeat`, what the
/// figures are (`aggregate`), the repetitions' folders, and per controller (matched by its
/// place in the runs' order) every figure as `{median, min, max, runs}`.
pub fn summarise(summaries: &[Value]) -> Result<Value> {
    let Some(first) = summaries.first().and_then(Value::as_object) else {
        bail!("no repetition to summarise");
    };
    let count = summaries.len();
    let mut summary = Map::new();
    for key in first.keys().filter(|k| *k != "controllers") {
        let values: Vec<Value> = summaries.iter().map(|s| s[key].clone()).collect();
        summary.insert(key.clone(), agreed_or_runs(values));
    }
    summary.insert("repeat".into(), json!(count));
    summary.insert(
        "aggregate".into(),
        json!(format!("median [min–max] over {count} runs")),
    );
    let folders: Vec<String> = (1..=count).map(|k| format!("repeat-{k}")).collect();
    summary.insert("repetitions".into(), json!(folders));
    summary.insert("controllers".into(), Value::Array(controllers(summaries)?));
    Ok(Value::Object(summary))
}

/// The controllers of the repetitions, merged by their place in the runs' order.
fn controllers(summaries: &[Value]) -> Result<Vec<Value>> {
    let lists: Vec<&Vec<Value>> = summaries
        .iter()
        .map(|s| s["controllers"].as_array())
        .collect::<Option<_>>()
        .ok_or_else(|| anyhow::anyhow!("a repetition's summary.json has no controllers"))?;
    let runs = lists[0].len();
    if lists.iter().any(|l| l.len() != runs) {
        bail!("the repetitions made different numbers of runs: cannot summarise them");
    }
    Ok((0..runs)
        .map(|i| merge_controller(&lists.iter().map(|l| &l[i]).collect::<Vec<_>>()))
        .collect())
}

/// One controller's entries over the repetitions: its name (the words its names share,
/// with every repetition's name in `names` where they differ, as the fixed baselines'
/// qualities may), and each figure as `{median, min, max, runs}`; a field without a number in any
/// repetition is kept where they agree, else as `{runs: [...]}`.
fn merge_controller(entries: &[&Value]) -> Value {
    let names: Vec<&str> = entries
        .iter()
        .map(|e| e["name"].as_str().unwrap_or("?"))
        .collect();
    let mut merged = Map::new();
    merged.insert("name".into(), json!(shared_words(&names)));
    if names.iter().any(|n| *n != names[0]) {
        merged.insert("names".into(), json!(names));
    }
    let mut keys: Vec<&String> = entries
        .iter()
        .filter_map(|e| e.as_object())
        .flat_map(|o| o.keys())
        .filter(|k| *k != "name")
        .collect();
    keys.sort();
    keys.dedup();
    for key in keys {
        let values: Vec<Value> = entries.iter().map(|e| e[key.as_str()].clone()).collect();
        let figure = match values.iter().any(Value::is_number) {
            true => spread(values),
            false => agreed_or_runs(values),
        };
        merged.insert(key.clone(), figure);
    }
    Value::Object(merged)
}

/// A figure over the repetitions: the median, smallest and largest of its numbers (a
/// repetition without it, e.g. a run that never settled, counts in `runs` as `null` only),
/// and every repetition's value in order.
fn spread(values: Vec<Value>) -> Value {
    let numbers: Vec<f64> = values.iter().filter_map(Value::as_f64).collect();
    let min = numbers.iter().copied().fold(f64::INFINITY, f64::min);
    let max = numbers.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    json!({
        "median": quantile(&numbers, 0.5),
        "min": min,
        "max": max,
        "runs": values,
    })
}

/// The value the repetitions agree on, else `{runs: [...]}` with every repetition's.
fn agreed_or_runs(values: Vec<Value>) -> Value {
    match values.iter().all(|v| *v == values[0]) {
        true => values[0].clone(),
        false => json!({ "runs": values }),
    }
}

/// The name of runs named `names` in the repetitions: the name itself where they are the
/// same; else the leading words they share before a fixed quality's label (`most-in-band
/// fixed` of `most-in-band fixed S=2 R=5` and `most-in-band fixed S=3 R=5`, and of `... S=2
/// R=5 x0.75`, whose shared `S=2 R=5` would claim a quality one repetition did not run),
/// then the temporal mode they share (`+temporal`, `+warp`).
fn shared_words(names: &[&str]) -> String {
    if names.iter().all(|name| *name == names[0]) {
        return names[0].to_string();
    }
    let words: Vec<Vec<&str>> = names.iter().map(|name| name.split(' ').collect()).collect();
    let first = &words[0];
    let before_quality = first.iter().take_while(|w| !w.starts_with("S=")).count();
    let lead = words.iter().fold(before_quality, |n, other| {
        first
            .iter()
            .zip(other)
            .take(n)
            .take_while(|(a, b)| a == b)
            .count()
    });
    let modes = words.iter().fold(first.len() - lead, |n, other| {
        first
            .iter()
            .rev()
            .zip(other.iter().rev())
            .take(n)
            .take_while(|(a, b)| a == b && a.starts_with('+'))
            .count()
    });
    let mut shared = first[..lead].to_vec();
    shared.extend(&first[first.len() - modes..]);
    shared.join(" ")
}

/// The table of a repeated bench's summary (Markdown): one row per controller, each figure
/// of the single run's table (the display's under the real clock) as `median [min–max]`
/// over the repetitions, under a line saying so; a figure no repetition has shows as `-`.
pub fn repeated_table(summary: &Value) -> String {
    let columns: Vec<(&str, &str, usize, f64)> = match summary["clock"].as_str() {
        Some("real") => DISPLAY_COLUMNS
            .iter()
            .map(|&(header, key, decimals)| (header, key, decimals, 1.0))
            .collect(),
        _ => FRAME_COLUMNS.to_vec(),
    };
    let repeat = summary["repeat"].as_u64().unwrap_or(0);
    let mut out = format!("Each figure: median [min–max] over {repeat} runs.\n\n| controller |");
    for (header, ..) in &columns {
        let _ = write!(out, " {header} |");
    }
    out.push_str("\n|---|");
    out.push_str(&"---|".repeat(columns.len()));
    out.push('\n');
    let no_controllers = Vec::new();
    let controllers = summary["controllers"].as_array().unwrap_or(&no_controllers);
    for c in controllers {
        let _ = write!(out, "| {} |", c["name"].as_str().unwrap_or("?"));
        for &(_, key, decimals, factor) in &columns {
            let _ = write!(out, " {} |", cell(&c[key], decimals, factor));
        }
        out.push('\n');
    }
    out
}

/// A figure's cell: `median [min–max]` times `factor`, or `-` without a number.
fn cell(figure: &Value, decimals: usize, factor: f64) -> String {
    let number = |key: &str| figure[key].as_f64().map(|v| v * factor);
    match (number("median"), number("min"), number("max")) {
        (Some(median), Some(min), Some(max)) => {
            format!("{median:.decimals$} [{min:.decimals$}–{max:.decimals$}]")
        }
        _ => "-".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(name: &str, in_band: f64, settle: Value) -> Value {
        json!({ "name": name, "in_band_pct": in_band, "settle_max": settle, "band_ms": [15.0, 20.0] })
    }

    #[test]
    fn figures_become_medians_and_ranges_of_the_repetitions() {
        let summaries = [
            json!({ "clock": "frames", "frames": 720, "controllers": [run("most-in-band fixed S=2 R=5", 90.0, json!(4))] }),
            json!({ "clock": "frames", "frames": 720, "controllers": [run("most-in-band fixed S=3 R=5", 80.0, Value::Null)] }),
            json!({ "clock": "frames", "frames": 720, "controllers": [run("most-in-band fixed S=2 R=4", 95.0, json!(6))] }),
        ];
        let summary = summarise(&summaries).unwrap();
        assert_eq!(summary["repeat"], 3);
        assert_eq!(summary["frames"], 720);
        let c = &summary["controllers"][0];
        assert_eq!(c["name"], "most-in-band fixed");
        assert_eq!(c["names"][1], "most-in-band fixed S=3 R=5");
        let in_band = &c["in_band_pct"];
        assert_eq!(in_band["median"], 90.0);
        assert_eq!(in_band["min"], 80.0);
        assert_eq!(in_band["max"], 95.0);
        assert_eq!(in_band["runs"], json!([90.0, 80.0, 95.0]));
        // A run that never settled has no settle time: the spread is of those that did.
        assert_eq!(c["settle_max"]["median"], 5.0);
        assert_eq!(c["settle_max"]["runs"][1], Value::Null);
        assert_eq!(c["band_ms"], json!([15.0, 20.0]));
        let table = repeated_table(&summary);
        assert!(table.starts_with("Each figure: median [min–max] over 3 runs."));
        assert!(table.contains("| most-in-band fixed | 90.0 [80.0–95.0] |"));
    }

    #[test]
    fn names_that_differ_share_the_words_before_the_quality_and_the_temporal_mode() {
        let shared = |names: &[&str]| shared_words(names);
        assert_eq!(shared(&["predictive", "predictive"]), "predictive");
        assert_eq!(
            shared(&[
                "best-looking fixed S=1 R=16 x0.75 +temporal +warp",
                "best-looking fixed S=1 R=16 +temporal +warp",
            ]),
            "best-looking fixed +temporal +warp"
        );
        assert_eq!(
            shared(&["most-in-band fixed S=2 R=5", "most-in-band fixed S=2 R=4"]),
            "most-in-band fixed"
        );
        // Summaries written before the rename share words the same way.
        assert_eq!(
            shared(&["best fixed S=2 R=5", "best fixed S=3 R=5"]),
            "best fixed"
        );
    }

    #[test]
    fn repetitions_with_other_runs_are_refused() {
        let summaries = [
            json!({ "clock": "frames", "controllers": [run("fixed", 1.0, Value::Null)] }),
            json!({ "clock": "frames", "controllers": [] }),
        ];
        let error = summarise(&summaries).unwrap_err().to_string();
        assert!(error.contains("different numbers of runs"));
    }
}
