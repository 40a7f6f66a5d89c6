//! The interface every renderer backend implements.

use crate::sample_stream::SampleStream;
use crate::{FrameStats, Image, RenderSettings, SettingsError, TemporalSettings};
use steadyray_budget::FrameBudget;
use steadyray_scene::{Camera, Scene};
use thiserror::Error;

/// Which backend and device rendered a frame, for reports.
#[derive(Clone, Debug, PartialEq)]
pub struct BackendInfo {
    /// "cpu" or "gpu".
    pub backend: String,
    /// The device: the CPU model and thread count, or the GPU adapter's name and driver.
    pub device: String,
}

/// Why a renderer could not render.
#[derive(Debug, Error)]
pub enum RenderError {
    /// Settings no renderer can render.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// A scene time that is not a finite number.
    #[error("scene time {0} s is not a finite number")]
    BadTime(f64),
    /// A camera with a non-finite or degenerate frame.
    #[error("cannot render from this camera: {0}")]
    BadCamera(String),
    /// Rendering before a scene was loaded.
    #[error("no scene loaded: call load_scene first")]
    NoScene,
    /// Reading a frame before one was rendered.
    #[error("no frame rendered yet: render before reading the image")]
    NoFrame,
    /// A scene this backend cannot render.
    #[error("scene cannot be rendered by this backend: {0}")]
    Scene(String),
    /// The GPU failed.
    #[error("GPU error: {0}")]
    Gpu(String),
    /// The backend cannot do what was asked.
    #[error("not available: {0}")]
    Unavailable(String),
}

/// A frame's 8-bit sRGB picture on the host: `width × height` RGBA pixels (alpha 255), row
/// major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// 8-bit sRGB RGBA per pixel, row-major, top row first.
    pub rgba: Vec<u8>,
}

/// Where a frame handed to a display by [`Renderer::present`] was tone-mapped.
#[derive(Clone, Debug, PartialEq)]
pub enum Presented {
    /// On the host: the picture a window uploads ([`Image::to_srgb8_rgba`]).
    Host(Picture),
    /// On the device, into the buffer a present pass there reads: nothing reached the host.
    Device,
}

/// Checks a camera given to [`Renderer::render`] or [`Renderer::present_warped`]
/// ([`Camera::check`]): a camera that is not finite would send rays no renderer can trace.
pub fn check_camera(camera: &Camera) -> Result<(), RenderError> {
    camera.check().map_err(RenderError::BadCamera)
}

/// Checks a scene time given to [`Renderer::render`]: any finite number of seconds.
pub fn check_time(time_s: f64) -> Result<(), RenderError> {
    if time_s.is_finite() {
        Ok(())
    } else {
        Err(RenderError::BadTime(time_s))
    }
}

/// A ray tracer backend. A scene is loaded once; frames are then rendered from any camera
/// at any quality, and the image of the last frame is read back only when asked for, so
/// timed loops never pay for readback.
pub trait Renderer {
    /// The backend and device, for reports.
    fn info(&self) -> BackendInfo;
    /// Prepares `scene` (acceleration structures, GPU buffers); replaces any earlier scene.
    fn load_scene(&mut self, scene: &Scene) -> Result<(), RenderError>;
    /// Renders one frame of the scene as it is at scene time `time_s` (seconds: where its
    /// moving objects are and which exist then) seen by `camera`, and reports its time and
    /// exact ray counts. Camera paths are separate: callers take the camera at the same
    /// time from the scene's path (`Scene::camera_at_time`) or from anywhere else.
    fn render(
        &mut self,
        camera: &Camera,
        time_s: f64,
        settings: &RenderSettings,
    ) -> Result<FrameStats, RenderError>;
    /// The linear image of the last rendered frame: in the temporal mode, the accumulated
    /// history at its full size.
    fn read_image(&mut self) -> Result<Image, RenderError>;
    /// Hands the last frame to a display the way this backend's window does, and returns
    /// once that is done: the cost after rendering that a frame pays before it can be shown
    /// (the real clock's hand-over, `docs/display.md`). The CPU backend tone-maps the image
    /// to the 8-bit picture a window uploads; a GPU backend tone-maps it on the device into
    /// the buffer its present pass reads, with no readback.
    fn present(&mut self) -> Result<Presented, RenderError>;
    /// The picture this backend's display shows, read to the host (for
    /// scores and videos, outside any timing): a GPU backend tone-maps on the device and
    /// reads back the 8-bit picture, a quarter of the linear image's bytes and no tone map on
    /// the host, so a caller that keeps every frame leaves the device idle for less time
    /// between frames. That is the last frame's picture, or after [`Renderer::present_warped`]
    /// the warped one, until the next frame or [`Renderer::present`].
    fn read_picture(&mut self) -> Result<Picture, RenderError>;
    /// Hands the last frame to the display again as `camera` sees it, for a refresh that
    /// has no new frame (`docs/temporal.md`, "Warped refreshes"): the temporal history
    /// reprojected by its geometry records to the new view, then handed over as by
    /// [`Renderer::present`]. The last frame's history is left as it was. Only in the
    /// temporal mode, after a frame; objects are shown where the frame had them.
    fn present_warped(&mut self, camera: &Camera) -> Result<Presented, RenderError>;
    /// Turns the temporal mode on, with a history of `temporal`'s size, or off (`None`); in
    /// either case any history starts over. In the temporal mode every frame is jittered,
    /// rendered at its own settings' size (at most the history's) and accumulated into the
    /// history by the rules of `docs/temporal.md`, inside the frame's time. Fails on an
    /// empty or too large history.
    fn set_temporal(&mut self, temporal: Option<TemporalSettings>) -> Result<(), RenderError>;
    /// Forgets the history (a camera cut): the next frame starts a new one.
    fn reset_history(&mut self);
    /// Chooses the samples plain frames draw from now on ([`SampleStream`]): a reference is
    /// rendered with [`SampleStream::Reference`], so that the frames it judges share none
    /// of its samples. Temporal frames draw their own, whatever the stream.
    fn set_sample_stream(&mut self, stream: SampleStream);
    /// Renders the frames from now on within `budget` (`None`: each frame whole, at its
    /// settings' S): the first sample of every pixel, then units of samples while the
    /// budget allows ([`FrameBudget::run_units`]), past the settings' S when the frame
    /// would end early; the frame's [`FrameStats::spp`] says the S it reached. A backend
    /// that cannot stop a frame part-way (the GPU's, whose passes run as one submission)
    /// refuses a budget with [`RenderError::Unavailable`], and so does the CPU renderer in
    /// the temporal mode.
    fn set_frame_budget(&mut self, budget: Option<FrameBudget>) -> Result<(), RenderError>;
}
