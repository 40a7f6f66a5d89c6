//! What a warped refresh costs on the CPU beside the frame's own hand-over: the corridor
//! sweep in the temporal mode (S = 1, R = 16, a history of 640×360 or the width given at
//! 16:9, frames at the scale given), each frame handed over (`present`) and then warped to
//! the camera a refresh later (`present_warped`), medians over the frames.
//!
//! `cargo run --release -p steadyray-render-cpu --example warp_cost [threads] [scale] [width]`

use std::time::Instant;
use steadyray_render::{RenderSettings, Renderer, TemporalSettings};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::builtin;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let mut args = std::env::args().skip(1);
    let threads = args.next().and_then(|a| a.parse().ok()).unwrap_or(0);
    let scale: f32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1.0);
    let scene = builtin("corridor").expect("the corridor is built in");
    let width: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(640);
    let height = width * 9 / 16;
    let settings = RenderSettings::scaled((width, height), scale, 1.0, 16);
    let mut r = CpuRenderer::with_threads(threads);
    r.load_scene(&scene).expect("loads");
    r.set_temporal(Some(TemporalSettings { width, height }))
        .expect("a valid history");
    let (mut frame_ms, mut present_ms, mut warp_ms) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..60 {
        let t_s = f64::from(k) / 30.0;
        let stats = r
            .render(&scene.camera_at_time(t_s), t_s, &settings)
            .expect("renders");
        let start = Instant::now();
        r.present().expect("presents");
        let presented = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        r.present_warped(&scene.camera_at_time(t_s + 1.0 / 60.0))
            .expect("warps");
        let warped = start.elapsed().as_secs_f64() * 1e3;
        if k >= 5 {
            frame_ms.push(stats.render_ms);
            present_ms.push(presented);
            warp_ms.push(warped);
        }
    }
    println!(
        "{width}x{height}, {} threads, scale {scale}: frame {:.2} ms, hand-over {:.2} ms, warped refresh {:.2} ms \
         (medians)",
        r.threads(),
        median(frame_ms),
        median(present_ms),
        median(warp_ms)
    );
}
