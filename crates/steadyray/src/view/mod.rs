//! `steadyray view`: the interactive window. The scene renders continuously at the quality
//! the controller picks from each frame's render time; a HUD (egui) graphs the frame times
//! with the band shaded and retunes the controller live. `--playback DIR` shows a recorded
//! sequence at its real timing instead.
//!
//! Everything the window needs is checked before it opens (scene, controller, band, bounds,
//! recording), and every failure after (no display, no adapter that can present, a lost
//! surface or device) ends the view with a message and a non-zero exit, never a panic.

mod app;
mod camera;
mod capture;
mod display_band;
mod frames;
mod history;
mod hud;
mod input;
mod live_control;
mod path_clock;
mod playback;
mod present;
mod screen;

use crate::cli::{BoundsArgs, SceneArgs};
use anyhow::{Context, Result, bail};
use clap::Args;
use live_control::LiveControl;
use playback::Recording;
use screen::PresentChoice;
use std::path::PathBuf;
use steadyray_control::{Band, Quality};
use steadyray_experiment::recommended::Recommended;
use steadyray_scene::Scene;

#[derive(Debug, Args)]
pub struct ViewArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The controller at start (`fixed`, `step`, `hysteresis`, `predictive`, `perceptual`),
    /// optionally with options after a colon, e.g. `step:knob=both` or
    /// `perceptual:model=motion.json`. The HUD switches it live.
    #[arg(long, default_value = "predictive")]
    pub controller: String,
    /// Lower edge of a fixed frame-time band, ms (with --tmax; the other edge defaults to
    /// 15 or 20, the paper's band). Without either the band follows the display (--band).
    #[arg(long, conflicts_with = "band")]
    pub tmin: Option<f64>,
    /// Upper edge of a fixed frame-time band, ms.
    #[arg(long, conflicts_with = "band")]
    pub tmax: Option<f64>,
    /// The band from the display: render times whose frames, handed over to the window,
    /// make every refresh of its monitor (`refresh:M`: every M-th; 60 Hz where the monitor
    /// does not say), with the hand-over measured over the first frames; the paper's
    /// [15, 20] ms holds until then. Without it or --tmin/--tmax, the backend's recommended
    /// configuration (the CPU's decided on the scene suite, docs/results/scene-suite.md; the
    /// GPU's on the corridor, docs/results/viewer.md): on the
    /// CPU renderer `--band refresh:2 --temporal on --warp`, on a GPU `--band refresh
    /// --temporal off` (`bench --display` runs the same).
    #[arg(long, value_name = "refresh[:M]")]
    pub band: Option<steadyray_display::RefreshBand>,
    /// Window width in pixels (default 1280; in playback, the recording's frame size).
    #[arg(long)]
    pub width: Option<u32>,
    /// Window height in pixels (default 720; in playback, the recording's frame size).
    #[arg(long)]
    pub height: Option<u32>,
    /// Window pixels per rendered pixel at full resolution (default: 1 on a hardware GPU;
    /// a full-scale frame of about 640 pixels wide on the CPU and 160 on a software GPU).
    #[arg(long)]
    pub pixel_size: Option<u32>,
    /// How frames are presented.
    #[arg(long, value_enum, default_value_t = PresentChoice::Fifo)]
    pub present: PresentChoice,
    #[command(flatten)]
    pub bounds: BoundsArgs,
    /// Follow the scene's camera path instead of flying: `frames` shows one step of the path
    /// per frame (the paper's protocol), `real` the path at each frame's predicted display
    /// time (as `bench --clock real`).
    #[arg(long, value_enum)]
    pub clock: Option<crate::cli::ClockChoice>,
    /// Start with the automatic sweep on (Space toggles it). On a scene whose camera flies
    /// a keyed path (`flyby`), the sweep follows that path instead.
    #[arg(long)]
    pub sweep: bool,
    /// Seconds per full turn of the sweep.
    #[arg(long, default_value_t = 24.0)]
    pub sweep_seconds: f32,
    /// Camera speed of WASD/QE, scene units (metres) per second.
    #[arg(long, default_value_t = 2.0)]
    pub speed: f32,
    /// Start with the HUD hidden (F1 toggles it).
    #[arg(long)]
    pub no_hud: bool,
    /// The temporal mode at start (docs/temporal.md: frames accumulated into a
    /// full-resolution history; T toggles it). `auto` follows the backend's recommended
    /// configuration (docs/results/viewer.md): on with the CPU renderer, off on a GPU. A
    /// bare `--temporal` is `on`.
    #[arg(long, value_enum, default_value_t = ViewSwitch::Auto, num_args = 0..=1,
        default_missing_value = "on")]
    pub temporal: ViewSwitch,
    /// Show each refresh between two frames of `--band refresh:M` (M ≥ 2) as the last frame
    /// warped to the camera at that refresh (docs/temporal.md, "Warped refreshes"), as
    /// `bench --warp` does: M − 1 warps after each frame, their cost measured over the first
    /// ones and left free in the band. Needs the temporal mode (`on` turns it on); while T
    /// has it off, refreshes repeat the frame. `auto` follows the backend's recommended
    /// configuration (docs/results/viewer.md): on with the CPU renderer when the history is
    /// on and frames span two or more refreshes, off on a GPU. A bare `--warp` is `on`, and
    /// without --band it shows frames every two refreshes (`--band refresh:2`).
    #[arg(long, value_enum, default_value_t = ViewSwitch::Auto, num_args = 0..=1,
        default_missing_value = "on")]
    pub warp: ViewSwitch,
    /// Show this many frames, then exit (tests and CI drive the view this way).
    #[arg(long)]
    pub frames: Option<u32>,
    /// With --frames: write the last frame, HUD included, to this PNG.
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Play back a recording of `bench --record DIR` (timings.csv and frame_NNNNN.png) at
    /// its real timing instead of rendering.
    #[arg(long, value_name = "DIR")]
    pub playback: Option<PathBuf>,
}

/// What the window shows.
enum Content {
    Live(Box<LiveSetup>),
    Playback(Recording),
}

/// A live view's scene and controller, checked.
struct LiveSetup {
    scene: Scene,
    control: LiveControl,
}

/// Everything the window needs, checked before it opens.
struct Plan {
    content: Content,
    backend: crate::cli::BackendChoice,
    window: (u32, u32),
    pixel_size: Option<u32>,
    present: PresentChoice,
    band: Band,
    /// The display band, temporal mode and warps asked for, resolved per backend.
    display: DisplayChoice,
    clock: Option<crate::cli::ClockChoice>,
    sweep: bool,
    sweep_seconds: f32,
    speed: f32,
    hud: bool,
    frames: Option<u32>,
    screenshot: Option<PathBuf>,
}

/// A setting of the live view that follows the backend's recommended configuration
/// unless asked (`--temporal`, `--warp`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ViewSwitch {
    /// As recommended for the backend the view renders on (docs/results/viewer.md).
    Auto,
    On,
    Off,
}

/// The band a live view aligns to the display, if any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum BandChoice {
    /// None given: the backend's recommended multiple of the refresh interval.
    Recommended,
    /// `--band refresh[:M]`.
    Refresh(u32),
    /// A band of fixed --tmin/--tmax (or a playback, which runs no controller).
    Fixed,
}

/// The display settings asked for on the command line, resolved once the renderer's
/// backend is known ([`DisplayChoice::resolve`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct DisplayChoice {
    band: BandChoice,
    temporal: ViewSwitch,
    warp: ViewSwitch,
}

/// The display settings a live view starts with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct DisplaySetup {
    /// The multiple of the refresh interval the band is aligned to (None: a fixed band).
    aligned: Option<u32>,
    /// Whether the temporal mode starts on.
    temporal: bool,
    /// Warped refreshes after each frame (M − 1 at `refresh:M` with warps on).
    warps: u32,
}

impl DisplayChoice {
    /// The settings on a GPU (`gpu`) or the CPU renderer: what was asked, the rest as
    /// [`Recommended`] says for that backend. A `--warp` without --band shows frames every
    /// two refreshes, the least that leaves a refresh to warp.
    fn resolve(self, gpu: bool) -> DisplaySetup {
        let recommended = Recommended::for_backend(gpu);
        let aligned = match self.band {
            BandChoice::Recommended if self.warp == ViewSwitch::On => {
                Some(recommended.refreshes_per_frame.max(2))
            }
            BandChoice::Recommended => Some(recommended.refreshes_per_frame),
            BandChoice::Refresh(multiple) => Some(multiple),
            BandChoice::Fixed => None,
        };
        let temporal = match self.temporal {
            ViewSwitch::Auto => recommended.temporal || self.warp == ViewSwitch::On,
            ViewSwitch::On => true,
            ViewSwitch::Off => false,
        };
        let warp = match self.warp {
            ViewSwitch::Auto => recommended.warp && temporal,
            ViewSwitch::On => true,
            ViewSwitch::Off => false,
        };
        DisplaySetup {
            aligned,
            temporal,
            warps: if warp {
                aligned.unwrap_or(1).saturating_sub(1)
            } else {
                0
            },
        }
    }
}

/// The paper's band, ms: the window's band until the display's is measured, and the fixed
/// band's missing edge.
const PAPER_BAND_MS: (f64, f64) = (15.0, 20.0);

/// Default window size of the live view.
const DEFAULT_WINDOW: (u32, u32) = (1280, 720);

impl Plan {
    fn new(args: &ViewArgs) -> Result<Self> {
        let fixed_band = args.tmin.is_some() || args.tmax.is_some();
        let band = Band::new(
            args.tmin.unwrap_or(PAPER_BAND_MS.0),
            args.tmax.unwrap_or(PAPER_BAND_MS.1),
        )?;
        if args.band.is_some() && args.playback.is_some() {
            bail!("--band refresh sets a controller's band: it needs a live view, not --playback");
        }
        let display = display_choice(args, fixed_band)?;
        if args.frames == Some(0) {
            bail!("--frames must be at least 1");
        }
        if let Some(path) = &args.screenshot
            && path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase)
                .as_deref()
                != Some("png")
        {
            bail!(
                "--screenshot {}: the screenshot is a PNG; name it .png",
                path.display()
            );
        }
        if args.pixel_size == Some(0) {
            bail!("--pixel-size must be at least 1");
        }
        if !(args.sweep_seconds.is_finite() && args.sweep_seconds > 0.0) {
            bail!("--sweep-seconds must be a positive number of seconds");
        }
        if !(args.speed.is_finite() && args.speed >= 0.0) {
            bail!("--speed must be a number >= 0");
        }
        let (content, default_window) = match &args.playback {
            Some(dir) => {
                let recording = Recording::open(dir)?;
                let (w, h, _) = recording.load(0)?;
                (Content::Playback(recording), (w, h))
            }
            None => {
                let bounds = args.bounds.bounds()?;
                let start = Quality::new(bounds.spp_min, bounds.depth_max, bounds.scale_max);
                let (name, options) = args
                    .controller
                    .split_once(':')
                    .unwrap_or((&args.controller, ""));
                let control = LiveControl::new(name.trim(), options.trim(), band, bounds, start)
                    .with_context(|| format!("--controller {}", args.controller))?;
                let scene = args.scene.load()?;
                (
                    Content::Live(Box::new(LiveSetup { scene, control })),
                    DEFAULT_WINDOW,
                )
            }
        };
        let window = (
            args.width.unwrap_or(default_window.0),
            args.height.unwrap_or(default_window.1),
        );
        if window.0 == 0 || window.1 == 0 || window.0 > 16384 || window.1 > 16384 {
            bail!(
                "window size {}x{} is out of range (1 to 16384 a side)",
                window.0,
                window.1
            );
        }
        Ok(Self {
            content,
            backend: args.scene.backend,
            window,
            pixel_size: args.pixel_size,
            present: args.present,
            band,
            clock: args.clock,
            sweep: args.sweep,
            sweep_seconds: args.sweep_seconds,
            speed: args.speed,
            hud: !args.no_hud,
            display,
            frames: args.frames,
            screenshot: args.screenshot.clone(),
        })
    }
}

/// The display settings `args` ask for, checked: `--warp` needs a live view, the history
/// and frames two or more refreshes apart.
fn display_choice(args: &ViewArgs, fixed_band: bool) -> Result<DisplayChoice> {
    let band = match (args.band, fixed_band, &args.playback) {
        (Some(b), _, _) => BandChoice::Refresh(b.multiple),
        (None, false, None) => BandChoice::Recommended,
        _ => BandChoice::Fixed,
    };
    if args.warp == ViewSwitch::On {
        if args.playback.is_some() {
            bail!("--warp shows a live history again: it needs a live view, not --playback");
        }
        if matches!(band, BandChoice::Fixed | BandChoice::Refresh(1)) {
            bail!(
                "--warp fills the refreshes between frames of --band refresh:M with M >= 2 \
                 (e.g. --band refresh:2); at one refresh a frame, or a band of fixed \
                 --tmin/--tmax, no refresh is known to lack a new frame"
            );
        }
        if args.temporal == ViewSwitch::Off {
            bail!("--warp shows the temporal history again: it needs --temporal on or auto");
        }
    }
    Ok(DisplayChoice {
        band,
        temporal: args.temporal,
        warp: args.warp,
    })
}

/// Opens the window and runs until it is closed, `--frames` are shown, or something fails.
pub fn run(args: &ViewArgs) -> Result<()> {
    let plan = Plan::new(args)?;
    let event_loop = winit::event_loop::EventLoop::new().map_err(|e| {
        anyhow::anyhow!(
            "cannot open a window: {e} (is there a display? on a headless machine run under \
             Xvfb, e.g. `xvfb-run steadyray view ...`)"
        )
    })?;
    let instance = steadyray_render_gpu::display_instance(event_loop.owned_display_handle());
    let mut app = app::App::new(plan, instance);
    match run_guarded(|| event_loop.run_app(&mut app)) {
        Ok(result) => result.context("the window's event loop failed")?,
        Err(panic) => {
            // The window system's state is unknown after a panic inside it: leave the
            // window and GPU objects to the process exit rather than tear them down.
            std::mem::forget(app);
            bail!("the window system failed: {panic} (was the display closed?)");
        }
    }
    app.finish()
}

/// Runs `f`, turning a panic into its message: winit panics when the display connection
/// dies (e.g. the X server exits), which must end the view with a message, not a crash.
fn run_guarded<T>(f: impl FnOnce() -> T) -> std::result::Result<T, String> {
    let message = std::sync::Arc::new(std::sync::Mutex::new(None::<String>));
    let hook = std::panic::take_hook();
    let sink = message.clone();
    std::panic::set_hook(Box::new(move |info| {
        let text = format!("{info}");
        log::debug!("panic in the window system: {text}");
        if let Ok(mut m) = sink.lock() {
            m.get_or_insert(text);
        }
    }));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    std::panic::set_hook(hook);
    result.map_err(|_| {
        message
            .lock()
            .ok()
            .and_then(|mut m| m.take())
            .unwrap_or_else(|| "unknown panic".into())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    fn plan(args: &[&str]) -> Result<Plan> {
        let cli = crate::cli::Cli::try_parse_from(["steadyray", "view"].iter().chain(args))?;
        match &cli.command {
            crate::cli::Command::View(view) => Plan::new(view),
            other => panic!("parsed as {other:?}"),
        }
    }

    #[test]
    fn bad_arguments_fail_before_a_window_opens() {
        let cases: [(&[&str], &str); 13] = [
            (&["--tmin", "20", "--tmax", "10"], "Tmin"),
            (&["--tmin", "10", "--band", "refresh"], "--band"),
            (&["--controller", "fastest"], "fastest"),
            (&["--controller", "step:bogus=1"], "bogus"),
            (&["--frames", "0"], "--frames"),
            (&["--frames", "3", "--screenshot", "shot.jpg"], ".png"),
            (&["--scene", "nowhere"], "nowhere"),
            (&["--playback", "/nonexistent/recording"], "not a folder"),
            (&["--width", "0"], "window size"),
            (&["--warp", "--band", "refresh"], "refresh:M"),
            (&["--warp", "--tmax", "40"], "refresh:M"),
            (
                &["--warp", "--band", "refresh:2", "--temporal", "off"],
                "--temporal",
            ),
            (&["--warp", "--playback", "somewhere"], "--playback"),
        ];
        for (args, expected) in cases {
            let err = match plan(args) {
                Ok(_) => panic!("{args:?} was accepted"),
                Err(e) => format!("{e:#}"),
            };
            assert!(err.contains(expected), "{args:?}: {err}");
        }
    }

    #[test]
    fn a_panic_in_the_window_system_becomes_a_message() {
        assert_eq!(run_guarded(|| 7), Ok(7));
        let err = run_guarded(|| -> u32 { panic!("connection reset") }).unwrap_err();
        assert!(err.contains("connection reset"), "{err}");
    }

    fn setup(args: &[&str], gpu: bool) -> DisplaySetup {
        plan(args).unwrap().display.resolve(gpu)
    }

    #[test]
    fn the_defaults_are_each_backends_recommended_configuration() {
        let cpu = setup(&[], false);
        assert_eq!(
            cpu,
            DisplaySetup {
                aligned: Some(2),
                temporal: true,
                warps: 1
            },
            "--band refresh:2 --temporal on --warp"
        );
        let gpu = setup(&[], true);
        assert_eq!(
            gpu,
            DisplaySetup {
                aligned: Some(1),
                temporal: false,
                warps: 0
            },
            "--band refresh --temporal off"
        );
    }

    #[test]
    fn the_band_follows_the_display_unless_given() {
        assert_eq!(setup(&["--band", "refresh"], false).aligned, Some(1));
        assert_eq!(setup(&["--band", "refresh:2"], true).aligned, Some(2));
        let fixed = plan(&["--tmax", "30"]).unwrap();
        assert_eq!(fixed.display.resolve(false).aligned, None);
        assert_eq!((fixed.band.tmin_ms(), fixed.band.tmax_ms()), (15.0, 30.0));
    }

    #[test]
    fn the_temporal_mode_follows_the_backend_unless_asked() {
        let starts = |args: &[&str], gpu| setup(args, gpu).temporal;
        assert!(starts(&[], false) && !starts(&[], true));
        assert!(starts(&["--temporal"], true) && starts(&["--temporal", "on"], true));
        assert!(!starts(&["--temporal", "off"], false));
        assert_eq!(setup(&["--temporal", "off"], false).warps, 0);
        let err = format!("{:#}", plan(&["--temporal", "sometimes"]).err().unwrap());
        assert!(err.contains("sometimes"), "{err}");
    }

    #[test]
    fn warps_fill_the_refreshes_between_frames_with_the_history_on() {
        assert_eq!(setup(&["--band", "refresh"], false).warps, 0);
        assert_eq!(setup(&["--warp", "off"], false).warps, 0);
        let two = setup(&["--band", "refresh:2", "--warp"], true);
        assert_eq!(two.warps, 1);
        assert!(two.temporal, "--warp turns the history on");
        assert_eq!(setup(&["--warp"], true).aligned, Some(2));
        assert_eq!(setup(&["--band", "refresh:3", "--warp"], true).warps, 2);
        assert_eq!(setup(&["--band", "refresh:3"], false).warps, 2);
    }

    #[test]
    fn defaults_make_a_live_view() {
        let plan = plan(&["--controller", "step:knob=both"]).unwrap();
        assert_eq!(plan.window, DEFAULT_WINDOW);
        assert!(plan.hud && !plan.sweep && plan.frames.is_none());
        match plan.content {
            Content::Live(live) => {
                assert_eq!(live.control.name(), "step");
                assert_eq!(live.control.quality(), Quality::new(1.0, 16, 1.0));
                assert_eq!(live.scene.name, "corridor");
            }
            Content::Playback(_) => panic!("not a playback"),
        }
    }
}
