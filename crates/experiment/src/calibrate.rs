//! `steadyray calibrate`: measures (S, R, scale) settings over sampled views of the camera
//! path (rays, time, FLIP against a high-quality reference) and writes their Pareto front as
//! a ladder (`ladder.json`, format in `steadyray_control::ladder`) for `predictive`'s
//! `ladder=FILE` option. With `--motion` it measures the quality model of `perceptual`
//! instead ([`crate::calibrate_motion`]).

use crate::backend::create_renderer;
use crate::bench::quality::shown;
use crate::calibrate_motion::{JodTool, MotionPlan, calibrate_motion, stimulus_count};
use crate::config::SceneConfig;
use crate::frame_loop::FrameLoop;
use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use std::path::Path;
use std::path::PathBuf;
use steadyray_control::ladder::{Ladder, LadderPoint, Reference, pareto_front};
use steadyray_control::{MotionModel, Quality};
use steadyray_quality::{Rgb8Image, flip};
use steadyray_render::sample_stream::check_reference_spp;
use steadyray_render::{Renderer, SampleStream, TemporalSettings, check_image_size};
use steadyray_scene::Scene;

/// What `calibrate` measures: the settings tried over views of the camera path for a
/// ladder, or (`motion`) the stimuli of the perceptual quality model.
#[derive(Clone, Debug)]
pub struct CalibrateConfig {
    /// The scene and its renderer.
    pub scene: SceneConfig,
    /// Views of the camera path to measure, evenly spaced (default 8; with --motion, 2).
    pub views: Option<u32>,
    /// Frames in the camera path the views are taken from (as `bench --frames`).
    pub frames: u32,
    /// Full-scale image width (use the size you will bench at: FLIP's verdicts change with
    /// it; the default is `bench`'s on the CPU).
    pub width: u32,
    /// Full-scale image height.
    pub height: u32,
    /// Eye rays per pixel S to try, comma separated. Fractional values matter: at 640x360
    /// the corridor's front holds S = 1.25 and 1.5 but not 1.75 or 2, which cost more and
    /// score no better.
    pub spp: Vec<f32>,
    /// Reflection depths R to try, comma separated.
    pub depths: Vec<u32>,
    /// Resolution scales to try, comma separated.
    pub scales: Vec<f32>,
    /// The reference's eye rays per pixel S (full scale, at least 2; it draws samples no
    /// measured setting draws). The reference setting itself is
    /// also a point of the ladder (FLIP 0), so the ladder reaches the highest quality.
    /// Default 256; with --motion, where a reference is rendered per refresh, 16 (as the
    /// real clock's bench).
    pub reference_spp: Option<f32>,
    /// The reference's reflection depth R.
    pub reference_depth: u32,
    /// Where to write the ladder (default ladder.json; with --motion, motion.json).
    pub out: Option<PathBuf>,
    /// Measure the quality model of the `perceptual` controller instead of a ladder: short
    /// stimuli over a grid of screen speeds, frame times and points of --ladder, scored by
    /// displayed FLIP (and by JOD with --jod); written as motion.json.
    pub motion: bool,
    /// With --motion: the calibrated ladder whose points are scored.
    pub ladder: Option<PathBuf>,
    /// With --motion: measure nothing, but write the mean of these motion.json files (models
    /// of the same ladder and grids, e.g. on several scenes) to --out: how the model shipped
    /// with `perceptual` is made (docs/default-motion-model.md).
    pub merge: Vec<PathBuf>,
    /// With --motion: how many of the ladder's points to score, spread evenly by cost
    /// (0: all).
    pub points: usize,
    /// With --motion: screen speeds, degrees of visual angle per second, comma separated.
    pub speeds: Vec<f64>,
    /// With --motion: frame times, in refreshes of the display, comma separated.
    pub refreshes: Vec<u32>,
    /// With --motion: the display's refresh rate, Hz.
    pub refresh: f64,
    /// With --motion: each stimulus's length, seconds.
    pub stimulus: f64,
    /// With --motion: show the stimuli as `bench --temporal on --warp` does (frames
    /// accumulated into a temporal history, each refresh between two frames the last frame
    /// warped to its time), so the table scores long frames with their age warped away;
    /// score the points of a ladder from `calibrate --temporal`.
    pub warp: bool,
    /// With --motion: write each stimulus's screen and reference videos into DIR (one
    /// folder per view and speed, in the layout of `bench --video`).
    pub video: Option<PathBuf>,
    /// With --video: score the videos with the JOD tool (ColorVideoVDP, scripts/jod/jod.py)
    /// and fill the table with JOD; the displayed-FLIP table is written beside it
    /// (`<out>-flip.json`). A folder already scored (its jod.json) is not scored again.
    pub jod: bool,
    /// With --jod: the Python that runs the JOD tool (with scripts/jod/requirements.txt).
    pub python: String,
    /// With --jod: the JOD tool.
    pub jod_script: PathBuf,
    /// With --jod: keep every video once scored (else only video.json and jod.json stay).
    pub keep_video: bool,
    /// Calibrate for the temporal mode (docs/temporal.md): each setting renders FRAMES frames
    /// leading up to each view (1/--rate s apart on the path) into a history and is measured
    /// on it, so the ladder ranks the settings by what they look like with history.
    pub temporal: Option<u32>,
    /// With --temporal: frames per second of the frames leading up to each view.
    pub rate: f64,
}

/// What to measure: the grid of settings, the views and the reference.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Full-scale image width.
    pub width: u32,
    /// Full-scale image height.
    pub height: u32,
    /// Frames in the camera path the views are taken from.
    pub frames: u32,
    /// Views measured, evenly spaced.
    pub views: u32,
    /// Eye rays per pixel S to try.
    pub spp: Vec<f32>,
    /// Reflection depths R to try.
    pub depths: Vec<u32>,
    /// Resolution scales to try.
    pub scales: Vec<f32>,
    /// The reference's setting.
    pub reference: Reference,
    /// The temporal mode's frames before each view and their rate (frames per second).
    pub temporal: Option<(u32, f64)>,
}

impl Plan {
    /// The frames of the path measured: `views` evenly spaced ones.
    fn view_frames(&self) -> Vec<u32> {
        (0..self.views)
            .map(|i| (u64::from(i) * u64::from(self.frames) / u64::from(self.views)) as u32)
            .collect()
    }

    /// The settings measured (the reference's own is added by [`calibrate`]).
    fn settings(&self) -> Vec<(f32, u32, f32)> {
        let mut out = Vec::new();
        for &scale in &self.scales {
            for &spp in &self.spp {
                for &depth in &self.depths {
                    out.push((spp, depth, scale));
                }
            }
        }
        out
    }
}

/// One render's measurements.
struct Sample {
    rays: f64,
    ms: f64,
    image: Rgb8Image,
}

/// Renders `scene` at frame `k` at one setting and returns what the frame cost and showed:
/// one frame, or with `temporal` (frames, rate) the history after that many frames leading
/// up to it.
fn measure(
    renderer: &mut dyn Renderer,
    scene: &Scene,
    plan: &Plan,
    k: u32,
    (spp, depth, scale): (f32, u32, f32),
    temporal: Option<(u32, f64)>,
) -> Result<Sample> {
    let time_s = scene.path.frame_time(k, plan.frames);
    let mut frame_loop = FrameLoop::new((plan.width, plan.height));
    let quality = Quality::new(spp, depth, scale);
    let history = TemporalSettings {
        width: plan.width,
        height: plan.height,
    };
    renderer.set_temporal(temporal.map(|_| history))?;
    let (frames, rate) = temporal.unwrap_or((1, 1.0));
    let mut frame = None;
    for i in 0..frames {
        let t = time_s - f64::from(frames - 1 - i) / rate;
        let camera = if i + 1 == frames {
            scene.camera_at(k, plan.frames)
        } else {
            scene.camera_at_time(t)
        };
        frame = Some(
            frame_loop
                .render(renderer, &camera, t, quality)
                .with_context(|| format!("frame {k} at S={spp} R={depth} scale={scale}"))?,
        );
    }
    let frame = frame.context("no frame rendered")?;
    let image = shown(&renderer.read_image()?, plan.width, plan.height)?;
    Ok(Sample {
        rays: frame.stats.rays.total() as f64,
        ms: frame.report.tp_ms,
        image,
    })
}

/// Measures every setting of `plan` at every view against the reference and returns the
/// ladder: the Pareto front by mean rays and mean FLIP, the reference setting on top.
pub fn calibrate(
    renderer: &mut dyn Renderer,
    scene: &Scene,
    plan: &Plan,
    progress: &ProgressBar,
) -> Result<Ladder> {
    if plan.views == 0 || plan.frames == 0 {
        bail!("--views and --frames must be at least 1");
    }
    check_image_size(plan.width, plan.height)?;
    check_reference_spp(plan.reference.spp)?;
    if let Some((frames, rate)) = plan.temporal
        && (frames == 0 || !(rate.is_finite() && rate > 0.0))
    {
        bail!(
            "--temporal needs at least 1 frame and --rate a positive number of frames per second"
        );
    }
    let views = plan.view_frames();
    let settings = plan.settings();
    if settings.is_empty() {
        bail!("no settings to measure: give --spp, --depths and --scales");
    }
    let r = plan.reference;
    let mut sums = vec![(0.0, 0.0, 0.0); settings.len() + 1];
    for &k in &views {
        progress.set_message(format!("view {k}: reference"));
        // The reference draws its own samples, none of the settings' (`SampleStream`).
        renderer.set_sample_stream(SampleStream::Reference);
        let reference = measure(renderer, scene, plan, k, (r.spp, r.depth, r.scale), None);
        renderer.set_sample_stream(SampleStream::Frames);
        let reference = reference?;
        let top = &mut sums[settings.len()];
        top.0 += reference.rays;
        top.1 += reference.ms;
        progress.set_message(format!("view {k}"));
        for (i, &setting) in settings.iter().enumerate() {
            let s = measure(renderer, scene, plan, k, setting, plan.temporal)?;
            let f = flip(&reference.image, &s.image)?.mean();
            sums[i].0 += s.rays;
            sums[i].1 += s.ms;
            sums[i].2 += f;
            progress.inc(1);
        }
    }
    let n = views.len() as f64;
    let reference_setting = (r.spp, r.depth, r.scale);
    let measured: Vec<LadderPoint> = settings
        .iter()
        .chain(std::iter::once(&reference_setting))
        .zip(&sums)
        .map(|(&(spp, depth, scale), &(rays, ms, flip))| LadderPoint {
            spp,
            depth,
            scale,
            rays: rays / n,
            ms: ms / n,
            flip: flip / n,
        })
        .collect();
    let ladder = Ladder {
        scene: scene.name.clone(),
        resolution: [plan.width, plan.height],
        reference: r,
        views: plan.views,
        temporal_frames: plan.temporal.map(|(frames, _)| frames),
        points: pareto_front(measured),
    };
    ladder.validate().map_err(anyhow::Error::msg)?;
    Ok(ladder)
}

/// Runs the calibration, prints the front and writes the ladder (or, with `--motion`, the
/// quality model).
pub fn run(args: &CalibrateConfig) -> Result<()> {
    if !args.merge.is_empty() {
        return run_merge(args);
    }
    let scene = args.scene.load()?;
    let mut renderer = create_renderer(args.scene.backend)?;
    renderer.load_scene(&scene)?;
    if args.motion {
        return run_motion(args, renderer.as_mut(), &scene);
    }
    let out = args.out.clone().unwrap_or_else(|| "ladder.json".into());
    let plan = Plan {
        width: args.width,
        height: args.height,
        frames: args.frames,
        views: args.views.unwrap_or(8),
        spp: args.spp.clone(),
        depths: args.depths.clone(),
        scales: args.scales.clone(),
        reference: Reference {
            spp: args.reference_spp.unwrap_or(256.0),
            depth: args.reference_depth,
            scale: 1.0,
        },
        temporal: args.temporal.map(|frames| (frames, args.rate)),
    };
    let progress = crate::progress::progress_bar(
        plan.settings().len() as u64 * u64::from(plan.views),
        "renders",
    );
    let ladder = calibrate(renderer.as_mut(), &scene, &plan, &progress)?;
    progress.finish_and_clear();
    println!(
        "{:>6} {:>3} {:>6} {:>12} {:>9} {:>7}",
        "S", "R", "scale", "rays", "ms", "flip"
    );
    for p in &ladder.points {
        println!(
            "{:>6} {:>3} {:>6} {:>12.0} {:>9.2} {:>7.4}",
            p.spp, p.depth, p.scale, p.rays, p.ms, p.flip
        );
    }
    write_json(&ladder, &out)?;
    eprintln!(
        "calibrate: {} of {} settings on the front; wrote {}",
        ladder.points.len(),
        plan.settings().len() + 1,
        out.display()
    );
    Ok(())
}

/// Writes `value` as pretty JSON under a temporary name, then renames it over `path`.
fn write_json(value: &impl serde::Serialize, path: &Path) -> Result<()> {
    crate::bench::report::write_json(&serde_json::to_value(value)?, path)
}

/// `calibrate --motion`: measures, prints and writes the quality model.
fn run_motion(args: &CalibrateConfig, renderer: &mut dyn Renderer, scene: &Scene) -> Result<()> {
    let ladder_path = args
        .ladder
        .as_ref()
        .context("--motion scores the points of a calibrated ladder: give --ladder FILE")?;
    let text = std::fs::read_to_string(ladder_path)
        .with_context(|| format!("cannot read {}", ladder_path.display()))?;
    let ladder =
        Ladder::from_json(&text).map_err(|e| anyhow::anyhow!("{}: {e}", ladder_path.display()))?;
    let out = args.out.clone().unwrap_or_else(|| "motion.json".into());
    if let Some(dir) = &args.video {
        crate::bench::video::prepare(dir)?;
    }
    let plan = MotionPlan {
        width: args.width,
        height: args.height,
        ladder,
        points: args.points,
        speeds: args.speeds.clone(),
        refreshes: args.refreshes.clone(),
        refresh_hz: args.refresh,
        stimulus_s: args.stimulus,
        views: args.views.unwrap_or(2),
        reference: Quality::new(
            args.reference_spp.unwrap_or(16.0),
            args.reference_depth,
            1.0,
        ),
        video: args.video.clone(),
        jod: args.jod.then(|| JodTool {
            python: args.python.clone(),
            script: args.jod_script.clone(),
            keep_video: args.keep_video,
        }),
        warp: args.warp,
    };
    let progress = crate::progress::progress_bar(stimulus_count(&plan), "stimuli");
    let tables = calibrate_motion(renderer, scene, &plan, &progress)?;
    progress.finish_and_clear();
    print!("{}", motion_table(&tables.model));
    if let Some(flip) = &tables.flip {
        let stem = out.file_stem().map_or_else(
            || "motion".to_string(),
            |s| s.to_string_lossy().into_owned(),
        );
        let flip_path = out.with_file_name(format!("{stem}-flip.json"));
        write_json(flip, &flip_path)?;
        eprintln!(
            "calibrate: the displayed-FLIP table in {}",
            flip_path.display()
        );
    }
    write_json(&tables.model, &out)?;
    eprintln!(
        "calibrate: a {} table of {} speeds x {} frame times x {} ladder points; wrote {}",
        tables.model.metric,
        tables.model.speeds_deg_s.len(),
        tables.model.frame_times_ms.len(),
        tables.model.ladder.points.len(),
        out.display()
    );
    Ok(())
}

/// `calibrate --motion --merge A.json,B.json`: writes the mean of the models.
fn run_merge(args: &CalibrateConfig) -> Result<()> {
    if !args.motion {
        bail!("--merge averages motion models: give --motion too");
    }
    let models = args
        .merge
        .iter()
        .map(|path| {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            MotionModel::from_json(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
        })
        .collect::<Result<Vec<_>>>()?;
    let mean = MotionModel::mean(&models).map_err(|e| {
        let names: Vec<String> = args.merge.iter().map(|p| p.display().to_string()).collect();
        anyhow::anyhow!("cannot merge {} (in that order): {e}", names.join(", "))
    })?;
    let out = args.out.clone().unwrap_or_else(|| "motion.json".into());
    print!("{}", motion_table(&mean));
    write_json(&mean, &out)?;
    eprintln!(
        "calibrate: the mean of {} models ({}); wrote {}",
        models.len(),
        mean.scene,
        out.display()
    );
    Ok(())
}

/// The model as a text table: a row per speed and frame time, a column per ladder point.
fn motion_table(model: &MotionModel) -> String {
    let mut out = format!("{:>8} {:>9}", "deg/s", "frame ms");
    for p in &model.ladder.points {
        out.push_str(&format!(
            " {:>16}",
            format!("S={} R={} x{}", p.spp, p.depth, p.scale)
        ));
    }
    out.push('\n');
    for (i, speed) in model.speeds_deg_s.iter().enumerate() {
        for (j, ms) in model.frame_times_ms.iter().enumerate() {
            out.push_str(&format!("{speed:>8} {ms:>9.2}"));
            for score in &model.scores[i][j] {
                out.push_str(&format!(" {score:>16.4}"));
            }
            out.push('\n');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use steadyray_render_cpu::CpuRenderer;

    #[test]
    fn a_tiny_corridor_gives_a_front_of_rising_cost_and_falling_flip() {
        let scene = steadyray_scene::load_scene("corridor").unwrap();
        let mut renderer = CpuRenderer::new();
        renderer.load_scene(&scene).unwrap();
        let plan = Plan {
            width: 32,
            height: 18,
            frames: 8,
            views: 2,
            spp: vec![1.0, 2.0],
            depths: vec![0, 1, 3],
            scales: vec![0.5, 1.0],
            reference: Reference {
                spp: 8.0,
                depth: 4,
                scale: 1.0,
            },
            temporal: None,
        };
        let ladder = calibrate(&mut renderer, &scene, &plan, &ProgressBar::hidden()).unwrap();
        let p = &ladder.points;
        assert!(p.len() >= 3, "{p:?}");
        assert!(
            p.windows(2)
                .all(|w| w[1].rays > w[0].rays && w[1].flip < w[0].flip)
        );
        // The reference setting closes the front with no error at all.
        let top = p.last().unwrap();
        assert_eq!(
            (top.spp, top.depth, top.scale, top.flip),
            (8.0, 4, 1.0, 0.0)
        );
        assert!(p[0].flip > 0.0);
        assert_eq!(ladder.temporal_frames, None);
    }

    #[test]
    fn a_temporal_ladder_measures_the_history() {
        let scene = steadyray_scene::load_scene("corridor").unwrap();
        let mut renderer = CpuRenderer::new();
        renderer.load_scene(&scene).unwrap();
        let plan = |temporal| Plan {
            width: 32,
            height: 18,
            frames: 8,
            views: 2,
            spp: vec![1.0],
            depths: vec![3],
            scales: vec![1.0],
            reference: Reference {
                spp: 16.0,
                depth: 3,
                scale: 1.0,
            },
            temporal,
        };
        let single = calibrate(&mut renderer, &scene, &plan(None), &ProgressBar::hidden()).unwrap();
        let history = calibrate(
            &mut renderer,
            &scene,
            &plan(Some((12, 60.0))),
            &ProgressBar::hidden(),
        )
        .unwrap();
        assert_eq!(history.temporal_frames, Some(12));
        // S = 1 with 12 frames of history looks better than one frame of it.
        assert!(
            history.points[0].flip < single.points[0].flip,
            "{history:?} vs {single:?}"
        );
        let bad = calibrate(
            &mut renderer,
            &scene,
            &plan(Some((0, 60.0))),
            &ProgressBar::hidden(),
        );
        assert!(bad.is_err());
        // An empty image is refused before anything renders (a scaled side was clamped to
        // one pixel, and a ladder of an empty image written).
        let empty = Plan {
            width: 0,
            ..plan(None)
        };
        let err = calibrate(&mut renderer, &scene, &empty, &ProgressBar::hidden()).unwrap_err();
        assert!(err.to_string().contains("0x18 is empty"), "{err}");
    }
}
