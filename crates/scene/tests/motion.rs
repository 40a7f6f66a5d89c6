//! Moving worlds in the scene format: keyed camera paths, `[shapes.motion]`, visibility and
//! mesh instances. They parse to what the file says, write back bit for bit, and every
//! malformed one is an error naming the file, the line and the problem.

use steadyray_scene::*;

const HEAD: &str = r#"name = "moving"

[camera]
eye = [0.0, 1.0, 5.0]
target = [0.0, 1.0, 0.0]

[path]
type = "keys"
frames = 300
duration_s = 6.0
loop = true

[[path.keys]]
t = 0.0
eye = [0.0, 1.0, 5.0]
target = [0.0, 1.0, 0.0]

[[path.keys]]
t = 2.5
eye = [4.0, 1.5, 0.0]
target = [0.0, 0.5, 0.0]
vfov_deg = 40.0

[[path.keys]]
t = 4.0
eye = [0.0, 2.0, -5.0]
target = [0.0, 1.0, 0.0]

[[materials]]
name = "m"
type = "diffuse"
albedo = 0.5

[[shapes]]
name = "floor"
type = "plane"
material = "m"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
"#;

const BALL: &str = r#"
[[shapes]]
name = "ball"
type = "sphere"
material = "m"
center = [0.0, 1.0, 0.0]
radius = 0.5

[shapes.motion]
loop = true
spin_deg_per_s = 45.0
visible = [[0.0, 2.0], [3.0, 10.0]]

[[shapes.motion.keys]]
t = 0.0
translate = [0.0, 0.0, 0.0]
scale = 1.0

[[shapes.motion.keys]]
t = 1.0
translate = [2.0, 0.0, 0.0]
scale = 2.0

[[shapes.motion.keys]]
t = 2.0
translate = [0.0, 0.0, 0.0]
scale = 1.0
"#;

const SWARM: &str = r#"
[[shapes]]
name = "swarm"
type = "mesh"
material = "m"
positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
triangles = [[0, 1, 2]]
translate = [0.0, 1.0, -2.0]
scale = 0.5
instances = [
  { translate = [1.0, 0.0, 0.0] },
  { rotate_y_deg = 90.0, scale = [1.0, 2.0, 1.0] },
  {},
]

[shapes.motion]
visible = [[1.5, 4.0]]
"#;

fn scene() -> String {
    format!("{HEAD}{BALL}{SWARM}")
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    parse_scene(text, "moving.toml", None)
}

#[test]
fn moving_scene_parses_to_what_the_file_says() {
    let s = parse(&scene()).unwrap();
    assert_eq!(s.path.duration_s(), 6.0);
    assert_eq!(s.path.frames(), 300);
    let PathMotion::Keys(keys) = &s.path.motion else {
        panic!("a keys path: {:?}", s.path);
    };
    assert!(keys.looped);
    assert_eq!(keys.keys.len(), 3);
    assert_eq!(keys.keys[1].t, 2.5);
    assert_eq!(keys.keys[1].vfov_deg, Some(40.0));
    assert_eq!(keys.keys[1].look, KeyLook::Target(Vec3::new(0.0, 0.5, 0.0)));
    // The camera passes through its keys.
    let at = s.camera_at_time(2.5);
    assert!((at.eye - Vec3::new(4.0, 1.5, 0.0)).length() < 1e-5);
    assert_eq!(at.vfov_deg, 40.0);

    let ball = &s.objects[1];
    let motion = ball.motion.as_ref().unwrap();
    assert!(motion.looped);
    assert_eq!(motion.spin_deg_per_s, 45.0);
    assert_eq!(motion.visible, Some(vec![[0.0, 2.0], [3.0, 10.0]]));
    assert_eq!(motion.keys.len(), 3);
    assert_eq!(motion.keys[1].scale, Some(Vec3::splat(2.0)));
    assert_eq!(
        ball.pose_at(1.0),
        Some(Pose::Sphere {
            center: Vec3::new(2.0, 1.0, 0.0),
            radius: 1.0
        })
    );
    assert_eq!(ball.pose_at(2.5), None, "between its visible intervals");
    // Looped with a 2 s lap: t = 5 is t = 1 again.
    assert_eq!(ball.pose_at(5.0), ball.pose_at(1.0));

    let swarm = &s.objects[2];
    let Shape::Mesh {
        placement,
        instances,
        ..
    } = &swarm.shape
    else {
        panic!("a mesh");
    };
    assert_eq!(placement.scale, Vec3::splat(0.5));
    assert_eq!(instances.len(), 3);
    assert_eq!(instances[1].scale, Vec3::new(1.0, 2.0, 1.0));
    assert_eq!(instances[2], Transform::IDENTITY);
    assert!(swarm.pose_at(1.0).is_none());
    let Some(Pose::Mesh { copies, .. }) = swarm.pose_at(2.0) else {
        panic!("the swarm exists at 2 s");
    };
    assert_eq!(copies.len(), 3);
    assert!(s.is_animated());
    assert!(!builtin("corridor").unwrap().is_animated());
}

#[test]
fn moving_scene_round_trips_exactly() {
    let s = parse(&scene()).unwrap();
    let text = scene_to_toml(&s);
    let again = parse_scene(&text, "again.toml", None).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(s, again);
    assert_eq!(format!("{s:?}"), format!("{again:?}"));
    assert_eq!(scene_to_toml(&again), text);

    // Yaw/pitch keys, an open path, odd floats.
    let yaw = scene()
        .replace(
            "loop = true\n\n[[path.keys]]",
            "loop = false\n\n[[path.keys]]",
        )
        .replace(
            "target = [0.0, 1.0, 0.0]\n\n[[path.keys]]\nt = 2.5",
            "yaw_deg = 0.1\npitch_deg = -3.3\n\n[[path.keys]]\nt = 2.5",
        )
        .replace("target = [0.0, 0.5, 0.0]", "yaw_deg = 90.0")
        .replace(
            "t = 4.0\neye = [0.0, 2.0, -5.0]\ntarget = [0.0, 1.0, 0.0]",
            "t = 4.0\neye = [0.0, 2.0, -5.0]\nyaw_deg = 180.0",
        );
    let s = parse(&yaw).unwrap_or_else(|e| panic!("{e}\n{yaw}"));
    let PathMotion::Keys(keys) = &s.path.motion else {
        panic!("a keys path");
    };
    assert!(!keys.looped);
    assert_eq!(
        keys.keys[0].look,
        KeyLook::YawPitch {
            yaw_deg: 0.1,
            pitch_deg: -3.3
        }
    );
    let again = parse_scene(&scene_to_toml(&s), "again.toml", None).unwrap();
    assert_eq!(format!("{s:?}"), format!("{again:?}"));
}

/// The 1-based line of the `nth` (0-based) line of `text` starting with `marker`.
fn line_of(text: &str, marker: &str, nth: usize) -> usize {
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with(marker))
        .nth(nth)
        .unwrap_or_else(|| panic!("no line {marker:?} in\n{text}"))
        .0
        + 1
}

/// `text` must fail to parse with an error at the line of `marker` (its `nth` match)
/// whose message holds every one of `problem`.
fn expect_err(text: &str, marker: &str, nth: usize, problem: &[&str]) {
    let e = match parse_scene(text, "bad.toml", None) {
        Ok(_) => panic!("parsed, expected an error about {problem:?}:\n{text}"),
        Err(e) => e,
    };
    let msg = e.to_string();
    let line = line_of(text, marker, nth);
    assert!(
        msg.starts_with(&format!("bad.toml:{line}: ")),
        "expected line {line} in {msg:?}\n{text}"
    );
    for p in problem {
        assert!(msg.contains(p), "{msg:?} should mention {p:?}");
    }
}

/// The moving scene with the `nth` line starting with `old` replaced by `new`.
fn edit(old: &str, nth: usize, new: &str) -> String {
    let text = scene();
    let line = line_of(&text, old, nth);
    text.lines()
        .enumerate()
        .map(|(i, l)| if i + 1 == line { new } else { l })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn keys_whose_times_do_not_increase() {
    expect_err(
        &edit("t = 2.5", 0, "t = 5.0"),
        "t = 4.0",
        0,
        &[
            "path: key 3",
            "key times must increase",
            "t = 4 is not after key 2's t = 5",
        ],
    );
    expect_err(
        &edit("t = 1.0", 0, "t = 0.0"),
        "t = 0.0",
        2,
        &["shape \"ball\": motion: key 2", "key times must increase"],
    );
    expect_err(
        &edit("t = 0.0", 0, "t = 0.5"),
        "t = 0.5",
        0,
        &["path: key 1", "first key must be at t = 0"],
    );
}

#[test]
fn visible_intervals_that_are_empty_or_overlap() {
    expect_err(
        &edit("visible = [[0.0", 0, "visible = [[0.0, 2.0], [3.0, 3.0]]"),
        "visible = [[0.0",
        0,
        &["visible interval 2 [3, 3] is empty"],
    );
    expect_err(
        &edit("visible = [[0.0", 0, "visible = [[0.0, 2.0], [1.0, 3.0]]"),
        "visible = [[0.0",
        0,
        &["visible interval 2 [1, 3] overlaps", "interval 1 [0, 2]"],
    );
    expect_err(
        &edit("visible = [[0.0", 0, "visible = []"),
        "visible = []",
        0,
        &["at least one"],
    );
}

#[test]
fn motion_on_a_plane_is_refused() {
    let text = scene().replacen(
        "normal = [0.0, 1.0, 0.0]\n",
        "normal = [0.0, 1.0, 0.0]\n\n[shapes.motion]\nspin_deg_per_s = 10.0\n",
        1,
    );
    expect_err(
        &text,
        "[shapes.motion]",
        0,
        &["shape \"floor\"", "a plane cannot move"],
    );
}

#[test]
fn non_finite_values_are_refused() {
    expect_err(
        &edit("t = 1.0", 0, "t = nan"),
        "t = nan",
        0,
        &["motion: key 2", "t must be a finite number of seconds"],
    );
    expect_err(
        &edit("translate = [2.0", 0, "translate = [inf, 0.0, 0.0]"),
        "translate = [inf",
        0,
        &["motion: key 2", "translate must be finite"],
    );
    expect_err(
        &edit("spin_deg_per_s", 0, "spin_deg_per_s = -inf"),
        "spin_deg_per_s",
        0,
        &["spin_deg_per_s must be a finite number"],
    );
    expect_err(
        &edit("duration_s", 0, "duration_s = nan"),
        "duration_s",
        0,
        &["path: duration_s must be a finite number of seconds"],
    );
    expect_err(
        &edit("duration_s", 0, "duration_s = -2.0"),
        "duration_s",
        0,
        &["path: duration_s must be positive"],
    );
    expect_err(
        &edit("visible = [[0.0", 0, "visible = [[0.0, inf]]"),
        "visible = [[0.0",
        0,
        &["must be finite"],
    );
    expect_err(
        &edit(
            "  { translate = [1.0",
            0,
            "  { translate = [nan, 0.0, 0.0] },",
        ),
        "  { translate = [nan",
        0,
        &["shape \"swarm\": instance 1", "translate must be finite"],
    );
}

#[test]
fn instance_lists_must_not_be_empty_and_only_meshes_have_them() {
    let text = scene().replace(
        "instances = [\n  { translate = [1.0, 0.0, 0.0] },\n  { rotate_y_deg = 90.0, scale = [1.0, 2.0, 1.0] },\n  {},\n]",
        "instances = []",
    );
    expect_err(
        &text,
        "instances = []",
        0,
        &["shape \"swarm\"", "instances must list at least one copy"],
    );
    expect_err(
        &edit("radius = 0.5", 0, "radius = 0.5\ninstances = [{}]"),
        "instances = [{}]",
        0,
        &["key `instances` does not apply to a sphere"],
    );
}

#[test]
fn a_path_with_one_key_or_mixed_looks_is_refused() {
    let one = scene().replacen(
        "[[path.keys]]\nt = 2.5\neye = [4.0, 1.5, 0.0]\ntarget = [0.0, 0.5, 0.0]\nvfov_deg = 40.0\n\n\
         [[path.keys]]\nt = 4.0\neye = [0.0, 2.0, -5.0]\ntarget = [0.0, 1.0, 0.0]\n",
        "",
        1,
    );
    expect_err(
        &one,
        "[[path.keys]]",
        0,
        &["a keys path needs at least two keys, got 1"],
    );
    expect_err(
        &edit("target = [0.0, 0.5, 0.0]", 0, "yaw_deg = 20.0"),
        "[[path.keys]]",
        1,
        &["path: key 2", "every key must look the same way"],
    );
    let no_keys = scene().replace("[[path.keys]]", "[[unused]]");
    assert!(parse(&no_keys).is_err());
    expect_err(
        &edit("duration_s", 0, "duration_s = 4.0"),
        "[[path.keys]]",
        0,
        &["last key (t = 4) must come before duration_s (4 s)"],
    );
    expect_err(
        &edit("eye = [4.0", 0, "eye = [0.0, 0.5, 0.0]"),
        "target = [0.0, 0.5",
        0,
        &["path: key 2: target must differ from eye"],
    );
}

#[test]
fn spheres_keep_their_shape_and_loops_close() {
    expect_err(
        &edit("scale = 2.0", 0, "scale = [2.0, 1.0, 2.0]"),
        "scale = [2.0, 1.0",
        0,
        &["shape \"ball\"", "a sphere stays a sphere", "one number"],
    );
    let open_lap = edit(
        "translate = [0.0, 0.0, 0.0]",
        1,
        "translate = [1.0, 0.0, 0.0]",
    );
    expect_err(
        &open_lap,
        "loop = true",
        1,
        &["looped motion's last key closes the lap"],
    );
    expect_err(
        &edit("spin_deg_per_s", 0, "spinn = 3.0"),
        "spinn",
        0,
        &["unknown field `spinn`"],
    );
}
