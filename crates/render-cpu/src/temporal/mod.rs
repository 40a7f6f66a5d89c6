//! The CPU's temporal mode (`docs/temporal.md`): the history of a renderer, the frame's
//! geometry records, and the resolve that accumulates each frame into the history.

mod geometry;
mod resolve;
mod warp;

pub(crate) use geometry::{Geometry, GeometrySink};

use crate::simd::best_compiled;
use glam::Vec4;
use rayon::prelude::*;
use resolve::{Axis, Inputs, Prepared, PreparedRow, Preparing, Range, Seen};
use steadyray_render::sampling::samples_for_pixel;
use steadyray_render::surface_motion::SurfaceMove;
use steadyray_render::temporal::{HistoryClock, TemporalFrame, sharpen_strength, sharpened_within};
use steadyray_render::tonemap::linear_to_srgb8_fast;
use steadyray_render::{Image, Picture, TemporalSettings};
use steadyray_scene::camera::CameraFrame;

/// The picture of the `size` image `colour` (radiance and age per pixel) as the display
/// shows it: each pixel sharpened at strength `sharpen` (`temporal::sharpened`, its 3×3
/// neighbourhood read from the three rows around it, as `sharpened_image` does) when that
/// is above 0, then tone-mapped; a row at a time on the current rayon pool.
fn shown(colour: &[[f32; 4]], size: (u32, u32), sharpen: f32) -> Picture {
    let (width, height) = (size.0 as usize, size.1 as usize);
    let row = |y: usize| &colour[y * width..(y + 1) * width];
    let mut rgba = vec![255u8; 4 * width * height];
    rgba.par_chunks_mut(4 * width)
        .enumerate()
        .for_each(|(y, out)| {
            let rows = [
                row(y.saturating_sub(1)),
                row(y),
                row((y + 1).min(height - 1)),
            ];
            best_compiled(
                #[inline(always)]
                || shown_row(rows, sharpen, out),
            );
        });
    Picture {
        width: size.0,
        height: size.1,
        rgba,
    }
}

/// One row of [`shown`] (`out`, RGBA) from the rows above it, its own and the one below.
/// The 3×3 range of each pixel is the range of three column ranges, each column's taken
/// once for the three pixels that read it ([`sharpened_within`]).
#[inline(always)]
fn shown_row([above, here, below]: [&[[f32; 4]]; 3], sharpen: f32, out: &mut [u8]) {
    let width = here.len();
    let tap = |r: &[[f32; 4]], i: usize| Vec4::from_array(r[i]);
    let column = |x: usize| {
        let (a, h, b) = (tap(above, x), tap(here, x), tap(below, x));
        (a.min(h).min(b), a.max(h).max(b))
    };
    // The column ranges of x − 1, x and x + 1 (edges repeated).
    let mut columns = [column(0), column(0), column(1.min(width - 1))];
    for (x, pixel) in out.chunks_exact_mut(4).enumerate() {
        let c = if sharpen > 0.0 {
            if x > 0 {
                columns = [columns[1], columns[2], column((x + 1).min(width - 1))];
            }
            let lo = columns[0].0.min(columns[1].0).min(columns[2].0);
            let hi = columns[0].1.max(columns[1].1).max(columns[2].1);
            let (left, right) = (x.saturating_sub(1), (x + 1).min(width - 1));
            let cross = [
                tap(above, x),
                tap(here, left),
                tap(here, right),
                tap(below, x),
            ];
            sharpened_within(tap(here, x), cross, (lo, hi), sharpen)
        } else {
            tap(here, x)
        };
        for (channel, v) in pixel.iter_mut().zip([c.x, c.y, c.z]) {
            *channel = linear_to_srgb8_fast(v);
        }
    }
}

/// A renderer's temporal state: the history (radiance and age per pixel, and the geometry
/// it was made of), the frame being accumulated, and the clock that says which frame of
/// the history comes next.
pub(crate) struct History {
    pub clock: HistoryClock,
    /// The frame as rendered (its own size), then resolved into the history.
    pub low: Vec<[f32; 3]>,
    pub low_geometry: Vec<Geometry>,
    /// How each surface moved since the previous frame (while the world moves).
    pub moves: Vec<SurfaceMove>,
    /// What the resolve needs of each frame pixel, and of each history column and row.
    prepared: Vec<Prepared>,
    ranges: Vec<Range>,
    seen: Vec<Seen>,
    values: Vec<Vec4>,
    columns: Axis,
    rows: Axis,
    /// The history's radiance and age per pixel, and the frame pixel of the previous frame
    /// whose record is its geometry (`previous_geometry`).
    colour: Vec<[f32; 4]>,
    sources: Vec<u32>,
    previous_geometry: Vec<Geometry>,
    next_colour: Vec<[f32; 4]>,
    next_sources: Vec<u32>,
    /// Whether a frame was accumulated since the mode was set.
    accumulated: bool,
    /// The camera frame of the last frame accumulated (for the history's size).
    camera: Option<CameraFrame>,
    /// How strongly the last frame's history is sharpened for display ([`shown`],
    /// `sharpen_strength`: 0 when it did not resample the history).
    sharpen: f32,
    /// A warped refresh's motion field and picture before display, kept for the next warp.
    warp_motion: Vec<[f32; 2]>,
    warp_colour: Vec<[f32; 4]>,
}

impl History {
    /// An empty history of `settings`' size.
    pub fn new(settings: TemporalSettings) -> Self {
        let pixels = settings.width as usize * settings.height as usize;
        Self {
            clock: HistoryClock::new(settings),
            low: Vec::new(),
            low_geometry: Vec::new(),
            moves: Vec::new(),
            prepared: Vec::new(),
            ranges: Vec::new(),
            seen: Vec::new(),
            values: Vec::new(),
            columns: Axis::default(),
            rows: Axis::default(),
            colour: vec![[0.0; 4]; pixels],
            sources: vec![0; pixels],
            previous_geometry: Vec::new(),
            next_colour: vec![[0.0; 4]; pixels],
            next_sources: vec![0; pixels],
            accumulated: false,
            camera: None,
            sharpen: 0.0,
            warp_motion: Vec::new(),
            warp_colour: Vec::new(),
        }
    }

    /// Makes room for a `width` × `height` frame.
    pub fn prepare(&mut self, width: u32, height: u32) {
        let pixels = width as usize * height as usize;
        self.low.resize(pixels, [0.0; 3]);
        self.low_geometry.resize(pixels, Geometry::default());
        self.prepared.resize(pixels, Prepared::default());
        self.ranges.resize(pixels, Range::default());
        self.seen.resize(pixels, Seen::default());
        self.values.resize(pixels, Vec4::ZERO);
    }

    /// Accumulates the rendered frame (`low_size`, camera frame `camera` for the history's
    /// size) into the history, in parallel on the current rayon pool.
    pub fn resolve(&mut self, camera: CameraFrame, frame: TemporalFrame, low_size: (u32, u32)) {
        let settings = self.clock.settings();
        let size = (settings.width, settings.height);
        let preparing = Preparing {
            camera: &camera,
            frame: &frame,
            size,
            moves: &self.moves,
            low: &self.low,
            low_geometry: &self.low_geometry,
            low_size,
        };
        let low_w = low_size.0 as usize;
        self.prepared
            .par_chunks_mut(low_w)
            .zip(self.ranges.par_chunks_mut(low_w))
            .zip(self.seen.par_chunks_mut(low_w))
            .zip(self.values.par_chunks_mut(low_w))
            .enumerate()
            .for_each(|(y, (((prepared, ranges), seen), values))| {
                best_compiled(
                    #[inline(always)]
                    || {
                        let out = PreparedRow {
                            prepared,
                            ranges,
                            seen,
                            values,
                        };
                        preparing.row(y as u32, out)
                    },
                );
            });
        self.columns.fill(size.0, low_size.0, frame.anchor[0]);
        self.rows.fill(size.1, low_size.1, frame.anchor[1]);
        let inputs = Inputs {
            low: &self.low,
            prepared: &self.prepared,
            ranges: &self.ranges,
            seen: &self.seen,
            values: &self.values,
            low_size,
            columns: &self.columns,
            rows: &self.rows,
            history: &self.colour,
            sources: &self.sources,
            geometry: &self.previous_geometry,
            size,
            frame,
            counts: std::array::from_fn(|i| {
                samples_for_pixel(i as u32 % 8, i as u32 / 8, frame.spp) as f32
            }),
        };
        let width = settings.width as usize;
        self.next_colour
            .par_chunks_mut(width)
            .zip(self.next_sources.par_chunks_mut(width))
            .enumerate()
            .for_each(|(y, (colours, sources))| {
                inputs.resolve_row(y as u32, colours, sources);
            });
        std::mem::swap(&mut self.colour, &mut self.next_colour);
        std::mem::swap(&mut self.sources, &mut self.next_sources);
        std::mem::swap(&mut self.previous_geometry, &mut self.low_geometry);
        self.accumulated = true;
        self.camera = Some(camera);
        self.sharpen = sharpen_strength(&frame, low_size, size);
    }

    /// The accumulated image as the display shows it ([`shown`], on the current rayon
    /// pool), if a frame was accumulated.
    pub fn picture(&self) -> Option<Picture> {
        let settings = self.clock.settings();
        let size = (settings.width, settings.height);
        self.accumulated
            .then(|| shown(&self.colour, size, self.sharpen))
    }

    /// The accumulated image, if a frame was accumulated.
    pub fn image(&self) -> Option<Image> {
        let settings = self.clock.settings();
        self.accumulated.then(|| Image {
            width: settings.width,
            height: settings.height,
            pixels: self.colour.iter().map(|&[r, g, b, _]| [r, g, b]).collect(),
        })
    }
}
