//! `steadyray render`: one still image, or with `--temporal` the history of a sequence (with
//! `--shown`, the picture the display shows of it).

use crate::cli::RenderArgs;
use crate::image_out::{ImageFormat, image_format, save_image, save_picture};
use anyhow::{Context, Result, bail};
use serde_json::json;
use std::path::Path;
use steadyray_experiment::backend::create_renderer;
use steadyray_render::sample_stream::check_reference_spp;
use steadyray_render::{RenderSettings, Renderer, SampleStream, TemporalSettings};
use steadyray_scene::{Camera, Scene};

/// Where the asked-for view comes from: a fixed camera, or the scene's path at a time.
enum View {
    Fixed(Camera),
    Path,
}

/// The frames of a `--temporal` sequence (one frame without it): `frames` frames `1/rate`
/// seconds apart, the last at `end_s`.
struct Sequence {
    frames: u32,
    rate: f64,
    end_s: f64,
}

impl Sequence {
    /// The scene time of frame `i`.
    fn time(&self, i: u32) -> f64 {
        self.end_s - f64::from(self.frames - 1 - i) / self.rate
    }
}

/// Renders the asked-for frame (or sequence), writes the image, and prints the last frame's
/// statistics.
pub fn run(args: &RenderArgs) -> Result<()> {
    let scene = args.scene.load()?;
    let full = RenderSettings {
        width: args.width,
        height: args.height,
        spp: args.spp,
        max_depth: args.depth,
    };
    full.validate()?;
    if args.reference {
        check_reference_spp(args.spp)?;
    }
    if image_format(&args.output)? != ImageFormat::Png && args.shown {
        bail!(
            "--shown writes the display's 8-bit picture: {} must be a .png",
            args.output.display()
        );
    }
    if let Some(t) = args.time
        && !t.is_finite()
    {
        bail!("--time {t} is not a finite number of seconds");
    }
    let (view, time_s) = match (args.yaw, args.frame, args.time) {
        (Some(yaw), _, time) => {
            let pitch = scene.camera.forward.normalize().y.clamp(-1.0, 1.0).asin();
            let camera = Camera::yaw_pitch(scene.camera.eye, yaw, pitch, scene.camera.vfov_deg);
            (View::Fixed(camera), time.unwrap_or(0.0))
        }
        (None, Some(k), _) => {
            let n = args.frames.unwrap_or_else(|| scene.path.frames());
            if n == 0 || k >= n {
                bail!("--frame {k} is outside a path of {n} frames");
            }
            (View::Path, scene.path.frame_time(k, n))
        }
        (None, None, Some(t)) => (View::Path, t),
        (None, None, None) => (View::Fixed(scene.camera), 0.0),
    };
    let camera_at = |t: f64| match &view {
        View::Fixed(camera) => *camera,
        View::Path => scene.camera_at_time(t),
    };
    let sequence = match args.temporal {
        None => Sequence {
            frames: 1,
            rate: 1.0,
            end_s: time_s,
        },
        Some(0) => bail!("--temporal needs at least 1 frame"),
        Some(frames) => {
            if !(args.rate.is_finite() && args.rate > 0.0) {
                bail!(
                    "--rate {} is not a positive number of frames per second",
                    args.rate
                );
            }
            if !(args.scale > 0.0 && args.scale <= 1.0) {
                bail!("--scale {} is outside (0, 1]", args.scale);
            }
            Sequence {
                frames,
                rate: args.rate,
                end_s: time_s,
            }
        }
    };
    let settings = RenderSettings::scaled(
        (full.width, full.height),
        args.scale,
        full.spp,
        full.max_depth,
    );
    let mut renderer = create_renderer(args.scene.backend.into())?;
    renderer.load_scene(&scene)?;
    if args.reference {
        renderer.set_sample_stream(SampleStream::Reference);
    }
    if args.temporal.is_some() {
        renderer.set_temporal(Some(TemporalSettings {
            width: full.width,
            height: full.height,
        }))?;
    }
    let first = sequence.time(0);
    for _ in 0..args.warmup {
        renderer.render(&camera_at(first), first, &settings)?;
    }
    renderer.reset_history();
    if let Some(dir) = &args.sequence {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let mut stats = None;
    for i in 0..sequence.frames {
        let t = sequence.time(i);
        stats = Some(renderer.render(&camera_at(t), t, &settings)?);
        if let Some(dir) = &args.sequence {
            write_last(
                renderer.as_mut(),
                args.shown,
                &dir.join(format!("frame_{i:04}.png")),
            )?;
        }
    }
    let stats = stats.context("no frame rendered")?;
    write_last(renderer.as_mut(), args.shown, &args.output)
        .with_context(|| format!("rendering {} failed", scene.name))?;
    if args.stats {
        print_stats(&scene, renderer.info(), &settings, &stats, time_s, args);
    }
    Ok(())
}

/// Writes the last frame's image to `path`: the display's picture with `shown`, else the
/// image (the history, in the temporal mode) as it is.
fn write_last(renderer: &mut dyn Renderer, shown: bool, path: &Path) -> Result<()> {
    if shown {
        save_picture(&renderer.read_picture()?, path)
    } else {
        save_image(&renderer.read_image()?, path)
    }
}

/// Prints the last frame's statistics as one JSON line.
fn print_stats(
    scene: &Scene,
    info: steadyray_render::BackendInfo,
    settings: &RenderSettings,
    stats: &steadyray_render::FrameStats,
    time_s: f64,
    args: &RenderArgs,
) {
    let line = json!({
        "scene": scene.name,
        "backend": info.backend,
        "device": info.device,
        "width": stats.width,
        "height": stats.height,
        "spp": settings.spp,
        "depth": settings.max_depth,
        "time_s": time_s,
        "temporal_frames": args.temporal,
        "shown": args.shown,
        "render_ms": stats.render_ms,
        "accel_ms": stats.accel_ms,
        "wall_ms": stats.wall_ms,
        "timing": format!("{:?}", stats.timing),
        "samples": stats.samples,
        "rays_per_depth": stats.rays.per_depth,
        "shadow_rays": stats.rays.shadow,
        "rays_stopped": stats.rays.stopped,
        "rays_total": stats.rays.total(),
        "rays_per_s": stats.rays_per_second(),
    });
    println!("{line}");
}
