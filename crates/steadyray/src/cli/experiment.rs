//! The clap arguments of the experiment's commands (`bench`, `calibrate`, `raybench`,
//! `compare`, `jod`) and how they become the library's plain configurations.

use super::{BoundsArgs, ClockChoice, DisplayArgs, SceneArgs, TemporalChoice};
use clap::{Args, Subcommand, ValueEnum};
use std::path::PathBuf;
use steadyray_display::RefreshBand;
use steadyray_experiment::bench::{BenchConfig, BestLookingFixed, DEFAULT_CONTROLLERS};
use steadyray_experiment::calibrate::CalibrateConfig;
use steadyray_experiment::compare::CompareConfig;
use steadyray_experiment::jod::JodCommand as JodConfig;
use steadyray_experiment::raybench::{RaybenchBackend as RaybenchBackendConfig, RaybenchConfig};
use steadyray_experiment::recommended::Recommended;
use steadyray_quality::PIXELS_PER_DEGREE;

/// `steadyray bench`: the experiment's command line.
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
    /// `fixed` also adds the most-in-band fixed quality (unless --no-in-band-fixed) and, with
    /// --clock real --quality, the best-looking fixed quality (unless
    /// --no-best-looking-fixed). `steadyray controllers` lists every option.
    /// `predictive:budget=true` (each frame rendered within a time budget) joins the
    /// default list on the CPU renderer under the frame clock.
    #[arg(long, default_value = DEFAULT_CONTROLLERS)]
    pub controllers: String,
    /// Full-scale image width (default: suits the backend, so the band is reachable).
    #[arg(long)]
    pub width: Option<u32>,
    /// Full-scale image height (default: suits the backend).
    #[arg(long)]
    pub height: Option<u32>,
    /// Output folder.
    #[arg(short = 'o', long, default_value = "results/bench")]
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
    /// Skip the most-in-band fixed quality: the single fixed quality with the most frames in
    /// the band, found by a search over the sweep (chosen by frame time alone, not by how
    /// it looks). Its old name --no-best-fixed still works.
    #[arg(long, alias = "no-best-fixed")]
    pub no_in_band_fixed: bool,
    /// Views of the sweep the most-in-band search renders each candidate at.
    #[arg(long, default_value_t = 48)]
    pub search_views: u32,
    /// Skip the best-looking fixed quality, which --clock real --quality adds after the
    /// first `fixed`: of nine fixed qualities (S 1, 2, 4; R 2, 4, 16; scale 0.5, 0.75, 1;
    /// docs/bench-protocol.md), each run for the display span, the one with the lowest
    /// displayed FLIP (its JOD, scored after the bench, is reported like any run's).
    #[arg(long, conflicts_with = "only_best_looking_fixed")]
    pub no_best_looking_fixed: bool,
    /// Run the best-looking fixed quality alone (once per temporal mode): its nine
    /// candidates, and the winner reported as the bench's only run. Needs --clock real
    /// --quality.
    #[arg(long, conflicts_with = "controllers")]
    pub only_best_looking_fixed: bool,
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
    /// its length) or `real` (display time on the display model, docs/display.md: each frame
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
    /// With --clock real and --quality or --video: keep the references in DIR and reuse the
    /// ones already there, so benches of the same scene, renderer, size, reference quality
    /// and source revision render each reference once (the scene suite's cells share them).
    #[arg(long, value_name = "DIR")]
    pub references: Option<PathBuf>,
    /// Run the whole experiment N times, each repetition a fresh run into OUT/repeat-K/ (as
    /// a single run writes OUT): its own renderer, and the costs measured before the runs
    /// (hand-over, warped refresh, the fixed baselines' searches) measured again; the simulated
    /// renderer draws repetition K's noise from seed K. OUT/summary.json, OUT/table.md and
    /// the table printed at the end give every figure per controller as median [min–max]
    /// over the N runs (summary.json: {median, min, max, runs}). 1: a single run into OUT.
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub repeat: u32,
    /// The display experiment in the recommended configuration of the backend used
    /// (the CPU's decided on the scene suite, docs/results/scene-suite.md; the GPU's on the
    /// corridor, docs/results/viewer.md): `--clock real` with,
    /// on the CPU renderer, `--band refresh:2 --temporal on --warp`; on a GPU, `--band
    /// refresh --temporal off` (`--backend auto` counts as a GPU where a hardware adapter
    /// is present). `view` starts in the same configuration. With --simulate, which keeps no
    /// history, `--band refresh` alone.
    #[arg(
        long = "display",
        conflicts_with_all = ["clock", "band", "tmin", "tmax", "temporal", "warp"]
    )]
    pub display_preset: bool,
}

impl BenchArgs {
    /// The library's configuration of these arguments, with `--display` expanded for the
    /// backend the bench will use.
    pub fn config(&self) -> BenchConfig {
        let mut config = BenchConfig::from(self);
        if self.display_preset {
            Recommended::for_choice(config.scene.backend).apply_to_bench(&mut config);
        }
        config
    }
}

impl From<&BenchArgs> for BenchConfig {
    fn from(args: &BenchArgs) -> Self {
        Self {
            scene: (&args.scene).into(),
            frames: args.frames,
            warmup: args.warmup,
            tmin: args.tmin,
            tmax: args.tmax,
            band: args.band,
            controllers: args.controllers.clone(),
            width: args.width,
            height: args.height,
            out: args.out.clone(),
            simulate: args.simulate,
            bounds: (&args.bounds).into(),
            fixed_depth: args.fixed_depth,
            no_in_band_fixed: args.no_in_band_fixed,
            search_views: args.search_views,
            best_looking_fixed: match (args.no_best_looking_fixed, args.only_best_looking_fixed) {
                (_, true) => BestLookingFixed::Only,
                (true, false) => BestLookingFixed::Skip,
                (false, false) => BestLookingFixed::WithFixed,
            },
            quality: args.quality,
            every: args.every,
            reference_spp: args.reference_spp,
            reference_depth: args.reference_depth,
            record: args.record.clone(),
            clock: (&args.clock).into(),
            duration: args.duration,
            display: (&args.display).into(),
            temporal: (&args.temporal).into(),
            warp: args.warp,
            video: args.video.clone(),
            references: args.references.clone(),
            repeat: args.repeat,
        }
    }
}

/// `steadyray calibrate`: the ladder and motion calibrations' command line.
#[derive(Debug, Args)]
pub struct CalibrateArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Views of the camera path to measure, evenly spaced (default 8; with --motion, 2).
    #[arg(long)]
    pub views: Option<u32>,
    /// Frames in the camera path the views are taken from (as `bench --frames`).
    #[arg(long, default_value_t = 720)]
    pub frames: u32,
    /// Full-scale image width (use the size you will bench at: FLIP's verdicts change with
    /// it; the default is `bench`'s on the CPU).
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Full-scale image height.
    #[arg(long, default_value_t = 360)]
    pub height: u32,
    /// Eye rays per pixel S to try, comma separated. Fractional values matter: at 640x360
    /// the corridor's front holds S = 1.25 and 1.5 but not 1.75 or 2, which cost more and
    /// score no better.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1,1.25,1.5,2,2.5,3,4,8,16"
    )]
    pub spp: Vec<f32>,
    /// Reflection depths R to try, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "0,1,2,3,4,6,8,12,16")]
    pub depths: Vec<u32>,
    /// Resolution scales to try, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "0.5,0.75,1")]
    pub scales: Vec<f32>,
    /// The reference's eye rays per pixel S (full scale, at least 2; it draws samples no
    /// measured setting draws). The reference setting itself is
    /// also a point of the ladder (FLIP 0), so the ladder reaches the highest quality.
    /// Default 256; with --motion, where a reference is rendered per refresh, 16 (as the
    /// real clock's bench).
    #[arg(long)]
    pub reference_spp: Option<f32>,
    /// The reference's reflection depth R.
    #[arg(long, default_value_t = 16)]
    pub reference_depth: u32,
    /// Where to write the ladder (default ladder.json; with --motion, motion.json).
    #[arg(short = 'o', long = "out", alias = "output")]
    pub out: Option<PathBuf>,
    /// Measure the quality model of the `perceptual` controller instead of a ladder: short
    /// stimuli over a grid of screen speeds, frame times and points of --ladder, scored by
    /// displayed FLIP (and by JOD with --jod); written as motion.json.
    #[arg(long)]
    pub motion: bool,
    /// With --motion: the calibrated ladder whose points are scored.
    #[arg(long, requires = "motion", value_name = "FILE")]
    pub ladder: Option<PathBuf>,
    /// With --motion: measure nothing, but write the mean of these motion.json files (models
    /// of the same ladder and grids, e.g. on several scenes; comma separated) to --out: how
    /// the model shipped with `perceptual` is made (docs/default-motion-model.md).
    #[arg(long, requires = "motion", value_delimiter = ',', value_name = "FILES")]
    pub merge: Vec<PathBuf>,
    /// With --motion: how many of the ladder's points to score, spread evenly by cost
    /// (0: all).
    #[arg(long, requires = "motion", default_value_t = 5)]
    pub points: usize,
    /// With --motion: screen speeds, degrees of visual angle per second, comma separated.
    #[arg(
        long,
        requires = "motion",
        value_delimiter = ',',
        default_value = "0,8,32,96"
    )]
    pub speeds: Vec<f64>,
    /// With --motion: frame times, in refreshes of the display, comma separated.
    #[arg(
        long,
        requires = "motion",
        value_delimiter = ',',
        default_value = "1,2,3"
    )]
    pub refreshes: Vec<u32>,
    /// With --motion: the display's refresh rate, Hz.
    #[arg(long, requires = "motion", default_value_t = 60.0)]
    pub refresh: f64,
    /// With --motion: each stimulus's length, seconds.
    #[arg(long, requires = "motion", default_value_t = 0.5)]
    pub stimulus: f64,
    /// With --motion: show the stimuli as `bench --temporal on --warp` does (frames
    /// accumulated into a temporal history, each refresh between two frames the last frame
    /// warped to its time), so the table scores long frames with their age warped away;
    /// score the points of a ladder from `calibrate --temporal`.
    #[arg(long, requires = "motion")]
    pub warp: bool,
    /// With --motion: write each stimulus's screen and reference videos into DIR (one
    /// folder per view and speed, in the layout of `bench --video`).
    #[arg(long, requires = "motion", value_name = "DIR")]
    pub video: Option<PathBuf>,
    /// With --video: score the videos with the JOD tool (ColorVideoVDP, scripts/jod/jod.py)
    /// and fill the table with JOD; the displayed-FLIP table is written beside it
    /// (`<out>-flip.json`). A folder already scored (its jod.json) is not scored again.
    #[arg(long, requires = "video")]
    pub jod: bool,
    /// With --jod: the Python that runs the JOD tool (with scripts/jod/requirements.txt).
    #[arg(long, requires = "jod", default_value = "python3")]
    pub python: String,
    /// With --jod: the JOD tool.
    #[arg(long, requires = "jod", default_value = "scripts/jod/jod.py")]
    pub jod_script: PathBuf,
    /// With --jod: keep every video once scored (else only video.json and jod.json stay).
    #[arg(long, requires = "jod")]
    pub keep_video: bool,
    /// Calibrate for the temporal mode (docs/temporal.md): each setting renders FRAMES frames
    /// leading up to each view (1/--rate s apart on the path) into a history and is measured
    /// on it, so the ladder ranks the settings by what they look like with history.
    #[arg(long, value_name = "FRAMES", conflicts_with = "motion")]
    pub temporal: Option<u32>,
    /// With --temporal: frames per second of the frames leading up to each view.
    #[arg(long, default_value_t = 60.0, requires = "temporal")]
    pub rate: f64,
}

impl From<&CalibrateArgs> for CalibrateConfig {
    fn from(args: &CalibrateArgs) -> Self {
        Self {
            scene: (&args.scene).into(),
            views: args.views,
            frames: args.frames,
            width: args.width,
            height: args.height,
            spp: args.spp.clone(),
            depths: args.depths.clone(),
            scales: args.scales.clone(),
            reference_spp: args.reference_spp,
            reference_depth: args.reference_depth,
            out: args.out.clone(),
            motion: args.motion,
            ladder: args.ladder.clone(),
            merge: args.merge.clone(),
            points: args.points,
            speeds: args.speeds.clone(),
            refreshes: args.refreshes.clone(),
            refresh: args.refresh,
            stimulus: args.stimulus,
            warp: args.warp,
            video: args.video.clone(),
            jod: args.jod,
            python: args.python.clone(),
            jod_script: args.jod_script.clone(),
            keep_video: args.keep_video,
            temporal: args.temporal,
            rate: args.rate,
        }
    }
}

/// `steadyray raybench`: the BVH throughput measurement's command line.
#[derive(Debug, Args)]
pub struct RaybenchArgs {
    /// The mesh file (.obj).
    #[arg(long)]
    pub mesh: PathBuf,
    /// `auto` (the mesh's bounding box, seen from +z) or JSON
    /// `{"eye":[x,y,z],"target":[x,y,z],"up":[x,y,z],"vfov":degrees}`.
    #[arg(long, default_value = "auto")]
    pub camera: String,
    /// Image width in pixels (one primary ray per pixel).
    #[arg(long, default_value_t = 1920)]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 1080)]
    pub height: u32,
    /// Where to trace (`auto`: a hardware GPU where there is one, else the CPU).
    #[arg(long, value_enum, default_value_t = RaybenchBackend::Auto)]
    pub backend: RaybenchBackend,
    /// Timed repetitions of each ray set; the median is reported.
    #[arg(long, default_value_t = 5)]
    pub reps: u32,
    /// Worker threads on the CPU, for the BVH build and CPU tracing (0: one per available
    /// CPU), each taking the next chunk of 1024 rays until none is left.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Seed of the bounce directions.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Split every triangle into four at its edge midpoints this many times before building:
    /// the same surface from 4^N times the triangles, for measuring how cost grows with
    /// triangle count at a fixed view (at most 6).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=6))]
    pub subdivide: u32,
    /// Also write the triangles and the exact rays traced (both sets, with their t ranges
    /// and closest hits) to this file, in the binary format `scripts/embree/` reads.
    #[arg(long)]
    pub dump_rays: Option<PathBuf>,
}

impl From<&RaybenchArgs> for RaybenchConfig {
    fn from(args: &RaybenchArgs) -> Self {
        Self {
            mesh: args.mesh.clone(),
            camera: args.camera.clone(),
            width: args.width,
            height: args.height,
            backend: (&args.backend).into(),
            reps: args.reps,
            threads: args.threads,
            seed: args.seed,
            subdivide: args.subdivide,
            dump_rays: args.dump_rays.clone(),
        }
    }
}

/// `steadyray compare`: the image comparison's command line.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The reference image (any format the `image` crate reads; alpha is dropped).
    pub reference: PathBuf,
    /// The image to judge. A different size is brought to the reference's by a bilinear
    /// upscale (as a frame rendered at a reduced resolution scale is shown).
    pub test: PathBuf,
    /// Also write the FLIP error map (magma colours: black is no error) to this PNG.
    #[arg(long, value_name = "PNG")]
    pub error_map: Option<PathBuf>,
    /// Also write the test image (upscaled), the reference and the FLIP error map side by
    /// side, in that order, to this PNG.
    #[arg(long, value_name = "PNG")]
    pub side_by_side: Option<PathBuf>,
    /// FLIP's viewing condition: pixels of the reference per degree of visual angle as
    /// shown (the bench's displayed FLIP uses the standard FHD set-up's, 12.6 for a
    /// 640-pixel-wide frame filling the display).
    #[arg(long, value_name = "PIXELS", default_value_t = PIXELS_PER_DEGREE)]
    pub ppd: f32,
}

impl From<&CompareArgs> for CompareConfig {
    fn from(args: &CompareArgs) -> Self {
        Self {
            reference: args.reference.clone(),
            test: args.test.clone(),
            error_map: args.error_map.clone(),
            side_by_side: args.side_by_side.clone(),
            ppd: args.ppd,
        }
    }
}

/// `steadyray jod`: the JOD scores' command line.
#[derive(Debug, Args)]
pub struct JodArgs {
    #[command(subcommand)]
    pub command: JodCommand,
}

/// A `jod` subcommand.
#[derive(Debug, Subcommand)]
pub enum JodCommand {
    /// Add the scores of `jod.py` (its jod.json) to the bench's summary.json (each run's
    /// `jod`) and rewrite table.md beside it.
    Merge {
        /// The scores: DIR/jod.json of `scripts/jod/jod.py DIR`.
        #[arg(long)]
        scores: PathBuf,
        /// The summary.json of the `bench --clock real --video DIR` run that made DIR.
        #[arg(long)]
        summary: PathBuf,
    },
    /// Plot JOD against mean displayed frames per second, a point per method, for the runs
    /// of one or more merged summary.json files (PNG and SVG).
    Plot {
        /// Merged summary.json files.
        #[arg(required = true)]
        summaries: Vec<PathBuf>,
        /// The PNG to write (an SVG of the same name beside it).
        #[arg(short = 'o', long = "out", alias = "output")]
        output: PathBuf,
    },
    /// How well each figure of merged summary.json files ranks their methods as JOD does:
    /// Spearman's rank correlation over every scored method (1: the same order), and the
    /// pairs of methods the displayed FLIP orders against JOD.
    Agree {
        /// Merged summary.json files.
        #[arg(required = true)]
        summaries: Vec<PathBuf>,
    },
}

impl From<&JodArgs> for JodConfig {
    fn from(args: &JodArgs) -> Self {
        match &args.command {
            JodCommand::Merge { scores, summary } => JodConfig::Merge {
                scores: scores.clone(),
                summary: summary.clone(),
            },
            JodCommand::Plot { summaries, output } => JodConfig::Plot {
                summaries: summaries.clone(),
                output: output.clone(),
            },
            JodCommand::Agree { summaries } => JodConfig::Agree {
                summaries: summaries.clone(),
            },
        }
    }
}

/// Where `raybench` traces its rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum RaybenchBackend {
    /// A hardware GPU adapter where there is one (narrowed by `STEADYRAY_ADAPTER`), else
    /// the CPU.
    Auto,
    /// The 8-wide BVH on the CPU, rayon tasks over chunks of rays.
    Cpu,
    /// The 4-wide BVH in WGSL on a GPU adapter (software ones such as lavapipe included;
    /// `STEADYRAY_ADAPTER=name` picks one by name).
    Gpu,
}

impl From<&RaybenchBackend> for RaybenchBackendConfig {
    fn from(backend: &RaybenchBackend) -> Self {
        match backend {
            RaybenchBackend::Auto => RaybenchBackendConfig::Auto,
            RaybenchBackend::Cpu => RaybenchBackendConfig::Cpu,
            RaybenchBackend::Gpu => RaybenchBackendConfig::Gpu,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::{Cli, Command};
    use clap::Parser;

    #[test]
    fn bench_without_arguments_is_the_librarys_default_bench() {
        let cli = Cli::try_parse_from(["steadyray", "bench"]).unwrap();
        let Command::Bench(args) = cli.command else {
            panic!("not the bench");
        };
        assert_eq!(BenchConfig::from(&args), BenchConfig::default());
    }

    /// The bench's config of `steadyray bench` with `flags`.
    fn bench_config(flags: &[&str]) -> BenchConfig {
        let args = ["steadyray", "bench"].iter().chain(flags);
        let Command::Bench(args) = Cli::try_parse_from(args).unwrap().command else {
            panic!("not the bench");
        };
        BenchConfig::from(&args)
    }

    #[test]
    fn the_fixed_baselines_flags() {
        assert!(bench_config(&["--no-in-band-fixed"]).no_in_band_fixed);
        assert!(
            bench_config(&["--no-best-fixed"]).no_in_band_fixed,
            "the old name still works"
        );
        assert_eq!(
            bench_config(&["--no-best-looking-fixed"]).best_looking_fixed,
            BestLookingFixed::Skip
        );
        assert_eq!(
            bench_config(&["--only-best-looking-fixed"]).best_looking_fixed,
            BestLookingFixed::Only
        );
        for other in ["--controllers", "--no-best-looking-fixed"] {
            let args = [
                "steadyray",
                "bench",
                "--only-best-looking-fixed",
                other,
                "fixed",
            ];
            let args = if other == "--controllers" {
                &args[..]
            } else {
                &args[..4]
            };
            let err = Cli::try_parse_from(args).unwrap_err().to_string();
            assert!(err.contains("--only-best-looking-fixed"), "{other}: {err}");
        }
    }
}

#[cfg(test)]
mod display_preset_tests {
    use crate::cli::{Cli, Command};
    use clap::Parser;
    use steadyray_experiment::config::{ClockChoice, TemporalChoice};

    #[test]
    fn bench_display_on_the_cpu_is_the_cpus_recommendation() {
        let cli =
            Cli::try_parse_from(["steadyray", "bench", "--display", "--backend", "cpu"]).unwrap();
        let Command::Bench(args) = cli.command else {
            panic!("not the bench");
        };
        let config = args.config();
        assert_eq!(config.clock, ClockChoice::Real);
        assert_eq!(config.band.map(|b| b.multiple), Some(2));
        assert_eq!(config.temporal, TemporalChoice::On);
        assert!(config.warp);
    }

    #[test]
    fn bench_display_refuses_the_flags_it_sets_naming_both() {
        for flag in [
            &["--clock", "frames"][..],
            &["--band", "refresh"],
            &["--tmin", "10"],
            &["--temporal", "off"],
            &["--warp"],
        ] {
            let args = ["steadyray", "bench", "--display"].iter().chain(flag);
            let err = Cli::try_parse_from(args).unwrap_err().to_string();
            assert!(
                err.contains("--display") && err.contains(flag[0]),
                "{flag:?}: {err}"
            );
        }
    }
}
