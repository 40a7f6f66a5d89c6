//! `steadyray bench`: the paper's experiment (`spec/bench.md`). Every controller runs the
//! same camera sweep from the same starting quality, one after another in one process; the
//! paper's fixed-R baseline and the best fixed quality run beside them. Writes a table,
//! `frames.csv`, `summary.json` and `frametime.png`/`.svg` into the output folder.
//!
//! `--quality` also measures what each controller delivers: every `--every`-th frame's FLIP
//! against a reference of the same view (rendered before the runs, [`quality`]);
//! `--record DIR` keeps every delivered frame for playback ([`playback`]).
//!
//! `--clock real` runs each controller for a span of display time on the display model
//! instead ([`real_clock`], `spec/display.md`): the table, `summary.json` and `table.md` then
//! say what the viewer saw (frames shown per second, repeats, pacing, latency); `--quality`
//! measures the screen against the world at sampled refreshes ([`displayed`]; each one's
//! scores in `displayed.csv`) and `--video DIR` writes the screen and the reference at every
//! refresh ([`video`]).

pub(crate) mod displayed;
mod experiment;
pub(crate) mod machine;
mod playback;
pub mod plot;
pub mod quality;
pub(crate) mod real_clock;
mod record;
pub mod report;
pub(crate) mod source;
pub(crate) mod video;

use crate::backend::create_renderer;
use crate::cli::{BoundsArgs, ClockChoice, DisplayArgs, SceneArgs, TemporalChoice};
use anyhow::{Context, Result, bail};
use clap::Args;
use displayed::{TimedReferences, run_samples, time_key};
use experiment::{Capture, Sweep, run_controller, search_best_fixed};
use indicatif::{ProgressBar, ProgressStyle};
use real_clock::{Keep, RealSweep, run_controller_real};
use record::ControllerRun;
use report::{RealContext, RunContext, quality_label};
use source::{FrameSource, RendererSource};
use std::collections::BTreeSet;
use std::path::PathBuf;
use steadyray_control::{
    Band, CONTROLLER_NAMES, Controller, Quality, Setup, from_name, parse_options,
};
use steadyray_display::model::refresh_at_or_after;
use steadyray_display::{RealClock, SyncMode, ViewingSetup, aligned_band};
use steadyray_motion::{MotionProbe, MotionTracker};
use steadyray_render::check_image_size;
use steadyray_render::sample_stream::check_reference_spp;

#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames in the sweep (frame k has yaw 2π·k/frames).
    #[arg(long, default_value_t = 720)]
    pub frames: u32,
    /// Warm-up frames before each controller's counted frames: at the first view under the
    /// frame clock; under the real clock one refresh apart leading up to the path's start.
    #[arg(long, default_value_t = 10)]
    pub warmup: u32,
    /// Lower edge of the frame-time band, ms.
    #[arg(long, default_value_t = 15.0)]
    pub tmin: f64,
    /// Upper edge of the frame-time band, ms.
    #[arg(long, default_value_t = 20.0)]
    pub tmax: f64,
    /// With --clock real: `refresh` derives the band from the display instead of --tmin and
    /// --tmax: render times whose frames, handed over, make every refresh (`refresh:M`:
    /// every M-th), with the hand-over measured before the runs; with --warp and M of 2 or
    /// more the band of the runs with the history also leaves room for the M − 1 warped
    /// refreshes after each frame, their cost measured before the runs too (see
    /// `steadyray_display::aligned_band`); the runs without it (`--temporal both`) show no
    /// warps and keep the band without them.
    #[arg(long, value_name = "refresh[:M]", conflicts_with_all = ["tmin", "tmax"])]
    pub band: Option<RefreshBand>,
    /// Controllers to run, comma separated; each may take options after a colon, e.g.
    /// `step:knob=both`, `predictive:order=depth,spp` or `fixed:spp=4 depth=16`. The first
    /// `fixed` also adds the best fixed quality (unless --no-best-fixed).
    #[arg(
        long,
        default_value = "fixed,step,step:knob=both,hysteresis,predictive"
    )]
    pub controllers: String,
    /// Full-scale image width (default: suits the backend, so the band is reachable).
    #[arg(long)]
    pub width: Option<u32>,
    /// Full-scale image height (default: suits the backend).
    #[arg(long)]
    pub height: Option<u32>,
    /// Output folder.
    #[arg(long, default_value = "results/bench")]
    pub out: PathBuf,
    /// Use the simulated renderer (a cost model on a fake clock) instead of a real one.
    #[arg(long)]
    pub simulate: bool,
    #[command(flatten)]
    pub bounds: BoundsArgs,
    /// R of the paper's fixed baseline and of every controller's start (default: the
    /// largest R). S starts at its minimum and the scale at its maximum.
    #[arg(long)]
    pub fixed_depth: Option<u32>,
    /// Skip the search for the best fixed quality.
    #[arg(long)]
    pub no_best_fixed: bool,
    /// Views of the sweep the best-fixed search renders each candidate at.
    #[arg(long, default_value_t = 48)]
    pub search_views: u32,
    /// Measure the delivered quality: FLIP of every `--every`-th frame against a reference
    /// render of the same view (outside the timed loop). Adds flip_mean and flip_p95 to
    /// summary.json and the table, a flip column to frames.csv and a quality row to the plot.
    #[arg(long)]
    pub quality: bool,
    /// With --quality: measure frames 0, K, 2K, ... of the sweep (with --clock real: the
    /// screen at one refresh in K, its place in each run of K moving on from run to run, so
    /// frames held for several refreshes are seen at each of them).
    #[arg(long, default_value_t = 24, value_name = "K")]
    pub every: u32,
    /// With --quality or --video: the reference's eye rays per pixel S, at full scale, at
    /// least 2 (default 256; with --clock real, where a reference is rendered per refresh,
    /// 16). References draw samples no frame draws (docs/quality.md).
    #[arg(long)]
    pub reference_spp: Option<f32>,
    /// With --quality: the reference's reflection depth R.
    #[arg(long, default_value_t = 16)]
    pub reference_depth: u32,
    /// Write every delivered frame (PNG, full resolution) and timings.csv for playback
    /// (`steadyray view --playback`): into DIR when one controller runs, else into one
    /// sub-folder of DIR per controller.
    #[arg(long, value_name = "DIR")]
    pub record: Option<PathBuf>,
    /// How time runs: `frames` (the paper's protocol: frame k of N shows the path at k/N of
    /// its length) or `real` (display time on the display model, spec/display.md: each frame
    /// renders the world at its predicted display time; a faster controller renders more).
    #[arg(long, value_enum, default_value_t = ClockChoice::Frames)]
    pub clock: ClockChoice,
    /// With --clock real: seconds of display time per run (default: the path's length, its
    /// frames at 60 per second).
    #[arg(long, allow_negative_numbers = true)]
    pub duration: Option<f64>,
    #[command(flatten)]
    pub display: DisplayArgs,
    /// The temporal mode (docs/temporal.md): `off`, `on` (every run accumulates its frames
    /// into a full-resolution history, the pass inside Tp), or `both` (every controller runs
    /// without, then with it, labelled "+temporal"). `--temporal` alone means `on`.
    #[arg(
        long,
        value_enum,
        default_value_t = TemporalChoice::Off,
        num_args = 0..=1,
        default_missing_value = "on"
    )]
    pub temporal: TemporalChoice,
    /// With --clock real, vsync on and the temporal mode: a refresh whose frame rendered the
    /// world of another time shows it warped to the refresh's camera from its history
    /// (docs/temporal.md, "Warped refreshes"): a refresh without a new frame (the warp made
    /// while the next frame renders, delaying it, but never past its refresh) and a frame
    /// shown a refresh early or late (the warp made before its refresh, if it fits). The temporal runs are labelled
    /// "+temporal +warp".
    #[arg(long)]
    pub warp: bool,
    /// With --clock real: write the screen of every run and the reference at every refresh
    /// into DIR (lossless PNG sequences, timings.csv, a video each, video.json) for the JOD
    /// tool (scripts/jod/). References already in DIR/reference for the same set-up are
    /// reused.
    #[arg(long, value_name = "DIR")]
    pub video: Option<PathBuf>,
}

/// `--band refresh[:M]`: a band for frames shown every M-th refresh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RefreshBand {
    pub multiple: u32,
}

impl std::str::FromStr for RefreshBand {
    type Err = String;

    fn from_str(text: &str) -> std::result::Result<Self, Self::Err> {
        let bad = || format!("`{text}`: write refresh, or refresh:M with M a whole number >= 1");
        let multiple = match text.trim().split_once(':') {
            None if text.trim() == "refresh" => 1,
            Some(("refresh", m)) => m.trim().parse::<u32>().map_err(|_| bad())?,
            _ => return Err(bad()),
        };
        if multiple == 0 {
            return Err(bad());
        }
        Ok(Self { multiple })
    }
}

impl std::fmt::Display for RefreshBand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.multiple {
            1 => write!(f, "refresh"),
            m => write!(f, "refresh:{m}"),
        }
    }
}

/// The median of `measure(i)` over the calls i = `frames` to 2 · `frames` − 1, after as
/// many not kept (the first frames' buffers are still being allocated); `what` names it
/// in the error when nothing was measured.
fn median_after_warm_up(
    frames: u32,
    what: &str,
    mut measure: impl FnMut(u32) -> Result<f64>,
) -> Result<f64> {
    let mut times = Vec::new();
    for i in 0..2 * frames {
        let ms = measure(i)?;
        if i >= frames {
            times.push(ms);
        }
    }
    steadyray_display::stats::quantile(&times, 0.5)
        .with_context(|| format!("no frame to measure the {what}"))
}

/// The median hand-over cost of `frames` frames at the path's start at quality `q`, ms
/// ([`median_after_warm_up`]).
fn measure_hand_over(source: &mut dyn FrameSource, q: Quality, frames: u32) -> Result<f64> {
    median_after_warm_up(frames, "hand-over", |_| {
        source.frame(source::PathPoint::Time { index: 0, t_s: 0.0 }, q)?;
        Ok(source.hand_over()?.ms)
    })
}

/// The median cost of a warped refresh, ms ([`median_after_warm_up`]): frames at quality
/// `q` from the path's start, one refresh (`period_s`) apart, accumulated into a history
/// (moving, so that each resamples it, as in a run), each handed over and then warped to
/// the camera of the next refresh; the temporal mode is off again afterwards.
fn measure_warp(
    source: &mut dyn FrameSource,
    q: Quality,
    frames: u32,
    period_s: f64,
) -> Result<f64> {
    source.set_temporal(true)?;
    let ms = median_after_warm_up(frames, "warp", |i| {
        let t_s = f64::from(i) * period_s;
        let index = i as usize;
        source.frame(source::PathPoint::Time { index, t_s }, q)?;
        source.hand_over()?;
        Ok(source.warp(t_s + period_s, false)?.ms)
    })?;
    source.set_temporal(false)?;
    Ok(ms)
}

/// The real clock's settings, checked.
struct RealOptions {
    display: steadyray_display::DisplayConfig,
}

/// Checks the clock options: the display's under `--clock real`, none of them under the
/// frame clock, and `--record` only under the frame clock.
fn real_options(args: &BenchArgs) -> Result<Option<RealOptions>> {
    match args.clock {
        ClockChoice::Frames => {
            if args.duration.is_some()
                || args.display.is_given()
                || args.video.is_some()
                || args.warp
            {
                bail!(
                    "--duration, --refresh, --vsync, --vrr, --video and --warp need --clock real"
                );
            }
            Ok(None)
        }
        ClockChoice::Real => {
            if args.record.is_some() {
                bail!("--record keeps frames of the frame clock; with --clock real use --video");
            }
            if args.simulate && (args.quality || args.video.is_some()) {
                bail!(
                    "--quality and --video need a renderer that produces images (not --simulate)"
                );
            }
            let display = args.display.config()?;
            if args.warp {
                if args.temporal == TemporalChoice::Off {
                    bail!("--warp shows a temporal history again: it needs --temporal on or both");
                }
                if display.sync != SyncMode::Vsync {
                    bail!("--warp fills the refreshes of a display with vsync on (--vsync on)");
                }
            }
            Ok(Some(RealOptions { display }))
        }
    }
}

/// The runs of one temporal mode: with the history (and, with `--warp`, its warped
/// refreshes) or without, their band and their controllers (one per `--controllers` entry,
/// in order).
struct Arm {
    temporal: bool,
    band: Band,
    setup: Setup,
    controllers: Vec<Box<dyn Controller>>,
}

/// One controller to run, as named on the command line (the window builds its controllers
/// from one too).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ControllerSpec {
    pub(crate) name: String,
    pub(crate) options: String,
}

impl ControllerSpec {
    /// A `perceptual` controller not told its hand-over: under the real clock the bench
    /// measures it and passes it on, so that its bands are `--band refresh`'s.
    fn lacks_hand_over(&self) -> bool {
        self.lacks("hand_over")
    }

    /// A `perceptual` controller not told what a warped refresh costs: under `--warp` the
    /// bench measures it and passes it on, so that its bands leave room for the warps.
    fn lacks_warp(&self) -> bool {
        self.lacks("warp")
    }

    /// A `perceptual` controller whose options do not give `key`.
    pub(crate) fn lacks(&self, key: &str) -> bool {
        self.name == "perceptual"
            && !parse_options(&self.options).is_ok_and(|o| o.iter().any(|(k, _)| k == key))
    }

    /// Tells a `perceptual` controller a measured cost (`hand_over`, `warp`) its options do
    /// not give, as `key=ms`; whether it was told.
    pub(crate) fn tell_measured(&mut self, key: &str, ms: f64) -> bool {
        let lacks = self.lacks(key);
        if lacks {
            self.add_option(&format!("{key}={ms:.3}"));
        }
        lacks
    }

    /// Appends `key=value` to the options.
    fn add_option(&mut self, option: &str) {
        if !self.options.is_empty() {
            self.options.push(' ');
        }
        self.options.push_str(option);
    }

    /// The run's name in reports (not for `fixed`, named by its quality): the controller and
    /// its options; for `perceptual`, its `model` file by its stem and the measured
    /// `hand_over` and `warp` left out.
    fn label(&self) -> String {
        if self.name != "perceptual" {
            return match self.options.is_empty() {
                true => self.name.clone(),
                false => format!("{} {}", self.name, self.options.replace(',', "+")),
            };
        }
        let options: Vec<String> = parse_options(&self.options)
            .unwrap_or_default()
            .into_iter()
            .filter(|(k, _)| k != "hand_over" && k != "warp")
            .map(|(k, v)| match k.as_str() {
                "model" => {
                    let stem = std::path::Path::new(&v)
                        .file_stem()
                        .map_or_else(|| v.clone(), |s| s.to_string_lossy().into_owned());
                    format!("{k}={stem}")
                }
                _ => format!("{k}={v}"),
            })
            .collect();
        if options.is_empty() {
            self.name.clone()
        } else {
            format!("{} {}", self.name, options.join("+"))
        }
    }
}

/// Splits `--controllers`: commas separate controllers, except inside an option value
/// (a piece that does not start with a controller name belongs to the one before).
fn parse_controllers(text: &str) -> Result<Vec<ControllerSpec>> {
    let mut specs: Vec<ControllerSpec> = Vec::new();
    for piece in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (name, options) = piece.split_once(':').unwrap_or((piece, ""));
        if CONTROLLER_NAMES.contains(&name.trim()) {
            specs.push(ControllerSpec {
                name: name.trim().to_string(),
                options: options.trim().to_string(),
            });
        } else if let Some(last) = specs.last_mut().filter(|s| !s.options.is_empty()) {
            last.options.push(',');
            last.options.push_str(piece);
        } else {
            bail!(
                "unknown controller {name:?} in --controllers (expected one of: {})",
                CONTROLLER_NAMES.join(", ")
            );
        }
    }
    if specs.is_empty() {
        bail!("--controllers names no controller");
    }
    Ok(specs)
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

/// Runs the experiment and writes its reports.
pub fn run(args: &BenchArgs) -> Result<()> {
    let bounds = args.bounds.bounds()?;
    let start = Quality {
        spp: bounds.spp_min,
        depth: args.fixed_depth.unwrap_or(bounds.depth_max),
        scale: bounds.scale_max,
    };
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    if let Some(spp) = args.reference_spp {
        check_reference_spp(spp)?;
    }
    let real = real_options(args)?;
    if args.simulate && args.temporal != TemporalChoice::Off {
        bail!("--temporal needs a renderer (not --simulate)");
    }
    let mut specs = parse_controllers(&args.controllers)?;
    let build =
        |band: Band, specs: &[ControllerSpec]| -> Result<(Setup, Vec<Box<dyn Controller>>)> {
            let setup =
                Setup::new(band, bounds, start).context("--fixed-depth is outside the R bounds")?;
            let controllers = specs
                .iter()
                .map(|s| Ok(from_name(&s.name, setup, &s.options)?))
                .collect::<Result<Vec<_>>>()?;
            Ok((setup, controllers))
        };
    // Checks the controllers before anything renders (a band aligned with the display is
    // only known once the hand-over is measured).
    build(Band::new(args.tmin, args.tmax)?, &specs)?;
    if let Some(dir) = &args.video {
        video::prepare(dir)?;
    }

    let (mut source, scene_name): (Box<dyn FrameSource>, String) = if args.simulate {
        (
            Box::new(source::simulated(args.frames)),
            "corridor (simulated)".into(),
        )
    } else {
        let scene = args.scene.load()?;
        let mut renderer = create_renderer(args.scene.backend)?;
        renderer.load_scene(&scene)?;
        let info = renderer.info();
        let (w, h) = default_resolution(&info.backend, &info.device);
        let name = scene.name.clone();
        let (width, height) = (args.width.unwrap_or(w), args.height.unwrap_or(h));
        check_image_size(width, height)?;
        let motion = MotionProbe::new(&scene, (width, height), ViewingSetup::standard_fhd())?;
        let source = RendererSource {
            renderer,
            scene,
            width,
            height,
            motion: MotionTracker::new(motion),
        };
        (Box::new(source), name)
    };
    // The hand-over, measured once when a display-aligned band or a controller choosing its
    // frame time needs it.
    let needs_hand_over = real.is_some()
        && (args.band.is_some() || specs.iter().any(ControllerSpec::lacks_hand_over));
    let hand_over_ms = if needs_hand_over {
        Some(measure_hand_over(
            source.as_mut(),
            start,
            args.warmup.max(5),
        )?)
    } else {
        None
    };
    if let Some(ms) = hand_over_ms {
        for spec in specs.iter_mut() {
            if spec.tell_measured("hand_over", ms) {
                eprintln!(
                    "bench: {}: hand-over {ms:.2} ms (median at the start quality)",
                    spec.name
                );
            }
        }
    }
    // Warped refreshes between frames run on the same machine as the frames: their cost,
    // measured once when a band of more than one refresh or a controller choosing its frame
    // time leaves room for them.
    let needs_warp = args.warp
        && (args.band.is_some_and(|b| b.multiple > 1)
            || specs.iter().any(ControllerSpec::lacks_warp));
    let modes = args.temporal.modes();
    // The runs without the history show no warps: their controllers are not told of any.
    let mut warped_specs = specs.clone();
    let measured_warp_ms = match &real {
        Some(options) if needs_warp => {
            let period_s = options.display.period_ms() / 1000.0;
            let ms = measure_warp(source.as_mut(), start, args.warmup.max(5), period_s)?;
            for spec in warped_specs.iter_mut() {
                if spec.tell_measured("warp", ms) {
                    eprintln!(
                        "bench: {}: warped refresh {ms:.2} ms (median at the start quality)",
                        spec.name
                    );
                }
            }
            Some(ms)
        }
        _ => None,
    };
    // The band of the runs that warp, and of those that do not (the same band unless a
    // display-aligned band leaves room for warps).
    let (band, plain_band, aligned) = match (&args.band, &real, hand_over_ms) {
        (None, _, _) => {
            let band = Band::new(args.tmin, args.tmax)?;
            (band, band, None)
        }
        (Some(_), None, _) => bail!("--band refresh needs --clock real"),
        (Some(_), Some(_), None) => bail!("the hand-over was not measured"),
        (Some(choice), Some(options), Some(hand_over_ms)) => {
            let warp_ms = match measured_warp_ms {
                Some(ms) if choice.multiple > 1 => ms,
                _ => 0.0,
            };
            let aligned = |warp_ms| -> Result<Band> {
                let (tmin, tmax) =
                    aligned_band(&options.display, choice.multiple, hand_over_ms, warp_ms)?;
                Ok(Band::new(tmin, tmax)?)
            };
            let band = aligned(warp_ms)?;
            let plain_band = aligned(0.0)?;
            let (tmin, tmax) = (band.tmin_ms(), band.tmax_ms());
            let costs = if warp_ms > 0.0 {
                let warps = choice.multiple - 1;
                format!(
                    "hand-over {hand_over_ms:.2} ms, {warps} warp(s) of {warp_ms:.2} ms (medians"
                )
            } else {
                format!("hand-over {hand_over_ms:.2} ms (median")
            };
            // Runs without the history in a band of their own.
            let plain_runs = plain_band != band && modes.contains(&false);
            let plain = if plain_runs {
                format!(
                    "; runs without the history (no warps): [{:.2}, {:.2}] ms",
                    plain_band.tmin_ms(),
                    plain_band.tmax_ms()
                )
            } else {
                String::new()
            };
            eprintln!(
                "bench: --band {choice}: {costs} at the start quality), band [{tmin:.2}, {tmax:.2}] ms{plain}"
            );
            (
                band,
                plain_band,
                Some(report::AlignedBand {
                    refreshes: choice.multiple,
                    hand_over_ms,
                    warp_ms,
                    plain_band_ms: plain_runs.then(|| [plain_band.tmin_ms(), plain_band.tmax_ms()]),
                }),
            )
        }
    };
    // One set of controllers per arm: a run with the history and its warps, or without.
    let mut arms = Vec::new();
    for &temporal in modes {
        let warps = temporal && args.warp;
        let (arm_band, arm_specs) = match warps {
            true => (band, &warped_specs),
            false => (plain_band, &specs),
        };
        let (setup, controllers) = build(arm_band, arm_specs)?;
        arms.push(Arm {
            temporal,
            band: arm_band,
            setup,
            controllers,
        });
    }
    let real = match real {
        Some(options) => {
            let duration_s = args.duration.unwrap_or_else(|| source.path_duration_s());
            // Checks the duration before any run.
            RealClock::new(options.display, duration_s)?;
            Some(RealSweep {
                display: options.display,
                duration_s,
                warmup: args.warmup,
                band,
                bounds,
                warp: false,
            })
        }
        None => None,
    };
    let (backend, device) = source.describe();
    let (width, height) = source.resolution();
    match &real {
        None => eprintln!(
            "bench: {scene_name} at {width}x{height} on {backend} ({device}), band [{}, {}] ms, {} frames",
            band.tmin_ms(),
            band.tmax_ms(),
            args.frames
        ),
        Some(r) => eprintln!(
            "bench: {scene_name} at {width}x{height} on {backend} ({device}), band [{}, {}] ms, clock real: {} s on {}",
            band.tmin_ms(),
            band.tmax_ms(),
            r.duration_s,
            r.display
        ),
    }
    let sweep = Sweep {
        frames: args.frames,
        warmup: args.warmup,
        band,
        bounds,
    };
    // Progress counts frames under the frame clock, ms of display time under the real one.
    let per_run = match &real {
        None => u64::from(args.frames + args.warmup),
        Some(r) => (r.duration_s * 1000.0) as u64,
    };
    let unit = if real.is_some() { "ms shown" } else { "frames" };
    let progress = ProgressBar::new(per_run * (specs.len() * modes.len()) as u64);
    progress.set_style(
        ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {unit}, {{msg}} [{{elapsed}}]"
        ))
        .expect("the progress template is valid"),
    );
    let reference_quality = Quality::new(
        args.reference_spp
            .unwrap_or(if real.is_some() { 16.0 } else { 256.0 }),
        args.reference_depth,
        1.0,
    );
    let references = if args.quality && real.is_none() {
        source.set_temporal(false)?;
        let every = args.every.max(1);
        progress.inc_length(args.frames.div_ceil(every) as u64);
        progress.set_message("references");
        Some(quality::References::render(
            source.as_mut(),
            args.frames,
            args.every,
            reference_quality,
            || progress.inc(1),
        )?)
    } else {
        None
    };
    if args.quality && args.every == 0 {
        bail!("--every must be at least 1");
    }
    let measured = if args.quality {
        Keep::Every(args.every)
    } else {
        Keep::Nothing
    };
    let keep_pictures = if args.video.is_some() {
        Keep::Every(1)
    } else {
        measured
    };
    let run_count = modes.len()
        * (specs.len()
            + usize::from(!args.no_best_fixed && specs.iter().any(|s| s.name == "fixed")));
    let mut video_runs = Vec::new();
    // Encodes a finished run's frames (between runs, never during one) and frees those no
    // longer needed.
    let mut keep = |mut run: ControllerRun| -> Result<ControllerRun> {
        if let Some(dir) = &args.record {
            let folder = playback::run_folder(dir, &run.name, run_count);
            playback::write_recording(&run, &folder, width, height)?;
            progress.println(format!(
                "bench: recorded {} to {}",
                run.name,
                folder.display()
            ));
            run.recorded = Vec::new();
        }
        if let (Some(shown), Some(r)) = (run.display.as_mut(), &real) {
            if let Some(dir) = &args.video {
                let folder = video::write_run(dir, &run.name, shown, &r.display, (width, height))?;
                progress.println(format!("bench: video of {} in {folder}", run.name));
                video_runs.push(video::VideoRun {
                    name: run.name.clone(),
                    folder,
                });
            }
            let needed: BTreeSet<Option<usize>> =
                run_samples(shown, r.display.period_ms(), |i| measured.wants(i))
                    .iter()
                    .map(|s| s.frame)
                    .collect();
            shown.pictures.retain(|frame, _| needed.contains(frame));
            shown
                .warps
                .pictures
                .retain(|&refresh, _| measured.wants(refresh));
        }
        Ok(run)
    };
    let capture = Capture {
        references: references.as_ref(),
        record: args.record.is_some(),
    };
    // A temporal run under the real clock warps its refreshes without a new frame with
    // --warp; each arm runs in its own band.
    let run_one = |source: &mut dyn FrameSource,
                   controller: &mut dyn Controller,
                   label: &str,
                   (band, temporal): (Band, bool)|
     -> Result<ControllerRun> {
        match &real {
            None => {
                let sweep = Sweep { band, ..sweep };
                run_controller(source, controller, label, &sweep, capture, &progress)
            }
            Some(r) => {
                let r = RealSweep {
                    band,
                    warp: args.warp && temporal,
                    ..*r
                };
                run_controller_real(source, controller, label, &r, keep_pictures, &progress)
            }
        }
    };
    let mut runs: Vec<ControllerRun> = Vec::new();
    // The best fixed quality runs once per temporal mode, after the first fixed one.
    let mut best_fixed_due = vec![!args.no_best_fixed; modes.len()];
    for (i, spec) in specs.iter().enumerate() {
        for (arm, best_due) in arms.iter_mut().zip(&mut best_fixed_due) {
            let mode = (arm.band, arm.temporal);
            let controller = &mut arm.controllers[i];
            let label = match spec.name.as_str() {
                "fixed" => format!("fixed {}", quality_label(&controller.quality(), &bounds)),
                _ => spec.label(),
            };
            let suffix = match (arm.temporal, args.warp) {
                (false, _) => "",
                (true, false) => " +temporal",
                (true, true) => " +temporal +warp",
            };
            source.set_temporal(arm.temporal)?;
            let label = format!("{label}{suffix}");
            runs.push(keep(run_one(
                source.as_mut(),
                controller.as_mut(),
                &label,
                mode,
            )?)?);
            if spec.name == "fixed" && *best_due {
                *best_due = false;
                progress.inc_length(per_run);
                let arm_sweep = Sweep {
                    band: arm.band,
                    ..sweep
                };
                let best =
                    search_best_fixed(source.as_mut(), &arm_sweep, args.search_views, &progress)?;
                let mut fixed = from_name(
                    "fixed",
                    Setup {
                        start: best,
                        ..arm.setup
                    },
                    "",
                )?;
                let label = format!("best fixed {}{suffix}", quality_label(&best, &bounds));
                source.set_temporal(arm.temporal)?;
                runs.push(keep(run_one(
                    source.as_mut(),
                    fixed.as_mut(),
                    &label,
                    mode,
                )?)?);
            }
        }
    }
    // References are plain frames.
    source.set_temporal(false)?;
    if let Some(r) = &real {
        let period = r.display.period_ms();
        let refreshes = refresh_at_or_after(r.duration_s * 1000.0, period) as usize;
        let grid: Vec<f64> = (0..refreshes).map(|i| i as f64 * period / 1000.0).collect();
        // The world times the displayed quality compares with: each sampled refresh's and
        // the world time of the frame on screen then.
        let mut needed = Vec::new();
        for run in &runs {
            if let Some(shown) = &run.display {
                for s in run_samples(shown, period, |i| measured.wants(i)) {
                    needed.extend([s.time_s, s.world_s]);
                }
            }
        }
        let needed_keys: BTreeSet<i64> = needed.iter().map(|&t| time_key(t)).collect();
        let mut references = TimedReferences::new(reference_quality);
        if let Some(dir) = &args.video {
            progress.inc_length(refreshes as u64);
            progress.set_message("references");
            let key = video::ReferenceKey {
                scene: scene_name.clone(),
                backend: backend.clone(),
                device: device.clone(),
                resolution: [width, height],
                refresh_hz: r.display.refresh_hz,
                refreshes,
                spp: reference_quality.spp,
                depth: reference_quality.depth,
                git_revision: machine::git_revision(),
            };
            video::write_references(
                dir,
                &key,
                &grid,
                source.as_mut(),
                &mut references,
                |t| needed_keys.contains(&time_key(t)),
                || progress.inc(1),
            )?;
            video::write_index(
                dir,
                &video::VideoIndex {
                    scene: scene_name.clone(),
                    refresh_hz: r.display.refresh_hz,
                    refreshes,
                    resolution: [width, height],
                    duration_s: r.duration_s,
                    display: r.display,
                    viewing: ViewingSetup::standard_fhd(),
                    reference: key,
                    runs: std::mem::take(&mut video_runs),
                },
            )?;
        }
        if args.quality {
            progress.set_message("displayed quality");
            references.render_missing(source.as_mut(), needed, || {
                progress.inc_length(1);
                progress.inc(1);
            })?;
            let ppd = ViewingSetup::standard_fhd().pixels_per_degree(width) as f32;
            for run in &mut runs {
                if let Some(shown) = run.display.as_mut() {
                    let samples = run_samples(shown, period, |i| measured.wants(i));
                    shown.quality =
                        displayed::measure(shown, &samples, &mut references, (width, height), ppd)?;
                    shown.pictures.clear();
                    shown.warps.pictures.clear();
                }
            }
        }
    }
    progress.finish_and_clear();

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let context = RunContext {
        scene: scene_name,
        backend,
        device,
        machine: machine::Machine::detect(),
        resolution: [width, height],
        band_ms: [band.tmin_ms(), band.tmax_ms()],
        frames: args.frames,
        warmup: args.warmup,
        bounds: bounds.to_string(),
        start: start.to_string(),
        git_revision: machine::git_revision(),
        clock: if real.is_some() { "real" } else { "frames" },
        temporal: args.temporal,
        real: real.as_ref().map(|r| RealContext {
            duration_s: r.duration_s,
            display: r.display,
            viewing: ViewingSetup::standard_fhd(),
            reference: (args.quality || args.video.is_some())
                .then(|| reference_quality.to_string()),
            every: args.quality.then_some(args.every),
            aligned_band: aligned,
            warp: args.warp,
        }),
    };
    record::write_frames_csv(&runs, &args.out.join("frames.csv"))?;
    let displayed_csv = real.is_some() && args.quality;
    if displayed_csv {
        record::write_displayed_csv(&runs, &args.out.join("displayed.csv"))?;
    }
    let summary = report::write_summary(&context, &runs, &args.out.join("summary.json"))?;
    if real.is_some() {
        let controllers = summary["controllers"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let table = report::display_table(&controllers);
        print!("{table}");
        let path = args.out.join("table.md");
        std::fs::write(&path, &table)
            .with_context(|| format!("cannot write {}", path.display()))?;
    } else {
        print!("{}", report::table(&runs));
        println!(
            "paper (GeForce 6800GT, 2005): {:.1} % in band without control, {:.1} % with step control",
            report::PAPER_IN_BAND_FIXED_PCT,
            report::PAPER_IN_BAND_CONTROLLED_PCT
        );
    }
    plot::write_plots(
        &runs,
        (band.tmin_ms(), band.tmax_ms()),
        &args.out.join("frametime.png"),
        &args.out.join("frametime.svg"),
    )?;
    eprintln!(
        "bench: wrote frames.csv{}, summary.json{}, frametime.png and frametime.svg to {}",
        if displayed_csv { ", displayed.csv" } else { "" },
        if real.is_some() { ", table.md" } else { "" },
        args.out.display()
    );

    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controller_lists_keep_commas_inside_options() {
        let specs = parse_controllers("fixed, step:knob=both,predictive:order=depth,spp").unwrap();
        let names: Vec<_> = specs.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["fixed", "step", "predictive"]);
        assert_eq!(specs[1].options, "knob=both");
        assert_eq!(specs[2].options, "order=depth,spp");
    }

    #[test]
    fn perceptual_runs_are_told_the_hand_over_and_named_by_their_model() {
        let mut specs =
            parse_controllers("predictive:order=depth,spp,perceptual:model=out/motion.json")
                .unwrap();
        assert!(!specs[0].lacks_hand_over());
        assert!(specs[1].lacks_hand_over());
        specs[1].add_option("hand_over=1.600");
        assert!(!specs[1].lacks_hand_over());
        assert!(!specs[0].lacks_warp() && specs[1].lacks_warp());
        specs[1].add_option("warp=6.500");
        assert!(!specs[1].lacks_warp());
        assert_eq!(
            specs[1].options,
            "model=out/motion.json hand_over=1.600 warp=6.500"
        );
        assert_eq!(specs[1].label(), "perceptual model=motion");
        assert_eq!(specs[0].label(), "predictive order=depth+spp");
    }

    #[test]
    fn perceptual_bands_are_the_display_aligned_bands() {
        use steadyray_control::ladder::{Ladder, LadderPoint, Reference};
        use steadyray_control::{Bounds, Metric, MotionModel, Perceptual, PerceptualParams};
        use steadyray_display::{DisplayConfig, SyncMode};
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
            let params = PerceptualParams {
                model: Some(model.clone()),
                hand_over_ms: 1.6,
                warp_ms,
                ..PerceptualParams::default()
            };
            let c = Perceptual::new(setup, params).unwrap();
            // It starts at the longest frame time: three refreshes, two of them warped.
            let (tmin, tmax) = aligned_band(&display, 3, 1.6, warp_ms).unwrap();
            assert!((c.band().tmin_ms() - tmin).abs() < 1e-9);
            assert!((c.band().tmax_ms() - tmax).abs() < 1e-9);
        }
    }

    #[test]
    fn unknown_or_empty_controller_lists_are_errors() {
        let err = parse_controllers("fixed,bogus").unwrap_err().to_string();
        assert!(err.contains("bogus") && err.contains("predictive"), "{err}");
        assert!(parse_controllers(" , ").is_err());
    }

    #[test]
    fn refresh_bands_parse() {
        assert_eq!("refresh".parse(), Ok(RefreshBand { multiple: 1 }));
        assert_eq!("refresh:2".parse(), Ok(RefreshBand { multiple: 2 }));
        for bad in ["refresh:0", "refresh:x", "vsync", "refresh:"] {
            let err = bad.parse::<RefreshBand>().unwrap_err();
            assert!(err.contains("refresh:M"), "{bad}: {err}");
        }
        assert_eq!(RefreshBand { multiple: 2 }.to_string(), "refresh:2");
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
