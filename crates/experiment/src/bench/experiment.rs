//! Running controllers over the sweep, and finding the most-in-band fixed quality.

use super::quality::{References, flip_stats};
use super::record::{ControllerRun, FrameRow};
use super::source::{FrameSource, PathPoint};
use anyhow::{Context, Result};
use indicatif::ProgressBar;
use rayon::prelude::*;
use steadyray_control::{Band, Bounds, Controller, FrameRecord, Quality, summarize};

/// The sweep every run follows.
#[derive(Clone, Copy, Debug)]
pub struct Sweep {
    /// Counted frames: frame k has yaw 2π·k/frames.
    pub frames: u32,
    /// Frames rendered (and shown to the controller) at the first view before counting.
    pub warmup: u32,
    /// The frame-time band.
    pub band: Band,
    /// The quality knobs' bounds.
    pub bounds: Bounds,
}

impl Sweep {
    /// Frame `k` of the sweep on the camera path.
    pub fn at(&self, k: u32) -> PathPoint {
        PathPoint::Frame { k, n: self.frames }
    }
}

/// What a run keeps besides the timings: FLIP of the sampled frames, the delivered frames.
#[derive(Clone, Copy, Default)]
pub struct Capture<'a> {
    /// References of the sampled frames (`bench --quality`).
    pub references: Option<&'a References>,
    /// Keep every counted frame's picture (`bench --record`).
    pub record: bool,
}

/// Runs `controller` over the sweep: warm-up frames first (not counted), then every frame
/// of the sweep, each rendered at the quality the controller asked for. Pictures are read
/// back only after a frame's Tp was taken (the renderer's own timing), so `capture` never
/// changes the timings, and compared with their references after the run, in parallel,
/// so a GPU is not left idle between frames while a comparison runs (its clocks follow how
/// busy it is).
pub fn run_controller(
    source: &mut dyn FrameSource,
    controller: &mut dyn Controller,
    name: &str,
    sweep: &Sweep,
    capture: Capture<'_>,
    progress: &ProgressBar,
) -> Result<ControllerRun> {
    controller.reset();
    progress.set_message(name.to_string());
    for _ in 0..sweep.warmup {
        let m =
            source.frame_within(sweep.at(0), controller.quality(), controller.frame_budget())?;
        // A refused report (e.g. a 0 ms reading) leaves the controller as it was.
        let _ = controller.observe(&m.report);
        progress.inc(1);
    }
    let mut rows = Vec::with_capacity(sweep.frames as usize);
    let mut records = Vec::with_capacity(sweep.frames as usize);
    let mut recorded = Vec::new();
    let mut to_compare = Vec::new();
    let (width, height) = source.resolution();
    for k in 0..sweep.frames {
        let q = controller.quality();
        let target_ms = controller.target_frame_ms();
        let predicted_ms = controller.decision().and_then(|d| d.predicted_ms);
        let m = source
            .frame_within(sweep.at(k), q, controller.frame_budget())
            .with_context(|| format!("{name}: frame {k} at {q} failed"))?;
        let rays = m.report.total_rays();
        let tp_ms = m.report.tp_ms;
        if let Err(e) = controller.observe(&m.report) {
            log::warn!("{name}: frame {k}: report refused: {e}");
        }
        let reference = capture.references.and_then(|r| r.get(k));
        if reference.is_some() || capture.record {
            let picture = source
                .last_picture()?
                .context("this source produces no images to measure or record")?;
            match reference {
                Some(reference) if capture.record => {
                    to_compare.push((rows.len(), reference, picture.clone()));
                    recorded.push(picture);
                }
                Some(reference) => to_compare.push((rows.len(), reference, picture)),
                None => recorded.push(picture),
            }
        }
        let t_s = source.path_duration_s() * f64::from(k) / f64::from(sweep.frames);
        rows.push(
            FrameRow {
                target_ms,
                ..FrameRow::measured(k, t_s, &m, sweep.band)
            }
            .with_decision(predicted_ms, controller.decision()),
        );
        records.push(FrameRecord {
            frame: k as usize,
            tp_ms,
            quality: q,
            rays,
        });
        progress.inc(1);
    }
    let flips = to_compare
        .into_par_iter()
        .map(|(row, reference, picture)| {
            let delivered = picture.resize_bilinear(width, height);
            Ok((row, steadyray_quality::flip(reference, &delivered)?.mean()))
        })
        .collect::<Result<Vec<_>>>()?;
    for (row, flip) in flips {
        rows[row].flip = Some(flip);
    }
    let changes = source.load_changes(sweep.frames);
    let summary = summarize(
        &records,
        sweep.band,
        sweep.bounds.max_quality(),
        changes.as_deref(),
    );
    let flips: Vec<f64> = rows.iter().filter_map(|r| r.flip).collect();
    Ok(ControllerRun {
        name: name.to_string(),
        band: sweep.band,
        rows,
        summary,
        flip: flip_stats(&flips),
        recorded,
        display: None,
        budgeted: controller.frame_budget().is_some(),
    })
}

/// Frames of the sweep the most-in-band search looks at: about `views` evenly spaced ones.
fn search_frames(frames: u32, views: u32) -> Vec<u32> {
    let stride = (frames / views.max(1)).max(1);
    (0..frames).step_by(stride as usize).collect()
}

/// Candidate S values of the search: 1, 2, 3, 4, 6, 8, 12, 16, ... up to the bound.
fn spp_candidates(bounds: &Bounds) -> Vec<f32> {
    let mut out = Vec::new();
    let mut s = bounds.spp_min.max(1.0).ceil();
    while s <= bounds.spp_max {
        out.push(s);
        let next = if s < 4.0 { s + 1.0 } else { s * 1.5 };
        s = next.round();
    }
    out
}

/// Candidate resolution scales of the search: full, 3/4 and 1/2, where the bounds allow.
fn scale_candidates(bounds: &Bounds) -> Vec<f32> {
    [1.0, 0.75, 0.5]
        .into_iter()
        .filter(|s| (bounds.scale_min..=bounds.scale_max).contains(s))
        .collect()
}

/// Finds the single quality with the most frames in the band over (a subsample of) the
/// sweep: the baseline a controller must beat at holding the band (chosen by frame time
/// alone, not by how it looks). Frame time only grows with S and R, so the
/// share of frames over Tmax only grows too: a candidate whose frames over Tmax already
/// exceed what the best so far left over cannot win, and neither can any costlier one along
/// the same S (branch and bound).
pub fn search_most_in_band_fixed(
    source: &mut dyn FrameSource,
    sweep: &Sweep,
    views: u32,
    progress: &ProgressBar,
) -> Result<Quality> {
    let frames = search_frames(sweep.frames, views);
    let bounds = &sweep.bounds;
    let mut best: Option<(Quality, usize)> = None;
    progress.set_message("most-in-band fixed: search");
    for scale in scale_candidates(bounds) {
        'spp: for spp in spp_candidates(bounds) {
            for depth in bounds.depth_min..=bounds.depth_max {
                let q = Quality { spp, depth, scale };
                let best_in = best.map_or(0, |(_, n)| n);
                // Frames over Tmax beyond this many mean the candidate cannot beat the best.
                let over_limit = frames.len() - best_in;
                let (mut in_band, mut over) = (0, 0);
                for &k in &frames {
                    let m = source.frame(sweep.at(k), q)?;
                    // The search's length is known only as it goes (it stops early on
                    // candidates that cannot win): each frame adds to the total as it is
                    // done, so the bar never passes 100 %.
                    progress.inc_length(1);
                    progress.inc(1);
                    if sweep.band.contains(m.report.tp_ms) {
                        in_band += 1;
                    } else if m.report.tp_ms > sweep.band.tmax_ms() {
                        over += 1;
                        if over >= over_limit {
                            break;
                        }
                    }
                }
                if over >= over_limit {
                    if depth == bounds.depth_min {
                        break 'spp;
                    }
                    continue 'spp;
                }
                if in_band > best_in {
                    best = Some((q, in_band));
                }
            }
        }
    }
    let (q, _) = best.context("no fixed quality put any frame of the sweep in the band")?;
    Ok(q)
}
