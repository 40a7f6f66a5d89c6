//! Long work shows progress a log can read: with stderr piped (not a terminal), `bench`
//! writes plain lines with the percentage done and the time left.

use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

#[test]
fn a_piped_bench_writes_plain_progress_lines() {
    let dir = tempfile::Builder::new()
        .prefix("steadyray-progress-")
        .tempdir()
        .unwrap();
    let out = dir.path().join("bench");
    let output = Command::new(BIN)
        .args(["bench", "--simulate", "--frames", "300", "--out"])
        .arg(&out)
        .output()
        .expect("steadyray runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("% ") && l.contains("frames") && l.contains("left]"))
        .collect();
    assert!(!lines.is_empty(), "no progress line in:\n{stderr}");
    assert!(
        lines.iter().all(|l| !l.contains('\u{1b}')),
        "escape codes in a plain line: {lines:?}"
    );
}
