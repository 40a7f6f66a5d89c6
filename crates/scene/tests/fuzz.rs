//! Property tests: no input makes the parser panic, and any valid scene's floats survive
//! writing and reading back bit for bit.

use proptest::prelude::*;
use steadyray_scene::*;

const CORRIDOR: &str = include_str!("../builtin/corridor.toml");

/// Tokens that tend to reach the checks rather than stop at the TOML syntax.
const TOKENS: &[&str] = &[
    "0",
    "-1",
    "nan",
    "inf",
    "-inf",
    "1e39",
    "\"x\"",
    "[]",
    "[1, 2]",
    "[nan, 0, 0]",
    "{}",
    "true",
    "\n",
    "[[shapes]]\n",
    "[[materials]]\n",
    "[camera]\n",
    "=",
    "]",
    "\"",
    "type = \"mesh\"\n",
    "path = \"nowhere.obj\"\n",
    "radius = 0\n",
    "name = \"red\"\n",
    "4294967296",
];

/// The corridor with a span replaced by a token (or deleted).
fn garbled() -> impl Strategy<Value = String> {
    (
        0..CORRIDOR.len(),
        0usize..40,
        prop::option::of(0..TOKENS.len()),
    )
        .prop_map(|(start, len, token)| {
            let mut start = start;
            while !CORRIDOR.is_char_boundary(start) {
                start -= 1;
            }
            let mut end = (start + len).min(CORRIDOR.len());
            while !CORRIDOR.is_char_boundary(end) {
                end -= 1;
            }
            format!(
                "{}{}{}",
                &CORRIDOR[..start],
                token.map_or("", |t| TOKENS[t]),
                &CORRIDOR[end..]
            )
        })
}

proptest! {
    // A fixed seed keeps the suite deterministic; 1024 cases still run in well under a second.
    #![proptest_config(ProptestConfig {
        cases: 1024,
        rng_seed: prop::test_runner::RngSeed::Fixed(0x5ce7e),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_text_never_panics(text in "\\PC{0,200}") {
        let _ = parse_scene(&text, "fuzz.toml", None);
    }

    #[test]
    fn garbled_corridor_never_panics(text in garbled()) {
        match parse_scene(&text, "fuzz.toml", None) {
            Ok(scene) => {
                // Whatever parses also writes and reads back unchanged.
                let again = parse_scene(&scene_to_toml(&scene), "again.toml", None).unwrap();
                prop_assert_eq!(format!("{scene:?}"), format!("{again:?}"));
            }
            Err(e) => prop_assert!(e.to_string().starts_with("fuzz.toml")),
        }
    }

    #[test]
    fn any_floats_round_trip(
        center in prop::array::uniform3(prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO),
        radius in prop::num::f32::POSITIVE.prop_filter("finite, > 0", |r| r.is_finite() && *r > 0.0),
        albedo in prop::array::uniform3(0.0f32..10.0),
        ior in 0.001f32..4.0,
        vfov in 0.01f32..179.99,
    ) {
        let mut scene = builtin("corridor").unwrap();
        scene.objects[3].shape = Shape::Sphere { center: Vec3::from(center), radius };
        scene.materials[2].1 = Material::Diffuse { albedo: Vec3::from(albedo), checker: None };
        scene.materials[5].1 = Material::Dielectric { ior, tint: Vec3::from(albedo) };
        scene.camera.vfov_deg = vfov;
        let again = parse_scene(&scene_to_toml(&scene), "again.toml", None).unwrap();
        prop_assert_eq!(format!("{scene:?}"), format!("{again:?}"));
    }
}
