//! `steadyray view` in a real window: under an Xvfb server this test starts itself, with
//! lavapipe (or any adapter) for the GPU backend. The screenshot of the last frame must show
//! the scene (outside the HUD, the same pixels as `steadyray render` of the same view) and
//! the HUD (inside its area, not the plain render).
//!
//! Without Xvfb (or an adapter) the window tests skip loudly, unless
//! `STEADYRAY_REQUIRE_GPU=1`, which makes them fail. The bad-input tests need neither.

mod scratch;
use scratch::scratch;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

mod support;

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn required() -> bool {
    std::env::var("STEADYRAY_REQUIRE_GPU").as_deref() == Ok("1")
}

/// Skips (returns) loudly, or fails when the GPU checks are required.
macro_rules! skip {
    ($($why:tt)*) => {{
        let why = format!($($why)*);
        if required() {
            panic!("STEADYRAY_REQUIRE_GPU=1 but {why}");
        }
        eprintln!("SKIPPED: {why}");
        return Default::default();
    }};
}

/// An Xvfb server on a display it chose itself, stopped when dropped.
struct Xvfb {
    child: Child,
    display: String,
    number: u32,
}

/// The lock and socket files an X server on display `n` leaves in /tmp.
fn display_files(n: u32) -> [PathBuf; 2] {
    [
        PathBuf::from(format!("/tmp/.X{n}-lock")),
        PathBuf::from(format!("/tmp/.X11-unix/X{n}")),
    ]
}

impl Xvfb {
    /// Starts Xvfb with `-displayfd`, so that the server itself takes a free display (atomically,
    /// by binding its socket) and reports it once it accepts connections: tests running at once
    /// never share, or kill, each other's server. An error says why none started.
    fn start() -> Result<Self, String> {
        let mut child = Command::new("Xvfb")
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| format!("cannot run Xvfb ({e}); install the xvfb package"))?;
        let stdout = child.stdout.take().expect("Xvfb's stdout is piped");
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = std::io::BufRead::read_line(&mut std::io::BufReader::new(stdout), &mut line);
            let _ = sender.send(line);
        });
        let line = receiver.recv_timeout(Duration::from_secs(20));
        match line.map(|l| l.trim().parse::<u32>()) {
            Ok(Ok(number)) => Ok(Self {
                child,
                display: format!(":{number}"),
                number,
            }),
            other => {
                let _ = child.kill();
                let _ = child.wait();
                Err(format!("Xvfb reported no display within 20 s ({other:?})"))
            }
        }
    }
}

impl Drop for Xvfb {
    /// Stops the server with SIGTERM, so that it removes its own lock and socket. Only when it
    /// does not stop is it killed and are its files removed here, so that test runs do not use
    /// up the displays.
    fn drop(&mut self) {
        let terminated = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status()
            .is_ok_and(|s| s.success());
        let deadline = Instant::now() + Duration::from_secs(5);
        while terminated && Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        for file in display_files(self.number) {
            let _ = std::fs::remove_file(file);
        }
    }
}

fn run(display: Option<&str>, args: &[&str]) -> Output {
    let mut command = Command::new(BIN);
    command
        .args(args)
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .env("RUST_LOG", "error");
    match display {
        Some(d) => command.env("DISPLAY", d),
        None => command.env_remove("DISPLAY"),
    };
    command.output().expect("the steadyray binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn rgba(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
        .into_rgba8()
}

/// The window: 640x360 pixels; the frame: 160x90 at full scale (4x4 window pixels each).
const WINDOW: (u32, u32) = (640, 360);
const PIXEL: u32 = 4;

/// `view`'s arguments for that window, 30 frames long.
fn window_args() -> Vec<String> {
    [
        ("--width", WINDOW.0),
        ("--height", WINDOW.1),
        ("--pixel-size", PIXEL),
        ("--frames", 30),
    ]
    .iter()
    .flat_map(|(key, value)| [key.to_string(), value.to_string()])
    .collect()
}

/// Runs `view --frames 30 --screenshot` on `backend` with the temporal arguments `flag`
/// (none: the default) and checks the screenshot against a `render` of the same view; with
/// `temporal` (what `flag` must amount to), both accumulate the 30 frames of the still view
/// (`render --temporal 30`) and must agree as well. Returns the view's summary (none when
/// skipped).
fn window_matches_render(backend: &str, flag: &[&str], temporal: bool) -> Option<Value> {
    let xvfb = match Xvfb::start() {
        Ok(x) => x,
        Err(why) => skip!("no X server for the window test: {why}"),
    };
    let tmp = scratch(&format!("{backend}-{temporal}-{}", flag.join("")));
    let dir = tmp.path();
    let shot = dir.join("view.png");
    let reference = dir.join("render.png");
    let window = window_args();
    let mut view_args = vec![
        "view",
        "--scene",
        "corridor",
        "--backend",
        backend,
        "--controller",
        "fixed",
        "--spp-min",
        "1",
        "--depth-max",
        "6",
        "--screenshot",
        shot.to_str().unwrap(),
    ];
    view_args.extend(window.iter().map(String::as_str));
    view_args.extend(flag);
    let view = run(Some(&xvfb.display), &view_args);
    let stderr = text(&view.stderr);
    assert!(!stderr.contains("panicked"), "the view panicked:\n{stderr}");
    if !view.status.success() && backend == "gpu" && stderr.contains("no GPU adapter") {
        skip!("no GPU adapter for the window: {stderr}");
    }
    assert!(
        view.status.success(),
        "view failed ({}):\n{stderr}",
        view.status
    );
    let summary: Value = serde_json::from_str(text(&view.stdout).trim())
        .unwrap_or_else(|e| panic!("no JSON summary ({e}):\n{}", text(&view.stdout)));
    assert_eq!(summary["frames"], 30, "{summary}");
    assert_eq!(
        summary["last_frame"],
        serde_json::json!([160, 90]),
        "{summary}"
    );
    assert_eq!(
        summary["window"],
        serde_json::json!([WINDOW.0, WINDOW.1]),
        "{summary}"
    );
    assert!(
        summary["render_ms"]["mean"].as_f64().unwrap() > 0.0,
        "{summary}"
    );
    assert!(
        summary["present_ms"]["mean"].as_f64().unwrap() > 0.0,
        "{summary}"
    );

    let mut render_args = vec![
        "render",
        "--scene",
        "corridor",
        "--backend",
        backend,
        "--width",
        "160",
        "--height",
        "90",
        "--spp",
        "1",
        "--depth",
        "6",
        "-o",
        reference.to_str().unwrap(),
    ];
    if temporal {
        render_args.extend(["--temporal", "30"]);
    }
    let render = run(None, &render_args);
    assert!(
        render.status.success(),
        "render failed:\n{}",
        text(&render.stderr)
    );

    let shot = rgba(&shot);
    let reference = rgba(&reference);
    assert_eq!(shot.dimensions(), WINDOW);
    let hud: Vec<f64> = summary["hud_rect"]
        .as_array()
        .expect("the HUD was shown")
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // Window pixels inside the HUD (with a margin for its shadow).
    let in_hud = |x: u32, y: u32| {
        let (x, y) = (f64::from(x), f64::from(y));
        x >= hud[0] - 16.0 && x < hud[2] + 16.0 && y >= hud[1] - 16.0 && y < hud[3] + 16.0
    };
    let (mut outside, mut outside_bad, mut outside_err) = (0u64, 0u64, 0u64);
    let (mut inside, mut inside_err) = (0u64, 0u64);
    for y in 0..WINDOW.1 {
        for x in 0..WINDOW.0 {
            let a = shot.get_pixel(x, y).0;
            let b = reference.get_pixel(x / PIXEL, y / PIXEL).0;
            let err = (0..3).map(|c| a[c].abs_diff(b[c]) as u64).max().unwrap();
            if in_hud(x, y) {
                inside += 1;
                inside_err += err;
            } else {
                outside += 1;
                outside_err += err;
                outside_bad += u64::from(err > 2);
            }
        }
    }
    assert!(
        outside > 50_000,
        "too little of the frame is outside the HUD: {hud:?}"
    );
    let bad_share = outside_bad as f64 / outside as f64;
    let mean_err = outside_err as f64 / outside as f64;
    eprintln!(
        "{backend}: outside the HUD {outside} px, {:.3} % off by more than 2 levels, mean error \
         {mean_err:.3}; inside the HUD mean difference {:.1}",
        bad_share * 100.0,
        inside_err as f64 / inside as f64
    );
    assert!(
        bad_share < 0.005 && mean_err < 0.1,
        "the frame differs from the render"
    );
    assert!(
        inside_err as f64 / inside as f64 > 10.0,
        "the HUD's area looks like the plain render: no HUD drawn?"
    );
    Some(summary)
}

/// On a GPU the view starts in its recommended configuration, `--band refresh --temporal
/// off` (docs/results/viewer.md).
#[test]
fn gpu_window_shows_the_scene_and_the_hud() {
    window_matches_render("gpu", &[], false);
}

#[test]
fn cpu_window_shows_the_scene_and_the_hud() {
    window_matches_render("cpu", &["--temporal", "off"], false);
}

/// A bare `--temporal` turns the mode on.
#[test]
fn gpu_window_shows_the_temporal_history() {
    window_matches_render("gpu", &["--temporal"], true);
}

/// On the CPU renderer the view starts in its recommended configuration
/// (docs/results/viewer.md): `--band refresh:2 --temporal on --warp`, one warped refresh
/// after every frame.
#[test]
fn cpu_window_starts_in_the_recommended_configuration() {
    let Some(summary) = window_matches_render("cpu", &[], true) else {
        return;
    };
    assert_eq!(summary["warped_refreshes"], 30, "{summary}");
}

/// `--warp` at two refreshes a frame shows one warped refresh after every frame, and the run
/// ends on the last frame's: the still camera's warp is the history's picture itself.
fn window_shows_warped_refreshes_between_frames(backend: &str) {
    let flag = ["--band", "refresh:2", "--warp"];
    let Some(summary) = window_matches_render(backend, &flag, true) else {
        return;
    };
    assert_eq!(summary["warped_refreshes"], 30, "{summary}");
    assert!(
        summary["warp_ms"]["mean"].as_f64().unwrap() > 0.0,
        "{summary}"
    );
}

#[test]
fn cpu_window_shows_warped_refreshes_between_frames() {
    window_shows_warped_refreshes_between_frames("cpu");
}

#[test]
fn gpu_window_shows_warped_refreshes_between_frames() {
    window_shows_warped_refreshes_between_frames("gpu");
}

/// A `perceptual` controller that holds one refresh a frame under `--band refresh:2 --warp`
/// shows (almost) no warped refresh, and the band still gets the warps' cost: the window
/// times warps it does not show (and tells the controller, as it does the hand-over).
#[test]
fn the_band_measures_warps_that_no_refresh_shows() {
    let xvfb = match Xvfb::start() {
        Ok(x) => x,
        Err(why) => skip!("no X server for the window test: {why}"),
    };
    let tmp = scratch("unshown-warps");
    let dir = tmp.path();
    let model = dir.join("motion.json");
    // One refresh a frame scores far above two, and the controller moves to it at once.
    support::write_one_point_model(&model, [9.0, 5.0]);
    let controller = format!("perceptual:model={};hold_ms=0", model.display());
    let mut args = vec![
        "view",
        "--backend",
        "cpu",
        "--controller",
        &controller,
        "--band",
        "refresh:2",
        "--warp",
    ];
    let mut window = window_args();
    *window.last_mut().unwrap() = "40".into();
    args.extend(window.iter().map(String::as_str));
    let out = run(Some(&xvfb.display), &args);
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(out.status.success(), "view failed:\n{stderr}");
    let summary: Value = serde_json::from_str(text(&out.stdout).trim()).unwrap();
    assert_eq!(summary["frames"], 40, "{summary}");
    // A few may show before the controller has fitted its cost model and moved to one
    // refresh; fewer than the band needs measured (twice HAND_OVER_FRAMES, 20).
    let shown = summary["warped_refreshes"].as_u64().unwrap();
    assert!(shown < 20, "{summary}");
    let warp_ms = stderr
        .split(", warp ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no warp in the band's line: {stderr}"));
    assert!(warp_ms > 0.0, "{stderr}");
}

#[test]
fn playback_shows_recorded_frames() {
    let xvfb = match Xvfb::start() {
        Ok(x) => x,
        Err(why) => skip!("no X server for the playback test: {why}"),
    };
    let tmp = scratch("playback");
    let dir = tmp.path();
    let recording = dir.join("recording");
    std::fs::create_dir_all(&recording).unwrap();
    let mut csv = String::from("frame,presented_ms,tp_ms\n");
    for i in 0..4u8 {
        csv.push_str(&format!("{i},{},{}\n", u32::from(i) * 40, 10 + i));
        let colour = [60 * i, 200 - 40 * i, 90, 255];
        let frame = image::RgbaImage::from_pixel(80, 45, image::Rgba(colour));
        frame
            .save(recording.join(format!("frame_{i:05}.png")))
            .unwrap();
    }
    std::fs::write(recording.join("timings.csv"), csv).unwrap();
    let shot = dir.join("playback.png");
    let started = Instant::now();
    let out = run(
        Some(&xvfb.display),
        &[
            "view",
            "--playback",
            recording.to_str().unwrap(),
            "--width",
            "640",
            "--height",
            "360",
            "--frames",
            "4",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
    );
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    if !out.status.success() && stderr.contains("no GPU adapter") {
        skip!("no GPU adapter for the window: {stderr}");
    }
    assert!(out.status.success(), "playback failed:\n{stderr}");
    assert!(
        started.elapsed() >= Duration::from_millis(120),
        "4 frames 40 ms apart took {:?}",
        started.elapsed()
    );
    let summary: Value = serde_json::from_str(text(&out.stdout).trim()).unwrap();
    assert_eq!(summary["mode"], "playback");
    // Playback shows the frame due at each redraw, so a redraw late by a frame's 40 ms (a
    // loaded machine: tests run beside each other) skips one, as on a real display.
    let shown = summary["frames"].as_u64().unwrap();
    assert!((3..=4).contains(&shown), "{shown} recorded frames shown");
    // The last frame (i = 3) fills the window outside the HUD.
    let shot = rgba(&shot);
    assert_eq!(shot.get_pixel(630, 350).0, [180, 80, 90, 255]);
}

/// `view --band refresh:2` sets the band from the display after its first frames: under
/// Xvfb's 60 Hz (or the 60 Hz assumed), frames handed over by every second refresh.
#[test]
fn the_band_follows_the_display() {
    let xvfb = match Xvfb::start() {
        Ok(x) => x,
        Err(why) => skip!("no X server for the window test: {why}"),
    };
    let window = window_args();
    let mut args = vec!["view", "--backend", "cpu", "--band", "refresh:2"];
    args.extend(window.iter().map(String::as_str));
    let out = run(Some(&xvfb.display), &args);
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    if !out.status.success() && stderr.contains("no GPU adapter") {
        skip!("no GPU adapter for the window: {stderr}");
    }
    assert!(out.status.success(), "view failed:\n{stderr}");
    assert!(stderr.contains("--band refresh at"), "{stderr}");
    let summary: Value = serde_json::from_str(text(&out.stdout).trim()).unwrap();
    let band = &summary["band_ms"];
    let (tmin, tmax) = (band[0].as_f64().unwrap(), band[1].as_f64().unwrap());
    // Tmax = 0.95 · 2 refreshes − the hand-over; the band is 0.2 of the interval wide.
    let hz = stderr
        .split("--band refresh at ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no refresh rate in: {stderr}"));
    let interval = 2000.0 / hz;
    assert!(tmax < 0.95 * interval && tmax > 0.5 * interval, "{summary}");
    assert!((tmax - tmin - 0.2 * interval).abs() < 0.02, "{summary}");
}

#[test]
fn no_display_is_a_clean_error() {
    let out = run(None, &["view", "--frames", "1"]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("cannot open a window"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn a_broken_recording_is_a_clean_error() {
    let tmp = scratch("broken");
    let dir = tmp.path();
    std::fs::write(dir.join("timings.csv"), "frame,presented_ms,tp_ms\n0,0,5\n").unwrap();
    let out = run(None, &["view", "--playback", dir.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("frame_00000.png is missing"), "{stderr}");
    let out = run(
        None,
        &["view", "--playback", dir.join("nothing").to_str().unwrap()],
    );
    assert!(text(&out.stderr).contains("is not a folder"));
}

#[test]
fn losing_the_display_is_a_clean_error() {
    let xvfb = match Xvfb::start() {
        Ok(x) => x,
        Err(why) => skip!("no X server for the lost-display test: {why}"),
    };
    let mut view = Command::new(BIN)
        .args([
            "view",
            "--backend",
            "cpu",
            "--width",
            "320",
            "--height",
            "180",
        ])
        .env("DISPLAY", &xvfb.display)
        .env("RUST_LOG", "error")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(3));
    drop(xvfb);
    let deadline = Instant::now() + Duration::from_secs(30);
    while view.try_wait().unwrap().is_none() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(100));
    }
    if view.try_wait().unwrap().is_none() {
        let _ = view.kill();
        panic!("the view kept running after its display went away");
    }
    let out = view.wait_with_output().unwrap();
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("thread 'main' panicked"), "{stderr}");
    assert!(stderr.contains("error:"), "{stderr}");
}
