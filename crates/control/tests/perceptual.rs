//! The perceptual controller on the simulated renderer's fake clock: it chooses the frame
//! time from the screen speed, holds it, and lets the predictive cost model keep it.

mod common;

use common::{FAST, FRAME_TIMES, model, model_file};
use steadyray_control::simulate::{Load, LoadProfile, RendererModel, SimRenderer};
use steadyray_control::{
    Band, Bounds, Controller, DisplayCosts, MotionModel, Perceptual, PerceptualParams, Quality,
    ReportError, Setup,
};

fn controller() -> Perceptual {
    let bounds = Bounds::default();
    let setup = Setup::new(Band::PAPER, bounds, Quality::new(1.0, 4, 1.0)).unwrap();
    let params = PerceptualParams::with_model(model());
    Perceptual::new(setup, params).unwrap()
}

/// A constant view at 640x360: S = 1 takes about 5 ms, S = 12 about 50 ms.
fn renderer(speeds: Vec<f64>) -> SimRenderer {
    renderer_at(speeds, 3.0)
}

/// [`renderer`]'s view at `ns_per_ray` nanoseconds a ray.
fn renderer_at(speeds: Vec<f64>, ns_per_ray: f64) -> SimRenderer {
    let load = Load::geometric(0.5, 0.8, 1.0, 1.0);
    let mut model = RendererModel::corridor(1)
        .with_profile(LoadProfile::Constant(load))
        .with_speeds(speeds);
    model.ns_per_ray = ns_per_ray;
    model.timer_ms = 0.0;
    SimRenderer::new(model)
}

/// One frame of a run.
struct Step {
    target_ms: f64,
    tp_ms: f64,
    quality: Quality,
}

fn run(c: &mut Perceptual, speeds: &[f64]) -> Vec<Step> {
    run_on(c, speeds, renderer(speeds.to_vec()))
}

fn run_on(c: &mut Perceptual, speeds: &[f64], mut r: SimRenderer) -> Vec<Step> {
    (0..speeds.len())
        .map(|i| {
            let q = c.quality();
            let report = r.render(i, q);
            c.observe(&report).unwrap();
            Step {
                target_ms: c.target_frame_ms().unwrap(),
                tp_ms: report.tp_ms,
                quality: q,
            }
        })
        .collect()
}

/// The frames at which the target changed.
fn switches(steps: &[Step]) -> Vec<usize> {
    (1..steps.len())
        .filter(|&i| steps[i].target_ms != steps[i - 1].target_ms)
        .collect()
}

#[test]
fn a_still_picture_gets_the_longest_frame_and_a_speed_step_the_shortest_within_frames() {
    let mut c = controller();
    let step_at = 120;
    let mut speeds = vec![0.0; step_at];
    speeds.extend(std::iter::repeat_n(FAST, 60));
    let steps = run(&mut c, &speeds);
    // Still: the longest frame time throughout, spent on S.
    assert!(
        steps[..step_at]
            .iter()
            .all(|s| s.target_ms == FRAME_TIMES[2]),
        "{:?}",
        switches(&steps)
    );
    let still = steps[step_at - 1].quality;
    assert!(still.spp >= 8.0, "{still}");
    assert!(
        steps[step_at - 20..step_at]
            .iter()
            .all(|s| s.tp_ms < FRAME_TIMES[2])
    );
    // The speed step: the shortest frame time within 3 frames, and frames fitting it
    // within 3 more.
    let moved = (step_at..speeds.len())
        .find(|&i| steps[i].target_ms == FRAME_TIMES[0])
        .expect("the target never moved to the shortest frame time");
    assert!(
        moved - step_at <= 3,
        "moved {} frames after the step",
        moved - step_at
    );
    let fitted = steps[moved + 3..].iter().all(|s| s.tp_ms < FRAME_TIMES[0]);
    assert!(fitted, "frames do not fit a refresh after the switch");
    assert_eq!(switches(&steps), [moved]);
    let fast = steps.last().unwrap().quality;
    assert!(fast.spp < still.spp / 2.0, "{fast} vs {still}");
}

#[test]
fn the_target_follows_the_speed_profile_and_holds_each_change() {
    let mut c = controller();
    // Holds, fast turns and a slow pan, 150 frames each, then a speed jittering frame to
    // frame across the point where two frame times score the same (where a controller
    // without hysteresis flickers between them).
    const SEGMENT: usize = 150;
    let mut speeds = Vec::new();
    for v in [0.0, FAST, 5.0, FAST, 0.0] {
        speeds.extend(std::iter::repeat_n(v, SEGMENT));
    }
    let jitter_from = speeds.len();
    speeds.extend((0..300).map(|i| 28.0 + if i % 2 == 0 { 6.0 } else { -6.0 }));
    let steps = run(&mut c, &speeds);
    let wanted = [
        FRAME_TIMES[2],
        FRAME_TIMES[0],
        FRAME_TIMES[2],
        FRAME_TIMES[0],
        FRAME_TIMES[2],
    ];
    for (segment, want) in wanted.into_iter().enumerate() {
        // A fast turn gets short frames at once; a slow stretch after one gets long frames
        // once the decided speed has fallen (`fall_ms`) and the hold allows: by 100 frames.
        let (start, end) = (segment * SEGMENT, (segment + 1) * SEGMENT);
        let settle = if want == FRAME_TIMES[0] { 3 } else { 100 };
        let got: Vec<f64> = steps[start + settle.min(start)..end]
            .iter()
            .map(|s| s.target_ms)
            .collect();
        assert!(got.iter().all(|&t| t == want), "segment {segment}: {got:?}");
    }
    // No move to a longer frame time closer than the hold to the change before it (display
    // time counted at the target times); a move to a shorter one is not held back.
    let hold_ms = PerceptualParams::default().hold_ms;
    let changes = switches(&steps);
    for pair in changes.windows(2) {
        let longer = steps[pair[1]].target_ms > steps[pair[1] - 1].target_ms;
        let held: f64 = steps[pair[0]..pair[1]].iter().map(|s| s.target_ms).sum();
        assert!(
            !longer || held >= hold_ms,
            "changes at frames {pair:?}, {held} ms apart"
        );
    }
    // The jitter: one change (to the short frames the faster speed asks for), then none.
    let jittery = changes.iter().filter(|&&i| i > jitter_from).count();
    assert!(jittery <= 1, "{changes:?}");
}

/// A turn that starts right after the target moved to longer frames is not held back by
/// the hold: its first frames already aim at the shortest frame time.
#[test]
fn a_turn_right_after_a_longer_target_gets_short_frames_at_once() {
    const TURN: usize = 60;
    let mut speeds = vec![FAST; TURN];
    speeds.extend(std::iter::repeat_n(0.0, 300));
    let still = run(&mut controller(), &speeds);
    let lengthened = (TURN..speeds.len())
        .find(|&i| still[i].target_ms > still[i - 1].target_ms)
        .expect("the target never moved to longer frames once still");

    // The same run, a turn again the frame after that change.
    let turn_at = lengthened + 1;
    speeds.truncate(turn_at);
    speeds.extend(std::iter::repeat_n(FAST, 30));
    let steps = run(&mut controller(), &speeds);
    assert!(steps[lengthened].target_ms > FRAME_TIMES[0]);
    let held: f64 = steps[lengthened..turn_at + 3]
        .iter()
        .map(|s| s.target_ms)
        .sum();
    assert!(held < PerceptualParams::default().hold_ms, "{held} ms");
    assert!(
        steps[turn_at + 3..]
            .iter()
            .all(|s| s.target_ms == FRAME_TIMES[0]),
        "{:?}",
        switches(&steps)
    );
}

/// Out of the box (the shipped model, no options), on a view where the ladder's top does not
/// fit one refresh (S = 1 at full scale about 25 ms): a still picture gets the longest frame
/// time and the best picture it affords; a fast turn the shortest frame time within a few
/// frames, and back to the longest once still again. (Where the top fits one refresh, every
/// frame time shows the same picture when still, and it keeps the one it has.)
#[test]
fn the_shipped_model_gives_long_frames_when_still_and_short_ones_in_fast_motion() {
    let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
    let mut c = Perceptual::new(setup, PerceptualParams::default()).unwrap();
    let times = c.model().frame_times_ms.clone();
    let (shortest, longest) = (times[0], times[times.len() - 1]);
    let fastest = *c.model().speeds_deg_s.last().unwrap();
    let mut speeds = vec![0.0; 120];
    speeds.extend(std::iter::repeat_n(fastest, 120));
    speeds.extend(std::iter::repeat_n(0.0, 240));
    let steps = run_on(&mut c, &speeds, renderer_at(speeds.clone(), 15.0));
    let still = &steps[60..120];
    assert!(
        still.iter().all(|s| s.target_ms == longest),
        "{:?}",
        switches(&steps)
    );
    let moved = (120..240)
        .find(|&i| steps[i].target_ms == shortest)
        .expect("fast motion never got the shortest frame time");
    assert!(
        moved - 120 <= 3,
        "moved {} frames after the turn",
        moved - 120
    );
    assert!(steps[moved..240].iter().all(|s| s.target_ms == shortest));
    assert!(steps[400..].iter().all(|s| s.target_ms == longest));
    let (q_still, q_fast) = (steps[119].quality, steps[239].quality);
    assert!(q_fast.level() < q_still.level(), "{q_fast} vs {q_still}");
}

#[test]
fn a_bad_speed_is_refused_and_changes_nothing() {
    let mut c = controller();
    let mut r = renderer(vec![0.0]);
    for i in 0..10 {
        let report = r.render(i, c.quality());
        c.observe(&report).unwrap();
    }
    let (q, target) = (c.quality(), c.target_ms());
    for bad in [f64::NAN, -1.0, f64::INFINITY] {
        let mut report = r.render(10, q);
        report.speed_deg_s = bad;
        let refused = c.observe(&report).unwrap_err();
        assert!(matches!(refused, ReportError::BadSpeed(_)), "{refused}");
        assert!(refused.to_string().contains("screen speed"));
        assert_eq!((c.quality(), c.target_ms()), (q, target));
    }
}

#[test]
fn options_are_checked() {
    let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
    // No options: the shipped model.
    let shipped = steadyray_control::from_name("perceptual", setup, "").unwrap();
    let longest = MotionModel::shipped()
        .unwrap()
        .frame_times_ms
        .last()
        .copied();
    assert_eq!(shipped.target_frame_ms(), longest);
    let mut p = PerceptualParams::default();
    assert!(
        p.set("ladder", "x.json")
            .unwrap_err()
            .to_string()
            .contains("model=PATH")
    );
    p.set("forgetting", "0.9").unwrap();
    assert_eq!(p.predictive.cost.forgetting, 0.9);
    let unknown = p.set("colour", "1").unwrap_err().to_string();
    assert!(
        unknown.contains("perceptual") && unknown.contains("hold_ms"),
        "{unknown}"
    );
    // `model` names a file: the parameters take a parsed model, from_name_with reads one.
    assert!(
        p.set("model", "motion.json")
            .unwrap_err()
            .to_string()
            .contains("from_name_with")
    );
    let missing = steadyray_control::from_name_with(
        "perceptual",
        setup,
        "model=/nonexistent/motion.json",
        &common::Disk,
    )
    .unwrap_err();
    assert!(missing.to_string().contains("cannot read"), "{missing}");
    let text = std::fs::read_to_string(model_file().path()).unwrap();
    p.model = Some(steadyray_control::MotionModel::from_json(&text).unwrap());
    assert_eq!(
        p.model.map(|m| m.ladder.points.len()),
        Some(model().ladder.points.len())
    );
    // A hand-over as long as the shortest frame leaves it no band.
    let mut params = PerceptualParams::with_model(model());
    params.hand_over_ms = 16.0;
    let err = Perceptual::new(setup, params).unwrap_err().to_string();
    assert!(err.contains("leaves no band"), "{err}");
}

/// With warped refreshes between frames (`warp`), the band for M refreshes ends M − 1 warps
/// earlier; one refresh a frame has no warp to leave room for.
#[test]
fn warped_refreshes_take_their_time_from_the_longer_frames_bands() {
    let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
    let controller = |warp_ms: f64| {
        let mut params = PerceptualParams::with_model(model());
        params.warp_ms = warp_ms;
        Perceptual::new(setup, params).unwrap()
    };
    // It starts at three refreshes a frame: two warps of 6 ms come off; the lower edge stays
    // where a frame and its hand-over (1 ms) miss the second refresh.
    let (plain, warped) = (controller(0.0).band(), controller(6.0).band());
    assert!((plain.tmax_ms() - warped.tmax_ms() - 12.0).abs() < 1e-9);
    assert!((warped.tmin_ms() - (FRAME_TIMES[1] - 1.0)).abs() < 1e-9);
    // Fast motion moves the target to one refresh a frame: nothing comes off.
    let fast = |mut c: Perceptual| {
        run(&mut c, &[FAST; 20]);
        assert_eq!(c.target_ms(), FRAME_TIMES[0]);
        c.band()
    };
    assert_eq!(fast(controller(0.0)), fast(controller(6.0)));
    let mut p = PerceptualParams::default();
    p.set("warp", "6.5").unwrap();
    assert_eq!(p.warp_ms, 6.5);
    assert!(p.set("warp", "-1").is_err());
}

/// Costs measured while it runs (a live view's hand-over and warps) move its bands as the
/// options would have, and keep its target frame time and what its cost model learned; costs
/// that leave a frame time no band are refused and change nothing.
#[test]
fn measured_costs_move_the_bands_and_keep_what_it_learned() {
    let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
    let built = |warp_ms: f64| {
        let mut params = PerceptualParams::with_model(model());
        params.warp_ms = warp_ms;
        Perceptual::new(setup, params).unwrap()
    };
    let mut c = built(0.0);
    // Still: it holds the longest frame time and settles its quality there.
    run(&mut c, &[0.0; 60]);
    let (target, settled) = (c.target_ms(), c.quality());
    let costs = DisplayCosts {
        hand_over_ms: None,
        warp_ms: Some(6.0),
    };
    c.set_display_costs(costs).unwrap();
    assert_eq!(c.target_ms(), target);
    assert_eq!(c.band(), built(6.0).band());
    // The band came 12 ms closer: the next frame is already planned cheaper.
    assert!(
        c.quality().level() < settled.level(),
        "{settled} -> {}",
        c.quality()
    );
    let band = c.band();
    let too_long = DisplayCosts {
        hand_over_ms: Some(16.0),
        warp_ms: None,
    };
    let err = c.set_display_costs(too_long).unwrap_err().to_string();
    assert!(err.contains("leaves no band"), "{err}");
    assert_eq!(c.band(), band);
    let nan = DisplayCosts {
        hand_over_ms: Some(f64::NAN),
        warp_ms: None,
    };
    assert!(c.set_display_costs(nan).is_err());
    assert_eq!(c.band(), band);
}

#[test]
fn fast_motion_gets_one_refresh_below_the_shipped_ladders_cheapest_point() {
    // A view on which the shipped ladder's cheapest point takes 20 ms, over the band of one
    // refresh (about 11.5 to 14.8 ms at 60 Hz): one refresh is reached at lower resolution.
    let setup = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 4, 1.0)).unwrap();
    let mut c = Perceptual::new(setup, PerceptualParams::default()).unwrap();
    let cheapest = c.model().ladder.points[0].quality();
    let shortest = c.model().frame_times_ms[0];
    let fastest = *c.model().speeds_deg_s.last().unwrap();
    let probe = renderer_at(Vec::new(), 1.0);
    let load = probe.model().profile.load(0);
    let per_ns = probe.model().ideal_ms(&cheapest, &load) - probe.model().fixed_ms;
    let ns_per_ray = (20.0 - probe.model().fixed_ms) / per_ns;
    let speeds = vec![fastest; 240];
    let steps = run_on(&mut c, &speeds, renderer_at(speeds.clone(), ns_per_ray));
    let settled = &steps[60..];
    assert!(
        settled.iter().all(|s| s.target_ms == shortest),
        "{:?}",
        switches(&steps)
    );
    assert!(settled.iter().all(|s| s.quality.scale < cheapest.scale));
    let band = c.band();
    let in_band = settled.iter().filter(|s| band.contains(s.tp_ms)).count();
    assert!(
        in_band as f64 >= 0.9 * settled.len() as f64,
        "{in_band} of {} in {band:?}",
        settled.len()
    );
    // With warped refreshes the shipped model (of frames held, not warped) is not trusted
    // below its ladder: the same motion keeps a longer frame time.
    assert!(c.trusts_below_ladder());
    let mut params = PerceptualParams::default();
    params.warp_ms = 2.0;
    let mut warped = Perceptual::new(setup, params).unwrap();
    assert!(!warped.trusts_below_ladder());
    let steps = run_on(
        &mut warped,
        &speeds,
        renderer_at(speeds.clone(), ns_per_ray),
    );
    assert!(steps[60..].iter().all(|s| s.target_ms > shortest));
}
