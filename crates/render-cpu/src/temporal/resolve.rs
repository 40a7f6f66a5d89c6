//! The per-pixel resolve of `docs/temporal.md`: find the frame's sample that lands in the
//! pixel, reproject the history by that sample's point, keep the taps whose surface is still
//! seen around the pixel, filter them, clamp to the frame's local colour range and blend (a
//! still camera keeps the history as it is). The arithmetic is `temporal.wgsl`'s operation
//! for operation, so both round alike; what the GPU computes per history pixel the CPU
//! computes once per frame pixel or once per row and column ([`Prepared`], [`Axis`]), which
//! changes no result.

use super::geometry::Geometry;
use steadyray_render::surface_motion::SurfaceMove;
use steadyray_render::temporal::{
    APPROX_FLAG, HISTORY_CAP, ID_MASK, MIRROR_FLAG, NORMAL_COS, PLANE_TOLERANCE, SPECULAR_CAP,
    STILL_CAP, TemporalFrame, catmull_rom, covering, dot3, floor, landed_from, project,
};
use steadyray_scene::camera::CameraFrame;

/// What the resolve needs of one frame pixel besides its colour and record.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Prepared {
    /// Where its record's point was in the previous frame minus where it is now, in history
    /// pixels; None when either position is behind its camera or its surface is new.
    motion: Option<[f32; 2]>,
    /// Its record's point and normal as they were in the previous frame (moved back with
    /// its object), and the point's distance from the previous eye.
    previous_q: [f32; 3],
    previous_n: [f32; 3],
    distance: f32,
    /// Whether its surface existed in the previous frame.
    existed: bool,
    /// Whether its colour is finite.
    finite: bool,
}

/// For each history column (or row): the frame column covering its centre, and the frame
/// column landing in it (`u32::MAX` for none).
#[derive(Clone, Debug, Default)]
pub(crate) struct Axis {
    covering: Vec<u32>,
    landed: Vec<u32>,
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
    }
}

/// Everything the resolve of one frame reads.
pub(crate) struct Inputs<'a> {
    /// The frame as rendered: `low_size` pixels of radiance and geometry, and what
    /// [`Inputs::prepare`] made of them.
    pub low: &'a [[f32; 3]],
    pub low_geometry: &'a [Geometry],
    pub prepared: &'a [Prepared],
    pub low_size: (u32, u32),
    pub columns: &'a Axis,
    pub rows: &'a Axis,
    /// The history before this frame: `size` pixels of (radiance, age) and geometry.
    pub history: &'a [[f32; 4]],
    pub geometry: &'a [Geometry],
    pub size: (u32, u32),
    pub frame: TemporalFrame,
}

/// How the surface of record `g` moved since the previous frame: a surface seen directly in
/// a world that moved follows its object; anything else is taken as still (seen through a
/// mirror, its image does not follow its object: that is left to the cap and the clamp).
pub(crate) fn move_of(g: &Geometry, frame: &TemporalFrame, moves: &[SurfaceMove]) -> SurfaceMove {
    if !frame.world_moved || g.q[3] == 0.0 || g.tag & MIRROR_FLAG != 0 {
        return SurfaceMove::Still;
    }
    moves
        .get((g.tag & ID_MASK) as usize)
        .copied()
        .unwrap_or_default()
}

/// The frame's 3×3 pixels around a history pixel: the range of their finite colours and
/// their indices.
struct Neighbourhood {
    range: Option<([f32; 3], [f32; 3])>,
    pixels: [u32; 9],
    count: usize,
}

/// Whether every channel is finite.
#[inline]
fn finite(c: [f32; 3]) -> bool {
    c.iter().all(|v| v.is_finite())
}

/// |a − b|.
#[inline]
fn distance(a: [f32; 4], b: [f32; 3]) -> f32 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

impl Inputs<'_> {
    /// What the resolve needs of a frame pixel, given the frame's camera frame, the
    /// history's size and how the surfaces moved.
    pub fn prepare(
        camera: &CameraFrame,
        frame: &TemporalFrame,
        size: (u32, u32),
        moves: &[SurfaceMove],
        colour: [f32; 3],
        g: &Geometry,
    ) -> Prepared {
        let q = [g.q[0], g.q[1], g.q[2]];
        let (previous_q, previous_n, existed) = match move_of(g, frame, moves) {
            SurfaceMove::Still => (q, g.n, true),
            SurfaceMove::Moved(map) => (map.point(q), map.normal(g.n), true),
            SurfaceMove::New => (q, g.n, false),
        };
        let motion = frame
            .previous
            .as_ref()
            .filter(|_| existed)
            .and_then(|previous| {
                let q_before = [previous_q[0], previous_q[1], previous_q[2], g.q[3]];
                let before = project(previous, q_before, size.0, size.1)?;
                let now = project(camera, g.q, size.0, size.1)?;
                Some([before[0] - now[0], before[1] - now[1]])
            });
        let eye = frame
            .previous
            .as_ref()
            .map_or([0.0; 3], |p| p.eye.to_array());
        Prepared {
            motion,
            previous_q,
            previous_n,
            distance: distance([previous_q[0], previous_q[1], previous_q[2], 1.0], eye),
            existed,
            finite: finite(colour),
        }
    }

    /// The new history and geometry of pixel (x, y).
    pub fn resolve(&self, x: u32, y: u32) -> ([f32; 4], Geometry) {
        let width = self.size.0;
        let low_w = self.low_size.0;
        let (cx, cy) = (
            self.columns.covering[x as usize],
            self.rows.covering[y as usize],
        );
        let (lx, ly) = (
            self.columns.landed[x as usize],
            self.rows.landed[y as usize],
        );
        let landed = lx != u32::MAX && ly != u32::MAX;
        let (sx, sy) = if landed { (lx, ly) } else { (cx, cy) };
        let source = (sy * low_w + sx) as usize;
        let geometry = self.low_geometry[source];
        let c = self.low[source];
        let current_ok = self.prepared[source].finite;
        let fresh = landed && current_ok;

        let history = if self.frame.still {
            let h = self.history[(y * width + x) as usize];
            Some(([h[0], h[1], h[2]], h[3]))
        } else if self.frame.previous.is_some() {
            let near = self.neighbourhood(cx, cy);
            self.history_at(x, y, &self.prepared[source], &near)
                .map(|(colour, age)| match near.range {
                    Some((lo, hi)) => ([0, 1, 2].map(|i| colour[i].max(lo[i]).min(hi[i])), age),
                    None => (colour, age),
                })
        } else {
            None
        };
        let frame = &self.frame;
        let approx = geometry.tag & APPROX_FLAG != 0;
        let mirrored = geometry.tag & MIRROR_FLAG != 0;
        let cap = if frame.still {
            STILL_CAP
        } else if (approx && (frame.eye_moved || frame.world_moved))
            || (mirrored && frame.world_moved)
        {
            SPECULAR_CAP
        } else {
            HISTORY_CAP
        };
        let out = match (history, fresh) {
            (Some((h, age)), true) => {
                let a = age.min(cap);
                let alpha = 1.0 / (a + 1.0);
                [
                    h[0] + (c[0] - h[0]) * alpha,
                    h[1] + (c[1] - h[1]) * alpha,
                    h[2] + (c[2] - h[2]) * alpha,
                    a + 1.0,
                ]
            }
            (Some((h, age)), false) => [h[0], h[1], h[2], age.min(cap)],
            (None, true) => [c[0], c[1], c[2], 1.0],
            (None, false) if current_ok => [c[0], c[1], c[2], 0.0],
            (None, false) => [0.0; 4],
        };
        (out, geometry)
    }

    /// The 3×3 frame pixels around (cx, cy) that lie in the frame, row by row.
    fn neighbourhood(&self, cx: u32, cy: u32) -> Neighbourhood {
        let (low_w, low_h) = self.low_size;
        let mut near = Neighbourhood {
            range: None,
            pixels: [0; 9],
            count: 0,
        };
        for ny in cy.saturating_sub(1)..=(cy + 1).min(low_h - 1) {
            for nx in cx.saturating_sub(1)..=(cx + 1).min(low_w - 1) {
                let i = ny * low_w + nx;
                near.pixels[near.count] = i;
                near.count += 1;
                if !self.prepared[i as usize].finite {
                    continue;
                }
                let c = self.low[i as usize];
                near.range = Some(match near.range {
                    None => (c, c),
                    Some((lo, hi)) => (
                        [0, 1, 2].map(|k| lo[k].min(c[k])),
                        [0, 1, 2].map(|k| hi[k].max(c[k])),
                    ),
                });
            }
        }
        near
    }

    /// Whether the history's surface `old` is one the neighbourhood sees (as it was in the
    /// previous frame): the same surface id and, for a point, within the tolerance of its
    /// tangent plane and facing alike.
    fn seen_nearby(&self, near: &Neighbourhood, old: &Geometry) -> bool {
        near.pixels[..near.count].iter().any(|&i| {
            let g = &self.low_geometry[i as usize];
            let p = &self.prepared[i as usize];
            if g.tag & ID_MASK != old.tag & ID_MASK || !p.existed {
                return false;
            }
            if g.q[3] == 0.0 {
                return true;
            }
            let q = p.previous_q;
            let off = [old.q[0] - q[0], old.q[1] - q[1], old.q[2] - q[2]];
            dot3(off, p.previous_n).abs() <= PLANE_TOLERANCE * p.distance
                && dot3(p.previous_n, old.n) >= NORMAL_COS
        })
    }

    /// The reprojected history of pixel (x, y), whose frame sample is `sample`: its filtered
    /// colour and age, or None where there is none to keep.
    fn history_at(
        &self,
        x: u32,
        y: u32,
        sample: &Prepared,
        near: &Neighbourhood,
    ) -> Option<([f32; 3], f32)> {
        let (width, height) = self.size;
        let motion = sample.motion?;
        let bx = x as f32 + motion[0];
        let by = y as f32 + motion[1];
        if !(bx >= -1.0 && bx < width as f32 && by >= -1.0 && by < height as f32) {
            return None;
        }
        let (fx0, fy0) = (floor(bx), floor(by));
        let (fx, fy) = (bx - fx0, by - fy0);
        let (ix, iy) = (fx0 as i32, fy0 as i32);
        let bilinear = [
            (1.0 - fx) * (1.0 - fy),
            fx * (1.0 - fy),
            (1.0 - fx) * fy,
            fx * fy,
        ];
        let taps = [(ix, iy), (ix + 1, iy), (ix, iy + 1), (ix + 1, iy + 1)];
        let mut all_valid = true;
        let mut weight = 0.0f32;
        let mut colour = [0.0f32; 3];
        let mut age = 0.0f32;
        for (&(tx, ty), &w) in taps.iter().zip(&bilinear) {
            if tx < 0 || ty < 0 || tx >= width as i32 || ty >= height as i32 {
                all_valid = false;
                continue;
            }
            let i = (ty as u32 * width + tx as u32) as usize;
            if !self.seen_nearby(near, &self.geometry[i]) {
                all_valid = false;
                continue;
            }
            let h = self.history[i];
            weight += w;
            colour = [0, 1, 2].map(|c| colour[c] + w * h[c]);
            age += w * h[3];
        }
        if weight <= 0.0 {
            return None;
        }
        let inside = ix >= 1 && iy >= 1 && ix + 2 < width as i32 && iy + 2 < height as i32;
        let colour = if all_valid && inside {
            self.catmull_rom(ix, iy, fx, fy)
        } else {
            colour.map(|c| c / weight)
        };
        finite(colour).then_some((colour, age / weight))
    }

    /// The history's Catmull–Rom filter over the 4×4 pixels from (ix − 1, iy − 1) at
    /// fractions (fx, fy) past (ix, iy): rows first, then the column.
    fn catmull_rom(&self, ix: i32, iy: i32, fx: f32, fy: f32) -> [f32; 3] {
        let (wx, wy) = (catmull_rom(fx), catmull_rom(fy));
        let width = self.size.0 as usize;
        let first = (iy - 1) as usize * width + (ix - 1) as usize;
        let mut sum = [0.0f32; 3];
        for (b, &wb) in wy.iter().enumerate() {
            let row = &self.history[first + b * width..][..4];
            let mut line = [0.0f32; 3];
            for (h, &wa) in row.iter().zip(&wx) {
                line = [0, 1, 2].map(|c| line[c] + wa * h[c]);
            }
            sum = [0, 1, 2].map(|c| sum[c] + wb * line[c]);
        }
        sum
    }
}
