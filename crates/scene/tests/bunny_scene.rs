//! The repository's `scenes/bunny-cornell.toml`: the Stanford bunny (from `assets/meshes/`)
//! in a Cornell box.

use std::path::Path;
use steadyray_scene::{Shape, load_scene_file};

#[test]
fn bunny_cornell_loads_with_all_triangles() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let scene = load_scene_file(&root.join("scenes/bunny-cornell.toml")).unwrap();
    let meshes: Vec<_> = scene
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            Shape::Mesh {
                mesh, placement, ..
            } => Some((mesh, placement)),
            _ => None,
        })
        .collect();
    assert_eq!(meshes.len(), 1);
    let (mesh, placement) = meshes[0];
    assert_eq!(mesh.triangles.len(), 69_451);
    // The bunny sits on the floor (y = 0) inside the box.
    let min_y = mesh
        .positions
        .iter()
        .map(|&p| placement.apply(p).y)
        .fold(f32::INFINITY, f32::min);
    assert!(min_y.abs() < 0.02, "bunny's lowest point {min_y}");
}
