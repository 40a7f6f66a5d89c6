//! `predictive` with a calibrated ladder on the simulated corridor: it holds the band like
//! the default knob order does, and only ever delivers qualities on the ladder (its points or
//! between two neighbours).

use steadyray_control::ladder::{Ladder, LadderPoint, Reference};
use steadyray_control::metrics::summarize;
use steadyray_control::simulate::{RendererModel, run};
use steadyray_control::{
    Band, Bounds, ConfigError, OptionFiles, Quality, Setup, from_name, from_name_with,
};

/// Reads the files that options name from disk, as the steadyray binary does.
struct Disk;

impl OptionFiles for Disk {
    fn read(&self, path: &str) -> Result<String, String> {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))
    }
}

const WARM_UP: usize = 20;

/// A plausible front for the corridor: cheap low-resolution direct light first, then depth,
/// resolution and samples together, up to the highest quality.
fn ladder() -> Ladder {
    let settings: [(f32, u32, f32); 12] = [
        (1.0, 0, 0.25),
        (1.0, 1, 0.35),
        (1.0, 1, 0.5),
        (1.0, 2, 0.6),
        (1.0, 3, 0.75),
        (1.0, 4, 1.0),
        (2.0, 6, 1.0),
        (4.0, 8, 1.0),
        (8.0, 10, 1.0),
        (32.0, 12, 1.0),
        (96.0, 16, 1.0),
        (256.0, 16, 1.0),
    ];
    let points = settings
        .iter()
        .enumerate()
        .map(|(i, &(spp, depth, scale))| {
            let q = Quality::new(spp, depth, scale);
            LadderPoint {
                spp,
                depth,
                scale,
                rays: q.level() * 1e5,
                ms: 0.0,
                flip: 0.5 / (i + 1) as f64,
            }
        })
        .collect();
    let ladder = Ladder {
        scene: "corridor (simulated)".into(),
        resolution: [640, 360],
        reference: Reference {
            spp: 256.0,
            depth: 16,
            scale: 1.0,
        },
        views: 0,
        temporal_frames: None,
        points,
    };
    ladder.validate().unwrap();
    ladder
}

/// Whether every knob of `q` lies between those of two neighbouring points.
fn between_neighbours(points: &[Quality], q: &Quality) -> bool {
    let within = |v: f64, a: f64, b: f64| v >= a.min(b) - 1e-4 && v <= a.max(b) + 1e-4;
    points.windows(2).any(|w| {
        within(f64::from(q.spp), f64::from(w[0].spp), f64::from(w[1].spp))
            && within(
                f64::from(q.depth),
                f64::from(w[0].depth),
                f64::from(w[1].depth),
            )
            && within(
                f64::from(q.scale),
                f64::from(w[0].scale),
                f64::from(w[1].scale),
            )
    })
}

fn setup() -> Setup {
    let b = Bounds::default();
    Setup::new(Band::PAPER, b, b.max_quality()).unwrap()
}

#[test]
fn holds_the_corridor_sweep_like_the_default_order() {
    let dir = tempfile::Builder::new()
        .prefix("steadyray-ladder-")
        .tempdir()
        .unwrap();
    let path = dir.path().join("ladder.json");
    std::fs::write(&path, serde_json::to_string_pretty(&ladder()).unwrap()).unwrap();
    let frames = 720;
    let top = Bounds::default().max_quality();
    let on_ladder = ladder().qualities();
    for seed in 1..=3 {
        let mut model = RendererModel::corridor(frames);
        model.seed = seed;
        let mut summaries = Vec::new();
        for options in [String::new(), format!("ladder={}", path.display())] {
            let mut c = from_name_with("predictive", setup(), &options, &Disk).unwrap();
            let records = run(c.as_mut(), &model, frames + WARM_UP);
            let counted = &records[WARM_UP..];
            if !options.is_empty() {
                for r in counted {
                    assert!(between_neighbours(&on_ladder, &r.quality), "{}", r.quality);
                }
            }
            summaries.push(summarize(counted, Band::PAPER, top, Some(&[])));
        }
        let (default, laddered) = (&summaries[0], &summaries[1]);
        println!("seed {seed}: default {default:?}\nladder {laddered:?}");
        assert!(laddered.ok_pct >= 99.0, "seed {seed}: {laddered:?}");
        assert!(laddered.ok_pct >= default.ok_pct - 1.0, "seed {seed}");
        assert!(laddered.longest_over_run <= 2, "seed {seed}: {laddered:?}");
        assert!(
            laddered.reversals_per_100 <= 5.0,
            "seed {seed}: {laddered:?}"
        );
    }
}

#[test]
fn a_missing_or_bad_ladder_is_a_clear_error() {
    let missing = "ladder=/nonexistent/ladder.json";
    let err = from_name_with("predictive", setup(), missing, &Disk).unwrap_err();
    assert!(
        matches!(&err, ConfigError::BadOption { key, .. } if key == "ladder"),
        "{err}"
    );
    assert!(err.to_string().contains("cannot read"), "{err}");
    // Without a way to read files the library refuses the option and says what to do.
    let err = from_name("predictive", setup(), missing).unwrap_err();
    assert!(err.to_string().contains("from_name_with"), "{err}");
}
