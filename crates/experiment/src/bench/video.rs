//! `bench --video DIR`: the screen and the reference at every refresh, for a full-reference
//! video metric (ColorVideoVDP, `scripts/jod/`) and for people to watch.
//!
//! ```text
//! DIR/video.json                  the index, written last: set-up, rate, size, runs
//! DIR/reference/frame_00000.png   the world at refresh i (reference quality, full scale)
//! DIR/reference/reference.json    what the references are, to reuse them in a later bench
//! DIR/reference.y4m               the same as a video (reference.mkv with ffmpeg)
//! DIR/<run>/displayed/frame_00000.png   the screen at refresh i
//! DIR/<run>/timings.csv           per refresh: the frame on screen, its world time, whether warped
//! DIR/<run>/displayed.y4m         the same as a video (displayed.mkv with ffmpeg)
//! ```
//!
//! Every picture is 8-bit sRGB at the full-scale size (frames rendered smaller upscaled
//! bilinearly), lossless. The `.y4m` is 4:4:4 full-range BT.601 YCbCr (close to lossless:
//! only the colour transform rounds); where an `ffmpeg` binary is found a lossless FFV1 `.mkv`
//! of the PNGs replaces it. Each folder is written under a temporary name and renamed when
//! complete, and `video.json` comes last: a folder without it is not a finished video.

use super::displayed::{TimedReferences, screen_picture, screen_samples};
use super::record::safe_name;
use super::reference_store::StoreKey;
use super::screen::{DisplayRun, ScreenSample};
use super::source::FrameSource;
use anyhow::{Context, Result, bail};
use image::ImageEncoder;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use steadyray_display::{DisplayConfig, ViewingSetup};
use steadyray_quality::Rgb8Image;

/// The name of a refresh's picture.
fn frame_name(i: usize) -> String {
    format!("frame_{i:05}.png")
}

/// Creates `dir` and checks that files can be written in it, before any run (a bench must
/// not fail for an unwritable folder after its runs).
pub fn prepare(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("--video: cannot create the folder {}", dir.display()))?;
    let probe = dir.join(".steadyray-write-test");
    std::fs::write(&probe, b"")
        .with_context(|| format!("--video: cannot write into {}", dir.display()))?;
    std::fs::remove_file(&probe)
        .with_context(|| format!("--video: cannot remove {}", probe.display()))?;
    Ok(())
}

/// A folder being written: under a temporary name until [`Staging::finish`] renames it.
struct Staging {
    temp: PathBuf,
    target: PathBuf,
}

impl Staging {
    fn new(dir: &Path, name: &str) -> Result<Self> {
        let temp = dir.join(format!(".{name}.partial"));
        if temp.exists() {
            std::fs::remove_dir_all(&temp)
                .with_context(|| format!("cannot remove {}", temp.display()))?;
        }
        std::fs::create_dir_all(&temp)
            .with_context(|| format!("cannot create {}", temp.display()))?;
        Ok(Self {
            temp,
            target: dir.join(name),
        })
    }

    fn finish(self) -> Result<PathBuf> {
        if self.target.exists() {
            std::fs::remove_dir_all(&self.target)
                .with_context(|| format!("cannot replace {}", self.target.display()))?;
        }
        std::fs::rename(&self.temp, &self.target).with_context(|| {
            format!(
                "cannot rename {} to {}",
                self.temp.display(),
                self.target.display()
            )
        })?;
        Ok(self.target)
    }
}

/// Pictures encoded at once, in parallel: enough to keep every core busy, few enough that a
/// batch of 1080p frames stays small in memory.
const ENCODE_BATCH: usize = 32;

/// A picture as it is written: a lossless PNG and its planes for the `.y4m`.
struct Encoded {
    png: Vec<u8>,
    planes: Vec<u8>,
}

impl Encoded {
    fn new(picture: &Rgb8Image) -> Result<Self> {
        Ok(Self {
            png: encode_png(picture)?,
            planes: y4m_frame(picture),
        })
    }
}

/// A lossless PNG of `image`, in memory.
pub(super) fn encode_png(image: &Rgb8Image) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes).write_image(
        image.as_bytes(),
        image.width(),
        image.height(),
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(bytes)
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    std::fs::write(path, bytes).with_context(|| format!("cannot write {}", path.display()))
}

/// The refresh rate as a y4m frame rate `num:den`.
fn y4m_rate(hz: f64) -> (u64, u64) {
    let num = (hz * 1000.0).round() as u64;
    let gcd = |mut a: u64, mut b: u64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let g = gcd(num, 1000).max(1);
    (num / g, 1000 / g)
}

/// One frame's planes in 4:4:4 full-range BT.601 YCbCr, as y4m wants them.
fn y4m_frame(image: &Rgb8Image) -> Vec<u8> {
    let n = image.as_bytes().len() / 3;
    let mut out = vec![0u8; 3 * n];
    for (i, p) in image.as_bytes().chunks_exact(3).enumerate() {
        let [r, g, b] = [p[0], p[1], p[2]].map(f64::from);
        let y = 0.299 * r + 0.587 * g + 0.114 * b;
        let cb = 128.0 + (b - y) / 1.772;
        let cr = 128.0 + (r - y) / 1.402;
        for (plane, v) in [y, cb, cr].into_iter().enumerate() {
            out[plane * n + i] = v.round().clamp(0.0, 255.0) as u8;
        }
    }
    out
}

/// A `.y4m` video being written frame by frame.
struct Y4mWriter {
    out: std::io::BufWriter<std::fs::File>,
    path: PathBuf,
}

impl Y4mWriter {
    fn create(path: &Path, (width, height): (u32, u32), hz: f64) -> Result<Self> {
        let file = std::fs::File::create(path)
            .with_context(|| format!("cannot create {}", path.display()))?;
        let mut out = std::io::BufWriter::new(file);
        let (num, den) = y4m_rate(hz);
        writeln!(
            out,
            "YUV4MPEG2 W{width} H{height} F{num}:{den} Ip A1:1 C444 XCOLORRANGE=FULL"
        )?;
        Ok(Self {
            out,
            path: path.to_path_buf(),
        })
    }

    fn frame(&mut self, planes: &[u8]) -> Result<()> {
        self.out.write_all(b"FRAME\n")?;
        self.out
            .write_all(planes)
            .with_context(|| format!("cannot write {}", self.path.display()))
    }

    fn finish(mut self) -> Result<()> {
        self.out
            .flush()
            .with_context(|| format!("cannot write {}", self.path.display()))
    }
}

/// Whether an `ffmpeg` binary runs here.
fn has_ffmpeg() -> bool {
    Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The video of a PNG sequence: a lossless FFV1 `.mkv` made by ffmpeg when there is one (the
/// `.y4m` written meanwhile is then removed), else the `.y4m` stays. Returns its file name.
fn finish_movie(folder: &Path, frames: &str, stem: &str, hz: f64) -> Result<String> {
    if !has_ffmpeg() {
        return Ok(format!("{stem}.y4m"));
    }
    let mkv = format!("{stem}.mkv");
    let status = Command::new("ffmpeg")
        .current_dir(folder)
        .args(["-y", "-v", "error", "-framerate", &hz.to_string(), "-i"])
        .arg(format!("{frames}/frame_%05d.png"))
        .args(["-c:v", "ffv1", "-level", "3", &mkv])
        .status()
        .context("cannot run ffmpeg")?;
    if !status.success() {
        bail!(
            "ffmpeg failed ({status}) making {}",
            folder.join(&mkv).display()
        );
    }
    std::fs::remove_file(folder.join(format!("{stem}.y4m")))?;
    Ok(mkv)
}

/// Writes one run's screen at every refresh into `dir/<run>`: PNGs, `timings.csv`, the
/// video. Returns the folder's name.
pub fn write_run(
    dir: &Path,
    name: &str,
    run: &DisplayRun,
    display: &DisplayConfig,
    size: (u32, u32),
) -> Result<String> {
    let folder_name = safe_name(name);
    let staging = Staging::new(dir, &folder_name)?;
    let frames_dir = staging.temp.join("displayed");
    std::fs::create_dir_all(&frames_dir)?;
    let samples = screen_samples(run, display.period_ms(), |_| true);
    let mut csv = String::from("refresh,time_ms,frame,world_s,age_ms,warped\n");
    let mut movie = Y4mWriter::create(
        &staging.temp.join("displayed.y4m"),
        size,
        display.refresh_hz,
    )?;
    // Refreshes showing the same picture: a frame's, or a warp's alone.
    let shown: Vec<&[ScreenSample]> = samples
        .chunk_by(|a, b| a.frame == b.frame && !a.warped && !b.warped)
        .collect();
    for batch in shown.chunks(ENCODE_BATCH) {
        let encoded = batch
            .par_iter()
            .map(|refreshes| Encoded::new(&screen_picture(run, &refreshes[0], size)?))
            .collect::<Result<Vec<_>>>()?;
        for (refreshes, picture) in batch.iter().zip(&encoded) {
            for s in *refreshes {
                write_file(&frames_dir.join(frame_name(s.index)), &picture.png)?;
                movie.frame(&picture.planes)?;
                let frame = s
                    .frame
                    .map_or_else(|| "warmup".to_string(), |j| j.to_string());
                csv.push_str(&format!(
                    "{},{:.4},{frame},{:.6},{:.4},{}\n",
                    s.index,
                    1000.0 * s.time_s,
                    s.world_s,
                    1000.0 * (s.time_s - s.world_s),
                    u8::from(s.warped)
                ));
            }
        }
    }
    movie.finish()?;
    write_file(&staging.temp.join("timings.csv"), csv.as_bytes())?;
    finish_movie(&staging.temp, "displayed", "displayed", display.refresh_hz)?;
    staging.finish()?;
    Ok(folder_name)
}

/// Removes the folder `folder` of a run's video from `dir` (a run the bench does not report
/// after all: a best-looking fixed candidate that did not win).
pub fn remove_run(dir: &Path, folder: &str) -> Result<()> {
    let path = dir.join(folder);
    std::fs::remove_dir_all(&path).with_context(|| format!("cannot remove {}", path.display()))
}

/// What a reference folder holds: a later bench reuses it when all of this matches. The
/// set-up is the one a reference store is keyed by ([`StoreKey`], written flat into
/// `reference.json`); a video adds its rate and length.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceKey {
    /// What the references are of: scene, renderer, size, reference quality, revision.
    #[serde(flatten)]
    pub set_up: StoreKey,
    /// The refresh rate, Hz.
    pub refresh_hz: f64,
    /// Refreshes in the video.
    pub refreshes: usize,
}

/// The shared reference at every refresh `times_s` (one per refresh, in order), in
/// `dir/reference/` and `dir/reference.y4m`: reused when `dir/reference/reference.json`
/// matches `key` (and the revision is not a dirty tree), else rendered and written. The
/// references at times `wanted` picks are kept in `references` for the displayed quality.
pub fn write_references(
    dir: &Path,
    key: &ReferenceKey,
    times_s: &[f64],
    source: &mut dyn FrameSource,
    references: &mut TimedReferences,
    wanted: impl Fn(f64) -> bool,
    mut progress: impl FnMut(),
) -> Result<()> {
    let folder = dir.join("reference");
    let meta = folder.join("reference.json");
    let cached = std::fs::read_to_string(&meta)
        .ok()
        .and_then(|text| serde_json::from_str::<ReferenceKey>(&text).ok())
        .is_some_and(|k| &k == key && key.set_up.reusable());
    if cached {
        for (i, &t) in times_s.iter().enumerate() {
            if wanted(t) {
                let path = folder.join(frame_name(i));
                let image = image::open(&path)
                    .with_context(|| format!("cannot read the reference {}", path.display()))?
                    .to_rgb8();
                let (w, h) = image.dimensions();
                references.insert(t, Rgb8Image::from_rgb(w, h, image.into_raw())?);
            }
            progress();
        }
        eprintln!("bench: reusing the references in {}", folder.display());
        return Ok(());
    }
    let size = source.resolution();
    let staging = Staging::new(dir, "reference")?;
    let y4m = dir.join(".reference.y4m.partial");
    let mut movie = Y4mWriter::create(&y4m, size, key.refresh_hz)?;
    for (batch_index, batch) in times_s.chunks(ENCODE_BATCH).enumerate() {
        let first = batch_index * ENCODE_BATCH;
        let mut pictures = Vec::with_capacity(batch.len());
        for (i, &t_s) in (first..).zip(batch) {
            let picture = references
                .fetch(source, t_s)
                .with_context(|| format!("reference of refresh {i} failed"))?;
            pictures.push(picture);
        }
        let encoded = pictures
            .par_iter()
            .map(Encoded::new)
            .collect::<Result<Vec<_>>>()?;
        for (((i, &t_s), picture), encoded) in (first..).zip(batch).zip(pictures).zip(encoded) {
            write_file(&staging.temp.join(frame_name(i)), &encoded.png)?;
            movie.frame(&encoded.planes)?;
            if wanted(t_s) {
                references.insert(t_s, picture);
            }
            progress();
        }
    }
    movie.finish()?;
    write_file(
        &staging.temp.join("reference.json"),
        serde_json::to_string_pretty(key)?.as_bytes(),
    )?;
    for old in ["reference.y4m", "reference.mkv"] {
        let _ = std::fs::remove_file(dir.join(old));
    }
    std::fs::rename(&y4m, dir.join("reference.y4m"))?;
    staging.finish()?;
    finish_movie(dir, "reference", "reference", key.refresh_hz)?;
    Ok(())
}

/// `video.json`: what the folder holds, for the JOD tool.
#[derive(Debug, Serialize)]
pub struct VideoIndex {
    /// The scene's name.
    pub scene: String,
    /// The refresh rate, Hz.
    pub refresh_hz: f64,
    /// Refreshes in each video.
    pub refreshes: usize,
    /// Full-scale image size.
    pub resolution: [u32; 2],
    /// Display time per run, s.
    pub duration_s: f64,
    /// The display model.
    pub display: DisplayConfig,
    /// The viewing set-up every metric assumes.
    pub viewing: ViewingSetup,
    /// The shared reference.
    pub reference: ReferenceKey,
    /// Each run's name and folder, in the order of summary.json.
    pub runs: Vec<VideoRun>,
}

/// One run of `video.json`.
#[derive(Debug, Serialize)]
pub struct VideoRun {
    /// The run's name in reports.
    pub name: String,
    /// Its folder, relative to the video folder.
    pub folder: String,
}

/// Writes `video.json` (under a temporary name, then renamed): the video is complete.
pub fn write_index(dir: &Path, index: &VideoIndex) -> Result<()> {
    let temp = dir.join(".video.json.partial");
    write_file(
        &temp,
        (serde_json::to_string_pretty(index)? + "\n").as_bytes(),
    )?;
    std::fs::rename(&temp, dir.join("video.json"))
        .with_context(|| format!("cannot write {}", dir.join("video.json").display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_rates_as_fractions() {
        assert_eq!(y4m_rate(60.0), (60, 1));
        assert_eq!(y4m_rate(59.94), (2997, 50));
        assert_eq!(y4m_rate(143.5), (287, 2));
    }

    #[test]
    fn y4m_planes_of_grey_white_and_red() {
        let image =
            Rgb8Image::from_rgb(3, 1, vec![128, 128, 128, 255, 255, 255, 255, 0, 0]).unwrap();
        let planes = y4m_frame(&image);
        // Y plane, then Cb, then Cr; greys have Cb = Cr = 128.
        assert_eq!(planes[..3], [128, 255, 76]);
        assert_eq!(planes[3..5], [128, 128]);
        assert_eq!((planes[5], planes[8]), (85, 255));
    }

    #[test]
    fn an_unwritable_folder_fails_up_front() {
        let err = prepare(Path::new("/proc/steadyray-video")).unwrap_err();
        assert!(format!("{err:#}").contains("--video"), "{err:#}");
    }
}
