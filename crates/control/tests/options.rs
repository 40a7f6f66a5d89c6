//! The options table (`steadyray_control::options`) and the parsers agree: every key the
//! table lists is accepted by `from_name_with`, a key it does not list is refused with the
//! table's list, and every controller has a line.

use steadyray_control::options::{CONTROLLERS, describe_controllers, expected_keys, options_of};
use steadyray_control::{
    Band, Bounds, CONTROLLER_NAMES, ConfigError, NoFiles, Quality, Setup, from_name_with,
};

fn setup() -> Setup {
    Setup::new(Band::PAPER, Bounds::default(), Quality::new(1.0, 16, 1.0)).unwrap()
}

#[test]
fn the_table_lists_every_controller() {
    let listed: Vec<&str> = CONTROLLERS.iter().map(|(name, _)| *name).collect();
    assert_eq!(listed, CONTROLLER_NAMES);
}

#[test]
fn every_key_in_the_table_is_accepted() {
    for (name, _) in CONTROLLERS {
        for option in options_of(name) {
            let spec = format!("{}={}", option.key, option.default);
            let refused = matches!(
                from_name_with(name, setup(), &spec, &NoFiles),
                Err(ConfigError::UnknownOption { .. })
            );
            assert!(
                !refused,
                "{name}: the table lists `{}`, the parser refuses it",
                option.key
            );
        }
    }
}

#[test]
fn an_unknown_key_is_refused_with_the_tables_keys() {
    for (name, _) in CONTROLLERS {
        let err = match from_name_with(name, setup(), "bogus=1", &NoFiles) {
            Err(e) => e,
            Ok(_) => panic!("{name} took bogus=1"),
        };
        match &err {
            ConfigError::UnknownOption { expected, .. } => {
                assert_eq!(expected, &expected_keys(name), "{name}");
            }
            other => panic!("{name}: {other}"),
        }
    }
}

#[test]
fn the_listing_names_every_controller_and_key() {
    let text = describe_controllers();
    for (name, _) in CONTROLLERS {
        assert!(text.contains(&format!("{name}: ")), "{name}");
        for option in options_of(name) {
            assert!(text.contains(option.key) && text.contains(option.default));
        }
    }
}
