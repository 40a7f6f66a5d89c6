//! The GPU renderer against the CPU reference: the same pictures (up to float rounding) and
//! exactly the same ray counts, on the built-in scenes and on triangle meshes, at several
//! (S, R).

mod common;

use common::{assert_counts, compare, gpu};
use std::f32::consts::PI;
use steadyray_render::{RenderSettings, Renderer, SampleStream};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::Transform;
use steadyray_scene::mesh_import::import_mesh;
use steadyray_scene::{
    Camera, CameraPath, Checker, Material, Motion, MotionKey, Object, PointLight, Scene, Shape,
    TriangleMesh, Vec3, builtin,
};

/// Renders `scene` from `camera` on both backends at each (S, R) and checks parity;
/// returns a line per setting for the log.
fn check_parity(name: &str, scene: &Scene, camera: &Camera, size: (u32, u32), sr: &[(f32, u32)]) {
    check_parity_at(name, scene, camera, &[0.0], size, sr);
}

/// As [`check_parity`], at each of the scene times `times` (seconds).
fn check_parity_at(
    name: &str,
    scene: &Scene,
    camera: &Camera,
    times: &[f64],
    size: (u32, u32),
    sr: &[(f32, u32)],
) {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let mut cpu = CpuRenderer::new();
    gpu.load_scene(scene).unwrap();
    cpu.load_scene(scene).unwrap();
    for (&time, &(spp, max_depth)) in times.iter().flat_map(|t| std::iter::repeat(t).zip(sr)) {
        let settings = RenderSettings {
            width: size.0,
            height: size.1,
            spp,
            max_depth,
        };
        let g = gpu.render(camera, time, &settings).unwrap();
        let c = cpu.render(camera, time, &settings).unwrap();
        let diff = compare(&gpu.read_image().unwrap(), &cpu.read_image().unwrap());
        eprintln!(
            "{name} t={time} {}x{} S={spp} R={max_depth}: max {} mean {:.4} over2 {} ({:.3}%) \
             linear {:e}; \
             rays gpu {:?} shadow {} / cpu {:?} shadow {}; gpu {:.1} ms ({:?})",
            size.0,
            size.1,
            diff.max,
            diff.mean,
            diff.pixels_over_2,
            diff.fraction_over_2() * 100.0,
            diff.max_linear,
            g.rays.per_depth,
            g.rays.shadow,
            c.rays.per_depth,
            c.rays.shadow,
            g.render_ms,
            g.timing,
        );
        let what = format!("{name} t={time} S={spp} R={max_depth}");
        let exact = gpu.adapter().is_software;
        diff.assert_parity(&what, exact);
        assert_counts(&g.rays, &c.rays, exact, scene.lights.len(), &what);
        assert_eq!(g.samples, c.samples, "{what}: samples");
    }
}

const SETTINGS: [(f32, u32); 4] = [(1.0, 0), (1.0, 3), (4.0, 8), (2.5, 4)];

#[test]
fn corridor_facing_the_mirrors() {
    let scene = builtin("corridor").unwrap();
    check_parity(
        "corridor yaw 0",
        &scene,
        &scene.camera_at(0, 1),
        (96, 64),
        &SETTINGS,
    );
}

/// References draw the samples reserved for them (`SampleStream::Reference`) alike on both
/// backends, and not the frames' (the image changes with the stream).
#[test]
fn references_draw_the_same_reserved_samples() {
    let Some(mut gpu) = gpu() else {
        return;
    };
    let scene = builtin("corridor").unwrap();
    let camera = scene.camera_at_time(0.5);
    let mut cpu = CpuRenderer::new();
    gpu.load_scene(&scene).unwrap();
    cpu.load_scene(&scene).unwrap();
    let exact = gpu.adapter().is_software;
    for (spp, max_depth) in [(16.0, 8), (2.5, 4)] {
        let settings = RenderSettings {
            width: 96,
            height: 64,
            spp,
            max_depth,
        };
        let frames = {
            gpu.render(&camera, 0.0, &settings).unwrap();
            gpu.read_image().unwrap()
        };
        gpu.set_sample_stream(SampleStream::Reference);
        cpu.set_sample_stream(SampleStream::Reference);
        let g = gpu.render(&camera, 0.0, &settings).unwrap();
        let c = cpu.render(&camera, 0.0, &settings).unwrap();
        let what = format!("reference stream S={spp} R={max_depth}");
        let reference = gpu.read_image().unwrap();
        let diff = compare(&reference, &cpu.read_image().unwrap());
        eprintln!("{what}: max {} mean {:.4}", diff.max, diff.mean);
        diff.assert_parity(&what, exact);
        assert_counts(&g.rays, &c.rays, exact, scene.lights.len(), &what);
        assert!(
            compare(&frames, &reference).pixels_over_2 > 100,
            "{what}: the reference drew the frames' samples"
        );
        gpu.set_sample_stream(SampleStream::Frames);
        cpu.set_sample_stream(SampleStream::Frames);
    }
}

/// The corridor's glass sphere from above and close, filling most of the frame.
fn glass_view() -> Camera {
    Camera::look_at(
        Vec3::new(0.3, 1.2, -2.6),
        Vec3::new(0.6, 0.45, -4.0),
        Vec3::Y,
        40.0,
    )
}

#[test]
fn corridor_other_views() {
    let scene = builtin("corridor").unwrap();
    // Behind the camera (the three diffuse spheres), then down at the glass sphere.
    let behind = scene.camera_at(1, 2);
    let glass = glass_view();
    check_parity(
        "corridor yaw pi",
        &scene,
        &behind,
        (96, 64),
        &[(1.0, 2), (2.5, 5)],
    );
    check_parity(
        "corridor glass",
        &scene,
        &glass,
        (96, 64),
        &[(1.0, 6), (4.0, 16)],
    );
}

/// A frame whose pixels take more samples than one dispatch traces (16 a pixel on a software
/// adapter, 256 on hardware) continues each pixel's sum over several dispatches and keeps its
/// bits. Lavapipe ends an invocation's loops after 65,535 iterations, which a glass pixel at
/// R = 16 reached after about 124 samples in one dispatch: the rest came back black.
#[test]
fn many_samples_in_several_dispatches() {
    let scene = builtin("corridor").unwrap();
    let glass = glass_view();
    check_parity(
        "corridor glass, many samples",
        &scene,
        &glass,
        (48, 32),
        &[(40.5, 16), (300.0, 16)],
    );
}

#[test]
fn other_builtins() {
    for name in ["cornell", "spheres"] {
        let scene = builtin(name).unwrap();
        check_parity(
            name,
            &scene,
            &scene.camera_at(0, 8),
            (96, 64),
            &[(1.0, 4), (2.5, 6)],
        );
        check_parity(name, &scene, &scene.camera_at(3, 8), (96, 64), &[(1.0, 4)]);
    }
}

/// An icosahedron subdivided once (80 triangles) around `center`, outward-facing.
fn icosphere(center: Vec3, radius: f32) -> TriangleMesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut positions: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let faces: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut triangles = Vec::new();
    let midpoint = |a: u32, b: u32, positions: &mut Vec<Vec3>| {
        positions.push(((positions[a as usize] + positions[b as usize]) * 0.5).normalize());
        positions.len() as u32 - 1
    };
    for [a, b, c] in faces {
        let ab = midpoint(a, b, &mut positions);
        let bc = midpoint(b, c, &mut positions);
        let ca = midpoint(c, a, &mut positions);
        triangles.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    TriangleMesh {
        positions: positions.iter().map(|&p| center + p * radius).collect(),
        triangles,
    }
}

fn mesh_scene(extra: Vec<Object>) -> Scene {
    let mut objects = vec![
        Object {
            name: "ground".into(),
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            material: 0,
            motion: None,
        },
        Object {
            name: "glass ball".into(),
            shape: Shape::mesh(
                icosphere(Vec3::new(-0.6, 0.7, -4.0), 0.7),
                Transform::IDENTITY,
            ),
            material: 1,
            motion: None,
        },
        Object {
            name: "block".into(),
            shape: Shape::mesh(
                TriangleMesh::cuboid(Vec3::new(0.4, 0.0, -5.0), Vec3::new(1.4, 1.2, -4.2)),
                Transform::IDENTITY,
            ),
            material: 2,
            motion: None,
        },
        Object {
            name: "lamp".into(),
            shape: Shape::Sphere {
                center: Vec3::new(1.8, 2.2, -6.0),
                radius: 0.3,
            },
            material: 3,
            motion: None,
        },
        Object {
            name: "mirror".into(),
            shape: Shape::Quad {
                corner: Vec3::new(-3.0, 0.0, -7.0),
                edge_u: Vec3::new(5.0, 0.0, -1.0),
                edge_v: Vec3::new(0.0, 3.0, 0.0),
            },
            material: 4,
            motion: None,
        },
    ];
    objects.extend(extra);
    Scene {
        name: "meshes".into(),
        materials: vec![
            (
                "ground".into(),
                Material::Diffuse {
                    albedo: Vec3::splat(0.75),
                    checker: Some(Checker {
                        size: 0.5,
                        albedo_b: Vec3::splat(0.2),
                    }),
                },
            ),
            (
                "glass".into(),
                Material::Dielectric {
                    ior: 1.5,
                    tint: Vec3::new(0.9, 1.0, 0.95),
                },
            ),
            (
                "block".into(),
                Material::Diffuse {
                    albedo: Vec3::new(0.2, 0.5, 0.8),
                    checker: Some(Checker {
                        size: 0.25,
                        albedo_b: Vec3::new(0.8, 0.5, 0.2),
                    }),
                },
            ),
            (
                "lamp".into(),
                Material::Emissive {
                    radiance: Vec3::new(4.0, 3.5, 3.0),
                },
            ),
            (
                "mirror".into(),
                Material::Mirror {
                    reflectance: Vec3::new(0.9, 0.9, 0.85),
                },
            ),
        ],
        objects,
        lights: vec![
            PointLight {
                position: Vec3::new(-1.0, 3.0, -2.0),
                intensity: Vec3::splat(6.0),
            },
            PointLight {
                position: Vec3::new(2.0, 2.5, -3.0),
                intensity: Vec3::new(3.0, 2.5, 2.0),
            },
        ],
        ambient: 0.05,
        background: Vec3::new(0.05, 0.07, 0.12),
        camera: Camera::look_at(
            Vec3::new(0.0, 1.4, 0.0),
            Vec3::new(0.0, 0.6, -4.5),
            Vec3::Y,
            55.0,
        ),
        path: CameraPath::sweep(1),
    }
}

#[test]
fn triangle_meshes() {
    let scene = mesh_scene(Vec::new());
    check_parity("meshes", &scene, &scene.camera, (96, 64), &SETTINGS);
    let side = Camera::yaw_pitch(Vec3::new(1.5, 1.0, -1.5), PI / 8.0, -0.2, 60.0);
    check_parity("meshes side", &scene, &side, (96, 64), &[(1.0, 6)]);
}

/// A key of `[shapes.motion]` in tests.
fn key(t: f64, translate: [f32; 3], rotate_y_deg: f32, scale: f32) -> MotionKey {
    MotionKey {
        t,
        translate: Some(Vec3::from(translate)),
        rotate_y_deg: Some(rotate_y_deg),
        scale: Some(Vec3::splat(scale)),
    }
}

/// Moving spheres and quads, a mesh in several copies (turned, stretched, mirrored) that
/// moves and spins, a swarm that appears, and two quads in one plane (a tie at every hit,
/// which the lower key takes): the same pictures and counts on both backends at several
/// scene times.
#[test]
fn moving_world() {
    let moving = |name: &str, shape: Shape, material: usize, motion: Motion| Object {
        motion: Some(motion),
        ..Object::fixed(name, shape, material)
    };
    let glass = icosphere(Vec3::ZERO, 0.4);
    let swarm_copies: Vec<Transform> = (0..12)
        .map(|i| Transform {
            translate: Vec3::new((i % 4) as f32 * 0.5 - 0.75, 0.0, (i / 4) as f32 * -0.5),
            rotate_y_deg: i as f32 * 25.0,
            scale: Vec3::splat(0.3 + 0.02 * i as f32),
        })
        .collect();
    let scene = mesh_scene(vec![
        moving(
            "flying mirror ball",
            Shape::Sphere {
                center: Vec3::new(-1.0, 1.2, -3.5),
                radius: 0.3,
            },
            4,
            Motion {
                keys: vec![
                    key(0.0, [0.0, 0.0, 0.0], 0.0, 1.0),
                    key(1.0, [2.0, 0.3, -1.0], 0.0, 1.5),
                    key(2.0, [0.0, 0.0, 0.0], 0.0, 1.0),
                ],
                looped: true,
                ..Default::default()
            },
        ),
        moving(
            "turning pane",
            Shape::Quad {
                corner: Vec3::new(0.5, 0.2, -3.0),
                edge_u: Vec3::new(0.8, 0.0, 0.0),
                edge_v: Vec3::new(0.0, 0.9, 0.0),
            },
            1,
            Motion {
                spin_deg_per_s: 70.0,
                ..Default::default()
            },
        ),
        moving(
            "glass copies",
            Shape::Mesh {
                mesh: glass.clone(),
                placement: Transform {
                    translate: Vec3::new(0.0, 0.5, -3.6),
                    ..Transform::IDENTITY
                },
                instances: vec![
                    Transform::IDENTITY,
                    Transform {
                        translate: Vec3::new(-1.1, 0.2, -0.4),
                        rotate_y_deg: 40.0,
                        scale: Vec3::new(1.5, 0.7, 1.0),
                    },
                    Transform {
                        translate: Vec3::new(1.0, 0.1, 0.2),
                        rotate_y_deg: -15.0,
                        scale: Vec3::new(-1.0, 1.2, 1.0),
                    },
                ],
            },
            1,
            Motion {
                keys: vec![
                    key(0.0, [0.0, 0.0, 0.0], 0.0, 1.0),
                    key(1.5, [0.3, 0.2, 0.4], 30.0, 0.8),
                ],
                spin_deg_per_s: 20.0,
                ..Default::default()
            },
        ),
        moving(
            "swarm",
            Shape::Mesh {
                mesh: TriangleMesh::cuboid(Vec3::splat(-0.3), Vec3::splat(0.3)),
                placement: Transform {
                    translate: Vec3::new(0.2, 1.6, -4.6),
                    ..Transform::IDENTITY
                },
                instances: swarm_copies,
            },
            2,
            Motion {
                visible: Some(vec![[0.5, 5.0]]),
                ..Default::default()
            },
        ),
        Object::fixed(
            "tile a",
            Shape::Quad {
                corner: Vec3::new(-2.0, 0.001, -3.0),
                edge_u: Vec3::new(1.0, 0.0, 0.0),
                edge_v: Vec3::new(0.0, 0.0, 1.0),
            },
            3,
        ),
        Object::fixed(
            "tile b",
            Shape::Quad {
                corner: Vec3::new(-2.0, 0.001, -3.0),
                edge_u: Vec3::new(1.0, 0.0, 0.0),
                edge_v: Vec3::new(0.0, 0.0, 1.0),
            },
            2,
        ),
    ]);
    check_parity_at(
        "moving world",
        &scene,
        &scene.camera,
        &[0.0, 0.7, 1.3],
        (96, 64),
        &[(1.0, 4), (2.5, 6)],
    );
}

#[test]
fn teapot() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/teapot.obj"
    );
    let transform = Transform {
        translate: Vec3::new(0.3, 0.0, -4.5),
        scale: Vec3::splat(0.5),
        rotate_y_deg: 30.0,
    };
    let teapot = import_mesh(path.as_ref(), &transform).unwrap().mesh;
    let scene = mesh_scene(vec![Object {
        name: "teapot".into(),
        shape: Shape::mesh(teapot, Transform::IDENTITY),
        material: 4,
        motion: None,
    }]);
    check_parity("teapot", &scene, &scene.camera, (64, 48), &[(1.0, 2)]);
}

/// The Stanford bunny (69,451 triangles, through the BVH) standing in the Cornell box,
/// seen in the box's mirror and glass spheres too.
#[test]
fn bunny_in_the_cornell_box() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/stanford-bunny.obj"
    );
    let mut scene = builtin("cornell").unwrap();
    let white = scene
        .materials
        .iter()
        .position(|(name, _)| name == "white")
        .unwrap();
    let transform = Transform {
        translate: Vec3::new(0.1, -0.2, 0.2),
        scale: Vec3::splat(6.0),
        rotate_y_deg: 20.0,
    };
    let bunny = import_mesh(path.as_ref(), &transform).unwrap().mesh;
    scene.objects.push(Object {
        name: "bunny".into(),
        shape: Shape::mesh(bunny, Transform::IDENTITY),
        material: white,
        motion: None,
    });
    check_parity(
        "bunny in the Cornell box",
        &scene,
        &scene.camera,
        (64, 48),
        &[(1.0, 4), (2.5, 3)],
    );
}
