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
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/stanford-bunny.obj")
}

/// `steadyray raybench` at 32x18, one repetition, on `backend`, with `adapter` as
/// `STEADYRAY_ADAPTER` when given.
fn raybench(backend: &str, adapter: Option<&str>) -> Output {
    raybench_with(backend, adapter, &[])
}

/// [`raybench`] with `extra` arguments.
fn raybench_with(backend: &str, adapter: Option<&str>, extra: &[&std::ffi::OsStr]) -> Output {
    let mut command = Command::new(BIN);
    command
        .arg("raybench")
        .args(["--backend", backend, "--camera", CAMERA])
        .args(["--width", "32", "--height", "18", "--reps", "1"])
        .arg("--mesh")
        .arg(bunny())
        .args(extra);
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

/// `--dump-rays` writes the triangles and both ray sets as documented in
/// `commands/ray_dump.rs`: as many rays as the report counts, primary rays from the eye on
/// (T_MIN, ∞), and hits whose fractions are the report's and whose t puts the hit point on
/// the triangle hit. A folder that does not exist is a clear error.
#[test]
fn dumped_rays_are_the_rays_traced() {
    let tmp = tempfile::Builder::new()
        .prefix("steadyray-raybench-dump-")
        .tempdir()
        .unwrap();
    let dir = tmp.path();
    let path = dir.join("rays.bin");
    let output = raybench_with("cpu", None, &["--dump-rays".as_ref(), path.as_os_str()]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let r = report(&output);
    let bytes = std::fs::read(&path).unwrap();
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let float = |at: usize| f32::from_bits(word(at));
    assert_eq!(&bytes[..8], b"SRAYDUMP");
    assert_eq!(word(8), 1, "version");
    let triangles = word(12) as usize;
    assert_eq!(triangles as u64, r["triangles"].as_u64().unwrap());
    assert_eq!(word(16), 2, "two ray sets");
    let corner = |tri: usize, k: usize| {
        let at = 24 + 36 * tri + 12 * k;
        [float(at), float(at + 4), float(at + 8)]
    };
    let mut at = 24 + 36 * triangles;
    for name in ["primary", "bounce"] {
        assert_eq!(&bytes[at..at + name.len()], name.as_bytes());
        let count = u64::from_le_bytes(bytes[at + 16..at + 24].try_into().unwrap()) as usize;
        assert_eq!(count as u64, r[format!("{name}_rays")].as_u64().unwrap());
        at += 24;
        let mut hits = 0;
        for ray in 0..count {
            let f = |k: usize| float(at + 40 * ray + 4 * k);
            let (origin, dir) = ([f(0), f(1), f(2)], [f(3), f(4), f(5)]);
            assert_eq!((f(6), f(7)), (1e-4, f32::INFINITY), "{name} ray {ray}");
            if name == "primary" {
                assert_eq!(origin, [0.0869666, 0.110154, 0.1782621]);
            }
            let (t, tri) = (f(8), word(at + 40 * ray + 36));
            if tri == u32::MAX {
                assert!(t.is_nan(), "{name} ray {ray}: a miss has t NaN");
                continue;
            }
            hits += 1;
            let hit: [f32; 3] = std::array::from_fn(|k| origin[k] + t * dir[k]);
            let [a, b, c] = [0, 1, 2].map(|k| corner(tri as usize, k));
            for k in 0..3 {
                let (lo, hi) = (a[k].min(b[k]).min(c[k]), a[k].max(b[k]).max(c[k]));
                assert!(
                    (lo - 1e-5..=hi + 1e-5).contains(&hit[k]),
                    "{name} ray {ray}: hit point off its triangle"
                );
            }
        }
        let fraction = hits as f64 / count as f64;
        assert_eq!(
            fraction,
            r[format!("{name}_hit_fraction")].as_f64().unwrap()
        );
        at += 40 * count;
    }
    assert_eq!(at, bytes.len());

    let nowhere = dir.join("no such folder").join("rays.bin");
    let output = raybench_with("cpu", None, &["--dump-rays".as_ref(), nowhere.as_os_str()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(output.stdout.is_empty());
    assert!(stderr.contains("cannot write the ray dump"), "{stderr}");
}
