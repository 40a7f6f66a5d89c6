//! Choosing and creating a renderer backend.

use crate::config::BackendChoice;
use anyhow::{Context, Result, bail};
use steadyray_render::Renderer;
use steadyray_render_cpu::CpuRenderer;
use steadyray_render_gpu::{GpuOptions, GpuRenderer, list_adapters};

/// The environment variable that selects a GPU adapter by (part of) its name.
pub const ADAPTER_ENV: &str = "STEADYRAY_ADAPTER";

/// The adapter options of an explicit `--backend gpu`: any adapter that can run the compute
/// shaders, software ones such as lavapipe included, narrowed by `STEADYRAY_ADAPTER`.
pub fn requested_gpu_options() -> GpuOptions {
    GpuOptions {
        adapter_name: std::env::var(ADAPTER_ENV).ok().filter(|s| !s.is_empty()),
        allow_software: true,
    }
}

/// Creates the renderer `choice` asks for, saying on stderr which one it picked and why.
pub fn create_renderer(choice: BackendChoice) -> Result<Box<dyn Renderer>> {
    let adapter_name = std::env::var(ADAPTER_ENV).ok().filter(|s| !s.is_empty());
    match choice {
        BackendChoice::Cpu => {
            eprintln!("steadyray: backend cpu (asked for)");
            Ok(Box::new(CpuRenderer::new()))
        }
        BackendChoice::Gpu => {
            let gpu = GpuRenderer::new(&requested_gpu_options())
                .context("the gpu backend is not available")?;
            eprintln!(
                "steadyray: backend gpu on {} (asked for)",
                gpu.info().device
            );
            Ok(Box::new(gpu))
        }
        BackendChoice::Auto => {
            let hardware = list_adapters().into_iter().find(|a| {
                !a.is_software
                    && adapter_name
                        .as_deref()
                        .is_none_or(|want| a.name.to_lowercase().contains(&want.to_lowercase()))
            });
            let Some(adapter) = hardware else {
                eprintln!(
                    "steadyray: backend cpu (auto: no hardware GPU adapter{}; software \
                     adapters such as lavapipe are slower than the CPU renderer)",
                    adapter_name
                        .as_deref()
                        .map(|n| format!(" matching {ADAPTER_ENV}={n:?}"))
                        .unwrap_or_default()
                );
                return Ok(Box::new(CpuRenderer::new()));
            };
            let options = GpuOptions {
                adapter_name: Some(adapter.name.clone()),
                allow_software: false,
            };
            match GpuRenderer::new(&options) {
                Ok(gpu) => {
                    eprintln!("steadyray: backend gpu on {} (auto)", gpu.info().device);
                    Ok(Box::new(gpu))
                }
                Err(e) => {
                    eprintln!(
                        "steadyray: backend cpu (auto: GPU adapter {} failed to start: {e})",
                        adapter.name
                    );
                    Ok(Box::new(CpuRenderer::new()))
                }
            }
        }
    }
}

/// Prints the adapters wgpu can see, one per line; fails when there is none.
pub fn print_adapters() -> Result<()> {
    let adapters = list_adapters();
    if adapters.is_empty() {
        bail!("no GPU adapter found (install a Vulkan driver, e.g. mesa-vulkan-drivers)");
    }
    for a in adapters {
        println!(
            "{}\t{:?}\t{:?}\t{}{}",
            a.name,
            a.backend,
            a.device_type,
            a.driver,
            if a.is_software { "\t(software)" } else { "" }
        );
    }
    Ok(())
}
