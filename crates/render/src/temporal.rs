//! The temporal mode's rules that both backends follow bit for bit (`docs/temporal.md`;
//! mirrored in `render-gpu/src/shaders/temporal.wgsl`): the sub-pixel jitter sequence, where a
//! low-resolution sample lands in the full-resolution history, the reprojection of a point
//! into a camera, the history filter's weights, and the constants of the history's
//! acceptance, clamp and blend. The per-pixel pass itself is written once per backend
//! (`render-cpu/src/temporal/`, `temporal.wgsl`) from these rules.

use crate::sampling::sample_offset;
use crate::{Image, RenderSettings, SettingsError};
use glam::{BVec4A, Vec3, Vec4};
use steadyray_scene::camera::CameraFrame;

/// The most samples a pixel's history stands for while the camera moves (its age, counted
/// in samples, is capped here, so a new frame pixel of n samples never weighs less than
/// n / (HISTORY_CAP + n)): every frame resamples a moving history, and a longer one gathers
/// more blur than it removes noise. Counting samples, not frames, lets a frame of many
/// samples outweigh the blurred history it would otherwise be averaged into. On the
/// corridor's sweep at 640x360 (the 2-core AMD EPYC VM), 4 against the earlier 8 made the
/// history at S = 1, scale 0.71 and at S = 2 and 3 at full scale 7–22 % better by FLIP at
/// 12.6 and at 67 pixels a degree (S = 1 at full scale was 3–7 % better at 12.6 and 4–8 %
/// worse at 67; S = 2 at scale 0.71 level at 12.6, 5 % worse at 67), and lowered displayed
/// FLIP 9–11 % in `bench --temporal on --warp` runs at the paper's band and at one refresh
/// (`docs/temporal.md`, *The moving cap, again*).
pub const HISTORY_CAP: f32 = 4.0;
/// The cap while the camera stands still, in frames (STILL_CAP · n samples for a pixel of
/// n samples a frame): the history is then kept pixel for pixel, without resampling, and
/// converges toward the reference.
pub const STILL_CAP: f32 = 64.0;
/// The cap, in samples, on pixels whose reprojection is only approximate (glass, curved
/// mirrors) while the eye moves: their reflected or refracted image has a parallax that the
/// reprojected point does not have, so they keep a short history.
pub const SPECULAR_CAP: f32 = 4.0;
/// A history tap's surface is seen again where its point lies within this fraction of the
/// distance to the previous eye from the tangent plane of a surface seen now.
pub const PLANE_TOLERANCE: f32 = 0.02;
/// History is rejected where the cosine between its normal and the current one is below
/// this (60°).
pub const NORMAL_COS: f32 = 0.5;
/// The surface id of a path that leaves the scene.
pub const MISS_ID: u32 = 0x3fff_ffff;
/// Mask of the surface id in a geometry record's tag.
pub const ID_MASK: u32 = 0x3fff_ffff;
/// Tag bit of a geometry record whose reprojection is approximate (a dielectric or a curved
/// mirror on the path).
pub const APPROX_FLAG: u32 = 0x8000_0000;
/// Tag bit of a geometry record seen through a mirror (its point is a mirror image, which
/// does not follow its object's motion).
pub const MIRROR_FLAG: u32 = 0x4000_0000;
/// The largest strength of the display's sharpening of a resampled history ([`sharpened`],
/// [`sharpen_strength`]): the picture is c + k · (c − the mean of c's four edge neighbours),
/// clamped to its 3×3 range, with k up to SHARPEN. Every moving frame resamples the history
/// (Catmull–Rom), and the blur that gathers is what FLIP at the viewing distance holds
/// against it; on the corridor's sweep at 640x360 and S = 1 a strength of 0.5 lowered the
/// shown picture's FLIP at 12.6 pixels a degree by 8–9 % and at 67 by 3 %, and raised
/// ColorVideoVDP's JOD. A plain frame, which is not blurred, only gets worse.
pub const SHARPEN: f32 = 0.5;
/// The branch random numbers of frame k of a history use sample indices
/// `i + SAMPLE_STRIDE · (k mod 2^20)`, so that every frame chooses new dielectric branches
/// (S is at most 4096, so indices of different frames never meet).
pub const SAMPLE_STRIDE: u32 = 4096;
/// The jitter sequence's generators in 0.32 fixed point: round(2^32 / φ₂) and
/// round(2^32 / φ₂²), φ₂ the plastic number (the R2 sequence, Roberts 2018).
const JITTER_STEP: [u32; 2] = [0xc13f_a9a9, 0x91e1_0da6];

/// The temporal mode of a renderer: frames are accumulated into a history of this
/// (full-resolution) size, whatever resolution each frame is rendered at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TemporalSettings {
    /// The history's width in pixels.
    pub width: u32,
    /// The history's height in pixels.
    pub height: u32,
}

impl TemporalSettings {
    /// Checks the history's size as an image size.
    pub fn validate(&self) -> Result<(), SettingsError> {
        RenderSettings {
            width: self.width,
            height: self.height,
            spp: 1.0,
            max_depth: 0,
        }
        .validate()
    }

    /// Checks that a frame of `render` can be accumulated into this history: a valid history
    /// size, and a frame no larger than it (temporal upsampling only scales up).
    pub fn check(&self, render: &RenderSettings) -> Result<(), SettingsError> {
        self.validate()?;
        if render.width > self.width || render.height > self.height {
            return Err(SettingsError::LargerThanHistory {
                width: render.width,
                height: render.height,
                history_width: self.width,
                history_height: self.height,
            });
        }
        Ok(())
    }
}

/// The jitter J_k in [0, 1)² of frame k of a history: J_0 = (0, 0), then the points of the R2
/// sequence each followed by its mirror image about the pixel centre (frames 2m − 1 and 2m
/// take point m and its mirror), so that the mean sample position over every odd number of
/// frames is the pixel centre, as [`crate::sampling::sample_offset`] does within a frame
/// (the plain sequence left the mean of 16 frames 0.09 pixel off centre: a shifted image,
/// which FLIP scores as an error on every edge). Computed in 0.32 fixed point and rounded
/// down to 24 bits, so it is exact and the same on every backend at any k.
pub fn jitter(k: u32) -> [f32; 2] {
    let m = k.div_ceil(2);
    JITTER_STEP.map(|step| {
        let point = m.wrapping_mul(step);
        let u = if k.is_multiple_of(2) {
            point.wrapping_neg()
        } else {
            point
        };
        (u >> 8) as f32 * (1.0 / 16_777_216.0)
    })
}

/// `f32::floor(t)` bit for bit (−0 included) for finite |t| < 2³¹, without the call into
/// libm that `f32::floor` is on the baseline x86-64 target (it has no rounding
/// instruction): truncate, and step down where that rounded a negative number up.
#[inline]
pub fn floor(t: f32) -> f32 {
    let i = t as i32 as f32;
    if i > t { i - 1.0 } else { i.copysign(t) }
}

/// frac(t) = t - floor(t).
#[inline]
fn frac(t: f32) -> f32 {
    t - floor(t)
}

/// The sub-pixel position of a sample whose frame-less position is `offset`
/// ([`crate::sampling::sample_offset`]) in a frame of jitter `j`: frac(offset + j), so the
/// samples stay inside their pixel. With J_0 it is `offset` exactly.
#[inline]
pub fn jittered(offset: (f32, f32), j: [f32; 2]) -> (f32, f32) {
    (frac(offset.0 + j[0]), frac(offset.1 + j[1]))
}

/// The sub-pixel position of sample `i` of a pixel that takes `n` samples in a frame of
/// jitter `j`; `still_frame` is the frame's index k in a still view (its
/// [`TemporalFrame::still_frame`]), 0 for any other frame.
///
/// A moving frame (and a plain one, J = 0): each [`crate::sampling::sample_offset`] moved by
/// `j` ([`jittered`]), the mirrored sample of each pair by −`j`, so that every pair stays
/// mirrored about the pixel centre and a pixel of two or more samples keeps its centroid
/// there in every frame (moving the whole pattern by `j` shifted each frame's image by up to
/// a fifth of a pixel, which FLIP scored 1.25x worse than the plain frame at S = 16). The
/// centre sample of an odd n ≥ 3 stays put; the one sample of n = 1 moves by `j`, which is
/// what the history gathers its sub-pixel detail from.
///
/// A still frame: [`still_sample`], new positions in every frame.
pub fn jittered_sample(i: u32, n: u32, j: [f32; 2], still_frame: u32) -> (f32, f32) {
    if still_frame != 0 {
        return still_sample(i, n, j, still_frame);
    }
    let offset = sample_offset(i, n);
    let odd = n & 1;
    if n <= 1 {
        jittered(offset, j)
    } else if i < odd {
        offset
    } else if (i - odd) & 1 == 1 {
        jittered(offset, [-j[0], -j[1]])
    } else {
        jittered(offset, j)
    }
}

/// Sample `i` of a pixel's `n` in frame k = `still_frame` ≥ 1 of a still view, of jitter
/// `j`: the frame takes the next ⌊n/2⌋ mirrored pairs of the R2 sequence after the k·⌊n/2⌋
/// that frames 0 to k − 1 took (pair m at 0.5 + m · (1/φ₂, 1/φ₂²) and its mirror image about
/// the centre, in 0.32 fixed point, exact on both backends at any k); the one sample of
/// n = 1 sits at 0.5 + `j` (where its value lands), and the centre sample of an odd n ≥ 3 at
/// `j` itself (the jitter is ± m′ · (1/φ₂, 1/φ₂²) too, so at 0.5 + `j` it would land on
/// pair points of other frames). The moving rule's pairs moved
/// by ±J_k land on the same R2 points frame after frame (the jitter is that sequence too:
/// pair m moved by J_k = m′ · (1/φ₂, 1/φ₂²) is pair m + m′), and an odd n's centre sample
/// never moves, so a still history of 31 frames at S = 16 held about 100 distinct positions
/// of its 496 samples and converged no better than one frame at S = 64, and at S = 3 a third
/// of its samples sat at the centre (`docs/temporal.md`, *The frame's samples*).
pub fn still_sample(i: u32, n: u32, j: [f32; 2], still_frame: u32) -> (f32, f32) {
    let odd = n & 1;
    if n <= 1 {
        return jittered((0.5, 0.5), j);
    }
    if i < odd {
        return (j[0], j[1]);
    }
    let pair = i - odd;
    let m = (pair / 2 + 1).wrapping_add(still_frame.wrapping_mul(n / 2));
    let [u, v] = JITTER_STEP.map(|step| {
        let point = m.wrapping_mul(step).wrapping_add(0x8000_0000);
        let point = if pair & 1 == 1 {
            point.wrapping_neg()
        } else {
            point
        };
        (point >> 8) as f32 * (1.0 / 16_777_216.0)
    });
    (u, v)
}

/// Where a low-resolution pixel's value lands inside it: its centre moved by the jitter,
/// frac(0.5 + J) per axis (the position of a single sample, S = 1).
pub fn anchor(j: [f32; 2]) -> [f32; 2] {
    [frac(0.5 + j[0]), frac(0.5 + j[1])]
}

/// The first sample index of frame k: `SAMPLE_STRIDE · (k mod 2^20)`.
pub fn sample_base(k: u32) -> u32 {
    (k & 0xf_ffff) * SAMPLE_STRIDE
}

/// The full-resolution column (or row) where low-resolution column `x` lands:
/// floor((x + anchor) · full / low).
#[inline]
pub fn landing(x: u32, anchor: f32, full: u32, low: u32) -> u32 {
    floor((x as f32 + anchor) * full as f32 / low as f32) as u32
}

/// The low-resolution column covering the centre of full-resolution column `x`:
/// floor((x + 0.5) · low / full), at most low - 1.
#[inline]
pub fn covering(x: u32, full: u32, low: u32) -> u32 {
    (floor((x as f32 + 0.5) * low as f32 / full as f32) as u32).min(low - 1)
}

/// The tent weight, along one axis, of low-resolution column `c`'s centre at the centre of
/// full-resolution column `x`: 1 − |distance| in low-resolution pixels, at least 0. A frame
/// pixel of two or more samples, whose centroid is its centre, reaches the moving history
/// pixels it covers with this weight where it does not land ([`landed_from`]).
#[inline]
pub fn splat_weight(x: u32, c: u32, full: u32, low: u32) -> f32 {
    let k = full as f32 / low as f32;
    let d = ((x as f32 + 0.5) - (c as f32 + 0.5) * k).abs() / k;
    (1.0 - d).max(0.0)
}

/// The tent weight, along one axis, at the centre of full-resolution column `x`, of the
/// samples of low-resolution column `s` whose centroid lies `at` past the column's left edge
/// (the anchor for a pixel of one sample, ½ for two or more): max(1 − |(s + at) · full / low
/// − (x + ½)|, 0), the distance measured in full-resolution pixels. Where a frame pixel
/// lands in a moving history, the frame is read at the history pixel's centre with these
/// weights (`docs/temporal.md`, step 1 of the resolve): a sample that lands off the centre
/// otherwise shifts the picture, by the jitter at scale 1 and by where the landing falls
/// below it.
#[inline]
pub fn centre_weight(x: u32, s: u32, at: f32, full: u32, low: u32) -> f32 {
    let position = (s as f32 + at) * full as f32 / low as f32;
    (1.0 - (position - (x as f32 + 0.5)).abs()).max(0.0)
}

/// The low-resolution column whose value lands in full-resolution column `x`, if any: the
/// first of covering − 1, covering, covering + 1 whose [`landing`] is `x`.
#[inline]
pub fn landed_from(x: u32, anchor: f32, full: u32, low: u32) -> Option<u32> {
    let c = covering(x, full, low);
    [c.wrapping_sub(1), c, c + 1]
        .into_iter()
        .find(|&s| s < low && landing(s, anchor, full, low) == x)
}

/// The Catmull–Rom weights of the four taps at offsets -1, 0, 1, 2 from a sample at
/// fraction `f` in [0, 1) past tap 0.
#[inline]
pub fn catmull_rom(f: f32) -> [f32; 4] {
    [
        f * (-0.5 + f * (1.0 - 0.5 * f)),
        1.0 + f * f * (-2.5 + 1.5 * f),
        f * (0.5 + f * (2.0 - 1.5 * f)),
        f * f * (-0.5 + 0.5 * f),
    ]
}

/// a · b, summed left to right (as the WGSL writes it).
#[inline]
pub fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where camera `frame` sees four points (lanes of x, y, z, w: a point where w = 1, a
/// direction, a point at infinity, where w = 0), in pixels of a `size` image: x, y, and
/// whether each lies in front of the camera (not behind it, on its plane or NaN). Each
/// lane's arithmetic is the scalar rule's of `docs/temporal.md`, so it rounds alike.
#[inline]
pub fn project4(frame: &CameraFrame, q: [Vec4; 4], size: (u32, u32)) -> (Vec4, Vec4, BVec4A) {
    let e = frame.eye;
    let point = q[3].cmpne(Vec4::ZERO);
    let v = [
        Vec4::select(point, q[0] - e.x, q[0]),
        Vec4::select(point, q[1] - e.y, q[1]),
        Vec4::select(point, q[2] - e.z, q[2]),
    ];
    let dot = |a: Vec3| v[0] * a.x + v[1] * a.y + v[2] * a.z;
    let z = dot(frame.forward);
    let sx = dot(frame.right) / z;
    let sy = dot(frame.true_up) / z;
    (
        (sx / frame.half_width + 1.0) * 0.5 * size.0 as f32,
        (1.0 - sy / frame.half_height) * 0.5 * size.1 as f32,
        z.cmpgt(Vec4::ZERO),
    )
}

/// How strongly the display sharpens the history after `frame`, rendered at `low` pixels
/// into a `full` history: SHARPEN · max(1 − d / HISTORY_CAP, 0), d = S · (low pixels / full
/// pixels) the samples a history pixel receives per frame; 0 when the frame did not resample
/// the history (the first after a reset, or a still one). The more samples each frame
/// brings, the less of each pixel is resampled history and the less it is blurred: at
/// 640x360 on the corridor's sweep a strength of 0.5 helped at S = 1, hurt at 67 pixels a
/// degree at S = 4 (FLIP +17 %, where 0.25 was level) and hurt everywhere at S = 16 (+40 to
/// +65 %), so the strength falls to 0 where a frame alone carries the history's cap.
pub fn sharpen_strength(frame: &TemporalFrame, low: (u32, u32), full: (u32, u32)) -> f32 {
    if frame.previous.is_none() || frame.still {
        return 0.0;
    }
    let share = (low.0 as f32 * low.1 as f32) / (full.0 as f32 * full.1 as f32);
    SHARPEN * (1.0 - frame.spp * share / HISTORY_CAP).max(0.0)
}

/// The displayed colour of a history pixel whose 3×3 neighbourhood (rows top to bottom,
/// each left to right, `n[4]` the pixel; taps past the image's edges repeat the edge) is
/// `n`, sharpened at strength `k` ([`sharpen_strength`]): c + k · (c − ((up + down) +
/// (left + right)) · ¼), clamped to the neighbourhood's per-channel range (lanes alike; the
/// fourth, the age, is carried along and dropped by the caller). The clamp keeps edges
/// from ringing.
#[inline]
pub fn sharpened(n: &[Vec4; 9], k: f32) -> Vec4 {
    let (mut lo, mut hi) = (n[0], n[0]);
    for &v in &n[1..] {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    sharpened_within(n[4], [n[1], n[3], n[5], n[7]], (lo, hi), k)
}

/// [`sharpened`] of the pixel `c` whose four neighbours are `[up, left, right, down]`, its
/// neighbourhood's per-channel range `(lo, hi)` given: for a caller that takes the range
/// from the column ranges neighbouring pixels share. The minimum and maximum of values
/// without NaN (a history holds none) are the same in any order but for the sign of a zero,
/// which the tone map after it does not see.
#[inline]
pub fn sharpened_within(
    c: Vec4,
    [up, left, right, down]: [Vec4; 4],
    (lo, hi): (Vec4, Vec4),
    k: f32,
) -> Vec4 {
    let cross = ((up + down) + (left + right)) * 0.25;
    let s = c + k * (c - cross);
    s.max(lo).min(hi)
}

/// `image` as the display shows a history of it sharpened at strength `k`
/// ([`sharpen_strength`]): [`sharpened`] at every pixel, taps past the edges repeating the
/// edge. The rule written plainly, that the backends' display passes are tested against.
pub fn sharpened_image(image: &Image, k: f32) -> Image {
    let (width, height) = (image.width, image.height);
    let pixels = (0..width * height)
        .map(|i| {
            let n = neighbourhood(i % width, i / width, width, height, |j| {
                let [r, g, b] = image.pixels[j];
                Vec4::new(r, g, b, 0.0)
            });
            let c = sharpened(&n, k);
            [c.x, c.y, c.z]
        })
        .collect();
    Image {
        width,
        height,
        pixels,
    }
}

/// The 3×3 neighbourhood of pixel (x, y) of a `width` × `height` image whose pixel i is
/// `at(i)`, as [`sharpened`] reads it (taps past the edges repeat the edge).
fn neighbourhood(x: u32, y: u32, width: u32, height: u32, at: impl Fn(usize) -> Vec4) -> [Vec4; 9] {
    let columns = [x.saturating_sub(1), x, (x + 1).min(width - 1)];
    let rows = [y.saturating_sub(1), y, (y + 1).min(height - 1)];
    std::array::from_fn(|k| at((rows[k / 3] * width + columns[k % 3]) as usize))
}

/// What a backend needs of the history's past to accumulate one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TemporalFrame {
    /// k: frames since the history started (0 for its first frame).
    pub index: u32,
    /// J_k.
    pub jitter: [f32; 2],
    /// [`anchor`] of J_k.
    pub anchor: [f32; 2],
    /// The previous frame's camera frame (for the output size), None when the history
    /// starts over with this frame.
    pub previous: Option<CameraFrame>,
    /// Whether the eye moved since the previous frame (the [`SPECULAR_CAP`] rule).
    pub eye_moved: bool,
    /// Whether objects may have moved since the previous frame: the scene is animated and
    /// its time changed (`crate::surface_motion` then says how each surface moved).
    pub world_moved: bool,
    /// The previous frame's scene time, s (with `previous`).
    pub previous_time_s: f64,
    /// Whether the camera frame is the previous one exactly and no object moved: the
    /// history is then kept as it is, pixel for pixel, without geometry tests or clamp.
    pub still: bool,
    /// The frame's eye rays per pixel S: a frame pixel's sample count
    /// (`sampling::samples_for_pixel`) is what its value weighs in the blend.
    pub spp: f32,
}

impl TemporalFrame {
    /// k for a still frame (k ≥ 1: the first frame of a history is never still), 0 for any
    /// other: what [`jittered_sample`] takes to place a still view's samples anew.
    pub fn still_frame(&self) -> u32 {
        if self.still { self.index } else { 0 }
    }
}

/// The host side of a history: its size, the number of frames it holds and the last
/// frame's camera and scene time. Both backends keep one and ask it for each frame's
/// [`TemporalFrame`].
#[derive(Clone, Debug, PartialEq)]
pub struct HistoryClock {
    settings: TemporalSettings,
    frames: u32,
    previous: Option<(CameraFrame, f64)>,
}

impl HistoryClock {
    /// An empty history of `settings`' size.
    pub fn new(settings: TemporalSettings) -> Self {
        Self {
            settings,
            frames: 0,
            previous: None,
        }
    }

    /// The history's size.
    pub fn settings(&self) -> TemporalSettings {
        self.settings
    }

    /// Forgets the history (a camera cut): the next frame starts a new one.
    pub fn reset(&mut self) {
        self.frames = 0;
        self.previous = None;
    }

    /// The next frame's [`TemporalFrame`] for camera frame `current` (made for the output
    /// size) at scene time `time_s` of a scene that is `animated` or not, rendered at `spp`
    /// eye rays per pixel, counting the frame as accumulated.
    pub fn advance(
        &mut self,
        current: CameraFrame,
        time_s: f64,
        animated: bool,
        spp: f32,
    ) -> TemporalFrame {
        let k = self.frames;
        let j = jitter(k);
        let previous = self.previous.map(|(camera, _)| camera);
        let previous_time_s = self.previous.map_or(time_s, |(_, t)| t);
        let world_moved = animated && previous_time_s != time_s;
        let frame = TemporalFrame {
            index: k,
            jitter: j,
            anchor: anchor(j),
            previous,
            eye_moved: previous.is_some_and(|p| p.eye != current.eye),
            world_moved,
            previous_time_s,
            still: previous == Some(current) && !world_moved,
            spp,
        };
        self.frames = self.frames.wrapping_add(1);
        self.previous = Some((current, time_s));
        frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_scene::Camera;

    #[test]
    fn jitter_starts_at_zero_and_fills_the_pixel() {
        assert_eq!(jitter(0), [0.0, 0.0]);
        assert_eq!(anchor(jitter(0)), [0.5, 0.5]);
        // 17 frames spread over a 4x4 grid of cells, at most three in any, and centred.
        let mut cells = [0u32; 16];
        let mut sum = [0.0f64; 2];
        for k in 0..17 {
            let [u, v] = anchor(jitter(k));
            assert!((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v));
            cells[(u * 4.0) as usize * 4 + (v * 4.0) as usize] += 1;
            sum = [sum[0] + f64::from(u), sum[1] + f64::from(v)];
        }
        assert!(cells.iter().all(|&c| c <= 3), "{cells:?}");
        assert!(cells.iter().filter(|&&c| c > 0).count() >= 10, "{cells:?}");
        for s in sum {
            assert!((s / 17.0 - 0.5).abs() < 1e-6, "{sum:?}");
        }
    }

    #[test]
    fn jittered_offsets_stay_in_the_pixel() {
        for k in 0..64 {
            let j = jitter(k);
            for (u, v) in [(0.0, 0.0), (0.5, 0.5), (0.999_999, 0.25)] {
                let (a, b) = jittered((u, v), j);
                assert!((0.0..1.0).contains(&a) && (0.0..1.0).contains(&b));
            }
        }
        assert_eq!(jittered((0.3, 0.7), jitter(0)), (0.3, 0.7));
    }

    #[test]
    fn jittered_samples_keep_their_centroid_at_the_centre() {
        for k in 1..40 {
            let j = jitter(k);
            assert_eq!(
                jittered_sample(0, 1, j, 0),
                jittered(sample_offset(0, 1), j)
            );
            for n in 2..=9 {
                let (mut u, mut v) = (0.0f64, 0.0f64);
                for i in 0..n {
                    let (a, b) = jittered_sample(i, n, j, 0);
                    assert!((0.0..1.0).contains(&a) && (0.0..1.0).contains(&b));
                    (u, v) = (u + f64::from(a), v + f64::from(b));
                }
                let centroid = [u / f64::from(n), v / f64::from(n)];
                assert!(
                    centroid.iter().all(|c| (c - 0.5).abs() < 1e-5),
                    "n = {n}, k = {k}: {centroid:?}"
                );
            }
        }
    }

    /// The positions of a still history of `frames` frames (frame 0 plain, then still
    /// frames 1, 2, ...) at n samples a pixel.
    fn still_history_positions(frames: u32, n: u32) -> Vec<(f32, f32)> {
        (0..frames)
            .flat_map(|k| (0..n).map(move |i| jittered_sample(i, n, jitter(k), k)))
            .collect()
    }

    #[test]
    fn a_still_view_takes_new_positions_in_every_frame() {
        for n in [2, 3, 4, 16] {
            let positions = still_history_positions(31, n);
            let distinct: std::collections::BTreeSet<_> = positions
                .iter()
                .map(|&(u, v)| (u.to_bits(), v.to_bits()))
                .collect();
            assert_eq!(distinct.len(), positions.len(), "n = {n}");
            assert!(
                positions
                    .iter()
                    .all(|&(u, v)| (0.0..1.0).contains(&u) && (0.0..1.0).contains(&v))
            );
        }
        // The moving rule's positions collapse onto the same R2 points frame after frame.
        let moving: std::collections::BTreeSet<_> = (0..31)
            .flat_map(|k| (0..16).map(move |i| jittered_sample(i, 16, jitter(k), 0)))
            .map(|(u, v)| ((u * 1e4) as i32, (v * 1e4) as i32))
            .collect();
        assert!(moving.len() < 200, "{} of 496", moving.len());
    }

    #[test]
    fn a_still_frame_keeps_an_even_pixels_centroid_and_moves_an_odd_ones_centre_sample_by_the_jitter()
     {
        for k in 1..40 {
            let j = jitter(k);
            assert_eq!(jittered_sample(0, 1, j, k), jittered((0.5, 0.5), j));
            assert_eq!(jittered_sample(0, 3, j, k), (j[0], j[1]));
            for n in [2, 4, 6, 16] {
                let (mut u, mut v) = (0.0f64, 0.0f64);
                for i in 0..n {
                    let (a, b) = jittered_sample(i, n, j, k);
                    (u, v) = (u + f64::from(a), v + f64::from(b));
                }
                let centroid = [u / f64::from(n), v / f64::from(n)];
                assert!(
                    centroid.iter().all(|c| (c - 0.5).abs() < 1e-6),
                    "n = {n}, k = {k}: {centroid:?}"
                );
            }
        }
    }

    #[test]
    fn every_column_lands_where_its_sample_lies() {
        for (full, low) in [(640u32, 640u32), (640, 320), (640, 211), (97, 25)] {
            for k in 0..8 {
                let a = anchor(jitter(k))[0];
                let mut hit = vec![0u32; full as usize];
                for x in 0..low {
                    let l = landing(x, a, full, low);
                    assert!(l < full);
                    hit[l as usize] += 1;
                }
                for (x, &n) in hit.iter().enumerate() {
                    let from = landed_from(x as u32, a, full, low);
                    assert_eq!(n, u32::from(from.is_some()), "{full}/{low} column {x}");
                    if let Some(s) = from {
                        assert_eq!(landing(s, a, full, low), x as u32);
                    }
                }
            }
        }
    }

    #[test]
    fn floor_is_exact() {
        let values = [
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -2.0,
            2.999_999_8,
            -2.999_999_8,
        ];
        for t in values
            .into_iter()
            .chain([1e7 + 0.5, -1e9, 16_777_217.0, -0.000_001])
        {
            assert_eq!(floor(t).to_bits(), t.floor().to_bits(), "{t}");
        }
    }

    #[test]
    fn sharpening_leaves_flat_colour_and_stays_in_the_neighbourhoods_range() {
        let flat = [Vec4::splat(0.3); 9];
        assert_eq!(sharpened(&flat, SHARPEN), Vec4::splat(0.3));
        // A soft step: the pixel between dark and light is pushed toward the light side,
        // but never past the neighbourhood's brightest.
        let mut step = [Vec4::splat(0.2); 9];
        for k in [2, 5, 8] {
            step[k] = Vec4::splat(1.0);
        }
        step[4] = Vec4::splat(0.6);
        let s = sharpened(&step, SHARPEN);
        // cross = (0.2 + 0.2 + 0.2 + 1.0) / 4 = 0.4; 0.6 + 0.5 · 0.2 = 0.7.
        assert!((s.x - 0.7).abs() < 1e-6, "{s}");
        step[4] = Vec4::splat(0.95);
        // 0.95 + 0.5 · (0.95 − 0.4875) ≈ 1.18, clamped to 1.
        assert_eq!(sharpened(&step, SHARPEN).x, 1.0);
        // The edges repeat: at a corner of a 2 × 2 image the taps are its pixels.
        let image = [1.0f32, 2.0, 3.0, 4.0];
        let n = neighbourhood(0, 0, 2, 2, |i| Vec4::splat(image[i]));
        let taps: Vec<f32> = n.iter().map(|v| v.x).collect();
        assert_eq!(taps, [1.0, 1.0, 2.0, 1.0, 1.0, 2.0, 3.0, 3.0, 4.0]);
    }

    #[test]
    fn sharpening_falls_as_a_frame_brings_more_samples_and_stops_when_nothing_was_resampled() {
        let view = |x: f32| Camera::look_at(Vec3::new(x, 1.0, 3.0), Vec3::ZERO, Vec3::Y, 50.0);
        let mut clock = HistoryClock::new(TemporalSettings {
            width: 64,
            height: 32,
        });
        let first = clock.advance(view(0.0).frame(64, 32), 0.0, false, 1.0);
        let full = (64, 32);
        assert_eq!(sharpen_strength(&first, full, full), 0.0);
        let moving = clock.advance(view(0.1).frame(64, 32), 0.0, false, 1.0);
        assert_eq!(
            sharpen_strength(&moving, full, full),
            SHARPEN * (1.0 - 1.0 / HISTORY_CAP)
        );
        // At half scale a history pixel receives a quarter of a sample a frame.
        assert_eq!(
            sharpen_strength(&moving, (32, 16), full),
            SHARPEN * (1.0 - 0.25 / HISTORY_CAP)
        );
        let many = TemporalFrame {
            spp: HISTORY_CAP,
            ..moving
        };
        assert_eq!(sharpen_strength(&many, full, full), 0.0);
        let still = clock.advance(view(0.1).frame(64, 32), 0.0, false, 1.0);
        assert!(still.still);
        assert_eq!(sharpen_strength(&still, full, full), 0.0);
    }

    #[test]
    fn catmull_rom_interpolates_and_sums_to_one() {
        assert_eq!(catmull_rom(0.0), [0.0, 1.0, 0.0, 0.0]);
        for i in 0..10 {
            let w = catmull_rom(i as f32 / 10.0);
            assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn projection_inverts_the_eye_ray() {
        let camera = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 50.0);
        let frame = camera.frame(320, 180);
        for (px, py, u, v) in [
            (0, 0, 0.5, 0.5),
            (100, 37, 0.2, 0.9),
            (319, 179, 0.99, 0.01),
        ] {
            let d = frame.ray_dir(px, py, u, v, 320, 180);
            let point = (frame.eye + 7.5 * d).extend(1.0);
            let behind = (frame.eye - frame.forward).extend(1.0);
            // Lanes: the point, the direction, a point behind the eye, a NaN.
            let lanes = [point, d.extend(0.0), behind, Vec4::NAN];
            let q = [0, 1, 2, 3].map(|c| Vec4::from_array(lanes.map(|l| l[c])));
            let (x, y, front) = project4(&frame, q, (320, 180));
            for lane in 0..2 {
                assert!(front.test(lane));
                assert!((x[lane] - (px as f32 + u)).abs() < 1e-3, "{x}");
                assert!((y[lane] - (py as f32 + v)).abs() < 1e-3, "{y}");
            }
            assert!(!front.test(2) && !front.test(3), "{front:?}");
        }
    }

    #[test]
    fn the_clock_counts_frames_and_forgets_on_reset() {
        let size = TemporalSettings {
            width: 64,
            height: 32,
        };
        let mut clock = HistoryClock::new(size);
        let a = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 60.0).frame(64, 32);
        let mut b = a;
        b.eye.x = 0.5;
        let first = clock.advance(a, 0.0, true, 1.0);
        assert_eq!(
            (first.index, first.previous, first.eye_moved),
            (0, None, false)
        );
        assert!(!first.still && !first.world_moved);
        let second = clock.advance(a, 0.0, true, 1.0);
        assert_eq!((second.index, second.previous), (1, Some(a)));
        assert!(!second.eye_moved && second.still);
        let third = clock.advance(b, 0.0, true, 1.0);
        assert!(third.eye_moved && !third.still);
        // Time runs: objects of an animated scene move, those of a static one do not.
        let fourth = clock.advance(b, 0.5, true, 1.0);
        assert!(fourth.world_moved && !fourth.still && fourth.previous_time_s == 0.0);
        let fifth = clock.advance(b, 1.0, false, 1.0);
        assert!(!fifth.world_moved && fifth.still);
        clock.reset();
        let after = clock.advance(b, 1.0, false, 1.0);
        assert_eq!((after.index, after.previous), (0, None));
    }

    #[test]
    fn frames_larger_than_the_history_are_refused() {
        let size = TemporalSettings {
            width: 64,
            height: 32,
        };
        let frame = |width, height| RenderSettings {
            width,
            height,
            spp: 1.0,
            max_depth: 2,
        };
        assert!(size.check(&frame(64, 32)).is_ok());
        assert!(size.check(&frame(16, 8)).is_ok());
        assert!(size.check(&frame(65, 32)).is_err());
        let empty = TemporalSettings {
            width: 0,
            height: 32,
        };
        assert!(empty.check(&frame(1, 1)).is_err());
    }
}
