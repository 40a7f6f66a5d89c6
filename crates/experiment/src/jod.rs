//! `steadyray jod`: what the JOD tool (`scripts/jod/jod.py`, ColorVideoVDP) measured, brought
//! into the bench's reports. `merge` adds each run's `jod` to a real-clock bench's
//! `summary.json` and `table.md`; `plot` draws JOD against the frames shown per second for
//! every method of one or more benches; `agree` says how well each cheap figure ranks those
//! methods as JOD does.

use crate::bench::plot::JodPoint;
use crate::bench::report::{display_table, write_json};
use anyhow::{Context, Result, bail};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A `jod` subcommand and its arguments.
#[derive(Clone, Debug)]
pub enum JodCommand {
    /// Add the scores of `jod.py` (its jod.json) to the bench's summary.json (each run's
    /// `jod`) and rewrite table.md beside it.
    Merge {
        /// The scores: DIR/jod.json of `scripts/jod/jod.py DIR`.
        scores: PathBuf,
        /// The summary.json of the `bench --clock real --video DIR` run that made DIR.
        summary: PathBuf,
    },
    /// Plot JOD against mean displayed frames per second, a point per method, for the runs
    /// of one or more merged summary.json files (PNG and SVG).
    Plot {
        /// Merged summary.json files.
        summaries: Vec<PathBuf>,
        /// The PNG to write (an SVG of the same name beside it).
        output: PathBuf,
    },
    /// How well each figure of merged summary.json files ranks their methods as JOD does:
    /// Spearman's rank correlation over every scored method (1: the same order), and the
    /// pairs of methods the displayed FLIP orders against JOD.
    Agree {
        /// Merged summary.json files.
        summaries: Vec<PathBuf>,
    },
}

/// Runs a `jod` subcommand.
pub fn run(command: &JodCommand) -> Result<()> {
    match command {
        JodCommand::Merge { scores, summary } => {
            let table = merge(scores, summary)?;
            print!("{table}");
            Ok(())
        }
        JodCommand::Plot { summaries, output } => {
            let points = summaries
                .iter()
                .map(|path| {
                    plot_points(&read_json(path)?).with_context(|| path.display().to_string())
                })
                .collect::<Result<Vec<_>>>()?
                .concat();
            crate::bench::plot::write_jod_plot(&points, output)?;
            eprintln!("jod: wrote {}", output.display());
            Ok(())
        }
        JodCommand::Agree { summaries } => {
            let mut methods = Vec::new();
            for path in summaries {
                methods.extend(scored_methods(&read_json(path)?));
            }
            print!("{}", agreement(&methods)?);
            Ok(())
        }
    }
}

fn read_json(path: &Path) -> Result<Value> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{} is not valid JSON", path.display()))
}

/// Merges the scores of `scores_path` into `summary_path` (and its `table.md`); returns the
/// table. The summary must be a real-clock bench's under the viewing set-up the scores were
/// made with, and every score must name one of its runs; nothing is written otherwise.
pub fn merge(scores_path: &Path, summary_path: &Path) -> Result<String> {
    let scores = read_json(scores_path)?;
    let mut summary = read_json(summary_path)?;
    if summary.get("clock").and_then(Value::as_str) != Some("real") {
        bail!(
            "{} is not from `bench --clock real`: JOD scores a screen video",
            summary_path.display()
        );
    }
    if scores.get("viewing") != summary.get("viewing") {
        bail!(
            "the viewing set-up of {} differs from that of {}",
            scores_path.display(),
            summary_path.display()
        );
    }
    let jod = scores
        .get("jod")
        .and_then(Value::as_object)
        .with_context(|| format!("{} has no `jod` object", scores_path.display()))?;
    let controllers = summary
        .get_mut("controllers")
        .and_then(Value::as_array_mut)
        .with_context(|| format!("{} has no `controllers` list", summary_path.display()))?;
    let name_of = |c: &Value| c.get("name").and_then(Value::as_str).map(str::to_string);
    let known: Vec<String> = controllers.iter().filter_map(name_of).collect();
    for (name, value) in jod {
        let score = value
            .as_f64()
            .filter(|v| v.is_finite())
            .with_context(|| format!("the score of {name:?} is not a number: {value}"))?;
        let entry = controllers
            .iter_mut()
            .find(|c| name_of(c).as_deref() == Some(name.as_str()))
            .with_context(|| {
                format!(
                    "{} scores {name:?}, which {} does not have (it has: {})",
                    scores_path.display(),
                    summary_path.display(),
                    known.join(", ")
                )
            })?;
        entry["jod"] = Value::from(score);
    }
    let unscored: Vec<String> = controllers
        .iter()
        .filter(|c| c.get("jod").is_none())
        .filter_map(name_of)
        .collect();
    if !unscored.is_empty() {
        eprintln!("jod: no score yet for {}", unscored.join(", "));
    }
    let table = display_table(controllers);
    write_json(&summary, summary_path)?;
    let table_path = summary_path.with_file_name("table.md");
    std::fs::write(&table_path, &table)
        .with_context(|| format!("cannot write {}", table_path.display()))?;
    Ok(table)
}

/// A `band_ms` pair.
fn band_of(value: &Value) -> Option<[f64; 2]> {
    let b = value.get("band_ms")?.as_array()?;
    Some([b.first()?.as_f64()?, b.get(1)?.as_f64()?])
}

/// The scored runs of a merged summary, each in its own band (summaries before runs had
/// one: the bench's).
fn plot_points(summary: &Value) -> Result<Vec<JodPoint>> {
    let band = band_of(summary).context("no band_ms")?;
    let controllers = summary
        .get("controllers")
        .and_then(Value::as_array)
        .context("no controllers")?;
    let points: Vec<JodPoint> = controllers
        .iter()
        .filter_map(|c| {
            Some(JodPoint {
                name: c.get("name")?.as_str()?.to_string(),
                band_ms: band_of(c).unwrap_or(band),
                displayed_fps: c.get("displayed_fps")?.as_f64()?,
                jod: c.get("jod")?.as_f64()?,
            })
        })
        .collect();
    if points.is_empty() {
        bail!("no run has both displayed_fps and jod: merge the JOD scores first");
    }
    Ok(points)
}

/// The figures `agree` ranks, and whether a higher value should mean a better picture.
const RANKED: [(&str, bool); 9] = [
    ("displayed_flip_mean", false),
    ("displayed_flip_p95", false),
    ("frame_flip_mean", false),
    ("age_flip_mean", false),
    ("screen_age_ms_mean", false),
    ("displayed_fps", true),
    ("repeated_pct", false),
    ("pacing_std_ms", false),
    ("latency_ms_mean", false),
];

/// A scored method: its label (name and band), its JOD and its summary entry.
struct Scored {
    label: String,
    jod: f64,
    entry: Value,
}

/// The runs of a merged summary that have a JOD score, labelled with their band (the
/// bench's in summaries before runs had their own).
fn scored_methods(summary: &Value) -> Vec<Scored> {
    let bench_band = band_of(summary);
    summary
        .get("controllers")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(|c| {
            let band = band_of(c)
                .or(bench_band)
                .map(|[tmin, tmax]| format!("{tmin:.3}-{tmax:.3}"))
                .unwrap_or_default();
            Some(Scored {
                label: format!(
                    "{} [{band}]",
                    c.get("name").and_then(Value::as_str).unwrap_or("?")
                ),
                jod: c.get("jod")?.as_f64()?,
                entry: c.clone(),
            })
        })
        .collect()
}

/// Ranks of `values` (1 = smallest), ties sharing their mean rank.
fn ranks(values: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut out = vec![0.0; values.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && values[order[j + 1]] == values[order[i]] {
            j += 1;
        }
        let rank = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            out[k] = rank;
        }
        i = j + 1;
    }
    out
}

/// Spearman's rank correlation of two equally long lists (Pearson's of their ranks); `None`
/// when either has no spread.
pub fn spearman(a: &[f64], b: &[f64]) -> Option<f64> {
    let (ra, rb) = (ranks(a), ranks(b));
    let n = ra.len() as f64;
    let (ma, mb) = (ra.iter().sum::<f64>() / n, rb.iter().sum::<f64>() / n);
    let cov: f64 = ra.iter().zip(&rb).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = ra.iter().map(|x| (x - ma) * (x - ma)).sum();
    let vb: f64 = rb.iter().map(|y| (y - mb) * (y - mb)).sum();
    (va > 0.0 && vb > 0.0).then(|| cov / (va * vb).sqrt())
}

/// The agreement table: each figure's rank correlation with JOD, signed so that 1 means the
/// figure orders the methods as JOD does; then the pairs displayed FLIP orders against JOD,
/// the largest JOD differences first.
fn agreement(methods: &[Scored]) -> Result<String> {
    if methods.len() < 3 {
        bail!(
            "{} scored methods: rank correlations need at least 3",
            methods.len()
        );
    }
    let jod: Vec<f64> = methods.iter().map(|m| m.jod).collect();
    let mut out = format!(
        "{} methods scored\n\n| figure | rank correlation with JOD |\n|---|---|\n",
        methods.len()
    );
    for (key, higher_is_better) in RANKED {
        let values: Option<Vec<f64>> = methods.iter().map(|m| m.entry.get(key)?.as_f64()).collect();
        let rho = values.and_then(|v| spearman(&v, &jod));
        let shown = rho.map_or_else(
            || "-".to_string(),
            |r| format!("{:+.3}", if higher_is_better { r } else { -r }),
        );
        out.push_str(&format!("| {key} | {shown} |\n"));
    }
    let flip: Option<Vec<f64>> = methods
        .iter()
        .map(|m| m.entry.get("displayed_flip_mean")?.as_f64())
        .collect();
    if let Some(flip) = flip {
        let mut discordant = Vec::new();
        for i in 0..methods.len() {
            for j in 0..methods.len() {
                if jod[i] > jod[j] && flip[i] > flip[j] {
                    discordant.push((jod[i] - jod[j], i, j));
                }
            }
        }
        discordant.sort_by(|a, b| b.0.total_cmp(&a.0));
        out.push_str(&format!(
            "\n{} of {} pairs ordered against JOD by displayed FLIP; the widest:\n\n",
            discordant.len(),
            methods.len() * (methods.len() - 1) / 2
        ));
        out.push_str("| better by JOD | worse by JOD | JOD difference | displayed FLIP |\n|---|---|---|---|\n");
        for (gap, i, j) in discordant.iter().take(8) {
            out.push_str(&format!(
                "| {} | {} | {gap:.3} | {:.4} vs {:.4} |\n",
                methods[*i].label, methods[*j].label, flip[*i], flip[*j]
            ));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn scratch(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("steadyray-jod-{name}-"))
            .tempdir()
            .unwrap()
    }

    fn viewing() -> Value {
        json!({"name": "standard_fhd", "diagonal_in": 24.0, "resolution": [1920, 1080], "distance_m": 0.6})
    }

    /// A hand-made summary of a real-clock bench with two runs.
    fn summary() -> Value {
        json!({
            "clock": "real",
            "band_ms": [15.0, 20.0],
            "viewing": viewing(),
            "controllers": [
                {"name": "fixed S=1 R=16", "displayed_fps": 59.0, "in_band_pct": 10.0},
                {"name": "predictive", "displayed_fps": 31.5, "in_band_pct": 90.0}
            ]
        })
    }

    fn write(dir: &Path, name: &str, value: &Value) -> PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, value.to_string()).unwrap();
        path
    }

    #[test]
    fn rank_correlation_of_hand_made_lists() {
        assert_eq!(ranks(&[3.0, 1.0, 2.0, 1.0]), [4.0, 1.5, 3.0, 1.5]);
        let close = |a: Option<f64>, b: f64| (a.unwrap() - b).abs() < 1e-12;
        assert!(close(spearman(&[1.0, 2.0, 3.0], &[10.0, 20.0, 30.0]), 1.0));
        assert!(close(spearman(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]), -1.0));
        // Ranks 1 2 3 4 against 1 3 2 4: 1 − 6·2/(4·15) = 0.8.
        assert!(close(
            spearman(&[1.0, 2.0, 3.0, 4.0], &[1.0, 3.0, 2.0, 4.0]),
            0.8
        ));
        assert_eq!(spearman(&[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0]), None);
    }

    /// A run's own band (the runs without the history of `bench --temporal both --warp
    /// --band refresh:M` have one of their own) labels it; older summaries give the bench's.
    #[test]
    fn each_run_is_labelled_and_plotted_with_its_own_band() {
        let summary = json!({
            "band_ms": [17.5, 24.0],
            "controllers": [
                {"name": "predictive", "band_ms": [23.8, 30.5], "jod": 8.0, "displayed_fps": 30.0},
                {"name": "predictive +temporal +warp", "jod": 9.0, "displayed_fps": 30.0}
            ]
        });
        let labels: Vec<String> = scored_methods(&summary)
            .into_iter()
            .map(|m| m.label)
            .collect();
        assert_eq!(
            labels,
            [
                "predictive [23.800-30.500]",
                "predictive +temporal +warp [17.500-24.000]"
            ]
        );
        let bands: Vec<[f64; 2]> = plot_points(&summary)
            .unwrap()
            .into_iter()
            .map(|p| p.band_ms)
            .collect();
        assert_eq!(bands, [[23.8, 30.5], [17.5, 24.0]]);
    }

    #[test]
    fn agreement_ranks_each_figure_and_names_the_pairs_flip_orders_wrong() {
        let summary = json!({
            "band_ms": [15.0, 20.0],
            "controllers": [
                {"name": "a", "jod": 8.0, "displayed_flip_mean": 0.02, "displayed_fps": 60.0},
                {"name": "b", "jod": 7.0, "displayed_flip_mean": 0.01, "displayed_fps": 30.0},
                {"name": "c", "jod": 6.0, "displayed_flip_mean": 0.03, "displayed_fps": 20.0},
                {"name": "unscored", "displayed_flip_mean": 0.5}
            ]
        });
        let methods = scored_methods(&summary);
        assert_eq!(methods.len(), 3);
        let table = agreement(&methods).unwrap();
        assert!(table.contains("| displayed_fps | +1.000 |"), "{table}");
        // FLIP orders a (8.0) below b (7.0): one discordant pair of three.
        assert!(
            table.contains("| displayed_flip_mean | +0.500 |"),
            "{table}"
        );
        assert!(table.contains("1 of 3 pairs"), "{table}");
        assert!(
            table.contains("| a [15.000-20.000] | b [15.000-20.000] | 1.000 |"),
            "{table}"
        );
        assert!(table.contains("| frame_flip_mean | - |"), "{table}");
        assert!(agreement(&methods[..2]).is_err());
    }

    #[test]
    fn scores_land_on_their_runs_and_in_the_table() {
        let tmp = scratch("merge");
        let dir = tmp.path();
        let summary_path = write(dir, "summary.json", &summary());
        let scores =
            json!({"viewing": viewing(), "jod": {"predictive": 8.25, "fixed S=1 R=16": 7.5}});
        let scores_path = write(dir, "jod.json", &scores);
        let table = merge(&scores_path, &summary_path).unwrap();
        let merged = read_json(&summary_path).unwrap();
        assert_eq!(merged["controllers"][0]["jod"], json!(7.5));
        assert_eq!(merged["controllers"][1]["jod"], json!(8.25));
        assert_eq!(
            merged["controllers"][1]["in_band_pct"],
            json!(90.0),
            "the rest stays"
        );
        let predictive_row = table
            .lines()
            .find(|l| l.starts_with("| predictive"))
            .unwrap();
        assert!(predictive_row.ends_with("| 8.25 |"), "{predictive_row}");
        assert_eq!(
            std::fs::read_to_string(dir.join("table.md")).unwrap(),
            table
        );
        let points = plot_points(&merged).unwrap();
        assert_eq!(points.len(), 2);
        assert_eq!((points[1].displayed_fps, points[1].jod), (31.5, 8.25));
    }

    #[test]
    fn a_partial_score_list_merges_and_leaves_the_others() {
        let tmp = scratch("partial");
        let dir = tmp.path();
        let summary_path = write(dir, "summary.json", &summary());
        let scores_path = write(
            dir,
            "jod.json",
            &json!({"viewing": viewing(), "jod": {"predictive": 8.0}}),
        );
        let table = merge(&scores_path, &summary_path).unwrap();
        let merged = read_json(&summary_path).unwrap();
        assert!(merged["controllers"][0].get("jod").is_none());
        let fixed_row = table.lines().find(|l| l.starts_with("| fixed")).unwrap();
        assert!(fixed_row.ends_with("| - |"), "{fixed_row}");
    }

    #[test]
    fn mismatches_are_refused_and_nothing_is_written() {
        let tmp = scratch("refuse");
        let dir = tmp.path();
        let original = summary();
        let summary_path = write(dir, "summary.json", &original);
        let cases = [
            (
                json!({"viewing": viewing(), "jod": {"hysteresis": 8.0}}),
                "hysteresis",
            ),
            (
                json!({"viewing": viewing(), "jod": {"predictive": "high"}}),
                "not a number",
            ),
            (json!({"viewing": viewing()}), "no `jod`"),
            (
                json!({"viewing": {"name": "standard_4k"}, "jod": {"predictive": 8.0}}),
                "viewing set-up",
            ),
        ];
        for (scores, expected) in cases {
            let scores_path = write(dir, "jod.json", &scores);
            let err = format!("{:#}", merge(&scores_path, &summary_path).unwrap_err());
            assert!(err.contains(expected), "{err}");
            assert_eq!(read_json(&summary_path).unwrap(), original);
            assert!(!dir.join("table.md").exists());
        }
        let frames_clock = write(
            dir,
            "frames.json",
            &json!({"clock": "frames", "controllers": []}),
        );
        let scores_path = write(dir, "jod.json", &json!({"viewing": viewing(), "jod": {}}));
        let err = merge(&scores_path, &frames_clock).unwrap_err().to_string();
        assert!(err.contains("--clock real"), "{err}");
        std::fs::write(dir.join("broken.json"), "{ not json").unwrap();
        let err = merge(&dir.join("broken.json"), &summary_path)
            .unwrap_err()
            .to_string();
        assert!(err.contains("not valid JSON"), "{err}");
    }
}
