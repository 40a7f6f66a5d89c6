//! `steadyray calibrate --motion`: the quality model of the `perceptual` controller
//! (`motion.json`, format in `steadyray_control::motion_model`): how good the displayed video
//! looks over a grid of screen speeds, frame times (whole numbers of refreshes) and points of
//! a calibrated ladder.
//!
//! Each cell is a short stimulus: the camera turns in place at the yaw rate that moves the
//! picture at the cell's speed (mean over the picture, as `crates/motion` measures it),
//! centred on a view of the scene's path, the world frozen at that view's time. Frames are
//! rendered at the cell's ladder point and shown on the display model exactly every
//! `refreshes` refreshes, each rendering the world at its display time (as the real clock
//! does for a frame that keeps its band); the reference is the world at every refresh at the
//! reference quality. A cell's score is the displayed video against the reference video:
//! mean displayed FLIP (the bench's, under the same viewing set-up) always; with `--jod`,
//! ColorVideoVDP's JOD by the project's JOD tool (`scripts/jod/jod.py`), which the table then
//! holds. A still picture looks the same at every frame time, so speed 0 is rendered once
//! per point and shared. Scores are averaged over the views.
//!
//! With `warp` (`calibrate --motion --warp`) the stimuli are shown as `bench --temporal on
//! --warp` shows them: each run accumulates its frames into a new temporal history, and each
//! refresh between two frames shows the last frame warped to that refresh's camera, so the
//! table scores what a long frame costs when its age is warped away.

use crate::bench::displayed::{TimedReferences, measure, screen_samples};
use crate::bench::machine::reference_revision;
use crate::bench::reference_store::{StoreKey, digest};
use crate::bench::screen::{DisplayRun, Warps};
use crate::bench::source::{
    FrameSource, HandOver, Measured, PathPoint, read_picture, render_measured, set_history,
    warp_measured,
};
use crate::bench::video::{self, ReferenceKey, VideoIndex, VideoRun};
use crate::frame_loop::FrameLoop;
use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;
use steadyray_control::ladder::Ladder;
use steadyray_control::{Metric, MotionModel, Quality};
use steadyray_display::model::refresh_at_or_after;
use steadyray_display::{DisplayConfig, DisplayFigures, RealClock, SyncMode, ViewingSetup};
use steadyray_motion::{MotionProbe, ScreenSpeed, Shot};
use steadyray_quality::Rgb8Image;
use steadyray_render::sample_stream::check_reference_spp;
use steadyray_render::{FrameBudget, Renderer, SampleStream, check_image_size};
use steadyray_scene::{Camera, Scene};

/// What to measure.
#[derive(Clone, Debug)]
pub struct MotionPlan {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The ladder the points come from.
    pub ladder: Ladder,
    /// How many of its points to score (0: all).
    pub points: usize,
    /// Screen speeds, deg/s, strictly rising.
    pub speeds: Vec<f64>,
    /// Frame times in refreshes, strictly rising.
    pub refreshes: Vec<u32>,
    /// The display's refresh rate, Hz.
    pub refresh_hz: f64,
    /// Each stimulus's length, s.
    pub stimulus_s: f64,
    /// Views of the path the stimuli turn around, evenly spaced in time.
    pub views: u32,
    /// The references' quality.
    pub reference: Quality,
    /// Where to write the stimuli's videos, for the JOD tool.
    pub video: Option<PathBuf>,
    /// How to run the JOD tool on them (the table then holds JOD).
    pub jod: Option<JodTool>,
    /// Show the stimuli in the temporal mode with warped refreshes between frames.
    pub warp: bool,
}

impl MotionPlan {
    /// The ladder points scored are those calibrated at no more than twice the longest
    /// frame time, ms.
    fn max_point_ms(&self) -> f64 {
        let longest = self.refreshes.iter().copied().max().unwrap_or(1);
        2.0 * f64::from(longest) * 1000.0 / self.refresh_hz
    }
}

/// The JOD tool and what to keep of the videos it scored.
#[derive(Clone, Debug)]
pub struct JodTool {
    /// The Python that runs the tool.
    pub python: String,
    /// The JOD tool's script.
    pub script: PathBuf,
    /// Keep every video (else only `video.json` and `jod.json` stay once scored).
    pub keep_video: bool,
}

/// `count` points of the ladder, spread evenly by the logarithm of their rays, the cheapest
/// and the dearest included (all of them when `count` is 0 or at least their number), among
/// the points its calibration timed at `max_ms` or less (the cheapest always): a point that
/// takes far longer than the longest frame time can never be chosen.
pub fn pick_points(ladder: &Ladder, count: usize, max_ms: f64) -> Ladder {
    let affordable: Vec<_> = ladder
        .points
        .iter()
        .enumerate()
        .filter(|(i, p)| *i == 0 || p.ms <= max_ms)
        .map(|(_, p)| *p)
        .collect();
    let ladder = Ladder {
        points: affordable,
        ..ladder.clone()
    };
    let n = ladder.points.len();
    if count == 0 || count >= n {
        return ladder;
    }
    let log = |i: usize| ladder.points[i].rays.max(1.0).ln();
    let (lo, hi) = (log(0), log(n - 1));
    let mut chosen: Vec<usize> = Vec::new();
    for j in 0..count {
        let want = lo + (hi - lo) * j as f64 / (count - 1).max(1) as f64;
        let best = (0..n)
            .filter(|i| !chosen.contains(i))
            .min_by(|&a, &b| (log(a) - want).abs().total_cmp(&(log(b) - want).abs()))
            .expect("fewer points chosen than the ladder holds");
        chosen.push(best);
    }
    chosen.sort_unstable();
    Ladder {
        points: chosen.iter().map(|&i| ladder.points[i]).collect(),
        ..ladder.clone()
    }
}

/// A camera turning in place at a constant yaw rate, centred (at `centre_s`) on a view.
#[derive(Clone, Copy, Debug)]
struct Turn {
    base: Camera,
    yaw: f32,
    pitch: f32,
    rad_per_s: f64,
    centre_s: f64,
}

impl Turn {
    /// A turn at `rad_per_s` through `view` at stimulus time `centre_s`.
    fn new(view: Camera, rad_per_s: f64, centre_s: f64) -> Self {
        let f = view.forward.normalize();
        Self {
            base: view,
            yaw: (-f.x).atan2(-f.z),
            pitch: f.y.clamp(-1.0, 1.0).asin(),
            rad_per_s,
            centre_s,
        }
    }

    fn camera(&self, t_s: f64) -> Camera {
        let yaw = self.yaw + (self.rad_per_s * (t_s - self.centre_s)) as f32;
        Camera::yaw_pitch(self.base.eye, yaw, self.pitch, self.base.vfov_deg)
    }
}

/// The yaw rate that moves the picture of `view` at `speed` deg/s on average: the turn is a
/// rotation about the eye, so the speed is proportional to the rate (measured at 10°/s).
fn rate_for_speed(probe: &mut MotionProbe, view: Camera, world_s: f64, speed: f64) -> Result<f64> {
    if speed == 0.0 {
        return Ok(0.0);
    }
    let unit = 10f64.to_radians();
    let turn = Turn::new(view, unit, 0.0);
    let dt = 1.0 / 240.0;
    // The world stays at the view's time: only the camera turns.
    let at = |t: f64| Shot {
        camera: turn.camera(t),
        time_s: t,
        world_s,
    };
    let measured: ScreenSpeed = probe.measure(&at(0.0), &at(dt))?;
    if measured.mean_deg_s <= 0.0 {
        bail!("a turn of this view moves nothing on screen: cannot set a speed");
    }
    Ok(unit * speed / measured.mean_deg_s)
}

/// Frames of one stimulus: the renderer, turning camera and frozen world of a view.
struct StimulusSource<'a> {
    renderer: &'a mut dyn Renderer,
    turn: Turn,
    world_s: f64,
    /// Renders the frames at the plan's size and says which time the controller sees.
    frame_loop: FrameLoop,
    duration_s: f64,
}

impl FrameSource for StimulusSource<'_> {
    fn describe(&self) -> (String, String) {
        let info = self.renderer.info();
        (info.backend, info.device)
    }

    fn resolution(&self) -> (u32, u32) {
        self.frame_loop.full_size()
    }

    fn path_duration_s(&self) -> f64 {
        self.duration_s
    }

    fn frame_within(
        &mut self,
        at: PathPoint,
        q: Quality,
        budget: Option<FrameBudget>,
    ) -> Result<Measured> {
        let t_s = match at {
            PathPoint::Time { t_s, .. } => t_s,
            PathPoint::Frame { k, n } => self.duration_s * f64::from(k) / f64::from(n.max(1)),
        };
        let camera = self.turn.camera(t_s);
        // The world stands still at the view's time; the stimulus's motion is the camera's
        // turn, known, not measured.
        render_measured(
            &mut self.frame_loop,
            &mut *self.renderer,
            &camera,
            self.world_s,
            (q, budget),
        )
    }

    fn hand_over(&mut self) -> Result<HandOver> {
        Ok(HandOver {
            ms: 0.0,
            image: Some(read_picture(&mut *self.renderer)?),
        })
    }

    fn warp(&mut self, t_s: f64, picture: bool) -> Result<HandOver> {
        let camera = self.turn.camera(t_s);
        warp_measured(&mut *self.renderer, &camera, picture)
    }

    fn takes_wall_time(&self) -> bool {
        false
    }

    fn load_changes(&self, _n: u32) -> Option<Vec<usize>> {
        None
    }

    fn set_temporal(&mut self, on: bool) -> Result<()> {
        set_history(&mut *self.renderer, self.frame_loop.full_size(), on)
    }

    fn last_picture(&mut self) -> Result<Option<Rgb8Image>> {
        Ok(Some(read_picture(&mut *self.renderer)?))
    }

    fn set_sample_stream(&mut self, stream: SampleStream) {
        self.renderer.set_sample_stream(stream);
    }
}

/// The screen of a stimulus at ladder point `q`, each frame shown for exactly `refreshes`
/// refreshes: before the first frame, one rendered at time 0 (the bench's warm-up frame).
/// With `warp`, the frames accumulate into a new temporal history and every refresh after a
/// frame's first shows it warped to that refresh's time.
fn stimulus_run(
    source: &mut StimulusSource<'_>,
    display: DisplayConfig,
    refreshes: u32,
    q: Quality,
    warp: bool,
) -> Result<DisplayRun> {
    let period_ms = display.period_ms();
    // Done a tenth of a millisecond before its refresh: shown exactly on it.
    let busy_ms = f64::from(refreshes) * period_ms - 0.1;
    let mut clock = RealClock::new(display, source.duration_s)?;
    clock.expect(busy_ms);
    // The refreshes of the stimulus (as its references).
    let count = refresh_at_or_after(source.duration_s * 1000.0, period_ms) as usize;
    let mut warps = Warps::default();
    // Warps of the frame on screen since refresh `shown` to the refreshes before `until`.
    let mut warp_between = |source: &mut StimulusSource<'_>, shown: usize, until: usize| {
        for refresh in shown + 1..until.min(count) {
            let t_s = refresh as f64 * period_ms / 1000.0;
            let warped = source.warp(t_s, true)?;
            warps.record(refresh, warped.ms, warped.image);
        }
        anyhow::Ok(())
    };
    source.set_temporal(warp)?;
    let mut pictures = BTreeMap::new();
    source.frame(PathPoint::Time { index: 0, t_s: 0.0 }, q)?;
    pictures.insert(None, picture(source)?);
    let mut world_s = Vec::new();
    let mut shown = 0;
    while let Some(slot) = clock.next_frame() {
        if warp {
            let next = (slot.show_ms / period_ms).round() as usize;
            warp_between(source, shown, next)?;
        }
        let at = PathPoint::Time {
            index: slot.index,
            t_s: slot.world_s(),
        };
        source.frame(at, q)?;
        pictures.insert(Some(slot.index), picture(source)?);
        world_s.push(slot.world_s());
        let times = clock.present(busy_ms, 0.0)?;
        shown = (times.visible_ms / period_ms).round() as usize;
    }
    if warp {
        warp_between(source, shown, count)?;
    }
    source.set_temporal(false)?;
    let timeline = clock.finish();
    Ok(DisplayRun {
        figures: DisplayFigures::of(&timeline),
        timeline,
        pictures,
        warps,
        world_s,
        lead_in_world_s: 0.0,
        quality: None,
        busy_pct: None,
    })
}

/// The last frame's tone-mapped picture at its rendered size.
fn picture(source: &mut StimulusSource<'_>) -> Result<Rgb8Image> {
    source
        .hand_over()?
        .image
        .context("the stimulus renderer gave no picture")
}

/// A run's name in a stimulus folder: its frame time and ladder point.
fn run_name(refreshes: u32, q: &Quality) -> String {
    format!("r{refreshes}-S{}-R{}-x{}", q.spp, q.depth, q.scale)
}

/// Scores of one (view, speed) stimulus folder: by (refreshes, point).
type Cells = BTreeMap<(u32, usize), f64>;

/// Runs the JOD tool on a finished stimulus folder and reads its scores (reusing a
/// `jod.json` that already holds every run).
pub(crate) fn score_with_jod(
    tool: &JodTool,
    folder: &Path,
    runs: &[String],
) -> Result<BTreeMap<String, f64>> {
    let read = || -> Option<BTreeMap<String, f64>> {
        let text = std::fs::read_to_string(folder.join("jod.json")).ok()?;
        let value: serde_json::Value = serde_json::from_str(&text).ok()?;
        let scores: BTreeMap<String, f64> = serde_json::from_value(value["jod"].clone()).ok()?;
        runs.iter()
            .all(|r| scores.contains_key(r))
            .then_some(scores)
    };
    if let Some(scores) = read() {
        return Ok(scores);
    }
    let status = Command::new(&tool.python)
        .arg(&tool.script)
        .arg(folder)
        .status()
        .with_context(|| {
            format!(
                "cannot run the JOD tool: {} {}",
                tool.python,
                tool.script.display()
            )
        })?;
    if !status.success() {
        bail!("the JOD tool failed ({status}) on {}", folder.display());
    }
    read().with_context(|| format!("{}/jod.json lacks some runs", folder.display()))
}

/// Removes a scored folder's pictures and videos, keeping its scores and what it held.
pub(crate) fn prune_video(folder: &Path) -> Result<()> {
    for entry in std::fs::read_dir(folder)? {
        let path = entry?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if ["video.json", "jod.json", "flip.json", "stimulus.json"].contains(&name) {
            continue;
        }
        if path.is_dir() {
            std::fs::remove_dir_all(&path)
        } else {
            std::fs::remove_file(&path)
        }
        .with_context(|| format!("cannot remove {}", path.display()))?;
    }
    Ok(())
}

/// What a stimulus folder holds (`stimulus.json`, written when it is complete): a later
/// calibration reuses its scores (displayed FLIP, and JOD once scored) when this matches, so
/// the long JOD scoring can be done folder by folder and run by run in between. A change of
/// the renderer does not show here: delete the folders after one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct StimulusKey {
    scene: String,
    resolution: [u32; 2],
    refresh_hz: f64,
    stimulus_s: f64,
    view_s: f64,
    speed_deg_s: f64,
    reference: Quality,
    runs: Vec<String>,
    /// Shown in the temporal mode with warped refreshes (`--warp`).
    #[serde(default)]
    warp: bool,
}

/// Displayed FLIP of each run of a stimulus folder (`flip.json`).
#[derive(Debug, Serialize, Deserialize)]
struct FlipScores {
    displayed_flip: BTreeMap<String, f64>,
}

/// A stimulus's scores by (refreshes, point): displayed FLIP, and JOD when scored.
struct StimulusScores {
    flip: Cells,
    jod: Cells,
}

/// One view turning at one speed, shown at every frame time of `refreshes`.
struct Stimulus {
    view: u32,
    view_s: f64,
    speed: f64,
    rate: f64,
    camera: Camera,
    refreshes: Vec<u32>,
}

impl Stimulus {
    /// The runs, by (refreshes, point index) and name.
    fn runs(&self, ladder: &Ladder) -> Vec<((u32, usize), String)> {
        let mut out = Vec::new();
        for &k in &self.refreshes {
            for (p, point) in ladder.points.iter().enumerate() {
                out.push(((k, p), run_name(k, &point.quality())));
            }
        }
        out
    }

    /// Renders (or reuses) the stimulus and scores every run: displayed FLIP, and JOD with
    /// the JOD tool.
    fn score(
        &self,
        renderer: &mut dyn Renderer,
        scene: &Scene,
        plan: &MotionPlan,
        ladder: &Ladder,
        progress: &ProgressBar,
    ) -> Result<StimulusScores> {
        let runs = self.runs(ladder);
        let names: Vec<String> = runs.iter().map(|(_, n)| n.clone()).collect();
        let key = StimulusKey {
            scene: scene.name.clone(),
            resolution: [plan.width, plan.height],
            refresh_hz: plan.refresh_hz,
            stimulus_s: plan.stimulus_s,
            view_s: self.view_s,
            speed_deg_s: self.speed,
            reference: plan.reference,
            runs: names.clone(),
            warp: plan.warp,
        };
        let label = format!("view {}, {} deg/s", self.view, self.speed);
        let folder = plan
            .video
            .as_ref()
            .map(|dir| dir.join(format!("view{}-speed{}", self.view, self.speed)));
        let reused = folder.as_deref().and_then(|f| reuse(f, &key));
        let flips = match reused {
            Some(flips) => {
                progress.inc(runs.len() as u64);
                flips
            }
            None => {
                let output = folder.as_deref().map(|f| (f, &key));
                self.render(renderer, scene, plan, ladder, output, progress)?
            }
        };
        let by_cell = |scores: &BTreeMap<String, f64>| -> Cells {
            runs.iter()
                .filter_map(|(cell, name)| scores.get(name).map(|&v| (*cell, v)))
                .collect()
        };
        let mut jod = Cells::new();
        if let (Some(tool), Some(folder)) = (&plan.jod, &folder) {
            progress.set_message(format!("{label}: JOD"));
            let started = Instant::now();
            let scores = score_with_jod(tool, folder, &names)?;
            progress.println(format!(
                "calibrate: JOD of {label} ({:.0} s)",
                started.elapsed().as_secs_f64()
            ));
            jod = by_cell(&scores);
            if !tool.keep_video {
                prune_video(folder)?;
            }
        }
        Ok(StimulusScores {
            flip: by_cell(&flips),
            jod,
        })
    }

    /// Renders the references and every run and measures their displayed FLIP; given a
    /// folder, writes the videos (`video.json`), `flip.json` and, last, `stimulus.json`
    /// (its key).
    fn render(
        &self,
        renderer: &mut dyn Renderer,
        scene: &Scene,
        plan: &MotionPlan,
        ladder: &Ladder,
        output: Option<(&Path, &StimulusKey)>,
        progress: &ProgressBar,
    ) -> Result<BTreeMap<String, f64>> {
        let folder = output.map(|(folder, _)| folder);
        let display = DisplayConfig::new(plan.refresh_hz, SyncMode::Vsync)?;
        let viewing = ViewingSetup::standard_fhd();
        let size = (plan.width, plan.height);
        let ppd = viewing.pixels_per_degree(plan.width) as f32;
        let period_ms = display.period_ms();
        let count = refresh_at_or_after(plan.stimulus_s * 1000.0, period_ms) as usize;
        let grid: Vec<f64> = (0..count).map(|i| i as f64 * period_ms / 1000.0).collect();
        let info = renderer.info();
        let mut source = StimulusSource {
            renderer,
            turn: Turn::new(self.camera, self.rate, 0.5 * plan.stimulus_s),
            world_s: self.view_s,
            frame_loop: FrameLoop::new((plan.width, plan.height)),
            duration_s: plan.stimulus_s,
        };
        progress.set_message(format!(
            "view {}, {} deg/s: references",
            self.view, self.speed
        ));
        let reference_key = ReferenceKey {
            set_up: StoreKey {
                scene: format!("{} (view {}, {} deg/s)", scene.name, self.view, self.speed),
                scene_digest: digest(&format!("{scene:?}")),
                backend: info.backend,
                device: info.device,
                resolution: [plan.width, plan.height],
                spp: plan.reference.spp,
                depth: plan.reference.depth,
                renderer_revision: reference_revision(),
            },
            refresh_hz: plan.refresh_hz,
            refreshes: count,
        };
        let mut references = TimedReferences::new(plan.reference);
        match folder {
            Some(folder) => {
                std::fs::create_dir_all(folder)
                    .with_context(|| format!("cannot create {}", folder.display()))?;
                for done in ["stimulus.json", "video.json", "jod.json"] {
                    let _ = std::fs::remove_file(folder.join(done));
                }
                video::write_references(
                    folder,
                    &reference_key,
                    &grid,
                    &mut source,
                    &mut references,
                    |_| true,
                    || (),
                )?;
            }
            None => references.render_missing(&mut source, grid.iter().copied(), || ())?,
        }
        let mut flips = BTreeMap::new();
        let mut videos = Vec::new();
        for ((k, p), name) in self.runs(ladder) {
            progress.set_message(format!(
                "view {}, {} deg/s, {k} refreshes, point {p}",
                self.view, self.speed
            ));
            let point = ladder.points[p].quality();
            let run = stimulus_run(&mut source, display, k, point, plan.warp)?;
            let samples = screen_samples(&run, period_ms, |_| true);
            let shown = measure(&run, &samples, &mut references, size, ppd)?
                .context("a stimulus showed no refresh")?;
            flips.insert(name.clone(), shown.flip_mean);
            if let Some(folder) = folder {
                let written = video::write_run(folder, &name, &run, &display, size)?;
                videos.push(VideoRun {
                    name,
                    folder: written,
                });
            }
            progress.inc(1);
        }
        if let Some((folder, key)) = output {
            let text = serde_json::to_string_pretty(&FlipScores {
                displayed_flip: flips.clone(),
            })?;
            write_atomically(&folder.join("flip.json"), &text)?;
            video::write_index(
                folder,
                &VideoIndex {
                    scene: scene.name.clone(),
                    refresh_hz: plan.refresh_hz,
                    refreshes: count,
                    resolution: [plan.width, plan.height],
                    duration_s: plan.stimulus_s,
                    display,
                    viewing,
                    reference: reference_key,
                    runs: videos,
                },
            )?;
            write_atomically(
                &folder.join("stimulus.json"),
                &serde_json::to_string_pretty(key)?,
            )?;
        }
        Ok(flips)
    }
}

/// The displayed FLIP of a complete stimulus folder made for `key` (its `stimulus.json`
/// matches and its `flip.json` holds every run), or `None`.
fn reuse(folder: &Path, key: &StimulusKey) -> Option<BTreeMap<String, f64>> {
    let read = |name: &str| std::fs::read_to_string(folder.join(name)).ok();
    let stored: StimulusKey = serde_json::from_str(&read("stimulus.json")?).ok()?;
    let flips: FlipScores = serde_json::from_str(&read("flip.json")?).ok()?;
    (stored == *key
        && key
            .runs
            .iter()
            .all(|r| flips.displayed_flip.contains_key(r)))
    .then_some(flips.displayed_flip)
}

/// Writes `text` under a temporary name, then renames it over `path`.
fn write_atomically(path: &Path, text: &str) -> Result<()> {
    let temp = path.with_extension("partial");
    std::fs::write(&temp, text).with_context(|| format!("cannot write {}", temp.display()))?;
    std::fs::rename(&temp, path).with_context(|| format!("cannot write {}", path.display()))
}

/// The measured model: JOD when the JOD tool ran, else displayed FLIP; with JOD, the FLIP
/// table is returned beside it.
pub struct MotionTables {
    /// The model as scored (by JOD with the JOD tool, else by displayed FLIP).
    pub model: MotionModel,
    /// The displayed-FLIP model beside a JOD one.
    pub flip: Option<MotionModel>,
}

/// Measures the model of `plan` on `scene` (its path gives the views).
pub fn calibrate_motion(
    renderer: &mut dyn Renderer,
    scene: &Scene,
    plan: &MotionPlan,
    progress: &ProgressBar,
) -> Result<MotionTables> {
    check_plan(plan)?;
    let ladder = pick_points(&plan.ladder, plan.points, plan.max_point_ms());
    let viewing = ViewingSetup::standard_fhd();
    let mut probe = MotionProbe::new(scene, (plan.width, plan.height), viewing.clone())?;
    let period_ms = 1000.0 / plan.refresh_hz;
    // Sums over views of each cell's scores: displayed FLIP and JOD.
    let mut flip_sums: BTreeMap<(usize, u32, usize), f64> = BTreeMap::new();
    let mut jod_sums: BTreeMap<(usize, u32, usize), f64> = BTreeMap::new();
    for v in 0..plan.views {
        let view_s = scene.path.duration_s() * f64::from(v) / f64::from(plan.views);
        let view = scene.camera_at_time(view_s);
        for (si, &speed) in plan.speeds.iter().enumerate() {
            let stimulus = Stimulus {
                view: v,
                view_s,
                speed,
                rate: rate_for_speed(&mut probe, view, view_s, speed)?,
                camera: view,
                // A still picture: the same screen at every frame time.
                refreshes: if speed == 0.0 {
                    plan.refreshes[..1].to_vec()
                } else {
                    plan.refreshes.clone()
                },
            };
            let scores = stimulus.score(renderer, scene, plan, &ladder, progress)?;
            for (cells, sums) in [(&scores.flip, &mut flip_sums), (&scores.jod, &mut jod_sums)] {
                for &k in &plan.refreshes {
                    for p in 0..ladder.points.len() {
                        // Speed 0 shares its one frame time's score with the others.
                        let measured_k = if speed == 0.0 {
                            stimulus.refreshes[0]
                        } else {
                            k
                        };
                        if let Some(score) = cells.get(&(measured_k, p)) {
                            *sums.entry((si, k, p)).or_insert(0.0) += score;
                        }
                    }
                }
            }
        }
    }
    let table = |metric: Metric, sums: &BTreeMap<(usize, u32, usize), f64>| MotionModel {
        metric,
        scene: scene.name.clone(),
        resolution: [plan.width, plan.height],
        refresh_hz: plan.refresh_hz,
        stimulus_s: plan.stimulus_s,
        warped: plan.warp,
        viewing: serde_json::to_value(&viewing).unwrap_or(serde_json::Value::Null),
        ladder: ladder.clone(),
        speeds_deg_s: plan.speeds.clone(),
        frame_times_ms: plan
            .refreshes
            .iter()
            .map(|&k| f64::from(k) * period_ms)
            .collect(),
        scores: (0..plan.speeds.len())
            .map(|si| {
                plan.refreshes
                    .iter()
                    .map(|&k| {
                        (0..ladder.points.len())
                            .map(|p| sums[&(si, k, p)] / f64::from(plan.views))
                            .collect()
                    })
                    .collect()
            })
            .collect(),
    };
    let flip = table(Metric::DisplayedFlip, &flip_sums);
    flip.validate().map_err(anyhow::Error::msg)?;
    if plan.jod.is_none() {
        return Ok(MotionTables {
            model: flip,
            flip: None,
        });
    }
    let jod = table(Metric::Jod, &jod_sums);
    jod.validate().map_err(anyhow::Error::msg)?;
    Ok(MotionTables {
        model: jod,
        flip: Some(flip),
    })
}

/// The stimuli `plan` renders, for a progress bar.
pub fn stimulus_count(plan: &MotionPlan) -> u64 {
    let points = pick_points(&plan.ladder, plan.points, plan.max_point_ms())
        .points
        .len() as u64;
    let moving = plan.speeds.iter().filter(|&&s| s > 0.0).count() as u64;
    let still = plan.speeds.len() as u64 - moving;
    u64::from(plan.views) * points * (moving * plan.refreshes.len() as u64 + still)
}

/// Refuses a plan that would give an empty or malformed table.
fn check_plan(plan: &MotionPlan) -> Result<()> {
    let rising = |v: &[f64]| v.windows(2).all(|w| w[1] > w[0]);
    if plan.speeds.is_empty()
        || !rising(&plan.speeds)
        || plan.speeds.iter().any(|s| !(s.is_finite() && *s >= 0.0))
    {
        bail!("--speeds must be finite speeds of 0 or more, strictly rising");
    }
    let refreshes: Vec<f64> = plan.refreshes.iter().map(|&k| f64::from(k)).collect();
    if refreshes.is_empty() || !rising(&refreshes) || plan.refreshes[0] == 0 {
        bail!("--refreshes must be whole numbers of refreshes of 1 or more, strictly rising");
    }
    if plan.views == 0 {
        bail!("--views must be at least 1");
    }
    check_image_size(plan.width, plan.height)?;
    if !(plan.stimulus_s.is_finite() && plan.stimulus_s > 0.0 && plan.stimulus_s <= 60.0) {
        bail!("--stimulus must be a number of seconds above 0 and at most 60");
    }
    if plan.jod.is_some() && plan.video.is_none() {
        bail!("--jod scores the stimuli's videos: give --video DIR");
    }
    check_reference_spp(plan.reference.spp)?;
    plan.ladder.validate().map_err(anyhow::Error::msg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_control::ladder::{LadderPoint, Reference};
    use steadyray_render_cpu::CpuRenderer;

    fn ladder(points: &[(f32, f32, f64, f64)]) -> Ladder {
        Ladder {
            scene: "corridor".into(),
            resolution: [32, 18],
            reference: Reference {
                spp: 16.0,
                depth: 4,
                scale: 1.0,
            },
            views: 1,
            temporal_frames: None,
            points: points
                .iter()
                .enumerate()
                .map(|(i, &(spp, scale, rays, ms))| LadderPoint {
                    spp,
                    depth: 4,
                    scale,
                    rays,
                    ms,
                    flip: 0.5 / (1.0 + i as f64),
                })
                .collect(),
        }
    }

    #[test]
    fn a_complete_stimulus_folder_of_the_same_key_is_reused() {
        let tmp = tempfile::Builder::new()
            .prefix("steadyray-stimulus-")
            .tempdir()
            .unwrap();
        let dir = tmp.path();
        let key = StimulusKey {
            scene: "corridor".into(),
            resolution: [32, 18],
            refresh_hz: 60.0,
            stimulus_s: 0.5,
            view_s: 0.0,
            speed_deg_s: 8.0,
            reference: Quality::new(16.0, 16, 1.0),
            runs: vec!["r1-S1-R16-x1".into(), "r2-S1-R16-x1".into()],
            warp: false,
        };
        assert_eq!(reuse(dir, &key), None, "an empty folder");
        let flips: BTreeMap<String, f64> = [
            ("r1-S1-R16-x1".to_string(), 0.1),
            ("r2-S1-R16-x1".to_string(), 0.2),
        ]
        .into();
        let text = serde_json::to_string(&FlipScores {
            displayed_flip: flips.clone(),
        })
        .unwrap();
        write_atomically(&dir.join("flip.json"), &text).unwrap();
        assert_eq!(reuse(dir, &key), None, "no stimulus.json: not complete");
        write_atomically(
            &dir.join("stimulus.json"),
            &serde_json::to_string(&key).unwrap(),
        )
        .unwrap();
        assert_eq!(reuse(dir, &key), Some(flips));
        let other = StimulusKey {
            speed_deg_s: 32.0,
            ..key
        };
        assert_eq!(reuse(dir, &other), None, "another stimulus");
        let warped = StimulusKey {
            warp: true,
            ..other
        };
        assert_eq!(reuse(dir, &warped), None, "warped stimuli");
    }

    #[test]
    fn points_spread_by_cost_among_the_affordable() {
        let l = ladder(&[
            (1.0, 0.5, 1e3, 1.0),
            (1.0, 0.75, 2e3, 2.0),
            (1.0, 1.0, 4e3, 4.0),
            (2.0, 1.0, 8e3, 8.0),
            (4.0, 1.0, 16e3, 16.0),
            (64.0, 1.0, 1e6, 1000.0),
        ]);
        let picked = pick_points(&l, 3, 100.0);
        let spp: Vec<(f32, f32)> = picked.points.iter().map(|p| (p.spp, p.scale)).collect();
        assert_eq!(spp, [(1.0, 0.5), (1.0, 1.0), (4.0, 1.0)]);
        picked.validate().unwrap();
        assert_eq!(
            pick_points(&l, 0, 100.0).points.len(),
            5,
            "the dearest cannot fit"
        );
        assert_eq!(
            pick_points(&l, 0, 0.5).points.len(),
            1,
            "the cheapest stays"
        );
    }

    /// The corridor on the CPU renderer.
    fn corridor() -> (Scene, CpuRenderer) {
        let scene = steadyray_scene::load_scene("corridor").unwrap();
        let mut renderer = CpuRenderer::new();
        renderer.load_scene(&scene).unwrap();
        (scene, renderer)
    }

    /// A plan of 0.1 s stimuli at 32 × 18, one view, frames of one and three refreshes.
    fn tiny_plan(ladder: Ladder, speeds: Vec<f64>) -> MotionPlan {
        MotionPlan {
            width: 32,
            height: 18,
            ladder,
            points: 0,
            speeds,
            refreshes: vec![1, 3],
            refresh_hz: 60.0,
            stimulus_s: 0.1,
            views: 1,
            reference: Quality::new(4.0, 4, 1.0),
            video: None,
            jod: None,
            warp: false,
        }
    }

    #[test]
    fn a_tiny_model_of_displayed_flip_punishes_long_frames_of_fast_motion() {
        let (scene, mut renderer) = corridor();
        let points = ladder(&[(1.0, 0.5, 1e3, 1.0), (2.0, 1.0, 4e3, 2.0)]);
        let plan = tiny_plan(points, vec![0.0, 60.0]);
        assert_eq!(stimulus_count(&plan), 2 * (2 + 1));
        let tables =
            calibrate_motion(&mut renderer, &scene, &plan, &ProgressBar::hidden()).unwrap();
        let m = tables.model;
        assert!(tables.flip.is_none());
        assert_eq!(m.metric, Metric::DisplayedFlip);
        m.validate().unwrap();
        let s = &m.scores;
        // Still: the frame time does not matter, the better point scores better.
        assert_eq!(s[0][0], s[0][1]);
        assert!(s[0][0][1] < s[0][0][0], "{s:?}");
        // Fast: three refreshes per frame show a staler world than one.
        for p in 0..2 {
            assert!(s[1][1][p] > s[1][0][p], "{s:?}");
        }
        let bad = MotionPlan {
            refreshes: vec![2, 1],
            ..plan
        };
        let err = calibrate_motion(&mut renderer, &scene, &bad, &ProgressBar::hidden());
        assert!(err.err().unwrap().to_string().contains("--refreshes"));
    }

    /// Warped stimuli: the refreshes between frames show the frame warped to their time, so
    /// three refreshes a frame of fast motion cost far less over one than held frames do.
    #[test]
    fn warped_stimuli_take_the_age_out_of_long_frames() {
        let (scene, mut renderer) = corridor();
        let plan = tiny_plan(ladder(&[(2.0, 1.0, 4e3, 2.0)]), vec![120.0]);
        let progress = ProgressBar::hidden();
        let held = calibrate_motion(&mut renderer, &scene, &plan, &progress).unwrap();
        let plan = MotionPlan { warp: true, ..plan };
        let warped = calibrate_motion(&mut renderer, &scene, &plan, &progress).unwrap();
        let (held, warped) = (held.model, warped.model);
        assert!(warped.warped && !held.warped);
        let (h, w) = (&held.scores[0], &warped.scores[0]);
        // What three refreshes a frame cost over one: at least halved (0.091 → 0.029 here).
        let (held_cost, warped_cost) = (h[1][0] - h[0][0], w[1][0] - w[0][0]);
        assert!(held_cost > 0.0, "held {h:?}");
        assert!(warped_cost < 0.5 * held_cost, "held {h:?}, warped {w:?}");
    }
}
