//! The scene suite's files (`scenes/suite/`, `docs/scene-suite.md`): each loads, turns on the
//! `pans` path, and has the character it is in the suite for.

use std::path::Path;
use steadyray_scene::{Material, PathMotion, Scene, Shape, load_scene_file};

fn suite_scene(name: &str) -> Scene {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/suite/{name}.toml"));
    load_scene_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// How many objects use a material of the kind `is_kind` picks.
fn objects_of(scene: &Scene, is_kind: fn(&Material) -> bool) -> usize {
    scene
        .objects
        .iter()
        .filter(|o| is_kind(&scene.materials[o.material].1))
        .count()
}

#[test]
fn every_suite_scene_loads_on_the_pans_path() {
    for name in ["glass", "meshes", "open", "kaleidoscope"] {
        let scene = suite_scene(name);
        assert_eq!(scene.name, name);
        assert!(matches!(scene.path.motion, PathMotion::Pans), "{name}");
        assert!(!scene.lights.is_empty(), "{name}");
    }
}

#[test]
fn each_has_its_character() {
    let glass = suite_scene("glass");
    assert!(objects_of(&glass, |m| matches!(m, Material::Dielectric { .. })) >= 15);

    let meshes = suite_scene("meshes");
    let copies: usize = meshes
        .objects
        .iter()
        .map(|o| match &o.shape {
            Shape::Mesh {
                instances, mesh, ..
            } => instances.len().max(1) * mesh.triangles.len(),
            _ => 0,
        })
        .sum();
    assert!(copies > 2_000_000, "{copies} instanced triangles");

    let open = suite_scene("open");
    assert_eq!(
        objects_of(&open, |m| matches!(m, Material::Mirror { .. })),
        1
    );

    let kaleidoscope = suite_scene("kaleidoscope");
    assert!(objects_of(&kaleidoscope, |m| matches!(m, Material::Mirror { .. })) >= 7);
}
