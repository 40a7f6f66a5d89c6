//! `bench --repeat N` on the simulated renderer: the repetitions' folders, each as a single
//! run writes it, and the summary of their medians and ranges (repetition K draws the
//! simulated noise from seed K, so repetitions differ as fresh runs do and repetition 1 is
//! the single run).

use serde_json::Value;
use std::path::{Path, PathBuf};
use steadyray_experiment::bench::{self, BenchConfig};
use tempfile::TempDir;

/// A fresh temporary folder named after `test`, removed when dropped.
fn scratch(test: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("steadyray-{test}-"))
        .tempdir()
        .unwrap()
}

/// A short simulated bench of three controllers into `out`, a folder not made yet.
fn simulated(out: PathBuf, repeat: u32) -> BenchConfig {
    BenchConfig {
        simulate: true,
        frames: 120,
        search_views: 12,
        controllers: "fixed,hysteresis,predictive".into(),
        out,
        repeat,
        ..BenchConfig::default()
    }
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn repetition(out: &Path, k: u32) -> PathBuf {
    out.join(format!("repeat-{k}"))
}

#[test]
fn a_repeated_bench_summarises_its_repetitions() {
    let dir = scratch("repeat-3");
    let config = simulated(dir.path().join("bench"), 3);
    bench::run(&config).expect("the repeated simulated bench runs");
    let out = &config.out;
    let runs: Vec<Value> = (1..=3)
        .map(|k| {
            let dir = repetition(out, k);
            for file in ["frames.csv", "frametime.png", "frametime.svg"] {
                assert!(dir.join(file).is_file(), "repeat-{k} has no {file}");
            }
            read_json(&dir.join("summary.json"))
        })
        .collect();
    assert!(!repetition(out, 4).exists());
    let summary = read_json(&out.join("summary.json"));
    assert_eq!(summary["repeat"], 3);
    assert_eq!(summary["aggregate"], "median [min–max] over 3 runs");
    let table = std::fs::read_to_string(out.join("table.md")).unwrap();
    assert!(table.starts_with("Each figure: median [min–max] over 3 runs."));

    let controllers = summary["controllers"].as_array().unwrap();
    // fixed, best fixed, hysteresis, predictive.
    assert_eq!(controllers.len(), 4);
    let mut some_range = false;
    for (i, c) in controllers.iter().enumerate() {
        for figure in ["in_band_pct", "tp_mean", "tp_p95", "reversals_per_100"] {
            let mut values: Vec<f64> = runs
                .iter()
                .map(|r| r["controllers"][i][figure].as_f64().unwrap())
                .collect();
            assert_eq!(c[figure]["runs"], serde_json::json!(values));
            values.sort_by(f64::total_cmp);
            assert_eq!(c[figure]["min"], values[0], "{figure} of run {i}");
            assert_eq!(c[figure]["median"], values[1], "{figure} of run {i}");
            assert_eq!(c[figure]["max"], values[2], "{figure} of run {i}");
            some_range |= values[0] != values[2];
        }
        let name = runs[0]["controllers"][i]["name"].as_str().unwrap();
        assert!(name.starts_with(c["name"].as_str().unwrap()));
        assert!(table.contains(&format!("| {} |", c["name"].as_str().unwrap())));
    }
    // Only the controller that predicts its frames has an aim ceiling: a share of frames.
    let ceiling = controllers[3]["aim_ceiling_pct"]["median"]
        .as_f64()
        .unwrap();
    assert!(
        (50.0..=100.0).contains(&ceiling),
        "predictive's aim ceiling {ceiling}"
    );
    assert!(controllers[0].get("aim_ceiling_pct").is_none());
    assert!(table.contains("| aim ceiling % |"));
    // Each repetition draws its own noise: the figures spread as fresh runs' do.
    assert!(some_range, "three seeds gave three identical runs");
}

#[test]
fn the_first_repetition_is_the_single_run() {
    let dir = scratch("repeat-first");
    let single = simulated(dir.path().join("single"), 1);
    bench::run(&single).unwrap();
    assert!(!repetition(&single.out, 1).exists());
    let repeated = simulated(dir.path().join("repeated"), 2);
    bench::run(&repeated).unwrap();
    let frames = |dir: &Path| std::fs::read_to_string(dir.join("frames.csv")).unwrap();
    assert_eq!(frames(&single.out), frames(&repetition(&repeated.out, 1)));
    assert_ne!(frames(&single.out), frames(&repetition(&repeated.out, 2)));
}

#[test]
fn no_repetitions_is_refused_naming_the_flag() {
    let dir = scratch("repeat-0");
    let config = simulated(dir.path().join("bench"), 0);
    let error = bench::run(&config).unwrap_err().to_string();
    assert!(error.contains("--repeat"), "{error}");
    assert!(!config.out.exists(), "nothing is written");
}
