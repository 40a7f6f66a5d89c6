//! The GPU context a renderer owns: adapter, device, queue, error capture, and blocking
//! readback.

use crate::adapter::{AdapterSummary, GpuOptions, new_instance, select_adapter};
use crate::error::{ErrorSink, gpu_error, scoped};
use std::sync::mpsc;
use steadyray_render::RenderError;

/// One device and its queue, with wgpu's errors routed into an [`ErrorSink`].
pub(crate) struct GpuContext {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) info: wgpu::AdapterInfo,
    pub(crate) adapter: AdapterSummary,
    /// Whether compute passes can write timestamps.
    pub(crate) timestamps: bool,
    pub(crate) errors: ErrorSink,
}

impl GpuContext {
    /// Chooses an adapter by `options` and opens a device with its full limits.
    pub(crate) fn new(options: &GpuOptions) -> Result<Self, RenderError> {
        let instance = new_instance();
        let adapter = select_adapter(&instance, options)?;
        Self::open(&adapter)
    }

    /// Opens a device with its full limits on `adapter` (e.g. one chosen for a window).
    pub(crate) fn open(adapter: &wgpu::Adapter) -> Result<Self, RenderError> {
        let info = adapter.get_info();
        let summary = AdapterSummary::of(adapter);
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let required_features = if timestamps {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("steadyray"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| gpu_error(&format!("cannot open a device on {}", info.name), e))?;
        let errors = ErrorSink::default();
        errors.install(&device);
        Ok(Self {
            device,
            queue,
            info,
            adapter: summary,
            timestamps,
            errors,
        })
    }

    /// The device as reports and logs name it: adapter name, graphics API and driver, e.g.
    /// "llvmpipe (LLVM 15.0.6, 256 bits) (vulkan, llvmpipe Mesa 22.3.6 (LLVM 15.0.6))".
    pub(crate) fn description(&self) -> String {
        let info = &self.info;
        format!(
            "{} ({}, {} {})",
            info.name,
            info.backend.to_str(),
            info.driver,
            info.driver_info
        )
        .replace(" )", ")")
    }

    /// A command encoder labelled `label` (the label names it in validation errors).
    pub(crate) fn encoder(&self, label: &str) -> wgpu::CommandEncoder {
        self.device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) })
    }

    /// Submits `commands` and waits for the GPU to finish them, surfacing validation errors,
    /// device loss and uncaptured errors as [`RenderError::Gpu`].
    pub(crate) fn submit_and_wait(&self, commands: wgpu::CommandBuffer) -> Result<(), RenderError> {
        scoped(&self.device, "GPU submission failed", || {
            self.queue.submit([commands]);
        })?;
        self.wait()
    }

    /// Waits for all submitted work (and pending map callbacks).
    pub(crate) fn wait(&self) -> Result<(), RenderError> {
        let polled = self.device.poll(wgpu::PollType::wait_indefinitely());
        self.errors.check()?;
        polled
            .map(drop)
            .map_err(|e| gpu_error("waiting for the GPU failed", e))
    }

    /// Maps the first `size` bytes of `buffer` (MAP_READ, idle) and copies them out.
    pub(crate) fn read_buffer(
        &self,
        buffer: &wgpu::Buffer,
        size: u64,
    ) -> Result<Vec<u8>, RenderError> {
        let slice = buffer.slice(..size);
        let (sender, receiver) = mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            // The receiver outlives the wait below; a failed send means nobody listens.
            let _ = sender.send(result);
        });
        self.wait()?;
        receiver
            .recv()
            .map_err(|e| gpu_error("buffer map callback never ran", e))?
            .map_err(|e| gpu_error("cannot map a readback buffer", e))?;
        let bytes = slice
            .get_mapped_range()
            .map_err(|e| gpu_error("cannot read a mapped buffer", e))?
            .to_vec();
        buffer.unmap();
        Ok(bytes)
    }
}
