//! Sharing the renderer's GPU with a window: an instance that can create surfaces, and the
//! adapter that both renders and presents to one. A window's surface must come from the same
//! [`wgpu::Instance`] as the adapter and device that draw into it, so a caller creates the
//! instance here, its surface from it, then [`surface_adapter`] and
//! [`crate::GpuRenderer::with_adapter`].

use crate::GpuOptions;
use crate::adapter::select_adapter_where;
use std::fmt::Debug;
use steadyray_render::RenderError;

/// A wgpu instance over the default backends (or those `WGPU_BACKEND` names) that can
/// create surfaces on `display` (e.g. winit's `OwnedDisplayHandle`).
pub fn display_instance(
    display: impl wgpu::rwh::HasDisplayHandle + Debug + Send + Sync + 'static,
) -> wgpu::Instance {
    let mut descriptor = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(display));
    descriptor.backends = crate::adapter::DEFAULT_BACKENDS;
    wgpu::Instance::new(descriptor.with_env())
}

/// The best adapter of `instance` that `options` allow and that can present to `surface`, or
/// a message naming what was seen.
pub fn surface_adapter(
    instance: &wgpu::Instance,
    surface: &wgpu::Surface<'_>,
    options: &GpuOptions,
) -> Result<wgpu::Adapter, RenderError> {
    select_adapter_where(instance, options, ", presents to the window", |adapter| {
        adapter.is_surface_supported(surface)
    })
}
