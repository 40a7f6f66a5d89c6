//! `bench --record DIR`: every delivered frame as a PNG with its timing, so the sequence can
//! be shown to people at its real pace (`steadyray view --playback DIR`), e.g. as stimuli of
//! a subjective test (ITU-T P.910 ACR).
//!
//! A recording folder holds `timings.csv` (header `frame,presented_ms,tp_ms`) and
//! `frame_00000.png`, `frame_00001.png`, ... (8-bit sRGB, upscaled bilinearly to the full
//! resolution when rendered at a scale below 1). `presented_ms` is when the frame would be
//! shown, counted from the first frame: frame k is shown when its render ends, so
//! presented_ms(0) = 0 and presented_ms(k) = presented_ms(k − 1) + tp_ms(k).
//!
//! The frames are kept in memory during a run and encoded after it, off the timed loop.

use super::record::{ControllerRun, safe_name};
use anyhow::{Context, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The presentation times of frames that took `tp_ms` each (see the module documentation).
pub fn presented_ms(tp_ms: &[f64]) -> Vec<f64> {
    let mut t = 0.0;
    tp_ms
        .iter()
        .enumerate()
        .map(|(k, &tp)| {
            if k > 0 {
                t += tp;
            }
            t
        })
        .collect()
}

/// The folder a run is recorded in: `dir` itself when only one run is recorded, else a
/// sub-folder named after the run (letters, digits, `-`, `_`, `.`, `=` kept; others `_`).
pub fn run_folder(dir: &Path, name: &str, runs: usize) -> PathBuf {
    if runs <= 1 {
        return dir.to_path_buf();
    }
    dir.join(safe_name(name))
}

/// Writes `run`'s recorded frames (upscaled to `width`×`height`) and `timings.csv` into
/// `folder`.
pub fn write_recording(run: &ControllerRun, folder: &Path, width: u32, height: u32) -> Result<()> {
    std::fs::create_dir_all(folder)
        .with_context(|| format!("cannot create {}", folder.display()))?;
    let tp: Vec<f64> = run.rows.iter().map(|r| r.tp_ms).collect();
    let csv_path = folder.join("timings.csv");
    let mut csv = std::io::BufWriter::new(
        std::fs::File::create(&csv_path)
            .with_context(|| format!("cannot create {}", csv_path.display()))?,
    );
    writeln!(csv, "frame,presented_ms,tp_ms")?;
    for (k, (shown_at, tp)) in presented_ms(&tp).iter().zip(&tp).enumerate() {
        writeln!(csv, "{k},{shown_at:.4},{tp:.4}")?;
    }
    csv.flush()
        .with_context(|| format!("cannot write {}", csv_path.display()))?;
    for (k, frame) in run.recorded.iter().enumerate() {
        let full = frame.resize_bilinear(width, height);
        let path = folder.join(format!("frame_{k:05}.png"));
        image::save_buffer(
            &path,
            full.as_bytes(),
            width,
            height,
            image::ExtendedColorType::Rgb8,
        )
        .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_presented_when_their_render_ends() {
        assert_eq!(presented_ms(&[10.0, 20.0, 15.0]), [0.0, 20.0, 35.0]);
        assert!(presented_ms(&[]).is_empty());
    }

    #[test]
    fn several_runs_get_a_folder_each() {
        let dir = Path::new("out");
        assert_eq!(run_folder(dir, "predictive", 1), dir);
        assert_eq!(
            run_folder(dir, "most-in-band fixed S=2 R=5", 3),
            dir.join("most-in-band_fixed_S=2_R=5")
        );
    }
}
