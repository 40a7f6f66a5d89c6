//! The built-in scenes: they load, they round-trip through `scene_to_toml` bit for bit, and
//! the corridor is exactly `docs/corridor.md`.

use steadyray_scene::*;

fn assert_identical(a: &Scene, b: &Scene) {
    assert_eq!(a, b);
    // `==` treats 0.0 and -0.0 alike; Debug prints every float in shortest round-trip form,
    // so equal Debug text means equal bits.
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
}

#[test]
fn names_descriptions_and_default() {
    assert_eq!(builtin_names(), ["corridor", "cornell", "spheres", "flyby"]);
    assert_eq!(DEFAULT_SCENE, "corridor");
    for (b, name) in builtin_scenes().iter().zip(builtin_names()) {
        assert_eq!(b.name, *name);
        assert_eq!(builtin_description(name), Some(b.description));
        assert!(
            !b.description.contains('\n'),
            "one line: {:?}",
            b.description
        );
        assert_eq!(builtin(name).unwrap().name, *name);
    }
    assert_eq!(builtin_description("nope"), None);
}

#[test]
fn unknown_builtin_is_an_error() {
    let e = builtin("nope").unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::UnknownScene);
    assert!(e.to_string().contains("corridor"), "{e}");
    let e = load_scene("no/such/scene.toml").unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::UnknownScene);
    assert!(e.to_string().contains("no/such/scene.toml"), "{e}");
}

#[test]
fn every_builtin_round_trips_exactly() {
    for name in builtin_names() {
        let scene = builtin(name).unwrap();
        let text = scene_to_toml(&scene);
        let again = parse_scene(&text, "written.toml", None)
            .unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_identical(&scene, &again);
        // And writing is stable.
        assert_eq!(scene_to_toml(&again), text);
    }
}

#[test]
fn load_scene_takes_names_and_paths() {
    let tmp = tempfile::Builder::new()
        .prefix("steadyray-scene-load-")
        .tempdir()
        .unwrap();
    let file = tmp.path().join("mine.toml");
    let corridor = load_scene("corridor").unwrap();
    std::fs::write(&file, scene_to_toml(&corridor)).unwrap();
    let loaded = load_scene(file.to_str().unwrap()).unwrap();
    assert_identical(&corridor, &loaded);
    assert_identical(&corridor, &load_scene_file(&file).unwrap());
}

fn object<'a>(s: &'a Scene, name: &str) -> &'a Object {
    s.objects
        .iter()
        .find(|o| o.name == name)
        .unwrap_or_else(|| panic!("no object {name}"))
}

fn material<'a>(s: &'a Scene, object_name: &str) -> &'a Material {
    &s.materials[object(s, object_name).material].1
}

fn sphere(s: &Scene, name: &str) -> (Vec3, f32) {
    match object(s, name).shape {
        Shape::Sphere { center, radius } => (center, radius),
        ref other => panic!("{name} is not a sphere: {other:?}"),
    }
}

/// The quad's extent as (min, max) corners; corridor quads are axis-aligned.
fn quad_box(s: &Scene, name: &str) -> (Vec3, Vec3) {
    match object(s, name).shape {
        Shape::Quad {
            corner,
            edge_u,
            edge_v,
        } => {
            let pts = [
                corner,
                corner + edge_u,
                corner + edge_v,
                corner + edge_u + edge_v,
            ];
            let lo = pts.iter().fold(Vec3::INFINITY, |a, &p| a.min(p));
            let hi = pts.iter().fold(Vec3::NEG_INFINITY, |a, &p| a.max(p));
            (lo, hi)
        }
        ref other => panic!("{name} is not a quad: {other:?}"),
    }
}

fn diffuse(albedo: [f32; 3]) -> Material {
    Material::Diffuse {
        albedo: Vec3::from(albedo),
        checker: None,
    }
}

#[test]
fn corridor_matches_the_spec() {
    let s = builtin("corridor").unwrap();
    assert_eq!(s.objects.len(), 12);

    let v = Vec3::new;
    assert_eq!(
        quad_box(&s, "mirror_left"),
        (v(-2.0, 0.0, -12.0), v(-2.0, 3.0, -2.0))
    );
    assert_eq!(
        quad_box(&s, "mirror_right"),
        (v(2.0, 0.0, -12.0), v(2.0, 3.0, -2.0))
    );
    assert_eq!(
        quad_box(&s, "floor"),
        (v(-2.0, 0.0, -12.0), v(2.0, 0.0, -2.0))
    );
    let mirror = Material::Mirror {
        reflectance: Vec3::splat(0.9),
    };
    assert_eq!(material(&s, "mirror_left"), &mirror);
    assert_eq!(material(&s, "mirror_right"), &mirror);
    assert_eq!(
        material(&s, "floor"),
        &Material::Diffuse {
            albedo: Vec3::splat(0.8),
            checker: Some(Checker {
                size: 0.5,
                albedo_b: Vec3::splat(0.25)
            }),
        }
    );

    let spheres: [(&str, [f32; 3], f32, Material); 9] = [
        ("red", [-0.8, 0.5, -5.0], 0.5, diffuse([0.80, 0.15, 0.10])),
        ("green", [0.9, 0.6, -7.0], 0.6, diffuse([0.15, 0.70, 0.20])),
        ("blue", [0.0, 0.7, -9.5], 0.7, diffuse([0.15, 0.30, 0.85])),
        (
            "glass",
            [0.6, 0.45, -4.0],
            0.45,
            Material::Dielectric {
                ior: 1.5,
                tint: Vec3::ONE,
            },
        ),
        (
            "chrome",
            [-1.0, 0.55, -8.0],
            0.55,
            Material::Mirror {
                reflectance: Vec3::splat(0.95),
            },
        ),
        (
            "yellow",
            [1.2, 0.35, -10.5],
            0.35,
            diffuse([0.90, 0.80, 0.20]),
        ),
        (
            "behind_1",
            [-1.5, 1.0, 6.0],
            1.0,
            diffuse([0.70, 0.70, 0.70]),
        ),
        (
            "behind_2",
            [1.5, 0.8, 7.0],
            0.8,
            diffuse([0.60, 0.40, 0.70]),
        ),
        (
            "behind_3",
            [0.0, 0.6, 5.0],
            0.6,
            diffuse([0.40, 0.60, 0.80]),
        ),
    ];
    for (name, center, radius, m) in &spheres {
        assert_eq!(sphere(&s, name), (Vec3::from(*center), *radius), "{name}");
        assert_eq!(material(&s, name), m, "{name}");
    }

    let lights: Vec<_> = s.lights.iter().map(|l| (l.position, l.intensity)).collect();
    assert_eq!(
        lights,
        [
            (v(0.0, 2.8, -5.0), Vec3::splat(5.0)),
            (v(0.0, 2.8, -9.0), Vec3::splat(5.0)),
            (v(0.0, 3.0, 6.0), Vec3::splat(5.0)),
        ]
    );
    assert_eq!(s.ambient, 0.05);
    assert_eq!(s.background, v(0.05, 0.07, 0.12));
    assert_eq!(s.camera.eye, v(0.0, 1.5, 0.0));
    assert_eq!(s.camera.forward, v(0.0, 0.0, -1.0));
    assert_eq!(s.camera.up, Vec3::Y);
    assert_eq!(s.camera.vfov_deg, 60.0);
    assert_eq!(s.path, CameraPath::sweep(720));
    // Frame 0 of the sweep is the scene's camera.
    assert_eq!(s.camera_at(0, 720), s.camera);
}

#[test]
fn cameras_are_frame_zero_of_their_paths() {
    for name in builtin_names() {
        let s = builtin(name).unwrap();
        let c = s.camera_at(0, s.path.frames());
        assert!((c.eye - s.camera.eye).length() < 1e-6, "{name}");
        assert!((c.forward - s.camera.forward).length() < 1e-6, "{name}");
    }
}

#[test]
fn cornell_and_spheres_have_what_they_promise() {
    let c = builtin("cornell").unwrap();
    let kinds = |s: &Scene, f: fn(&Material) -> bool| {
        s.objects
            .iter()
            .filter(|o| f(&s.materials[o.material].1))
            .count()
    };
    assert_eq!(kinds(&c, |m| matches!(m, Material::Mirror { .. })), 1);
    assert_eq!(kinds(&c, |m| matches!(m, Material::Dielectric { .. })), 1);
    assert_eq!(c.lights.len(), 1);

    let s = builtin("spheres").unwrap();
    let spheres = s
        .objects
        .iter()
        .filter(|o| matches!(o.shape, Shape::Sphere { .. }))
        .count();
    assert!(spheres >= 49, "{spheres}");
    assert!(kinds(&s, |m| matches!(m, Material::Mirror { .. })) > 0);
    assert!(kinds(&s, |m| matches!(m, Material::Dielectric { .. })) > 0);
    assert!(s.lights.len() >= 3);
    assert!(matches!(s.path.motion, PathMotion::Orbit { .. }));
}

#[test]
fn paths_are_functions_of_time() {
    for name in builtin_names() {
        let s = builtin(name).unwrap();
        let n = s.path.frames();
        assert!(
            (s.path.duration_s() - n as f64 / 60.0).abs() < 1e-12,
            "{name}"
        );
        for k in [0, 1, n / 3, n - 1] {
            let t = s.path.frame_time(k, n);
            let (a, b) = (s.camera_at(k, n), s.camera_at_time(t));
            assert!((a.eye - b.eye).length() < 1e-5, "{name} frame {k}");
            assert!((a.forward - b.forward).length() < 1e-5, "{name} frame {k}");
        }
        // The path repeats after its duration.
        let (a, b) = (
            s.camera_at_time(0.25),
            s.camera_at_time(0.25 + s.path.duration_s()),
        );
        assert!((a.forward - b.forward).length() < 1e-5, "{name}");
    }
}

/// The objects of `s` that exist at time `t`, each mesh copy counted.
fn objects_at(s: &Scene, t: f64) -> usize {
    s.objects
        .iter()
        .filter_map(|o| o.pose_at(t))
        .map(|p| match p {
            Pose::Mesh { copies, .. } => copies.len(),
            _ => 1,
        })
        .sum()
}

#[test]
fn flyby_moves_as_described() {
    let s = builtin("flyby").unwrap();
    assert!(s.is_animated());
    assert_eq!(s.path.duration_s(), 12.0);
    assert_eq!(s.path.frames(), 720);
    let PathMotion::Keys(keys) = &s.path.motion else {
        panic!("flyby flies a keyed path");
    };
    assert!(keys.looped);
    // The swarm appears at once at 4 s: ten times the objects (and more), gone at 8 s.
    let (before, during) = (objects_at(&s, 3.99), objects_at(&s, 4.0));
    assert!(during >= 10 * before, "{before} -> {during}");
    // At 8 s the swarm is gone and the glass ball has come.
    assert_eq!(objects_at(&s, 8.0), before + 1);
    assert_eq!(objects_at(&s, 11.5), before);
    // Objects fly between the mirrors (x in (-2.5, 2.5)) and move.
    let chrome = object(&s, "chrome_flyer");
    let (Some(Pose::Sphere { center: a, .. }), Some(Pose::Sphere { center: b, .. })) =
        (chrome.pose_at(0.0), chrome.pose_at(1.5))
    else {
        panic!("chrome flyer is a sphere");
    };
    assert!(a.x < -1.5 && b.x > 1.5, "{a} -> {b}");
    // The glass ball passes close in front of the camera around 9.5 s.
    let glass = object(&s, "glass_passer");
    let Some(Pose::Sphere { center, .. }) = glass.pose_at(9.5) else {
        panic!("the glass ball exists at 9.5 s");
    };
    let cam = s.camera_at_time(9.5);
    let to_glass = center - cam.eye;
    let distance = to_glass.length();
    let off_axis = to_glass
        .normalize()
        .dot(cam.forward.normalize())
        .acos()
        .to_degrees();
    assert!(
        distance < 3.0 && off_axis < 10.0,
        "{distance} m, {off_axis} deg"
    );
    assert!(glass.pose_at(7.0).is_none() && glass.pose_at(11.5).is_none());
    // The camera's flight is smooth and closed: where it starts, it ends.
    let (start, end) = (s.camera_at_time(0.0), s.camera_at_time(11.9999));
    assert!(
        (start.eye - end.eye).length() < 1e-3,
        "{start:?} vs {end:?}"
    );
}
