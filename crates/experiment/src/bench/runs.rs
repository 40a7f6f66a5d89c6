//! The bench's runs: every controller of every arm over the sweep (frame clock) or for a
//! span of display time (real clock), the fixed baselines after the first `fixed` (the
//! most-in-band fixed quality and, where the displayed quality is measured, the
//! best-looking one), and what each finished run leaves behind (its recording, its video,
//! the pictures its displayed quality still needs).

use super::arms::Arm;
use super::best_looking::{self, lowest_flip};
use super::displayed::{TimedReferences, run_samples};
use super::experiment::{Capture, Sweep, run_controller, search_most_in_band_fixed};
use super::playback;
use super::quality::References;
use super::real_clock::{Keep, RealSweep, run_controller_real};
use super::record::ControllerRun;
use super::report::quality_label;
use super::screen_quality::{Scoring, score_runs};
use super::source::FrameSource;
use super::video::{self, VideoRun};
use super::{BenchConfig, BestLookingFixed};
use anyhow::{Context, Result};
use indicatif::ProgressBar;
use std::collections::BTreeSet;
use steadyray_control::{Band, Bounds, Controller, ControllerSpec, Quality, Setup, from_name};

/// What every run shares, and what the finished runs left for after them.
pub struct Runner<'a> {
    /// The bench's configuration.
    pub config: &'a BenchConfig,
    /// The quality bounds (for the fixed runs' labels).
    pub bounds: Bounds,
    /// The frame clock's sweep (its band replaced by each arm's).
    pub sweep: Sweep,
    /// The real clock's runs, when it runs (its band replaced by each arm's).
    pub real: Option<RealSweep>,
    /// Told of every frame, or ms of display time.
    pub progress: &'a ProgressBar,
    /// The progress one run makes.
    pub per_run: u64,
    /// References of the frame clock's measured frames (`--quality`).
    pub references: Option<&'a References>,
    /// The samples whose displayed quality is measured (real clock).
    pub measured: Keep,
    /// The samples whose pictures a run keeps (real clock).
    pub keep_pictures: Keep,
    /// The full-scale size.
    pub resolution: (u32, u32),
    /// The videos written so far (`--video`).
    pub video_runs: Vec<VideoRun>,
    /// The references of the screen every run's displayed quality is measured against
    /// (real clock, `--quality`): those the best-looking search renders are shared with the
    /// runs measured after the runs.
    pub screen_references: TimedReferences,
}

impl Runner<'_> {
    /// Whether the best-looking fixed quality runs after the first `fixed` of each arm: where
    /// the displayed quality is measured, unless `--no-best-looking-fixed`.
    fn best_looking_with_fixed(&self) -> bool {
        self.config.best_looking_fixed == BestLookingFixed::WithFixed
            && self.real.is_some()
            && self.config.quality
    }

    /// How many runs the bench reports: every controller in every arm, and once per arm
    /// after the first `fixed` the most-in-band fixed quality (unless `--no-in-band-fixed`)
    /// and the best-looking one (where it runs); with `--only-best-looking-fixed`, the
    /// best-looking one per arm.
    fn run_count(&self, specs: &[ControllerSpec]) -> usize {
        let per_arm = match self.config.best_looking_fixed {
            BestLookingFixed::Only => 1,
            _ if specs.iter().any(|s| s.name == "fixed") => {
                specs.len()
                    + usize::from(!self.config.no_in_band_fixed)
                    + usize::from(self.best_looking_with_fixed())
            }
            _ => specs.len(),
        };
        self.config.temporal.modes().len() * per_arm
    }

    /// Runs every controller of every arm, in the order of `specs` (each controller in
    /// every arm before the next), the fixed baselines after the first `fixed` of each arm;
    /// with `--only-best-looking-fixed` the best-looking fixed quality of each arm alone.
    pub fn run_arms(
        &mut self,
        source: &mut dyn FrameSource,
        arms: &mut [Arm],
        specs: &[ControllerSpec],
    ) -> Result<Vec<ControllerRun>> {
        let run_count = self.run_count(specs);
        let mut runs = Vec::new();
        let mut baselines_due = vec![true; arms.len()];
        for (i, spec) in specs.iter().enumerate() {
            for (arm, due) in arms.iter_mut().zip(&mut baselines_due) {
                let suffix = self.suffix(arm.temporal);
                let controller = &mut arm.controllers[i];
                let label = match spec.name.as_str() {
                    "fixed" => format!(
                        "fixed {}",
                        quality_label(&controller.quality(), &self.bounds)
                    ),
                    _ => spec.label(),
                };
                source.set_temporal(arm.temporal)?;
                let label = format!("{label}{suffix}");
                let mode = (arm.band, arm.temporal);
                let run = self.run_one(source, controller.as_mut(), &label, mode)?;
                runs.push(self.keep(run, run_count)?);
                if spec.name == "fixed" && *due {
                    *due = false;
                    if !self.config.no_in_band_fixed {
                        let run = self.run_most_in_band_fixed(source, arm)?;
                        runs.push(self.keep(run, run_count)?);
                    }
                    if self.best_looking_with_fixed() {
                        runs.push(self.run_best_looking_fixed(source, arm, run_count)?);
                    }
                }
            }
        }
        if self.config.best_looking_fixed == BestLookingFixed::Only {
            for arm in arms.iter() {
                runs.push(self.run_best_looking_fixed(source, arm, run_count)?);
            }
        }
        Ok(runs)
    }

    /// The label suffix of an arm's runs.
    fn suffix(&self, temporal: bool) -> &'static str {
        match (temporal, self.config.warp) {
            (false, _) => "",
            (true, false) => " +temporal",
            (true, true) => " +temporal +warp",
        }
    }

    /// Searches the most-in-band fixed quality of an arm in its band and runs it.
    fn run_most_in_band_fixed(
        &self,
        source: &mut dyn FrameSource,
        arm: &Arm,
    ) -> Result<ControllerRun> {
        self.progress.inc_length(self.per_run);
        let arm_sweep = Sweep {
            band: arm.band,
            ..self.sweep
        };
        let views = self.config.search_views;
        let best = search_most_in_band_fixed(source, &arm_sweep, views, self.progress)?;
        self.run_fixed(source, arm, best, "most-in-band fixed")
    }

    /// Runs the fixed quality `quality` in `arm`, labelled `name` and the quality.
    fn run_fixed(
        &self,
        source: &mut dyn FrameSource,
        arm: &Arm,
        quality: Quality,
        name: &str,
    ) -> Result<ControllerRun> {
        let setup = Setup {
            start: quality,
            ..arm.setup
        };
        let mut fixed = from_name("fixed", setup, "")?;
        let label = format!(
            "{name} {}{}",
            quality_label(&quality, &self.bounds),
            self.suffix(arm.temporal)
        );
        source.set_temporal(arm.temporal)?;
        self.run_one(source, fixed.as_mut(), &label, (arm.band, arm.temporal))
    }

    /// Runs every candidate of the best-looking fixed quality in `arm` for the display span
    /// ([`best_looking`]), each kept (its video written) and its displayed quality measured
    /// at once, and returns the one with the lowest displayed FLIP; the others' videos are
    /// removed. Says on stderr what each scored.
    fn run_best_looking_fixed(
        &mut self,
        source: &mut dyn FrameSource,
        arm: &Arm,
        run_count: usize,
    ) -> Result<ControllerRun> {
        let real = self
            .real
            .context("the best-looking fixed quality is chosen on the real clock")?;
        let scoring = Scoring {
            period_ms: real.display.period_ms(),
            measured: self.measured,
            size: self.resolution,
        };
        let candidates = best_looking::candidates(&self.bounds);
        self.progress
            .inc_length(self.per_run * candidates.len() as u64);
        let mut tried = Vec::with_capacity(candidates.len());
        for quality in candidates {
            tried.push(self.run_candidate(source, (arm, quality), scoring, run_count)?);
        }
        let flips: Vec<Option<f64>> = tried.iter().map(|(_, flip)| *flip).collect();
        let best = lowest_flip(&flips)
            .context("no best-looking fixed candidate showed a sample to score (--duration)")?;
        let (winner, flip) = tried.swap_remove(best);
        for (loser, _) in &tried {
            self.remove_video(&loser.name)?;
        }
        self.say(&format!(
            "bench: {}: the lowest displayed FLIP ({:.4}) of {} candidates",
            winner.name,
            flip.unwrap_or_default(),
            tried.len() + 1
        ));
        Ok(winner)
    }

    /// Runs one best-looking fixed candidate, `quality` in `arm`, keeps it (its video
    /// written) and measures its displayed quality at once; says its displayed FLIP.
    fn run_candidate(
        &mut self,
        source: &mut dyn FrameSource,
        (arm, quality): (&Arm, Quality),
        scoring: Scoring,
        run_count: usize,
    ) -> Result<(ControllerRun, Option<f64>)> {
        let run = self.run_fixed(source, arm, quality, best_looking::LABEL)?;
        let mut run = self.keep(run, run_count)?;
        // References are plain frames.
        source.set_temporal(false)?;
        let references = &mut self.screen_references;
        let runs = std::slice::from_mut(&mut run);
        score_runs(runs, scoring, references, source, self.progress)?;
        let flip = displayed_flip(&run);
        let score = flip.map_or_else(|| "- (no sample)".to_string(), |f| format!("{f:.4}"));
        self.say(&format!("bench: {}: displayed FLIP {score}", run.name));
        Ok((run, flip))
    }

    /// Says `line` on stderr, above the progress bar (also where the bar is hidden).
    fn say(&self, line: &str) {
        self.progress.suspend(|| eprintln!("{line}"));
    }

    /// Removes the video of the run named `name` (`--video`), if one was written.
    fn remove_video(&mut self, name: &str) -> Result<()> {
        let Some(dir) = &self.config.video else {
            return Ok(());
        };
        if let Some(i) = self.video_runs.iter().position(|v| v.name == name) {
            let removed = self.video_runs.remove(i);
            video::remove_run(dir, &removed.folder)?;
        }
        Ok(())
    }

    /// One run of `controller` in `band`: over the sweep, or under the real clock (a
    /// temporal run warping its refreshes without a new frame with `--warp`).
    fn run_one(
        &self,
        source: &mut dyn FrameSource,
        controller: &mut dyn Controller,
        label: &str,
        (band, temporal): (Band, bool),
    ) -> Result<ControllerRun> {
        match &self.real {
            None => {
                let sweep = Sweep { band, ..self.sweep };
                let capture = Capture {
                    references: self.references,
                    record: self.config.record.is_some(),
                };
                run_controller(source, controller, label, &sweep, capture, self.progress)
            }
            Some(r) => {
                let r = RealSweep {
                    band,
                    warp: self.config.warp && temporal,
                    ..*r
                };
                let keep = self.keep_pictures;
                run_controller_real(source, controller, label, &r, keep, self.progress)
            }
        }
    }

    /// Encodes a finished run's frames (between runs, never during one) and frees those no
    /// longer needed.
    fn keep(&mut self, mut run: ControllerRun, run_count: usize) -> Result<ControllerRun> {
        let (width, height) = self.resolution;
        if let Some(dir) = &self.config.record {
            let folder = playback::run_folder(dir, &run.name, run_count);
            playback::write_recording(&run, &folder, width, height)?;
            self.progress.println(format!(
                "bench: recorded {} to {}",
                run.name,
                folder.display()
            ));
            run.recorded = Vec::new();
        }
        if let (Some(shown), Some(r)) = (run.display.as_mut(), &self.real) {
            if let Some(dir) = &self.config.video {
                let folder = video::write_run(dir, &run.name, shown, &r.display, (width, height))?;
                self.progress
                    .println(format!("bench: video of {} in {folder}", run.name));
                self.video_runs.push(VideoRun {
                    name: run.name.clone(),
                    folder,
                });
            }
            let measured = self.measured;
            let needed: BTreeSet<Option<usize>> =
                run_samples(shown, r.display.period_ms(), |i| measured.wants(i))
                    .iter()
                    .map(|s| s.frame)
                    .collect();
            shown.pictures.retain(|frame, _| needed.contains(frame));
            shown
                .warps
                .pictures
                .retain(|&refresh, _| measured.wants(refresh));
        }
        Ok(run)
    }
}

/// A real-clock run's displayed FLIP (mean over its samples), once measured.
fn displayed_flip(run: &ControllerRun) -> Option<f64> {
    run.display
        .as_ref()
        .and_then(|shown| shown.quality.as_ref())
        .map(|q| q.flip_mean)
}
