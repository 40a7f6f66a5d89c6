//! Warped refreshes (`Renderer::present_warped`, `docs/temporal.md`) on the GPU against the
//! CPU reference: the history of the corridor's sweep shown again from the cameras of later
//! display refreshes is the same picture byte for byte on a software adapter (which rounds
//! as the CPU does); shown from its own camera it is the frame; it leaves the history as it
//! was, stays on display until the next frame or `present`, and needs the temporal mode and
//! a frame.

mod common;

use common::{Diff, compare, gpu};
use steadyray_render::temporal::{HISTORY_CAP, SHARPEN, sharpened_image};
use steadyray_render::{
    Picture, Presented, RenderError, RenderSettings, Renderer, TemporalSettings,
};
use steadyray_render_cpu::CpuRenderer;
use steadyray_render_gpu::GpuRenderer;
use steadyray_scene::{Scene, builtin};

/// The history's size.
const HISTORY: TemporalSettings = TemporalSettings {
    width: 160,
    height: 90,
};
/// The display's refresh interval, s.
const REFRESH_S: f64 = 1.0 / 60.0;
/// The scene time of the last frame.
const END_S: f64 = 0.5;
/// Frames of the sweep, one refresh apart, ending at [`END_S`].
const FRAMES: u32 = 12;
/// The sweep's frame rendered at half the history's size.
const REDUCED_FRAME: u32 = 7;

fn settings(width: u32, height: u32) -> RenderSettings {
    RenderSettings {
        width,
        height,
        spp: 2.0,
        max_depth: 8,
    }
}

/// Renders the corridor's sweep into a [`HISTORY`]-sized history on `r`.
fn sweep(r: &mut dyn Renderer, scene: &Scene) {
    r.load_scene(scene).unwrap();
    r.set_temporal(Some(HISTORY)).unwrap();
    for k in 0..FRAMES {
        let t_s = END_S - f64::from(FRAMES - 1 - k) * REFRESH_S;
        let s = if k == REDUCED_FRAME {
            settings(HISTORY.width / 2, HISTORY.height / 2)
        } else {
            settings(HISTORY.width, HISTORY.height)
        };
        r.render(&scene.camera_at_time(t_s), t_s, &s).unwrap();
    }
}

/// The picture a backend handed to the host, or (for one that kept it on the device) the
/// one its display shows.
fn shown(r: &mut dyn Renderer, presented: Presented) -> Picture {
    match presented {
        Presented::Host(picture) => picture,
        Presented::Device => r.read_picture().unwrap(),
    }
}

/// Where two pictures differ: (bytes that differ, the largest difference).
fn picture_diff(a: &Picture, b: &Picture) -> (usize, u8) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let diffs = a.rgba.iter().zip(&b.rgba).map(|(x, y)| x.abs_diff(*y));
    diffs.fold((0, 0), |(n, max), d| (n + usize::from(d > 0), max.max(d)))
}

/// Checks the GPU's picture against the CPU's: byte for byte on a software adapter (which
/// rounds as the CPU does); on a GPU, whose driver may fuse multiply-adds, within the parity
/// bar of the frames themselves ([`Diff::assert_parity`]).
fn assert_pictures_match(gpu: &Picture, cpu: &Picture, exact: bool, what: &str) {
    let (off, max) = picture_diff(gpu, cpu);
    eprintln!(
        "{what}: {off} of {} bytes differ, by at most {max}",
        gpu.rgba.len()
    );
    if exact {
        assert!(off == 0, "{what}: GPU and CPU pictures differ");
        return;
    }
    let pixels = gpu.rgba.len() / 4;
    let channels = |p: &[u8], q: &[u8]| (0..3).map(|c| p[c].abs_diff(q[c])).collect::<Vec<_>>();
    let per_pixel: Vec<Vec<u8>> = gpu
        .rgba
        .chunks_exact(4)
        .zip(cpu.rgba.chunks_exact(4))
        .map(|(p, q)| channels(p, q))
        .collect();
    let sum: u64 = per_pixel.iter().flatten().map(|&d| u64::from(d)).sum();
    Diff {
        max,
        mean: sum as f64 / (pixels * 3) as f64,
        pixels_over_2: per_pixel
            .iter()
            .filter(|d| d.iter().any(|&d| d > 2))
            .count(),
        pixels,
        max_linear: 0.0,
    }
    .assert_parity(what, false);
}

/// The history's picture as the host shows it: sharpened by the shared rule, tone-mapped.
fn host_picture(r: &mut GpuRenderer) -> Picture {
    let image = r.read_image().unwrap();
    // After a moving full-scale frame of `settings` (S = 2) the display sharpens the history
    // (`sharpen_strength`).
    let k = SHARPEN * (1.0 - 2.0 / HISTORY_CAP);
    Picture {
        width: image.width,
        height: image.height,
        rgba: sharpened_image(&image, k).to_srgb8_rgba(),
    }
}

#[test]
fn warped_refreshes_match_the_cpu() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    let mut cpu = CpuRenderer::new();
    sweep(&mut *gpu, &scene);
    sweep(&mut cpu, &scene);
    let exact = gpu.adapter().is_software;
    let history = gpu.read_image().unwrap();
    let diff = compare(&history, &cpu.read_image().unwrap());
    if exact {
        assert_eq!(diff.max_linear, 0.0, "the histories differ: {diff:?}");
    } else {
        diff.assert_parity("the history", false);
    }
    let frame = gpu.read_picture().unwrap();
    let presented = cpu.present().unwrap();
    let cpu_frame = shown(&mut cpu, presented);
    assert_pictures_match(&frame, &cpu_frame, exact, "the frame");
    for refreshes in [1, 2, 4] {
        let camera = scene.camera_at_time(END_S + f64::from(refreshes) * REFRESH_S);
        let presented = gpu.present_warped(&camera).unwrap();
        assert_eq!(presented, Presented::Device, "the warp stays on the device");
        let on_gpu = gpu.read_picture().unwrap();
        let presented = cpu.present_warped(&camera).unwrap();
        let on_cpu = shown(&mut cpu, presented);
        let what = format!("{refreshes} refreshes on");
        assert_pictures_match(&on_gpu, &on_cpu, exact, &what);
        let (moved, _) = picture_diff(&on_gpu, &frame);
        assert!(moved > 0, "{what}: the warp did not move the picture");
    }
    assert_eq!(
        gpu.read_image().unwrap(),
        history,
        "a warp changed the history"
    );
    // The next frame still agrees: the warps left both histories as they were.
    let t_s = END_S + REFRESH_S;
    let next = settings(HISTORY.width, HISTORY.height);
    gpu.render(&scene.camera_at_time(t_s), t_s, &next).unwrap();
    cpu.render(&scene.camera_at_time(t_s), t_s, &next).unwrap();
    let diff = compare(&gpu.read_image().unwrap(), &cpu.read_image().unwrap());
    if exact {
        assert_eq!(diff.max_linear, 0.0, "the next frame differs: {diff:?}");
    } else {
        diff.assert_parity("the frame after the warps", false);
    }
}

#[test]
fn a_warp_to_the_frames_own_view_is_the_frame() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    sweep(&mut *gpu, &scene);
    assert_eq!(gpu.present().unwrap(), Presented::Device);
    let frame = gpu.read_picture().unwrap();
    gpu.present_warped(&scene.camera_at_time(END_S)).unwrap();
    let warped = gpu.read_picture().unwrap();
    let exact = gpu.adapter().is_software;
    assert_pictures_match(&warped, &frame, exact, "the frame from its own camera");
}

#[test]
fn the_display_shows_the_warp_until_the_frame_is_presented_or_replaced() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    sweep(&mut *gpu, &scene);
    let frame = gpu.read_picture().unwrap();
    assert!(
        frame == host_picture(&mut gpu),
        "the frame's picture is not its history as the host shows it"
    );
    let later = scene.camera_at_time(END_S + 4.0 * REFRESH_S);
    gpu.present_warped(&later).unwrap();
    let warped = gpu.read_picture().unwrap();
    assert_ne!(
        warped.rgba, frame.rgba,
        "the warp did not reach the display"
    );
    assert_eq!(gpu.read_picture().unwrap(), warped, "read again, the warp");
    assert_eq!(
        gpu.read_srgb8().unwrap(),
        warped.rgba,
        "the display's bytes"
    );
    // A warp reads the history, never the display: warping again gives the same picture.
    gpu.present_warped(&later).unwrap();
    assert_eq!(gpu.read_picture().unwrap(), warped, "warped again");
    // Presented, the frame is on display again.
    assert_eq!(gpu.present().unwrap(), Presented::Device);
    assert_eq!(
        gpu.read_picture().unwrap(),
        frame,
        "presented again, the frame"
    );
    // The next frame replaces a warp on display, read straight away.
    gpu.present_warped(&later).unwrap();
    let t_s = END_S + REFRESH_S;
    gpu.render(
        &scene.camera_at_time(t_s),
        t_s,
        &settings(HISTORY.width, HISTORY.height),
    )
    .unwrap();
    let next = gpu.read_picture().unwrap();
    assert!(
        next == host_picture(&mut gpu),
        "after a warp, the next frame's picture is not its history as the host shows it"
    );
    assert_ne!(next.rgba, warped.rgba, "the warp stayed on display");
}

#[test]
fn a_warp_needs_the_temporal_mode_and_a_frame() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    let camera = scene.camera;
    gpu.load_scene(&scene).unwrap();
    gpu.set_temporal(None).unwrap();
    gpu.render(&camera, 0.0, &settings(32, 18)).unwrap();
    let err = gpu.present_warped(&camera).unwrap_err();
    match &err {
        RenderError::Unavailable(why) => assert_eq!(
            why,
            "a warped refresh needs the temporal mode (its history and geometry)"
        ),
        other => panic!("expected Unavailable, got {other}"),
    }
    // The refused warp left the plain frame presentable.
    assert_eq!(gpu.present().unwrap(), Presented::Device);
    gpu.set_temporal(Some(TemporalSettings {
        width: 32,
        height: 18,
    }))
    .unwrap();
    assert!(matches!(
        gpu.present_warped(&camera),
        Err(RenderError::NoFrame)
    ));
    assert!(matches!(gpu.read_picture(), Err(RenderError::NoFrame)));
}
