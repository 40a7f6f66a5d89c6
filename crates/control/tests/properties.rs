//! Properties over arbitrary report sequences.

mod common;

use proptest::prelude::*;
use steadyray_control::{Band, Bounds, ConfigError, FrameReport, Quality, Setup, from_name_with};

fn tp() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => 0.01f64..200.0,
        1 => Just(f64::NAN),
        1 => Just(0.0),
        1 => -100.0f64..0.0,
        1 => 1e5f64..1e12,
        1 => Just(f64::INFINITY),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn quality_always_stays_inside_bounds(
        name in prop::sample::select(vec!["fixed", "step", "hysteresis", "predictive", "perceptual"]),
        knob in prop::sample::select(vec!["depth", "spp", "both"]),
        frames in prop::collection::vec((tp(), 1u64..5_000_000, 0.0f64..1.0, 0u64..3_000_000, 0.0f64..200.0), 1..120),
        tmin in 1.0f64..50.0,
        width in 0.5f64..30.0,
    ) {
        let bounds = Bounds::new((1.0, 64.0), (0, 12), (0.25, 1.0)).unwrap();
        let setup = Setup::new(Band::new(tmin, tmin + width).unwrap(), bounds, Quality::new(4.0, 4, 0.5)).unwrap();
        let model = common::model_file();
        let opts = match name {
            "step" => format!("knob={knob}"),
            "perceptual" => format!("model={}", model.path().display()),
            _ => String::new(),
        };
        let mut c = build(name, setup, &opts).unwrap();
        for (tp_ms, eye, decay, shadow, speed) in frames {
            let q = c.quality();
            let depth = q.depth as usize;
            let rays: Vec<u64> = (0..=depth).map(|k| (eye as f64 * decay.powi(k as i32)) as u64).collect();
            let report = FrameReport { tp_ms, rays_per_depth: rays, shadow_rays: shadow, rays_stopped: None, pixels: eye.div_ceil(4), quality: q, speed_deg_s: speed, first_sample: None };
            let before = c.quality();
            match c.observe(&report) {
                Ok(next) => {
                    prop_assert!(bounds.contains(&next), "{} left the bounds: {}", name, next);
                    prop_assert_eq!(next, c.quality());
                    prop_assert!(next.spp.is_finite() && next.scale.is_finite());
                }
                Err(_) => prop_assert_eq!(c.quality(), before),
            }
        }
    }
}

/// Builds a controller with the files its options name read from disk.
fn build(
    name: &str,
    setup: Setup,
    options: &str,
) -> Result<Box<dyn steadyray_control::Controller>, ConfigError> {
    from_name_with(name, setup, options, &common::Disk)
}
