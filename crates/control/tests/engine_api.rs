//! The renderer-neutral way in: an engine that knows only its frame time and the pixels it
//! shaded gets `predictive`'s full behaviour through `frame_done`, and each decision says
//! what moved and why.

use std::time::Duration;
use steadyray_control::{
    Action, Band, Bounds, Controller, FrameReport, Knob, Quality, Reason, Setup, from_name,
};

const FULL: (f64, f64) = (1920.0, 1080.0);

/// A raster engine: 2 ms fixed plus 6 ns a pixel, times the load.
fn render_ms(scale: f32, load: f64) -> (f64, u64) {
    let pixels = ((FULL.0 * f64::from(scale)).round() * (FULL.1 * f64::from(scale)).round()) as u64;
    (2.0 + 6e-6 * load * pixels as f64, pixels)
}

fn raster_controller() -> Box<dyn Controller> {
    let bounds = Bounds::scale_only(0.25, 1.0).unwrap();
    let band = Band::new(12.0, 15.0).unwrap();
    from_name(
        "predictive",
        Setup::new(band, bounds, bounds.max_quality()).unwrap(),
        "",
    )
    .unwrap()
}

/// Runs `frames` frames at `load(frame)`; returns each frame's time and decision.
fn run(
    c: &mut dyn Controller,
    frames: usize,
    load: impl Fn(usize) -> f64,
) -> Vec<(f64, steadyray_control::Decision)> {
    (0..frames)
        .map(|frame| {
            let (ms, pixels) = render_ms(c.quality().scale, load(frame));
            c.frame_done(Duration::from_secs_f64(ms / 1e3), pixels)
                .unwrap();
            (
                ms,
                c.decision().expect("predictive explains itself").clone(),
            )
        })
        .collect()
}

#[test]
fn a_raster_engine_is_held_in_its_band_by_the_render_scale() {
    let mut c = raster_controller();
    let frames = run(c.as_mut(), 400, |f| if f < 200 { 1.0 } else { 2.0 });
    let band = Band::new(12.0, 15.0).unwrap();
    let settled = frames[10..200].iter().chain(&frames[210..]);
    let in_band = settled.clone().filter(|(ms, _)| band.contains(*ms)).count();
    assert!(
        in_band as f64 >= 0.98 * settled.count() as f64,
        "{in_band} frames in the band"
    );
    // The scale alone moved, and it moved with the load.
    let scale_at = |f: usize| frames[f].1.to.scale;
    assert!(
        scale_at(399) < scale_at(199) - 0.2,
        "{} then {}",
        scale_at(199),
        scale_at(399)
    );
    assert!(
        frames
            .iter()
            .all(|(_, d)| d.to.spp == 1.0 && d.to.depth == 0)
    );
}

#[test]
fn decisions_say_what_moved_and_why() {
    let mut c = raster_controller();
    let frames = run(c.as_mut(), 300, |f| if f < 200 { 1.0 } else { 2.0 });
    // Settled: holding inside the inner band, with a prediction that comes true.
    let (_, steady) = &frames[150];
    assert_eq!(
        (steady.action, steady.reason),
        (Action::Hold, Reason::InInnerBand)
    );
    let predicted = steady.predicted_ms.unwrap();
    assert!(
        (predicted - frames[151].0).abs() < 0.05 * frames[151].0,
        "{predicted}"
    );
    assert!(steady.inner_ms[0] <= steady.target_ms && steady.target_ms <= steady.inner_ms[1]);
    assert_eq!(steady.band_ms, [12.0, 15.0]);
    // The load doubles at frame 200: within a few frames a cut of the scale, for a reason
    // that names the slow frames.
    let cut = frames[200..206]
        .iter()
        .map(|(_, d)| d)
        .find(|d| d.action == Action::Cut)
        .expect("a cut after the load doubled");
    assert_eq!(cut.knobs_moved(), [Knob::Scale]);
    assert!(cut.to.scale < cut.from.scale);
    assert!(
        matches!(cut.reason, Reason::Drift | Reason::OverInnerBand),
        "{cut}"
    );
    assert!(cut.to_string().starts_with("cut scale ("), "{cut}");
}

#[test]
fn a_pixel_report_counts_samples_as_eye_rays() {
    let q = Quality::new(2.5, 2, 0.5);
    let r = FrameReport::from_pixels(Duration::from_micros(16_500), 1000, q);
    assert_eq!(r.rays_per_depth, [2500, 0, 0]);
    assert_eq!(r.pixels, 1000);
    assert!((r.tp_ms - 16.5).abs() < 1e-12);
    assert_eq!(r.quality, q);
}

#[test]
fn a_frame_without_time_is_refused_and_changes_nothing() {
    let mut c = raster_controller();
    run(c.as_mut(), 20, |_| 1.0);
    let (before, decision) = (c.quality(), c.decision().cloned());
    assert!(c.frame_done(Duration::ZERO, 1000).is_err());
    assert_eq!(c.quality(), before);
    assert_eq!(c.decision().cloned(), decision);
}

#[test]
fn controllers_that_explain_nothing_say_so() {
    let bounds = Bounds::scale_only(0.25, 1.0).unwrap();
    let setup = Setup::new(Band::new(12.0, 15.0).unwrap(), bounds, bounds.max_quality()).unwrap();
    let mut c = from_name("hysteresis", setup, "").unwrap();
    c.frame_done(Duration::from_millis(13), 1000).unwrap();
    assert!(c.decision().is_none());
}

#[test]
fn every_error_converts_into_the_crate_error() {
    fn frame(time: Duration) -> Result<Quality, steadyray_control::Error> {
        let bounds = Bounds::scale_only(0.25, 1.0)?;
        let setup = Setup::new(Band::new(12.0, 15.0)?, bounds, bounds.max_quality())?;
        let mut c = from_name("predictive", setup, "")?;
        Ok(c.frame_done(time, 1000)?)
    }
    assert!(frame(Duration::from_millis(13)).is_ok());
    let refused = frame(Duration::ZERO).unwrap_err();
    assert!(
        matches!(refused, steadyray_control::Error::Report(_)),
        "{refused}"
    );
    assert!(refused.to_string().contains("not positive"), "{refused}");
}
