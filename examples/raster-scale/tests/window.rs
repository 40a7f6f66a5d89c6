//! The example in a real window under Xvfb (`xvfb-run`), on lavapipe or any adapter: the
//! controller must move the render scale with the load and keep far more frames in the band
//! than the same engine at a fixed full scale.
//!
//! Without `xvfb-run` or an adapter the window test skips loudly, unless
//! `STEADYRAY_REQUIRE_GPU=1`, which makes it fail. The bad-input tests need neither.

use serde_json::Value;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_raster-scale");

fn required() -> bool {
    std::env::var("STEADYRAY_REQUIRE_GPU").as_deref() == Ok("1")
}

/// Runs the example under `xvfb-run` with `args`: its summary, or why it could not run.
fn run_in_window(args: &[&str]) -> Result<Value, String> {
    let output = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1024x768x24", BIN])
        .args(args)
        .output()
        .map_err(|e| format!("cannot run xvfb-run ({e}); install the xvfb package"))?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!("raster-scale {args:?} failed: {stderr}"));
    }
    eprintln!("{stderr}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let line = stdout.lines().last().ok_or("no summary printed")?;
    serde_json::from_str(line).map_err(|e| format!("the summary is not JSON ({e}): {line}"))
}

fn number(summary: &Value, key: &str) -> f64 {
    summary[key]
        .as_f64()
        .unwrap_or_else(|| panic!("`{key}` missing from {summary}"))
}

/// The mean scale the run chose at load level `load`.
fn scale_at(summary: &Value, load: f64) -> f64 {
    summary["by_load"]
        .as_array()
        .expect("by_load")
        .iter()
        .find(|l| l["load"].as_f64() == Some(load))
        .and_then(|l| l["mean_scale"].as_f64())
        .unwrap_or_else(|| panic!("no scale at load {load} in {summary}"))
}

#[test]
fn the_controller_holds_the_band_where_a_fixed_scale_cannot() {
    let frames = ["--frames", "360", "--phase-frames", "90"];
    let runs = ["predictive", "fixed:scale=1"].map(|controller| {
        let mut args = vec!["--controller", controller];
        args.extend(frames);
        run_in_window(&args)
    });
    let [controlled, fixed] = match runs {
        [Ok(c), Ok(f)] => [c, f],
        [Err(e), _] | [_, Err(e)] => {
            if required() {
                panic!("STEADYRAY_REQUIRE_GPU=1 but {e}");
            }
            eprintln!("SKIPPED: {e}");
            return;
        }
    };
    eprintln!("controlled: {controlled}\nfixed: {fixed}");
    let (ours, theirs) = (
        number(&controlled, "in_band_pct"),
        number(&fixed, "in_band_pct"),
    );
    assert!(
        ours >= theirs + 25.0,
        "in band {ours:.1} % with the controller against {theirs:.1} % at a fixed scale"
    );
    // The scale follows the load: lowest at the heaviest level, highest at the lightest.
    let (light, heavy) = (scale_at(&controlled, 1.0), scale_at(&controlled, 3.5));
    assert!(
        heavy < light - 0.2,
        "scale {heavy:.2} at load 3.5 against {light:.2} at load 1"
    );
    assert_eq!(scale_at(&fixed, 3.5), 1.0);
}

fn run_plain(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("runs")
}

#[test]
fn bad_arguments_are_refused_with_a_message() {
    for (args, message) in [
        (
            &["--refresh-hz", "0"][..],
            "--refresh-hz must be a positive number",
        ),
        (&["--width", "0"][..], "--width and --height"),
        (&["--frames", "0"][..], "--frames must be at least 1"),
        (&["--controller", "bogus"][..], "controller `bogus`"),
        (
            &["--controller", "fixed:scale=0.1"][..],
            "controller `fixed:scale=0.1`",
        ),
    ] {
        let out = run_plain(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} was accepted");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}
