//! The per-pixel resolve of `docs/temporal.md`: find the frame's sample that lands in the
//! pixel, reproject the history by that sample's point, keep the taps whose surface is still
//! seen around the pixel, filter them, clamp to the frame's local colour range and blend (a
//! still camera keeps the history as it is).
//! Written operation for operation as `render-gpu/src/shaders/temporal.wgsl`, so both
//! round alike.

use super::geometry::Geometry;
use steadyray_render::temporal::{
    APPROX_FLAG, HISTORY_CAP, ID_MASK, NORMAL_COS, PLANE_TOLERANCE, SPECULAR_CAP, TemporalFrame,
    catmull_rom, covering, dot3, landed_from, project,
};
use steadyray_scene::camera::CameraFrame;

/// Everything the resolve of one frame reads.
pub(crate) struct Inputs<'a> {
    /// The frame as rendered: `low_size` pixels of radiance and geometry.
    pub low: &'a [[f32; 3]],
    pub low_geometry: &'a [Geometry],
    pub low_size: (u32, u32),
    /// The history before this frame: `size` pixels of (radiance, age) and geometry.
    pub history: &'a [[f32; 4]],
    pub geometry: &'a [Geometry],
    pub size: (u32, u32),
    /// The camera frame of this frame (for the history's size).
    pub camera: CameraFrame,
    pub frame: TemporalFrame,
}

/// The frame's 3×3 low-resolution pixels around a pixel: the range of their finite colours
/// and the surfaces they see, with their points' distances from the previous eye.
struct Neighbourhood {
    range: Option<([f32; 3], [f32; 3])>,
    surfaces: [(Geometry, f32); 9],
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

impl Neighbourhood {
    /// Whether the history's surface `old` is one the neighbourhood sees: the same surface
    /// id and, for a point, within the tolerance of its tangent plane and facing alike.
    fn sees(&self, old: &Geometry) -> bool {
        self.surfaces[..self.count].iter().any(|(g, d)| {
            let off = [old.q[0] - g.q[0], old.q[1] - g.q[1], old.q[2] - g.q[2]];
            g.tag & ID_MASK == old.tag & ID_MASK
                && (g.q[3] == 0.0
                    || (dot3(off, g.n).abs() <= PLANE_TOLERANCE * d
                        && dot3(g.n, old.n) >= NORMAL_COS))
        })
    }
}

impl Inputs<'_> {
    /// The new history and geometry of pixel (x, y).
    pub fn resolve(&self, x: u32, y: u32) -> ([f32; 4], Geometry) {
        let (width, height) = self.size;
        let (low_w, low_h) = self.low_size;
        let anchor = self.frame.anchor;
        let (cx, cy) = (covering(x, width, low_w), covering(y, height, low_h));
        let landed =
            landed_from(x, anchor[0], width, low_w).zip(landed_from(y, anchor[1], height, low_h));
        let (sx, sy) = landed.unwrap_or((cx, cy));
        let source = (sy * low_w + sx) as usize;
        let geometry = self.low_geometry[source];
        let current = self.low[source];
        let current_ok = finite(current);
        let fresh = landed.is_some() && current_ok;

        let near = self.neighbourhood(cx, cy);
        let history = if self.frame.still {
            let h = self.history[(y * width + x) as usize];
            Some(([h[0], h[1], h[2]], h[3]))
        } else {
            self.history_at(x, y, &geometry, &near)
                .map(|(colour, age)| {
                    let colour = match near.range {
                        Some((lo, hi)) => [0, 1, 2].map(|c| colour[c].max(lo[c]).min(hi[c])),
                        None => colour,
                    };
                    (colour, age)
                })
        };
        let cap = if geometry.tag & APPROX_FLAG != 0 && self.frame.eye_moved {
            SPECULAR_CAP
        } else {
            HISTORY_CAP
        };
        let c = current;
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

    /// The 3×3 low-resolution pixels around (cx, cy), row by row.
    fn neighbourhood(&self, cx: u32, cy: u32) -> Neighbourhood {
        let (low_w, low_h) = self.low_size;
        let eye = self.frame.previous.map_or([0.0; 3], |p| p.eye.to_array());
        let mut near = Neighbourhood {
            range: None,
            surfaces: [(Geometry::default(), 0.0); 9],
            count: 0,
        };
        for dy in [-1i32, 0, 1] {
            for dx in [-1i32, 0, 1] {
                let (nx, ny) = (cx as i32 + dx, cy as i32 + dy);
                if nx < 0 || ny < 0 || nx >= low_w as i32 || ny >= low_h as i32 {
                    continue;
                }
                let i = (ny as u32 * low_w + nx as u32) as usize;
                let g = self.low_geometry[i];
                near.surfaces[near.count] = (g, distance(g.q, eye));
                near.count += 1;
                let c = self.low[i];
                if !finite(c) {
                    continue;
                }
                near.range = Some(match near.range {
                    None => (c, c),
                    Some((lo, hi)) => (
                        [0, 1, 2].map(|i| lo[i].min(c[i])),
                        [0, 1, 2].map(|i| hi[i].max(c[i])),
                    ),
                });
            }
        }
        near
    }

    /// The reprojected history of pixel (x, y) for a frame whose sample there has `geometry`:
    /// its filtered colour and age, or None where there is none to keep.
    fn history_at(
        &self,
        x: u32,
        y: u32,
        geometry: &Geometry,
        near: &Neighbourhood,
    ) -> Option<([f32; 3], f32)> {
        let previous = self.frame.previous.as_ref()?;
        let (width, height) = self.size;
        let before = project(previous, geometry.q, width, height)?;
        let now = project(&self.camera, geometry.q, width, height)?;
        let bx = x as f32 + (before[0] - now[0]);
        let by = y as f32 + (before[1] - now[1]);
        if !(bx >= -1.0 && bx < width as f32 && by >= -1.0 && by < height as f32) {
            return None;
        }
        let (fx0, fy0) = (bx.floor(), by.floor());
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
            let old = &self.geometry[i];
            if !near.sees(old) {
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
        let width = self.size.0 as i32;
        let mut sum = [0.0f32; 3];
        for (b, &wb) in wy.iter().enumerate() {
            let row = (iy - 1 + b as i32) * width;
            let mut line = [0.0f32; 3];
            for (a, &wa) in wx.iter().enumerate() {
                let h = self.history[(row + ix - 1 + a as i32) as usize];
                line = [0, 1, 2].map(|c| line[c] + wa * h[c]);
            }
            sum = [0, 1, 2].map(|c| sum[c] + wb * line[c]);
        }
        sum
    }
}
