//! Local shading: point lights, ambient, shadow rays and checkers, against the formula of
//! `docs/shading.md` computed independently in f64.

mod common;

use common::*;
use steadyray_render::Renderer;
use steadyray_scene::{Checker, Material, Shape, Vec3};

/// albedo · (ambient + I · max(0, n·l) / dist²) in f64, for one unshadowed light.
fn predicted(
    albedo: Vec3,
    ambient: f64,
    p: [f64; 3],
    n: [f64; 3],
    light: [f64; 3],
    i: f64,
) -> [f64; 3] {
    let to = [light[0] - p[0], light[1] - p[1], light[2] - p[2]];
    let dist2 = to[0] * to[0] + to[1] * to[1] + to[2] * to[2];
    let dist = dist2.sqrt();
    let cos = (n[0] * to[0] + n[1] * to[1] + n[2] * to[2]) / dist;
    let irr = ambient + i * cos.max(0.0) / dist2;
    [
        albedo.x as f64 * irr,
        albedo.y as f64 * irr,
        albedo.z as f64 * irr,
    ]
}

#[test]
fn diffuse_plane_under_a_point_light_matches_the_formula_at_the_centre() {
    let albedo = v([0.8, 0.6, 0.4]);
    let light_pos = [1.0, 0.5, -1.0];
    for ambient in [0.0, 0.1] {
        let s = scene(
            vec![diffuse(albedo)],
            vec![(plane(v([0.0, 0.0, -2.0]), Vec3::Z), 0)],
            vec![light(Vec3::from(light_pos.map(|c| c as f32)), 3.0)],
            ambient as f32,
            Vec3::ZERO,
        );
        // A 1×1 image: the single centred sample looks straight down -z and hits (0, 0, -2).
        let img = render(&s, settings(1, 1, 1.0, 4));
        let want = predicted(
            albedo,
            ambient,
            [0.0, 0.0, -2.0],
            [0.0, 0.0, 1.0],
            light_pos,
            3.0,
        );
        // dist = 1.5, cos = 2/3: irradiance 3 · (2/3) / 2.25 = 8/9.
        assert!((want[0] - 0.8 * (ambient + 8.0 / 9.0)).abs() < 1e-6);
        let got = img.get(0, 0);
        for c in 0..3 {
            assert!(
                (got[c] as f64 - want[c]).abs() < 1e-3,
                "ambient {ambient}: {got:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn diffuse_plane_matches_the_formula_at_every_pixel_and_counts_shadow_rays() {
    let albedo = v([0.7, 0.5, 0.9]);
    let lit = [0.4, -0.3, -0.5];
    let s = scene(
        vec![diffuse(albedo)],
        vec![(plane(v([0.0, 0.0, -2.0]), Vec3::Z), 0)],
        vec![
            light(Vec3::from(lit.map(|c| c as f32)), 2.0),
            // behind the plane: n·l < 0, so no shadow ray and no light
            light(v([0.0, 0.0, -3.0]), 50.0),
        ],
        0.05,
        Vec3::ZERO,
    );
    let (w, h) = (9, 7);
    let mut r = loaded(&s);
    let stats = r.render(&s.camera, 0.0, &settings(w, h, 1.0, 3)).unwrap();
    let img = r.read_image().unwrap();
    assert_eq!(stats.rays.per_depth, vec![63, 0, 0, 0]);
    assert_eq!(
        stats.rays.shadow, 63,
        "one shadow ray per hit, only toward the lit side"
    );
    let frame = s.camera.frame(w, h);
    for py in 0..h {
        for px in 0..w {
            let d = frame.ray_dir(px, py, 0.5, 0.5, w, h).as_dvec3();
            let t = -2.0 / d.z;
            let p = (d * t).to_array();
            let want = predicted(albedo, 0.05, p, [0.0, 0.0, 1.0], lit, 2.0);
            let got = img.get(px, py);
            for c in 0..3 {
                assert!(
                    (got[c] as f64 - want[c]).abs() < 1e-3,
                    "({px},{py}) {got:?} vs {want:?}"
                );
            }
        }
    }
}

#[test]
fn occluders_between_point_and_light_cast_shadows_and_others_do_not() {
    let albedo = v([0.5, 0.5, 0.5]);
    let light_pos = v([1.0, 0.0, -1.0]);
    let trace = |occluder: Vec3| {
        let s = scene(
            vec![diffuse(albedo)],
            vec![
                (plane(v([0.0, 0.0, -2.0]), Vec3::Z), 0),
                (sphere(occluder, 0.1), 0),
            ],
            vec![light(light_pos, 1.0)],
            0.2,
            Vec3::ZERO,
        );
        loaded(&s)
            .trace_ray(Vec3::ZERO, Vec3::NEG_Z, (0, 0), 0, 2)
            .unwrap()
    };
    // Midway between the hit point (0, 0, -2) and the light: in shadow, ambient only.
    let shadowed = trace(v([0.5, 0.0, -1.5]));
    assert_eq!(shadowed.shadow_rays, 1);
    assert_close(shadowed.radiance, albedo * 0.2, 1e-6, "shadowed");
    // On the same line but past the light: lit.
    let lit = trace(v([1.5, 0.0, -0.5]));
    assert_eq!(lit.shadow_rays, 1);
    let cos = 1.0 / 2f32.sqrt();
    assert_close(lit.radiance, albedo * (0.2 + cos / 2.0), 1e-5, "lit");
}

fn checker(albedo: Vec3, albedo_b: Vec3, size: f32) -> Material {
    Material::Diffuse {
        albedo,
        checker: Some(Checker { size, albedo_b }),
    }
}

/// Shoots straight down at (x, z) and returns the radiance (ambient 1, no lights: the albedo).
fn albedo_seen(shape: Shape, x: f32, z: f32) -> Vec3 {
    let s = scene(
        vec![checker(Vec3::ONE, Vec3::splat(0.25), 0.5)],
        vec![(shape, 0)],
        vec![],
        1.0,
        Vec3::ZERO,
    );
    loaded(&s)
        .trace_ray(v([x, 5.0, z]), Vec3::NEG_Y, (0, 0), 0, 0)
        .unwrap()
        .radiance
}

fn odd(coords: &[f32]) -> bool {
    coords
        .iter()
        .map(|c| (c / 0.5).floor() as i64)
        .sum::<i64>()
        .rem_euclid(2)
        == 1
}

#[test]
fn checkers_use_the_contract_surface_coordinates() {
    let points: Vec<(f32, f32)> = (0..40)
        .map(|i| (-1.9 + 0.0937 * i as f32, -11.8 + 0.237 * i as f32))
        .collect();
    let floor_quad = Shape::Quad {
        corner: v([-2.0, 0.0, -12.0]),
        edge_u: v([4.0, 0.0, 0.0]),
        edge_v: v([0.0, 0.0, 10.0]),
    };
    let floor_plane = plane(v([0.3, 0.0, 0.2]), Vec3::Y);
    let (mut odd_seen, mut even_seen) = (0, 0);
    for &(x, z) in &points {
        // quad: metres along the edges from the corner
        let want = if odd(&[x + 2.0, z + 12.0]) { 0.25 } else { 1.0 };
        assert_close(
            albedo_seen(floor_quad.clone(), x, z),
            Vec3::splat(want),
            1e-6,
            "quad",
        );
        // plane with normal +y: a = -z, b = -x, relative to its point
        let want = if odd(&[-(z - 0.2), -(x - 0.3)]) {
            0.25
        } else {
            1.0
        };
        assert_close(
            albedo_seen(floor_plane.clone(), x, z),
            Vec3::splat(want),
            1e-6,
            "plane",
        );
        if want == 1.0 {
            even_seen += 1
        } else {
            odd_seen += 1
        }
    }
    assert!(odd_seen > 5 && even_seen > 5);
    // sphere: the 3D checker at the hit point
    let ball = sphere(v([0.0, 0.0, 0.0]), 1.0);
    for i in 0..20 {
        let (x, z) = (-0.6 + 0.061 * i as f32, 0.55 - 0.057 * i as f32);
        let y = (1.0 - x * x - z * z).sqrt();
        let want = if odd(&[x, y, z]) { 0.25 } else { 1.0 };
        assert_close(
            albedo_seen(ball.clone(), x, z),
            Vec3::splat(want),
            1e-6,
            "sphere",
        );
    }
}

#[test]
fn emissive_surfaces_show_their_radiance_without_shadow_rays() {
    let s = scene(
        vec![Material::Emissive {
            radiance: v([2.0, 1.0, 0.5]),
        }],
        vec![(sphere(v([0.0, 0.0, -3.0]), 1.0), 0)],
        vec![light(v([0.0, 0.0, 0.0]), 1.0)],
        0.1,
        Vec3::ZERO,
    );
    let path = loaded(&s)
        .trace_ray(Vec3::ZERO, Vec3::NEG_Z, (0, 0), 0, 3)
        .unwrap();
    assert_eq!(path.radiance, v([2.0, 1.0, 0.5]));
    assert_eq!(path.shadow_rays, 0);
    assert_eq!(path.rays.len(), 1);
}
