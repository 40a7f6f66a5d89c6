//! The parallel frame: rows of pixels as tiles, rendered on a rayon pool, with exact ray
//! counts summed per tile.

use crate::integrator::{PathSink, SampleId, trace};
use crate::ray::Ray;
use crate::world::World;
use glam::Vec3A;
use rayon::prelude::*;
use steadyray_render::sampling::{sample_offset, samples_for_pixel};
use steadyray_render::{MAX_DEPTH, RayCounts, RenderSettings};
use steadyray_scene::camera::CameraFrame;

/// Ray counts of one tile: fixed size, so counting never allocates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TileCounts {
    per_depth: [u64; MAX_DEPTH as usize + 1],
    shadow: u64,
}

impl Default for TileCounts {
    fn default() -> Self {
        Self {
            per_depth: [0; MAX_DEPTH as usize + 1],
            shadow: 0,
        }
    }
}

impl TileCounts {
    /// The sum of two tiles' counts.
    fn merged(mut self, other: Self) -> Self {
        for (a, b) in self.per_depth.iter_mut().zip(other.per_depth) {
            *a += b;
        }
        self.shadow += other.shadow;
        self
    }

    /// The frame's counts for depth `max_depth` (per_depth has R + 1 entries).
    pub fn ray_counts(&self, max_depth: u32) -> RayCounts {
        RayCounts {
            per_depth: self.per_depth[..=max_depth as usize].to_vec(),
            shadow: self.shadow,
        }
    }
}

impl PathSink for TileCounts {
    #[inline]
    fn ray(&mut self, depth: u32, _ray: &Ray) {
        self.per_depth[depth as usize] += 1;
    }

    #[inline]
    fn shadow_ray(&mut self) {
        self.shadow += 1;
    }
}

/// Renders every pixel of `pixels` (row-major, `settings.width` wide) in parallel on the
/// current rayon pool. `settings` must be valid.
pub(crate) fn render_frame(
    world: &World,
    frame: &CameraFrame,
    settings: &RenderSettings,
    pixels: &mut [[f32; 3]],
) -> TileCounts {
    let width = settings.width as usize;
    pixels
        .par_chunks_mut(width)
        .enumerate()
        .map(|(py, row)| {
            let mut counts = TileCounts::default();
            render_row(world, frame, settings, py as u32, row, &mut counts);
            counts
        })
        .reduce(TileCounts::default, TileCounts::merged)
}

/// One row of pixels: each pixel is the mean radiance of its eye samples.
fn render_row(
    world: &World,
    frame: &CameraFrame,
    settings: &RenderSettings,
    py: u32,
    row: &mut [[f32; 3]],
    counts: &mut TileCounts,
) {
    let (width, height) = (settings.width, settings.height);
    let eye = Vec3A::from(frame.eye);
    for (px, out) in (0u32..).zip(row.iter_mut()) {
        let n = samples_for_pixel(px, py, settings.spp);
        let mut sum = Vec3A::ZERO;
        for sample in 0..n {
            let (u, v) = sample_offset(sample, n);
            let dir = frame.ray_dir(px, py, u, v, width, height);
            let id = SampleId { px, py, sample };
            sum += trace(
                world,
                Ray::new(eye, dir.into()),
                id,
                settings.max_depth,
                counts,
            );
        }
        *out = (sum / n as f32).to_array();
    }
}
