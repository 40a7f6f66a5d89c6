//! Controllers against the simulated renderer: deterministic, on a fake clock, never the wall
//! clock. Run with `--nocapture` to see the figures.

use std::f64::consts::{FRAC_PI_2, PI};
use steadyray_control::metrics::{FrameRecord, RunSummary, summarize};
use steadyray_control::simulate::{
    Load, LoadProfile, RendererModel, SimRenderer, corridor_load, run,
};
use steadyray_control::{Band, Bounds, Controller, Quality, ReportError, Setup, from_name};

const BAND: Band = Band::PAPER;
const WARM_UP: usize = 20;

fn setup(start: Quality) -> Setup {
    Setup::new(BAND, Bounds::default(), start).unwrap()
}

fn controller(name: &str, start: Quality) -> Box<dyn Controller> {
    from_name(name, setup(start), "").unwrap()
}

fn top() -> Quality {
    Bounds::default().max_quality()
}

fn show(label: &str, s: &RunSummary) {
    println!(
        "{label:40} in {:5.1}% over {:4.1}% under {:4.1}% (at max {:4.1}%) rev/100 {:4.2} \
         changes {:3} settle {:?}/{:?} spp {:6.1} R {:4.1} scale {:4.2}",
        s.in_band_pct,
        s.over_pct,
        s.under_pct,
        s.under_at_max_pct,
        s.reversals_per_100,
        s.quality_changes,
        s.settle_mean,
        s.settle_max,
        s.mean_spp,
        s.mean_depth,
        s.mean_scale
    );
}

fn sweep(name: &str, noise: f64, seed: u64) -> RunSummary {
    let frames = 720;
    let mut model = RendererModel::corridor(frames);
    model.noise = noise;
    model.seed = seed;
    let mut c = controller(name, top());
    // A warm-up lap, then the counted lap (the load profile repeats every `frames`).
    let records = run(c.as_mut(), &model, frames + WARM_UP);
    let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
    show(&format!("{name} corridor noise {noise} seed {seed}"), &s);
    s
}

#[test]
fn the_simulated_corridor_needs_control() {
    let model = RendererModel::corridor(720);
    let max = top();
    // Mirrors in view: the highest quality takes many times Tmax.
    assert!(model.ideal_ms(&max, &corridor_load(0.0)) > 5.0 * BAND.tmax_ms());
    // Nothing in view: even the highest quality is under Tmin.
    assert!(model.ideal_ms(&max, &corridor_load(FRAC_PI_2)) < BAND.tmin_ms());
    assert!(model.ideal_ms(&max, &corridor_load(-FRAC_PI_2)) < BAND.tmin_ms());
    // Looking back at the spheres: medium.
    let back = model.ideal_ms(&max, &corridor_load(PI));
    assert!(back > model.ideal_ms(&max, &corridor_load(FRAC_PI_2)) && back < 2.0 * BAND.tmax_ms());
    let fixed = sweep("fixed", 0.03, 1);
    assert!(fixed.over_pct > 30.0 && fixed.under_at_max_pct > 20.0);
}

#[test]
fn step_on_depth_oscillates_across_a_narrow_band() {
    // A steady view where one level of R costs more than the band is wide.
    let load = Load::geometric(0.9, 0.95, 1.0, 1.8);
    let model = RendererModel::corridor(720).with_profile(LoadProfile::Constant(load.clone()));
    let start = Quality::new(128.0, 16, 1.0);
    let times: Vec<f64> = (0..=16)
        .map(|r| model.ideal_ms(&Quality { depth: r, ..start }, &load))
        .collect();
    let r = times.iter().position(|&t| t > BAND.tmax_ms()).unwrap();
    assert!(
        r > 0 && times[r - 1] < BAND.tmin_ms(),
        "no depth straddles the band: {times:?}"
    );

    let mut c = controller("step", start);
    let records = run(c.as_mut(), &model, 300);
    let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
    show("step(depth) constant, band < one step", &s);
    assert!(s.reversals_per_100 > 30.0, "{s:?}");
    assert!(
        s.in_band_pct < 50.0 && s.over_pct > 20.0 && s.under_pct > 20.0,
        "{s:?}"
    );
    for name in ["hysteresis", "predictive"] {
        let mut c = controller(name, start);
        let records = run(c.as_mut(), &model, 400);
        // The steady stretch, once the first cuts from the start quality are done.
        let s = summarize(&records[50..], BAND, top(), Some(&[]));
        show(&format!("{name} constant, same load"), &s);
        assert!(
            s.in_band_pct >= 99.0 && s.reversals_per_100 <= 1.5,
            "{name}: {s:?}"
        );
    }
}

#[test]
fn hysteresis_and_predictive_hold_the_corridor_sweep() {
    for seed in 1..=3 {
        for name in ["hysteresis", "predictive"] {
            let s = sweep(name, 0.03, seed);
            assert!(s.ok_pct >= 99.0, "{name} seed {seed}: {s:?}");
            assert!(s.longest_over_run <= 1, "{name} seed {seed}: {s:?}");
            // The sweep turns four times; beyond that, hardly any flips.
            assert!(s.reversals_per_100 <= 2.0, "{name} seed {seed}: {s:?}");
        }
        let s = sweep("predictive", 0.05, seed);
        assert!(
            s.ok_pct >= 99.0 && s.reversals_per_100 <= 1.5,
            "seed {seed}: {s:?}"
        );
    }
}

#[test]
fn steady_load_is_held_still_at_the_centre() {
    for theta in [0.0, 0.6, 1.0, PI] {
        let model =
            RendererModel::corridor(720).with_profile(LoadProfile::Constant(corridor_load(theta)));
        for name in ["hysteresis", "predictive"] {
            let mut c = controller(name, top());
            let records = run(c.as_mut(), &model, 600);
            let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
            show(&format!("{name} constant θ={theta:.1}"), &s);
            assert!(s.ok_pct >= 99.0, "{name} θ={theta}: {s:?}");
            assert!(s.reversals_per_100 <= 1.5, "{name} θ={theta}: {s:?}");
            if name == "predictive" && s.under_at_max_pct == 0.0 {
                // Continuous knobs: it sits at the band's centre, not at an edge.
                assert!(
                    (s.tp_mean - BAND.centre_ms()).abs() < 1.0,
                    "θ={theta}: {s:?}"
                );
            }
        }
    }
}

fn step_run(name: &str, profile: LoadProfile, frames: usize) -> (Vec<FrameRecord>, RunSummary) {
    let model = RendererModel::corridor(720).with_profile(profile.clone());
    let mut c = controller(name, top());
    let records = run(c.as_mut(), &model, frames);
    let changes: Vec<usize> = profile
        .changes(frames)
        .iter()
        .map(|&f| f - WARM_UP)
        .collect();
    let s = summarize(&records[WARM_UP..], BAND, top(), Some(&changes));
    (records, s)
}

#[test]
fn settles_within_five_frames_after_a_2x_load_step() {
    let base = corridor_load(0.5);
    let profiles = [
        ("2x rays", LoadProfile::ray_step(base.clone(), 2.0, 16, 150)),
        (
            "2x cost per ray",
            LoadProfile::Step {
                before: base.clone(),
                after: base.clone().with_cost_factor(2.0),
                at: 150,
            },
        ),
        ("0.5x rays (a drop)", {
            let LoadProfile::Step { before, after, at } =
                LoadProfile::ray_step(base.clone(), 2.0, 16, 150)
            else {
                unreachable!()
            };
            LoadProfile::Step {
                before: after,
                after: before,
                at,
            }
        }),
    ];
    for (label, profile) in profiles {
        for name in ["hysteresis", "predictive"] {
            let (_, s) = step_run(name, profile.clone(), 400);
            show(&format!("{name} {label} at frame 150"), &s);
            assert_eq!(
                (s.settle_events, s.unsettled),
                (1, 0),
                "{name} {label}: {s:?}"
            );
            assert!(s.settle_max.unwrap() <= 5, "{name} {label}: {s:?}");
        }
    }
}

#[test]
fn returns_to_the_highest_quality_when_the_load_drops() {
    let profile = LoadProfile::Step {
        before: corridor_load(0.0),
        after: corridor_load(FRAC_PI_2),
        at: 100,
    };
    for name in ["hysteresis", "predictive"] {
        let (records, _) = step_run(name, profile.clone(), 300);
        assert!(
            records[99].quality.cmp_level(&top()).is_lt(),
            "{name} never cut"
        );
        let back = records
            .iter()
            .skip(100)
            .position(|r| r.quality == top())
            .map(|p| p + 100);
        println!("{name}: back at the highest quality on frame {back:?}");
        let back = back.unwrap_or_else(|| panic!("{name} stayed degraded"));
        assert!(back < 160, "{name} took until frame {back}");
        assert!(
            records[back..].iter().all(|r| r.quality == top()),
            "{name} left the top again"
        );
    }
}

/// A swarm of objects appearing at once in view and vanishing 150 frames later: the world
/// changes, not the camera. A quarter of the eye rays then hit swarm objects (mirrors: most
/// of those bounce on, each takes two shadow rays) and the scene holds 20 times the
/// objects (each ray's BVH traversal a few levels deeper), so within one frame the rays per
/// depth and the cost per ray jump. Over a light view (the highest quality fits the band)
/// and a heavy one (the band sets the quality), both adaptive controllers settle within
/// five frames of each change and, once the swarm is gone, come back to the quality they
/// held before it: the highest the band allows.
#[test]
fn a_swarm_appearing_and_vanishing_is_settled_within_five_frames() {
    let (from, until, frames) = (150, 300, 500);
    for (view, theta) in [("light view", FRAC_PI_2), ("heavy view", 0.5)] {
        let base = corridor_load(theta);
        let swarm = base.clone().with_swarm(0.25, 0.8, 2.0, 20.0, 4.0);
        let model = RendererModel::corridor(720);
        let (before_ms, during_ms) = (
            model.ideal_ms(&top(), &base),
            model.ideal_ms(&top(), &swarm),
        );
        assert!(
            during_ms > 2.0 * before_ms,
            "{view}: the swarm takes {during_ms:.1} ms against {before_ms:.1} ms"
        );
        let profile = LoadProfile::Interval {
            base,
            during: swarm,
            from,
            until,
        };
        for name in ["hysteresis", "predictive"] {
            let (records, s) = step_run(name, profile.clone(), frames);
            show(&format!("{name} swarm, {view}"), &s);
            assert_eq!(
                (s.settle_events, s.unsettled),
                (2, 0),
                "{name} {view}: {s:?}"
            );
            assert!(s.settle_max.unwrap() <= 5, "{name} {view}: {s:?}");
            // The rays per depth jump within the frame the swarm appears.
            let level = |r: &FrameRecord| r.rays as f64 / f64::from(r.quality.spp);
            assert!(
                level(&records[from]) > 1.2 * level(&records[from - 1]),
                "{name} {view}: rays per eye ray {} -> {}",
                level(&records[from - 1]),
                level(&records[from])
            );
            // Afterwards, back to the quality held before the swarm.
            let mean_spp = |r: &[FrameRecord]| {
                r.iter().map(|r| f64::from(r.quality.spp)).sum::<f64>() / r.len() as f64
            };
            let before = mean_spp(&records[from - 50..from]);
            let after = mean_spp(&records[until + 100..]);
            println!("{name} {view}: mean S {before:.2} before, {after:.2} after");
            assert!(
                (after - before).abs() <= 0.1 * before,
                "{name} {view}: mean S {before:.2} before the swarm, {after:.2} after"
            );
            assert!(
                records[until + 100..]
                    .iter()
                    .all(|r| r.quality.depth == records[from - 1].quality.depth),
                "{name} {view}: R changed"
            );
            if view == "light view" {
                assert!(
                    records[until + 100..].iter().all(|r| r.quality == top()),
                    "{name}: not back at the highest quality"
                );
            }
        }
    }
}

/// The qualities of a run where `spikes` frames are 10x hitches, and of the same run without.
fn with_and_without_spike(name: &str, spike_at: usize) -> (Vec<Quality>, Vec<Quality>) {
    let mut model =
        RendererModel::corridor(720).with_profile(LoadProfile::Constant(corridor_load(0.4)));
    model.timer_ms = 0.0; // so the hitch does not shift the timer's phase for later frames
    let baseline = run(controller(name, top()).as_mut(), &model, 300);
    model.spike_frames = vec![spike_at];
    let spiked = run(controller(name, top()).as_mut(), &model, 300);
    assert!(spiked[spike_at].tp_ms > 9.0 * baseline[spike_at].tp_ms);
    let q = |r: Vec<FrameRecord>| r.into_iter().map(|r| r.quality).collect();
    (q(baseline), q(spiked))
}

#[test]
fn a_single_10x_spike_costs_at_most_two_frames_of_quality() {
    for name in ["hysteresis", "predictive"] {
        let (baseline, spiked) = with_and_without_spike(name, 150);
        let lowered = baseline
            .iter()
            .zip(&spiked)
            .filter(|(b, s)| s.cmp_level(b).is_lt())
            .count();
        println!("{name}: a 10x spike lowered quality for {lowered} frames");
        assert!(lowered <= 2, "{name}: {lowered} frames lowered");
        assert_eq!(
            baseline[160..],
            spiked[160..],
            "{name} did not return to the same course"
        );
    }
}

#[test]
fn refused_reports_never_poison_a_controller() {
    let model = RendererModel::corridor(300);
    for name in ["fixed", "step", "hysteresis", "predictive"] {
        let start = Quality::new(8.0, 8, 1.0);
        let mut clean = controller(name, start);
        let baseline = run(clean.as_mut(), &model, 300);
        let mut c = controller(name, start);
        let mut renderer = SimRenderer::new(model.clone());
        for (frame, expected) in baseline.iter().enumerate() {
            let q = c.quality();
            assert_eq!(q, expected.quality, "{name} diverged at frame {frame}");
            let report = renderer.render(frame, q);
            if frame % 37 == 5 {
                for bad in [f64::NAN, f64::INFINITY, 0.0, -4.0, 1e9] {
                    let mut r = report.clone();
                    r.tp_ms = bad;
                    assert!(c.observe(&r).is_err(), "{name} accepted {bad}");
                    assert_eq!(c.quality(), q);
                }
            }
            c.observe(&report).unwrap();
        }
    }
    let mut p = controller("predictive", top());
    let mut r = SimRenderer::new(model).render(0, top());
    r.rays_per_depth.clear();
    assert_eq!(p.observe(&r), Err(ReportError::NoRays));
}

#[test]
fn reset_restarts_the_same_run() {
    let model = RendererModel::corridor(200);
    for name in ["step", "hysteresis", "predictive"] {
        let mut c = controller(name, top());
        let first = run(c.as_mut(), &model, 200);
        c.reset();
        assert_eq!(c.quality(), top());
        let second = run(c.as_mut(), &model, 200);
        assert_eq!(first, second, "{name}");
    }
}

/// The cost per ray drifting by 2.7x over 60 frames, up (a mesh filling the view, as the
/// bunny does on an H100: 0.03 to 0.08 ns per ray) or down, at 1920x1080 with GPU-like timing
/// (0.3 ms fixed, exact timestamps). Each frame is only a little off its prediction, so no
/// frame is an outlier; a cost line fitted across the drift blamed it on the fixed cost and
/// cut far too deep on every overload, swinging S between 40 and 70 for 30 frames (94 % in
/// band, 5.7 reversals per 100 frames on the H100).
#[test]
fn a_drifting_cost_per_ray_is_followed_without_swinging() {
    let base = Load::geometric(0.0, 0.0, 1.0, 0.0);
    for (label, from, to) in [("rising", 1.0f64, 2.7), ("falling", 2.7, 1.0)] {
        let loads: Vec<Load> = (0..400)
            .map(|f| {
                let x = ((f as f64 - 100.0) / 60.0).clamp(0.0, 1.0);
                base.clone().with_cost_factor(from * (to / from).powf(x))
            })
            .collect();
        for noise in [0.01, 0.03] {
            let mut model =
                RendererModel::corridor(720).with_profile(LoadProfile::Frames(loads.clone()));
            model.full_pixels = 1920 * 1080;
            model.ns_per_ray = 0.02;
            model.fixed_ms = 0.3;
            model.noise = noise;
            model.timer_ms = 0.0;
            for name in ["hysteresis", "predictive"] {
                let mut c = controller(name, top());
                let records = run(c.as_mut(), &model, 400);
                let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
                show(&format!("{name} cost per ray {label}, noise {noise}"), &s);
                // `predictive` keeps 97.6 % on the rising cost with 3 % noise (98.5 % or more
                // before issue 47's aim: its inner band now follows the measured noise, and
                // the errors it measures across a drift include the model's lag), and its
                // narrower inner band re-plans more often: 1.6 reversals per 100 frames at
                // most, not the 5.7 of the swinging this test guards against.
                assert!(s.in_band_pct >= 97.5, "{name} {label} noise {noise}: {s:?}");
                assert!(
                    s.reversals_per_100 <= 2.0,
                    "{name} {label} noise {noise}: {s:?}"
                );
            }
        }
    }
}

/// A pass-sized fixed cost (8 ms, as the temporal mode's on two cores) and a view whose
/// rays bounce between the mirrors: from the top, `predictive` keeps R = 16 and cuts the
/// scale. A run that arrives with R cut (here it starts at R = 3, as after an overload cut
/// on a view where deeper levels carried under 2 % of the rays) raises R only as deep as it
/// has seen rays go, then the scale, and once inside the inner band raises and cuts do
/// nothing: without trades it stays short of R = 16; with them it reaches what the run
/// from the top holds.
#[test]
fn an_r_cut_on_a_shallow_view_is_traded_back_on_a_deep_one() {
    let load = corridor_load(0.0);
    let mut model = RendererModel::corridor(720).with_profile(LoadProfile::Constant(load.clone()));
    model.fixed_ms = 8.0;
    let one = Quality::new(1.0, 16, 1.0);
    model.ns_per_ray *= 10.0 / (model.ideal_ms(&one, &load) - model.fixed_ms);
    let from_top = run(controller("predictive", top()).as_mut(), &model, 300);
    let settled = from_top[299].quality;
    assert_eq!(settled.depth, 16, "{settled}");
    // R = 3 at the scale that takes the band's centre.
    let (mut lo, mut hi) = (0.25f32, 1.0f32);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if model.ideal_ms(&Quality::new(1.0, 3, mid), &load) < BAND.centre_ms() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let cut = Quality::new(1.0, 3, lo);
    for (options, traded) in [("", true), ("trades=false", false)] {
        let mut c = from_name("predictive", setup(cut), options).unwrap();
        let records = run(c.as_mut(), &model, 300);
        let last = records[299].quality;
        println!("predictive {options}: from {cut} to {last} (from the top: {settled})");
        if traded {
            assert_eq!(last.depth, settled.depth, "{last}");
            assert!(
                (last.scale - settled.scale).abs() <= 0.05,
                "{last} vs {settled}"
            );
        } else {
            assert!(last.depth < 16, "without trades R came back: {last}");
        }
        let s = summarize(&records[50..], BAND, top(), Some(&[]));
        assert!(
            s.in_band_pct >= 95.0 && s.reversals_per_100 <= 2.0,
            "{options}: {s:?}"
        );
    }
}

/// A pass-sized fixed cost (8 ms), a shallow view (the
/// level reached by some rays, the next by none), a slow spell of sixteen frames at 2.8
/// times the time, then a deep view (rays bouncing between the mirrors), from R = 0: where a
/// cut once left a run (the spell, which no quality answers, ended cut to the floor while
/// one slow frame was cut on; spikes are now set aside until confirmed, and the confirmed
/// change is taken as a cost per ray, which the scale answers). Frames at R = 0 once
/// measured no level ratio and carried the last one, read from the two deepest levels
/// alone as 0 (some rays, then none): no level beyond 0 looked reached, and R stayed 0 on
/// the deep view for good (`predictive +temporal` at one refresh on the CPU). Now the ratio
/// is read from all measured levels, and each frame counts the next level's rays (the
/// chains its depth limit stopped), so R comes back as the view deepens.
#[test]
fn a_cut_to_r_zero_comes_back_on_a_deep_view() {
    let shallow = Load {
        reach: vec![1.0, 0.3, 0.09, 0.027, 0.0081],
        shadow_eye: 1.0,
        shadow_bounce: 1.0,
        cost_factor: 1.0,
    };
    let deep = corridor_load(0.0);
    let loads: Vec<Load> = (0..300)
        .map(|f| {
            if f < 60 {
                shallow.clone()
            } else {
                deep.clone()
            }
        })
        .collect();
    // The deep view at R = 16 fits the band's centre at 0.6 of the scale.
    let model = RendererModel::corridor(720).with_profile(LoadProfile::Frames(loads));
    let mut model = with_fixed_cost(model, &deep, 8.0, 0.6);
    let start = Quality::new(1.0, 0, 1.0);
    model.spike_factor = 2.8;
    model.spike_frames = (28..44).collect();
    let records = run(controller("predictive", start).as_mut(), &model, 300);
    let depths: Vec<u32> = records.iter().map(|r| r.quality.depth).collect();
    println!("R per frame: {depths:?}");
    assert!(depths[299] >= 8, "{depths:?}");
}

/// A view where 1 % of the eye rays meet a mirror and then bounce on between two (95 % go
/// on at each level), a pass-sized fixed cost, and a run arriving at R = 0 (after a cut).
/// No level beyond 0 is reached by `min_reach` (2 %) of the eye rays, so R was raised only
/// after S reached its top, which it never does here: R stayed 0, and the mirror pixels
/// dull. The levels beyond together cost little, so R goes to its top first.
#[test]
fn a_cheap_depth_comes_back_before_samples() {
    let load = Load::geometric(0.01, 0.95, 1.0, 1.0);
    let model = RendererModel::corridor(720).with_profile(LoadProfile::Constant(load.clone()));
    let model = with_fixed_cost(model, &load, 8.0, 0.6);
    let records = run(
        controller("predictive", Quality::new(1.0, 0, 0.5)).as_mut(),
        &model,
        200,
    );
    let last = records[199].quality;
    println!("from R = 0: {last}");
    assert_eq!(last.depth, 16, "{last}");
    let s = summarize(&records[50..], BAND, top(), Some(&[]));
    assert!(s.in_band_pct >= 95.0 && s.reversals_per_100 <= 2.0, "{s:?}");
}

/// `model` with a fixed cost of `fixed_ms` (pass-sized: the temporal mode's on two cores)
/// and the cost per ray at which S = 1, R = 16 on `load` takes the band's centre at `scale`
/// of the resolution.
fn with_fixed_cost(
    mut model: RendererModel,
    load: &Load,
    fixed_ms: f64,
    scale: f64,
) -> RendererModel {
    model.fixed_ms = fixed_ms;
    let full = Quality::new(1.0, 16, 1.0);
    let rays_ms = (BAND.centre_ms() - fixed_ms) / (scale * scale);
    model.ns_per_ray *= rays_ms / (model.ideal_ms(&full, load) - fixed_ms);
    model
}

/// `predictive` from S = 1, R = 16 at full scale on the corridor's mirror view with a fixed cost of `fixed_ms`
/// (R = 16 fitting at `scale`), frames 100, 140 and 180 taking 1.6 times their prediction (a
/// slow spell of the machine): the quality of each of those frames and of the next.
fn around_slow_frames(fixed_ms: f64, scale: f64) -> Vec<(Quality, Quality)> {
    let load = corridor_load(0.0);
    let model = RendererModel::corridor(720).with_profile(LoadProfile::Constant(load.clone()));
    let mut model = with_fixed_cost(model, &load, fixed_ms, scale);
    model.spike_factor = 1.6;
    model.spike_frames = vec![100, 140, 180];
    let full = Quality::new(1.0, 16, 1.0);
    let records = run(controller("predictive", full).as_mut(), &model, 220);
    model
        .spike_frames
        .iter()
        .map(|&f| {
            let (before, after) = (records[f].quality, records[f + 1].quality);
            println!("fixed {fixed_ms} ms, slow frame {f}: {before} then {after}");
            (before, after)
        })
        .collect()
}

/// A fixed cost that fills most of the band (14 ms of [15, 20], as the temporal pass does at
/// one refresh) and single slow frames. Where the fitted fixed cost, scaled by the frame's
/// surprise, is over the target alone, no quality fits: the overload cut went to the floor
/// (S = 1, R = 0, scale 0.25) for the next frame, a flash of a poor picture (here after
/// frame 180). Now such a surprise is not scaled: a cut that can restore the band still
/// happens (after frames 100 and 140, the scale), a cut to the floor does not.
#[test]
fn a_slow_frame_no_cut_can_answer_leaves_the_quality() {
    for (before, after) in around_slow_frames(14.0, 0.6) {
        assert_eq!(after.depth, 16, "{before} then {after}");
        assert!(after.scale > 0.25, "{before} then {after}");
    }
}

/// An 8 ms fixed cost in [15, 20] with the scale held low (R = 16 fits at about 0.3 of it)
/// and single slow frames. With S at 1 and the scale nearly at its floor, the surprise's cut
/// fell on R (to 0: the mirrors' reflections gone until R came back). A cut on one
/// unconfirmed overload now keeps R; here even the scale's floor would not fit under the
/// surprise, so no cut is made at all.
#[test]
fn one_slow_frame_does_not_cut_r() {
    for (before, after) in around_slow_frames(8.0, 0.3) {
        assert_eq!(after.depth, 16, "{before} then {after}");
        assert!(after.scale > 0.25, "{before} then {after}");
    }
}
