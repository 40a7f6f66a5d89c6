//! The golden test of `steadyray bench --simulate`: with its default arguments it writes the
//! same `frames.csv` and `summary.json` as the files kept in
//! `crates/experiment/tests/golden/bench-simulate/` (the library's golden test, which calls
//! `bench::run`, compares the same files). The simulated renderer runs on a fake clock with seeded noise, so both files are the same
//! from run to run and from machine to machine, except for two fields of `summary.json`
//! masked here (replaced by `"masked"` in the kept file and in the run's before comparing):
//! `machine` (host name, CPU, threads) and `git_revision`.
//!
//! To write the kept files again from the code as it is (after a deliberate change of the
//! controllers or of the bench's output), run
//! `STEADYRAY_BLESS=1 cargo test -p steadyray-experiment --test golden`.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

/// The summary's fields that say where and from which source a run was made.
const MASKED: [&str; 2] = ["machine", "git_revision"];

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiment/tests/golden/bench-simulate")
}

/// `summary.json` with the fields of [`MASKED`] replaced by `"masked"`.
fn masked_summary(text: &str) -> Value {
    let mut summary: Value = serde_json::from_str(text).expect("summary.json is JSON");
    for field in MASKED {
        let entry = summary
            .get_mut(field)
            .unwrap_or_else(|| panic!("summary.json has no {field}"));
        *entry = Value::String("masked".into());
    }
    summary
}

#[test]
fn the_simulated_bench_writes_the_kept_frames_and_summary() {
    let out = std::env::temp_dir().join(format!("steadyray-golden-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
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
    let frames = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    let summary = masked_summary(&std::fs::read_to_string(out.join("summary.json")).unwrap());
    let _ = std::fs::remove_dir_all(&out);

    let golden = golden_dir();
    if std::env::var_os("STEADYRAY_BLESS").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(&golden).unwrap();
        std::fs::write(golden.join("frames.csv"), &frames).unwrap();
        let text = serde_json::to_string_pretty(&summary).unwrap() + "\n";
        std::fs::write(golden.join("summary.json"), text).unwrap();
        return;
    }
    let kept_frames = std::fs::read_to_string(golden.join("frames.csv"))
        .expect("no kept frames.csv: write it with STEADYRAY_BLESS=1");
    let kept_summary =
        masked_summary(&std::fs::read_to_string(golden.join("summary.json")).unwrap());
    if let Some((i, (kept, now))) = kept_frames
        .lines()
        .zip(frames.lines())
        .enumerate()
        .find(|(_, (a, b))| a != b)
    {
        panic!(
            "frames.csv line {} differs:\nkept: {kept}\nnow:  {now}",
            i + 1
        );
    }
    assert_eq!(
        kept_frames.lines().count(),
        frames.lines().count(),
        "frames.csv has another number of lines"
    );
    assert_eq!(kept_summary, summary, "summary.json differs");
}
