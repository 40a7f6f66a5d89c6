//! What several test files share: a quality model over (speed, frame time, ladder point)
//! where still pictures prefer long frames and fast ones short frames.

use steadyray_control::ladder::{Ladder, LadderPoint, Reference};
use steadyray_control::{Metric, MotionModel};
use tempfile::NamedTempFile;

pub const FRAME_TIMES: [f64; 3] = [1000.0 / 60.0, 2000.0 / 60.0, 3000.0 / 60.0];
pub const FAST: f64 = 60.0;
/// Eye rays per pixel of the ladder's points (R = 4, full scale).
const LADDER_SPP: [f32; 7] = [1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0];

/// A ladder of S at R = 4 (its rays and FLIP are only information for the controller).
fn ladder() -> Ladder {
    let points = LADDER_SPP
        .iter()
        .enumerate()
        .map(|(i, &spp)| LadderPoint {
            spp,
            depth: 4,
            scale: 1.0,
            rays: f64::from(spp) * 1e6,
            ms: f64::from(spp) * 4.0,
            flip: 0.3 / (1.0 + i as f64),
        })
        .collect();
    Ladder {
        scene: "simulated".into(),
        resolution: [640, 360],
        reference: Reference {
            spp: 16.0,
            depth: 4,
            scale: 1.0,
        },
        views: 1,
        temporal_frames: None,
        points,
    }
}

/// A model where a better ladder point scores up to 3 JOD more and judder costs
/// speed · frame time / 400 JOD: still pictures prefer long frames, fast ones short frames.
pub fn model() -> MotionModel {
    let ladder = ladder();
    let n = ladder.points.len();
    let speeds = vec![0.0, FAST];
    let scores = speeds
        .iter()
        .map(|&v| {
            FRAME_TIMES
                .iter()
                .map(|&t| {
                    (0..n)
                        .map(|k| 6.0 + 3.0 * k as f64 / (n - 1) as f64 - v * t / 400.0)
                        .collect()
                })
                .collect()
        })
        .collect();
    MotionModel {
        metric: Metric::Jod,
        scene: "simulated".into(),
        resolution: [640, 360],
        refresh_hz: 60.0,
        stimulus_s: 1.0,
        warped: false,
        viewing: serde_json::Value::Null,
        ladder,
        speeds_deg_s: speeds,
        frame_times_ms: FRAME_TIMES.to_vec(),
        scores,
    }
}

/// [`model`] written to a file of its own in the temporary folder, for `model=PATH`; the
/// file is removed when the returned value is dropped.
pub fn model_file() -> NamedTempFile {
    // A file per call: tests run in parallel threads, and one writing the file another
    // reads made the reader fail now and then.
    let file = tempfile::Builder::new()
        .prefix("steadyray-control-test-motion-")
        .suffix(".json")
        .tempfile()
        .unwrap();
    std::fs::write(file.path(), serde_json::to_string(&model()).unwrap()).unwrap();
    file
}

/// Reads the files that options name from disk, as the steadyray binary does.
pub struct Disk;

impl steadyray_control::OptionFiles for Disk {
    fn read(&self, path: &str) -> Result<String, String> {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))
    }
}
