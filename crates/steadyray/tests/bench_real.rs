//! `steadyray bench --clock real` on the simulated renderer (its fake clock): the frames
//! rendered and the refreshes that show them are what the display model gives for the
//! measured times, and bad display settings are clear errors that leave nothing behind.

mod scratch;
use scratch::scratch;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::SystemTime;
use steadyray_display::{DisplayConfig, DisplayFigures, RealClock, SyncMode};

mod support;

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn bench(args: &[&str], out: &Path) -> Output {
    Command::new(BIN)
        .args(["bench", "--simulate", "--clock", "real", "--out"])
        .arg(out)
        .args(args)
        .output()
        .expect("cannot run steadyray")
}

/// A bench of the CPU renderer at 32 × 18 under the real clock, 0.1 s after one warm-up
/// frame: the rest of the arguments are the caller's.
fn tiny_cpu_bench() -> Command {
    let mut command = Command::new(BIN);
    command
        .args([
            "bench",
            "--backend",
            "cpu",
            "--width",
            "32",
            "--height",
            "18",
        ])
        .args(["--clock", "real", "--duration", "0.1", "--warmup", "1"]);
    command
}

/// frames.csv's rows of one controller: (tp_ms + warp_ms, the frame's time on the display;
/// hand_over_ms, start_ms, visible_ms).
fn rows(out: &Path, controller: &str) -> Vec<[f64; 4]> {
    let csv = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let cols = ["tp_ms", "hand_over_ms", "start_ms", "visible_ms", "warp_ms"].map(col);
    lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|f| f[0] == controller)
        .map(|f| {
            let [tp, hand_over, start, visible, warp] = cols.map(|c| f[c].parse::<f64>().unwrap());
            [tp + warp, hand_over, start, visible]
        })
        .collect()
}

#[test]
fn frames_and_refreshes_are_what_the_display_model_says() {
    let tmp = scratch("model");
    let out = tmp.path().join("out");
    let output = bench(
        &[
            "--duration",
            "2",
            "--controllers",
            "fixed,predictive",
            "--no-in-band-fixed",
        ],
        &out,
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["clock"], "real");
    assert_eq!(summary["display"]["mode"], "vsync");
    let mut rendered = Vec::new();
    for c in summary["controllers"].as_array().unwrap() {
        let name = c["name"].as_str().unwrap();
        // Simulated frames take no wall time: no share of it is reported.
        assert!(c.get("busy_pct").is_none(), "{name}");
        let rows = rows(&out, name);
        // Replay the display model on the measured times (as written, to 4 decimals).
        let mut clock =
            RealClock::new(DisplayConfig::new(60.0, SyncMode::Vsync).unwrap(), 2.0).unwrap();
        for [tp, hand_over, start, visible] in &rows {
            let slot = clock.next_frame().expect("the model starts this frame too");
            assert!(
                (slot.start_ms - start).abs() < 1e-3,
                "{name}: {slot:?} vs {start}"
            );
            let frame = clock.present(*tp, *hand_over).unwrap();
            assert!((frame.visible_ms - visible).abs() < 1e-3, "{name}");
        }
        assert!(
            clock.next_frame().is_none(),
            "{name}: the model starts no more frames"
        );
        let figures = DisplayFigures::of(&clock.finish());
        assert_eq!(c["frames_rendered"], figures.frames_rendered, "{name}");
        assert_eq!(c["frames_shown"], figures.frames_shown, "{name}");
        let close = |key: &str, v: f64| (c[key].as_f64().unwrap() - v).abs() < 1e-6;
        assert!(close("displayed_fps", figures.displayed_fps), "{name}");
        assert!(close("repeated_pct", figures.repeated_pct), "{name}");
        assert!(
            close("latency_ms_mean", figures.latency_ms_mean.unwrap()),
            "{name}"
        );
        rendered.push(figures.frames_rendered);
    }
    // The simulated fixed S=1 takes a few ms a frame: a frame every refresh, 120 in 2 s. The
    // predictive controller fills its 15-20 ms band: with the hand-over most frames miss a
    // refresh, and it renders fewer frames in the same time.
    assert_eq!(rendered[0], 120);
    assert!(rendered[1] < 100, "{rendered:?}");
    let table = std::fs::read_to_string(out.join("table.md")).unwrap();
    assert!(table.contains("| predictive |"), "{table}");
}

#[test]
fn bad_display_settings_are_clear_errors_and_write_nothing() {
    let tmp = scratch("bad");
    let out = tmp.path().join("out");
    let cases: [(&[&str], &str); 6] = [
        (&["--refresh", "0"], "refresh rate 0"),
        (&["--refresh", "NaN"], "refresh rate NaN"),
        (&["--duration", "-1"], "duration -1"),
        (&["--duration", "NaN"], "duration NaN"),
        (&["--vrr", "60-48"], "MIN-MAX"),
        (&["--vrr", "48-144", "--vsync", "off"], "--vsync"),
    ];
    for (args, expected) in cases {
        let output = bench(args, &out);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?} was accepted");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
    // A band aligned with the display leaves the measured hand-over (1 ms simulated) and a
    // 5 % margin under the refresh: at 60 Hz, [11.5, 14.83] ms for every refresh.
    let output = bench(
        &[
            "--band",
            "refresh",
            "--duration",
            "0.5",
            "--controllers",
            "fixed",
            "--no-in-band-fixed",
        ],
        &out,
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let band = summary["band_ms"].as_array().unwrap();
    assert!((band[0].as_f64().unwrap() - 11.5).abs() < 1e-9, "{band:?}");
    assert!((band[1].as_f64().unwrap() - (1000.0 / 60.0 * 0.95 - 1.0)).abs() < 1e-9);
    assert_eq!(summary["aligned_band"]["hand_over_ms"], 1.0);
    std::fs::remove_dir_all(&out).unwrap();
    // An unwritable video folder fails before any run, not after them.
    let output = Command::new(BIN)
        .args([
            "bench",
            "--backend",
            "cpu",
            "--clock",
            "real",
            "--video",
            "/proc/steadyray",
        ])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("--video: cannot"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("bench: corridor"),
        "no run started: {stderr}"
    );
    assert!(!out.exists());
    let output = Command::new(BIN)
        .args(["bench", "--simulate", "--duration", "1", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("--clock real"),
        "{stderr}"
    );
}

/// A tiny CPU bench with --video and --quality: a complete video folder (every refresh of the
/// screen and of the reference, timings, index) and the displayed FLIP in summary.json; a
/// second bench reuses the references (outside a git checkout, whose uncommitted changes
/// could have changed the renderer).
#[test]
fn video_and_displayed_quality_on_the_cpu_renderer() {
    let tmp = scratch("video");
    let (out, video) = (tmp.path().join("out"), tmp.path().join("video"));
    let run = || {
        let output = tiny_cpu_bench()
            .current_dir(tmp.path())
            .args([
                "--controllers",
                "fixed",
                "--no-in-band-fixed",
                "--no-best-looking-fixed",
                "--reference-spp",
                "4",
            ])
            .args(["--quality", "--every", "2", "--video"])
            .arg(&video)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        assert!(output.status.success(), "{stderr}");
        stderr
    };
    let first = run();
    assert!(!first.contains("reusing"), "{first}");
    let index: Value =
        serde_json::from_str(&std::fs::read_to_string(video.join("video.json")).unwrap()).unwrap();
    assert_eq!(index["refreshes"], 6);
    assert_eq!(index["viewing"]["name"], "standard_fhd");
    let folder = video.join(index["runs"][0]["folder"].as_str().unwrap());
    for i in 0..6 {
        let name = format!("frame_{i:05}.png");
        for dir in [folder.join("displayed"), video.join("reference")] {
            let picture = image::open(dir.join(&name)).unwrap();
            assert_eq!((picture.width(), picture.height()), (32, 18));
        }
    }
    assert!(!folder.join("displayed").join("frame_00006.png").exists());
    let timings = std::fs::read_to_string(folder.join("timings.csv")).unwrap();
    assert_eq!(timings.lines().count(), 7, "{timings}");
    assert!(
        timings
            .lines()
            .nth(1)
            .unwrap()
            .starts_with("0,0.0000,warmup"),
        "{timings}"
    );
    let y4m = std::fs::read(folder.join("displayed.y4m")).unwrap();
    assert!(y4m.starts_with(b"YUV4MPEG2 W32 H18 F60:1"));
    let header = y4m.iter().position(|&b| b == b'\n').unwrap() + 1;
    assert_eq!(
        y4m.len() - header,
        6 * (6 + 3 * 32 * 18),
        "six frames of 4:4:4"
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let fixed = &summary["controllers"][0];
    // Refresh 0 shows the last warm-up frame (a refresh before the path's start): the
    // scores begin with the run's first frame on screen.
    assert_eq!(fixed["displayed_samples"], 2, "refreshes 3 and 4");
    let displayed = std::fs::read_to_string(out.join("displayed.csv")).unwrap();
    let rows: Vec<&str> = displayed.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{displayed}");
    assert!(
        rows.iter()
            .all(|row| row.split(',').nth(3).is_some_and(|frame| !frame.is_empty())),
        "{displayed}"
    );
    assert!(timings.contains("0,0.0000,warmup,-0.016667,"), "{timings}");
    let flip = fixed["displayed_flip_mean"].as_f64().unwrap();
    assert!(flip > 0.0 && flip < 0.5, "{flip}");
    assert!(fixed["frame_flip_mean"].as_f64().unwrap() <= flip + 1e-9);
    let age_flip = fixed["age_flip_mean"].as_f64().unwrap();
    assert!((0.0..0.5).contains(&age_flip), "{age_flip}");
    // The CPU renderer's frames take wall time: their share of the run's is reported.
    let busy = fixed["busy_pct"].as_f64().unwrap();
    assert!(busy > 0.0 && busy <= 100.0, "{busy}");
    assert!(first.contains("of the run's"), "{first}");
    let second = run();
    assert!(second.contains("reusing the references"), "{second}");
    let again: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        again["controllers"][0]["displayed_flip_mean"],
        fixed["displayed_flip_mean"]
    );
}

/// `--references DIR`: the first tiny CPU bench renders its references into the store, a
/// second one finds every reference there and renders none (the store gains no file), and
/// scores the same; without --quality or --video, or under the frame clock, it is refused.
/// (Run outside a git checkout, whose uncommitted changes to the renderer would make each
/// bench render its own.)
#[test]
fn a_reference_store_is_filled_once_and_shared() {
    let tmp = scratch("store");
    let (out, store) = (tmp.path().join("out"), tmp.path().join("store"));
    let run = || {
        let output = tiny_cpu_bench()
            .current_dir(tmp.path())
            .args(["--controllers", "fixed", "--no-best-fixed"])
            .args(["--reference-spp", "4", "--quality", "--every", "2"])
            .arg("--references")
            .arg(&store)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let summary: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        summary["controllers"][0]["displayed_flip_mean"].clone()
    };
    let stored = |store: &Path| -> Vec<PathBuf> {
        let folders: Vec<PathBuf> = std::fs::read_dir(store)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        assert_eq!(folders.len(), 1, "one set-up: {folders:?}");
        let mut files: Vec<PathBuf> = std::fs::read_dir(&folders[0])
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        files.sort();
        files
    };
    let first = run();
    let files = stored(&store);
    assert!(files.iter().any(|f| f.ends_with("key.json")), "{files:?}");
    assert!(
        files.len() >= 3,
        "the key and the sampled references: {files:?}"
    );
    let times: Vec<SystemTime> = files
        .iter()
        .map(|f| std::fs::metadata(f).unwrap().modified().unwrap())
        .collect();
    let second = run();
    assert_eq!(stored(&store), files, "nothing new rendered");
    let again: Vec<SystemTime> = files
        .iter()
        .map(|f| std::fs::metadata(f).unwrap().modified().unwrap())
        .collect();
    assert_eq!(again, times, "nothing rewritten");
    assert!(first.as_f64().is_some(), "{first}");
    assert_eq!(second, first);
    for (flags, says) in [
        (vec!["--clock", "real"], "--quality or --video"),
        (vec!["--clock", "frames"], "need --clock real"),
    ] {
        let output = Command::new(BIN)
            .args(["bench", "--backend", "cpu", "--references"])
            .arg(&store)
            .args(flags)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && stderr.contains(says),
            "{stderr}"
        );
    }
}

/// With warped refreshes, a band of two refreshes a frame leaves room for the warp that
/// shows the refresh between two frames, its cost measured before the runs; a band of one
/// refresh has no refresh between frames and leaves none. The runs without the history
/// (`--temporal both`) show no warps and keep the band without them.
#[test]
fn a_warped_band_leaves_room_for_the_warps_between_frames() {
    let tmp = scratch("warped-band");
    let out = tmp.path().join("out");
    let run_with = |band: &str, temporal: &str| -> Value {
        let output = tiny_cpu_bench()
            .args(["--controllers", "fixed", "--no-in-band-fixed"])
            .args(["--temporal", temporal, "--warp", "--band", band, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{stderr}");
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
    };
    let run = |band: &str| run_with(band, "on");
    let period = 1000.0 / 60.0;
    let summary = run("refresh:2");
    let aligned = &summary["aligned_band"];
    assert_eq!(aligned["refreshes"], 2);
    let hand_over = aligned["hand_over_ms"].as_f64().unwrap();
    let warp = aligned["warp_ms"].as_f64().unwrap();
    assert!(warp > 0.0 && warp < period, "{warp}");
    let band = summary["band_ms"].as_array().unwrap();
    let (tmin, tmax) = (band[0].as_f64().unwrap(), band[1].as_f64().unwrap());
    assert!(
        (tmax - (2.0 * period * 0.95 - hand_over - warp)).abs() < 1e-9,
        "{tmax} {hand_over} {warp}"
    );
    assert!(
        (tmax - tmin - 0.2 * 2.0 * period).abs() < 1e-9,
        "{tmin} {tmax}"
    );
    assert_eq!(summary["controllers"][0]["band_ms"], summary["band_ms"]);
    assert!(aligned.get("plain_band_ms").is_none(), "{aligned}");

    let both = run_with("refresh:2", "both");
    let warp = both["aligned_band"]["warp_ms"].as_f64().unwrap();
    let plain = &both["aligned_band"]["plain_band_ms"];
    let runs = both["controllers"].as_array().unwrap();
    assert_eq!(runs.len(), 2, "{both}");
    assert!(!runs[0]["name"].as_str().unwrap().contains("+temporal"));
    assert_eq!(&runs[0]["band_ms"], plain);
    assert_eq!(runs[1]["band_ms"], both["band_ms"]);
    for k in 0..2 {
        let (plain, warped) = (
            plain[k].as_f64().unwrap(),
            both["band_ms"][k].as_f64().unwrap(),
        );
        assert!(
            (plain - warped - warp).abs() < 1e-9,
            "{plain} {warped} {warp}"
        );
    }

    let summary = run("refresh");
    assert_eq!(summary["aligned_band"]["warp_ms"], 0.0);
}

/// A `perceptual` controller under `--warp` is told what a warped refresh costs (measured
/// before the runs), so that its bands of two or more refreshes leave room for the warps.
#[test]
fn a_perceptual_controller_is_told_the_warps_cost() {
    let tmp = scratch("perceptual-warp");
    let out = tmp.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    let model_path = out.join("motion.json");
    support::write_one_point_model(&model_path, [8.0, 8.0]);
    let output = tiny_cpu_bench()
        .arg("--controllers")
        .arg(format!("perceptual:model={}", model_path.display()))
        .args(["--no-in-band-fixed", "--temporal", "on", "--warp", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let told = stderr
        .split("bench: perceptual: warped refresh ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no warp passed on in: {stderr}"));
    assert!(told > 0.0 && told < 1000.0 / 60.0, "{told}");
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let name = summary["controllers"][0]["name"].as_str().unwrap();
    assert!(
        name.starts_with("perceptual") && !name.contains("warp="),
        "{name}"
    );
}

/// `--only-best-looking-fixed` on the CPU renderer at 32 × 18: every candidate runs for the
/// display span and is scored, and the bench reports the one with the lowest displayed FLIP
/// as its only run (in summary.json and frames.csv); with --video only the winner's video
/// is left.
#[test]
fn the_best_looking_fixed_quality_is_the_candidate_with_the_lowest_displayed_flip() {
    let tmp = scratch("best-looking");
    let (out, video) = (tmp.path().join("out"), tmp.path().join("video"));
    let output = tiny_cpu_bench()
        .current_dir(tmp.path())
        .args(["--only-best-looking-fixed", "--quality", "--every", "2"])
        .args(["--reference-spp", "4", "--video"])
        .arg(&video)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    // "bench: best-looking fixed S=.. R=..: displayed FLIP 0.1234", one line per candidate.
    let tried: Vec<(&str, f64)> = stderr
        .lines()
        .filter_map(|l| l.strip_prefix("bench: "))
        .filter_map(|l| l.split_once(": displayed FLIP "))
        .map(|(name, flip)| (name, flip.parse().unwrap()))
        .collect();
    assert_eq!(tried.len(), 9, "{stderr}");
    let lowest = tried.iter().map(|t| t.1).fold(f64::INFINITY, f64::min);
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let runs = summary["controllers"].as_array().unwrap();
    assert_eq!(runs.len(), 1, "{summary}");
    let name = runs[0]["name"].as_str().unwrap();
    assert!(name.starts_with("best-looking fixed S="), "{name}");
    let (_, flip) = tried.iter().find(|t| t.0 == name).unwrap();
    assert_eq!(*flip, lowest, "{stderr}");
    let reported = runs[0]["displayed_flip_mean"].as_f64().unwrap();
    assert!((reported - lowest).abs() < 1e-4, "{reported} {lowest}");
    let csv = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    assert!(csv.lines().skip(1).all(|l| l.starts_with(name)), "{csv}");
    let index: Value =
        serde_json::from_str(&std::fs::read_to_string(video.join("video.json")).unwrap()).unwrap();
    assert_eq!(index["runs"].as_array().unwrap().len(), 1);
    assert_eq!(index["runs"][0]["name"], name);
    let folders = std::fs::read_dir(&video).unwrap().filter(|e| {
        let path = e.as_ref().unwrap().path();
        path.is_dir() && !path.ends_with("reference")
    });
    assert_eq!(folders.count(), 1, "the losers' videos are removed");
}

/// The best-looking fixed quality is chosen by the displayed quality: the flag without
/// `--clock real --quality` is refused, naming it, before the scene loads (a scene that does
/// not exist is not the error) and before anything is written.
#[test]
fn only_best_looking_fixed_needs_the_displayed_quality() {
    let tmp = scratch("best-looking-refused");
    let out = tmp.path().join("out");
    for clock in [&["--clock", "real"][..], &["--quality"], &[]] {
        let output = Command::new(BIN)
            .args([
                "bench",
                "--only-best-looking-fixed",
                "--scene",
                "no/such/scene.toml",
            ])
            .args(clock)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{clock:?}");
        assert!(
            stderr.contains("--only-best-looking-fixed")
                && stderr.contains("--clock real --quality"),
            "{clock:?}: {stderr}"
        );
        assert!(!out.exists(), "{clock:?} wrote {}", out.display());
    }
}
