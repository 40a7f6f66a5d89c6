//! The bench's phases called as a library, on the simulated renderer (its fake clock): the
//! checks before anything renders, the costs measured before the runs, the bands and arms,
//! one run, and the report built from it.

use steadyray_control::{Band, ControllerSpec};
use steadyray_display::RefreshBand;
use steadyray_experiment::bench::arms::{Bands, build_arms};
use steadyray_experiment::bench::costs::measure_costs;
use steadyray_experiment::bench::experiment::{Capture, Sweep, run_controller};
use steadyray_experiment::bench::plan::Plan;
use steadyray_experiment::bench::report;
use steadyray_experiment::bench::source::SIM_HAND_OVER_MS;
use steadyray_experiment::bench::{BenchConfig, open_source};
use steadyray_experiment::config::{ClockChoice, TemporalChoice};

/// The simulated bench's configuration, `frames` frames long.
fn simulated(frames: u32) -> BenchConfig {
    BenchConfig {
        simulate: true,
        frames,
        ..BenchConfig::default()
    }
}

#[test]
fn the_plan_refuses_bad_configurations_before_anything_renders() {
    let error = |config: BenchConfig| Plan::check(&config).err().unwrap().to_string();
    assert!(error(simulated(0)).contains("--frames"));
    let warp_without_real = BenchConfig {
        warp: true,
        ..simulated(10)
    };
    assert!(error(warp_without_real).contains("need --clock real"));
    let bad_controller = BenchConfig {
        controllers: "fixed,bogus".into(),
        ..simulated(10)
    };
    assert!(error(bad_controller).contains("bogus"));
    let temporal = BenchConfig {
        temporal: TemporalChoice::On,
        ..simulated(10)
    };
    assert!(error(temporal).contains("--temporal needs a renderer"));
    let plan = Plan::check(&simulated(10)).unwrap();
    assert_eq!(plan.specs.len(), 5);
    // Every controller starts at the smallest S, the largest R and full resolution.
    let start = plan.start;
    assert_eq!((start.spp, start.depth, start.scale), (1.0, 16, 1.0));
}

#[test]
fn costs_and_a_display_aligned_band_come_from_the_simulated_display() {
    let config = BenchConfig {
        clock: ClockChoice::Real,
        band: Some(RefreshBand { multiple: 2 }),
        controllers: "fixed,step".into(),
        ..simulated(60)
    };
    let mut plan = Plan::check(&config).unwrap();
    let (mut source, _) = open_source(&config).unwrap();
    let costs = measure_costs(&config, &mut plan, source.as_mut()).unwrap();
    assert_eq!(costs.hand_over_ms, Some(SIM_HAND_OVER_MS));
    assert_eq!(costs.warp_ms, None);
    // Only a perceptual controller is told the hand-over.
    let fixed = ControllerSpec {
        name: "fixed".into(),
        options: String::new(),
    };
    assert_eq!(plan.specs[0], fixed);
    let bands = Bands::derive(&config, &plan, &costs).unwrap();
    let aligned = bands.aligned.unwrap();
    assert_eq!(
        (aligned.refreshes, aligned.hand_over_ms),
        (2, SIM_HAND_OVER_MS)
    );
    // Two refreshes of 60 Hz, less the hand-over, hold the band's top.
    assert!(bands.band.tmax_ms() < 2000.0 / 60.0 - SIM_HAND_OVER_MS);
    assert_eq!(bands.plain, bands.band);
    let arms = build_arms(&config, &plan, &costs, &bands).unwrap();
    assert_eq!(arms.len(), 1);
    assert_eq!(arms[0].controllers.len(), 2);
    assert_eq!(arms[0].band, bands.band);
}

#[test]
fn a_band_from_the_display_needs_the_real_clock() {
    let config = BenchConfig {
        band: Some(RefreshBand { multiple: 1 }),
        ..simulated(10)
    };
    let mut plan = Plan::check(&config).unwrap();
    let (mut source, _) = open_source(&config).unwrap();
    let costs = measure_costs(&config, &mut plan, source.as_mut()).unwrap();
    let err = Bands::derive(&config, &plan, &costs).err().unwrap();
    assert!(
        err.to_string()
            .contains("--band refresh needs --clock real")
    );
}

#[test]
fn one_run_and_its_report() {
    let config = simulated(120);
    let plan = Plan::check(&config).unwrap();
    let (mut source, _) = open_source(&config).unwrap();
    let (_, mut controllers) = plan.build(Band::PAPER, &plan.specs[1..2]).unwrap();
    let sweep = Sweep {
        frames: 120,
        warmup: 10,
        band: Band::PAPER,
        bounds: plan.bounds,
    };
    let progress = indicatif::ProgressBar::hidden();
    let run = run_controller(
        source.as_mut(),
        controllers[0].as_mut(),
        "step",
        &sweep,
        Capture::default(),
        &progress,
    )
    .unwrap();
    assert_eq!(run.rows.len(), 120);
    assert_eq!(run.summary.frames, 120);
    // The summary is of the rows: every ray of every counted frame.
    let rays: u64 = run.rows.iter().map(|r| r.rays).sum();
    assert_eq!(run.summary.rays_total, rays);
    assert_eq!(run.rows[7].frame, 7);
    let table = report::table(std::slice::from_ref(&run));
    assert!(table.contains("step"), "{table}");
}
