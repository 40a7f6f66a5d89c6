//! `steadyray compare`: FLIP at the default 67 pixels a degree and at the viewing condition
//! `--ppd` names (the bench's displayed FLIP views a 640-pixel frame at 12.6); a bad `--ppd`
//! is a clear error.

mod scratch;
use scratch::scratch;
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the steadyray binary runs")
}

fn render(path: &Path, spp: &str) {
    let out = run(&[
        "render",
        "--backend",
        "cpu",
        "--width",
        "64",
        "--height",
        "36",
        "--depth",
        "3",
        "--warmup",
        "0",
        "--yaw",
        "0.4",
        "--spp",
        spp,
        "-o",
        path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn compare(reference: &Path, test: &Path, extra: &[&str]) -> Value {
    let mut args = vec![
        "compare",
        reference.to_str().unwrap(),
        test.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = run(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn flip_is_scored_at_the_viewing_condition_asked() {
    let tmp = scratch("compare");
    let dir = tmp.path();
    let (reference, test) = (dir.join("reference.png"), dir.join("test.png"));
    render(&reference, "16");
    render(&test, "1");
    let default = compare(&reference, &test, &[]);
    let coarse = compare(&reference, &test, &["--ppd", "12.6"]);
    let flip = |v: &Value| v["flip"].as_f64().unwrap();
    assert!(
        (default["ppd"].as_f64().unwrap() - 67.0).abs() < 0.01,
        "{default}"
    );
    assert!(
        (coarse["ppd"].as_f64().unwrap() - 12.6).abs() < 1e-4,
        "{coarse}"
    );
    assert!(flip(&default) > 0.0 && flip(&coarse) > 0.0);
    // Larger pixels show the same error plainer: FLIP's filters see more of it.
    assert!(flip(&coarse) > flip(&default), "{default} {coarse}");
    assert_eq!(default["psnr"], coarse["psnr"]);
    assert_eq!(default["ssim"], coarse["ssim"]);
    let same = compare(&reference, &reference, &["--ppd", "12.6"]);
    assert_eq!(flip(&same), 0.0);
    for bad in ["0", "-3", "nan"] {
        let ppd = format!("--ppd={bad}");
        let out = run(&[
            "compare",
            reference.to_str().unwrap(),
            test.to_str().unwrap(),
            &ppd,
        ]);
        assert!(!out.status.success(), "--ppd {bad} was accepted");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--ppd"), "{err}");
    }
}
