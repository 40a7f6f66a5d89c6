//! Bad arguments are clear errors.

mod common;

use std::path::Path;
use steadyray_control::{Band, Bounds, ConfigError, Quality, Setup, from_name_with};

/// The options a controller needs to be built: none, or `perceptual`'s model at `model`.
fn needed_options(name: &str, model: &Path) -> String {
    match name {
        "perceptual" => format!("model={}", model.display()),
        _ => String::new(),
    }
}

fn setup() -> Setup {
    let b = Bounds::default();
    Setup::new(Band::PAPER, b, b.max_quality()).unwrap()
}

#[test]
fn every_name_builds_with_defaults() {
    let model = common::model_file();
    for name in steadyray_control::CONTROLLER_NAMES {
        let c = build(name, setup(), &needed_options(name, model.path())).unwrap();
        assert_eq!(c.name(), name);
        assert_eq!(c.quality(), Bounds::default().max_quality());
    }
}

#[test]
fn options_are_parsed_and_checked() {
    assert!(build("step", setup(), "knob=both").is_ok());
    assert!(build("hysteresis", setup(), "up_after=10; order=depth,spp").is_ok());
    assert!(
        build(
            "predictive",
            setup(),
            "order=spp,scale target=0.4 forgetting=0.8"
        )
        .is_ok()
    );
    let err = |name: &str, opts: &str| build(name, setup(), opts).unwrap_err();
    assert!(matches!(
        err("step", "knob=colour"),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("step", "gain=2"),
        ConfigError::UnknownOption { .. }
    ));
    assert!(matches!(
        err("fixed", "knob=depth"),
        ConfigError::UnknownOption { .. }
    ));
    let fixed = build("fixed", setup(), "spp=4 depth=3 scale=0.5").unwrap();
    assert_eq!(fixed.quality(), Quality::new(4.0, 3, 0.5));
    assert!(matches!(
        err("fixed", "spp=1000"),
        ConfigError::StartOutOfBounds { .. }
    ));
    assert!(matches!(
        err("fixed", "depth=two"),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("hysteresis", "up_after=-1"),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("hysteresis", "target=0.9"),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("predictive", "order=depth,depth"),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("predictive", "order="),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("predictive", "target=0.95"),
        ConfigError::BadOption { .. }
    ));
    assert!(matches!(
        err("predictive", "trend"),
        ConfigError::BadOption { .. }
    ));
    let e = err("pid", "");
    assert_eq!(e, ConfigError::UnknownController("pid".into()));
    assert!(
        e.to_string()
            .contains("fixed, step, hysteresis, predictive")
    );
}

#[test]
fn bad_bands_bounds_and_starts_are_errors() {
    assert!(matches!(
        Band::new(20.0, 15.0),
        Err(ConfigError::EmptyBand { .. })
    ));
    assert!(matches!(
        Band::new(f64::NAN, 15.0),
        Err(ConfigError::BadBandLimit { .. })
    ));
    let inverted = Bounds {
        depth_min: 5,
        depth_max: 2,
        ..Bounds::default()
    };
    let start = Quality::new(1.0, 3, 1.0);
    let e = Setup::new(Band::PAPER, inverted, start).unwrap_err();
    assert!(matches!(e, ConfigError::BadBounds { knob: "depth", .. }));
    assert!(e.to_string().contains("min > max"));
    let outside = Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 17, 1.0));
    assert!(matches!(outside, Err(ConfigError::StartOutOfBounds { .. })));
    // A hand-built setup is checked again by every constructor.
    let bad = Setup {
        band: Band::PAPER,
        bounds: inverted,
        start,
    };
    let model = common::model_file();
    for name in steadyray_control::CONTROLLER_NAMES {
        assert!(
            build(name, bad, &needed_options(name, model.path())).is_err(),
            "{name}"
        );
    }
    // Step on S needs a whole S inside the bounds: an empty ladder.
    let narrow = Bounds {
        spp_min: 1.2,
        spp_max: 1.8,
        ..Bounds::default()
    };
    let s = Setup::new(Band::PAPER, narrow, Quality::new(1.5, 3, 1.0)).unwrap();
    assert!(matches!(
        build("step", s, "knob=spp"),
        Err(ConfigError::EmptyLadder { .. })
    ));
    assert!(build("step", s, "knob=depth").is_ok());
}

/// Builds a controller with the files its options name read from disk.
fn build(
    name: &str,
    setup: Setup,
    options: &str,
) -> Result<Box<dyn steadyray_control::Controller>, ConfigError> {
    from_name_with(name, setup, options, &common::Disk)
}
