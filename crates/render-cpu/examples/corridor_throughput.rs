//! Measures the CPU renderer's throughput on a corridor-like scene (the test suite's copy of
//! `docs/corridor.md`), at 640×360, S = 4, R = 8, for a few camera yaws.
//!
//! `cargo run --release -p steadyray-render-cpu --example corridor_throughput [threads]`

#[path = "../tests/common/mod.rs"]
mod common;

use std::f32::consts::PI;
use steadyray_render::Renderer;
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::Camera;

fn main() {
    let threads = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(0);
    let scene = common::corridor();
    let mut r = CpuRenderer::with_threads(threads);
    r.load_scene(&scene).expect("scene loads");
    println!("{}", r.info().device);
    let set = common::settings(640, 360, 4.0, 8);
    for (label, yaw) in [("yaw 0", 0.0), ("yaw pi/2", PI / 2.0), ("yaw pi", PI)] {
        let camera = Camera::yaw_pitch(scene.camera.eye, yaw, 0.0, 60.0);
        r.render(&camera, 0.0, &set).expect("renders"); // warm-up
        let runs: Vec<_> = (0..3)
            .map(|_| r.render(&camera, 0.0, &set).expect("renders"))
            .collect();
        let best = runs
            .iter()
            .min_by(|a, b| a.render_ms.total_cmp(&b.render_ms))
            .expect("three runs");
        println!(
            "{label:9} {:8.1} ms  {:6.2} Mrays/s  rays {} (per depth {:?}, shadow {})",
            best.render_ms,
            best.rays_per_second() / 1e6,
            best.rays.total(),
            best.rays.per_depth,
            best.rays.shadow
        );
    }
}
