//! The frame-time history behind the HUD's graph and figures: render time (what the
//! controller sees) and presentation interval (what vsync makes of it) per frame.

use serde::Serialize;
use std::collections::VecDeque;
use steadyray_control::{Band, Quality};

/// Seconds of history kept for the graph and the figures.
pub const HISTORY_S: f64 = 10.0;
/// Frames kept at most, whatever the frame rate.
const MAX_SAMPLES: usize = 4096;

/// One shown frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Seconds since the view started.
    pub t_s: f64,
    /// Render time Tp, ms (GPU timestamps, or the CPU renderer's wall time).
    pub render_ms: f64,
    /// Time since the previous frame was presented, ms (None for the first).
    pub present_ms: Option<f64>,
    pub quality: Quality,
    /// Rays traced (0 when unknown, as in playback).
    pub rays: u64,
}

/// Mean, median, 95th percentile and maximum of some milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Spread {
    pub mean: f64,
    pub p50: f64,
    pub p95: f64,
    pub max: f64,
}

impl Spread {
    /// The spread of `values`, or None when there are none.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Self> {
        let mut v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
        Some(Self {
            mean: v.iter().sum::<f64>() / v.len() as f64,
            p50: at(0.5),
            p95: at(0.95),
            max: v[v.len() - 1],
        })
    }
}

/// The last [`HISTORY_S`] seconds of frames.
#[derive(Clone, Debug, Default)]
pub struct FrameHistory {
    samples: VecDeque<Sample>,
}

impl FrameHistory {
    /// Adds a frame and forgets those older than [`HISTORY_S`] before it.
    pub fn push(&mut self, sample: Sample) {
        self.samples.push_back(sample);
        while self.samples.len() > MAX_SAMPLES
            || self
                .samples
                .front()
                .is_some_and(|s| sample.t_s - s.t_s > HISTORY_S)
        {
            self.samples.pop_front();
        }
    }

    /// The frames kept, oldest first.
    pub fn samples(&self) -> impl DoubleEndedIterator<Item = &Sample> + ExactSizeIterator {
        self.samples.iter()
    }

    /// The newest frame.
    pub fn last(&self) -> Option<&Sample> {
        self.samples.back()
    }

    /// The frames of the last `window_s` seconds.
    fn recent(&self, window_s: f64) -> impl Iterator<Item = &Sample> {
        let now = self.last().map_or(0.0, |s| s.t_s);
        self.samples
            .iter()
            .rev()
            .take_while(move |s| now - s.t_s <= window_s)
    }

    /// Percentage of the last `window_s` seconds' frames whose render time lies in `band`.
    pub fn in_band_pct(&self, band: Band, window_s: f64) -> Option<f64> {
        let (inside, all) = self.recent(window_s).fold((0usize, 0usize), |(i, n), s| {
            (i + usize::from(band.contains(s.render_ms)), n + 1)
        });
        (all > 0).then(|| 100.0 * inside as f64 / all as f64)
    }

    /// Rays per second of render time over the last `window_s` seconds.
    pub fn rays_per_s(&self, window_s: f64) -> Option<f64> {
        let (rays, ms) = self
            .recent(window_s)
            .fold((0u64, 0.0), |(r, t), s| (r + s.rays, t + s.render_ms));
        (ms > 0.0 && rays > 0).then(|| rays as f64 / (ms * 1e-3))
    }

    /// Spread of the render times of the last `window_s` seconds.
    pub fn render_spread(&self, window_s: f64) -> Option<Spread> {
        Spread::of(self.recent(window_s).map(|s| s.render_ms))
    }

    /// Spread of the presentation intervals of the last `window_s` seconds.
    pub fn present_spread(&self, window_s: f64) -> Option<Spread> {
        Spread::of(self.recent(window_s).filter_map(|s| s.present_ms))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t_s: f64, render_ms: f64) -> Sample {
        Sample {
            t_s,
            render_ms,
            present_ms: Some(16.7),
            quality: Quality::new(1.0, 4, 1.0),
            rays: 1000,
        }
    }

    #[test]
    fn forgets_frames_older_than_the_window() {
        let mut h = FrameHistory::default();
        for i in 0..30 {
            h.push(sample(i as f64, 10.0));
        }
        let oldest = h.samples().next().unwrap().t_s;
        assert_eq!(oldest, 29.0 - HISTORY_S);
        assert_eq!(h.last().unwrap().t_s, 29.0);
    }

    #[test]
    fn in_band_share_counts_only_recent_frames() {
        let band = Band::new(15.0, 20.0).unwrap();
        let mut h = FrameHistory::default();
        assert_eq!(h.in_band_pct(band, 2.0), None);
        h.push(sample(0.0, 50.0));
        h.push(sample(5.0, 17.0));
        h.push(sample(5.5, 30.0));
        h.push(sample(6.0, 16.0));
        assert_eq!(h.in_band_pct(band, 2.0), Some(100.0 * 2.0 / 3.0));
        assert_eq!(h.in_band_pct(band, 10.0), Some(50.0));
    }

    #[test]
    fn rays_per_second_use_render_time() {
        let mut h = FrameHistory::default();
        h.push(sample(0.0, 10.0));
        h.push(sample(0.1, 10.0));
        assert_eq!(h.rays_per_s(1.0), Some(2000.0 / 0.02));
    }

    #[test]
    fn spreads_sort_and_skip_missing_intervals() {
        let s = Spread::of([4.0, 1.0, 3.0, 2.0, f64::NAN]).unwrap();
        assert_eq!((s.mean, s.p50, s.max), (2.5, 3.0, 4.0));
        assert_eq!(Spread::of([]), None);
        let mut h = FrameHistory::default();
        h.push(Sample {
            present_ms: None,
            ..sample(0.0, 5.0)
        });
        assert_eq!(h.present_spread(1.0), None);
        assert_eq!(h.render_spread(1.0).unwrap().max, 5.0);
    }
}
