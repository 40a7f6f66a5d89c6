//! Where the experiment's frames come from: a real renderer over the scene's camera path, or
//! the control crate's simulated renderer on a fake clock (`bench --simulate`).

use anyhow::Result;
use steadyray_control::simulate::{RendererModel, SimRenderer};
use steadyray_control::{FrameReport, Quality};
use steadyray_render::{Image, RenderSettings, Renderer};
use steadyray_scene::Scene;

/// One rendered (or simulated) frame as the experiment sees it.
pub struct Measured {
    /// What the controller is shown.
    pub report: FrameReport,
    /// Host wall time of the render call, ms.
    pub wall_ms: f64,
    /// Camera yaw of the frame, radians.
    pub angle: f32,
}

/// A source of frames at any quality along a fixed camera sweep.
pub trait FrameSource {
    /// The backend and device, for reports.
    fn describe(&self) -> (String, String);
    /// Full-scale image size.
    fn resolution(&self) -> (u32, u32);
    /// Renders frame `k` of an `n`-frame sweep at quality `q`.
    fn frame(&mut self, k: u32, n: u32, q: Quality) -> Result<Measured>;
    /// Frames where the load changes suddenly by construction, when known.
    fn load_changes(&self, n: u32) -> Option<Vec<usize>>;
    /// The linear image of the last frame (read back outside any timing), or `None` for a
    /// source without images (the simulated renderer).
    fn last_image(&mut self) -> Result<Option<Image>>;
}

/// The image size for a resolution scale: each side scaled and rounded, at least 1 pixel.
pub fn scaled_size(width: u32, height: u32, scale: f32) -> (u32, u32) {
    let side = |v: u32| ((v as f32 * scale).round() as u32).max(1);
    (side(width), side(height))
}

/// Frames from a real renderer.
pub struct RendererSource {
    pub renderer: Box<dyn Renderer>,
    pub scene: Scene,
    pub width: u32,
    pub height: u32,
}

impl FrameSource for RendererSource {
    fn describe(&self) -> (String, String) {
        let info = self.renderer.info();
        (info.backend, info.device)
    }

    fn resolution(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn frame(&mut self, k: u32, n: u32, q: Quality) -> Result<Measured> {
        let camera = self.scene.camera_at(k, n);
        let time_s = self.scene.path.frame_time(k, n);
        let (width, height) = scaled_size(self.width, self.height, q.scale);
        let settings = RenderSettings {
            width,
            height,
            spp: q.spp,
            max_depth: q.depth,
        };
        let stats = self.renderer.render(&camera, time_s, &settings)?;
        let f = camera.forward;
        Ok(Measured {
            report: FrameReport {
                tp_ms: stats.render_ms,
                rays_per_depth: stats.rays.per_depth,
                shadow_rays: stats.rays.shadow,
                pixels: settings.pixels(),
                quality: q,
                speed_deg_s: 0.0,
            },
            wall_ms: stats.wall_ms,
            angle: (-f.x).atan2(-f.z).rem_euclid(std::f32::consts::TAU),
        })
    }

    fn load_changes(&self, _n: u32) -> Option<Vec<usize>> {
        None
    }

    fn last_image(&mut self) -> Result<Option<Image>> {
        Ok(Some(self.renderer.read_image()?))
    }
}

/// Frames from the simulated renderer: a cost model driven by the corridor-shaped load.
pub struct SimulatedSource {
    pub renderer: SimRenderer,
}

impl FrameSource for SimulatedSource {
    fn describe(&self) -> (String, String) {
        let m = self.renderer.model();
        (
            "simulated".into(),
            format!(
                "cost model: {} ms + {} ns/ray, noise {}, timer {} ms",
                m.fixed_ms, m.ns_per_ray, m.noise, m.timer_ms
            ),
        )
    }

    fn resolution(&self) -> (u32, u32) {
        let pixels = self.renderer.model().full_pixels;
        let height = ((pixels as f64 * 9.0 / 16.0).sqrt().round() as u32).max(1);
        ((pixels / height as u64) as u32, height)
    }

    fn frame(&mut self, k: u32, n: u32, q: Quality) -> Result<Measured> {
        let report = self.renderer.render(k as usize, q);
        Ok(Measured {
            wall_ms: report.tp_ms,
            report,
            angle: std::f32::consts::TAU * k as f32 / n.max(1) as f32,
        })
    }

    fn load_changes(&self, n: u32) -> Option<Vec<usize>> {
        Some(self.renderer.model().profile.changes(n as usize))
    }

    fn last_image(&mut self) -> Result<Option<Image>> {
        Ok(None)
    }
}

/// A simulated source for an `n`-frame corridor sweep.
pub fn simulated(n: u32) -> SimulatedSource {
    SimulatedSource {
        renderer: SimRenderer::new(RendererModel::corridor(n as usize)),
    }
}
