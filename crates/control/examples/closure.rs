//! The smallest integration: no graphics at all. The "renderer" is a closure whose cost
//! grows with the pixels it draws and with a load that doubles half-way through; the
//! controller moves the render scale so that each frame lands in a 15–20 ms band.
//!
//! Run with `cargo run -p steadyray-control --example closure`.

use steadyray_control::{Band, Bounds, FrameReport, Setup, from_name};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (width, height) = (1920u64, 1080u64);
    // An engine with one knob: the render scale, from a quarter to all of the resolution.
    let bounds = Bounds::new((1.0, 1.0), (0, 0), (0.25, 1.0))?;
    let band = Band::new(15.0, 20.0)?;
    let mut controller = from_name(
        "predictive",
        Setup::new(band, bounds, bounds.max_quality())?,
        "",
    )?;

    // The renderer: 2 ms of fixed cost plus 12 ns a pixel, twice that after frame 300.
    let render = |frame: u64, pixels: u64| {
        let load = if frame < 300 { 1.0 } else { 2.0 };
        2.0 + 12e-6 * load * pixels as f64
    };

    let mut in_band = 0;
    for frame in 0..600 {
        let quality = controller.quality();
        let scale = f64::from(quality.scale);
        let pixels = ((width as f64 * scale).round() * (height as f64 * scale).round()) as u64;
        let tp_ms = render(frame, pixels);
        controller.observe(&FrameReport {
            tp_ms,
            rays_per_depth: vec![pixels],
            shadow_rays: 0,
            rays_stopped: None,
            pixels,
            quality,
            speed_deg_s: 0.0,
        })?;
        in_band += usize::from(band.contains(tp_ms));
        if frame % 100 == 0 || frame == 300 {
            println!("frame {frame:3}: scale {scale:.2}, {tp_ms:5.2} ms");
        }
    }
    println!("{in_band} of 600 frames in the band");
    Ok(())
}
