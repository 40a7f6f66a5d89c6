//! The golden test of the bench on the simulated renderer: `bench::run` with the default
//! configuration (as `steadyray bench --simulate` runs it) writes the same `frames.csv` and
//! `summary.json` as the files kept in `tests/golden/bench-simulate/` (how they are compared,
//! masked and written again: `tests/support/golden.rs`).

#[path = "support/golden.rs"]
mod golden;

use steadyray_experiment::bench::{self, BenchConfig};

#[test]
fn the_simulated_bench_writes_the_kept_frames_and_summary() {
    let dir = tempfile::Builder::new()
        .prefix("steadyray-golden-lib-")
        .tempdir()
        .unwrap();
    let out = dir.path().join("bench");
    let config = BenchConfig {
        simulate: true,
        out: out.clone(),
        ..BenchConfig::default()
    };
    bench::run(&config).expect("the simulated bench runs");
    golden::check_against_kept(&out);
}
