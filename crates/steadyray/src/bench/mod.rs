//! `steadyray bench`: the paper's experiment (`spec/bench.md`). Every controller runs the
//! same camera sweep from the same starting quality, one after another in one process; the
//! paper's fixed-R baseline and the best fixed quality run beside them. Writes a table,
//! `frames.csv`, `summary.json` and `frametime.png`/`.svg` into the output folder.
//!
//! `--quality` also measures what each controller delivers: every `--every`-th frame's FLIP
//! against a reference of the same view (rendered before the runs, [`quality`]);
//! `--record DIR` keeps every delivered frame for playback ([`playback`]).

mod experiment;
mod machine;
mod playback;
mod plot;
pub mod quality;
mod record;
mod report;
mod source;

use crate::backend::create_renderer;
use crate::cli::{BoundsArgs, SceneArgs};
use anyhow::{Context, Result, bail};
use clap::Args;
use experiment::{Capture, Sweep, run_controller, search_best_fixed};
use indicatif::{ProgressBar, ProgressStyle};
use record::ControllerRun;
use report::{RunContext, quality_label};
use source::{FrameSource, RendererSource};
use std::path::PathBuf;
use steadyray_control::{Band, CONTROLLER_NAMES, Quality, Setup, from_name};

#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames in the sweep (frame k has yaw 2π·k/frames).
    #[arg(long, default_value_t = 720)]
    pub frames: u32,
    /// Warm-up frames at the first view before each controller's counted frames.
    #[arg(long, default_value_t = 10)]
    pub warmup: u32,
    /// Lower edge of the frame-time band, ms.
    #[arg(long, default_value_t = 15.0)]
    pub tmin: f64,
    /// Upper edge of the frame-time band, ms.
    #[arg(long, default_value_t = 20.0)]
    pub tmax: f64,
    /// Controllers to run, comma separated; each may take options after a colon, e.g.
    /// `step:knob=both` or `predictive:order=depth,spp`. `fixed` also adds the best fixed
    /// quality (unless --no-best-fixed).
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
    /// With --quality: measure frames 0, K, 2K, ... of the sweep.
    #[arg(long, default_value_t = 24, value_name = "K")]
    pub every: u32,
    /// With --quality: the reference's eye rays per pixel S (at full scale).
    #[arg(long, default_value_t = 256.0)]
    pub reference_spp: f32,
    /// With --quality: the reference's reflection depth R.
    #[arg(long, default_value_t = 16)]
    pub reference_depth: u32,
    /// Write every delivered frame (PNG, full resolution) and timings.csv for playback
    /// (`steadyray view --playback`): into DIR when one controller runs, else into one
    /// sub-folder of DIR per controller.
    #[arg(long, value_name = "DIR")]
    pub record: Option<PathBuf>,
}

/// One controller to run, as named on the command line.
#[derive(Debug, PartialEq)]
struct ControllerSpec {
    name: String,
    options: String,
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
    let band = Band::new(args.tmin, args.tmax)?;
    let bounds = args.bounds.bounds()?;
    let start = Quality {
        spp: bounds.spp_min,
        depth: args.fixed_depth.unwrap_or(bounds.depth_max),
        scale: bounds.scale_max,
    };
    let setup = Setup::new(band, bounds, start).context("--fixed-depth is outside the R bounds")?;
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    let specs = parse_controllers(&args.controllers)?;
    let mut controllers = specs
        .iter()
        .map(|s| Ok((s, from_name(&s.name, setup, &s.options)?)))
        .collect::<Result<Vec<_>>>()?;

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
        let source = RendererSource {
            renderer,
            scene,
            width: args.width.unwrap_or(w),
            height: args.height.unwrap_or(h),
        };
        (Box::new(source), name)
    };
    let (backend, device) = source.describe();
    let (width, height) = source.resolution();
    eprintln!(
        "bench: {scene_name} at {width}x{height} on {backend} ({device}), band [{}, {}] ms, {} frames",
        band.tmin_ms(),
        band.tmax_ms(),
        args.frames
    );
    let sweep = Sweep {
        frames: args.frames,
        warmup: args.warmup,
        band,
        bounds,
    };
    let progress = ProgressBar::new((args.frames + args.warmup) as u64 * specs.len() as u64);
    progress.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} frames, {msg} [{elapsed}]")
            .expect("the progress template is valid"),
    );
    let references = if args.quality {
        let every = args.every.max(1);
        progress.inc_length(args.frames.div_ceil(every) as u64);
        progress.set_message("references");
        let reference = Quality::new(args.reference_spp, args.reference_depth, 1.0);
        Some(quality::References::render(
            source.as_mut(),
            args.frames,
            args.every,
            reference,
            || progress.inc(1),
        )?)
    } else {
        None
    };
    let run_count =
        specs.len() + usize::from(!args.no_best_fixed && specs.iter().any(|s| s.name == "fixed"));
    // Encodes a finished run's frames (between runs, never during one) and frees them.
    let keep = |mut run: ControllerRun| -> Result<ControllerRun> {
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
        Ok(run)
    };
    let capture = Capture {
        references: references.as_ref(),
        record: args.record.is_some(),
    };
    let mut runs: Vec<ControllerRun> = Vec::new();
    for (spec, controller) in &mut controllers {
        let label = match (spec.name.as_str(), spec.options.is_empty()) {
            ("fixed", _) => format!("fixed {}", quality_label(&start, &bounds)),
            (name, true) => name.to_string(),
            (name, false) => format!("{name} {}", spec.options.replace(',', "+")),
        };
        runs.push(keep(run_controller(
            source.as_mut(),
            controller.as_mut(),
            &label,
            &sweep,
            capture,
            &progress,
        )?)?);
        if spec.name == "fixed" && !args.no_best_fixed {
            progress.inc_length((args.frames + args.warmup) as u64);
            let best = search_best_fixed(source.as_mut(), &sweep, args.search_views, &progress)?;
            let mut fixed = from_name("fixed", Setup::new(band, bounds, best)?, "")?;
            let label = format!("best fixed {}", quality_label(&best, &bounds));
            runs.push(keep(run_controller(
                source.as_mut(),
                fixed.as_mut(),
                &label,
                &sweep,
                capture,
                &progress,
            )?)?);
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
    };
    print!("{}", report::table(&runs));
    println!(
        "paper (GeForce 6800GT, 2005): {:.1} % in band without control, {:.1} % with step control",
        report::PAPER_IN_BAND_FIXED_PCT,
        report::PAPER_IN_BAND_CONTROLLED_PCT
    );
    record::write_frames_csv(&runs, &args.out.join("frames.csv"))?;
    report::write_summary(&context, &runs, &args.out.join("summary.json"))?;
    plot::write_plots(
        &runs,
        (band.tmin_ms(), band.tmax_ms()),
        &args.out.join("frametime.png"),
        &args.out.join("frametime.svg"),
    )?;
    eprintln!(
        "bench: wrote frames.csv, summary.json, frametime.png and frametime.svg to {}",
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
    fn unknown_or_empty_controller_lists_are_errors() {
        let err = parse_controllers("fixed,bogus").unwrap_err().to_string();
        assert!(err.contains("bogus") && err.contains("predictive"), "{err}");
        assert!(parse_controllers(" , ").is_err());
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
