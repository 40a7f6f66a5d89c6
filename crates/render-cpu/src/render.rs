//! The parallel frame: rows of pixels as tiles, rendered on a rayon pool, with exact ray
//! counts summed per tile.

use crate::integrator::{PathSink, SampleId, trace};
use crate::ray::Ray;
use crate::temporal::{Geometry, GeometrySink};
use crate::world::World;
use glam::Vec3A;
use rayon::prelude::*;
use steadyray_budget::{UNIT_GROUPS, UNIT_SAMPLES, units_for_spp};
use steadyray_render::FrameBudget;
use steadyray_render::sampling::{dither_rank, samples_for_pixel};
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

/// The dither ranks of a unit's group of pixels: a sixteenth of the 64.
const RANKS_PER_GROUP: u32 = 64 / UNIT_GROUPS;

/// The side of the square tiles of pixels that units add samples to: whole tiles keep the
/// rays a thread traces one after another close together (a unit spread over single
/// pixels, eight apart, ran about a tenth slower).
const TILE: u32 = 8;

/// The most rows a thread takes at a time in a batch of units: a batch's rows differ a lot
/// in cost (a unit's tiles cover a quarter of the rows), and a thread left with a long
/// run of costly rows at the end of a batch keeps the other waiting.
const ROWS_PER_TASK: usize = 4;

/// The group of pixel (px, py): the dither rank of its tile, so units add samples to
/// tiles spread evenly over the image, group 0 first.
fn unit_group(px: u32, py: u32) -> u32 {
    dither_rank(px / TILE, py / TILE) / RANKS_PER_GROUP
}

/// Adds unit `unit`'s pair of samples to the pixels of its group in row `py`.
fn add_unit(
    unit: u32,
    py: u32,
    row: &mut [[f32; 3]],
    counts: &mut TileCounts,
    sample: &impl Fn(u32, u32, u32, &mut TileCounts) -> Vec3A,
) {
    let (pair, group) = (unit / UNIT_GROUPS, unit % UNIT_GROUPS);
    let width = row.len() as u32;
    for tile in (0..width.div_ceil(TILE)).filter(|&t| unit_group(t * TILE, py) == group) {
        for px in tile * TILE..((tile + 1) * TILE).min(width) {
            let out = &mut row[px as usize];
            let mut sum = Vec3A::from(*out);
            sum += sample(px, py, 2 * pair + 1, counts);
            sum += sample(px, py, 2 * pair + 2, counts);
            *out = sum.to_array();
        }
    }
}

/// Renders the frame a unit of samples at a time within `budget`
/// ([`FrameBudget::run_units`], `elapsed_ms` the frame's clock): the centre sample of every
/// pixel, then each unit a mirrored pair in the pixels of one group, summed in place in
/// `pixels`; at the end each pixel is the mean of the samples it took. A pixel's samples
/// are those a plain frame takes at an odd S, in the same order, so a frame that reaches
/// whole pairs in every pixel is the plain frame at that S bit for bit. Returns the counts.
/// `settings` must be valid.
pub(crate) fn render_frame_within(
    world: &World,
    frame: &CameraFrame,
    settings: &RenderSettings,
    pattern: SamplePattern,
    pixels: &mut [[f32; 3]],
    budget: &FrameBudget,
    elapsed_ms: impl Fn() -> f64,
) -> TileCounts {
    let width = settings.width as usize;
    let eye = Vec3A::from(frame.eye);
    let sample = |px: u32, py: u32, i: u32, counts: &mut TileCounts| {
        // Odd sample counts put sample 0 at the centre and pair the rest about it whatever
        // the count, so every pixel's i-th sample sits where it would at any odd S.
        let (u, v) = jittered_sample(i, u32::MAX, pattern.jitter, 0);
        let dir = Vec3A::from(frame.ray_dir(px, py, u, v, settings.width, settings.height));
        let id = SampleId {
            px,
            py,
            sample: i + pattern.sample_base,
        };
        trace(world, Ray::new(eye, dir), id, settings.max_depth, counts)
    };
    let mut counts = pixels
        .par_chunks_mut(width)
        .enumerate()
        .map(|(py, row)| {
            let mut counts = TileCounts::default();
            for (px, out) in (0u32..).zip(row.iter_mut()) {
                *out = sample(px, py as u32, 0, &mut counts).to_array();
            }
            counts
        })
        .reduce(TileCounts::default, TileCounts::merged);
    let units = budget.run_units(units_for_spp(settings.spp), elapsed_ms, |batch| {
        let added = pixels
            .par_chunks_mut(width)
            .enumerate()
            .with_max_len(ROWS_PER_TASK)
            .map(|(py, row)| {
                let mut counts = TileCounts::default();
                for unit in batch.clone() {
                    add_unit(unit, py as u32, row, &mut counts, &sample);
                }
                counts
            })
            .reduce(TileCounts::default, TileCounts::merged);
        counts = counts.merged(added);
    });
    let (pairs, partial) = (units / UNIT_GROUPS, units % UNIT_GROUPS);
    pixels
        .par_chunks_mut(width)
        .enumerate()
        .for_each(|(py, row)| {
            for (px, out) in (0u32..).zip(row.iter_mut()) {
                let extra = u32::from(unit_group(px, py as u32) < partial);
                let n = 1 + UNIT_SAMPLES * (pairs + extra);
                *out = (Vec3A::from(*out) / n as f32).to_array();
            }
        });
    counts
}
