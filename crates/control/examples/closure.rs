//! The smallest integration: no graphics at all. The "renderer" is a closure whose cost
//! grows with the pixels it draws and with a load that doubles half-way through; the
//! controller moves the render scale so that each frame lands in a 15–20 ms band, and says
//! why whenever it changes it.
//!
//! Run with `cargo run -p steadyray-control --example closure`.

use std::time::Duration;
use steadyray_control::{Action, Band, Bounds, Setup, from_name};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (width, height) = (1920.0, 1080.0);
    // An engine with one knob: the render scale, from a quarter to all of the resolution.
    let bounds = Bounds::scale_only(0.25, 1.0)?;
    let band = Band::new(15.0, 20.0)?;
    let mut controller = from_name(
        "predictive",
        Setup::new(band, bounds, bounds.max_quality())?,
        "",
    )?;

    // The renderer: 2 ms of fixed cost plus 12 ns a pixel, twice that from frame 300 on.
    let render = |frame: u64, scale: f32| {
        let pixels = ((width * scale).round() * (height * scale).round()) as u64;
        let load = if frame < 300 { 1.0 } else { 2.0 };
        (
            Duration::from_secs_f64((2.0 + 12e-6 * load * pixels as f64) / 1e3),
            pixels,
        )
    };

    let mut in_band = 0;
    for frame in 0..600 {
        let (time, pixels) = render(frame, controller.quality().scale);
        controller.frame_done(time, pixels)?;
        in_band += usize::from(band.contains(time.as_secs_f64() * 1e3));
        if let Some(decision) = controller.decision().filter(|d| d.action != Action::Hold) {
            println!("frame {frame:3}: {decision}");
        }
    }
    println!("{in_band} of 600 frames in the band");
    Ok(())
}
