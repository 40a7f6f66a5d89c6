//! A fresh renderer refuses to render without a scene or to read an image before a frame.

mod common;

use common::gpu;
use steadyray_render::{Presented, RenderError, RenderSettings, Renderer};
use steadyray_scene::builtin;

#[test]
fn needs_a_scene_then_a_frame() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    let s = RenderSettings {
        width: 16,
        height: 16,
        spp: 1.0,
        max_depth: 1,
    };
    assert!(matches!(gpu.read_image(), Err(RenderError::NoFrame)));
    assert!(matches!(gpu.read_srgb8(), Err(RenderError::NoFrame)));
    assert!(matches!(gpu.present(), Err(RenderError::NoFrame)));
    assert!(matches!(gpu.read_picture(), Err(RenderError::NoFrame)));
    assert!(matches!(
        gpu.render(&scene.camera, 0.0, &s),
        Err(RenderError::NoScene)
    ));
    gpu.load_scene(&scene).unwrap();
    gpu.render(&scene.camera, 0.0, &s).unwrap();
    // Loading another scene keeps the last frame readable.
    gpu.load_scene(&builtin("spheres").unwrap()).unwrap();
    let image = gpu.read_image().unwrap();
    assert_eq!((image.width, image.height), (16, 16));
    // Presenting tone-maps on the device: nothing comes back, and the frame stays readable.
    assert_eq!(gpu.present().unwrap(), Presented::Device);
    assert_eq!(gpu.read_image().unwrap(), image);
    // The presented picture, read back: the device's own tone map of that frame.
    let picture = gpu.read_picture().unwrap();
    assert_eq!((picture.width, picture.height), (16, 16));
    assert_eq!(picture.rgba, gpu.read_srgb8().unwrap());
    // A presented frame is tone-mapped once; the next frame (the other scene) must be
    // tone-mapped anew, whether it is presented first or read straight away.
    gpu.render(&scene.camera, 0.0, &s).unwrap();
    let next = gpu.read_picture().unwrap();
    assert_ne!(next.rgba, picture.rgba, "the old frame's picture came back");
    let host = gpu.read_image().unwrap().to_srgb8_rgba();
    assert!(next.rgba == host, "device and host tone maps differ");
    gpu.render(&scene.camera, 0.0, &s).unwrap();
    assert_eq!(gpu.present().unwrap(), Presented::Device);
    assert_eq!(gpu.read_picture().unwrap().rgba, next.rgba);
}
