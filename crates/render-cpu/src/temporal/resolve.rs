//! The per-pixel resolve of `docs/temporal.md`: find the frame's sample that lands in the
//! pixel, reproject the history by that sample's point, keep the taps whose surface is still
//! seen around the pixel, filter them, clamp to the frame's local colour range and blend (a
//! still camera keeps the history as it is). The arithmetic is `temporal.wgsl`'s operation
//! for operation, so both round alike. What the GPU computes per history pixel the CPU
//! computes once per frame pixel (the sample's motion, [`Prepared`]; its neighbourhood's
//! colour range, [`Range`]; its surface as the neighbourhood test reads it, [`Seen`]) or once
//! per row and column ([`Axis`]), and it tests a tap against the neighbourhood's centre
//! first; none of that changes a result.

use super::geometry::Geometry;
use glam::Vec4;
use steadyray_render::surface_motion::SurfaceMove;
use steadyray_render::temporal::{
    APPROX_FLAG, HISTORY_CAP, ID_MASK, MIRROR_FLAG, NORMAL_COS, PLANE_TOLERANCE, SPECULAR_CAP,
    STILL_CAP, TemporalFrame, catmull_rom, centre_weight, covering, dot3, floor, landed_from,
    project4, splat_weight,
};
use steadyray_scene::camera::CameraFrame;

/// What the resolve needs of one frame pixel besides its colour, record and
/// [`centre_value`] (whose fourth lane says whether the colour is finite).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Prepared {
    /// Where its record's point was in the previous frame minus where it is now, in history
    /// pixels; None when either position is behind its camera or its surface is new.
    motion: Option<[f32; 2]>,
    /// Its record's tag (whose flags set the pixel's cap).
    tag: u32,
}

/// The per-channel range of the finite colours of a frame pixel's 3×3 neighbourhood (those
/// inside the frame); (−∞, +∞) when none is finite, which leaves a finite colour as it is.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Range {
    lo: [f32; 3],
    hi: [f32; 3],
}

impl Default for Range {
    fn default() -> Self {
        Self {
            lo: [f32::NEG_INFINITY; 3],
            hi: [f32::INFINITY; 3],
        }
    }
}

/// A frame pixel's surface as the neighbourhood test reads it: its record's point and normal
/// as they were in the previous frame (moved back with its object), the plane tolerance at
/// its distance from the previous eye, and its id.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(32))]
pub(crate) struct Seen {
    q: [f32; 3],
    tolerance: f32,
    n: [f32; 3],
    /// The surface id; with [`DIRECTION`] set for a direction (a miss: the id alone
    /// decides), and [`NOT_SEEN`] for a surface that did not exist in the previous frame.
    key: u32,
}

/// [`Seen::key`]'s bit for a record that is a direction.
const DIRECTION: u32 = 0x4000_0000;
/// [`Seen::key`] of a surface that matches no tap (no id has bit 31).
const NOT_SEEN: u32 = 0x8000_0000;

impl Seen {
    /// Whether the history's surface `old` is this one as it was in the previous frame: the
    /// same surface id and, for a point, within the tolerance of its tangent plane and
    /// facing alike.
    #[inline(always)]
    fn sees(&self, old: &Geometry) -> bool {
        if self.key & !DIRECTION != old.tag & ID_MASK {
            return false;
        }
        if self.key & DIRECTION != 0 {
            return true;
        }
        let off = [
            old.q[0] - self.q[0],
            old.q[1] - self.q[1],
            old.q[2] - self.q[2],
        ];
        dot3(off, self.n).abs() <= self.tolerance && dot3(self.n, old.n) >= NORMAL_COS
    }
}

/// For each history column (or row): the frame column covering its centre, the frame
/// column landing in it (`u32::MAX` for none), the covering column's tent weight there
/// (`splat_weight`), and the weights that read the frame at its centre ([`Centre`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Axis {
    covering: Vec<u32>,
    landed: Vec<u32>,
    splat: Vec<f32>,
    centre: Vec<Centre>,
}

/// The `centre_weight`s at a history column's centre of the frame columns landed − 1,
/// landed and landed + 1 (0 outside the frame or where none lands): `w[0]` for samples at
/// the anchor (a pixel of one sample), `w[1]` at the pixel's centre (two or more); bit j of
/// `live` is set where either weight of column j is not 0.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Centre {
    w: [[f32; 3]; 2],
    live: u8,
}

impl Axis {
    /// The table of a history axis of `full` pixels for a frame axis of `low` and `anchor`.
    pub fn fill(&mut self, full: u32, low: u32, anchor: f32) {
        self.covering.clear();
        self.covering
            .extend((0..full).map(|x| covering(x, full, low)));
        self.landed.clear();
        self.landed
            .extend((0..full).map(|x| landed_from(x, anchor, full, low).unwrap_or(u32::MAX)));
        self.splat.clear();
        self.splat.extend(
            self.covering
                .iter()
                .zip(0..full)
                .map(|(&c, x)| splat_weight(x, c, full, low)),
        );
        self.centre.clear();
        self.centre
            .extend(self.landed.iter().zip(0..full).map(|(&landed, x)| {
                let w = [anchor, 0.5].map(|at| {
                    [0, 1, 2].map(|k| {
                        let s = landed.wrapping_add(k).wrapping_sub(1);
                        if landed != u32::MAX && s < low {
                            centre_weight(x, s, at, full, low)
                        } else {
                            0.0
                        }
                    })
                });
                let live = (0..3)
                    .filter(|&j| w[0][j] != 0.0 || w[1][j] != 0.0)
                    .fold(0, |live, j| live | 1 << j);
                Centre { w, live }
            }));
    }
}

/// What [`Preparing::row`] reads: the frame, its camera and how its surfaces moved.
pub(crate) struct Preparing<'a> {
    pub camera: &'a CameraFrame,
    pub frame: &'a TemporalFrame,
    /// The history's size.
    pub size: (u32, u32),
    pub moves: &'a [SurfaceMove],
    /// The frame: `low_size` pixels of radiance and geometry.
    pub low: &'a [[f32; 3]],
    pub low_geometry: &'a [Geometry],
    pub low_size: (u32, u32),
}

/// Everything the resolve of one frame reads.
pub(crate) struct Inputs<'a> {
    /// The frame as rendered: `low_size` pixels of radiance and geometry, and what
    /// [`Preparing::row`] made of them.
    pub low: &'a [[f32; 3]],
    pub prepared: &'a [Prepared],
    pub ranges: &'a [Range],
    pub seen: &'a [Seen],
    /// Each frame pixel's [`centre_value`].
    pub values: &'a [Vec4],
    pub low_size: (u32, u32),
    pub columns: &'a Axis,
    pub rows: &'a Axis,
    /// The history before this frame: `size` pixels of (radiance, age), and of the index of
    /// their geometry record in the previous frame's records `geometry`.
    pub history: &'a [[f32; 4]],
    pub sources: &'a [u32],
    pub geometry: &'a [Geometry],
    pub size: (u32, u32),
    pub frame: TemporalFrame,
    /// A frame pixel's sample count, `samples_for_pixel` at the frame's S, by the pixel's
    /// place (x mod 8, y mod 8) in the 8×8 dither that sets it: element 8 · (y mod 8) +
    /// (x mod 8).
    pub counts: [f32; 64],
}

/// How the surface of record `g` moved since the previous frame: a surface seen directly in
/// a world that moved follows its object; anything else is taken as still (seen through a
/// mirror, its image does not follow its object: that is left to the cap and the clamp).
#[inline]
pub(crate) fn move_of(g: &Geometry, frame: &TemporalFrame, moves: &[SurfaceMove]) -> SurfaceMove {
    if !frame.world_moved || g.q[3] == 0.0 || g.tag & MIRROR_FLAG != 0 {
        return SurfaceMove::Still;
    }
    moves
        .get((g.tag & ID_MASK) as usize)
        .copied()
        .unwrap_or_default()
}

/// Whether every channel is finite.
#[inline]
fn finite(c: [f32; 3]) -> bool {
    c.iter().all(|v| v.is_finite())
}

/// A frame colour as the read at a history pixel's centre sums it ([`Inputs::at_centre`]):
/// (r, g, b, 1), so that one sum of weighted values is both the weighted colour and the sum
/// of the weights; zero where a channel is not finite, which adds +0 to both, as skipping
/// the pixel would.
#[inline]
fn centre_value(c: [f32; 3]) -> Vec4 {
    if finite(c) {
        Vec4::new(c[0], c[1], c[2], 1.0)
    } else {
        Vec4::ZERO
    }
}

/// One frame row of what [`Preparing::row`] makes.
pub(crate) struct PreparedRow<'a> {
    pub prepared: &'a mut [Prepared],
    pub ranges: &'a mut [Range],
    pub seen: &'a mut [Seen],
    pub values: &'a mut [Vec4],
}

impl Preparing<'_> {
    /// What the resolve needs of frame row `y`: each pixel's [`Prepared`], [`Range`],
    /// [`Seen`] and centre value ([`centre_value`]), four pixels at a time.
    #[inline(always)]
    pub fn row(&self, y: u32, out: PreparedRow<'_>) {
        let PreparedRow {
            prepared,
            ranges,
            seen,
            values,
        } = out;
        let start = (y * self.low_size.0) as usize;
        self.ranges(y, ranges);
        let fours = prepared.chunks_mut(4).zip(seen.chunks_mut(4));
        for (k, ((prepared, seen), values)) in fours.zip(values.chunks_mut(4)).enumerate() {
            self.four(start + 4 * k, prepared, seen, values);
        }
    }

    /// [`Preparing::row`] of the (up to) four frame pixels from `first`: the points moved
    /// back per pixel, then projected and measured four lanes at once (each lane's
    /// arithmetic is the scalar's, so it rounds alike).
    #[inline(always)]
    fn four(
        &self,
        first: usize,
        prepared: &mut [Prepared],
        seen: &mut [Seen],
        values: &mut [Vec4],
    ) {
        let records = &self.low_geometry[first..first + prepared.len()];
        // Component-major: q[c][lane].
        let mut q = [[0.0f32; 4]; 4];
        let mut q_before = [[0.0f32; 4]; 4];
        let mut n_before = [[0.0f32; 3]; 4];
        let mut existed = [false; 4];
        for (lane, g) in records.iter().enumerate() {
            let point = [g.q[0], g.q[1], g.q[2]];
            let (previous_q, previous_n, is_old) = match move_of(g, self.frame, self.moves) {
                SurfaceMove::Still => (point, g.n, true),
                SurfaceMove::Moved(map) => (map.point(point), map.normal(g.n), true),
                SurfaceMove::New => (point, g.n, false),
            };
            for (component, &v) in q.iter_mut().zip(&g.q) {
                component[lane] = v;
            }
            for (component, &v) in q_before.iter_mut().zip(&previous_q) {
                component[lane] = v;
            }
            q_before[3][lane] = g.q[3];
            n_before[lane] = previous_n;
            existed[lane] = is_old;
        }
        let lanes = |v: &[[f32; 4]; 4]| {
            [
                Vec4::from_array(v[0]),
                Vec4::from_array(v[1]),
                Vec4::from_array(v[2]),
                Vec4::from_array(v[3]),
            ]
        };
        let (q, q_before) = (lanes(&q), lanes(&q_before));
        let (motion, distance) = match &self.frame.previous {
            Some(previous) => {
                let (bx, by, b_ok) = project4(previous, q_before, self.size);
                let (nx, ny, n_ok) = project4(self.camera, q, self.size);
                let eye = previous.eye.to_array();
                (
                    Some((bx - nx, by - ny, b_ok & n_ok)),
                    distance4(q_before, eye),
                )
            }
            None => (None, distance4(q_before, [0.0; 3])),
        };
        let pixels = prepared.iter_mut().zip(seen).zip(values).zip(records);
        for (lane, (((p, s), value), g)) in pixels.enumerate() {
            let motion = match motion {
                Some((mx, my, ok)) if existed[lane] && ok.test(lane) => Some([mx[lane], my[lane]]),
                _ => None,
            };
            *value = centre_value(self.low[first + lane]);
            *p = Prepared { motion, tag: g.tag };
            let id = g.tag & ID_MASK;
            *s = Seen {
                q: [q_before[0][lane], q_before[1][lane], q_before[2][lane]],
                tolerance: PLANE_TOLERANCE * distance[lane],
                n: n_before[lane],
                key: match (existed[lane], g.q[3] == 0.0) {
                    (false, _) => NOT_SEEN,
                    (true, true) => id | DIRECTION,
                    (true, false) => id,
                },
            };
        }
    }

    /// The colour ranges of frame row `y`: the minimum and maximum of each column's finite
    /// colours over rows y − 1 to y + 1, then over columns x − 1 to x + 1 (no frame colour
    /// is −0, a sum from +0 of non-negative terms, so the order cannot change a bit).
    #[inline]
    fn ranges(&self, y: u32, ranges: &mut [Range]) {
        let (low_w, low_h) = (self.low_size.0 as usize, self.low_size.1);
        let (first, last) = (y.saturating_sub(1), (y + 1).min(low_h - 1));
        let rows = &self.low[first as usize * low_w..(last as usize + 1) * low_w];
        let column = |x: usize| {
            rows.chunks_exact(low_w)
                .fold((Vec4::INFINITY, Vec4::NEG_INFINITY), |(lo, hi), row| {
                    let [r, g, b] = row[x];
                    let c = Vec4::new(r, g, b, 0.0);
                    if c.is_finite_mask().all() {
                        (lo.min(c), hi.max(c))
                    } else {
                        (lo, hi)
                    }
                })
        };
        let mut before = column(0);
        let mut here = before;
        for (x, range) in ranges.iter_mut().enumerate() {
            let after = if x + 1 < low_w { column(x + 1) } else { here };
            let lo = before.0.min(here.0).min(after.0);
            let hi = before.1.max(here.1).max(after.1);
            *range = if lo.x == f32::INFINITY {
                Range::default()
            } else {
                Range {
                    lo: [lo.x, lo.y, lo.z],
                    hi: [hi.x, hi.y, hi.z],
                }
            };
            (before, here) = (here, after);
        }
    }
}

/// The distances |q − eye| of four points (lanes of x, y, z).
#[inline]
fn distance4(q: [Vec4; 4], eye: [f32; 3]) -> Vec4 {
    let d = [q[0] - eye[0], q[1] - eye[1], q[2] - eye[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// Where a pixel's history lies in the history before this frame: the first of its four
/// bilinear taps (ix, iy), the fractions past it and the taps' weights.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Reprojection {
    ix: i32,
    iy: i32,
    fx: f32,
    fy: f32,
    bilinear: [f32; 4],
}

impl Inputs<'_> {
    /// The new history of row `y` (`colours`), and the frame pixel whose record is each
    /// pixel's geometry (`sources`).
    pub fn resolve_row(&self, y: u32, colours: &mut [[f32; 4]], sources: &mut [u32]) {
        let width = self.size.0 as usize;
        let low_w = self.low_size.0;
        let (cy, ly) = (self.rows.covering[y as usize], self.rows.landed[y as usize]);
        let row_splat = self.rows.splat[y as usize];
        let frame = &self.frame;
        let history_row = &self.history[y as usize * width..][..width];
        let columns = (self.columns.covering.iter())
            .zip(&self.columns.landed)
            .zip(&self.columns.splat);
        let pixels = columns
            .zip(colours.iter_mut().zip(sources))
            .zip(history_row);
        for (x, ((((&cx, &lx), &column_splat), (colour, source)), old)) in pixels.enumerate() {
            let landed = lx != u32::MAX && ly != u32::MAX;
            let (sx, sy) = if landed { (lx, ly) } else { (cx, cy) };
            *source = sy * low_w + sx;
            let sample = &self.prepared[*source as usize];
            let current_ok = self.values[*source as usize].w != 0.0;
            let c = if landed && !frame.still && current_ok {
                self.at_centre(
                    sx,
                    sy,
                    &self.columns.centre[x],
                    &self.rows.centre[y as usize],
                )
            } else {
                self.low[*source as usize]
            };
            let n = self.count_at(sx, sy);
            // The frame's weight here (`docs/temporal.md`, the splat rule).
            let weight = if landed {
                1.0
            } else if !frame.still && n >= 2.0 {
                column_splat * row_splat
            } else {
                0.0
            };
            let fresh = weight > 0.0 && current_ok;
            let m = n * weight;
            let history = if frame.still {
                Some(([old[0], old[1], old[2]], old[3]))
            } else if frame.previous.is_some() {
                self.reprojected(x as u32, y, (cx, cy), sample)
            } else {
                None
            };
            let approx = sample.tag & APPROX_FLAG != 0;
            let mirrored = sample.tag & MIRROR_FLAG != 0;
            let cap = if frame.still {
                STILL_CAP * n
            } else if (approx && (frame.eye_moved || frame.world_moved))
                || (mirrored && frame.world_moved)
            {
                SPECULAR_CAP
            } else {
                HISTORY_CAP
            };
            *colour = match (history, fresh) {
                (Some((h, age)), true) => {
                    let a = age.min(cap);
                    let alpha = m / (a + m);
                    [
                        h[0] + (c[0] - h[0]) * alpha,
                        h[1] + (c[1] - h[1]) * alpha,
                        h[2] + (c[2] - h[2]) * alpha,
                        a + m,
                    ]
                }
                (Some((h, age)), false) => [h[0], h[1], h[2], age.min(cap)],
                (None, true) => [c[0], c[1], c[2], m],
                (None, false) if current_ok => [c[0], c[1], c[2], 0.0],
                (None, false) => [0.0; 4],
            };
        }
    }

    /// The frame at the centre of a history pixel where frame pixel (sx, sy) lands, in a
    /// moving frame: the finite colours of the 3×3 frame pixels around it (those inside the
    /// frame, row by row), each weighted by the `centre_weight`s of its samples' centroid
    /// (`column` and `row`: the landed axis tables), over the sum of the weights. A pixel
    /// whose weight is 0, or whose colour is not finite ([`centre_value`]), adds +0 to the
    /// sums: the same bits as the GPU, which adds a zero weight's +0 and skips a colour that
    /// is not finite. Rows and columns whose weights are all 0 are skipped, which leaves four
    /// of the nine at most. The weights are summed in the values' fourth lane.
    #[inline]
    fn at_centre(&self, sx: u32, sy: u32, column: &Centre, row: &Centre) -> [f32; 3] {
        let low_w = self.low_size.0;
        let mut sum = Vec4::ZERO;
        for k in (0..3).filter(|k| row.live & 1 << k != 0) {
            let ny = (sy + k as u32).wrapping_sub(1);
            for j in (0..3).filter(|j| column.live & 1 << j != 0) {
                let nx = (sx + j as u32).wrapping_sub(1);
                // The anchor's weights for a pixel of one sample, the centre's for more.
                let at = usize::from(self.count_at(nx, ny) >= 2.0);
                let w = column.w[at][j] * row.w[at][k];
                sum += w * self.values[(ny * low_w + nx) as usize];
            }
        }
        if sum.w > 0.0 {
            let c = sum / sum.w;
            [c.x, c.y, c.z]
        } else {
            self.low[(sy * low_w + sx) as usize]
        }
    }

    /// The samples of frame pixel (x, y), from the 8×8 table [`Inputs::counts`].
    #[inline]
    fn count_at(&self, x: u32, y: u32) -> f32 {
        self.counts[((y & 7) * 8 + (x & 7)) as usize]
    }

    /// The reprojected, filtered and clamped history of pixel (x, y) of a moving frame,
    /// whose sample is `sample` and whose neighbourhood is around frame pixel `centre`:
    /// where the sample was in the previous frame, which of the four taps there are still
    /// seen around the pixel, and their filter clamped to the neighbourhood's range.
    #[inline]
    fn reprojected(
        &self,
        x: u32,
        y: u32,
        (cx, cy): (u32, u32),
        sample: &Prepared,
    ) -> Option<([f32; 3], f32)> {
        let r = self.reproject(x, y, sample)?;
        let centre = (cy * self.low_size.0 + cx) as usize;
        let kept = self.kept_taps(cx, cy, centre, &r);
        let (colour, age) = self.filtered(&r, kept)?;
        let Range { lo, hi } = self.ranges[centre];
        Some(([0, 1, 2].map(|i| colour[i].max(lo[i]).min(hi[i])), age))
    }

    /// Where the history of pixel (x, y), whose frame sample is `sample`, lies in the
    /// history before this frame; None where it has none (a new surface, behind a camera,
    /// outside the history).
    #[inline]
    fn reproject(&self, x: u32, y: u32, sample: &Prepared) -> Option<Reprojection> {
        let (width, height) = self.size;
        let motion = sample.motion?;
        let bx = x as f32 + motion[0];
        let by = y as f32 + motion[1];
        if !(bx >= -1.0 && bx < width as f32 && by >= -1.0 && by < height as f32) {
            return None;
        }
        let (fx0, fy0) = (floor(bx), floor(by));
        let (fx, fy) = (bx - fx0, by - fy0);
        Some(Reprojection {
            ix: fx0 as i32,
            iy: fy0 as i32,
            fx,
            fy,
            bilinear: [
                (1.0 - fx) * (1.0 - fy),
                fx * (1.0 - fy),
                (1.0 - fx) * fy,
                fx * fy,
            ],
        })
    }

    /// Which of the four taps of `r` lie in the history and hold a surface that the frame's
    /// pixels around (cx, cy) (frame pixel `centre`) still see (bit t for tap t).
    #[inline]
    fn kept_taps(&self, cx: u32, cy: u32, centre: usize, r: &Reprojection) -> u8 {
        let (width, height) = (self.size.0 as i32, self.size.1 as i32);
        let centre = &self.seen[centre];
        if r.ix >= 0 && r.iy >= 0 && r.ix + 1 < width && r.iy + 1 < height {
            let (first, w) = ((r.iy * width + r.ix) as usize, width as usize);
            return self.tap_kept(cx, cy, centre, first)
                | self.tap_kept(cx, cy, centre, first + 1) << 1
                | self.tap_kept(cx, cy, centre, first + w) << 2
                | self.tap_kept(cx, cy, centre, first + w + 1) << 3;
        }
        let mut kept = 0;
        for t in 0..4 {
            let (tx, ty) = (r.ix + (t & 1), r.iy + (t >> 1));
            if tx >= 0 && ty >= 0 && tx < width && ty < height {
                kept |= self.tap_kept(cx, cy, centre, (ty * width + tx) as usize) << t;
            }
        }
        kept
    }

    /// 1 if the surface of history pixel `i` is one the frame's pixels around (cx, cy) see
    /// (`centre` is (cx, cy)'s, asked first as the likeliest), else 0.
    #[inline(always)]
    fn tap_kept(&self, cx: u32, cy: u32, centre: &Seen, i: usize) -> u8 {
        let old = &self.geometry[self.sources[i] as usize];
        u8::from(centre.sees(old) || self.seen_around(cx, cy, old))
    }

    /// The history at `r` from the `kept` taps: the Catmull–Rom filter when all four are
    /// kept and its window lies in the history, else the kept taps' bilinear average; the
    /// age is the kept taps' bilinear average. None when no tap is kept or the colour is not
    /// finite.
    #[inline]
    fn filtered(&self, r: &Reprojection, kept: u8) -> Option<([f32; 3], f32)> {
        let (width, height) = (self.size.0 as i32, self.size.1 as i32);
        let mut weight = 0.0f32;
        // Colour and age, summed alike lane by lane.
        let mut sum = Vec4::ZERO;
        let (first, w) = (r.iy * width + r.ix, width);
        for (t, (offset, &b)) in [0, 1, w, w + 1].into_iter().zip(&r.bilinear).enumerate() {
            if kept & (1 << t) != 0 {
                weight += b;
                sum += b * Vec4::from_array(self.history[(first + offset) as usize]);
            }
        }
        if weight <= 0.0 {
            return None;
        }
        let (ix, iy) = (r.ix, r.iy);
        let inside = ix >= 1 && iy >= 1 && ix + 2 < width && iy + 2 < height;
        let colour = if kept == 0b1111 && inside {
            self.catmull_rom(ix, iy, r.fx, r.fy)
        } else {
            [sum.x / weight, sum.y / weight, sum.z / weight]
        };
        finite(colour).then_some((colour, sum.w / weight))
    }

    /// Whether the history's surface `old` is one that the frame's pixels around (cx, cy),
    /// other than (cx, cy) itself, see: asked only where (cx, cy) does not, which is rare.
    #[cold]
    #[inline(never)]
    fn seen_around(&self, cx: u32, cy: u32, old: &Geometry) -> bool {
        let (low_w, low_h) = self.low_size;
        let (x0, x1) = (cx.saturating_sub(1), (cx + 1).min(low_w - 1));
        (cy.saturating_sub(1)..=(cy + 1).min(low_h - 1)).any(|ny| {
            let row = &self.seen[(ny * low_w + x0) as usize..=(ny * low_w + x1) as usize];
            let skip = if ny == cy {
                (cx - x0) as usize
            } else {
                usize::MAX
            };
            row.iter()
                .enumerate()
                .any(|(k, s)| k != skip && s.sees(old))
        })
    }

    /// The history's Catmull–Rom filter over the 4×4 pixels from (ix − 1, iy − 1) at
    /// fractions (fx, fy) past (ix, iy): rows first, then the column (the age lane is
    /// summed alike and dropped).
    #[inline]
    fn catmull_rom(&self, ix: i32, iy: i32, fx: f32, fy: f32) -> [f32; 3] {
        let (wx, wy) = (catmull_rom(fx), catmull_rom(fy));
        let width = self.size.0 as usize;
        let first = (iy - 1) as usize * width + (ix - 1) as usize;
        let mut sum = Vec4::ZERO;
        for (b, &wb) in wy.iter().enumerate() {
            let row = &self.history[first + b * width..][..4];
            let mut line = Vec4::ZERO;
            for (h, &wa) in row.iter().zip(&wx) {
                line += wa * Vec4::from_array(*h);
            }
            sum += wb * line;
        }
        [sum.x, sum.y, sum.z]
    }
}
