//! Turning wgpu's errors into [`RenderError::Gpu`] with wgpu's own message: error scopes
//! around pipeline creation and submission, and a sink for what no scope caught
//! (uncaptured errors, device loss).

use std::sync::{Arc, Mutex, PoisonError};
use steadyray_render::RenderError;

/// A GPU error with context, as a [`RenderError`].
pub(crate) fn gpu_error(context: &str, message: impl std::fmt::Display) -> RenderError {
    RenderError::Gpu(format!("{context}: {message}"))
}

/// Errors wgpu reported outside any error scope, kept until the renderer next looks.
#[derive(Clone, Default)]
pub(crate) struct ErrorSink {
    state: Arc<Mutex<SinkState>>,
}

#[derive(Default)]
struct SinkState {
    lost: Option<String>,
    uncaptured: Vec<String>,
}

impl ErrorSink {
    /// Routes `device`'s uncaptured errors and loss into this sink (instead of wgpu's
    /// default handler, which panics).
    pub(crate) fn install(&self, device: &wgpu::Device) {
        let sink = self.clone();
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            sink.lock().uncaptured.push(error.to_string());
        }));
        let sink = self.clone();
        device.set_device_lost_callback(move |reason, message| {
            if reason != wgpu::DeviceLostReason::Destroyed {
                sink.lock().lost = Some(format!("GPU device lost ({reason:?}): {message}"));
            }
        });
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, SinkState> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Fails if the device was lost (for good) or errors arrived since the last check
    /// (which are then cleared).
    pub(crate) fn check(&self) -> Result<(), RenderError> {
        let mut state = self.lock();
        if let Some(lost) = &state.lost {
            return Err(RenderError::Gpu(lost.clone()));
        }
        if state.uncaptured.is_empty() {
            return Ok(());
        }
        let messages = std::mem::take(&mut state.uncaptured);
        Err(RenderError::Gpu(messages.join("\n")))
    }
}

/// Runs `f` inside validation, out-of-memory and internal error scopes on `device` and
/// returns the first error any of them caught, prefixed with `context`.
pub(crate) fn scoped<T>(
    device: &wgpu::Device,
    context: &str,
    f: impl FnOnce() -> T,
) -> Result<T, RenderError> {
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = f();
    let errors = [
        pollster::block_on(validation.pop()),
        pollster::block_on(memory.pop()),
        pollster::block_on(internal.pop()),
    ];
    match errors.into_iter().flatten().next() {
        Some(error) => Err(gpu_error(context, error)),
        None => Ok(value),
    }
}
