//! The GPU renderer's behaviour as a [`Renderer`]: reuse across sizes, qualities and scenes,
//! the tone-mapped readback, timing, errors, and adapter selection.

mod common;

use common::{assert_counts, compare, gpu};
use steadyray_render::{RenderError, RenderSettings, Renderer, TimingSource};
use steadyray_render_cpu::CpuRenderer;
use steadyray_render_gpu::{GpuOptions, GpuRenderer, list_adapters};
use steadyray_scene::builtin;

fn settings(width: u32, height: u32, spp: f32, max_depth: u32) -> RenderSettings {
    RenderSettings {
        width,
        height,
        spp,
        max_depth,
    }
}

#[test]
fn resizes_quality_changes_and_new_scenes_reuse_the_renderer() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let mut cpu = CpuRenderer::new();
    // Sizes that are not multiples of the workgroup, growing and shrinking.
    let frames = [
        ("corridor", settings(96, 64, 1.0, 2)),
        ("corridor", settings(37, 21, 2.0, 5)),
        ("corridor", settings(130, 70, 1.5, 1)),
        ("spheres", settings(50, 90, 1.0, 3)),
        ("corridor", settings(8, 8, 3.0, 0)),
    ];
    for (name, s) in frames {
        let scene = builtin(name).unwrap();
        gpu.load_scene(&scene).unwrap();
        cpu.load_scene(&scene).unwrap();
        let camera = scene.camera_at(1, 16);
        let g = gpu.render(&camera, 0.0, &s).unwrap();
        let c = cpu.render(&camera, 0.0, &s).unwrap();
        let what = format!("{name} {s:?}");
        let exact = gpu.adapter().is_software;
        assert_counts(&g.rays, &c.rays, exact, scene.lights.len(), &what);
        assert_eq!((g.width, g.height), (s.width, s.height));
        let image = gpu.read_image().unwrap();
        assert_eq!((image.width, image.height), (s.width, s.height));
        compare(&image, &cpu.read_image().unwrap()).assert_parity(&what, exact);
    }
}

#[test]
fn gpu_tone_map_matches_the_host_tone_map() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    gpu.load_scene(&scene).unwrap();
    gpu.render(&scene.camera, 0.0, &settings(77, 45, 2.0, 4))
        .unwrap();
    let on_gpu = gpu.read_srgb8().unwrap();
    let on_host = gpu.read_image().unwrap().to_srgb8_rgba();
    assert_eq!(on_gpu.len(), on_host.len());
    let off: Vec<(u8, u8)> = on_gpu
        .iter()
        .zip(&on_host)
        .filter(|(a, b)| a != b)
        .map(|(&a, &b)| (a, b))
        .collect();
    // The GPU looks levels up in the host's table: the same bytes, on any GPU.
    assert!(
        off.is_empty(),
        "{} of {} bytes differ: {off:?}",
        off.len(),
        on_gpu.len()
    );
}

#[test]
fn frame_time_comes_from_timestamps_when_the_device_has_them() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    gpu.load_scene(&scene).unwrap();
    let stats = gpu
        .render(&scene.camera, 0.0, &settings(64, 32, 1.0, 2))
        .unwrap();
    let expected = if gpu.has_timestamps() {
        TimingSource::GpuTimestamps
    } else {
        TimingSource::WallClock
    };
    assert_eq!(stats.timing, expected);
    assert!(
        stats.render_ms > 0.0 && stats.render_ms <= stats.wall_ms,
        "{stats:?}"
    );
    assert_eq!(stats.samples, 64 * 32);
    assert!(stats.rays_per_second() > 0.0);
    assert_eq!(gpu.info().backend, "gpu");
}

#[test]
fn bad_settings_and_scenes_are_errors() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let mut scene = builtin("corridor").unwrap();
    gpu.load_scene(&scene).unwrap();
    let err = gpu
        .render(&scene.camera, 0.0, &settings(16, 16, 0.5, 1))
        .unwrap_err();
    assert!(matches!(err, RenderError::Settings(_)), "{err}");
    let err = gpu
        .render(&scene.camera, 0.0, &settings(16, 16, 1.0, 65))
        .unwrap_err();
    assert!(matches!(err, RenderError::Settings(_)), "{err}");
    let err = gpu
        .render(&scene.camera, f64::NAN, &settings(16, 16, 1.0, 1))
        .unwrap_err();
    assert!(matches!(err, RenderError::BadTime(_)), "{err}");

    scene.objects[0].material = 99;
    let err = gpu.load_scene(&scene).unwrap_err();
    assert!(matches!(err, RenderError::Scene(_)), "{err}");
}

#[test]
fn adapters_are_listed_real_gpus_first() {
    let adapters = list_adapters();
    for a in &adapters {
        eprintln!("adapter: {a:?}");
    }
    if gpu().is_none() {
        return;
    }
    assert!(!adapters.is_empty());
    let first_software = adapters.iter().position(|a| a.is_software);
    if let Some(i) = first_software {
        assert!(adapters[i..].iter().all(|a| a.is_software), "{adapters:?}");
    }
}

#[test]
fn an_unknown_adapter_name_is_a_clear_error() {
    let options = GpuOptions {
        adapter_name: Some("no-such-gpu-4c1d".to_string()),
        allow_software: true,
    };
    let err = GpuRenderer::new(&options)
        .err()
        .expect("no adapter has that name");
    let message = err.to_string();
    assert!(message.contains("no GPU adapter found ("), "{message}");
    assert!(message.contains("no-such-gpu-4c1d"), "{message}");
}

#[test]
fn software_adapters_need_consent() {
    if list_adapters().iter().any(|a| !a.is_software) {
        eprintln!("SKIPPED: a hardware adapter exists, so the default options find it");
        return;
    }
    let err = GpuRenderer::new(&GpuOptions::default())
        .err()
        .expect("only software adapters");
    assert!(
        err.to_string().contains("software adapters not allowed"),
        "{err}"
    );
}
