//! Every malformed scene gives an error naming the file, the line and the problem; none
//! panics.

use steadyray_scene::*;

/// A valid scene to break: each case appends to it or replaces one of its lines.
const BASE: &str = r#"name = "t"
ambient = 0.05

[camera]
eye = [0.0, 1.0, 0.0]
yaw_deg = 0.0
vfov_deg = 60.0

[path]
type = "sweep"
frames = 10

[[materials]]
name = "m"
type = "diffuse"
albedo = 0.5

[[shapes]]
name = "ball"
type = "sphere"
material = "m"
center = [0.0, 0.0, -3.0]
radius = 1.0

[[lights]]
position = [0.0, 3.0, 0.0]
intensity = 5.0
"#;

/// `BASE` with the first line starting with `old` replaced by `new` (or `new` appended when
/// `old` is empty).
fn edit(old: &str, new: &str) -> String {
    if old.is_empty() {
        return format!("{BASE}\n{new}\n");
    }
    let mut found = false;
    let lines: Vec<String> = BASE
        .lines()
        .map(|l| {
            if !found && l.starts_with(old) {
                found = true;
                new.to_owned()
            } else {
                l.to_owned()
            }
        })
        .collect();
    assert!(found, "no line starts with {old:?}");
    lines.join("\n")
}

/// The 1-based line of the first line of `text` starting with `marker`, searching from the
/// `nth` (0-based) match.
fn line_of(text: &str, marker: &str, nth: usize) -> usize {
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with(marker))
        .nth(nth)
        .unwrap_or_else(|| panic!("no line {marker:?} in\n{text}"))
        .0
        + 1
}

/// Parses `text` as `bad.toml`, expecting an error at the line of `marker` (its `nth`
/// match) whose message contains every one of `problem`.
fn expect_err(text: &str, marker: &str, nth: usize, problem: &[&str]) -> SceneError {
    let e = match parse_scene(text, "bad.toml", None) {
        Ok(_) => panic!("parsed, expected an error about {problem:?}:\n{text}"),
        Err(e) => e,
    };
    let msg = e.to_string();
    let line = line_of(text, marker, nth);
    assert!(
        msg.starts_with(&format!("bad.toml:{line}: ")),
        "expected bad.toml:{line}: ..., got {msg}"
    );
    for p in problem {
        assert!(msg.contains(p), "expected {p:?} in: {msg}");
    }
    e
}

#[test]
fn base_is_valid() {
    parse_scene(BASE, "base.toml", None).unwrap();
}

#[test]
fn missing_fields() {
    let t = edit("radius = 1.0", "");
    expect_err(&t, "[[shapes]]", 0, &["shape \"ball\"", "missing `radius`"]);
    let t = edit("albedo = 0.5", "");
    expect_err(
        &t,
        "[[materials]]",
        0,
        &["material \"m\"", "missing `albedo`"],
    );
    let t = edit("name = \"ball\"", "");
    expect_err(&t, "[[shapes]]", 0, &["missing field `name`"]);
    let t = edit("eye = ", "");
    expect_err(&t, "[camera]", 0, &["missing field `eye`"]);
    let t = edit("intensity = ", "");
    expect_err(&t, "[[lights]]", 0, &["missing field `intensity`"]);
    let t = edit("yaw_deg = 0.0", "");
    expect_err(
        &t,
        "[camera]",
        0,
        &["exactly one of `target`, `forward` or `yaw_deg`"],
    );
}

#[test]
fn missing_camera_names_the_file() {
    let t = "name = \"x\"\n";
    let e = parse_scene(t, "bad.toml", None).unwrap_err();
    assert!(e.to_string().starts_with("bad.toml:"), "{e}");
    assert!(e.to_string().contains("missing field `camera`"), "{e}");
}

#[test]
fn wrong_types() {
    let t = edit("radius = 1.0", "radius = \"big\"");
    expect_err(
        &t,
        "radius =",
        0,
        &["invalid type: string \"big\"", "radius = \"big\""],
    );
    let t = edit("center = ", "center = [0.0, 1.0]");
    expect_err(&t, "center =", 0, &["invalid length 2", "center"]);
    let t = edit("intensity = ", "intensity = \"bright\"");
    expect_err(
        &t,
        "intensity =",
        0,
        &["a number or an array of three numbers"],
    );
    let t = edit("name = \"ball\"", "name = 3");
    expect_err(&t, "name = 3", 0, &["invalid type: integer"]);
    let t = edit("frames = 10", "frames = -1");
    expect_err(&t, "frames =", 0, &["invalid value: integer `-1`"]);
    let t = edit("frames = 10", "frames = 2.5");
    expect_err(&t, "frames =", 0, &["invalid type: floating point `2.5`"]);
}

#[test]
fn non_finite_numbers() {
    let t = edit("radius = 1.0", "radius = nan");
    expect_err(
        &t,
        "radius =",
        0,
        &["shape \"ball\"", "radius must be a finite number, got NaN"],
    );
    let t = edit("center = ", "center = [0.0, inf, 0.0]");
    expect_err(
        &t,
        "center =",
        0,
        &["shape \"ball\"", "center must be finite"],
    );
    let t = edit("ambient = ", "ambient = -inf");
    expect_err(&t, "ambient =", 0, &["ambient must be a finite number"]);
    let t = edit("eye = ", "eye = [nan, 0.0, 0.0]");
    expect_err(&t, "eye =", 0, &["camera", "eye must be finite"]);
    let t = edit("intensity = ", "intensity = [1.0, nan, 1.0]");
    expect_err(
        &t,
        "intensity =",
        0,
        &["light 1", "intensity must be finite"],
    );
    let t = edit("radius = 1.0", "radius = 1e300");
    expect_err(
        &t,
        "radius =",
        0,
        &["radius must be a finite number, got inf"],
    );
}

#[test]
fn bad_radius() {
    let t = edit("radius = 1.0", "radius = -0.5");
    let e = expect_err(
        &t,
        "radius =",
        0,
        &["shape \"ball\": radius must be positive, got -0.5"],
    );
    assert_eq!(e.kind, SceneErrorKind::Invalid);
    let t = edit("radius = 1.0", "radius = 0");
    expect_err(&t, "radius =", 0, &["radius must be positive, got 0"]);
}

const QUAD: &str = r#"[[shapes]]
name = "wall"
type = "quad"
material = "m"
corner = [0.0, 0.0, 0.0]
edge_u = [1.0, 0.0, 0.0]
edge_v = [0.0, 1.0, 0.0]"#;

#[test]
fn bad_quads() {
    let t = format!(
        "{BASE}\n{}",
        QUAD.replace("edge_u = [1.0, 0.0, 0.0]", "edge_u = [0, 0, 0]")
    );
    expect_err(
        &t,
        "edge_u =",
        0,
        &["shape \"wall\"", "edge_u must not be zero-length"],
    );
    let t = format!(
        "{BASE}\n{}",
        QUAD.replace("edge_v = [0.0, 1.0, 0.0]", "edge_v = [-2.0, 0.0, 0.0]")
    );
    expect_err(&t, "edge_v =", 0, &["shape \"wall\"", "are parallel"]);
    let t = format!("{BASE}\n{}", QUAD.replace("edge_v = [0.0, 1.0, 0.0]", ""));
    expect_err(&t, "[[shapes]]", 1, &["shape \"wall\"", "missing `edge_v`"]);
    parse_scene(&format!("{BASE}\n{QUAD}"), "ok.toml", None).unwrap();
}

#[test]
fn zero_plane_normal() {
    let plane = "[[shapes]]\nname = \"ground\"\ntype = \"plane\"\nmaterial = \"m\"\n\
                 point = [0, 0, 0]\nnormal = [0, 0, 0]";
    let t = format!("{BASE}\n{plane}");
    expect_err(
        &t,
        "normal =",
        0,
        &["shape \"ground\"", "normal must not be zero-length"],
    );
}

#[test]
fn unknown_material_name() {
    let t = edit("material = \"m\"", "material = \"gold\"");
    let e = expect_err(
        &t,
        "material =",
        0,
        &[
            "shape \"ball\"",
            "unknown material \"gold\"",
            "materials: m",
        ],
    );
    assert_eq!(e.kind, SceneErrorKind::Invalid);
}

#[test]
fn unknown_types() {
    let t = edit("type = \"diffuse\"", "type = \"velvet\"");
    expect_err(
        &t,
        "type = \"velvet\"",
        0,
        &["material \"m\"", "unknown material type \"velvet\""],
    );
    let t = edit("type = \"sphere\"", "type = \"cube\"");
    expect_err(
        &t,
        "type = \"cube\"",
        0,
        &["shape \"ball\"", "unknown shape type \"cube\""],
    );
    let t = edit("type = \"sweep\"", "type = \"spiral\"");
    expect_err(
        &t,
        "type = \"spiral\"",
        0,
        &["unknown path type \"spiral\""],
    );
}

#[test]
fn duplicate_names() {
    let t = edit(
        "",
        "[[materials]]\nname = \"m\"\ntype = \"mirror\"\nreflectance = 1",
    );
    expect_err(&t, "name = \"m\"", 1, &["duplicate material name \"m\""]);
    let t = edit(
        "",
        "[[shapes]]\nname = \"ball\"\ntype = \"sphere\"\nmaterial = \"m\"\n\
         center = [1, 1, 1]\nradius = 1",
    );
    expect_err(&t, "name = \"ball\"", 1, &["duplicate shape name \"ball\""]);
}

#[test]
fn missing_mesh_file() {
    let mesh = "[[shapes]]\nname = \"pot\"\ntype = \"mesh\"\nmaterial = \"m\"\n\
                path = \"meshes/nowhere.obj\"";
    let t = format!("{BASE}\n{mesh}");
    let e = expect_err(
        &t,
        "path =",
        0,
        &["shape \"pot\"", "meshes/nowhere.obj", "cannot read"],
    );
    assert_eq!(e.kind, SceneErrorKind::Mesh);
}

#[test]
fn camera_problems() {
    for bad in ["0", "0.0", "180", "200", "-30"] {
        let t = edit("vfov_deg = ", &format!("vfov_deg = {bad}"));
        expect_err(
            &t,
            "vfov_deg =",
            0,
            &["camera", "vfov_deg must be in (0, 180)"],
        );
    }
    let t = edit("yaw_deg = 0.0", "yaw_deg = 0.0\ntarget = [0, 0, -1]");
    expect_err(
        &t,
        "target =",
        0,
        &["exactly one of", "(got yaw_deg, target)"],
    );
    let t = edit("yaw_deg = 0.0", "target = [0.0, 1.0, 0.0]");
    expect_err(&t, "target =", 0, &["target must differ from eye"]);
    // Looking straight along `up` is fine (`Camera::frame` handles it).
    let t = edit("yaw_deg = 0.0", "yaw_deg = 0.0\npitch_deg = -90");
    parse_scene(&t, "ok.toml", None).unwrap();
    let t = edit("yaw_deg = 0.0", "pitch_deg = 10");
    expect_err(&t, "pitch_deg =", 0, &["pitch_deg needs yaw_deg"]);
    let t = edit("yaw_deg = 0.0", "yaw_deg = 0.0\nup = [0, 0, 0]");
    expect_err(&t, "up =", 0, &["up must not be zero-length"]);
}

#[test]
fn ior_must_be_positive() {
    for bad in ["0", "-1.5"] {
        let t = edit(
            "",
            &format!("[[materials]]\nname = \"g\"\ntype = \"dielectric\"\nior = {bad}"),
        );
        expect_err(&t, "ior =", 0, &["material \"g\"", "ior must be positive"]);
    }
}

#[test]
fn frames_must_be_positive() {
    let t = edit("frames = 10", "frames = 0");
    expect_err(
        &t,
        "frames =",
        0,
        &["path", "frames must be at least 1, got 0"],
    );
    let t = edit(
        "type = \"sweep\"",
        "type = \"orbit\"\ncenter = [0, 0, 0]\nradius = 0",
    );
    expect_err(&t, "radius = 0", 0, &["path", "radius must be positive"]);
    let t = edit("type = \"sweep\"", "type = \"orbit\"\ncenter = [0, 0, 0]");
    expect_err(&t, "[path]", 0, &["path", "missing `radius`"]);
}

#[test]
fn unknown_keys() {
    let t = edit("ambient = ", "ambient = 0.05\nexposure = 2");
    expect_err(&t, "exposure", 0, &["unknown field `exposure`"]);
    let t = edit("vfov_deg = ", "vfov_deg = 60\nfov = 60");
    expect_err(&t, "fov =", 0, &["unknown field `fov`"]);
    let t = edit("radius = 1.0", "radius = 1.0\nradiu = 1.0");
    expect_err(&t, "radiu =", 0, &["unknown field `radiu`"]);
    // A key of the format that does not belong to this type.
    let t = edit("radius = 1.0", "radius = 1.0\nnormal = [0, 1, 0]");
    expect_err(
        &t,
        "normal =",
        0,
        &["shape \"ball\"", "key `normal` does not apply to a sphere"],
    );
    let t = edit("albedo = 0.5", "albedo = 0.5\nior = 1.5");
    expect_err(
        &t,
        "ior =",
        0,
        &["material \"m\"", "key `ior` does not apply to a diffuse"],
    );
    let t = edit("frames = 10", "frames = 10\nradius = 3");
    expect_err(
        &t,
        "radius = 3",
        0,
        &["key `radius` does not apply to a sweep path"],
    );
}

#[test]
fn negative_colours() {
    let t = edit("albedo = 0.5", "albedo = [0.5, -0.1, 0.5]");
    expect_err(
        &t,
        "albedo =",
        0,
        &["material \"m\"", "albedo must not be negative"],
    );
    let t = edit("intensity = ", "intensity = -1");
    expect_err(
        &t,
        "intensity =",
        0,
        &["light 1", "intensity must not be negative"],
    );
    let t = edit(
        "albedo = 0.5",
        "albedo = 0.5\nchecker = { size = 0, albedo_b = 0.1 }",
    );
    expect_err(&t, "checker =", 0, &["checker.size must be positive"]);
}

#[test]
fn toml_syntax_errors() {
    let t = edit("radius = 1.0", "radius = [1.0");
    let e = parse_scene(&t, "bad.toml", None).unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::Syntax);
    assert!(e.to_string().starts_with("bad.toml:"), "{e}");
    let t = edit("ambient = ", "ambient = 0.05\nambient = 0.1");
    let line = line_of(&t, "ambient", 1);
    let e = parse_scene(&t, "bad.toml", None).unwrap_err();
    assert!(
        e.to_string().starts_with(&format!("bad.toml:{line}:")),
        "{e}"
    );
}

#[test]
fn unreadable_file_names_the_file() {
    let e = load_scene_file(std::path::Path::new("/no/such/dir/scene.toml")).unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::Io);
    assert!(
        e.to_string()
            .starts_with("/no/such/dir/scene.toml: cannot read"),
        "{e}"
    );
}
