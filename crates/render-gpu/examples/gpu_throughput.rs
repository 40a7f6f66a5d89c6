//! Rays per second of the GPU renderer on the corridor sweep, from GPU timestamps.
//!
//!     cargo run --release -p steadyray-render-gpu --example gpu_throughput -- \
//!         [WIDTH HEIGHT S R FRAMES]
//!
//! Defaults: 320 180 1 4 16. `STEADYRAY_ADAPTER` picks the adapter; software adapters are
//! allowed. The first frame (pipeline warm-up) is rendered but not counted.

use steadyray_render::{RenderSettings, Renderer};
use steadyray_render_gpu::{GpuOptions, GpuRenderer};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    env_logger::init();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.to_string());
    let settings = RenderSettings {
        width: arg(0, "320").parse()?,
        height: arg(1, "180").parse()?,
        spp: arg(2, "1").parse()?,
        max_depth: arg(3, "4").parse()?,
    };
    let frames: u32 = arg(4, "16").parse()?;
    let mut gpu = GpuRenderer::new(&GpuOptions {
        adapter_name: std::env::var("STEADYRAY_ADAPTER").ok(),
        allow_software: true,
    })?;
    println!("{} ({:?})", gpu.info().device, settings);
    let scene = steadyray_scene::builtin("corridor")?;
    gpu.load_scene(&scene)?;
    gpu.render(&scene.camera, 0.0, &settings)?;
    let (mut rays, mut ms, mut wall) = (0u64, 0.0, 0.0);
    for k in 0..frames {
        let t = scene.path.frame_time(k, frames);
        let stats = gpu.render(&scene.camera_at(k, frames), t, &settings)?;
        println!(
            "frame {k:3}: {:9.3} ms ({:?}), wall {:9.3} ms, {:10} rays, {:8.3} Mrays/s",
            stats.render_ms,
            stats.timing,
            stats.wall_ms,
            stats.rays.total(),
            stats.rays_per_second() / 1e6
        );
        rays += stats.rays.total();
        ms += stats.render_ms;
        wall += stats.wall_ms;
    }
    println!(
        "total: {rays} rays in {ms:.1} ms render ({wall:.1} ms wall): {:.3} Mrays/s",
        rays as f64 / (ms * 1e-3) / 1e6
    );
    Ok(())
}
