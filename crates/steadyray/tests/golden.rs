//! The golden test of `steadyray bench --simulate`: with its default arguments it writes the
//! same `frames.csv` and `summary.json` as the files the library's golden test keeps in
//! `crates/experiment/tests/golden/bench-simulate/`, compared by the same code
//! (`crates/experiment/tests/support/golden.rs`, included here).

#[path = "../../experiment/tests/support/golden.rs"]
mod golden;

use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

#[test]
fn the_simulated_bench_writes_the_kept_frames_and_summary() {
    let dir = tempfile::Builder::new()
        .prefix("steadyray-golden-")
        .tempdir()
        .unwrap();
    let out = dir.path().join("bench");
    let output = Command::new(BIN)
        .args(["bench", "--simulate", "--out"])
        .arg(&out)
        .output()
        .expect("cannot run steadyray");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    golden::check_against_kept(&out);
}
