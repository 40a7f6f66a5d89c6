//! `steadyray render --time` on the moving built-in scene: the world (and, without --yaw,
//! the camera) at that scene time, with its time and top-level update in `--stats`; bad
//! times, and a reference of one sample a pixel, are clear errors.

mod scratch;
use scratch::scratch;
use serde_json::Value;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn render(args: &[&str]) -> Output {
    Command::new(BIN)
        .arg("render")
        .args(["--backend", "cpu", "--width", "64", "--height", "36"])
        .args(["--spp", "1", "--depth", "3", "--warmup", "0"])
        .args(args)
        .output()
        .expect("the steadyray binary runs")
}

fn stats(out: &Output) -> Value {
    assert!(
        out.status.success(),
        "render failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_str(String::from_utf8_lossy(&out.stdout).trim()).unwrap()
}

#[test]
fn render_time_shows_the_world_at_that_time() {
    let tmp = scratch("time");
    let dir = tmp.path();
    let png = |t: &str| dir.join(format!("flyby-{t}.png"));
    let mut shots = Vec::new();
    for t in ["2", "5"] {
        let out = render(&[
            "--scene",
            "flyby",
            "--time",
            t,
            "--stats",
            "-o",
            png(t).to_str().unwrap(),
        ]);
        let s = stats(&out);
        assert_eq!(s["time_s"].as_f64(), Some(t.parse().unwrap()), "{s}");
        let accel = s["accel_ms"].as_f64().unwrap();
        assert!(
            accel >= 0.0 && accel <= s["render_ms"].as_f64().unwrap(),
            "{s}"
        );
        shots.push(image::open(png(t)).unwrap().into_rgba8());
    }
    assert_ne!(
        shots[0], shots[1],
        "the world and camera moved between 2 s and 5 s"
    );
    // The same time with the camera held still (--yaw) differs from another time only by
    // what moved: still a different picture while the swarm is out.
    let still = |t: &str| {
        let p = dir.join(format!("still-{t}.png"));
        let out = render(&[
            "--scene",
            "flyby",
            "--yaw",
            "0",
            "--time",
            t,
            "-o",
            p.to_str().unwrap(),
        ]);
        assert!(out.status.success());
        image::open(p).unwrap().into_rgba8()
    };
    assert_ne!(still("3"), still("5"), "the swarm appears at 4 s");
}

#[test]
fn bad_times_are_clear_errors() {
    let tmp = scratch("bad");
    let dir = tmp.path();
    let out_png = dir.join("x.png");
    for bad in ["nan", "inf"] {
        let out = render(&[
            "--scene",
            "flyby",
            "--time",
            bad,
            "-o",
            out_png.to_str().unwrap(),
        ]);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("not a finite number of seconds"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out_png.exists(), "no image for a refused render");
    }
    let out = render(&[
        "--time",
        "1",
        "--frame",
        "2",
        "-o",
        out_png.to_str().unwrap(),
    ]);
    assert!(!out.status.success(), "--time and --frame conflict");
}

/// A camera that is not finite is refused by the renderer (its rays overflowed the BVH's
/// traversal stack: a panic). Both renderers call the same check.
#[test]
fn a_camera_that_is_not_finite_is_a_clear_error() {
    let tmp = scratch("bad-camera");
    let dir = tmp.path();
    let out_png = dir.join("x.png");
    let out = render(&["--yaw", "nan", "-o", out_png.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.status.success());
    assert!(err.contains("cannot render from this camera"), "{err}");
    assert!(!out_png.exists(), "no image for a refused render");
}

#[test]
fn a_reference_of_one_sample_a_pixel_is_a_clear_error() {
    let tmp = scratch("reference");
    let dir = tmp.path();
    let out_png = dir.join("x.png");
    // The helper renders at S = 1.
    let out = render(&["--reference", "-o", out_png.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("a reference needs S >= 2"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out_png.exists(), "no image for a refused render");
}
