//! The command line: subcommands and their arguments.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

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
    Bench(crate::bench::BenchArgs),
    /// Render one still image to PNG (or EXR, by the file extension).
    Render(RenderArgs),
    /// List the built-in scenes.
    Scenes,
    /// List the GPU adapters wgpu can see.
    Adapters,
    /// Compare two images (FLIP, PSNR, SSIM) and print them as one JSON line.
    Compare(crate::commands::compare::CompareArgs),
    /// Measure (S, R, scale) settings' cost and FLIP over views of the camera path and write
    /// the Pareto front as a ladder for `predictive:ladder=FILE`.
    Calibrate(crate::commands::calibrate::CalibrateArgs),
    /// Open an interactive window: the scene rendered continuously at the controller's
    /// quality, with a live frame-time HUD (or play back a recording with --playback).
    View(crate::view::ViewArgs),
    /// Ray-casting throughput of the triangle BVH on a mesh: primary and diffuse-bounce rays
    /// per second, as one JSON line.
    Raybench(crate::commands::raybench::RaybenchArgs),
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
    /// Holds, slow pans and fast turns (one full turn in 12 s): motion on screen from 0 to
    /// about 80 degrees of visual angle per second (docs/scene-format.md).
    Pans,
}

impl SceneArgs {
    /// Loads the scene and puts `--path` in place of its camera path.
    pub fn load(&self) -> Result<steadyray_scene::Scene, steadyray_scene::SceneError> {
        use steadyray_scene::CameraPath;
        let mut scene = steadyray_scene::load_scene(&self.scene)?;
        let frames = scene.path.frames();
        match self.path {
            Some(PathChoice::Sweep) => scene.path = CameraPath::Sweep { frames },
            Some(PathChoice::Pans) => scene.path = CameraPath::Pans { frames },
            None => {}
        }
        Ok(scene)
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
    #[arg(short = 'o', long = "output", default_value = "render.png")]
    pub output: PathBuf,
}
