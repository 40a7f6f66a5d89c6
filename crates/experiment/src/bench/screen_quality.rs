//! After the real clock's runs: the references of the screen (every refresh's with
//! `--video`, written for the JOD tool) and the displayed quality of every run
//! (`--quality`), measured against them.

use super::BenchConfig;
use super::displayed::{self, TimedReferences, run_samples, time_key};
use super::machine;
use super::real_clock::{Keep, RealSweep};
use super::record::ControllerRun;
use super::reference_store::{ReferenceStore, StoreKey};
use super::source::FrameSource;
use super::video::{self, VideoRun};
use anyhow::Result;
use indicatif::ProgressBar;
use std::collections::BTreeSet;
use steadyray_control::Quality;
use steadyray_display::ViewingSetup;
use steadyray_display::model::refresh_at_or_after;

/// What the screen's references are of: the scene and the renderer that drew the runs.
pub struct Described {
    /// The scene's name.
    pub scene: String,
    /// The backend and device.
    pub backend: String,
    /// The device.
    pub device: String,
    /// The full-scale size.
    pub resolution: (u32, u32),
}

/// Renders the references the real clock's runs need (every refresh's into `--video`'s
/// folder, with its `video.json` naming `video_runs`) and measures each run's displayed
/// quality (`--quality`, at the samples `measured` asks for); the runs' pictures are freed.
pub fn measure_screens(
    (config, real): (&BenchConfig, &RealSweep),
    source: &mut dyn FrameSource,
    runs: &mut [ControllerRun],
    (reference_quality, measured): (Quality, Keep),
    described: &Described,
    video_runs: Vec<VideoRun>,
    progress: &ProgressBar,
) -> Result<()> {
    let period = real.display.period_ms();
    let refreshes = refresh_at_or_after(real.duration_s * 1000.0, period) as usize;
    // The world times the displayed quality compares with: each sampled refresh's and the
    // world time of the frame on screen then.
    let mut needed = Vec::new();
    for run in runs.iter() {
        if let Some(shown) = &run.display {
            for s in run_samples(shown, period, |i| measured.wants(i)) {
                needed.extend([s.time_s, s.world_s]);
            }
        }
    }
    let mut references = TimedReferences::new(reference_quality);
    if let Some(dir) = &config.references {
        let store = ReferenceStore::open(dir, &store_key(described, reference_quality, source))?;
        eprintln!("bench: references kept in {}", store.folder().display());
        references = references.with_store(store);
    }
    if let Some(dir) = &config.video {
        let needed_keys: BTreeSet<i64> = needed.iter().map(|&t| time_key(t)).collect();
        let grid: Vec<f64> = (0..refreshes).map(|i| i as f64 * period / 1000.0).collect();
        progress.inc_length(refreshes as u64);
        progress.set_message("references");
        let (width, height) = described.resolution;
        let key = video::ReferenceKey {
            scene: described.scene.clone(),
            backend: described.backend.clone(),
            device: described.device.clone(),
            resolution: [width, height],
            refresh_hz: real.display.refresh_hz,
            refreshes,
            spp: reference_quality.spp,
            depth: reference_quality.depth,
            git_revision: machine::git_revision(),
        };
        video::write_references(
            dir,
            &key,
            &grid,
            source,
            &mut references,
            |t| needed_keys.contains(&time_key(t)),
            || progress.inc(1),
        )?;
        video::write_index(
            dir,
            &video::VideoIndex {
                scene: described.scene.clone(),
                refresh_hz: real.display.refresh_hz,
                refreshes,
                resolution: [width, height],
                duration_s: real.duration_s,
                display: real.display,
                viewing: ViewingSetup::standard_fhd(),
                reference: key,
                runs: video_runs,
            },
        )?;
    }
    if config.quality {
        progress.set_message("displayed quality");
        references.render_missing(source, needed, || {
            progress.inc_length(1);
            progress.inc(1);
        })?;
        let (width, _) = described.resolution;
        let ppd = ViewingSetup::standard_fhd().pixels_per_degree(width) as f32;
        for run in runs.iter_mut() {
            if let Some(shown) = run.display.as_mut() {
                let samples = run_samples(shown, period, |i| measured.wants(i));
                shown.quality = displayed::measure(
                    shown,
                    &samples,
                    &mut references,
                    described.resolution,
                    ppd,
                )?;
                shown.pictures.clear();
                shown.warps.pictures.clear();
            }
        }
    }
    Ok(())
}

/// What the references of this bench are of, for `--references`.
fn store_key(described: &Described, quality: Quality, source: &dyn FrameSource) -> StoreKey {
    let (width, height) = described.resolution;
    StoreKey {
        scene: described.scene.clone(),
        scene_digest: source.world_digest().unwrap_or_default(),
        backend: described.backend.clone(),
        device: described.device.clone(),
        resolution: [width, height],
        spp: quality.spp,
        depth: quality.depth,
        git_revision: machine::git_revision(),
    }
}
