//! The displayed quality (`bench --quality --clock real`): FLIP of the screen at sampled
//! refreshes against a reference render of the world at that refresh's time, under the
//! stated viewing set-up. References are rendered after the runs (the runs do not wait for
//! them), once per time, and shared by every controller.

use super::reference_store::ReferenceStore;
use super::screen::{DisplayRun, DisplayedQuality, ScoredSample, ScreenSample};
use super::source::{FrameSource, PathPoint, render_reference};
use anyhow::{Context, Result, bail};
use rayon::prelude::*;
use std::collections::BTreeMap;
use steadyray_control::Quality;
use steadyray_display::stats::{mean, quantile};
use steadyray_quality::Rgb8Image;

/// A world time as a reference's key: whole nanoseconds, so that a frame rendered at a
/// refresh's time (i·P) finds that refresh's reference.
pub fn time_key(t_s: f64) -> i64 {
    (t_s * 1e9).round() as i64
}

/// References of the world at given times: reference quality, full scale, tone-mapped.
pub struct TimedReferences {
    quality: Quality,
    images: BTreeMap<i64, Rgb8Image>,
    /// Where references are kept between benches (`--references`), if anywhere.
    store: Option<ReferenceStore>,
    /// FLIP of the world at one time against the world at another (keys: then, now),
    /// shared by every run that showed a frame of that time at that refresh.
    age_flips: BTreeMap<(i64, i64), f64>,
}

impl TimedReferences {
    /// No references yet, to be rendered at `quality`.
    pub fn new(quality: Quality) -> Self {
        Self {
            quality,
            images: BTreeMap::new(),
            store: None,
            age_flips: BTreeMap::new(),
        }
    }

    /// References that come from `store` where it holds them, and go into it when rendered.
    pub fn with_store(mut self, store: ReferenceStore) -> Self {
        self.store = Some(store);
        self
    }

    /// The reference quality.
    pub fn quality(&self) -> Quality {
        self.quality
    }

    /// The reference of the world at `t_s`, if rendered.
    pub fn get(&self, t_s: f64) -> Option<&Rgb8Image> {
        self.images.get(&time_key(t_s))
    }

    /// Adds a reference made elsewhere (e.g. read from a video folder).
    pub fn insert(&mut self, t_s: f64, image: Rgb8Image) {
        self.images.insert(time_key(t_s), image);
    }

    /// The reference at `t_s`, or an error naming the missing time.
    fn at(&self, t_s: f64) -> Result<&Rgb8Image> {
        self.get(t_s)
            .with_context(|| format!("no reference of the world at {t_s:.4} s"))
    }

    /// Computes, in parallel, the FLIP of every pair (then, now) of `pairs` not held yet: the
    /// world at `then_s` shown at `now_s` against the reference at `now_s` (the truth), what
    /// a perfect picture costs for its age alone. [`Self::age_flip`] then reads them.
    pub fn measure_age_flips(
        &mut self,
        pairs: impl IntoIterator<Item = (f64, f64)>,
        pixels_per_degree: f32,
    ) -> Result<()> {
        let missing: BTreeMap<(i64, i64), (f64, f64)> = pairs
            .into_iter()
            .map(|(then_s, now_s)| ((time_key(then_s), time_key(now_s)), (then_s, now_s)))
            .filter(|(key, _)| key.0 != key.1 && !self.age_flips.contains_key(key))
            .collect();
        let measured = missing
            .par_iter()
            .map(|(&key, &(then_s, now_s))| {
                let flip = steadyray_quality::flip_at(
                    self.at(now_s)?,
                    self.at(then_s)?,
                    pixels_per_degree,
                )?;
                Ok((key, flip.mean()))
            })
            .collect::<Result<Vec<_>>>()?;
        self.age_flips.extend(measured);
        Ok(())
    }

    /// The FLIP of the world at `then_s` shown at `now_s` (0 when they are the same time),
    /// measured by [`Self::measure_age_flips`].
    pub fn age_flip(&self, then_s: f64, now_s: f64) -> Result<f64> {
        let key = (time_key(then_s), time_key(now_s));
        if key.0 == key.1 {
            return Ok(0.0);
        }
        self.age_flips.get(&key).copied().with_context(|| {
            format!(
                "the age FLIP of the world at {then_s:.4} s shown at {now_s:.4} s was not measured"
            )
        })
    }

    /// The reference of the world at `t_s` at the source's full-scale size: the one held,
    /// else the store's, else rendered (and kept in the store). It is not held afterwards:
    /// [`Self::insert`] it to keep it.
    pub fn fetch(&self, source: &mut dyn FrameSource, t_s: f64) -> Result<Rgb8Image> {
        if let Some(held) = self.get(t_s) {
            return Ok(held.clone());
        }
        if let Some(stored) = self
            .store
            .as_ref()
            .map(|s| s.load(t_s))
            .transpose()?
            .flatten()
        {
            return Ok(stored);
        }
        let (width, height) = source.resolution();
        let at = PathPoint::Time { index: 0, t_s };
        let picture = render_reference(source, at, self.quality)
            .with_context(|| format!("reference at {t_s:.4} s ({}) failed", self.quality))?;
        let Some(picture) = picture else {
            bail!("references need a renderer that produces images (not --simulate)");
        };
        let picture = picture.resize_bilinear(width, height);
        if let Some(store) = &self.store {
            store.save(t_s, &picture)?;
        }
        Ok(picture)
    }

    /// Fetches ([`Self::fetch`]) and holds the references of those `times` not held yet;
    /// `progress` is told of each.
    pub fn render_missing(
        &mut self,
        source: &mut dyn FrameSource,
        times: impl IntoIterator<Item = f64>,
        mut progress: impl FnMut(),
    ) -> Result<()> {
        let mut missing: Vec<f64> = times
            .into_iter()
            .filter(|&t| self.get(t).is_none())
            .collect();
        missing.sort_by(f64::total_cmp);
        missing.dedup_by_key(|t| time_key(*t));
        for t_s in missing {
            let picture = self.fetch(source, t_s)?;
            self.insert(t_s, picture);
            progress();
        }
        Ok(())
    }
}

/// The screen of a run at every sample `wants` asks for, every `period_ms`.
pub fn screen_samples(
    run: &DisplayRun,
    period_ms: f64,
    wants: impl Fn(usize) -> bool,
) -> Vec<ScreenSample> {
    run.timeline
        .sampled(period_ms)
        .iter()
        .enumerate()
        .filter(|(i, _)| wants(*i))
        .map(|(index, r)| {
            let warped = run.warps.shown.contains(&index);
            let time_s = r.time_ms / 1000.0;
            ScreenSample {
                index,
                time_s,
                frame: r.frame,
                warped,
                world_s: if warped {
                    time_s
                } else {
                    run.world_of(r.frame)
                },
            }
        })
        .collect()
}

/// The samples of a bench run that it is scored on: those from its first frame on screen.
/// Before it the screen shows the bench's last warm-up frame, which a run with `--warp` warps
/// and one without holds (a start the runs do not share), and which one sample would weigh as
/// much as a whole `--every` span of the run.
pub fn run_samples(
    run: &DisplayRun,
    period_ms: f64,
    wants: impl Fn(usize) -> bool,
) -> Vec<ScreenSample> {
    let mut samples = screen_samples(run, period_ms, wants);
    samples.retain(|s| s.frame.is_some());
    samples
}

/// The picture a sample shows at the full-scale size: its warp, or the kept frame upscaled,
/// or black when nothing was on screen yet (no warm-up frame).
pub fn screen_picture(
    run: &DisplayRun,
    sample: &ScreenSample,
    (width, height): (u32, u32),
) -> Result<Rgb8Image> {
    if sample.warped {
        let picture = run.warps.pictures.get(&sample.index).with_context(|| {
            format!(
                "the warped picture of refresh {} was not kept",
                sample.index
            )
        })?;
        return Ok(picture.resize_bilinear(width, height));
    }
    let frame = sample.frame;
    match run.pictures.get(&frame) {
        Some(picture) => Ok(picture.resize_bilinear(width, height)),
        None if frame.is_none() => Ok(Rgb8Image::from_fn(width, height, |_, _| [0; 3])),
        None => bail!("the picture of frame {frame:?} on screen was not kept"),
    }
}

/// Measures a run's screen at `samples` against `references` (which must hold every
/// sample's time and every sampled frame's world time) at `pixels_per_degree`.
pub fn measure(
    run: &DisplayRun,
    samples: &[ScreenSample],
    references: &mut TimedReferences,
    size: (u32, u32),
    pixels_per_degree: f32,
) -> Result<Option<DisplayedQuality>> {
    references.measure_age_flips(
        samples.iter().map(|s| (s.world_s, s.time_s)),
        pixels_per_degree,
    )?;
    let references = &*references;
    let scored = samples
        .par_iter()
        .map(|&sample| -> Result<ScoredSample> {
            let screen = screen_picture(run, &sample, size)?;
            let at = |t_s| -> Result<f64> {
                Ok(
                    steadyray_quality::flip_at(references.at(t_s)?, &screen, pixels_per_degree)?
                        .mean(),
                )
            };
            Ok(ScoredSample {
                sample,
                flip: at(sample.time_s)?,
                frame_flip: at(sample.world_s)?,
                age_flip: references.age_flip(sample.world_s, sample.time_s)?,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let column = |of: fn(&ScoredSample) -> f64| scored.iter().map(of).collect::<Vec<_>>();
    let displayed = column(|s| s.flip);
    let frame_flip_mean = mean(&column(|s| s.frame_flip)).unwrap_or(0.0);
    let age_flip_mean = mean(&column(|s| s.age_flip)).unwrap_or(0.0);
    let age_ms_mean =
        mean(&column(|s| 1000.0 * (s.sample.time_s - s.sample.world_s))).unwrap_or(0.0);
    Ok(mean(&displayed).map(|flip_mean| DisplayedQuality {
        flip_mean,
        flip_p95: quantile(&displayed, 0.95).unwrap_or(flip_mean),
        frame_flip_mean,
        age_flip_mean,
        age_ms_mean,
        scored,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::screen::Warps;
    use steadyray_display::{DisplayConfig, DisplayFigures, RealClock, SyncMode};

    const P_S: f64 = 1.0 / 60.0;

    /// The world at `t_s`: a white bar moving right at `speed` pixels per second.
    fn world(t_s: f64, speed: f64) -> Rgb8Image {
        Rgb8Image::from_fn(64, 32, |x, _| {
            if (f64::from(x) - 8.0 - speed * t_s).abs() < 3.0 {
                [255; 3]
            } else {
                [20; 3]
            }
        })
    }

    /// Nearly instant frames on a 60 Hz display (each shown at the next refresh), each showing
    /// the world `lag` refreshes before its display time; the references of every refresh.
    fn screen(lag: f64, speed: f64) -> (DisplayRun, TimedReferences) {
        let display = DisplayConfig::new(60.0, SyncMode::Vsync).unwrap();
        let mut clock = RealClock::new(display, 0.2).unwrap();
        let mut world_s = Vec::new();
        while let Some(slot) = clock.next_frame() {
            world_s.push(slot.world_s() - lag * P_S);
            clock.present(0.5, 0.0).unwrap();
        }
        let timeline = clock.finish();
        let mut pictures: BTreeMap<Option<usize>, Rgb8Image> = world_s
            .iter()
            .enumerate()
            .map(|(j, &t)| (Some(j), world(t, speed)))
            .collect();
        // The lead-in frame (the last warm-up frame) shows the world as late as the others.
        let lead_in_world_s = -lag * P_S;
        pictures.insert(None, world(lead_in_world_s, speed));
        let mut references = TimedReferences::new(Quality::new(16.0, 16, 1.0));
        for r in timeline.refreshes() {
            references.insert(r.time_ms / 1000.0, world(r.time_ms / 1000.0, speed));
        }
        for &t in world_s.iter().chain([&lead_in_world_s]) {
            references.insert(t, world(t, speed));
        }
        let run = DisplayRun {
            figures: DisplayFigures::of(&timeline),
            timeline,
            pictures,
            warps: Warps::default(),
            world_s,
            lead_in_world_s,
            quality: None,
            busy_pct: None,
        };
        (run, references)
    }

    fn displayed(lag: f64, speed: f64) -> DisplayedQuality {
        let (run, references) = screen(lag, speed);
        let samples = screen_samples(&run, 1000.0 * P_S, |_| true);
        assert_eq!(samples.len(), 12);
        let mut references = references;
        measure(&run, &samples, &mut references, (64, 32), 12.6)
            .unwrap()
            .unwrap()
    }

    #[test]
    fn frames_of_the_reference_shown_on_time_score_zero() {
        let q = displayed(0.0, 120.0);
        assert_eq!(
            (q.flip_mean, q.flip_p95, q.frame_flip_mean, q.age_flip_mean),
            (0.0, 0.0, 0.0, 0.0)
        );
        assert!(q.age_ms_mean.abs() < 1e-6);
    }

    #[test]
    fn a_stale_frame_costs_more_the_faster_the_camera_moves() {
        let slow = displayed(1.0, 60.0);
        let fast = displayed(1.0, 240.0);
        assert!(slow.flip_mean > 0.0, "{slow:?}");
        assert!(fast.flip_mean > 1.5 * slow.flip_mean, "{slow:?} {fast:?}");
        // Each frame is perfect for its own time: the error is its age alone.
        assert_eq!(fast.frame_flip_mean, 0.0);
        assert_eq!(fast.age_flip_mean, fast.flip_mean);
        assert_eq!(slow.age_flip_mean, slow.flip_mean);
        // Every refresh shows a frame one refresh old, refresh 0 the last warm-up frame (a
        // refresh before the path's start): its age too is age, not a fault of its picture.
        assert!((fast.age_ms_mean - 1000.0 * P_S).abs() < 1e-6);
        let lead_in = fast.scored[0];
        assert_eq!(lead_in.sample.frame, None);
        assert!((lead_in.sample.world_s + P_S).abs() < 1e-12);
        assert_eq!(lead_in.frame_flip, 0.0);
        assert!(lead_in.age_flip > 0.0 && lead_in.flip == lead_in.age_flip);
        assert_eq!(fast.scored.len(), 12);
    }

    #[test]
    fn stale_frames_of_a_static_camera_score_zero() {
        let q = displayed(2.0, 0.0);
        assert_eq!((q.flip_mean, q.age_flip_mean), (0.0, 0.0));
        assert!(q.age_ms_mean > 0.0);
    }

    /// Frames one refresh old, every refresh after the first replaced by a warp that shows
    /// the world at its own time: the screen is then the world, on time.
    #[test]
    fn a_warped_refresh_is_its_own_picture_at_its_own_time() {
        let speed = 240.0;
        let (mut run, mut references) = screen(1.0, speed);
        // Every refresh warped, the lead-in frame's at refresh 0 too (as `--warp` does).
        run.warps.shown.extend(0..12);
        let samples = screen_samples(&run, 1000.0 * P_S, |_| true);
        for s in &samples {
            let truth = references.get(s.time_s).unwrap().clone();
            run.warps.pictures.insert(s.index, truth);
        }
        assert!(samples.iter().all(|s| s.warped && s.world_s == s.time_s));
        let q = measure(&run, &samples, &mut references, (64, 32), 12.6)
            .unwrap()
            .unwrap();
        assert_eq!(
            (q.flip_mean, q.age_flip_mean, q.age_ms_mean),
            (0.0, 0.0, 0.0)
        );
        run.warps.pictures.remove(&5);
        let err = measure(&run, &samples, &mut references, (64, 32), 12.6).unwrap_err();
        assert!(
            err.to_string().contains("warped picture of refresh 5"),
            "{err}"
        );
    }

    #[test]
    fn a_missing_reference_or_picture_is_an_error() {
        let (mut run, mut references) = screen(0.0, 60.0);
        let samples = screen_samples(&run, 1000.0 * P_S, |_| true);
        let mut empty = TimedReferences::new(references.quality());
        let err = measure(&run, &samples, &mut empty, (64, 32), 12.6).unwrap_err();
        assert!(err.to_string().contains("no reference"), "{err}");
        run.pictures.remove(&Some(3));
        let err = measure(&run, &samples, &mut references, (64, 32), 12.6).unwrap_err();
        assert!(err.to_string().contains("not kept"), "{err}");
    }
}
