//! `steadyray bench`: the paper's experiment (`docs/bench-protocol.md`). Every controller runs the
//! same camera sweep from the same starting quality, one after another in one process; the
//! paper's fixed-R baseline and the most-in-band fixed quality (the single fixed quality with
//! the most frames in the band) run beside them; where the displayed quality is measured,
//! the best-looking fixed quality too ([`best_looking`]). Writes a table,
//! `frames.csv`, `summary.json` and `frametime.png`/`.svg` into the output folder.
//!
//! `--quality` also measures what each controller delivers: every `--every`-th frame's FLIP
//! against a reference of the same view (rendered before the runs, [`quality`]);
//! `--record DIR` keeps every delivered frame for playback ([`playback`]).
//!
//! `--repeat N` runs the whole experiment N times, each repetition a fresh run into its own
//! folder, and reports every figure's median and range over them ([`repeat`]).
//!
//! `--clock real` runs each controller for a span of display time on the display model
//! instead ([`real_clock`], `docs/display.md`): the table, `summary.json` and `table.md` then
//! say what the viewer saw (frames shown per second, repeats, pacing, latency); `--quality`
//! measures the screen against the world at sampled refreshes ([`displayed`]; each one's
//! scores in `displayed.csv`) and `--video DIR` writes the screen and the reference at every
//! refresh ([`video`]).

pub mod arms;
pub mod best_looking;
pub mod costs;
pub mod displayed;
pub mod experiment;
pub mod machine;
pub mod outputs;
pub mod plan;
pub mod playback;
pub mod plot;
pub mod quality;
pub mod real_clock;
pub mod record;
pub mod reference_store;
pub mod repeat;
pub mod repeat_summary;
pub mod report;
pub mod runs;
pub mod screen;
pub mod screen_quality;
pub mod source;
pub mod video;

use crate::backend::create_renderer;
use crate::config::{ClockChoice, DisplaySettings, SceneConfig, TemporalChoice};
use crate::frame_loop::FrameLoop;
use anyhow::{Result, bail};
use arms::{Bands, build_arms};
pub use best_looking::BestLookingFixed;
use costs::measure_costs;
use experiment::Sweep;
use indicatif::ProgressBar;
use outputs::{run_context, write_outputs};
use plan::Plan;
use real_clock::{Keep, RealSweep};
use runs::Runner;
use screen_quality::{Described, measure_screens};
use source::{FrameSource, RendererSource};
use std::path::PathBuf;
use steadyray_control::{Band, Quality, parse_controllers};
use steadyray_display::{RealClock, RefreshBand, ViewingSetup};
use steadyray_motion::{MotionProbe, MotionTracker};
use steadyray_render::check_image_size;

/// What `bench` runs: the scene and renderer (or the simulated one), the band, the
/// controllers, the clock, the display, what is measured and kept, and where the reports go.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchConfig {
    /// The scene and its renderer.
    pub scene: SceneConfig,
    /// Frames in the sweep (frame k has yaw 2π·k/frames).
    pub frames: u32,
    /// Warm-up frames before each controller's counted frames: at the first view under the
    /// frame clock; under the real clock one refresh apart leading up to the path's start.
    pub warmup: u32,
    /// Lower edge of the frame-time band, ms.
    pub tmin: f64,
    /// Upper edge of the frame-time band, ms.
    pub tmax: f64,
    /// With --clock real: `refresh` derives the band from the display instead of --tmin and
    /// --tmax: render times whose frames, handed over, make every refresh (`refresh:M`:
    /// every M-th), with the hand-over measured before the runs; with --warp and M of 2 or
    /// more the band of the runs with the history also leaves room for the M − 1 warped
    /// refreshes after each frame, their cost measured before the runs too (see
    /// `steadyray_display::aligned_band`); the runs without it (`--temporal both`) show no
    /// warps and keep the band without them.
    pub band: Option<RefreshBand>,
    /// Controllers to run, comma separated; each may take options after a colon, e.g.
    /// `step:knob=both`, `predictive:order=depth,spp` or `fixed:spp=4 depth=16`. The first
    /// `fixed` also adds the most-in-band fixed quality (unless --no-in-band-fixed) and, with
    /// --clock real --quality, the best-looking fixed quality (unless
    /// --no-best-looking-fixed).
    pub controllers: String,
    /// Full-scale image width (default: suits the backend, so the band is reachable).
    pub width: Option<u32>,
    /// Full-scale image height (default: suits the backend).
    pub height: Option<u32>,
    /// Output folder.
    pub out: PathBuf,
    /// Use the simulated renderer (a cost model on a fake clock) instead of a real one.
    pub simulate: bool,
    /// The bounds of the quality knobs, as given (the plan checks them before anything
    /// renders).
    pub bounds: steadyray_control::Bounds,
    /// R of the paper's fixed baseline and of every controller's start (default: the
    /// largest R). S starts at its minimum and the scale at its maximum.
    pub fixed_depth: Option<u32>,
    /// Skip the search for the most-in-band fixed quality (the single fixed quality with the
    /// most frames in the band).
    pub no_in_band_fixed: bool,
    /// Views of the sweep the most-in-band search renders each candidate at.
    pub search_views: u32,
    /// Which runs of the best-looking fixed quality (the fixed quality with the lowest
    /// displayed FLIP of a small set, [`best_looking`]) the bench makes.
    pub best_looking_fixed: BestLookingFixed,
    /// Measure the delivered quality: FLIP of every `--every`-th frame against a reference
    /// render of the same view (outside the timed loop). Adds flip_mean and flip_p95 to
    /// summary.json and the table, a flip column to frames.csv and a quality row to the plot.
    pub quality: bool,
    /// With --quality: measure frames 0, K, 2K, ... of the sweep (with --clock real: the
    /// screen at one refresh in K, its place in each run of K moving on from run to run, so
    /// frames held for several refreshes are seen at each of them).
    pub every: u32,
    /// With --quality or --video: the reference's eye rays per pixel S, at full scale, at
    /// least 2 (default 256; with --clock real, where a reference is rendered per refresh,
    /// 16). References draw samples no frame draws (docs/quality.md).
    pub reference_spp: Option<f32>,
    /// With --quality: the reference's reflection depth R.
    pub reference_depth: u32,
    /// Write every delivered frame (PNG, full resolution) and timings.csv for playback
    /// (`steadyray view --playback`): into DIR when one controller runs, else into one
    /// sub-folder of DIR per controller.
    pub record: Option<PathBuf>,
    /// How time runs: `frames` (the paper's protocol: frame k of N shows the path at k/N of
    /// its length) or `real` (display time on the display model, docs/display.md: each frame
    /// renders the world at its predicted display time; a faster controller renders more).
    pub clock: ClockChoice,
    /// With --clock real: seconds of display time per run (default: the path's length, its
    /// frames at 60 per second).
    pub duration: Option<f64>,
    /// The display model's settings (real clock).
    pub display: DisplaySettings,
    /// The temporal mode (docs/temporal.md): `off`, `on` (every run accumulates its frames
    /// into a full-resolution history, the pass inside Tp), or `both` (every controller runs
    /// without, then with it, labelled "+temporal"). `--temporal` alone means `on`.
    pub temporal: TemporalChoice,
    /// With --clock real, vsync on and the temporal mode: a refresh whose frame rendered the
    /// world of another time shows it warped to the refresh's camera from its history
    /// (docs/temporal.md, "Warped refreshes"): a refresh without a new frame (the warp made
    /// while the next frame renders, delaying it, but never past its refresh) and a frame
    /// shown a refresh early or late (the warp made before its refresh, if it fits). The temporal runs are labelled
    /// "+temporal +warp".
    pub warp: bool,
    /// With --clock real: write the screen of every run and the reference at every refresh
    /// into DIR (lossless PNG sequences, timings.csv, a video each, video.json) for the JOD
    /// tool (scripts/jod/). References already in DIR/reference for the same set-up are
    /// reused.
    pub video: Option<PathBuf>,
    /// With --clock real and --quality or --video: keep the references in DIR and reuse
    /// those already there ([`reference_store`]): benches of the same scene, renderer, size,
    /// reference quality and source revision render each reference once.
    pub references: Option<PathBuf>,
    /// Runs the whole experiment this many times, each repetition a fresh run (its own
    /// renderer, costs measured before the runs and the fixed baselines' searches) into
    /// `OUT/repeat-K/`, and reports per controller the median and range of every figure
    /// over the repetitions (`OUT/summary.json`, `OUT/table.md`, [`repeat`]). 1: one run
    /// written into `OUT` itself.
    pub repeat: u32,
}

/// The controllers `bench` runs unless told others: the paper's baseline and rule, the
/// rule on both knobs, `hysteresis` and `predictive`; on the CPU renderer and the
/// simulated one under the frame clock without the temporal mode, also
/// [`BUDGETED_CONTROLLER`].
pub const DEFAULT_CONTROLLERS: &str = "fixed,step,step:knob=both,hysteresis,predictive";

/// `predictive` handing each frame a time budget (`steadyray_control::budget`): the row the
/// default controllers gain where the renderer can honour one.
pub const BUDGETED_CONTROLLER: &str = "predictive:budget=true";

impl Default for BenchConfig {
    /// The paper's experiment as `steadyray bench` runs it without arguments: every
    /// controller over a 720-frame sweep of the default scene in the 15–20 ms band, written
    /// to `results/bench`.
    fn default() -> Self {
        Self {
            scene: SceneConfig::default(),
            frames: 720,
            warmup: 10,
            tmin: 15.0,
            tmax: 20.0,
            band: None,
            controllers: DEFAULT_CONTROLLERS.into(),
            width: None,
            height: None,
            out: PathBuf::from("results/bench"),
            simulate: false,
            bounds: steadyray_control::Bounds::default(),
            fixed_depth: None,
            no_in_band_fixed: false,
            search_views: 48,
            best_looking_fixed: BestLookingFixed::WithFixed,
            quality: false,
            every: 24,
            reference_spp: None,
            reference_depth: 16,
            record: None,
            clock: ClockChoice::Frames,
            duration: None,
            display: DisplaySettings::default(),
            temporal: TemporalChoice::Off,
            warp: false,
            video: None,
            references: None,
            repeat: 1,
        }
    }
}

/// The full-scale resolution a backend gets by default: large enough to matter, small
/// enough that the 15–20 ms band is reachable.
fn default_resolution(backend: &str, device: &str) -> (u32, u32) {
    let device = device.to_lowercase();
    let software = ["llvmpipe", "lavapipe", "swiftshader", "software"]
        .iter()
        .any(|s| device.contains(s));
    match backend {
        "gpu" if software => (160, 90),
        "gpu" => (1920, 1080),
        _ => (640, 360),
    }
}

/// Whether the default controllers gain [`BUDGETED_CONTROLLER`]: asked for none other, under
/// the frame clock without the temporal mode, on a renderer that honours a frame budget
/// (the CPU renderer, the simulated one).
fn takes_the_budgeted_row(config: &BenchConfig, backend: &str) -> bool {
    config.controllers == DEFAULT_CONTROLLERS
        && config.best_looking_fixed != BestLookingFixed::Only
        && config.clock == ClockChoice::Frames
        && config.temporal == TemporalChoice::Off
        && matches!(backend, "cpu" | "simulated")
}

/// Runs the experiment and writes its reports: once into `config.out`, or `config.repeat`
/// times with the repetitions' medians and ranges beside them ([`repeat::run_repeated`]).
pub fn run(config: &BenchConfig) -> Result<()> {
    match config.repeat {
        1 => run_once(config, 1),
        _ => repeat::run_repeated(config),
    }
}

/// Runs the experiment once (repetition `repetition`, counted from 1, which seeds the
/// simulated renderer's noise) and writes its reports, phase by phase: the configuration checked
/// ([`Plan::check`]), the frames' source opened, the costs the bands need measured before
/// the runs ([`measure_costs`]), the bands and arms ([`Bands::derive`], [`build_arms`]),
/// the references of the frame clock's measured frames, the runs ([`Runner::run_arms`]),
/// the real clock's screen references and displayed quality ([`measure_screens`]), and the
/// outputs ([`write_outputs`]).
pub fn run_once(config: &BenchConfig, repetition: u32) -> Result<()> {
    let mut plan = Plan::check(config)?;
    if let Some(dir) = &config.video {
        video::prepare(dir)?;
    }
    let (mut source, scene) = open_repetition_source(config, repetition)?;
    if takes_the_budgeted_row(config, &source.describe().0) {
        plan.specs.extend(parse_controllers(BUDGETED_CONTROLLER)?);
    }
    let costs = measure_costs(config, &mut plan, source.as_mut())?;
    let bands = Bands::derive(config, &plan, &costs)?;
    let mut arms = build_arms(config, &plan, &costs, &bands)?;
    let real = real_sweep(config, &plan, bands.band, source.as_ref())?;
    let (backend, device) = source.describe();
    let described = Described {
        scene,
        backend,
        device,
        resolution: source.resolution(),
    };
    announce(config, &described, bands.band, real.as_ref());
    let sweep = Sweep {
        frames: config.frames,
        warmup: config.warmup,
        band: bands.band,
        bounds: plan.bounds,
    };
    // Progress counts frames under the frame clock, ms of display time under the real one.
    let per_run = match &real {
        None => u64::from(config.frames + config.warmup),
        Some(r) => (r.duration_s * 1000.0) as u64,
    };
    let runs_made = (plan.specs.len() * config.temporal.modes().len()) as u64;
    let progress = progress_bar(per_run * runs_made, real.is_some());
    let reference_quality = Quality::new(
        config
            .reference_spp
            .unwrap_or(if real.is_some() { 16.0 } else { 256.0 }),
        config.reference_depth,
        1.0,
    );
    let references = match config.quality && real.is_none() {
        true => Some(frame_references(
            config,
            source.as_mut(),
            reference_quality,
            &progress,
        )?),
        false => None,
    };
    if config.quality && config.every == 0 {
        bail!("--every must be at least 1");
    }
    let measured = match config.quality {
        true => Keep::Every(config.every),
        false => Keep::Nothing,
    };
    let mut runner = Runner {
        config,
        bounds: plan.bounds,
        sweep,
        real,
        progress: &progress,
        per_run,
        references: references.as_ref(),
        measured,
        keep_pictures: if config.video.is_some() {
            Keep::Every(1)
        } else {
            measured
        },
        resolution: described.resolution,
        video_runs: Vec::new(),
        screen_references: screen_quality::screen_references(
            config,
            &described,
            reference_quality,
            source.as_ref(),
        )?,
    };
    let mut runs = runner.run_arms(source.as_mut(), &mut arms, &plan.specs)?;
    let Runner {
        video_runs,
        mut screen_references,
        ..
    } = runner;
    // References are plain frames.
    source.set_temporal(false)?;
    if let Some(r) = &real {
        let screens = (&mut screen_references, measured);
        measure_screens(
            (config, r),
            source.as_mut(),
            &mut runs,
            screens,
            &described,
            video_runs,
            &progress,
        )?;
    }
    progress.finish_and_clear();
    let context = run_context(
        config,
        &plan,
        &bands,
        real.as_ref(),
        described,
        reference_quality,
    );
    write_outputs(config, &context, &runs, &bands)
}

/// The source of the frames: the simulated renderer, or the scene on the configured
/// renderer at the configured (or the backend's default) size; and the scene's name.
pub fn open_source(config: &BenchConfig) -> Result<(Box<dyn FrameSource>, String)> {
    open_repetition_source(config, 1)
}

/// [`open_source`] for repetition `repetition` (from 1) of a repeated bench: a fresh
/// renderer, the simulated one's noise seeded with the repetition's number, so repetition 1
/// draws as a single run and the others draw noise of their own, as fresh runs do.
fn open_repetition_source(
    config: &BenchConfig,
    repetition: u32,
) -> Result<(Box<dyn FrameSource>, String)> {
    if config.simulate {
        let source = source::simulated_seeded(config.frames, u64::from(repetition));
        return Ok((Box::new(source), "corridor (simulated)".into()));
    }
    let scene = config.scene.load()?;
    let mut renderer = create_renderer(config.scene.backend)?;
    renderer.load_scene(&scene)?;
    let info = renderer.info();
    let (w, h) = default_resolution(&info.backend, &info.device);
    let name = scene.name.clone();
    let (width, height) = (config.width.unwrap_or(w), config.height.unwrap_or(h));
    check_image_size(width, height)?;
    let motion = MotionProbe::new(&scene, (width, height), ViewingSetup::standard_fhd())?;
    let source = RendererSource {
        renderer,
        scene,
        frame_loop: FrameLoop::new((width, height)),
        motion: MotionTracker::new(motion),
    };
    Ok((Box::new(source), name))
}

/// The real clock's runs in `band`, when the bench runs under it: the duration checked
/// before any run.
fn real_sweep(
    config: &BenchConfig,
    plan: &Plan,
    band: Band,
    source: &dyn FrameSource,
) -> Result<Option<RealSweep>> {
    let Some(display) = plan.display else {
        return Ok(None);
    };
    let duration_s = config.duration.unwrap_or_else(|| source.path_duration_s());
    RealClock::new(display, duration_s)?;
    Ok(Some(RealSweep {
        display,
        duration_s,
        warmup: config.warmup,
        band,
        bounds: plan.bounds,
        warp: false,
    }))
}

/// Says on stderr what the bench runs.
fn announce(config: &BenchConfig, described: &Described, band: Band, real: Option<&RealSweep>) {
    let (width, height) = described.resolution;
    let (scene, backend, device) = (&described.scene, &described.backend, &described.device);
    let (tmin, tmax) = (band.tmin_ms(), band.tmax_ms());
    match real {
        None => eprintln!(
            "bench: {scene} at {width}x{height} on {backend} ({device}), band [{tmin}, {tmax}] ms, {} frames",
            config.frames
        ),
        Some(r) => eprintln!(
            "bench: {scene} at {width}x{height} on {backend} ({device}), band [{tmin}, {tmax}] ms, clock real: {} s on {}",
            r.duration_s, r.display
        ),
    }
}

/// The progress bar of `len` frames (or ms of display time under the real clock).
fn progress_bar(len: u64, real: bool) -> ProgressBar {
    crate::progress::progress_bar(len, if real { "ms shown" } else { "frames" })
}

/// The references of the frame clock's measured frames (`--quality`), rendered before the
/// runs.
fn frame_references(
    config: &BenchConfig,
    source: &mut dyn FrameSource,
    reference_quality: Quality,
    progress: &ProgressBar,
) -> Result<quality::References> {
    source.set_temporal(false)?;
    let every = config.every.max(1);
    progress.inc_length(config.frames.div_ceil(every) as u64);
    progress.set_message("references");
    quality::References::render(
        source,
        config.frames,
        config.every,
        reference_quality,
        || progress.inc(1),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perceptual_bands_are_the_display_aligned_bands() {
        use steadyray_control::ladder::{Ladder, LadderPoint, Reference};
        use steadyray_control::{Bounds, Metric, MotionModel, Perceptual, PerceptualParams, Setup};
        use steadyray_display::{DisplayConfig, SyncMode, aligned_band};
        let display = DisplayConfig::new(60.0, SyncMode::Vsync).unwrap();
        let frame_times: Vec<f64> = (1..=3)
            .map(|m| f64::from(m) * display.period_ms())
            .collect();
        let point = LadderPoint {
            spp: 1.0,
            depth: 1,
            scale: 1.0,
            rays: 1.0,
            ms: 1.0,
            flip: 0.1,
        };
        let model = MotionModel {
            metric: Metric::Jod,
            scene: "test".into(),
            resolution: [64, 36],
            refresh_hz: 60.0,
            stimulus_s: 0.5,
            warped: false,
            viewing: serde_json::Value::Null,
            ladder: Ladder {
                scene: "test".into(),
                resolution: [64, 36],
                reference: Reference {
                    spp: 16.0,
                    depth: 16,
                    scale: 1.0,
                },
                views: 1,
                temporal_frames: None,
                points: vec![point],
            },
            speeds_deg_s: vec![0.0],
            scores: vec![vec![vec![9.0]; 3]],
            frame_times_ms: frame_times,
        };
        let bounds = Bounds::default();
        let setup = Setup::new(Band::PAPER, bounds, bounds.min_quality()).unwrap();
        for warp_ms in [0.0, 6.5] {
            let mut params = PerceptualParams::with_model(model.clone());
            params.hand_over_ms = 1.6;
            params.warp_ms = warp_ms;
            let c = Perceptual::new(setup, params).unwrap();
            // It starts at the longest frame time: three refreshes, two of them warped.
            let (tmin, tmax) = aligned_band(&display, 3, 1.6, warp_ms).unwrap();
            assert!((c.band().tmin_ms() - tmin).abs() < 1e-9);
            assert!((c.band().tmax_ms() - tmax).abs() < 1e-9);
        }
    }

    #[test]
    fn software_gpus_get_a_small_default_image() {
        assert_eq!(
            default_resolution("gpu", "llvmpipe (LLVM 15.0.6)"),
            (160, 90)
        );
        assert_eq!(
            default_resolution("gpu", "NVIDIA H100 80GB HBM3"),
            (1920, 1080)
        );
        assert_eq!(
            default_resolution("cpu", "AMD EPYC (2 threads)"),
            (640, 360)
        );
    }
}
