//! After the real clock's runs: the references of the screen (every refresh's with
//! `--video`, written for the JOD tool) and the displayed quality of every run
//! (`--quality`), measured against them; and the displayed quality of one run as soon as it
//! ran, for the best-looking fixed quality's search ([`score_runs`]).

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

/// What measuring a real-clock run's displayed quality needs besides its references: the
/// display's refresh period, the samples measured and the full-scale size.
#[derive(Clone, Copy, Debug)]
pub struct Scoring {
    /// The display's refresh period, ms.
    pub period_ms: f64,
    /// The samples of the screen measured.
    pub measured: Keep,
    /// The full-scale size.
    pub size: (u32, u32),
}

impl Scoring {
    /// The world times the displayed quality of `runs` not measured yet compares with: each
    /// sampled refresh's and the world time of the frame on screen then.
    fn needed_times(&self, runs: &[ControllerRun]) -> Vec<f64> {
        let mut needed = Vec::new();
        for shown in runs.iter().filter_map(|run| run.display.as_ref()) {
            if shown.quality.is_none() {
                for s in run_samples(shown, self.period_ms, |i| self.measured.wants(i)) {
                    needed.extend([s.time_s, s.world_s]);
                }
            }
        }
        needed
    }
}

/// Measures the displayed quality of those real-clock `runs` not measured yet against
/// `references` (shared by every run of the bench; those missing rendered first, as plain
/// frames of the current temporal mode of `source`) and frees their pictures.
pub fn score_runs(
    runs: &mut [ControllerRun],
    scoring: Scoring,
    references: &mut TimedReferences,
    source: &mut dyn FrameSource,
    progress: &ProgressBar,
) -> Result<()> {
    progress.set_message("displayed quality");
    references.render_missing(source, scoring.needed_times(runs), || {
        progress.inc_length(1);
        progress.inc(1);
    })?;
    let ppd = ViewingSetup::standard_fhd().pixels_per_degree(scoring.size.0) as f32;
    for run in runs.iter_mut() {
        if let Some(shown) = run.display.as_mut()
            && shown.quality.is_none()
        {
            let samples = run_samples(shown, scoring.period_ms, |i| scoring.measured.wants(i));
            shown.quality = displayed::measure(shown, &samples, references, scoring.size, ppd)?;
            shown.pictures.clear();
            shown.warps.pictures.clear();
        }
    }
    Ok(())
}

/// Renders the references the real clock's runs need (every refresh's into `--video`'s
/// folder, with its `video.json` naming `video_runs`) and measures the displayed quality of
/// each run not measured yet (`--quality`, at the samples `measured` asks for) against
/// `references`, which every run shares; the runs' pictures are freed.
pub fn measure_screens(
    (config, real): (&BenchConfig, &RealSweep),
    source: &mut dyn FrameSource,
    runs: &mut [ControllerRun],
    (references, measured): (&mut TimedReferences, Keep),
    described: &Described,
    video_runs: Vec<VideoRun>,
    progress: &ProgressBar,
) -> Result<()> {
    let period = real.display.period_ms();
    let refreshes = refresh_at_or_after(real.duration_s * 1000.0, period) as usize;
    let scoring = Scoring {
        period_ms: period,
        measured,
        size: described.resolution,
    };
    if let Some(dir) = &config.video {
        let needed = scoring.needed_times(runs);
        let needed_keys: BTreeSet<i64> = needed.iter().map(|&t| time_key(t)).collect();
        let grid: Vec<f64> = (0..refreshes).map(|i| i as f64 * period / 1000.0).collect();
        progress.inc_length(refreshes as u64);
        progress.set_message("references");
        let (width, height) = described.resolution;
        let key = video::ReferenceKey {
            set_up: store_key(described, references.quality(), source),
            refresh_hz: real.display.refresh_hz,
            refreshes,
        };
        video::write_references(
            dir,
            &key,
            &grid,
            source,
            references,
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
        score_runs(runs, scoring, references, source, progress)?;
    }
    Ok(())
}

/// The references every real-clock run of the bench shares, empty at first: with
/// `--references DIR`, backed by the store of this scene, renderer, size, reference quality
/// and renderer revision in `DIR`; not where that key is not [`StoreKey::reusable`], which
/// renders its own.
pub fn screen_references(
    config: &BenchConfig,
    described: &Described,
    quality: Quality,
    source: &dyn FrameSource,
) -> Result<TimedReferences> {
    let references = TimedReferences::new(quality);
    let Some(dir) = &config.references else {
        return Ok(references);
    };
    let key = store_key(described, quality, source);
    if !key.reusable() {
        eprintln!(
            "bench: --references {} not used: the renderer's sources have uncommitted \
             changes, so this run renders its own references",
            dir.display()
        );
        return Ok(references);
    }
    let store = ReferenceStore::open(dir, &key)?;
    eprintln!("bench: references kept in {}", store.folder().display());
    Ok(references.with_store(store))
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
        renderer_revision: machine::reference_revision(),
    }
}
