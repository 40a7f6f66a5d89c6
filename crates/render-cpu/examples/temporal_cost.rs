//! The temporal pass's cost on the CPU: the corridor sweep at 640×360, S = 1, R = 16, each
//! frame rendered plain and into a history (alternating, same views), median of the
//! difference.
//!
//! `cargo run --release -p steadyray-render-cpu --example temporal_cost [threads] [scale]`

use steadyray_render::{RenderSettings, Renderer, TemporalSettings};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::builtin;

fn main() {
    let mut args = std::env::args().skip(1);
    let threads = args.next().and_then(|a| a.parse().ok()).unwrap_or(0);
    let scale: f32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1.0);
    let scene = builtin("corridor").expect("the corridor is built in");
    let (width, height) = (640, 360);
    let settings = RenderSettings::scaled((width, height), scale, 1.0, 16);
    let mut plain = CpuRenderer::with_threads(threads);
    let mut temporal = CpuRenderer::with_threads(threads);
    plain.load_scene(&scene).expect("loads");
    temporal.load_scene(&scene).expect("loads");
    temporal
        .set_temporal(Some(TemporalSettings { width, height }))
        .expect("a valid history");
    let frames = 120;
    let mut extra = Vec::new();
    let mut plain_ms = Vec::new();
    for k in 0..frames {
        let camera = scene.camera_at(k, 720);
        let p = plain.render(&camera, 0.0, &settings).expect("renders");
        let t = temporal.render(&camera, 0.0, &settings).expect("renders");
        if k >= 10 {
            extra.push(t.render_ms - p.render_ms);
            plain_ms.push(p.render_ms);
        }
    }
    extra.sort_by(f64::total_cmp);
    plain_ms.sort_by(f64::total_cmp);
    let n = extra.len();
    println!(
        "{} threads, scale {scale}: plain frames {:.2} ms, the temporal pass adds {:.2} ms \
         (medians; quartiles {:.2} to {:.2})",
        plain.threads(),
        plain_ms[n / 2],
        extra[n / 2],
        extra[n / 4],
        extra[3 * n / 4]
    );
}
