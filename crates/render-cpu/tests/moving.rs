//! Moving worlds on the CPU reference: objects are where their motion puts them at the
//! frame's time, objects that do not exist then are not drawn, and a mesh's instances (rays
//! moved into the shared mesh) look like the same copies placed vertex by vertex.

mod common;

use common::*;
use glam::{DAffine3, DVec3};
use steadyray_render::Renderer;
use steadyray_scene::{Motion, MotionKey, Object, Scene, Shape, Transform, TriangleMesh, Vec3};

/// A floor, a light, and `extra` objects, seen from (0, 1.5, 2) looking at (0, 0.5, -3).
fn stage(extra: Vec<Object>) -> Scene {
    let mut s = scene(
        vec![
            diffuse(Vec3::splat(0.7)),
            glass(1.5),
            diffuse(Vec3::new(0.8, 0.3, 0.2)),
        ],
        vec![(plane(Vec3::ZERO, Vec3::Y), 0)],
        vec![light(Vec3::new(1.0, 4.0, 0.0), 12.0)],
        0.1,
        Vec3::new(0.1, 0.15, 0.3),
    );
    s.camera = steadyray_scene::Camera::look_at(
        Vec3::new(0.0, 1.5, 2.0),
        Vec3::new(0.0, 0.5, -3.0),
        Vec3::Y,
        55.0,
    );
    s.objects.extend(extra);
    s
}

fn render_at(scene: &Scene, time_s: f64, spp: f32, depth: u32) -> steadyray_render::Image {
    let mut r = loaded(scene);
    r.render(&scene.camera, time_s, &settings(96, 64, spp, depth))
        .expect("renders");
    r.read_image().expect("image")
}

/// The largest difference between two images' tone-mapped 8-bit values, and the share of
/// channels that differ by more than 2 levels.
fn difference(a: &steadyray_render::Image, b: &steadyray_render::Image) -> (u8, f64) {
    let (a, b) = (a.to_srgb8_rgba(), b.to_srgb8_rgba());
    let diffs: Vec<u8> = a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).collect();
    let over = diffs.iter().filter(|&&d| d > 2).count();
    (
        diffs.iter().copied().max().unwrap_or(0),
        over as f64 / diffs.len() as f64,
    )
}

#[test]
fn instances_look_like_the_same_copies_placed_vertex_by_vertex() {
    let mesh = TriangleMesh::cuboid(Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 0.8, 0.5));
    let placement = Transform {
        translate: Vec3::new(0.0, 0.0, -3.0),
        scale: Vec3::new(1.2, 1.0, 0.8),
        rotate_y_deg: 20.0,
    };
    let copies = vec![
        Transform {
            translate: Vec3::new(-1.0, 0.0, 0.0),
            rotate_y_deg: 35.0,
            scale: Vec3::new(1.0, 1.5, 0.7),
        },
        Transform {
            translate: Vec3::new(0.9, 0.3, 0.4),
            rotate_y_deg: -50.0,
            // Mirrored: the normals must still face out, as the placed copy's do.
            scale: Vec3::new(-1.0, 1.0, 1.0),
        },
    ];
    let instanced = stage(vec![Object::fixed(
        "glass blocks",
        Shape::Mesh {
            mesh: mesh.clone(),
            placement,
            instances: copies.clone(),
        },
        1,
    )]);
    // The documented map: placement origin + copy ∘ placement's scale and rotation.
    let placed: Vec<Object> = copies
        .iter()
        .enumerate()
        .map(|(i, copy)| {
            let map = DAffine3::from_translation(DVec3::from(placement.translate))
                * copy.to_affine()
                * placement.linear();
            let positions = mesh
                .positions
                .iter()
                .map(|&p| map.transform_point3(p.into()).as_vec3())
                .collect();
            Object::fixed(
                format!("block {i}"),
                Shape::mesh(
                    TriangleMesh {
                        positions,
                        triangles: mesh.triangles.clone(),
                    },
                    Transform::IDENTITY,
                ),
                1,
            )
        })
        .collect();
    let baked = stage(placed);
    let (a, b) = (
        render_at(&instanced, 0.0, 4.0, 6),
        render_at(&baked, 0.0, 4.0, 6),
    );
    let (max, over) = difference(&a, &b);
    // Rounding differs (rays are moved into the mesh instead), so a few edge pixels may
    // differ; a wrong transform or a flipped normal would change whole faces.
    assert!(
        over < 0.01,
        "{:.2} % of channels differ by > 2 (max {max})",
        over * 100.0
    );
    // And the blocks are there at all: the image differs from the empty stage.
    let (_, empty) = difference(&a, &render_at(&stage(Vec::new()), 0.0, 4.0, 6));
    assert!(
        empty > 0.05,
        "the blocks cover {:.1} % of channels",
        empty * 100.0
    );
}

fn slide(from: [f32; 3], to: [f32; 3]) -> Motion {
    Motion {
        keys: vec![
            MotionKey {
                t: 0.0,
                translate: Some(Vec3::from(from)),
                rotate_y_deg: None,
                scale: None,
            },
            MotionKey {
                t: 1.0,
                translate: Some(Vec3::from(to)),
                rotate_y_deg: None,
                scale: None,
            },
        ],
        ..Default::default()
    }
}

#[test]
fn objects_are_where_their_motion_puts_them() {
    let ball = |motion: Option<Motion>, center: Vec3| Object {
        motion,
        ..Object::fixed("ball", sphere(center, 0.4), 2)
    };
    let moving = stage(vec![ball(
        Some(slide([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0])),
        Vec3::new(0.0, 0.6, -3.0),
    )]);
    for (t, x) in [(0.0, -1.0), (0.5, 0.0), (1.0, 1.0)] {
        let still = stage(vec![ball(None, Vec3::new(x, 0.6, -3.0))]);
        assert_eq!(
            render_at(&moving, t, 1.0, 2).pixels,
            render_at(&still, 0.0, 1.0, 2).pixels,
            "t = {t}: the moving ball renders as a still one at x = {x}"
        );
    }
}

#[test]
fn objects_that_do_not_exist_are_not_drawn() {
    let ghost = Object {
        motion: Some(Motion {
            visible: Some(vec![[1.0, 2.0]]),
            ..Default::default()
        }),
        ..Object::fixed("ghost", sphere(Vec3::new(0.0, 0.6, -3.0), 0.5), 2)
    };
    let scene = stage(vec![ghost]);
    let empty = render_at(&stage(Vec::new()), 0.0, 1.0, 3);
    assert_eq!(render_at(&scene, 0.5, 1.0, 3).pixels, empty.pixels);
    assert_eq!(render_at(&scene, 2.0, 1.0, 3).pixels, empty.pixels);
    assert_ne!(render_at(&scene, 1.5, 1.0, 3).pixels, empty.pixels);
}

#[test]
fn the_top_level_update_is_reported_inside_the_frame_time() {
    let scene = stage(vec![Object {
        motion: Some(slide([0.0; 3], [1.0, 0.0, 0.0])),
        ..Object::fixed("ball", sphere(Vec3::new(0.0, 0.6, -3.0), 0.4), 2)
    }]);
    let mut r = loaded(&scene);
    for t in [0.0, 0.25, 0.5] {
        let stats = r
            .render(&scene.camera, t, &settings(32, 24, 1.0, 2))
            .unwrap();
        assert!(stats.accel_ms >= 0.0 && stats.accel_ms <= stats.render_ms);
    }
    // A world where nothing moves is placed once, at load.
    let still = stage(Vec::new());
    let mut r = loaded(&still);
    let stats = r
        .render(&still.camera, 3.0, &settings(32, 24, 1.0, 2))
        .unwrap();
    assert_eq!(stats.accel_ms, 0.0);
}
