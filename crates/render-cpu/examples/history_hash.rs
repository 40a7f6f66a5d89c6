//! A fingerprint of the CPU temporal mode's output, for changes that must keep its bits (a
//! faster resolve, a reordered loop): every built-in scene at 160×90, at five (frame scale,
//! S) set-ups, 14 frames each along its path (moving, then three still frames, then moving
//! again), hashing the history (`read_image`), the shown picture (`read_picture`) and the
//! history warped to a camera a few steps on (`present_warped`) after every frame. Run it
//! before and after the change; the lines must be equal. The hash is Rust's
//! `DefaultHasher`, so compare outputs of one toolchain only.
//!
//! `cargo run --release -p steadyray-render-cpu --example history_hash`

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use steadyray_render::{Presented, RenderSettings, Renderer, TemporalSettings};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{builtin, builtin_names};

/// The history's size.
const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
/// (frame scale, S): full scale and below it, whole and fractional S.
const SET_UPS: [(f32, f32); 5] = [(1.0, 1.0), (0.71, 1.0), (0.5, 2.5), (1.0, 4.0), (0.6, 1.3)];
const FRAMES: u32 = 14;

fn main() {
    let mut total = DefaultHasher::new();
    for name in builtin_names() {
        let scene = builtin(name).expect("a built-in scene parses");
        for (scale, spp) in SET_UPS {
            let settings = RenderSettings::scaled((WIDTH, HEIGHT), scale, spp, 8);
            let mut renderer = CpuRenderer::with_threads(2);
            renderer.load_scene(&scene).expect("loads");
            renderer
                .set_temporal(Some(TemporalSettings {
                    width: WIDTH,
                    height: HEIGHT,
                }))
                .expect("a valid history");
            let mut hash = DefaultHasher::new();
            for k in 0..FRAMES {
                // Frames 5 to 7 repeat frame 5's view and time: a still history.
                let step = if (5..8).contains(&k) { 5 } else { k };
                let camera = scene.camera_at(step * 7, 720);
                renderer
                    .render(&camera, f64::from(step) * 0.05, &settings)
                    .expect("renders");
                let image = renderer.read_image().expect("a history");
                for value in image.pixels.iter().flatten() {
                    value.to_bits().hash(&mut hash);
                }
                renderer
                    .read_picture()
                    .expect("a picture")
                    .rgba
                    .hash(&mut hash);
                // A refresh later: the history warped to a camera that moved on.
                match renderer
                    .present_warped(&scene.camera_at(step * 7 + 3, 720))
                    .expect("warps")
                {
                    Presented::Host(picture) => picture.rgba.hash(&mut hash),
                    Presented::Device => unreachable!("the CPU presents on the host"),
                }
            }
            let value = hash.finish();
            println!("{name} scale {scale} S {spp}: {value:016x}");
            value.hash(&mut total);
        }
    }
    println!("all: {:016x}", total.finish());
}
