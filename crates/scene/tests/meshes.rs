//! OBJ import: the repository's test meshes (`assets/meshes/`), transforms, malformed files,
//! meshes in scene files.

use std::path::{Path, PathBuf};
use steadyray_scene::Transform;
use steadyray_scene::mesh_import::{MeshImportError, MeshProblem, import_mesh};
use steadyray_scene::*;
use tempfile::TempDir;

fn repo_mesh(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes")
        .join(name)
}

/// A fresh directory for one test's files, removed when dropped.
fn temp_dir(test: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("steadyray-scene-{test}-"))
        .tempdir()
        .unwrap()
}

#[test]
fn teapot_has_all_its_triangles() {
    let m = import_mesh(&repo_mesh("teapot.obj"), &Transform::default()).unwrap();
    assert_eq!(m.mesh.triangles.len() + m.degenerate_dropped, 6320);
    assert_eq!(
        m.degenerate_dropped, 0,
        "the teapot has no zero-area triangles"
    );
    assert_eq!(m.mesh.positions.len(), 3644);
}

#[test]
fn bunny_has_all_its_triangles() {
    let m = import_mesh(&repo_mesh("stanford-bunny.obj"), &Transform::default()).unwrap();
    assert_eq!(m.mesh.triangles.len() + m.degenerate_dropped, 69451);
    assert_eq!(m.degenerate_dropped, 0);
    // Vertices no face uses are not imported.
    assert!(m.mesh.positions.len() <= 35947);
}

#[test]
fn transform_is_applied() {
    let plain = import_mesh(&repo_mesh("teapot.obj"), &Transform::default()).unwrap();
    let t = Transform {
        translate: Vec3::new(1.0, 2.0, 3.0),
        scale: Vec3::new(0.5, 2.0, 0.5),
        rotate_y_deg: 180.0,
    };
    let moved = import_mesh(&repo_mesh("teapot.obj"), &t).unwrap();
    assert_eq!(moved.mesh.triangles, plain.mesh.triangles);
    for (p, q) in plain.mesh.positions.iter().zip(&moved.mesh.positions) {
        let expect = Vec3::new(-0.5 * p.x + 1.0, 2.0 * p.y + 2.0, -0.5 * p.z + 3.0);
        assert!(
            (*q - expect).length() < 1e-5,
            "{p} -> {q}, expected {expect}"
        );
    }
}

#[test]
fn scene_file_mesh_paths_are_relative_to_the_file() {
    let tmp = temp_dir("relative");
    let dir = tmp.path();
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::copy(repo_mesh("teapot.obj"), dir.join("meshes/pot.obj")).unwrap();
    let scene = "[camera]\neye = [0, 1, 5]\ntarget = [0, 1, 0]\n\
                 [[materials]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.8\n\
                 [[shapes]]\nname = \"pot\"\ntype = \"mesh\"\nmaterial = \"white\"\n\
                 path = \"meshes/pot.obj\"\ntranslate = [0, 0, -1]\nscale = 0.5\nrotate_y_deg = 30\n";
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let s = load_scene_file(&dir.join("scene.toml")).unwrap();
    let Shape::Mesh {
        mesh, placement, ..
    } = &s.objects[0].shape
    else {
        panic!("not a mesh")
    };
    assert_eq!(mesh.triangles.len(), 6320);
    assert_eq!(placement.translate, Vec3::new(0.0, 0.0, -1.0));
    assert_eq!(placement.scale, Vec3::splat(0.5));
    assert_eq!(placement.rotate_y_deg, 30.0);
    // Written back inline, it reads back identically.
    let again = parse_scene(&scene_to_toml(&s), "again.toml", None).unwrap();
    assert_eq!(format!("{s:?}"), format!("{again:?}"));
}

#[test]
fn inline_mesh_with_degenerate_triangle_gives_a_note() {
    let scene = "[camera]\neye = [0, 1, 5]\ntarget = [0, 1, 0]\n\
                 [[materials]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.8\n\
                 [[shapes]]\nname = \"tri\"\ntype = \"mesh\"\nmaterial = \"white\"\n\
                 positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\ntriangles = [[0, 1, 2], [0, 0, 1]]\n";
    let (s, notes) = parse_scene_with_notes(scene, "n.toml", None).unwrap();
    assert_eq!(
        s.objects[0].shape,
        Shape::mesh(
            TriangleMesh {
                positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
                triangles: vec![[0, 1, 2]],
            },
            Transform::IDENTITY
        )
    );
    assert_eq!(notes.len(), 1);
    assert!(
        notes[0].starts_with("n.toml:8: shape \"tri\": dropped 1 degenerate"),
        "{notes:?}"
    );

    let bad = scene.replace("[0, 0, 1]]", "[0, 1, 3]]");
    let e = parse_scene(&bad, "n.toml", None).unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::Mesh);
    assert!(
        e.to_string()
            .starts_with("n.toml:12: shape \"tri\": triangle 1 refers to vertex 3"),
        "{e}"
    );
}

/// Writes `obj` as `<name>` in a temp dir and imports it, expecting an error whose message
/// names the file and contains `problem`.
fn bad_obj(name: &str, obj: &str, problem: &str) -> MeshImportError {
    let tmp = temp_dir(&format!("bad-{}", name.replace('.', "-")));
    let dir = tmp.path();
    let path = dir.join(name);
    std::fs::write(&path, obj).unwrap();
    let e = import_mesh(&path, &Transform::default()).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains(&path.display().to_string()),
        "file not named: {msg}"
    );
    assert!(msg.contains(problem), "expected {problem:?} in {msg}");
    e
}

#[test]
fn malformed_obj_files() {
    let e = bad_obj(
        "nan.obj",
        "v 0 0 0\nv 1 NaN 0\nv 0 1 0\nf 1 2 3\n",
        "vertex 1 is not finite",
    );
    assert!(matches!(
        e,
        MeshImportError::Invalid {
            problem: MeshProblem::NonFinite { vertex: 1, .. },
            ..
        }
    ));
    bad_obj(
        "inf.obj",
        "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n",
        "not finite",
    );
    bad_obj(
        "range.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
        "face vertex index out of bounds",
    );
    bad_obj(
        "zero.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
        "face vertex index out of bounds",
    );
    bad_obj(
        "negative.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -7\n",
        "out of bounds",
    );
    bad_obj("empty.obj", "# nothing\nv 0 0 0\n", "mesh has no triangles");
    bad_obj(
        "flat.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
        "all 1 triangles are degenerate",
    );
    bad_obj(
        "short.obj",
        "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "malformed OBJ",
    );
    bad_obj(
        "garbage.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n",
        "malformed OBJ",
    );
    bad_obj("mesh.ply", "ply\n", "unsupported format");
}

#[test]
fn texture_and_normal_indices_are_ignored() {
    // Out-of-range texture/normal indices must not upset the import (only v and f count).
    let tmp = temp_dir("texcoord");
    let dir = tmp.path();
    let path = dir.join("t.obj");
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n\
               f 1/0/0 2/99999999999999999999/ 3//-5\nf 1 1 2\n";
    std::fs::write(&path, obj).unwrap();
    let m = import_mesh(&path, &Transform::default()).unwrap();
    assert_eq!(m.mesh.triangles, vec![[0, 1, 2]]);
    assert_eq!(m.degenerate_dropped, 1);
}

#[test]
fn malformed_mesh_in_a_scene_names_scene_and_mesh() {
    let tmp = temp_dir("scene-bad-mesh");
    let dir = tmp.path();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap();
    let scene = "[camera]\neye = [0, 1, 5]\ntarget = [0, 1, 0]\n\
                 [[materials]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.8\n\
                 [[shapes]]\nname = \"thing\"\ntype = \"mesh\"\nmaterial = \"white\"\n\
                 path = \"bad.obj\"\n";
    let e = parse_scene(scene, "s.toml", Some(dir)).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.starts_with("s.toml:12: shape \"thing\": mesh \"bad.obj\": mesh file "),
        "{msg}"
    );
    assert!(msg.contains("face vertex index out of bounds"), "{msg}");
    // Both or neither of path and inline data is an error too.
    let both = scene.replace("path = \"bad.obj\"", "");
    let e = parse_scene(&both, "s.toml", Some(dir)).unwrap_err();
    assert!(e.to_string().contains("needs either `path`"), "{e}");
}
