//! `predictive` with a calibrated ladder on the simulated corridor: it holds the band like
//! the default knob order does, and only ever delivers qualities on the ladder (its points or
//! between two neighbours), or below its cheapest point at lower resolution when even that
//! is too dear.

use steadyray_control::ladder::{LADDER_FLOOR, Ladder, LadderPoint, Reference};
use steadyray_control::metrics::summarize;
use steadyray_control::predictive::{Predictive, PredictiveParams};
use steadyray_control::simulate::{LoadProfile, RendererModel, corridor_load, run};
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

#[test]
fn a_ladder_whose_cheapest_point_is_too_dear_goes_on_at_lower_resolution() {
    // A ladder calibrated where frames were cheaper: its cheapest point, S 1, R 4 at full
    // scale, takes 37 ms on this view, about twice the top of the paper's band.
    let mut dear = ladder();
    dear.points.drain(..5);
    let cheapest = dear.points[0].quality();
    let mut model = RendererModel::corridor(720)
        .with_profile(LoadProfile::Constant(corridor_load(std::f64::consts::PI)));
    let load = model.profile.load(0);
    model.ns_per_ray *= 36.0 / (model.ideal_ms(&cheapest, &load) - model.fixed_ms);
    let full_ms = model.ideal_ms(&cheapest, &load);
    assert!((full_ms - 37.0).abs() < 1e-6, "{full_ms}");
    let band = Band::new(15.0, 20.0).unwrap();
    let b = Bounds::default();
    let mut params = PredictiveParams::default();
    params.ladder = Some(dear.clone());
    let setup = Setup::new(band, b, b.max_quality()).unwrap();
    let mut c = Predictive::new(setup, params).unwrap();
    let records = run(&mut c, &model, 200 + WARM_UP);
    let counted = &records[WARM_UP..];
    for r in counted {
        let q = r.quality;
        assert_eq!((q.spp, q.depth), (cheapest.spp, cheapest.depth), "{q}");
        assert!(q.scale < cheapest.scale && q.scale >= b.scale_min, "{q}");
    }
    let summary = summarize(counted, band, b.max_quality(), Some(&[]));
    assert!(summary.ok_pct >= 95.0, "{summary:?}");
    // The lowest position is the cheapest point at the bounds' lowest scale.
    assert_eq!(
        c.ladder_quality(&dear, LADDER_FLOOR),
        Quality::new(cheapest.spp, cheapest.depth, b.scale_min)
    );
    assert!(c.ladder_position_within(20.0).unwrap() < 0.0);
    assert_eq!(c.ladder_position_within(1.0), None, "nothing fits");
}
