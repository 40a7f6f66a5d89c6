//! The golden files of the simulated bench and how a run is checked against them: shared by
//! the library's golden test and the binary's (which includes this file by path), so that
//! both compare the same way.
//!
//! The simulated renderer runs on a fake clock with seeded noise, so both files are the same
//! from run to run and from machine to machine, except for two fields of `summary.json`
//! masked here (replaced by `"masked"` in the kept file and in the run's before comparing):
//! `machine` (host name, CPU, threads) and `git_revision`. To write the kept files again from
//! the code as it is (after a deliberate change of the controllers or of the bench's output),
//! run `STEADYRAY_BLESS=1 cargo test -p steadyray-experiment --test golden`.

use serde_json::Value;
use std::path::{Path, PathBuf};

/// The summary's fields that say where and from which source a run was made.
const MASKED: [&str; 2] = ["machine", "git_revision"];

/// The kept files' folder.
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

/// Checks the `frames.csv` and `summary.json` a simulated bench wrote into `out` against
/// the kept files (or, with `STEADYRAY_BLESS=1`, keeps them), then removes `out`.
pub fn check_against_kept(out: &Path) {
    let frames = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    let summary = masked_summary(&std::fs::read_to_string(out.join("summary.json")).unwrap());
    let _ = std::fs::remove_dir_all(out);

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
