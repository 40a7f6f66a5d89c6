//! The temporal mode on the command line: `render --temporal` writes the accumulated
//! history at full size (also at a reduced scale) and every frame with `--sequence`, or with
//! `--shown` the picture the display shows; `bench
//! --temporal both` runs every controller without and with it; `--warp` warps the temporal
//! runs' refreshes without a new frame; bad values are clear errors.

mod scratch;
use scratch::scratch;
use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};
use steadyray_render::Image;
use steadyray_render::temporal::{HISTORY_CAP, SHARPEN, sharpened_image};

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("cannot run steadyray")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn render_writes_the_history_and_the_sequence() {
    let tmp = scratch("render");
    let dir = tmp.path();
    let out = dir.join("history.png");
    let sequence = dir.join("frames");
    let output = run(&[
        "render",
        "--backend",
        "cpu",
        "--width",
        "64",
        "--height",
        "36",
        "--spp",
        "1",
        "--depth",
        "4",
        "--frame",
        "10",
        "--frames",
        "720",
        "--temporal",
        "6",
        "--scale",
        "0.5",
        "--sequence",
        sequence.to_str().unwrap(),
        "--stats",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let image = image::open(&out).unwrap();
    assert_eq!(
        (image.width(), image.height()),
        (64, 36),
        "the history's size"
    );
    for i in 0..6 {
        let frame = image::open(sequence.join(format!("frame_{i:04}.png"))).unwrap();
        assert_eq!((frame.width(), frame.height()), (64, 36));
    }
    let stats: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(stats["temporal_frames"], 6);
    assert_eq!(
        (stats["width"].clone(), stats["height"].clone()),
        (32.into(), 18.into())
    );
}

/// `render --temporal --shown` writes what the display shows: the history, written as it is
/// (linear, .exr) by the same command without `--shown`, sharpened for display at the
/// strength its frames call for, and tone-mapped; a `.exr` output with `--shown` is an
/// error.
#[test]
fn render_shown_writes_the_sharpened_history() {
    let tmp = scratch("shown");
    let dir = tmp.path();
    let render = |extra: &[&str], out: &PathBuf| {
        let mut args = vec![
            "render",
            "--backend",
            "cpu",
            "--width",
            "64",
            "--height",
            "36",
            "--spp",
            "1",
            "--depth",
            "4",
            "--time",
            "0.5",
            "--temporal",
            "6",
            "--scale",
            "0.5",
            "-o",
        ];
        args.push(out.to_str().unwrap());
        args.extend(extra);
        run(&args)
    };
    let history_path = dir.join("history.exr");
    let output = render(&[], &history_path);
    assert!(output.status.success(), "{}", stderr(&output));
    let shown_path = dir.join("shown.png");
    let output = render(&["--shown"], &shown_path);
    assert!(output.status.success(), "{}", stderr(&output));

    let history = image::open(&history_path).unwrap().into_rgb32f();
    let history = Image {
        width: 64,
        height: 36,
        pixels: history.pixels().map(|p| p.0).collect(),
    };
    // One sample a frame pixel at scale 0.5: a quarter of a sample a history pixel.
    let strength = SHARPEN * (1.0 - 0.25 / HISTORY_CAP);
    let expected = sharpened_image(&history, strength).to_srgb8_rgba();
    let shown = image::open(&shown_path).unwrap().into_rgba8().into_raw();
    assert!(
        shown == expected,
        "--shown did not write the sharpened history"
    );
    assert!(
        shown != history.to_srgb8_rgba(),
        "the sharpening changed nothing: the test shows nothing"
    );

    let output = render(&["--shown"], &dir.join("shown.exr"));
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("must be a .png"),
        "{}",
        stderr(&output)
    );
    assert!(!dir.join("shown.exr").exists(), "nothing written");
}

#[test]
fn bad_temporal_values_are_errors() {
    let tmp = scratch("bad");
    let dir = tmp.path();
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    for (args, message) in [
        (vec!["--temporal", "0"], "at least 1 frame"),
        (vec!["--temporal", "4", "--scale", "1.5"], "outside (0, 1]"),
        (vec!["--temporal", "4", "--rate", "0"], "positive number"),
    ] {
        let mut all = vec![
            "render",
            "--backend",
            "cpu",
            "--width",
            "16",
            "--height",
            "9",
            "-o",
            out,
        ];
        all.extend(args);
        let output = run(&all);
        assert!(!output.status.success());
        assert!(stderr(&output).contains(message), "{}", stderr(&output));
    }
    assert!(!dir.join("x.png").exists(), "nothing written");
    let output = run(&[
        "bench",
        "--simulate",
        "--temporal",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("--temporal needs a renderer"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn bench_runs_every_controller_without_and_with_history() {
    let tmp = scratch("bench");
    let dir = tmp.path();
    let output = run(&[
        "bench",
        "--backend",
        "cpu",
        "--width",
        "48",
        "--height",
        "27",
        "--frames",
        "6",
        "--warmup",
        "1",
        "--controllers",
        "fixed,predictive",
        "--no-in-band-fixed",
        "--temporal",
        "both",
        "--quality",
        "--every",
        "3",
        "--reference-spp",
        "4",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["temporal"], "both");
    let names: Vec<&str> = summary["controllers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "fixed S=1 R=16",
            "fixed S=1 R=16 +temporal",
            "predictive",
            "predictive +temporal"
        ]
    );
    for c in summary["controllers"].as_array().unwrap() {
        assert!(c["flip_mean"].as_f64().unwrap() > 0.0, "{c}");
    }
}

/// `--warp` under the real clock: the temporal run shows warps at its refreshes without a
/// new frame (at least refresh 0, which shows the warm-up frame), and says so in
/// `summary.json` and the video's `timings.csv`; the plain run does not warp.
#[test]
fn bench_warps_the_temporal_runs_refreshes() {
    let tmp = scratch("warp");
    let dir = tmp.path();
    let video = dir.join("video");
    let output = run(&[
        "bench",
        "--backend",
        "cpu",
        "--width",
        "48",
        "--height",
        "27",
        "--clock",
        "real",
        "--duration",
        "0.2",
        "--warmup",
        "2",
        "--controllers",
        "predictive",
        "--temporal",
        "both",
        "--warp",
        "--quality",
        "--every",
        "1",
        "--reference-spp",
        "4",
        "--video",
        video.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["warp"], true);
    let controllers = summary["controllers"].as_array().unwrap();
    let names: Vec<&str> = controllers
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["predictive", "predictive +temporal +warp"]);
    assert!(
        controllers[0].get("warps_shown").is_none(),
        "{}",
        controllers[0]
    );
    let warped = &controllers[1];
    assert!(warped["warps_shown"].as_u64().unwrap() >= 1, "{warped}");
    assert!(warped["warp_ms_mean"].as_f64().unwrap() > 0.0, "{warped}");
    assert!(
        warped["displayed_flip_mean"].as_f64().unwrap() > 0.0,
        "{warped}"
    );
    let timings =
        std::fs::read_to_string(video.join("predictive__temporal__warp/timings.csv")).unwrap();
    let mut lines = timings.lines();
    assert!(lines.next().unwrap().ends_with(",warped"));
    let first = lines.next().unwrap();
    assert!(
        first.starts_with("0,0.0000,warmup") && first.ends_with(",1"),
        "refresh 0 shows the warm-up frame warped: {first}"
    );
}

#[test]
fn bad_warp_options_are_errors() {
    let tmp = scratch("bad-warp");
    let dir = tmp.path();
    let out = dir.to_str().unwrap();
    for (args, message) in [
        (vec!["--warp"], "need --clock real"),
        (
            vec!["--clock", "real", "--warp"],
            "needs --temporal on or both",
        ),
        (
            vec!["--clock", "real", "--temporal", "--warp", "--vsync", "off"],
            "vsync on",
        ),
    ] {
        let mut all = vec!["bench", "--backend", "cpu", "--out", out];
        all.extend(args);
        let output = run(&all);
        assert!(!output.status.success(), "{all:?}");
        assert!(
            stderr(&output).contains(message),
            "{all:?}: {}",
            stderr(&output)
        );
    }
    assert!(!dir.join("summary.json").exists(), "nothing written");
}
