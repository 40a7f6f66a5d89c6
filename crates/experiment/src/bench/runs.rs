//! The bench's runs: every controller of every arm over the sweep (frame clock) or for a
//! span of display time (real clock), the best fixed quality after the first `fixed`, and
//! what each finished run leaves behind (its recording, its video, the pictures its
//! displayed quality still needs).

use super::BenchConfig;
use super::arms::Arm;
use super::displayed::run_samples;
use super::experiment::{Capture, Sweep, run_controller, search_best_fixed};
use super::playback;
use super::quality::References;
use super::real_clock::{Keep, RealSweep, run_controller_real};
use super::record::ControllerRun;
use super::report::quality_label;
use super::source::FrameSource;
use super::video::{self, VideoRun};
use anyhow::Result;
use indicatif::ProgressBar;
use std::collections::BTreeSet;
use steadyray_control::{Band, Bounds, Controller, ControllerSpec, Setup, from_name};

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
}

impl Runner<'_> {
    /// How many runs the bench makes: every controller in every arm, and the best fixed
    /// quality once per arm after the first `fixed` (unless `--no-best-fixed`).
    fn run_count(&self, specs: &[ControllerSpec]) -> usize {
        let best_fixed = !self.config.no_best_fixed && specs.iter().any(|s| s.name == "fixed");
        self.config.temporal.modes().len() * (specs.len() + usize::from(best_fixed))
    }

    /// Runs every controller of every arm, in the order of `specs` (each controller in
    /// every arm before the next), the best fixed quality after the first `fixed` of each
    /// arm.
    pub fn run_arms(
        &mut self,
        source: &mut dyn FrameSource,
        arms: &mut [Arm],
        specs: &[ControllerSpec],
    ) -> Result<Vec<ControllerRun>> {
        let run_count = self.run_count(specs);
        let mut runs = Vec::new();
        let mut best_fixed_due = vec![!self.config.no_best_fixed; arms.len()];
        for (i, spec) in specs.iter().enumerate() {
            for (arm, best_due) in arms.iter_mut().zip(&mut best_fixed_due) {
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
                if spec.name == "fixed" && *best_due {
                    *best_due = false;
                    let run = self.run_best_fixed(source, (arm.band, arm.setup), arm.temporal)?;
                    runs.push(self.keep(run, run_count)?);
                }
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

    /// Searches the best fixed quality of an arm in its band and runs it.
    fn run_best_fixed(
        &self,
        source: &mut dyn FrameSource,
        (band, setup): (Band, Setup),
        temporal: bool,
    ) -> Result<ControllerRun> {
        self.progress.inc_length(self.per_run);
        let arm_sweep = Sweep { band, ..self.sweep };
        let best = search_best_fixed(source, &arm_sweep, self.config.search_views, self.progress)?;
        let mut fixed = from_name(
            "fixed",
            Setup {
                start: best,
                ..setup
            },
            "",
        )?;
        let label = format!(
            "best fixed {}{}",
            quality_label(&best, &self.bounds),
            self.suffix(temporal)
        );
        source.set_temporal(temporal)?;
        self.run_one(source, fixed.as_mut(), &label, (band, temporal))
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
