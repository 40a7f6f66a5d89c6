//! Warped refreshes (`docs/temporal.md`): the history shown again from the camera of a later
//! refresh that has no new frame. Shown from its own camera it is the frame itself; shown
//! from a camera one to four refreshes on along the corridor's sweep it is nearly as close
//! to the world seen from there as the frame is to its own view (the frame shown again is
//! not); it leaves the history as it was and is what the display shows until the frame is
//! presented again; and it needs the temporal mode and a frame.

mod common;

use common::*;
use steadyray_quality::{Rgb8Image, flip};
use steadyray_render::{Picture, Presented, RenderError, Renderer, TemporalSettings};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{Camera, Scene, builtin};

fn picture_of(presented: Presented) -> Rgb8Image {
    match presented {
        Presented::Host(Picture {
            width,
            height,
            rgba,
        }) => Rgb8Image::from_rgba(width, height, &rgba).unwrap(),
        Presented::Device => panic!("the CPU backend hands its picture to the host"),
    }
}

/// A temporal renderer with a 160×90 history after 30 frames of S = 4 along the corridor's
/// sweep, 1/60 s apart, ending at `end_s`.
fn swept(scene: &Scene, end_s: f64) -> CpuRenderer {
    let mut r = loaded(scene);
    r.set_temporal(Some(TemporalSettings {
        width: 160,
        height: 90,
    }))
    .unwrap();
    for k in 0..30 {
        let t_s = end_s - f64::from(29 - k) / 60.0;
        r.render(&scene.camera_at_time(t_s), t_s, &settings(160, 90, 4.0, 8))
            .unwrap();
    }
    r
}

/// The world at `t_s` from the sweep's camera then (S = 256).
fn world_at(scene: &Scene, t_s: f64) -> Rgb8Image {
    let mut view = scene.clone();
    view.camera = scene.camera_at_time(t_s);
    let image = render(&view, settings(160, 90, 256.0, 8));
    Rgb8Image::from_rgba(image.width, image.height, &image.to_srgb8_rgba()).unwrap()
}

#[test]
fn a_warp_to_the_frames_own_view_is_the_frame() {
    let scene = builtin("corridor").unwrap();
    let mut r = swept(&scene, 0.5);
    let shown = picture_of(r.present().unwrap());
    let warped = picture_of(r.present_warped(&scene.camera_at_time(0.5)).unwrap());
    assert!(
        shown == warped,
        "the frame shown again from its own camera changed"
    );
}

#[test]
fn a_warp_shows_the_view_of_a_later_refresh() {
    let scene = builtin("corridor").unwrap();
    let end_s = 0.5;
    let mut r = swept(&scene, end_s);
    let before = r.read_image().unwrap();
    let shown = picture_of(r.present().unwrap());
    for refreshes in [1, 2, 4] {
        let t_s = end_s + f64::from(refreshes) / 60.0;
        let truth = world_at(&scene, t_s);
        let warped = picture_of(r.present_warped(&scene.camera_at_time(t_s)).unwrap());
        let (stale, fresh) = (
            flip(&truth, &shown).unwrap().mean(),
            flip(&truth, &warped).unwrap().mean(),
        );
        let own = flip(&world_at(&scene, end_s), &shown).unwrap().mean();
        eprintln!(
            "{refreshes} refreshes on: the frame again {stale:.4}, warped {fresh:.4} \
             (the frame against its own view {own:.4})"
        );
        assert!(
            fresh < 0.3 * stale && fresh < 1.5 * own,
            "{refreshes} refreshes on: warped FLIP {fresh} against {stale} for the frame again \
             and {own} for the frame against its own view"
        );
    }
    assert_eq!(
        r.read_image().unwrap(),
        before,
        "a warp changed the history"
    );
    let t_s = end_s + 1.0 / 60.0;
    let warped = picture_of(r.present_warped(&scene.camera_at_time(t_s)).unwrap());
    let read = |r: &mut CpuRenderer| {
        let p = r.read_picture().unwrap();
        Rgb8Image::from_rgba(p.width, p.height, &p.rgba).unwrap()
    };
    assert!(
        read(&mut r) == warped,
        "the display shows the warped picture"
    );
    assert!(picture_of(r.present().unwrap()) == shown);
    assert!(
        read(&mut r) == shown,
        "presented again, the display shows the frame"
    );
}

#[test]
fn a_warp_needs_the_temporal_mode_and_a_frame() {
    let scene = builtin("corridor").unwrap();
    let camera: Camera = scene.camera;
    let mut plain = loaded(&scene);
    plain
        .render(&camera, 0.0, &settings(32, 18, 1.0, 2))
        .unwrap();
    let err = plain.present_warped(&camera).unwrap_err();
    assert!(
        matches!(err, RenderError::Unavailable(_)) && err.to_string().contains("temporal mode"),
        "{err}"
    );
    let mut empty = loaded(&scene);
    empty
        .set_temporal(Some(TemporalSettings {
            width: 32,
            height: 18,
        }))
        .unwrap();
    assert!(matches!(
        empty.present_warped(&camera),
        Err(RenderError::NoFrame)
    ));
}
