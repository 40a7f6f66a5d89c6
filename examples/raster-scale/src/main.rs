//! `raster-scale`: `steadyray-control` holding a raster engine's frame time at one refresh.
//!
//! A winit + wgpu window draws a deliberately heavy procedural fragment shader (its cost is
//! pixels × fractal steps) at a render scale into an offscreen texture and upscales it onto
//! the window. The workload's cost steps up and down over time ([`load::LEVELS`]); the
//! controller (any of `steadyray-control`'s, `predictive` by default) moves the render scale
//! to keep the frame time in a band just under one refresh. With `--frames N` it runs N
//! frames and prints a one-line JSON summary; `--controller fixed:scale=1` is the same
//! engine without control, for comparison.

mod calibrate;
mod engine;
mod gpu;
mod load;
mod summary;
mod timer;

use anyhow::{Context, Result, bail};
use clap::Parser;
use engine::Frame;
use gpu::Gpu;
use load::Schedule;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;
use steadyray_control::{Band, Controller};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// A raster workload held at one refresh by steadyray-control's render-scale decisions.
#[derive(Debug, Parser)]
#[command(name = "raster-scale", about)]
struct Args {
    /// The controller and its options, as `steadyray bench --controllers` writes one:
    /// `predictive`, `hysteresis`, `fixed:scale=1` (no control), ...
    #[arg(long, default_value = "predictive")]
    controller: String,
    /// Run this many frames after the warm-up, print the JSON summary and exit (else run
    /// until the window is closed).
    #[arg(long)]
    frames: Option<u64>,
    /// Frames at the start left out of the summary (the controller finding its scale).
    #[arg(long, default_value_t = 20)]
    warm_up: u64,
    /// The display's refresh rate, Hz: the band is [0.80, 0.95] of one refresh.
    #[arg(long, default_value_t = 60.0)]
    refresh_hz: f64,
    /// Frames each load level is held.
    #[arg(long, default_value_t = 90)]
    phase_frames: u64,
    /// Window width, pixels.
    #[arg(long, default_value_t = 640)]
    width: u32,
    /// Window height, pixels.
    #[arg(long, default_value_t = 360)]
    height: u32,
    /// Print each change of scale with the controller's reason (its decision) to stderr.
    #[arg(long)]
    log_decisions: bool,
}

impl Args {
    /// The band [0.80, 0.95] of a refresh, checked.
    fn band(&self) -> Result<Band> {
        if !(self.refresh_hz.is_finite() && self.refresh_hz > 0.0) {
            bail!(
                "--refresh-hz must be a positive number, got {}",
                self.refresh_hz
            );
        }
        let period = 1000.0 / self.refresh_hz;
        Ok(Band::new(0.80 * period, 0.95 * period)?)
    }

    fn check(&self) -> Result<()> {
        if self.width == 0 || self.height == 0 || self.width > 8192 || self.height > 8192 {
            bail!(
                "--width and --height must be 1 to 8192 pixels, got {}x{}",
                self.width,
                self.height
            );
        }
        if self.phase_frames == 0 {
            bail!("--phase-frames must be at least 1");
        }
        if self.frames == Some(0) {
            bail!("--frames must be at least 1");
        }
        Ok(())
    }
}

fn main() -> ExitCode {
    match run(Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: Args) -> Result<()> {
    args.check()?;
    let band = args.band()?;
    let controller = engine::controller(&args.controller, band)?;
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow::anyhow!("cannot open a window: {e} (on a headless machine run under xvfb-run)")
    })?;
    let instance = wgpu::Instance::new(
        wgpu::InstanceDescriptor::new_with_display_handle(Box::new(
            event_loop.owned_display_handle(),
        ))
        .with_env(),
    );
    let mut app = App {
        args,
        band,
        instance,
        controller,
        running: None,
        frames: Vec::new(),
        error: None,
    };
    event_loop
        .run_app(&mut app)
        .context("the window's event loop failed")?;
    if let Some(error) = app.error {
        return Err(error);
    }
    app.finish()
}

/// The window and what runs in it.
struct App {
    args: Args,
    band: Band,
    instance: wgpu::Instance,
    controller: Box<dyn Controller>,
    running: Option<Running>,
    /// Every frame drawn after calibration.
    frames: Vec<Frame>,
    error: Option<anyhow::Error>,
}

/// The open window, its GPU and the load schedule calibrated on it.
struct Running {
    window: Arc<Window>,
    gpu: Gpu,
    schedule: Schedule,
    start: Instant,
}

impl App {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<Running> {
        let attributes = Window::default_attributes()
            .with_title("raster-scale: steadyray-control on a raster workload")
            .with_inner_size(PhysicalSize::new(self.args.width, self.args.height))
            .with_resizable(false);
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("cannot create the window")?,
        );
        let mut gpu = Gpu::new(&self.instance, window.clone())?;
        let base_iterations = calibrate::base_iterations(&mut gpu, self.band.centre_ms())?;
        eprintln!(
            "raster-scale: {} at {}x{}, load 1 = {base_iterations:.0} steps per pixel, band [{:.2}, {:.2}] ms",
            gpu.adapter,
            gpu.size().0,
            gpu.size().1,
            self.band.tmin_ms(),
            self.band.tmax_ms()
        );
        Ok(Running {
            window,
            gpu,
            schedule: Schedule {
                phase_frames: self.args.phase_frames,
                base_iterations,
            },
            start: Instant::now(),
        })
    }

    /// Draws the next frame; true when the run is complete.
    fn redraw(&mut self) -> Result<bool> {
        let Some(running) = self.running.as_mut() else {
            return Ok(false);
        };
        let index = self.frames.len() as u64;
        let time_s = running.start.elapsed().as_secs_f32();
        if let Some(frame) = engine::step(
            &mut running.gpu,
            self.controller.as_mut(),
            &running.schedule,
            index,
            time_s,
            self.args.log_decisions,
        )? {
            self.frames.push(frame);
        }
        let wanted = self.args.frames.map(|n| n + self.args.warm_up);
        Ok(wanted.is_some_and(|n| self.frames.len() as u64 >= n))
    }

    /// Prints the summary of the frames after the warm-up (nothing when none were drawn).
    fn finish(&self) -> Result<()> {
        let Some(running) = &self.running else {
            return Ok(());
        };
        let kept = self.frames.get(self.args.warm_up as usize..).unwrap_or(&[]);
        if kept.is_empty() {
            bail!("the window closed before any frame after the warm-up was drawn");
        }
        let summary = summary::summarize(
            &self.args.controller,
            &running.gpu.adapter,
            kept,
            self.band,
            running.schedule.base_iterations,
            running.schedule.phase_frames,
        );
        println!("{}", serde_json::to_string(&summary)?);
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error = Some(error);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        event_loop.set_control_flow(ControlFlow::Poll);
        match self.start(event_loop) {
            Ok(running) => self.running = Some(running),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => match self.redraw() {
                Ok(true) => event_loop.exit(),
                Ok(false) => {}
                Err(e) => self.fail(event_loop, e),
            },
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(running) = &self.running {
            running.window.request_redraw();
        }
    }
}
