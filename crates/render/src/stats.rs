//! What a rendered frame reports: its time and the exact rays it traced.

/// Rays traced in one frame, counted exactly.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// `per_depth[k]` = rays traced after k reflection/refraction events (k = 0: eye rays).
    /// Its length is R + 1 for a frame rendered with depth R.
    pub per_depth: Vec<u64>,
    /// Shadow rays toward point lights.
    pub shadow: u64,
    /// Chains the depth limit ended at a mirror or a dielectric: the rays a frame of depth
    /// R + 1 would trace at level R + 1 (not traced, not in [`RayCounts::total`]). The
    /// controllers see with it how far the next level reaches, which no ray of this frame
    /// could tell them.
    pub stopped: u64,
}

impl RayCounts {
    /// Zero counts for a frame of depth `max_depth`.
    pub fn zeros(max_depth: u32) -> Self {
        Self {
            per_depth: vec![0; max_depth as usize + 1],
            shadow: 0,
            stopped: 0,
        }
    }

    /// Eye, secondary and shadow rays together.
    pub fn total(&self) -> u64 {
        self.per_depth.iter().sum::<u64>() + self.shadow
    }

    /// Adds another count of the same depth (used to merge per-tile or per-workgroup counts).
    pub fn add(&mut self, other: &RayCounts) {
        if self.per_depth.len() < other.per_depth.len() {
            self.per_depth.resize(other.per_depth.len(), 0);
        }
        for (a, b) in self.per_depth.iter_mut().zip(&other.per_depth) {
            *a += b;
        }
        self.shadow += other.shadow;
        self.stopped += other.stopped;
    }
}

/// Where a frame's render time came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimingSource {
    /// GPU timestamp queries around the render dispatches.
    GpuTimestamps,
    /// The host's monotonic clock around the render (CPU backend, or GPUs without timestamps).
    WallClock,
}

/// The measurements of one rendered frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameStats {
    /// Tp: the image-generation time, in milliseconds, including `accel_ms`.
    pub render_ms: f64,
    /// The part of Tp spent placing the frame's objects and updating the top-level BVH
    /// (and, on the GPU, uploading it), ms; about 0 for a scene where nothing moves.
    pub accel_ms: f64,
    /// Host wall-clock time of the whole `render` call (submit and wait included), ms.
    pub wall_ms: f64,
    /// Where `render_ms` comes from.
    pub timing: TimingSource,
    /// The rays traced.
    pub rays: RayCounts,
    /// The frame's width in pixels.
    pub width: u32,
    /// The frame's height in pixels.
    pub height: u32,
    /// Eye samples actually taken (S × pixels, with fractional S dithered).
    pub samples: u64,
    /// The eye rays per pixel the frame took: the settings' S, or within a frame budget
    /// ([`crate::Renderer::set_frame_budget`]) the mean S it reached.
    pub spp: f32,
}

impl FrameStats {
    /// Rays per second over the render time.
    pub fn rays_per_second(&self) -> f64 {
        if self.render_ms > 0.0 {
            self.rays.total() as f64 / (self.render_ms * 1e-3)
        } else {
            0.0
        }
    }
}
