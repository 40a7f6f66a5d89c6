//! glTF materials: base colour, metallic and transmission mapped onto diffuse, mirror and
//! dielectric; one object per material; the scene's `material` as an override; round-trip.

use std::path::{Path, PathBuf};
use steadyray_scene::{Material, Shape, Vec3, parse_scene, scene_to_toml};
use tempfile::TempDir;

fn dir(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("steadyray-gltfmat-{name}-"))
        .tempdir()
        .unwrap()
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A .gltf file with an embedded buffer holding two triangles (the second shifted by +2 x),
/// drawn by primitives with the given materials (`null` for none), and `materials_json`.
fn gltf(d: &Path, name: &str, prim_materials: &[&str], materials_json: &str) -> PathBuf {
    let mut bin = Vec::new();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    let prims: Vec<String> = prim_materials
        .iter()
        .map(|m| {
            let m = if *m == "null" {
                String::new()
            } else {
                format!(r#", "material": {m}"#)
            };
            format!(r#"{{"attributes": {{"POSITION": 0}}{m}}}"#)
        })
        .collect();
    let meshes: Vec<String> = prims
        .iter()
        .map(|p| format!(r#"{{"primitives": [{p}]}}"#))
        .collect();
    let nodes: Vec<String> = (0..prims.len())
        .map(|i| format!(r#"{{"mesh": {i}, "translation": [{}, 0, 0]}}"#, 2 * i))
        .collect();
    let roots: Vec<String> = (0..prims.len()).map(|i| i.to_string()).collect();
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],
  "scene": 0,
  "scenes": [{{"nodes": [{}]}}],
  "nodes": [{}],
  "meshes": [{}],
  "materials": {materials_json},
  "buffers": [{{"uri": "data:application/octet-stream;base64,{}", "byteLength": 36}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}
  ]
}}"#,
        roots.join(", "),
        nodes.join(", "),
        meshes.join(", "),
        base64(&bin)
    );
    let p = d.join(name);
    std::fs::write(&p, json).unwrap();
    p
}

const RED: &str = r#"{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1], "metallicFactor": 0}}"#;
const GOLD: &str = r#"{"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.3, 1], "metallicFactor": 1}}"#;
const GLASS: &str = r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 1, 0.9, 1], "metallicFactor": 0}, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33}}}"#;

fn scene_text(shape: &str) -> String {
    format!(
        "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n\n\
         [[materials]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.7\n\n\
         [[shapes]]\n{shape}"
    )
}

fn load(d: &Path, shape: &str) -> steadyray_scene::Scene {
    parse_scene(&scene_text(shape), "test.toml", Some(d)).unwrap()
}

fn round_trips(scene: &steadyray_scene::Scene) {
    let text = scene_to_toml(scene);
    let back = parse_scene(&text, "written.toml", None).unwrap();
    assert_eq!(&back, scene);
}

#[test]
fn base_colour_becomes_diffuse_albedo() {
    let tmp = dir("diffuse");
    let d = tmp.path();
    gltf(d, "red.gltf", &["0"], &format!("[{RED}]"));
    let s = load(d, "name = \"tri\"\ntype = \"mesh\"\npath = \"red.gltf\"");
    assert_eq!(s.objects.len(), 1);
    assert_eq!(s.objects[0].name, "tri");
    assert_eq!(s.materials[s.objects[0].material].0, "tri/red");
    assert_eq!(
        *s.material_of(0),
        Material::Diffuse {
            albedo: Vec3::new(0.8, 0.1, 0.1),
            checker: None
        }
    );
    round_trips(&s);
}

#[test]
fn metallic_becomes_mirror_and_transmission_dielectric() {
    let tmp = dir("metal");
    let d = tmp.path();
    gltf(d, "gold.gltf", &["0"], &format!("[{GOLD}]"));
    let s = load(d, "name = \"tri\"\ntype = \"mesh\"\npath = \"gold.gltf\"");
    assert_eq!(
        *s.material_of(0),
        Material::Mirror {
            reflectance: Vec3::new(1.0, 0.8, 0.3)
        }
    );
    gltf(d, "glass.gltf", &["0"], &format!("[{GLASS}]"));
    let s = load(d, "name = \"tri\"\ntype = \"mesh\"\npath = \"glass.gltf\"");
    // An unnamed glTF material is labelled by its index.
    assert_eq!(s.materials[s.objects[0].material].0, "tri/0");
    assert_eq!(
        *s.material_of(0),
        Material::Dielectric {
            ior: 1.33,
            tint: Vec3::new(0.9, 1.0, 0.9)
        }
    );
    round_trips(&s);
}

#[test]
fn two_materials_make_two_objects() {
    let tmp = dir("two");
    let d = tmp.path();
    gltf(d, "two.gltf", &["1", "0"], &format!("[{RED}, {GOLD}]"));
    let s = load(d, "name = \"pair\"\ntype = \"mesh\"\npath = \"two.gltf\"");
    assert_eq!(s.objects.len(), 2);
    let by_name = |n: &str| s.objects.iter().position(|o| o.name == n).unwrap();
    let red = by_name("pair/red");
    let gold = by_name("pair/gold");
    assert!(matches!(s.material_of(red), Material::Diffuse { .. }));
    assert!(matches!(s.material_of(gold), Material::Mirror { .. }));
    assert_eq!(s.materials[s.objects[red].material].0, "pair/red");
    assert_eq!(s.materials[s.objects[gold].material].0, "pair/gold");
    // Each object holds its own triangle: red's is the one moved by +2 x.
    let Shape::Mesh { mesh: m, .. } = &s.objects[red].shape else {
        panic!("not a mesh")
    };
    assert_eq!(m.triangles.len(), 1);
    assert_eq!(m.triangle(0)[0], Vec3::new(2.0, 0.0, 0.0));
    assert_eq!(s.materials.len(), 3);
    round_trips(&s);
}

#[test]
fn scene_material_overrides_the_files() {
    let tmp = dir("override");
    let d = tmp.path();
    gltf(d, "two.gltf", &["1", "0"], &format!("[{RED}, {GOLD}]"));
    let s = load(
        d,
        "name = \"pair\"\ntype = \"mesh\"\nmaterial = \"white\"\npath = \"two.gltf\"",
    );
    assert_eq!(s.objects.len(), 1);
    assert_eq!(s.objects[0].name, "pair");
    assert_eq!(s.materials.len(), 1);
    assert_eq!(s.objects[0].material, 0);
    let Shape::Mesh { mesh: m, .. } = &s.objects[0].shape else {
        panic!("not a mesh")
    };
    assert_eq!(m.triangles.len(), 2);
    round_trips(&s);
}

#[test]
fn missing_materials_are_clear_errors() {
    let tmp = dir("errors");
    let d = tmp.path();
    gltf(d, "bare.gltf", &["null"], "[]");
    let e = parse_scene(
        &scene_text("name = \"t\"\ntype = \"mesh\"\npath = \"bare.gltf\""),
        "test.toml",
        Some(d),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("no material") && e.contains("give the shape a `material`"),
        "{e}"
    );
    // With the override it loads.
    load(
        d,
        "name = \"t\"\ntype = \"mesh\"\nmaterial = \"white\"\npath = \"bare.gltf\"",
    );
    let e = parse_scene(
        &scene_text("name = \"b\"\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1"),
        "test.toml",
        None,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("shape \"b\": missing `material`"), "{e}");
    // A generated material name that is already taken.
    gltf(d, "red.gltf", &["0"], &format!("[{RED}]"));
    let text = scene_text("name = \"t\"\ntype = \"mesh\"\npath = \"red.gltf\"")
        .replace("name = \"white\"", "name = \"t/red\"");
    let e = parse_scene(&text, "test.toml", Some(d))
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"t/red\", which is already a material"), "{e}");
}
