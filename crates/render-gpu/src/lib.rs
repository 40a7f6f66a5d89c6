//! The GPU backend of steadyray: the Whitted integrator of `docs/shading.md` as wgpu compute
//! shaders (WGSL in `src/shaders/`), one thread per pixel, with exact ray counts per
//! workgroup summed as 64-bit totals and GPU timestamps for the frame time.
//!
//! [`list_adapters`] tells a caller whether a real GPU is present; [`GpuRenderer::new`]
//! opens one (chosen by [`GpuOptions`]) and implements [`steadyray_render::Renderer`].
//! [`GpuRayCaster`] casts rays through a mesh's BVH alone, with the renderer's traversal, for
//! `steadyray raybench`.

mod adapter;
mod buffers;
mod device;
mod error;
pub mod layout;
mod pipeline;
mod raycast;
mod renderer;
mod sample_ranges;
mod scene_buffers;
mod surface;
mod temporal;
mod timing;
mod warp;

pub use adapter::{AdapterSummary, DeviceKind, GpuOptions, list_adapters};
pub use raycast::{CastOutcome, GpuRayCaster};
pub use renderer::GpuRenderer;
pub use renderer::display::DisplayImage;
pub use surface::{display_instance, surface_adapter};
