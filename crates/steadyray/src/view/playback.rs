//! Playing back a recorded sequence (`bench --record DIR`) at its real timing.
//!
//! The recording: `DIR/timings.csv` with the header `frame,presented_ms,tp_ms` (the time
//! since the first frame at which frame `frame` is shown, and its render time) and one 8-bit
//! sRGB PNG per frame, `frame_00000.png`, `frame_00001.png`, ... It plays once and stays on
//! its last frame (Space plays it again).

use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};

/// One frame of a recording.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecordedFrame {
    /// The number in the frame's file name.
    pub frame: u32,
    /// When the frame is shown, ms after the first.
    pub presented_ms: f64,
    /// Its render time, ms.
    pub tp_ms: f64,
}

/// A recorded sequence, checked when opened: every frame listed has its PNG.
#[derive(Clone, Debug)]
pub struct Recording {
    dir: PathBuf,
    frames: Vec<RecordedFrame>,
}

/// The header `timings.csv` must start with.
const HEADER: [&str; 3] = ["frame", "presented_ms", "tp_ms"];

/// Parses `timings.csv`; `name` names the file in messages.
pub fn parse_timings(text: &str, name: &str) -> Result<Vec<RecordedFrame>> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let header: Vec<&str> = match lines.next() {
        Some((_, line)) => line.split(',').map(str::trim).collect(),
        None => bail!("{name} is empty (expected the header {})", HEADER.join(",")),
    };
    if header != HEADER {
        bail!(
            "{name} has the header {:?}; expected {}",
            header.join(","),
            HEADER.join(",")
        );
    }
    let mut frames: Vec<RecordedFrame> = Vec::new();
    for (i, line) in lines {
        let at = || format!("{name} line {}", i + 1);
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [frame, presented, tp] = fields[..] else {
            bail!(
                "{}: expected 3 fields, found {}: {line:?}",
                at(),
                fields.len()
            );
        };
        let number = |field: &str, what: &str| -> Result<f64> {
            let v: f64 = field
                .parse()
                .with_context(|| format!("{}: {what} {field:?} is not a number", at()))?;
            if !(v.is_finite() && v >= 0.0) {
                bail!("{}: {what} {v} must be a finite number >= 0", at());
            }
            Ok(v)
        };
        let row = RecordedFrame {
            frame: frame
                .parse()
                .with_context(|| format!("{}: frame {frame:?} is not a frame number", at()))?,
            presented_ms: number(presented, "presented_ms")?,
            tp_ms: number(tp, "tp_ms")?,
        };
        if let Some(prev) = frames.last()
            && row.presented_ms < prev.presented_ms
        {
            bail!(
                "{}: presented_ms {} goes back in time (previous frame at {})",
                at(),
                row.presented_ms,
                prev.presented_ms
            );
        }
        frames.push(row);
    }
    if frames.is_empty() {
        bail!("{name} lists no frames");
    }
    Ok(frames)
}

impl Recording {
    /// Opens the recording in `dir`: reads `timings.csv` and checks that each frame's PNG
    /// exists.
    pub fn open(dir: &Path) -> Result<Self> {
        if !dir.is_dir() {
            bail!(
                "playback: {} is not a folder (expected a recording made by `bench --record`)",
                dir.display()
            );
        }
        let csv = dir.join("timings.csv");
        let text = std::fs::read_to_string(&csv)
            .with_context(|| format!("playback: cannot read {}", csv.display()))?;
        let frames = parse_timings(&text, &csv.display().to_string())?;
        let recording = Self {
            dir: dir.to_path_buf(),
            frames,
        };
        if let Some(missing) = (0..recording.len())
            .map(|i| recording.png_path(i))
            .find(|p| !p.is_file())
        {
            bail!("playback: {} is missing", missing.display());
        }
        Ok(recording)
    }

    /// Frames in the recording (at least one).
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Frame `i` (0-based position in the recording).
    pub fn frame(&self, i: usize) -> RecordedFrame {
        self.frames[i]
    }

    /// The frame to show `elapsed_ms` after playback started: the last one whose time has
    /// come (the last frame once the recording has ended).
    pub fn frame_at(&self, elapsed_ms: f64) -> usize {
        self.frames
            .partition_point(|f| f.presented_ms <= elapsed_ms)
            .saturating_sub(1)
    }

    /// The PNG of frame `i`.
    pub fn png_path(&self, i: usize) -> PathBuf {
        self.dir
            .join(format!("frame_{:05}.png", self.frames[i].frame))
    }

    /// Decodes frame `i` as RGBA8 sRGB: (width, height, bytes).
    pub fn load(&self, i: usize) -> Result<(u32, u32, Vec<u8>)> {
        let path = self.png_path(i);
        let image = image::open(&path)
            .with_context(|| format!("playback: cannot decode {}", path.display()))?
            .into_rgba8();
        Ok((image.width(), image.height(), image.into_raw()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CSV: &str = "frame,presented_ms,tp_ms\n0,0,12.5\n1,16.7,14\n2,33.4,30.25\n";

    #[test]
    fn parses_timings() {
        let frames = parse_timings(CSV, "t.csv").unwrap();
        assert_eq!(frames.len(), 3);
        assert_eq!(
            frames[2],
            RecordedFrame {
                frame: 2,
                presented_ms: 33.4,
                tp_ms: 30.25
            }
        );
    }

    #[test]
    fn malformed_timings_say_where() {
        let cases = [
            ("", "empty"),
            ("frame,tp_ms\n0,1\n", "header"),
            ("frame,presented_ms,tp_ms\n", "no frames"),
            (
                "frame,presented_ms,tp_ms\n0,0\n",
                "line 2: expected 3 fields",
            ),
            (
                "frame,presented_ms,tp_ms\n0,x,1\n",
                "line 2: presented_ms \"x\"",
            ),
            ("frame,presented_ms,tp_ms\n-1,0,1\n", "frame \"-1\""),
            ("frame,presented_ms,tp_ms\n0,0,NaN\n", "finite"),
            (
                "frame,presented_ms,tp_ms\n0,5,1\n1,4,1\n",
                "line 3: presented_ms 4 goes back",
            ),
        ];
        for (text, expected) in cases {
            let err = format!("{:#}", parse_timings(text, "t.csv").unwrap_err());
            assert!(err.contains(expected), "{text:?}: {err}");
        }
    }

    fn write_recording(dir: &Path, frames: usize) {
        std::fs::create_dir_all(dir).unwrap();
        let mut csv = String::from("frame,presented_ms,tp_ms\n");
        for i in 0..frames {
            csv.push_str(&format!("{i},{},{}\n", i as f64 * 10.0, 5.0 + i as f64));
            let pixel = [i as u8 * 50, 0, 0, 255];
            let rgba: Vec<u8> = pixel.repeat(4 * 2);
            image::save_buffer(
                dir.join(format!("frame_{i:05}.png")),
                &rgba,
                4,
                2,
                image::ExtendedColorType::Rgba8,
            )
            .unwrap();
        }
        std::fs::write(dir.join("timings.csv"), csv).unwrap();
    }

    #[test]
    fn plays_frames_at_their_times_once() {
        let tmp = tempfile::Builder::new()
            .prefix("steadyray-playback-")
            .tempdir()
            .unwrap();
        let dir = tmp.path().join("recording");
        write_recording(&dir, 3);
        let r = Recording::open(&dir).unwrap();
        let shown: Vec<usize> = [-1.0, 0.0, 9.9, 10.0, 25.0, 29.9, 30.0, 1e9]
            .iter()
            .map(|&t| r.frame_at(t))
            .collect();
        assert_eq!(shown, [0, 0, 0, 1, 2, 2, 2, 2]);
        let (w, h, rgba) = r.load(2).unwrap();
        assert_eq!((w, h, &rgba[..4]), (4, 2, &[100, 0, 0, 255][..]));

        std::fs::remove_file(dir.join("frame_00001.png")).unwrap();
        let err = Recording::open(&dir).unwrap_err().to_string();
        assert!(err.contains("frame_00001.png is missing"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
        let err = Recording::open(&dir).unwrap_err().to_string();
        assert!(err.contains("is not a folder"), "{err}");
    }
}
