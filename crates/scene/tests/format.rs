//! What the format accepts and the defaults it fills in (`docs/scene-format.md`).

use steadyray_scene::*;

const MINIMAL: &str = "[camera]\neye = [0, 1, 0]\ntarget = [0, 1, -1]\n";

#[test]
fn defaults() {
    let s = parse_scene(MINIMAL, "dir/minimal.toml", None).unwrap();
    assert_eq!(s.name, "minimal");
    assert_eq!(s.background, Vec3::ZERO);
    assert_eq!(s.ambient, 0.0);
    assert_eq!(s.path, CameraPath::sweep(720));
    assert_eq!(s.camera.vfov_deg, 60.0);
    assert_eq!(s.camera.up, Vec3::Y);
    assert_eq!(s.camera.forward, Vec3::NEG_Z);
    assert!(s.objects.is_empty() && s.materials.is_empty() && s.lights.is_empty());
}

#[test]
fn numbers_colours_and_directions() {
    let text = format!(
        "{MINIMAL}\
         [[materials]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 2\n\
         [[materials]]\nname = \"lamp\"\ntype = \"emissive\"\nradiance = [1, 2, 3]\n\
         [[shapes]]\nname = \"ground\"\ntype = \"plane\"\nmaterial = \"glass\"\n\
         point = [0, 0, 0]\nnormal = [0, 3, 0]\n\
         [[lights]]\nposition = [1, 2, 3]\nintensity = 7\n\
         [[lights]]\nposition = [1, 2, 3]\nintensity = [1, 0.5, 0]\n"
    );
    let s = parse_scene(&text, "x.toml", None).unwrap();
    assert_eq!(
        s.materials[0].1,
        Material::Dielectric {
            ior: 2.0,
            tint: Vec3::ONE
        }
    );
    assert_eq!(
        s.materials[1].1,
        Material::Emissive {
            radiance: Vec3::new(1.0, 2.0, 3.0)
        }
    );
    assert_eq!(
        s.objects[0].shape,
        Shape::Plane {
            point: Vec3::ZERO,
            normal: Vec3::Y
        }
    );
    assert_eq!(s.lights[0].intensity, Vec3::splat(7.0));
    assert_eq!(s.lights[1].intensity, Vec3::new(1.0, 0.5, 0.0));
}

#[test]
fn camera_forms() {
    let cam = |body: &str| {
        parse_scene(
            &format!("[camera]\neye = [0, 0, 0]\n{body}\n"),
            "c.toml",
            None,
        )
        .unwrap()
        .camera
    };
    // Yaw turns left from -z: yaw 90 looks along -x (docs/corridor.md).
    let c = cam("yaw_deg = 90");
    assert!((c.forward - Vec3::NEG_X).length() < 1e-6, "{}", c.forward);
    let c = cam("yaw_deg = 0\npitch_deg = 30");
    assert!((c.forward - Vec3::new(0.0, 0.5, -3f32.sqrt() / 2.0)).length() < 1e-6);
    let c = cam("forward = [0, 0, -5]\nup = [1, 0, 0]\nvfov_deg = 45");
    assert_eq!((c.forward, c.up, c.vfov_deg), (Vec3::NEG_Z, Vec3::X, 45.0));
    let c = cam("target = [3, 0, -4]");
    assert!((c.forward - Vec3::new(0.6, 0.0, -0.8)).length() < 1e-6);
}

#[test]
fn orbit_path() {
    let text =
        format!("{MINIMAL}[path]\ntype = \"orbit\"\ncenter = [1, 2, 3]\nradius = 4\nheight = 5\n");
    let s = parse_scene(&text, "o.toml", None).unwrap();
    assert_eq!(
        s.path,
        CameraPath {
            motion: PathMotion::Orbit {
                center: Vec3::new(1.0, 2.0, 3.0),
                radius: 4.0,
                height: 5.0,
            },
            frames: 720,
            duration_s: None,
        }
    );
}

#[test]
fn pans_path() {
    let text = format!("{MINIMAL}[path]\ntype = \"pans\"\nframes = 360\n");
    let s = parse_scene(&text, "p.toml", None).unwrap();
    assert_eq!(s.path, CameraPath::pans(360));
    assert_eq!(s.path.duration_s(), 8.0);
    let again = parse_scene(&scene_to_toml(&s), "again.toml", None).unwrap();
    assert_eq!(again.path, s.path);
    let extra = format!("{MINIMAL}[path]\ntype = \"pans\"\nradius = 3\n");
    let e = parse_scene(&extra, "p.toml", None).unwrap_err().to_string();
    assert!(e.contains("radius"), "{e}");
}

#[test]
fn hand_made_scenes_round_trip() {
    // Odd floats, odd names, every material and shape kind (meshes in tests/meshes.rs).
    let text = r#"name = "q\"uote\\ \u00e9"
background = [0.1, 0.2, 0.30000001]
ambient = 1e-7
[camera]
eye = [0.1, 0.2, 0.3]
target = [1.7, -0.3, 2.9]
up = [0.1, 1, 0]
vfov_deg = 33.3
[path]
type = "orbit"
center = [0.1, 0.2, 0.3]
radius = 3.3
height = -0.7
frames = 17
[[materials]]
name = "d"
type = "diffuse"
albedo = [0.3, 0.6, 0.9]
checker = { size = 0.3, albedo_b = [0.1, 0.2, 0.3] }
[[materials]]
name = "g"
type = "dielectric"
ior = 1.33
tint = [0.9, 1, 0.95]
[[materials]]
name = "e"
type = "emissive"
radiance = 2.5
[[shapes]]
name = "p"
type = "plane"
material = "e"
point = [1, 2, 3]
normal = [0.3, 0.4, 0.5]
[[shapes]]
name = "q"
type = "quad"
material = "g"
corner = [0.1, 0.1, 0.1]
edge_u = [0.7, 0.1, 0]
edge_v = [0, 0.3, 0.9]
[[shapes]]
name = "s"
type = "sphere"
material = "d"
center = [0.1, 0, 0]
radius = 0.123456789
"#;
    let s = parse_scene(text, "h.toml", None).unwrap();
    let again = parse_scene(&scene_to_toml(&s), "h2.toml", None).unwrap();
    assert_eq!(s, again);
    assert_eq!(format!("{s:?}"), format!("{again:?}"));
}

#[test]
fn the_documented_example_parses() {
    let doc = include_str!("../../../docs/scene-format.md");
    let start = doc.find("```toml\n").unwrap() + "```toml\n".len();
    let end = start + doc[start..].find("```").unwrap();
    let example = doc[start..end].replace("meshes/teapot.obj", "teapot.obj");
    let meshes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes");
    let s = parse_scene(&example, "example.toml", Some(&meshes)).unwrap();
    assert_eq!(s.name, "example");
    assert_eq!(s.objects.len(), 4);
    assert!(
        matches!(&s.objects[3].shape, Shape::Mesh { mesh, .. } if mesh.triangles.len() == 6320)
    );
}
