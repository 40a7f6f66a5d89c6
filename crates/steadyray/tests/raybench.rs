//! `steadyray raybench` on both backends: the GPU run prints one JSON line with the same
//! fields as the CPU run (device and timing in place of threads and the traversal's SIMD
//! form) and the same hit fractions
//! (the same rays, traced to the same hits). Without a GPU adapter the GPU test skips
//! loudly, unless `STEADYRAY_REQUIRE_GPU=1`, which makes it fail; a GPU asked for but not
//! found is a clear error, never a panic.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

/// The raybench issue's view of the bunny.
const CAMERA: &str = r#"{"eye":[0.0869666,0.110154,0.1782621],"target":[-0.0168405,0.110154,-0.001537],"up":[0,1,0],"vfov":45}"#;

fn bunny() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes/stanford-bunny.obj")
}

/// `steadyray raybench` at 32x18, one repetition, on `backend`, with `adapter` as
/// `STEADYRAY_ADAPTER` when given.
fn raybench(backend: &str, adapter: Option<&str>) -> Output {
    let mut command = Command::new(BIN);
    command
        .arg("raybench")
        .args(["--backend", backend, "--camera", CAMERA])
        .args(["--width", "32", "--height", "18", "--reps", "1"])
        .arg("--mesh")
        .arg(bunny());
    if let Some(name) = adapter {
        command.env("STEADYRAY_ADAPTER", name);
    }
    command.output().expect("cannot run steadyray")
}

/// The single JSON line of a successful run.
fn report(output: &Output) -> Value {
    let stdout = String::from_utf8_lossy(&output.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 1, "one line on stdout: {stdout}");
    serde_json::from_str(lines[0]).unwrap_or_else(|e| panic!("{e}: {}", lines[0]))
}

#[test]
fn gpu_hit_fractions_equal_the_cpu_run() {
    let gpu = raybench("gpu", std::env::var("STEADYRAY_ADAPTER").ok().as_deref());
    let stderr = String::from_utf8_lossy(&gpu.stderr);
    if !gpu.status.success() && stderr.contains("no GPU adapter found") {
        if std::env::var("STEADYRAY_REQUIRE_GPU").as_deref() == Ok("1") {
            panic!("STEADYRAY_REQUIRE_GPU=1 but raybench found no adapter: {stderr}");
        }
        eprintln!("SKIPPED: no GPU adapter ({stderr})");
        return;
    }
    assert!(gpu.status.success(), "gpu raybench failed: {stderr}");
    let cpu = raybench("cpu", None);
    assert!(
        cpu.status.success(),
        "cpu raybench failed: {}",
        String::from_utf8_lossy(&cpu.stderr)
    );
    let (g, c) = (report(&gpu), report(&cpu));
    eprintln!("gpu: {g}\ncpu: {c}");

    assert_eq!(g["backend"], "gpu");
    assert_eq!(c["backend"], "cpu");
    assert!(g["device"].as_str().is_some_and(|d| !d.is_empty()), "{g}");
    assert!(g.get("threads").is_none(), "{g}");
    assert!(g.get("simd").is_none(), "{g}");
    assert!(
        matches!(g["timing"].as_str(), Some("timestamps" | "wall")),
        "{g}"
    );
    assert_eq!(c["timing"], "wall");
    for key in [
        "triangles",
        "width",
        "height",
        "reps",
        "primary_rays",
        "bounce_rays",
        "primary_hit_fraction",
        "bounce_hit_fraction",
        "camera",
    ] {
        assert_eq!(g[key], c[key], "{key}");
    }
    assert_eq!(g["primary_rays"], 32 * 18);
    for key in ["primary_rays_per_s", "bounce_rays_per_s"] {
        assert!(g[key].as_f64().is_some_and(|r| r > 0.0), "{key}: {g}");
    }
    let hits = g["primary_hit_fraction"].as_f64().unwrap();
    assert!((0.15..0.6).contains(&hits), "primary hit fraction {hits}");
}

/// A CPU run reports its threads and which compiled form of the traversal ran, and no
/// GPU device.
#[test]
fn the_cpu_run_names_its_threads_and_traversal() {
    let cpu = raybench("cpu", None);
    assert!(
        cpu.status.success(),
        "cpu raybench failed: {}",
        String::from_utf8_lossy(&cpu.stderr)
    );
    let c = report(&cpu);
    assert_eq!(c["backend"], "cpu");
    assert!(c["threads"].as_u64().is_some_and(|t| t >= 1), "{c}");
    assert!(
        matches!(c["simd"].as_str(), Some("avx512" | "avx2" | "portable")),
        "{c}"
    );
    assert!(c.get("device").is_none(), "{c}");
    assert_eq!(c["primary_rays"], 32 * 18);
    let hits = c["primary_hit_fraction"].as_f64().unwrap();
    assert!((0.15..0.6).contains(&hits), "primary hit fraction {hits}");
}

#[test]
fn a_missing_adapter_is_a_clear_error() {
    let output = raybench("gpu", Some("no such adapter, surely"));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(output.stdout.is_empty());
    assert!(
        stderr.contains("the gpu backend is not available")
            && stderr.contains("no GPU adapter found"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}
