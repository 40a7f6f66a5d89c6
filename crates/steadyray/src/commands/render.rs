//! `steadyray render`: one still image.

use crate::backend::create_renderer;
use crate::cli::RenderArgs;
use crate::image_out::{image_format, save_image};
use anyhow::{Context, Result, bail};
use serde_json::json;
use steadyray_render::RenderSettings;
use steadyray_scene::Camera;

/// Renders the asked-for frame, writes the image, and prints the frame's statistics.
pub fn run(args: &RenderArgs) -> Result<()> {
    let scene = args.scene.load()?;
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        spp: args.spp,
        max_depth: args.depth,
    };
    settings.validate()?;
    image_format(&args.output)?;
    if let Some(t) = args.time
        && !t.is_finite()
    {
        bail!("--time {t} is not a finite number of seconds");
    }
    let (camera, time_s) = match (args.yaw, args.frame, args.time) {
        (Some(yaw), _, time) => {
            let pitch = scene.camera.forward.normalize().y.clamp(-1.0, 1.0).asin();
            let camera = Camera::yaw_pitch(scene.camera.eye, yaw, pitch, scene.camera.vfov_deg);
            (camera, time.unwrap_or(0.0))
        }
        (None, Some(k), _) => {
            let n = args.frames.unwrap_or_else(|| scene.path.frames());
            if n == 0 || k >= n {
                bail!("--frame {k} is outside a path of {n} frames");
            }
            (scene.camera_at(k, n), scene.path.frame_time(k, n))
        }
        (None, None, Some(t)) => (scene.camera_at_time(t), t),
        (None, None, None) => (scene.camera, 0.0),
    };
    let mut renderer = create_renderer(args.scene.backend)?;
    renderer.load_scene(&scene)?;
    for _ in 0..args.warmup {
        renderer.render(&camera, time_s, &settings)?;
    }
    let stats = renderer.render(&camera, time_s, &settings)?;
    let image = renderer.read_image()?;
    save_image(&image, &args.output).with_context(|| format!("rendering {} failed", scene.name))?;
    if args.stats {
        let info = renderer.info();
        let line = json!({
            "scene": scene.name,
            "backend": info.backend,
            "device": info.device,
            "width": stats.width,
            "height": stats.height,
            "spp": settings.spp,
            "depth": settings.max_depth,
            "time_s": time_s,
            "render_ms": stats.render_ms,
            "accel_ms": stats.accel_ms,
            "wall_ms": stats.wall_ms,
            "timing": format!("{:?}", stats.timing),
            "samples": stats.samples,
            "rays_per_depth": stats.rays.per_depth,
            "shadow_rays": stats.rays.shadow,
            "rays_total": stats.rays.total(),
            "rays_per_s": stats.rays_per_second(),
        });
        println!("{line}");
    }
    Ok(())
}
