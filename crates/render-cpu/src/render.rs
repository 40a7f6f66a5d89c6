//! The parallel frame: rows of pixels as tiles, rendered on a rayon pool, with exact ray
//! counts summed per tile.

use crate::integrator::{PathSink, SampleId, trace};
use crate::ray::Ray;
use crate::temporal::{Geometry, GeometrySink};
use crate::world::World;
use glam::Vec3A;
use rayon::prelude::*;
use steadyray_render::sampling::samples_for_pixel;
use steadyray_render::temporal::jittered_sample;
use steadyray_render::{MAX_DEPTH, RayCounts, RenderSettings};
use steadyray_scene::camera::CameraFrame;

/// Where a frame's samples go: the temporal mode's jitter and first branch sample index
/// (`docs/temporal.md`); zero outside it, which leaves the pattern of `docs/shading.md`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SamplePattern {
    pub jitter: [f32; 2],
    pub sample_base: u32,
    /// The frame's index in a still view (`TemporalFrame::still_frame`), else 0.
    pub still_frame: u32,
}

/// A frame's samples as its pixels draw them: their sub-pixel positions for the two sample
/// counts the pixels take (floor(S) and one more, `samples_for_pixel`), computed once per
/// frame (computed per sample, they took a tenth of an S = 8 frame), and the index of
/// sample 0's random numbers.
struct FrameSamples {
    fewer: u32,
    positions: [Vec<(f32, f32)>; 2],
    base: u32,
}

impl FrameSamples {
    /// The samples of a frame at `spp` (at least 1) drawn by `pattern`.
    fn new(spp: f32, pattern: SamplePattern) -> Self {
        let fewer = spp.floor() as u32;
        let table = |n: u32| {
            (0..n)
                .map(|i| jittered_sample(i, n, pattern.jitter, pattern.still_frame))
                .collect()
        };
        Self {
            fewer,
            positions: [table(fewer), table(fewer + 1)],
            base: pattern.sample_base,
        }
    }

    /// The positions of the samples of a pixel that takes `n` of them.
    #[inline]
    fn of(&self, n: u32) -> &[(f32, f32)] {
        &self.positions[(n - self.fewer) as usize]
    }
}

/// Ray counts of one tile: fixed size, so counting never allocates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TileCounts {
    per_depth: [u64; MAX_DEPTH as usize + 1],
    shadow: u64,
    stopped: u64,
}

impl Default for TileCounts {
    fn default() -> Self {
        Self {
            per_depth: [0; MAX_DEPTH as usize + 1],
            shadow: 0,
            stopped: 0,
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
        self.stopped += other.stopped;
        self
    }

    /// The frame's counts for depth `max_depth` (per_depth has R + 1 entries).
    pub fn ray_counts(&self, max_depth: u32) -> RayCounts {
        RayCounts {
            per_depth: self.per_depth[..=max_depth as usize].to_vec(),
            shadow: self.shadow,
            stopped: self.stopped,
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

    #[inline]
    fn stopped(&mut self) {
        self.stopped += 1;
    }
}

/// The frame's outputs: radiance per pixel, and in the temporal mode the geometry record of
/// each pixel's sample 0; both row-major, `settings.width` wide.
pub(crate) struct FrameOutputs<'a> {
    pub pixels: &'a mut [[f32; 3]],
    pub geometry: Option<&'a mut [Geometry]>,
}

/// Renders every pixel of the frame in parallel on the current rayon pool. `settings` must
/// be valid.
pub(crate) fn render_frame(
    world: &World,
    frame: &CameraFrame,
    settings: &RenderSettings,
    pattern: SamplePattern,
    outputs: FrameOutputs<'_>,
) -> TileCounts {
    let width = settings.width as usize;
    let samples = FrameSamples::new(settings.spp, pattern);
    let render = |py: usize, row: &mut [[f32; 3]], geometry: Option<&mut [Geometry]>| {
        let mut counts = TileCounts::default();
        let row = Row {
            py: py as u32,
            pixels: row,
            geometry,
        };
        render_row(world, frame, settings, &samples, row, &mut counts);
        counts
    };
    let rows = outputs.pixels.par_chunks_mut(width).enumerate();
    match outputs.geometry {
        Some(geometry) => rows
            .zip(geometry.par_chunks_mut(width))
            .map(|((py, row), g)| render(py, row, Some(g)))
            .reduce(TileCounts::default, TileCounts::merged),
        None => rows
            .map(|(py, row)| render(py, row, None))
            .reduce(TileCounts::default, TileCounts::merged),
    }
}

/// One row of a frame's outputs.
struct Row<'a> {
    py: u32,
    pixels: &'a mut [[f32; 3]],
    geometry: Option<&'a mut [Geometry]>,
}

/// One row of pixels: each pixel is the mean radiance of its eye samples; sample 0 records
/// the pixel's geometry when asked to.
fn render_row(
    world: &World,
    frame: &CameraFrame,
    settings: &RenderSettings,
    samples: &FrameSamples,
    mut row: Row<'_>,
    counts: &mut TileCounts,
) {
    let (width, height) = (settings.width, settings.height);
    let eye = Vec3A::from(frame.eye);
    let py = row.py;
    for (px, out) in (0u32..).zip(row.pixels.iter_mut()) {
        let n = samples_for_pixel(px, py, settings.spp);
        let mut sum = Vec3A::ZERO;
        for (sample, &(u, v)) in (0u32..).zip(samples.of(n)) {
            let dir = Vec3A::from(frame.ray_dir(px, py, u, v, width, height));
            let id = SampleId {
                px,
                py,
                sample: sample + samples.base,
            };
            let ray = Ray::new(eye, dir);
            let depth = settings.max_depth;
            sum += match row.geometry.as_deref_mut() {
                Some(geometry) if sample == 0 => {
                    let mut sink = GeometrySink::new(counts, world, eye, dir);
                    let radiance = trace(world, ray, id, depth, &mut sink);
                    geometry[px as usize] = sink.finish();
                    radiance
                }
                _ => trace(world, ray, id, depth, counts),
            };
        }
        *out = (sum / n as f32).to_array();
    }
}
