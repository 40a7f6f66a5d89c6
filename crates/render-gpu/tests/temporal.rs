//! The GPU's temporal mode against the CPU reference: the same sequence of frames gives the
//! same accumulated history (bit for bit on a software adapter, which rounds as the CPU
//! does), through camera motion, reduced scales, fractional S, cuts and resizes; and the
//! history is shown without readback as the CPU shows it (sharpened after a moving frame).

mod common;

use common::{compare, gpu};
use steadyray_render::{RenderSettings, Renderer, TemporalSettings};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{Camera, Vec3, builtin};

/// One frame of a sequence: the camera, the scene time and the frame's settings.
type Step = (Camera, f64, RenderSettings);

fn settings(width: u32, height: u32, spp: f32, max_depth: u32) -> RenderSettings {
    RenderSettings {
        width,
        height,
        spp,
        max_depth,
    }
}

/// Renders `steps` on both backends with a `size` history (resetting before the steps in
/// `cuts`) and checks every accumulated frame for parity.
fn check_sequence(name: &str, scene_name: &str, size: (u32, u32), steps: &[Step], cuts: &[usize]) {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin(scene_name).unwrap();
    let mut cpu = CpuRenderer::new();
    let history = TemporalSettings {
        width: size.0,
        height: size.1,
    };
    for r in [&mut *gpu as &mut dyn Renderer, &mut cpu] {
        r.load_scene(&scene).unwrap();
        r.set_temporal(Some(history)).unwrap();
    }
    let exact = gpu.adapter().is_software;
    for (k, &(camera, time_s, ref set)) in steps.iter().enumerate() {
        if cuts.contains(&k) {
            gpu.reset_history();
            cpu.reset_history();
        }
        let g = gpu.render(&camera, time_s, set).unwrap();
        let c = cpu.render(&camera, time_s, set).unwrap();
        assert_eq!(
            g.rays.per_depth[0], c.rays.per_depth[0],
            "{name} frame {k}: eye rays"
        );
        if exact {
            assert_eq!(g.rays, c.rays, "{name} frame {k}: ray counts");
        }
        let (gi, ci) = (gpu.read_image().unwrap(), cpu.read_image().unwrap());
        assert_eq!(
            (gi.width, gi.height),
            size,
            "{name} frame {k}: history size"
        );
        let diff = compare(&gi, &ci);
        let what = format!(
            "{name} frame {k} ({}x{} S={} R={})",
            set.width, set.height, set.spp, set.max_depth
        );
        if exact {
            assert_eq!(diff.max_linear, 0.0, "{what}: not bit-identical: {diff:?}");
        } else {
            diff.assert_parity(&what, false);
        }
    }
    eprintln!("{name}: {} frames, parity held", steps.len());
}

#[test]
fn a_sweep_with_changing_scale_and_quality() {
    let scene = builtin("corridor").unwrap();
    let (w, h) = (96, 54);
    let qualities = [
        (1.0, 1.0, 6),
        (0.5, 1.0, 6),
        (0.75, 2.5, 4),
        (1.0, 1.5, 8),
        (0.25, 1.0, 3),
        (0.5, 4.0, 5),
        // More samples than one dispatch of a software adapter traces.
        (0.75, 18.5, 5),
    ];
    let steps: Vec<Step> = (0..15)
        .map(|k| {
            let (scale, spp, depth) = qualities[k % qualities.len()];
            (
                scene.camera_at(k as u32, 90),
                0.0,
                RenderSettings::scaled((w, h), scale, spp, depth),
            )
        })
        .collect();
    check_sequence("corridor sweep", "corridor", (w, h), &steps, &[9]);
}

#[test]
fn a_still_camera_then_a_moving_eye() {
    let scene = builtin("corridor").unwrap();
    let set = settings(64, 36, 1.0, 6);
    // A still view takes new sample positions every frame (odd, even and fractional S).
    let mut steps: Vec<Step> = [1.0, 1.0, 3.0, 3.0, 4.0, 2.5, 2.5]
        .into_iter()
        .map(|spp| (scene.camera, 0.0, settings(64, 36, spp, 6)))
        .collect();
    // The eye walks toward the glass sphere: parallax, disocclusions, the specular cap.
    steps.extend((0..6).map(|k| {
        let eye = Vec3::new(0.1 * k as f32, 1.4, -0.3 * k as f32);
        (
            Camera::look_at(eye, Vec3::new(0.6, 0.45, -4.0), Vec3::Y, 50.0),
            0.0,
            set,
        )
    }));
    check_sequence("corridor walk", "corridor", (64, 36), &steps, &[]);
}

#[test]
fn meshes_and_other_scenes() {
    for name in ["cornell", "spheres"] {
        let scene = builtin(name).unwrap();
        let steps: Vec<Step> = (0..6)
            .map(|k| {
                (
                    scene.camera_at(k, 64),
                    0.0,
                    settings(48, 32, 1.0 + 0.5 * (k % 2) as f32, 4),
                )
            })
            .collect();
        check_sequence(name, name, (64, 40), &steps, &[]);
    }
}

#[test]
fn a_moving_world() {
    // The flyby: objects flying between mirrors, a swarm appearing at 4 s, a glass ball
    // passing the camera, the camera on a keyed path; frames around the swarm's arrival,
    // with a still camera for a while (the world still moves).
    let scene = builtin("flyby").unwrap();
    let set = settings(64, 36, 1.0, 6);
    let mut steps: Vec<Step> = (0..8)
        .map(|k| {
            let t = 3.9 + f64::from(k) / 30.0;
            (scene.camera_at_time(t), t, set)
        })
        .collect();
    let still = scene.camera_at_time(4.2);
    steps.extend((0..4).map(|k| (still, 4.2 + f64::from(k) / 30.0, set)));
    check_sequence("flyby", "flyby", (64, 36), &steps, &[]);
}

#[test]
fn the_shown_history_is_the_cpus_picture_of_it() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    let mut cpu = CpuRenderer::new();
    for r in [&mut *gpu as &mut dyn Renderer, &mut cpu] {
        r.load_scene(&scene).unwrap();
        r.set_temporal(Some(TemporalSettings {
            width: 80,
            height: 45,
        }))
        .unwrap();
    }
    let set = settings(40, 23, 1.0, 4);
    // Moving frames resample the history, which is sharpened for display; a still frame
    // keeps it as it is, and it is shown as it is.
    for (k, sharpened) in [(0, false), (1, true), (2, true), (2, false)] {
        for r in [&mut *gpu as &mut dyn Renderer, &mut cpu] {
            r.render(&scene.camera_at(k, 90), 0.0, &set).unwrap();
        }
        let shown = gpu.read_srgb8().unwrap();
        let image = gpu.read_image().unwrap();
        assert_eq!((image.width, image.height), (80, 45));
        assert!(
            shown == cpu.read_picture().unwrap().rgba,
            "frame {k}: the GPU's shown history differs from the CPU's picture"
        );
        let plain = image.to_srgb8_rgba();
        assert_eq!(shown.len(), plain.len());
        assert_eq!(
            shown != plain,
            sharpened,
            "frame {k}: sharpened for display should be {sharpened}"
        );
    }
    gpu.set_temporal(None).unwrap();
}
