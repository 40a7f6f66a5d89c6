//! Whole frames: determinism, fractional S, buffer reuse, errors, meshes against quads.

mod common;

use common::*;
use steadyray_render::sampling::samples_for_pixel;
use steadyray_render::{Picture, Presented, RenderError, RenderSettings, Renderer, SettingsError};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{Shape, Transform, TriangleMesh, Vec3};

#[test]
fn the_same_frame_twice_is_bit_identical_on_any_thread_count() {
    let s = corridor();
    let set = settings(48, 27, 2.5, 6);
    let mut two = CpuRenderer::with_threads(2);
    two.load_scene(&s).unwrap();
    let a = two.render(&s.camera, 0.0, &set).unwrap();
    let img_a = two.read_image().unwrap();
    let b = two.render(&s.camera, 0.0, &set).unwrap();
    let img_b = two.read_image().unwrap();
    let mut one = CpuRenderer::with_threads(1);
    one.load_scene(&s).unwrap();
    let c = one.render(&s.camera, 0.0, &set).unwrap();
    let img_c = one.read_image().unwrap();
    let bits = |img: &steadyray_render::Image| -> Vec<u32> {
        img.pixels.iter().flatten().map(|c| c.to_bits()).collect()
    };
    assert_eq!(bits(&img_a), bits(&img_b));
    assert_eq!(bits(&img_a), bits(&img_c));
    assert_eq!(a.rays, b.rays);
    assert_eq!(a.rays, c.rays);
    assert_eq!(a.samples, c.samples);
}

#[test]
fn corridor_counts_are_consistent() {
    let s = corridor();
    let mut r = loaded(&s);
    let stats = r.render(&s.camera, 0.0, &settings(64, 36, 1.0, 8)).unwrap();
    let d = &stats.rays.per_depth;
    assert_eq!(d.len(), 9);
    assert_eq!(d[0], 64 * 36);
    assert_eq!(stats.samples, d[0]);
    assert!(
        d.windows(2).all(|w| w[1] <= w[0]),
        "a chain never grows: {d:?}"
    );
    assert!(d[3] > 0, "rays bounce between the mirror walls");
    assert!(stats.rays.shadow > 0);
    assert_eq!(stats.width, 64);
    assert!(stats.render_ms >= 0.0 && stats.render_ms == stats.wall_ms);
    assert!(stats.rays_per_second() >= 0.0);
    // some pixel shows something other than the background
    let img = r.read_image().unwrap();
    assert!(img.pixels.iter().any(|p| p[0] > 0.2));
}

#[test]
fn fractional_spp_takes_the_dithered_sample_counts() {
    let s = corridor();
    let mut r = loaded(&s);
    for spp in [1.0f32, 1.5, 2.25, 3.9] {
        let (w, h) = (20, 13);
        let stats = r.render(&s.camera, 0.0, &settings(w, h, spp, 2)).unwrap();
        let want: u64 = (0..h)
            .flat_map(|y| (0..w).map(move |x| samples_for_pixel(x, y, spp) as u64))
            .sum();
        assert_eq!(stats.samples, want, "S = {spp}");
        assert_eq!(stats.rays.per_depth[0], want);
    }
    // 16×16 = four whole Bayer blocks: exactly S per pixel on average
    let stats = r.render(&s.camera, 0.0, &settings(16, 16, 1.5, 2)).unwrap();
    assert_eq!(stats.samples, 384);
}

#[test]
fn the_image_follows_the_frame_size() {
    let s = corridor();
    let mut r = loaded(&s);
    assert!(matches!(r.read_image(), Err(RenderError::NoFrame)));
    r.render(&s.camera, 0.0, &settings(8, 8, 1.0, 1)).unwrap();
    let big = r.read_image().unwrap();
    r.render(&s.camera, 0.0, &settings(5, 3, 1.0, 1)).unwrap();
    let small = r.read_image().unwrap();
    assert_eq!((small.width, small.height, small.pixels.len()), (5, 3, 15));
    r.render(&s.camera, 0.0, &settings(8, 8, 1.0, 1)).unwrap();
    assert_eq!(r.read_image().unwrap(), big);
}

#[test]
fn presenting_hands_over_the_tone_mapped_frame() {
    let s = corridor();
    let mut r = loaded(&s);
    assert!(matches!(r.present(), Err(RenderError::NoFrame)));
    r.render(&s.camera, 0.0, &settings(9, 7, 1.0, 2)).unwrap();
    let image = r.read_image().unwrap();
    let want = Picture {
        width: 9,
        height: 7,
        rgba: image.to_srgb8_rgba(),
    };
    assert_eq!(r.present().unwrap(), Presented::Host(want.clone()));
    assert_eq!(r.read_picture().unwrap(), want);
}

#[test]
fn bad_settings_are_errors_not_panics() {
    let s = corridor();
    let mut r = loaded(&s);
    let cases = [
        settings(0, 10, 1.0, 1),
        settings(10, 0, 1.0, 1),
        settings(10, 10, f32::NAN, 1),
        settings(10, 10, 0.5, 1),
        settings(10, 10, f32::INFINITY, 1),
        settings(10, 10, 1.0, 65),
        settings(20_000, 10, 1.0, 1),
    ];
    for set in cases {
        assert!(
            matches!(
                r.render(&s.camera, 0.0, &set),
                Err(RenderError::Settings(_))
            ),
            "{set:?}"
        );
    }
    assert!(matches!(
        r.render(&s.camera, 0.0, &settings(0, 1, 1.0, 1)),
        Err(RenderError::Settings(SettingsError::EmptyImage { .. }))
    ));
    for t in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = r.render(&s.camera, t, &settings(4, 4, 1.0, 1)).unwrap_err();
        assert!(matches!(e, RenderError::BadTime(_)), "{e}");
        assert!(e.to_string().contains("not a finite number"), "{e}");
    }
    assert!(matches!(
        r.trace_ray(Vec3::ZERO, Vec3::NEG_Z, (0, 0), 0, 65),
        Err(RenderError::Settings(SettingsError::BadDepth(65)))
    ));
}

#[test]
fn rendering_before_loading_a_scene_is_no_scene() {
    let mut r = CpuRenderer::with_threads(1);
    let set = RenderSettings {
        width: 4,
        height: 4,
        spp: 1.0,
        max_depth: 1,
    };
    assert!(matches!(
        r.render(&looking_down_neg_z(), 0.0, &set),
        Err(RenderError::NoScene)
    ));
    assert!(matches!(
        r.trace_ray(Vec3::ZERO, Vec3::NEG_Z, (0, 0), 0, 1),
        Err(RenderError::NoScene)
    ));
    // settings are checked first
    let bad = RenderSettings { width: 0, ..set };
    assert!(matches!(
        r.render(&looking_down_neg_z(), 0.0, &bad),
        Err(RenderError::Settings(_))
    ));
}

#[test]
fn broken_scenes_are_refused() {
    let bad_material = scene(
        vec![diffuse(Vec3::ONE)],
        vec![(sphere(v([0.0, 0.0, -3.0]), 1.0), 1)],
        vec![],
        0.1,
        Vec3::ZERO,
    );
    let flat_quad = scene(
        vec![diffuse(Vec3::ONE)],
        vec![(
            Shape::Quad {
                corner: Vec3::ZERO,
                edge_u: Vec3::X,
                edge_v: Vec3::X,
            },
            0,
        )],
        vec![],
        0.1,
        Vec3::ZERO,
    );
    let bad_vertex = scene(
        vec![diffuse(Vec3::ONE)],
        vec![(
            Shape::mesh(
                TriangleMesh {
                    positions: vec![Vec3::ZERO, Vec3::X],
                    triangles: vec![[0, 1, 2]],
                },
                Transform::IDENTITY,
            ),
            0,
        )],
        vec![],
        0.1,
        Vec3::ZERO,
    );
    let zero_radius = scene(
        vec![diffuse(Vec3::ONE)],
        vec![(sphere(Vec3::ZERO, 0.0), 0)],
        vec![],
        0.1,
        Vec3::ZERO,
    );
    for s in [bad_material, flat_quad, bad_vertex, zero_radius] {
        let mut r = CpuRenderer::with_threads(1);
        assert!(matches!(r.load_scene(&s), Err(RenderError::Scene(_))));
    }
}

#[test]
fn a_mesh_renders_like_the_quad_it_triangulates() {
    let (corner, eu, ev) = (
        v([-1.0, -0.8, -3.0]),
        v([2.0, 0.0, -0.5]),
        v([0.0, 1.6, 0.0]),
    );
    let quad = Shape::Quad {
        corner,
        edge_u: eu,
        edge_v: ev,
    };
    let mesh = Shape::mesh(
        TriangleMesh {
            positions: vec![corner, corner + eu, corner + eu + ev, corner + ev],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        },
        Transform::IDENTITY,
    );
    let build = |shape: Shape| {
        scene(
            vec![diffuse(v([0.9, 0.6, 0.3]))],
            vec![(shape, 0)],
            vec![light(v([0.5, 0.5, -1.0]), 2.0)],
            0.05,
            v([0.1, 0.2, 0.3]),
        )
    };
    let set = settings(40, 30, 2.0, 2);
    let a = render(&build(quad), set);
    let b = render(&build(mesh), set);
    let mut max_diff = 0.0f32;
    let mut covered = 0;
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for c in 0..3 {
            max_diff = max_diff.max((p[c] - q[c]).abs());
        }
        covered += usize::from(p[0] != 0.1);
    }
    assert!(max_diff < 1e-4, "max difference {max_diff}");
    assert!(covered > 150, "{covered} pixels show the quad");
}

#[test]
fn info_names_the_cpu_and_threads() {
    let r = CpuRenderer::with_threads(2);
    let info = r.info();
    assert_eq!(info.backend, "cpu");
    assert!(info.device.ends_with("(2 threads)"), "{}", info.device);
    assert_eq!(r.threads(), 2);
    assert!(CpuRenderer::new().threads() >= 1);
}
