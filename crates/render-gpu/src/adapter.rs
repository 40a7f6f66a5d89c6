//! Finding GPU adapters and choosing one.

use steadyray_render::RenderError;

/// Which GPU adapter [`crate::GpuRenderer::new`] uses.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GpuOptions {
    /// Only adapters whose name contains this (case-insensitive), e.g. from the
    /// `STEADYRAY_ADAPTER` environment variable, which the caller reads.
    pub adapter_name: Option<String>,
    /// Whether a software adapter (lavapipe/llvmpipe, any CPU-type device) may be used.
    pub allow_software: bool,
}

/// The kind of device behind an adapter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DeviceKind {
    /// A separate graphics card.
    DiscreteGpu,
    /// A GPU sharing the CPU's package and memory.
    IntegratedGpu,
    /// A virtual or hosted GPU, as the driver reports it.
    VirtualGpu,
    /// A software rasteriser on the CPU (lavapipe, llvmpipe, SwiftShader, WARP).
    Cpu,
    /// Anything the driver does not classify.
    Other,
}

/// What the system's graphics stack offers: one adapter, for listings and for choosing a
/// backend (`--backend auto` uses the GPU renderer only when a non-software adapter exists).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdapterSummary {
    /// The adapter's name, e.g. "NVIDIA H100 80GB HBM3" or "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub name: String,
    /// The graphics API wgpu reaches it through: "vulkan", "metal", "dx12" or "gl".
    pub backend: String,
    /// What kind of device it is.
    pub device_type: DeviceKind,
    /// Driver name and version, where the backend reports them.
    pub driver: String,
    /// Whether it runs on the CPU (slow; excluded unless [`GpuOptions::allow_software`]).
    pub is_software: bool,
    /// Whether it can run compute shaders (a steadyray requirement).
    pub supports_compute: bool,
}

impl AdapterSummary {
    pub(crate) fn of(adapter: &wgpu::Adapter) -> Self {
        let info = adapter.get_info();
        let device_type = match info.device_type {
            wgpu::DeviceType::DiscreteGpu => DeviceKind::DiscreteGpu,
            wgpu::DeviceType::IntegratedGpu => DeviceKind::IntegratedGpu,
            wgpu::DeviceType::VirtualGpu => DeviceKind::VirtualGpu,
            wgpu::DeviceType::Cpu => DeviceKind::Cpu,
            wgpu::DeviceType::Other => DeviceKind::Other,
        };
        let lower = info.name.to_lowercase();
        let is_software = device_type == DeviceKind::Cpu
            || [
                "llvmpipe",
                "lavapipe",
                "swiftshader",
                "softpipe",
                "microsoft basic render",
            ]
            .iter()
            .any(|s| lower.contains(s));
        let driver = [info.driver.as_str(), info.driver_info.as_str()]
            .into_iter()
            .filter(|s| !s.is_empty())
            .collect::<Vec<_>>()
            .join(" ");
        Self {
            name: info.name,
            backend: info.backend.to_str().to_string(),
            device_type,
            driver,
            is_software,
            supports_compute: adapter
                .get_downlevel_capabilities()
                .flags
                .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS),
        }
    }

    /// Preference order among usable adapters: real GPUs first, then native APIs over GL.
    fn rank(&self) -> (u8, u8) {
        let kind = match self.device_type {
            DeviceKind::DiscreteGpu => 0,
            DeviceKind::IntegratedGpu => 1,
            DeviceKind::VirtualGpu => 2,
            DeviceKind::Other => 3,
            DeviceKind::Cpu => 4,
        };
        let software = u8::from(self.is_software);
        (software * 10 + kind, u8::from(self.backend == "gl"))
    }
}

/// The backends searched unless `WGPU_BACKEND` names others: Vulkan, Metal, DX12. wgpu's GL
/// backend cannot run these compute shaders on NVIDIA's driver (it gets a GL 3.3 context
/// there, `docs/gpu.md`), and probing it only prints EGL noise on machines without a display.
pub(crate) const DEFAULT_BACKENDS: wgpu::Backends = wgpu::Backends::PRIMARY;

/// A wgpu instance over [`DEFAULT_BACKENDS`], or the backends `WGPU_BACKEND` names.
pub(crate) fn new_instance() -> wgpu::Instance {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle();
    descriptor.backends = DEFAULT_BACKENDS;
    wgpu::Instance::new(descriptor.with_env())
}

/// Every adapter the system offers, best first (see [`AdapterSummary`]).
pub fn list_adapters() -> Vec<AdapterSummary> {
    let instance = new_instance();
    let mut adapters: Vec<AdapterSummary> =
        pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()))
            .iter()
            .map(AdapterSummary::of)
            .collect();
    adapters.sort_by_key(AdapterSummary::rank);
    adapters
}

/// The best adapter of `instance` that `options` allow, or a message naming what was seen.
pub(crate) fn select_adapter(
    instance: &wgpu::Instance,
    options: &GpuOptions,
) -> Result<wgpu::Adapter, RenderError> {
    select_adapter_where(instance, options, "", |_| true)
}

/// As [`select_adapter`], among the adapters `keep` accepts; `requirement` names what `keep`
/// checks (", " and a phrase, or empty) for the message when none qualifies.
pub(crate) fn select_adapter_where(
    instance: &wgpu::Instance,
    options: &GpuOptions,
    requirement: &str,
    keep: impl Fn(&wgpu::Adapter) -> bool,
) -> Result<wgpu::Adapter, RenderError> {
    let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()));
    let seen: Vec<String> = adapters
        .iter()
        .map(|a| {
            let s = AdapterSummary::of(a);
            format!("{} [{}, {:?}]", s.name, s.backend, s.device_type)
        })
        .collect();
    let wanted = options.adapter_name.as_deref().map(str::to_lowercase);
    let best = adapters
        .into_iter()
        .map(|a| (AdapterSummary::of(&a), a))
        .filter(|(s, a)| s.supports_compute && keep(a))
        .filter(|(s, _)| options.allow_software || !s.is_software)
        .filter(|(s, _)| {
            wanted
                .as_deref()
                .is_none_or(|w| s.name.to_lowercase().contains(w))
        })
        .min_by_key(|(s, _)| s.rank());
    match best {
        Some((_, adapter)) => Ok(adapter),
        None => {
            let mut why = vec![format!("compute shaders{requirement}")];
            if let Some(name) = &options.adapter_name {
                why.push(format!("name containing {name:?}"));
            }
            if !options.allow_software {
                why.push("not software (software adapters not allowed)".to_string());
            }
            let seen = if seen.is_empty() {
                "none".to_string()
            } else {
                seen.join(", ")
            };
            Err(RenderError::Gpu(format!(
                "no GPU adapter found (required: {}; adapters seen: {seen})",
                why.join(", ")
            )))
        }
    }
}
