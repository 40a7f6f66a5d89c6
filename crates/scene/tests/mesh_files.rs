//! Mesh files: OBJ and glTF import, node transforms, and the errors for malformed files,
//! non-finite vertices, out-of-range indices and empty meshes, each naming the file.

use std::path::PathBuf;
use steadyray_scene::Transform;
use steadyray_scene::Vec3;
use steadyray_scene::mesh_import::import_mesh;
use tempfile::TempDir;

/// A fresh directory for this test's files, removed when dropped.
fn dir(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("steadyray-mesh-{name}-"))
        .tempdir()
        .unwrap()
}

fn write(dir: &std::path::Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// The error message of importing `path`, checked to name the file.
fn import_err(path: &std::path::Path) -> String {
    let e = import_mesh(path, &Transform::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains(&path.display().to_string()), "{e}");
    e
}

#[test]
fn bad_obj_files_name_the_file() {
    let tmp = dir("obj");
    let d = tmp.path();
    let cases: [(&str, &str, &str); 5] = [
        (
            "syntax.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
            "malformed OBJ",
        ),
        (
            "nan.obj",
            "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
            "not finite",
        ),
        (
            "inf.obj",
            "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n",
            "not finite",
        ),
        ("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", ""),
        ("empty.obj", "# nothing\n", ""),
    ];
    for (name, text, expect) in cases {
        let e = import_err(&write(d, name, text.as_bytes()));
        assert!(e.contains(expect), "{name}: {e}");
    }
    let e = import_err(&d.join("missing.obj"));
    assert!(e.contains("cannot read"), "{e}");
    let e = import_err(&write(d, "mesh.ply", b"ply\n"));
    assert!(e.contains("unsupported format"), "{e}");
}

#[test]
fn degenerate_obj_triangles_are_skipped_and_counted() {
    let tmp = dir("degenerate");
    let d = tmp.path();
    let p = write(
        d,
        "d.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 3 3 3\n",
    );
    let m = import_mesh(&p, &Transform::default()).unwrap();
    assert_eq!(m.degenerate_dropped, 2);
    assert_eq!(m.mesh.triangles, vec![[0, 1, 2]]);
}

/// A glTF file with one triangle (buffer `tri.bin`) instanced by `nodes_json`, whose
/// `indices` accessor holds `indices` (u16) and whose primitive has `mode`.
fn gltf_file(
    d: &std::path::Path,
    name: &str,
    nodes_json: &str,
    indices: [u16; 3],
    mode: u32,
) -> PathBuf {
    let mut bin = Vec::new();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    bin.extend_from_slice(&[0, 0]);
    std::fs::write(d.join("tri.bin"), &bin).unwrap();
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": {nodes_json},
  "meshes": [{{"name": "tri", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1, "mode": {mode}}}]}}],
  "buffers": [{{"uri": "tri.bin", "byteLength": 44}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 6}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}}
  ]
}}"#
    );
    write(d, name, json.as_bytes())
}

#[test]
fn gltf_nodes_place_their_meshes() {
    let tmp = dir("gltf");
    let d = tmp.path();
    // The root moves by +10 x; its child scales by 2 and carries the mesh; a second child
    // instances the mesh again unscaled.
    let nodes = r#"[
        {"translation": [10, 0, 0], "children": [1, 2]},
        {"scale": [2, 2, 2], "mesh": 0},
        {"translation": [0, 0, -1], "mesh": 0}
    ]"#;
    let p = gltf_file(d, "tri.gltf", nodes, [0, 1, 2], 4);
    let transform = Transform {
        translate: Vec3::new(0.0, 5.0, 0.0),
        ..Default::default()
    };
    let m = import_mesh(&p, &transform).unwrap();
    assert_eq!(m.mesh.triangles.len(), 2);
    let mut corners: Vec<[Vec3; 3]> = (0..2).map(|i| m.mesh.triangle(i)).collect();
    corners.sort_by(|a, b| a[1].x.total_cmp(&b[1].x));
    assert_eq!(
        corners[0],
        [
            Vec3::new(10.0, 5.0, -1.0),
            Vec3::new(11.0, 5.0, -1.0),
            Vec3::new(10.0, 6.0, -1.0)
        ]
    );
    assert_eq!(
        corners[1],
        [
            Vec3::new(10.0, 5.0, 0.0),
            Vec3::new(12.0, 5.0, 0.0),
            Vec3::new(10.0, 7.0, 0.0)
        ]
    );
}

#[test]
fn bad_gltf_files_name_the_file() {
    let tmp = dir("gltf-bad");
    let d = tmp.path();
    let e = import_err(&write(d, "garbage.gltf", b"{ not json"));
    assert!(e.contains("malformed glTF"), "{e}");
    let e = import_err(&write(d, "garbage.glb", b"glTF\x02\0\0\0junk"));
    assert!(e.contains("malformed glTF"), "{e}");
    let one = r#"[{"mesh": 0}]"#;
    let e = import_err(&gltf_file(d, "range.gltf", one, [0, 1, 7], 4));
    assert!(e.contains("index 7 is out of range"), "{e}");
    let e = import_err(&gltf_file(d, "lines.gltf", one, [0, 1, 2], 1));
    assert!(e.contains("only triangle lists"), "{e}");
    let e = import_err(&gltf_file(d, "flat.gltf", one, [0, 1, 1], 4));
    assert!(e.contains("degenerate"), "{e}");
    let e = import_err(&d.join("missing.glb"));
    assert!(e.contains("cannot read"), "{e}");
}
