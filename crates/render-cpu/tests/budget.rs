//! Frames rendered within a time budget (`Renderer::set_frame_budget`): a unit of samples
//! at a time, stopped before the budget's end or filled past the planned S. The budgets
//! here are set so that the clock decides nothing (never stop, or stop at once), so the
//! tests are exact and never depend on the machine's speed.

mod common;

use common::{corridor, loaded, settings};
use steadyray_render::{FrameBudget, Image, RenderError, Renderer, TemporalSettings};

/// A budget the clock never stops: fills up to `max_spp`.
fn unbounded(max_spp: f32) -> FrameBudget {
    FrameBudget::new(1e9, 1e9, max_spp).unwrap()
}

fn render(budget: Option<FrameBudget>, spp: f32) -> (Image, f32, Vec<u64>) {
    let scene = corridor();
    let mut r = loaded(&scene);
    r.set_frame_budget(budget).unwrap();
    let stats = r
        .render(&scene.camera, 0.0, &settings(64, 36, spp, 8))
        .unwrap();
    (r.read_image().unwrap(), stats.spp, stats.rays.per_depth)
}

#[test]
fn a_budget_that_never_runs_out_renders_the_plain_frame_bit_for_bit() {
    // At odd S every pixel takes whole pairs: the plain frame's samples in its order.
    for spp in [1.0, 3.0, 5.0] {
        let (plain, plain_spp, plain_rays) = render(None, spp);
        let (within, within_spp, within_rays) = render(Some(unbounded(spp)), spp);
        assert_eq!(within.pixels, plain.pixels, "S = {spp}");
        assert_eq!(
            (within_spp, within_rays),
            (plain_spp, plain_rays),
            "S = {spp}"
        );
    }
}

#[test]
fn a_frame_that_would_end_early_is_filled_up_to_the_budgets_most_samples() {
    // Planned at S = 1, filled while the clock allows, which it always does: S = 5.
    let (filled, spp, rays) = render(Some(unbounded(5.0)), 1.0);
    let (plain, _, plain_rays) = render(None, 5.0);
    assert_eq!(spp, 5.0);
    assert_eq!((filled.pixels, rays), (plain.pixels, plain_rays));
}

#[test]
fn a_spent_budget_leaves_one_sample_a_pixel() {
    // Stopped before any unit: the first (centre) sample of every pixel, the plain S = 1.
    let spent = FrameBudget::new(1e-9, 1e-9, 8.0).unwrap();
    let (cut, spp, rays) = render(Some(spent), 4.0);
    let (plain, _, plain_rays) = render(None, 1.0);
    assert_eq!(spp, 1.0);
    assert_eq!((cut.pixels, rays), (plain.pixels, plain_rays));
}

#[test]
fn a_fractional_s_is_reached_unit_by_unit_with_its_rays_counted() {
    // S = 2: eight units of pairs, half the pixels at 3 samples, half at 1; the S reported
    // is the frame's mean, eye rays over pixels.
    let (_, spp, rays) = render(Some(unbounded(2.0)), 2.0);
    assert_eq!(rays[0], 2 * 64 * 36, "eye rays");
    assert_eq!(spp, rays[0] as f32 / (64.0 * 36.0));
    // At a size whose 8×8 tiles split unevenly into the units' groups the mean moves off
    // the plan (here 1.70 for 1.5, five tiles by three): the S reported is still the
    // frame's own.
    let scene = corridor();
    let mut r = loaded(&scene);
    r.set_frame_budget(Some(unbounded(1.5))).unwrap();
    let stats = r
        .render(&scene.camera, 0.0, &settings(37, 21, 1.5, 8))
        .unwrap();
    let mean = stats.rays.per_depth[0] as f32 / (37.0 * 21.0);
    assert_eq!(stats.spp, mean);
    assert!(stats.spp > 1.0 && stats.spp < 2.0, "{}", stats.spp);
}

#[test]
fn the_temporal_mode_refuses_a_budget() {
    let scene = corridor();
    let mut r = loaded(&scene);
    let history = TemporalSettings {
        width: 64,
        height: 36,
    };
    r.set_temporal(Some(history)).unwrap();
    let err = r.set_frame_budget(Some(unbounded(4.0))).unwrap_err();
    assert!(matches!(err, RenderError::Unavailable(_)), "{err}");
    assert!(err.to_string().contains("temporal"), "{err}");
    // Set before the temporal mode, it is refused at the frame.
    let mut r = loaded(&scene);
    r.set_frame_budget(Some(unbounded(4.0))).unwrap();
    r.set_temporal(Some(history)).unwrap();
    let err = r.render(&scene.camera, 0.0, &settings(64, 36, 1.0, 8));
    assert!(matches!(err, Err(RenderError::Unavailable(_))));
}
