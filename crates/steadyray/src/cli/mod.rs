//! The command line: subcommands and their arguments.

pub mod experiment;
pub mod suite;

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use steadyray_experiment::config as lib;

/// steadyray: a real-time ray tracer that holds its frame rate steady by trading image
/// quality, frame by frame.
#[derive(Debug, Parser)]
#[command(name = "steadyray", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Reproduce the paper's experiment: every controller over the camera sweep, reported
    /// as a table, frames.csv, summary.json and frame-time plots.
    Bench(experiment::BenchArgs),
    /// Render one still image to PNG (or EXR, by the file extension).
    Render(RenderArgs),
    /// List the built-in scenes.
    Scenes,
    /// List the GPU adapters wgpu can see.
    Adapters,
    /// List every controller with its options, their defaults and what each does (the
    /// table the option parser uses).
    Controllers,
    /// Compare two images (FLIP, PSNR, SSIM) and print them as one JSON line.
    Compare(experiment::CompareArgs),
    /// Measure (S, R, scale) settings' cost and FLIP over views of the camera path and write
    /// the Pareto front as a ladder for `predictive:ladder=FILE`.
    Calibrate(experiment::CalibrateArgs),
    /// Open an interactive window: the scene rendered continuously at the controller's
    /// quality, with a live frame-time HUD (or play back a recording with --playback).
    View(crate::view::ViewArgs),
    /// Ray-casting throughput of the triangle BVH on a mesh: primary and diffuse-bounce rays
    /// per second, as one JSON line.
    Raybench(experiment::RaybenchArgs),
    /// Bring ColorVideoVDP's JOD scores (scripts/jod/) into a real-clock bench's reports:
    /// `merge` into summary.json and table.md, `plot` JOD against displayed fps.
    Jod(experiment::JodArgs),
    /// The subjective comparison over the scene suite (docs/scene-suite.md): `run` its
    /// cells (resumable, shardable), then `table` them.
    Suite(suite::SuiteArgs),
}

/// Which renderer backend to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BackendChoice {
    /// A real GPU (discrete or integrated) if there is one, else the CPU renderer.
    Auto,
    /// The wgpu compute renderer on any adapter, software ones (lavapipe) included.
    Gpu,
    /// The CPU reference renderer.
    Cpu,
}

/// The bounds of the quality knobs a controller may move (S, R, resolution scale).
#[derive(Debug, Args)]
pub struct BoundsArgs {
    /// Smallest eye rays per pixel S.
    #[arg(long, default_value_t = 1.0)]
    pub spp_min: f32,
    /// Largest eye rays per pixel S.
    #[arg(long, default_value_t = 256.0)]
    pub spp_max: f32,
    /// Smallest reflection depth R.
    #[arg(long, default_value_t = 0)]
    pub depth_min: u32,
    /// Largest reflection depth R (controllers start here, at the smallest S and full
    /// resolution).
    #[arg(long, default_value_t = 16)]
    pub depth_max: u32,
    /// Smallest resolution scale.
    #[arg(long, default_value_t = 0.25)]
    pub scale_min: f32,
    /// Largest resolution scale.
    #[arg(long, default_value_t = 1.0)]
    pub scale_max: f32,
}

impl BoundsArgs {
    /// The checked bounds.
    pub fn bounds(&self) -> Result<steadyray_control::Bounds, steadyray_control::ConfigError> {
        steadyray_control::Bounds::new(
            (self.spp_min, self.spp_max),
            (self.depth_min, self.depth_max),
            (self.scale_min, self.scale_max),
        )
    }
}

/// The bounds as given, checked later by the bench (its plan refuses bad bounds before
/// anything renders).
impl From<&BoundsArgs> for steadyray_control::Bounds {
    fn from(args: &BoundsArgs) -> Self {
        Self {
            spp_min: args.spp_min,
            spp_max: args.spp_max,
            depth_min: args.depth_min,
            depth_max: args.depth_max,
            scale_min: args.scale_min,
            scale_max: args.scale_max,
        }
    }
}

/// Arguments shared by every command that renders a scene.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// A built-in scene name (see `steadyray scenes`) or a scene file (.toml).
    #[arg(long, default_value = steadyray_scene::DEFAULT_SCENE)]
    pub scene: String,
    /// Renderer backend.
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    pub backend: BackendChoice,
    /// Replaces the scene's camera path (keeping its frame count), from the scene camera's
    /// eye and pitch.
    #[arg(long, value_enum)]
    pub path: Option<PathChoice>,
}

/// A camera path that `--path` puts in place of the scene's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PathChoice {
    /// The paper's sweep: one full turn of the yaw at constant speed.
    Sweep,
    /// Holds, slow pans and fast turns (one full turn in 8 s): motion on screen from 0 to
    /// about 100 degrees of visual angle per second (docs/scene-format.md).
    Pans,
}

impl SceneArgs {
    /// Loads the scene and puts `--path` in place of its camera path.
    pub fn load(&self) -> Result<steadyray_scene::Scene, steadyray_scene::SceneError> {
        lib::SceneConfig::from(self).load()
    }
}

impl From<&SceneArgs> for lib::SceneConfig {
    fn from(args: &SceneArgs) -> Self {
        Self {
            scene: args.scene.clone(),
            backend: args.backend.into(),
            path: args.path.map(|path| match path {
                PathChoice::Sweep => lib::PathChoice::Sweep,
                PathChoice::Pans => lib::PathChoice::Pans,
            }),
        }
    }
}

impl From<BackendChoice> for lib::BackendChoice {
    fn from(choice: BackendChoice) -> Self {
        match choice {
            BackendChoice::Auto => lib::BackendChoice::Auto,
            BackendChoice::Gpu => lib::BackendChoice::Gpu,
            BackendChoice::Cpu => lib::BackendChoice::Cpu,
        }
    }
}

#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Image width in pixels.
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 360)]
    pub height: u32,
    /// Eye rays per pixel S (may be fractional: pixels then take floor(S) or floor(S)+1).
    #[arg(long, default_value_t = 4.0)]
    pub spp: f32,
    /// Largest number of reflection/refraction events R on a path.
    #[arg(long, default_value_t = 8)]
    pub depth: u32,
    /// Camera yaw in radians at the scene camera's eye (0 looks along -z).
    #[arg(long, conflicts_with_all = ["frame", "frames"])]
    pub yaw: Option<f32>,
    /// Frame k of the scene's camera path.
    #[arg(long)]
    pub frame: Option<u32>,
    /// Frames in the camera path (default: the path's own count).
    #[arg(long, requires = "frame")]
    pub frames: Option<u32>,
    /// Scene time in seconds: moving objects where they are then, and (without --yaw) the
    /// camera where the scene's path has it then. Default 0, or frame k's time with --frame.
    #[arg(long, value_name = "SECONDS", conflicts_with = "frame")]
    pub time: Option<f64>,
    /// Print one JSON line with the frame's time and ray counts.
    #[arg(long)]
    pub stats: bool,
    /// Frames rendered and discarded before the reported one, so that `--stats` times a
    /// warm renderer (thread pool started, buffers allocated, pipelines compiled; on the
    /// 2-core CPU one frame is not enough: the first three run up to 40 % slower).
    #[arg(long, default_value_t = 3)]
    pub warmup: u32,
    /// Output image: .png (tone-mapped sRGB) or .exr (linear radiance).
    #[arg(
        short = 'o',
        long = "out",
        alias = "output",
        default_value = "render.png"
    )]
    pub output: PathBuf,
    /// The temporal mode (docs/temporal.md): render a sequence of FRAMES frames ending at the
    /// asked view, 1/--rate s apart on the camera path (the same view for --yaw or the
    /// scene's camera), accumulate them into a --width x --height history and write it.
    #[arg(long, value_name = "FRAMES")]
    pub temporal: Option<u32>,
    /// With --temporal: the resolution scale each frame is rendered at (the history stays at
    /// --width x --height: temporal upsampling).
    #[arg(long, default_value_t = 1.0, requires = "temporal")]
    pub scale: f32,
    /// With --temporal: frames per second of the sequence.
    #[arg(long, default_value_t = 60.0, requires = "temporal")]
    pub rate: f64,
    /// With --temporal: also write the history after every frame into DIR
    /// (frame_0000.png, frame_0001.png, ...; the shown picture with --shown).
    #[arg(long, value_name = "DIR", requires = "temporal")]
    pub sequence: Option<PathBuf>,
    /// With --temporal: write the picture the display shows (as `view` and `bench` show it:
    /// the history sharpened for display where its frame resampled it, docs/temporal.md)
    /// instead of the history itself. It is 8-bit sRGB, so the output must be a .png.
    #[arg(long, requires = "temporal")]
    pub shown: bool,
    /// Render a reference: draw the samples reserved for references (other sub-pixel
    /// positions and random numbers than any frame's), so that a frame compared with this
    /// image is not scored closer to it for sharing its samples. It needs S of 2 or more
    /// (one sample would sit off the pixel centre).
    #[arg(long, conflicts_with = "temporal")]
    pub reference: bool,
}

/// How time runs (`docs/display.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ClockChoice {
    /// The paper's protocol: frame k of N shows the path at k/N of its length, whatever its
    /// time.
    Frames,
    /// Display time: the path is a function of time and each frame shows the world at its
    /// predicted display time, so a faster controller shows more frames of the same motion.
    Real,
}

/// Which runs use the temporal mode (`docs/temporal.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TemporalChoice {
    /// None.
    Off,
    /// Every run.
    On,
    /// Every controller runs twice: without, then with it.
    Both,
}

impl From<&TemporalChoice> for lib::TemporalChoice {
    fn from(choice: &TemporalChoice) -> Self {
        match choice {
            TemporalChoice::Off => lib::TemporalChoice::Off,
            TemporalChoice::On => lib::TemporalChoice::On,
            TemporalChoice::Both => lib::TemporalChoice::Both,
        }
    }
}

impl From<&ClockChoice> for lib::ClockChoice {
    fn from(choice: &ClockChoice) -> Self {
        match choice {
            ClockChoice::Frames => lib::ClockChoice::Frames,
            ClockChoice::Real => lib::ClockChoice::Real,
        }
    }
}

/// On or off.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Switch {
    On,
    Off,
}

/// The display model's settings (`--clock real`).
#[derive(Debug, Args)]
pub struct DisplayArgs {
    /// With --clock real: the display's refresh rate, Hz (default 60; with --vrr, the
    /// range's maximum). The screen is sampled at this rate for --video and displayed FLIP.
    #[arg(long, allow_negative_numbers = true)]
    pub refresh: Option<f64>,
    /// With --clock real: vsync `on` (a frame shows at the first refresh after it is
    /// complete; the default) or `off` (at once).
    #[arg(long, value_enum)]
    pub vsync: Option<Switch>,
    /// With --clock real: variable refresh within MIN-MAX Hz (e.g. 48-144) instead of a
    /// fixed refresh.
    #[arg(long, value_name = "MIN-MAX", conflicts_with = "vsync")]
    pub vrr: Option<steadyray_display::VrrRange>,
}

impl From<&DisplayArgs> for lib::DisplaySettings {
    fn from(args: &DisplayArgs) -> Self {
        Self {
            refresh: args.refresh,
            vsync: args.vsync.map(|switch| switch == Switch::On),
            vrr: args.vrr,
        }
    }
}
