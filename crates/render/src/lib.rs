//! What every steadyray renderer backend shares: the [`Renderer`] trait, the settings of a
//! frame, what a frame reports, the linear image, and the rules both backends must follow
//! bit for bit (sample pattern, fractional-S dither, branch random numbers, tone map, and the
//! temporal mode's jitter, landing and reprojection rules). `docs/shading.md` and
//! `docs/temporal.md` are the prose version of the same contract. [`two_level`] lays a
//! scene out for the two-level BVH the same way for both.

pub mod image;
pub mod renderer;
pub mod sample_stream;
pub mod sampling;
pub mod settings;
pub mod stats;
pub mod surface_motion;
pub mod temporal;
#[cfg(test)]
mod test_scene;
pub mod tonemap;
pub mod two_level;

pub use image::Image;
pub use renderer::{
    BackendInfo, Picture, Presented, RenderError, Renderer, check_camera, check_time,
};
pub use sample_stream::SampleStream;
pub use settings::{MAX_DEPTH, MAX_SPP, RenderSettings, SettingsError, check_image_size};
pub use stats::{FrameStats, RayCounts, TimingSource};
/// A frame's time budget ([`Renderer::set_frame_budget`]).
pub use steadyray_budget::FrameBudget;
pub use temporal::TemporalSettings;
