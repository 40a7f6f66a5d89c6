//! `steadyray suite`: a small suite end to end on the CPU renderer (two scenes, two methods,
//! two runs, tiny images and short stimuli): every cell runs once, a second call redoes
//! none, shards split the cells, and the table joins them; bad input is refused by name.

mod scratch;
use scratch::scratch;
use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn steadyray(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .output()
        .expect("steadyray runs")
}

/// `suite run` of the small suite into `out`, for shard `shard`.
/// Cells a `suite run`'s stderr says it ran, and said were done before.
fn counts(stderr: &str) -> (usize, usize) {
    let lines = stderr.lines().filter(|l| l.starts_with("suite: ["));
    let ran = lines.clone().filter(|l| l.contains(" took ")).count();
    (ran, lines.filter(|l| l.ends_with("done before")).count())
}

fn run_small(out: &Path, shard: &str) -> String {
    let out = out.display().to_string();
    let output = steadyray(&[
        "suite",
        "run",
        "-o",
        &out,
        "--runs",
        "2",
        "--shard",
        shard,
        "--scenes",
        "open,glass",
        "--methods",
        "refresh,fixed-s1-r16",
        "--duration",
        "0.25",
        "--",
        "--backend",
        "cpu",
        "--width",
        "64",
        "--height",
        "36",
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(output.status.success(), "{stderr}");
    stderr
}

#[test]
fn a_small_suite_runs_resumes_and_tabulates() {
    let tmp = scratch("small");
    let out = tmp.path();
    let first = run_small(out, "1/1");
    assert_eq!(counts(&first), (8, 0), "{first}");
    let second = run_small(out, "1/1");
    assert_eq!(counts(&second), (0, 8), "{second}");

    let table = steadyray(&["suite", "table", &out.display().to_string()]);
    let markdown = String::from_utf8_lossy(&table.stdout);
    assert!(
        table.status.success(),
        "{}",
        String::from_utf8_lossy(&table.stderr)
    );
    assert!(
        markdown.contains("| method | glass | open | mean rank | wins |"),
        "{markdown}"
    );
    assert!(markdown.contains("8 cells"), "{markdown}");
    for file in ["table.md", "table.json", "suite.png", "suite.svg"] {
        assert!(out.join(file).is_file(), "{file}");
    }
}

#[test]
fn shards_split_the_cells_between_folders() {
    let (tmp_a, tmp_b) = (scratch("shard-a"), scratch("shard-b"));
    let (a, b) = (tmp_a.path(), tmp_b.path());
    let ran_a = run_small(a, "1/2");
    let ran_b = run_small(b, "2/2");
    assert_eq!((counts(&ran_a).0, counts(&ran_b).0), (4, 4));
    let table = steadyray(&[
        "suite",
        "table",
        &a.display().to_string(),
        &b.display().to_string(),
    ]);
    assert!(String::from_utf8_lossy(&table.stdout).contains("8 cells"));
}

#[test]
fn bad_input_is_refused_by_name() {
    for (args, message) in [
        (&["suite", "run", "--shard", "3/2"][..], "shard `3/2`"),
        (
            &["suite", "run", "--scenes", "atrium"][..],
            "unknown scene `atrium`",
        ),
        (
            &["suite", "run", "--methods", "best"][..],
            "unknown method `best`",
        ),
        (&["suite", "run", "--runs", "0"][..], "K must be at least 1"),
        (
            &["suite", "table", "/nonexistent/suite"][..],
            "no finished cell",
        ),
    ] {
        let out = steadyray(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} was accepted");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
}
