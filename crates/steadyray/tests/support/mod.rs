//! What several of these integration tests share.

use std::path::Path;
use steadyray_control::ladder::{Ladder, LadderPoint, Reference};
use steadyray_control::{Metric, MotionModel};

/// Writes to `path` a `perceptual` model of the corridor with one ladder point (S = 1,
/// R = 4, 600 rays in 1 ms at 32 × 18) scored at one and two refreshes of a 60 Hz display,
/// at every speed: `scores[0]` at one refresh a frame, `scores[1]` at two.
pub fn write_one_point_model(path: &Path, scores: [f64; 2]) {
    let model = MotionModel {
        metric: Metric::Jod,
        scene: "corridor".into(),
        resolution: [32, 18],
        refresh_hz: 60.0,
        stimulus_s: 0.5,
        warped: false,
        viewing: serde_json::Value::Null,
        ladder: Ladder {
            scene: "corridor".into(),
            resolution: [32, 18],
            reference: Reference {
                spp: 16.0,
                depth: 16,
                scale: 1.0,
            },
            views: 1,
            temporal_frames: None,
            points: vec![LadderPoint {
                spp: 1.0,
                depth: 4,
                scale: 1.0,
                rays: 600.0,
                ms: 1.0,
                flip: 0.1,
            }],
        },
        speeds_deg_s: vec![0.0],
        scores: vec![scores.iter().map(|&s| vec![s]).collect()],
        frame_times_ms: vec![1000.0 / 60.0, 2000.0 / 60.0],
    };
    std::fs::write(path, serde_json::to_string(&model).unwrap()).unwrap();
}
