//! Warped refreshes (`docs/temporal.md`): the history shown again from a camera that moved
//! since its frame, for a refresh that has no new frame. Each history pixel's record says
//! where its surface appears from the new camera; each screen pixel then looks for the
//! history pixel that lands on it (a few fixed-point steps on that motion field) and takes
//! the history's Catmull–Rom filter there, clamped to the four nearest pixels' range, and
//! the result is shown as the history is (sharpened when its frame resampled it).

use super::{History, shown};
use crate::simd::best_compiled;
use glam::Vec4;
use rayon::prelude::*;
use steadyray_render::Picture;
use steadyray_render::temporal::{catmull_rom, floor, project4};
use steadyray_scene::camera::CameraFrame;

/// Fixed-point steps from a screen pixel to the history pixel that lands on it: the motion
/// of a refresh is a few pixels and smooth within a surface, so two steps find it and a
/// third settles the edges.
const WARP_STEPS: usize = 3;

/// A motion no step follows: the record's point is behind one of the cameras.
const NO_MOTION: [f32; 2] = [f32::NAN; 2];

impl History {
    /// The accumulated image as camera frame `to` (made for the history's size) sees it,
    /// tone-mapped as the display shows it, or `None` before the first frame.
    pub fn warped(&mut self, to: &CameraFrame) -> Option<Picture> {
        let from = self.camera.filter(|_| self.accumulated)?;
        let settings = self.clock.settings();
        let (width, height) = (settings.width as usize, settings.height as usize);
        let size = (settings.width, settings.height);
        // Buffers kept from warp to warp: each pixel of both is written below.
        let mut motion = std::mem::take(&mut self.warp_motion);
        let mut warped = std::mem::take(&mut self.warp_colour);
        motion.resize(width * height, NO_MOTION);
        warped.resize(width * height, [0.0; 4]);
        motion
            .par_chunks_mut(width)
            .zip(self.sources.par_chunks(width))
            .for_each(|(row, sources)| {
                best_compiled(
                    #[inline(always)]
                    || self.motion_row(&from, to, row, sources),
                );
            });
        warped
            .par_chunks_mut(width)
            .enumerate()
            .for_each(|(y, row)| {
                best_compiled(
                    #[inline(always)]
                    || self.warp_row(y, row, &motion),
                );
            });
        // Shown as the history itself is: sharpened when its frame resampled it.
        let picture = shown(&warped, size, self.sharpen);
        self.warp_motion = motion;
        self.warp_colour = warped;
        Some(picture)
    }

    /// The motion field of one history row (`motion`, whose pixels' records are `sources`):
    /// where each record's point moves from camera `from` to camera `to`, four pixels at a
    /// time.
    #[inline(always)]
    fn motion_row(
        &self,
        from: &CameraFrame,
        to: &CameraFrame,
        motion: &mut [[f32; 2]],
        sources: &[u32],
    ) {
        let settings = self.clock.settings();
        let size = (settings.width, settings.height);
        for (motion, sources) in motion.chunks_mut(4).zip(sources.chunks(4)) {
            let mut q = [[0.0f32; 4]; 4];
            for (lane, &source) in sources.iter().enumerate() {
                let g = &self.previous_geometry[source as usize];
                for (component, &v) in q.iter_mut().zip(&g.q) {
                    component[lane] = v;
                }
            }
            let q = q.map(Vec4::from_array);
            let (ax, ay, a_ok) = project4(from, q, size);
            let (bx, by, b_ok) = project4(to, q, size);
            let (dx, dy) = (bx - ax, by - ay);
            for (lane, m) in motion.iter_mut().enumerate() {
                *m = if a_ok.test(lane) && b_ok.test(lane) {
                    [dx[lane], dy[lane]]
                } else {
                    NO_MOTION
                };
            }
        }
    }

    /// Row `y` of the warped picture from the motion field `motion`: each pixel's fixed-point
    /// steps, then the history's filter there.
    #[inline(always)]
    fn warp_row(&self, y: usize, row: &mut [[f32; 4]], motion: &[[f32; 2]]) {
        let settings = self.clock.settings();
        let (width, height) = (settings.width as usize, settings.height as usize);
        for (x, pixel) in row.iter_mut().enumerate() {
            let target = [x as f32 + 0.5, y as f32 + 0.5];
            let mut at = target;
            let mut read = usize::MAX;
            for _ in 0..WARP_STEPS {
                // The pixel under `at`, clamped to the image: floor(at) is the
                // truncation once at is at least 0.
                let px = (at[0].max(0.0) as usize).min(width - 1);
                let py = (at[1].max(0.0) as usize).min(height - 1);
                let pixel = py * width + px;
                if pixel == read {
                    // The same motion again: at stays where it is.
                    break;
                }
                read = pixel;
                let m = motion[pixel];
                if m[0].is_nan() {
                    break;
                }
                at = [target[0] - m[0], target[1] - m[1]];
            }
            let [r, g, b] = self.filtered_at(at, (width, height));
            *pixel = [r, g, b, 0.0];
        }
    }

    /// The history's Catmull–Rom filter at `at` (pixel centres at i + 0.5, taps past the
    /// edges clamped to them), clamped to the range of the four pixels around `at` so that
    /// it does not ring at edges.
    #[inline(always)]
    fn filtered_at(&self, at: [f32; 2], (width, height): (usize, usize)) -> [f32; 3] {
        let (u, v) = (at[0] - 0.5, at[1] - 0.5);
        let (fu, fv) = (floor(u), floor(v));
        let (wx, wy) = (catmull_rom(u - fu), catmull_rom(v - fv));
        // The 4 × 4 taps from (fu − 1, fv − 1), rows first.
        let window: [[Vec4; 4]; 4] = if fu >= 1.0
            && fu + 2.0 <= (width - 1) as f32
            && fv >= 1.0
            && fv + 2.0 <= (height - 1) as f32
        {
            // Inside the image: no tap is clamped, and each row's four lie side by side.
            let first = (fv as usize - 1) * width + fu as usize - 1;
            std::array::from_fn(|r| {
                let row = &self.colour[first + r * width..][..4];
                std::array::from_fn(|c| Vec4::from_array(row[c]))
            })
        } else {
            let tap = |i: f32, offset: i64, last: usize| -> usize {
                (i as i64 + offset).clamp(0, last as i64) as usize
            };
            let columns: [usize; 4] = std::array::from_fn(|k| tap(fu, k as i64 - 1, width - 1));
            let rows: [usize; 4] = std::array::from_fn(|k| tap(fv, k as i64 - 1, height - 1));
            rows.map(|r| columns.map(|c| Vec4::from_array(self.colour[r * width + c])))
        };
        let mut sum = Vec4::ZERO;
        for (taps, &wb) in window.iter().zip(&wy) {
            let mut line = Vec4::ZERO;
            for (&tap, &wa) in taps.iter().zip(&wx) {
                line += wa * tap;
            }
            sum += wb * line;
        }
        let near = [window[1][1], window[1][2], window[2][1], window[2][2]];
        let lo = near[0].min(near[1]).min(near[2]).min(near[3]);
        let hi = near[0].max(near[1]).max(near[2]).max(near[3]);
        let c = sum.max(lo).min(hi);
        [c.x, c.y, c.z]
    }
}
