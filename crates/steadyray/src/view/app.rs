//! The window and its frame loop (winit's [`ApplicationHandler`]): input to the camera, a
//! frame at the controller's quality, its render time to the controller, the HUD, and the
//! composited frame to the screen.

use super::camera::{FlyCamera, Sweep};
use super::capture::Screenshot;
use super::display_band::{DisplayBand, FALLBACK_REFRESH_HZ};
use super::frames::{LiveRenderer, Upload};
use super::history::{FrameHistory, Sample, Spread};
use super::hud::{self, HudChange, HudEdit, HudFacts};
use super::input::{Command, InputState};
use super::live_control::{LiveControl, MeasuredCosts};
use super::path_clock::PathClock;
use super::playback::Recording;
use super::screen::{Drawn, Screen, UiFrame};
use super::{Content, LiveSetup, Plan};
use crate::cli::BackendChoice;
use anyhow::{Context, Result, anyhow};
use glam::Vec3;
use serde::Serialize;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use steadyray_control::{Band, FrameReport};
use steadyray_display::ViewingSetup;
use steadyray_experiment::backend::ADAPTER_ENV;
use steadyray_experiment::frame_loop::FrameLoop;
use steadyray_motion::{MotionProbe, MotionTracker, Shot};
use steadyray_render::TemporalSettings;
use steadyray_render_cpu::CpuRenderer;
use steadyray_render_gpu::{GpuOptions, GpuRenderer, surface_adapter};
use steadyray_scene::{Camera, CameraPath, PathMotion};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

/// The winit application: the plan until the window opens, then the running view.
pub struct App {
    plan: Option<Plan>,
    instance: wgpu::Instance,
    running: Option<Running>,
    error: Option<anyhow::Error>,
    summary: Option<Summary>,
}

impl App {
    pub fn new(plan: Plan, instance: wgpu::Instance) -> Self {
        Self {
            plan: Some(plan),
            instance,
            running: None,
            error: None,
            summary: None,
        }
    }

    /// After the event loop: the error that ended the view, or its summary printed as one
    /// JSON line on stdout.
    pub fn finish(mut self) -> Result<()> {
        if let Some(running) = self.running.take() {
            self.summary = Some(running.summary());
        }
        if let Some(error) = self.error {
            return Err(error);
        }
        let summary = self
            .summary
            .ok_or_else(|| anyhow!("the window never opened (the event loop ended first)"))?;
        println!("{}", serde_json::to_string(&summary)?);
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error.get_or_insert(error);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        let Some(plan) = self.plan.take() else {
            return;
        };
        event_loop.set_control_flow(ControlFlow::Poll);
        match Running::start(event_loop, &self.instance, plan) {
            Ok(running) => self.running = Some(running),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(running) = self.running.as_mut() else {
            return;
        };
        match running.window_event(&event) {
            Ok(Flow::Continue) => {}
            Ok(Flow::Exit) => event_loop.exit(),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(running) = &self.running {
            running.window.request_redraw();
        }
    }
}

/// Whether the view goes on after an event.
enum Flow {
    Continue,
    Exit,
}

/// The live view's moving parts.
struct Live {
    renderer: LiveRenderer,
    /// Renders the frames at the window's size and says which time the controller sees.
    frame_loop: FrameLoop,
    control: LiveControl,
    camera: FlyCamera,
    sweep: Sweep,
    speed: f32,
    pixel_size: u32,
    /// Scene time, s: where moving objects are. It runs with the window's clock (stopped
    /// while paused) and starts over after the scene path's duration.
    scene_time_s: f64,
    /// The scene path's duration, s.
    scene_duration_s: f64,
    /// Measures each frame's motion on screen (since the last frame, in window time) for
    /// the controller and the HUD.
    motion: MotionTracker,
    /// A keyed camera path and the scene camera it starts from: while the sweep is on, the
    /// camera follows it at the scene time instead of turning.
    keyed_path: Option<(CameraPath, Camera)>,
    /// The scene's path, when the camera follows it (`--clock`).
    path_clock: Option<PathClock>,
    /// Whether frames accumulate into a history (`docs/temporal.md`), and the size the
    /// renderer's history has (None: off).
    temporal: bool,
    history: Option<(u32, u32)>,
    /// Refreshes shown warped after each frame in the temporal mode (`--warp`: M − 1 for
    /// `--band refresh:M`), and how many of the last frame's are still to show.
    warps: u32,
    warps_due: u32,
    /// Whether the refreshes between frames show warps (V; off, they repeat the frame).
    warps_on: bool,
    /// Whether the history holds a frame a refresh could show warped.
    warpable: bool,
    /// The monitor's refresh interval, ms (60 Hz where it does not say).
    refresh_ms: f64,
    /// The last frame's motion on screen, °/s (the HUD shows it through the warps too).
    speed_deg_s: Option<f64>,
}

impl Live {
    /// Gives the renderer the history the temporal mode asks for: `full` pixels (a resize
    /// starts a new one), or none. A new history or none leaves nothing to warp.
    fn sync_history(&mut self, full: (u32, u32)) -> Result<()> {
        let want = self.temporal.then_some(full);
        if want != self.history {
            let settings = want.map(|(width, height)| TemporalSettings { width, height });
            self.renderer.set_temporal(settings)?;
            self.history = want;
            self.warps_due = 0;
            self.warpable = false;
        }
        Ok(())
    }

    /// Times a warp of the last frame to `camera` that no refresh shows, for a band that
    /// waits for the warps' cost while no warps are shown (`perceptual` holding one refresh a
    /// frame, or V turned them off): None when there is no frame to warp, or the window
    /// shows warps.
    fn time_unshown_warp(
        &mut self,
        camera: &Camera,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Option<f64>> {
        if self.warps == 0 || !self.warpable || self.warps_after_frame() > 0 {
            return Ok(None);
        }
        let warping = Instant::now();
        self.renderer.warped(camera, device, queue)?;
        Ok(Some(warping.elapsed().as_secs_f64() * 1e3))
    }

    /// The refreshes to show warped after a frame: none without `--warp` or a history;
    /// those between frames of the controller's chosen frame time (`perceptual`), else of
    /// the band's.
    fn warps_after_frame(&self) -> u32 {
        if self.warps == 0 || !self.warps_on || self.history.is_none() {
            return 0;
        }
        match self.control.target_frame_ms() {
            Some(ms) => ((ms / self.refresh_ms).round() as u32).saturating_sub(1),
            None => self.warps,
        }
    }

    /// Renders a frame of `full` pixels at the controller's quality, seen by the camera at
    /// scene time and window time `(camera, scene_time_s, t_s)`, and tells the controller
    /// its render time (`timing`: where it comes from, changed to the wall clock when GPU
    /// timestamps prove implausible) and motion on screen.
    fn render_frame(
        &mut self,
        (camera, scene_time_s, t_s): (Camera, f64, f64),
        full: (u32, u32),
        device: &wgpu::Device,
        timing: &mut String,
    ) -> Result<Sample> {
        let q = self.control.quality();
        self.frame_loop.set_full_size(full);
        // The previous frame's present work first: the render call's wall time is then its
        // own, a check on the GPU timestamps.
        if let Err(e) = device.poll(wgpu::PollType::wait_indefinitely()) {
            return Err(anyhow!("waiting for the GPU failed: {e}"));
        }
        let budget = self.control.frame_budget();
        let frame = self.frame_loop.render_within(
            self.renderer.renderer(),
            &camera,
            scene_time_s,
            q,
            budget,
        )?;
        self.warpable = self.history.is_some();
        if frame.time.switched {
            log::warn!(
                "GPU timestamps say {:.2} ms but the render call took {:.2} ms: the controller \
                 uses the wall clock from now on",
                frame.stats.render_ms,
                frame.stats.wall_ms
            );
            *timing = "GPU wall clock".into();
        }
        let render_ms = frame.report.tp_ms;
        // The motion on screen since the last frame (outside the render's time).
        let motion = self.motion.next(Shot {
            camera,
            time_s: t_s,
            world_s: self.scene_time_s,
        })?;
        self.speed_deg_s = Some(motion.mean_deg_s);
        let report = FrameReport {
            speed_deg_s: motion.mean_deg_s,
            ..frame.report
        };
        if let Err(e) = self.control.observe(&report) {
            log::warn!("the controller refused a frame report: {e}");
        }
        Ok(Sample {
            t_s,
            render_ms,
            present_ms: None,
            quality: q,
            rays: frame.stats.rays.total(),
        })
    }

    /// Moves the camera and the scene `dt_s` on (input, sweep or keyed path; none while
    /// `paused`) and returns the camera and scene time to show.
    fn advance(
        &mut self,
        dt_s: f32,
        look: (f32, f32),
        movement: Vec3,
        paused: bool,
    ) -> (Camera, f64) {
        if !paused {
            self.camera.look(look);
            self.camera.translate(movement, self.speed * dt_s);
            self.scene_time_s =
                (self.scene_time_s + f64::from(dt_s)).rem_euclid(self.scene_duration_s);
            match &self.keyed_path {
                Some((path, base)) if self.sweep.on => {
                    let camera = path.camera_at_time(base, self.scene_time_s);
                    self.camera = FlyCamera::from_camera(&camera);
                }
                _ => self.sweep.advance(&mut self.camera, dt_s),
            }
        }
        match &mut self.path_clock {
            Some(clock) => clock.next(f64::from(dt_s), paused),
            None => (self.camera.camera(), self.scene_time_s),
        }
    }
}

/// Playback's moving parts.
struct Playback {
    recording: Recording,
    upload: Upload,
    /// Recording time shown, ms (stops while paused).
    elapsed_ms: f64,
    shown: Option<usize>,
    /// When the shown frame first appeared.
    shown_at: Option<Instant>,
}

impl Playback {
    /// Plays the recording again from its first frame.
    fn restart(&mut self) {
        self.elapsed_ms = 0.0;
        self.shown = None;
        self.shown_at = None;
    }
}

enum Mode {
    Live(Box<Live>),
    Playback(Box<Playback>),
}

/// What the view reports when it ends (one JSON line on stdout).
#[derive(Debug, Serialize)]
pub struct Summary {
    mode: &'static str,
    device: String,
    timing: String,
    present_mode: String,
    window: [u32; 2],
    frames: usize,
    band_ms: [f64; 2],
    controller: Option<&'static str>,
    /// Render time over the whole run, ms.
    render_ms: Option<Spread>,
    /// Presentation interval between frames over the whole run, ms.
    present_ms: Option<Spread>,
    /// Refreshes shown warped (`--warp`), and their cost, ms.
    warped_refreshes: usize,
    warp_ms: Option<Spread>,
    in_band_pct: Option<f64>,
    last_frame: [u32; 2],
    /// The HUD's area in window pixels (x0, y0, x1, y1) on the last frame, if shown.
    hud_rect: Option<[f32; 4]>,
    screenshot: Option<PathBuf>,
}

/// The open window and everything drawn in it.
struct Running {
    window: Arc<Window>,
    screen: Screen,
    device: wgpu::Device,
    queue: wgpu::Queue,
    egui: egui::Context,
    egui_input: egui_winit::State,
    mode: Mode,
    device_label: String,
    timing: String,
    band: Band,
    history: FrameHistory,
    hud_visible: bool,
    hud_edit: HudEdit,
    hud_rect: Option<[f32; 4]>,
    message: Option<String>,
    input: InputState,
    paused: bool,
    started: Instant,
    last_frame: Instant,
    last_present: Option<Instant>,
    last_size: (u32, u32),
    /// Every frame's render time and presentation interval, for the summary.
    all_render_ms: Vec<f64>,
    all_present_ms: Vec<f64>,
    /// Every warped refresh's cost, ms.
    all_warp_ms: Vec<f64>,
    frames_limit: Option<u32>,
    screenshot: Option<PathBuf>,
    /// F12 was pressed: capture the next frame.
    shot_requested: bool,
    /// The `--frames` run is complete.
    finished: bool,
    /// `--band refresh[:M]`: the display's band and its measured costs.
    display_band: Option<DisplayBand>,
    /// Whether the band set from them was for frames followed by warps (None: none set yet).
    band_for_warps: Option<bool>,
    /// The last live frame's hand-over to the window, ms.
    hand_over_ms: Option<f64>,
}

/// Full-scale frame size for a window: one rendered pixel per `pixel_size` window pixels.
fn full_size((width, height): (u32, u32), pixel_size: u32) -> (u32, u32) {
    (
        width.div_ceil(pixel_size).max(1),
        height.div_ceil(pixel_size).max(1),
    )
}

/// The default pixel size: hardware GPUs render at window resolution; the CPU renderer at
/// about 640 pixels wide and software GPUs (lavapipe) at about 160.
fn default_pixel_size(window_width: u32, gpu: bool, software: bool) -> u32 {
    let target = match (gpu, software) {
        (true, false) => window_width,
        (true, true) => 160,
        (false, _) => 640,
    };
    window_width.div_ceil(target.max(1)).max(1)
}

/// What the window shows, opened: the mode, the adapter and device it runs on, the device's
/// label and where the frame times come from (for the HUD).
struct Opened {
    mode: Mode,
    adapter: wgpu::Adapter,
    device: wgpu::Device,
    queue: wgpu::Queue,
    device_label: String,
    timing: String,
    /// The multiple of the refresh interval the band is aligned to (None: a fixed band).
    aligned: Option<u32>,
}

/// The settings of the plan a live view starts with.
#[derive(Clone, Copy)]
struct LiveOptions {
    backend: BackendChoice,
    sweep: bool,
    sweep_seconds: f32,
    speed: f32,
    clock: Option<crate::cli::ClockChoice>,
    pixel_size: Option<u32>,
    display: super::DisplayChoice,
}

impl LiveOptions {
    fn of(plan: &Plan) -> Self {
        Self {
            backend: plan.backend,
            sweep: plan.sweep,
            sweep_seconds: plan.sweep_seconds,
            speed: plan.speed,
            clock: plan.clock,
            pixel_size: plan.pixel_size,
            display: plan.display,
        }
    }
}

/// Opens the live view of `setup` in a window of `size` on a monitor of `refresh_hz` (when
/// it says): its renderer on the window's surface, the scene loaded.
fn open_live_mode(
    instance: &wgpu::Instance,
    surface: &wgpu::Surface<'_>,
    setup: LiveSetup,
    options: LiveOptions,
    (size, refresh_hz): ((u32, u32), Option<f64>),
) -> Result<Opened> {
    let LiveSetup { scene, control } = setup;
    let (mut renderer, adapter, device, queue) = open_live(instance, surface, options.backend)?;
    let display = options
        .display
        .resolve(matches!(renderer, LiveRenderer::Gpu(_)));
    renderer.load_scene(&scene)?;
    let device_label = renderer.describe();
    let (gpu, software, timing) = match &renderer {
        LiveRenderer::Gpu(r) => (
            true,
            r.adapter().is_software,
            if r.has_timestamps() {
                "GPU timestamps"
            } else {
                "GPU wall clock"
            },
        ),
        LiveRenderer::Cpu { .. } => (false, false, "CPU wall clock"),
    };
    eprintln!("steadyray view: {device_label}");
    let motion = MotionProbe::new(
        &scene,
        (size.0.max(1), size.1.max(1)),
        ViewingSetup::standard_fhd(),
    )?;
    let live = Live {
        renderer,
        frame_loop: FrameLoop::new(size),
        control,
        motion: MotionTracker::new(motion),
        camera: FlyCamera::from_camera(&scene.camera),
        sweep: Sweep {
            on: options.sweep,
            period_s: options.sweep_seconds,
        },
        speed: options.speed,
        scene_time_s: 0.0,
        scene_duration_s: scene.path.duration_s(),
        keyed_path: matches!(scene.path.motion, PathMotion::Keys(_))
            .then(|| (scene.path.clone(), scene.camera)),
        path_clock: options
            .clock
            .map(|choice| PathClock::new(choice, scene.path.clone(), scene.camera)),
        pixel_size: options
            .pixel_size
            .unwrap_or_else(|| default_pixel_size(size.0, gpu, software)),
        temporal: display.temporal,
        history: None,
        warps: display.warps,
        warps_due: 0,
        warps_on: true,
        warpable: false,
        refresh_ms: 1000.0 / refresh_hz.unwrap_or(FALLBACK_REFRESH_HZ),
        speed_deg_s: None,
    };
    Ok(Opened {
        mode: Mode::Live(Box::new(live)),
        adapter,
        device,
        queue,
        device_label,
        timing: timing.to_string(),
        aligned: display.aligned,
    })
}

/// Opens the playback of `recording` on an adapter that can show the window's surface.
fn open_playback_mode(
    instance: &wgpu::Instance,
    surface: &wgpu::Surface<'_>,
    recording: Recording,
) -> Result<Opened> {
    let options = GpuOptions {
        adapter_name: std::env::var(ADAPTER_ENV).ok().filter(|s| !s.is_empty()),
        allow_software: true,
    };
    let adapter = surface_adapter(instance, surface, &options)
        .context("no GPU adapter can show frames in this window")?;
    let (device, queue) = display_device(&adapter)?;
    let label = format!("playback on {}", adapter.get_info().name);
    let playback = Playback {
        recording,
        upload: Upload::new(&device),
        elapsed_ms: 0.0,
        shown: None,
        shown_at: None,
    };
    Ok(Opened {
        mode: Mode::Playback(Box::new(playback)),
        adapter,
        device,
        queue,
        device_label: label,
        timing: "recorded Tp".to_string(),
        aligned: None,
    })
}

impl Playback {
    /// Moves the playback `dt_s` on and uploads the recorded frame due then, if it is not on
    /// screen yet: its index, and its sample when it is new (at window time `t_s`, shown
    /// `now`).
    fn advance(
        &mut self,
        dt_s: f32,
        (now, t_s): (Instant, f64),
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<(usize, Option<Sample>)> {
        self.elapsed_ms += f64::from(dt_s) * 1e3;
        let i = self.recording.frame_at(self.elapsed_ms);
        if self.shown == Some(i) {
            return Ok((i, None));
        }
        let (width, height, rgba) = self.recording.load(i)?;
        self.upload.write(device, queue, width, height, &rgba);
        self.shown = Some(i);
        // Shown on screen this long after the previous recorded frame.
        let interval = self
            .shown_at
            .replace(now)
            .map(|s| now.duration_since(s).as_secs_f64() * 1e3);
        let sample = Sample {
            t_s,
            render_ms: self.recording.frame(i).tp_ms,
            present_ms: interval,
            quality: steadyray_control::Quality::new(1.0, 0, 1.0),
            rays: 0,
        };
        Ok((i, Some(sample)))
    }
}

/// Opens a device on `adapter` for the window alone (CPU rendering and playback).
fn display_device(adapter: &wgpu::Adapter) -> Result<(wgpu::Device, wgpu::Queue)> {
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("steadyray view"),
        ..Default::default()
    }))
    .context("cannot open a device to show frames on")?;
    device.on_uncaptured_error(Arc::new(|error: wgpu::Error| {
        log::error!("GPU error outside any check: {error}");
    }));
    Ok((device, queue))
}

/// The live renderer `choice` asks for, with an adapter and device that can present to
/// `surface`; says on stderr which one it picked.
fn open_live(
    instance: &wgpu::Instance,
    surface: &wgpu::Surface<'_>,
    choice: BackendChoice,
) -> Result<(LiveRenderer, wgpu::Adapter, wgpu::Device, wgpu::Queue)> {
    let adapter_name = std::env::var(ADAPTER_ENV).ok().filter(|s| !s.is_empty());
    let gpu = |allow_software: bool| -> Result<_> {
        let options = GpuOptions {
            adapter_name: adapter_name.clone(),
            allow_software,
        };
        let adapter = surface_adapter(instance, surface, &options)?;
        let renderer = GpuRenderer::with_adapter(&adapter)?;
        let (device, queue) = (renderer.device().clone(), renderer.queue().clone());
        Ok((
            LiveRenderer::Gpu(Box::new(renderer)),
            adapter,
            device,
            queue,
        ))
    };
    let cpu = || -> Result<_> {
        let options = GpuOptions {
            adapter_name: adapter_name.clone(),
            allow_software: true,
        };
        let adapter = surface_adapter(instance, surface, &options)
            .context("no GPU adapter (software ones included) can show frames in this window")?;
        let (device, queue) = display_device(&adapter)?;
        let renderer = LiveRenderer::Cpu {
            renderer: Box::new(CpuRenderer::new()),
            upload: Upload::new(&device),
        };
        Ok((renderer, adapter, device, queue))
    };
    match choice {
        BackendChoice::Gpu => gpu(true).context("the gpu backend cannot render in this window"),
        BackendChoice::Cpu => cpu(),
        BackendChoice::Auto => gpu(false).or_else(|e| {
            eprintln!("steadyray view: backend cpu (auto: no hardware GPU for this window: {e:#})");
            cpu()
        }),
    }
}

impl Running {
    /// Opens the window and its surface, the renderer (or recording) and the HUD.
    fn start(event_loop: &ActiveEventLoop, instance: &wgpu::Instance, plan: Plan) -> Result<Self> {
        let title = match &plan.content {
            Content::Live(live) => format!("steadyray view: {}", live.scene.name),
            Content::Playback(_) => "steadyray view: playback".to_string(),
        };
        let attributes = Window::default_attributes()
            .with_title(title)
            .with_inner_size(PhysicalSize::new(plan.window.0, plan.window.1));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("cannot create the window")?,
        );
        let surface = instance
            .create_surface(window.clone())
            .context("cannot create a GPU surface for the window")?;
        let size = window.inner_size();
        let size = (size.width, size.height);
        let refresh_hz = window
            .current_monitor()
            .and_then(|m| m.refresh_rate_millihertz())
            .map(|mhz| f64::from(mhz) / 1000.0)
            .filter(|hz| hz.is_finite() && *hz > 0.0);

        let options = LiveOptions::of(&plan);
        let Opened {
            mode,
            adapter,
            device,
            queue,
            device_label,
            timing,
            aligned,
        } = match plan.content {
            Content::Live(setup) => {
                open_live_mode(instance, &surface, *setup, options, (size, refresh_hz))?
            }
            Content::Playback(recording) => open_playback_mode(instance, &surface, recording)?,
        };
        let screen = Screen::new(
            surface,
            &adapter,
            device.clone(),
            queue.clone(),
            size,
            plan.present,
        )?;
        let egui = egui::Context::default();
        let egui_input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(device.limits().max_texture_dimension_2d as usize),
        );
        let (controller, bounds) = match &mode {
            Mode::Live(live) => (live.control.name(), live.control.bounds()),
            Mode::Playback(_) => ("fixed", steadyray_control::Bounds::default()),
        };
        let warped = matches!(&mode, Mode::Live(live) if live.warps > 0);
        let display_band = match aligned {
            Some(multiple) => Some(DisplayBand::new(multiple, refresh_hz, warped)?),
            None => None,
        };
        let now = Instant::now();
        Ok(Self {
            hud_edit: HudEdit {
                controller,
                tmin_ms: plan.band.tmin_ms(),
                tmax_ms: plan.band.tmax_ms(),
                bounds,
                sweep: plan.sweep,
                temporal: match &mode {
                    Mode::Live(live) => live.temporal,
                    Mode::Playback(_) => false,
                },
                warps: match &mode {
                    Mode::Live(live) => (live.warps > 0).then_some(live.warps_on),
                    Mode::Playback(_) => None,
                },
                paused: false,
            },
            window,
            screen,
            device,
            queue,
            egui,
            egui_input,
            mode,
            device_label,
            timing,
            band: plan.band,
            history: FrameHistory::default(),
            hud_visible: plan.hud,
            hud_rect: None,
            message: None,
            input: InputState::default(),
            paused: false,
            started: now,
            last_frame: now,
            last_present: None,
            last_size: (0, 0),
            all_render_ms: Vec::new(),
            all_present_ms: Vec::new(),
            all_warp_ms: Vec::new(),
            frames_limit: plan.frames,
            screenshot: plan.screenshot,
            shot_requested: false,
            finished: false,
            display_band,
            band_for_warps: None,
            hand_over_ms: None,
        })
    }

    fn window_event(&mut self, event: &WindowEvent) -> Result<Flow> {
        let egui_response = self.egui_input.on_window_event(&self.window, event);
        match event {
            WindowEvent::CloseRequested => return Ok(Flow::Exit),
            WindowEvent::Resized(size) => self.screen.resize(size.width, size.height),
            WindowEvent::RedrawRequested => return self.redraw(),
            WindowEvent::Focused(false) => self.input.focus_lost(),
            WindowEvent::CursorLeft { .. } => self.input.cursor_left(),
            WindowEvent::CursorMoved { position, .. } => {
                self.input.cursor_moved(position.x, position.y);
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let pressed = *state == ElementState::Pressed;
                let look_button = matches!(button, MouseButton::Left | MouseButton::Right);
                // A press on the HUD belongs to the HUD; a release always ends the drag.
                if look_button && (!pressed || !egui_response.consumed) {
                    self.input.look_button(pressed);
                }
            }
            WindowEvent::KeyboardInput { event, .. } if !self.egui.egui_wants_keyboard_input() => {
                if let PhysicalKey::Code(code) = event.physical_key
                    && let Some(command) =
                        self.input.key(code, event.state.is_pressed(), event.repeat)
                {
                    return Ok(self.command(command));
                }
            }
            _ => {}
        }
        Ok(Flow::Continue)
    }

    fn command(&mut self, command: Command) -> Flow {
        match command {
            Command::ToggleHud => self.hud_visible = !self.hud_visible,
            Command::ToggleSweep => match &mut self.mode {
                Mode::Live(_) => self.apply(HudChange::Sweep(!self.hud_edit.sweep)),
                Mode::Playback(p) => p.restart(),
            },
            Command::TogglePause => self.apply(HudChange::Pause(!self.paused)),
            Command::ToggleTemporal => self.apply(HudChange::Temporal(!self.hud_edit.temporal)),
            Command::ToggleWarps => {
                if let Some(on) = self.hud_edit.warps {
                    self.apply(HudChange::Warps(!on));
                }
            }
            Command::Screenshot => self.shot_requested = true,
            Command::Quit => return Flow::Exit,
        }
        Flow::Continue
    }

    /// Applies one HUD edit; a refused one is shown in the HUD and undone there.
    fn apply(&mut self, change: HudChange) {
        let warps_changed = matches!(change, HudChange::Warps(_));
        let result = match (&mut self.mode, change) {
            (_, HudChange::Pause(paused)) => {
                self.paused = paused;
                Ok(())
            }
            (Mode::Live(live), HudChange::Sweep(on)) => {
                live.sweep.on = on;
                Ok(())
            }
            (Mode::Live(live), HudChange::Temporal(on)) => {
                live.temporal = on;
                Ok(())
            }
            (Mode::Live(live), HudChange::Warps(on)) => {
                live.warps_on = on;
                if !on {
                    live.warps_due = 0;
                }
                Ok(())
            }
            (Mode::Live(live), HudChange::Controller(name)) => live.control.set_controller(name),
            (Mode::Live(live), HudChange::Band { tmin_ms, tmax_ms }) => {
                live.control.set_band(tmin_ms, tmax_ms)
            }
            (Mode::Live(live), HudChange::Bounds(bounds)) => live.control.set_bounds(bounds),
            (Mode::Playback(_), HudChange::Band { tmin_ms, tmax_ms }) => {
                Band::new(tmin_ms, tmax_ms).map(|_| ()).map_err(Into::into)
            }
            (Mode::Playback(_), _) => Ok(()),
        };
        self.message = result.err().map(|e| format!("{e:#}"));
        self.sync_hud();
        if warps_changed {
            self.update_band();
        }
    }

    /// Makes the HUD's controls show what is in effect.
    fn sync_hud(&mut self) {
        self.hud_edit.paused = self.paused;
        match &self.mode {
            Mode::Live(live) => {
                self.band = live.control.band();
                self.hud_edit.controller = live.control.name();
                self.hud_edit.bounds = live.control.bounds();
                self.hud_edit.sweep = live.sweep.on;
                self.hud_edit.temporal = live.temporal;
                self.hud_edit.warps = (live.warps > 0).then_some(live.warps_on);
            }
            Mode::Playback(_) => {
                if let Ok(band) = Band::new(self.hud_edit.tmin_ms, self.hud_edit.tmax_ms) {
                    self.band = band;
                }
            }
        }
        self.hud_edit.tmin_ms = self.band.tmin_ms();
        self.hud_edit.tmax_ms = self.band.tmax_ms();
    }

    /// One frame: advance, render (or pick the recorded frame), HUD, present.
    fn redraw(&mut self) -> Result<Flow> {
        let now = Instant::now();
        let dt_s = now.duration_since(self.last_frame).as_secs_f32().min(0.25);
        self.last_frame = now;
        let t_s = now.duration_since(self.started).as_secs_f64();
        let paused = self.paused;
        let look = self.input.take_look();
        let movement = self.input.movement();
        let mut warp_ms = None;
        let mut unshown_warp_ms = None;
        let band_wants_warp = self
            .display_band
            .as_ref()
            .is_some_and(DisplayBand::wants_warp);
        let mut warps_due = 0;
        let warps_per_frame = match &self.mode {
            Mode::Live(live) => live.warps_after_frame(),
            Mode::Playback(_) => 0,
        };
        let (image, sample, playback, (speed_deg_s, target_ms)) = match &mut self.mode {
            Mode::Live(live) => {
                let (camera, scene_time_s) = live.advance(dt_s, look, movement, paused);
                let full = full_size(self.screen.size(), live.pixel_size);
                live.sync_history(full)?;
                let facts = |live: &Live| (live.speed_deg_s, live.control.target_frame_ms());
                if live.warps_due > 0 {
                    // A refresh without a new frame: the last one warped to this camera.
                    live.warps_due -= 1;
                    warps_due = live.warps_due;
                    let facts = facts(live);
                    let warping = Instant::now();
                    let image = live.renderer.warped(&camera, &self.device, &self.queue)?;
                    warp_ms = Some(warping.elapsed().as_secs_f64() * 1e3);
                    (image, None, None, facts)
                } else {
                    if band_wants_warp {
                        unshown_warp_ms =
                            live.time_unshown_warp(&camera, &self.device, &self.queue)?;
                    }
                    let at = (camera, scene_time_s, t_s);
                    let sample = live.render_frame(at, full, &self.device, &mut self.timing)?;
                    live.warps_due = live.warps_after_frame();
                    warps_due = live.warps_due;
                    let facts = facts(live);
                    let handing = Instant::now();
                    let image = live.renderer.image(&self.device, &self.queue)?;
                    self.hand_over_ms = Some(handing.elapsed().as_secs_f64() * 1e3);
                    (image, Some(sample), None, facts)
                }
            }
            Mode::Playback(p) => {
                let elapsed_s = if paused { 0.0 } else { dt_s };
                let (i, sample) = p.advance(elapsed_s, (now, t_s), &self.device, &self.queue)?;
                (
                    p.upload.image(),
                    sample,
                    Some((i, p.recording.len())),
                    (None, None),
                )
            }
        };
        let last_size = (image.width, image.height);
        let ui = Self::hud_frame(
            &self.window,
            &self.egui,
            &mut self.egui_input,
            HudPass {
                visible: self.hud_visible,
                edit: &mut self.hud_edit,
                rect: &mut self.hud_rect,
                facts: HudFacts {
                    history: &self.history,
                    band: self.band,
                    device: &self.device_label,
                    timing: &self.timing,
                    frame_size: last_size,
                    playback,
                    message: self.message.as_deref(),
                    speed_deg_s,
                    target_ms,
                    warps: (warps_per_frame > 0)
                        .then(|| (warps_per_frame, self.all_warp_ms.last().copied())),
                },
            },
        );
        // The frame that completes a `--frames` run (or, in playback, shows the last
        // recorded frame) ends the view, and is the screenshot's; after its warped
        // refreshes, when it has any.
        let at_end = playback.is_some_and(|(i, n)| i + 1 == n);
        let frames_shown = self.all_render_ms.len() + usize::from(sample.is_some());
        let ends_run = (sample.is_some() || warp_ms.is_some())
            && warps_due == 0
            && self
                .frames_limit
                .is_some_and(|n| frames_shown >= n as usize || at_end);
        let capture = self.shot_requested || (ends_run && self.screenshot.is_some());
        let drawn = self.screen.draw(&image, ui.frame, capture)?;
        let Drawn::Presented(shot) = drawn else {
            return Ok(Flow::Continue);
        };
        self.last_size = last_size;
        if let Some(ms) = warp_ms {
            self.all_warp_ms.push(ms);
        }
        if let Some(ms) = warp_ms.or(unshown_warp_ms) {
            self.observe_band(|band| band.observe_warp(ms));
        }
        let presented = Instant::now();
        // Between frames' presents (a warped refresh is not a frame).
        let interval = sample
            .as_ref()
            .and_then(|_| self.last_present.replace(presented))
            .map(|p| presented.duration_since(p).as_secs_f64() * 1e3);
        if let Some(mut sample) = sample {
            if matches!(self.mode, Mode::Live(_)) {
                sample.present_ms = interval;
            }
            self.history.push(sample);
            self.all_render_ms.push(sample.render_ms);
            if let Some(ms) = sample.present_ms {
                self.all_present_ms.push(ms);
            }
        }
        for change in ui.changes {
            self.apply(change);
        }
        if let Some(ms) = self.hand_over_ms.take() {
            self.observe_band(|band| band.observe(ms));
        }
        if let Some(shot) = shot {
            self.save_shot(&shot, ends_run)?;
        }
        self.finished = ends_run;
        Ok(if ends_run { Flow::Exit } else { Flow::Continue })
    }

    /// Takes a frame's hand-over or a warp's cost towards `--band refresh[:M]` (`observe`
    /// gives it to the display's band) and sets the band once it is measured.
    fn observe_band(&mut self, observe: impl FnOnce(&mut DisplayBand)) {
        if let Some(measuring) = &mut self.display_band {
            observe(measuring);
            self.update_band();
        }
    }

    /// Whether the refreshes between frames show warps (`--warp`, and V has not turned them
    /// off).
    fn warps_shown(&self) -> bool {
        matches!(&self.mode, Mode::Live(live) if live.warps > 0 && live.warps_on)
    }

    /// Sets `--band refresh[:M]`'s band, once measured, for the warps as they are shown
    /// (again when V turns them off or on), and tells the controller the costs (`perceptual`
    /// builds its own bands from them).
    fn update_band(&mut self) {
        let warps = self.warps_shown();
        let Some(measuring) = &self.display_band else {
            return;
        };
        if self.band_for_warps == Some(warps) {
            return;
        }
        match measuring.band(warps) {
            None => {}
            Some(Ok(b)) => {
                let costs = if b.warp_ms > 0.0 {
                    format!(", warp {:.2} ms (median)", b.warp_ms)
                } else {
                    String::new()
                };
                eprintln!(
                    "steadyray view: --band refresh at {:.2} Hz: hand-over {:.2} ms (median){costs}, band [{:.2}, {:.2}] ms",
                    b.refresh_hz, b.hand_over_ms, b.tmin_ms, b.tmax_ms
                );
                self.band_for_warps = Some(warps);
                self.apply(HudChange::Band {
                    tmin_ms: b.tmin_ms,
                    tmax_ms: b.tmax_ms,
                });
                if let Mode::Live(live) = &mut self.mode {
                    let costs = MeasuredCosts {
                        hand_over_ms: b.hand_over_ms,
                        warp_ms: b.warp_ms,
                    };
                    if let Err(e) = live.control.set_display_costs(costs) {
                        self.message = Some(format!("the display's costs: {e:#}"));
                    }
                }
            }
            Some(Err(e)) => {
                self.display_band = None;
                self.message = Some(format!("--band refresh: {e:#}"));
            }
        }
    }

    /// Writes a captured frame: to `--screenshot` when it ends the run, else (F12) to a
    /// time-stamped file in the current folder.
    fn save_shot(&mut self, shot: &Screenshot, ends_run: bool) -> Result<()> {
        let path = match &self.screenshot {
            Some(path) if ends_run => path.clone(),
            _ => {
                let stamp = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_millis());
                PathBuf::from(format!("steadyray-view-{stamp}.png"))
            }
        };
        shot.save(&path)?;
        eprintln!("steadyray view: screenshot written to {}", path.display());
        self.shot_requested = false;
        Ok(())
    }

    /// Runs egui for one frame: the HUD (if shown) and what its controls changed.
    fn hud_frame(
        window: &Window,
        egui: &egui::Context,
        egui_input: &mut egui_winit::State,
        pass: HudPass<'_>,
    ) -> HudOutput {
        let HudPass {
            visible,
            edit,
            rect,
            facts,
        } = pass;
        let before = edit.clone();
        let raw = egui_input.take_egui_input(window);
        let mut area = None;
        let output = egui.run_pass(raw, |ctx| {
            if visible {
                area = hud::show(ctx, edit, &facts);
            }
        });
        egui_input.handle_platform_output(window, output.platform_output);
        let ppp = output.pixels_per_point;
        *rect = area.map(|r| [r.min.x * ppp, r.min.y * ppp, r.max.x * ppp, r.max.y * ppp]);
        HudOutput {
            frame: UiFrame {
                paint_jobs: egui.tessellate(output.shapes, ppp),
                textures: output.textures_delta,
                pixels_per_point: ppp,
            },
            changes: edit.changes_since(&before),
        }
    }

    fn summary(&self) -> Summary {
        let (mode, controller) = match &self.mode {
            Mode::Live(live) => ("live", Some(live.control.name())),
            Mode::Playback(_) => ("playback", None),
        };
        let in_band = self
            .all_render_ms
            .iter()
            .filter(|&&ms| self.band.contains(ms))
            .count();
        let size = self.screen.size();
        Summary {
            mode,
            device: self.device_label.clone(),
            timing: self.timing.clone(),
            present_mode: format!("{:?}", self.screen.present_mode()),
            window: [size.0, size.1],
            frames: self.all_render_ms.len(),
            band_ms: [self.band.tmin_ms(), self.band.tmax_ms()],
            controller,
            render_ms: Spread::of(self.all_render_ms.iter().copied()),
            present_ms: Spread::of(self.all_present_ms.iter().copied()),
            warped_refreshes: self.all_warp_ms.len(),
            warp_ms: Spread::of(self.all_warp_ms.iter().copied()),
            in_band_pct: (!self.all_render_ms.is_empty())
                .then(|| 100.0 * in_band as f64 / self.all_render_ms.len() as f64),
            last_frame: [self.last_size.0, self.last_size.1],
            hud_rect: self.hud_rect,
            screenshot: self.screenshot.clone().filter(|_| self.finished),
        }
    }
}

/// What one HUD pass reads and edits.
struct HudPass<'a> {
    visible: bool,
    edit: &'a mut HudEdit,
    rect: &'a mut Option<[f32; 4]>,
    facts: HudFacts<'a>,
}

/// What one HUD pass gives back.
struct HudOutput {
    frame: UiFrame,
    changes: Vec<HudChange>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_render::RenderSettings;

    #[test]
    fn frame_sizes_follow_the_window_and_the_scale() {
        assert_eq!(full_size((480, 270), 3), (160, 90));
        assert_eq!(full_size((1281, 720), 2), (641, 360));
        assert_eq!(full_size((0, 0), 2), (1, 1));
        assert_eq!(RenderSettings::scaled_size((160, 90), 0.5), (80, 45));
        assert_eq!(RenderSettings::scaled_size((160, 90), 0.001), (1, 1));
    }

    #[test]
    fn software_renderers_get_coarse_pixels() {
        assert_eq!(default_pixel_size(1280, true, false), 1);
        assert_eq!(default_pixel_size(1280, true, true), 8);
        assert_eq!(default_pixel_size(1280, false, false), 2);
        assert_eq!(default_pixel_size(100, false, false), 1);
    }
}
