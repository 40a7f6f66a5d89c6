//! Mirrors: reflection geometry, the depth limit R, and exact per-depth ray counts.

mod common;

use common::*;
use glam::DVec3;
use steadyray_render::Renderer;
use steadyray_scene::{Material, Shape, Vec3};

const BACKGROUND: Vec3 = Vec3::new(0.05, 0.07, 0.12);

/// A mirror quad facing the camera at z = -2, filling the view, and an emissive sphere
/// behind the camera at (0, 0, 3).
fn mirror_and_sphere_behind() -> steadyray_scene::Scene {
    scene(
        vec![
            mirror(v([0.9, 0.8, 0.7])),
            Material::Emissive {
                radiance: v([0.2, 0.9, 0.3]),
            },
        ],
        vec![
            (
                Shape::Quad {
                    corner: v([-3.0, -3.0, -2.0]),
                    edge_u: v([6.0, 0.0, 0.0]),
                    edge_v: v([0.0, 6.0, 0.0]),
                },
                0,
            ),
            (sphere(v([0.0, 0.0, 3.0]), 0.5), 1),
        ],
        vec![],
        0.1,
        BACKGROUND,
    )
}

#[test]
fn a_mirror_shows_the_sphere_behind_the_camera_where_geometry_predicts() {
    let s = mirror_and_sphere_behind();
    let (w, h) = (32, 32);
    let mut r = loaded(&s);
    let stats = r.render(&s.camera, 0.0, &settings(w, h, 1.0, 1)).unwrap();
    let img = r.read_image().unwrap();
    let refl = v([0.9, 0.8, 0.7]);
    let frame = s.camera.frame(w, h);
    let centre = DVec3::new(0.0, 0.0, 3.0);
    let (mut sphere_px, mut background_px) = (0, 0);
    for py in 0..h {
        for px in 0..w {
            let d = frame.ray_dir(px, py, 0.5, 0.5, w, h).as_dvec3();
            let p = d * (-2.0 / d.z);
            let r_dir = DVec3::new(d.x, d.y, -d.z).normalize();
            // distance from the sphere's centre to the reflected ray's line
            let to_c = centre - p;
            let miss_distance = (to_c - r_dir * to_c.dot(r_dir)).length();
            let got = Vec3::from(img.get(px, py));
            if miss_distance < 0.49 {
                assert_close(got, refl * v([0.2, 0.9, 0.3]), 1e-6, "sphere pixel");
                sphere_px += 1;
            } else if miss_distance > 0.51 {
                assert_close(got, refl * BACKGROUND, 1e-6, "background pixel");
                background_px += 1;
            }
        }
    }
    assert!(
        sphere_px >= 8 && background_px > 900,
        "{sphere_px} {background_px}"
    );
    // Every eye ray hits the mirror and is reflected once.
    assert_eq!(stats.rays.per_depth, vec![1024, 1024]);
    assert_eq!(stats.rays.shadow, 0);
}

#[test]
fn at_r_zero_mirrors_are_shaded_locally() {
    let mut s = mirror_and_sphere_behind();
    s.lights.push(light(v([0.0, 0.0, -1.0]), 1.0));
    let mut r = loaded(&s);
    let stats = r.render(&s.camera, 0.0, &settings(1, 1, 1.0, 0)).unwrap();
    let img = r.read_image().unwrap();
    // local at (0, 0, -2): reflectance · (0.1 + 1 · 1 / 1²)
    assert_close(
        Vec3::from(img.get(0, 0)),
        v([0.9, 0.8, 0.7]) * 1.1,
        1e-6,
        "R = 0",
    );
    assert_eq!(stats.rays.per_depth, vec![1]);
    assert_eq!(stats.rays.shadow, 1);
    // The depth limit stopped the chain at the mirror: R = 1 would trace one more ray.
    assert_eq!(stats.rays.stopped, 1);
}

/// The camera between two infinite mirrors z = -1 and z = +1, looking at one of them.
fn facing_mirrors(refl: Vec3, with_light: bool) -> steadyray_scene::Scene {
    let lights = if with_light {
        vec![light(v([0.0, 0.3, 0.0]), 1.0)]
    } else {
        vec![]
    };
    scene(
        vec![mirror(refl)],
        vec![
            (plane(v([0.0, 0.0, -1.0]), Vec3::Z), 0),
            (plane(v([0.0, 0.0, 1.0]), Vec3::Z), 0),
        ],
        lights,
        0.2,
        BACKGROUND,
    )
}

#[test]
fn each_extra_depth_adds_exactly_one_reflection_between_facing_mirrors() {
    let refl = v([0.9, 0.5, 0.25]);
    let s = facing_mirrors(refl, false);
    let (w, h, spp) = (8, 6, 2.0);
    let mut r = loaded(&s);
    for depth in 0..=8 {
        let stats = r
            .render(&s.camera, 0.0, &settings(w, h, spp, depth))
            .unwrap();
        // Every ray bounces: each depth 0..=R traces exactly pixels · S rays.
        assert_eq!(
            stats.rays.per_depth,
            vec![96; depth as usize + 1],
            "R = {depth}"
        );
        assert_eq!(stats.rays.shadow, 0);
        assert_eq!(stats.rays.stopped, 96, "every chain ends at a mirror");
        assert_eq!(stats.samples, 96);
        // R reflections, then the mirror shaded locally (ambient only): refl^(R+1) · 0.2.
        let want = refl.powf(depth as f32 + 1.0) * 0.2;
        let img = r.read_image().unwrap();
        for p in &img.pixels {
            assert_close(Vec3::from(*p), want, 1e-6, "radiance");
        }
    }
}

#[test]
fn shadow_rays_are_traced_once_per_sample_at_the_last_depth_only() {
    let s = facing_mirrors(Vec3::splat(0.9), true);
    let mut r = loaded(&s);
    for depth in [0, 1, 5] {
        let stats = r
            .render(&s.camera, 0.0, &settings(8, 6, 2.0, depth))
            .unwrap();
        assert_eq!(stats.rays.per_depth, vec![96; depth as usize + 1]);
        // The light between the mirrors is always on the facing side.
        assert_eq!(stats.rays.shadow, 96);
    }
}

#[test]
fn a_single_reflection_follows_the_mirror_law() {
    let s = facing_mirrors(Vec3::ONE, false);
    let d = v([0.3, -0.2, -1.0]).normalize();
    let path = loaded(&s).trace_ray(Vec3::ZERO, d, (0, 0), 0, 3).unwrap();
    assert_eq!(path.rays.len(), 4);
    let hit = d * (1.0 / -d.z);
    assert_close(
        path.rays[1].origin,
        hit + Vec3::Z * 1e-4,
        1e-6,
        "offset hit point",
    );
    assert_close(
        path.rays[1].dir,
        v([d.x, d.y, -d.z]),
        1e-6,
        "reflected direction",
    );
    assert_close(path.rays[2].dir, d, 1e-6, "second reflection");
    assert_eq!(
        path.rays.iter().map(|r| r.depth).collect::<Vec<_>>(),
        vec![0, 1, 2, 3]
    );
}

/// The chains the depth limit stops are exactly the rays the next level traces: on the
/// corridor (two mirror walls, glass and diffuse spheres), at every R, with S = 2 (the same
/// samples and Fresnel branches at R and R + 1).
#[test]
fn the_stopped_chains_are_the_next_levels_rays() {
    let scene = steadyray_scene::builtin("corridor").unwrap();
    let mut r = loaded(&scene);
    let camera = scene.camera_at(0, 720);
    let counts: Vec<_> = (0..=8)
        .map(|depth| {
            r.render(&camera, 0.0, &settings(64, 36, 2.0, depth))
                .unwrap()
                .rays
        })
        .collect();
    assert!(counts[0].stopped > 0, "mirrors and glass are in view");
    for (depth, pair) in counts.windows(2).enumerate() {
        assert_eq!(pair[0].stopped, pair[1].per_depth[depth + 1], "R = {depth}");
    }
}
