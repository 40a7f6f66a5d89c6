//! Refraction: Snell's law, the Fresnel branch, total internal reflection, end to end
//! through glass spheres.

mod common;

use common::*;
use glam::Vec3A;
use steadyray_render::sampling::branch_random;
use steadyray_render_cpu::optics::{fresnel, reflect, refract, snell};
use steadyray_render_cpu::{CpuRenderer, PathTrace};
use steadyray_scene::Vec3;

/// A direction at `deg` degrees from the normal +z, coming in (dot(d, n) < 0).
fn incoming(deg: f32) -> Vec3A {
    let a = deg.to_radians();
    Vec3A::new(a.sin(), 0.0, -a.cos())
}

#[test]
fn refract_obeys_snells_law_both_ways() {
    let n = Vec3A::Z;
    for deg in (0..90).step_by(5) {
        let d = incoming(deg as f32);
        let sin_i = (deg as f32).to_radians().sin();
        // air into glass
        let t = refract(d, n, 1.0 / 1.5).expect("no TIR entering glass");
        assert!((t.length() - 1.0).abs() < 1e-5);
        assert!((t.x - sin_i / 1.5).abs() < 1e-6, "{deg}°: sin_t = {}", t.x);
        assert!(t.y == 0.0 && t.z < 0.0);
        // glass into air, below the critical angle
        if sin_i * 1.5 < 0.999 {
            let t = refract(d, n, 1.5).expect("below the critical angle");
            assert!((t.x - sin_i * 1.5).abs() < 1e-5, "{deg}°: sin_t = {}", t.x);
            assert!((t.length() - 1.0).abs() < 1e-5);
        }
    }
}

#[test]
fn total_internal_reflection_starts_at_the_critical_angle() {
    let critical = (1.0f32 / 1.5).asin().to_degrees(); // 41.81°
    let n = Vec3A::Z;
    assert!(snell(incoming(critical - 0.3), n, 1.5).is_some());
    assert!(refract(incoming(critical - 0.3), n, 1.5).is_some());
    assert!(snell(incoming(critical + 0.3), n, 1.5).is_none());
    assert!(refract(incoming(89.0), n, 1.5).is_none());
    // never entering the denser medium
    assert!(snell(incoming(89.9), n, 1.0 / 1.5).is_some());
}

/// Unpolarised Fresnel reflectance from the indices, in f64.
fn fresnel_f64(deg: f64, n_i: f64, n_t: f64) -> f64 {
    let cos_i = deg.to_radians().cos();
    let sin_t = n_i / n_t * deg.to_radians().sin();
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    let rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
    (rs * rs + rp * rp) / 2.0
}

#[test]
fn fresnel_matches_the_textbook_formula() {
    for (eta, n_i, n_t) in [(1.0 / 1.5, 1.0, 1.5), (1.5, 1.5, 1.0)] {
        for deg in [0.0, 10.0, 30.0, 41.0, 60.0, 85.0] {
            let Some((cos_i, cos_t)) = snell(incoming(deg as f32), Vec3A::Z, eta) else {
                continue;
            };
            let f = fresnel(cos_i, cos_t, eta);
            let want = fresnel_f64(deg, n_i, n_t);
            assert!(
                (f as f64 - want).abs() < 1e-5,
                "eta {eta} {deg}°: {f} vs {want}"
            );
        }
    }
    let (ci, ct) = snell(incoming(0.0), Vec3A::Z, 1.0 / 1.5).unwrap();
    assert!((fresnel(ci, ct, 1.0 / 1.5) - 0.04).abs() < 1e-6);
}

/// A renderer with a clear glass sphere of radius 1 at (0, 0, -5) with `tint`.
fn glass_sphere(tint: Vec3) -> CpuRenderer {
    let s = scene(
        vec![steadyray_scene::Material::Dielectric { ior: 1.5, tint }],
        vec![(sphere(v([0.0, 0.0, -5.0]), 1.0), 0)],
        vec![],
        0.1,
        v([0.3, 0.5, 0.7]),
    );
    loaded(&s)
}

/// A (pixel, sample) whose branch numbers at depths 0..depths all exceed `above`, so every
/// dielectric event refracts (when F < above).
fn refracting_sample(depths: u32, above: f32) -> ((u32, u32), u32) {
    (0..1000u32)
        .map(|i| ((i % 7, i / 7), i % 3))
        .find(|&((px, py), s)| (0..depths).all(|k| branch_random(px, py, s, k) > above))
        .expect("some sample refracts everywhere")
}

fn unit(v: Vec3) -> Vec3 {
    v.normalize()
}

#[test]
fn a_ray_through_a_glass_spheres_centre_passes_straight() {
    let tint = v([0.5, 0.8, 1.0]);
    let r = glass_sphere(tint);
    let (pixel, sample) = refracting_sample(2, 0.05);
    let path = r
        .trace_ray(Vec3::ZERO, Vec3::NEG_Z, pixel, sample, 4)
        .unwrap();
    assert_eq!(path.rays.len(), 3, "eye, inside, out: {path:?}");
    for ray in &path.rays {
        assert_close(ray.dir, Vec3::NEG_Z, 1e-6, "direction");
    }
    // refracting starts the next ray EPS behind the surface
    assert_close(
        path.rays[1].origin,
        v([0.0, 0.0, -4.0 - 1e-4]),
        1e-6,
        "entry",
    );
    assert_close(
        path.rays[2].origin,
        v([0.0, 0.0, -6.0 - 1e-4]),
        1e-6,
        "exit",
    );
    // two refractions: tint², then the background
    assert_close(
        path.radiance,
        tint * tint * v([0.3, 0.5, 0.7]),
        1e-6,
        "radiance",
    );
}

#[test]
fn an_off_centre_ray_bends_as_snell_predicts() {
    let r = glass_sphere(Vec3::ONE);
    let (pixel, sample) = refracting_sample(2, 0.2);
    let h = 0.5f32;
    let path = r
        .trace_ray(v([0.0, h, 0.0]), Vec3::NEG_Z, pixel, sample, 4)
        .unwrap();
    assert_eq!(path.rays.len(), 3);
    let centre = v([0.0, 0.0, -5.0]);
    // at entry and exit, sin(angle to the normal) outside = 1.5 · sin inside = h
    let entry_n = unit(path.rays[1].origin - centre);
    let exit_n = unit(path.rays[2].origin - centre);
    let sin_to = |d: Vec3, n: Vec3| unit(d).cross(n).length();
    assert!((sin_to(Vec3::NEG_Z, entry_n) - h).abs() < 1e-4);
    assert!((sin_to(path.rays[1].dir, entry_n) - h / 1.5).abs() < 1e-5);
    // (at the exit within 1e-4: the inner ray starts EPS below the surface, which moves its
    // chord by EPS · sin θt)
    assert!((sin_to(path.rays[1].dir, exit_n) - h / 1.5).abs() < 1e-4);
    assert!((sin_to(path.rays[2].dir, exit_n) - h).abs() < 1e-4);
    // the total deviation 2(θi - θt), toward the axis
    let (ti, tt) = (h.asin(), (h / 1.5).asin());
    let dev = 2.0 * (ti - tt);
    assert_close(
        unit(path.rays[2].dir),
        v([0.0, -dev.sin(), -dev.cos()]),
        1e-4,
        "exit direction",
    );
}

#[test]
fn the_branch_follows_branch_random_against_fresnel() {
    let r = glass_sphere(Vec3::ONE);
    let h = 0.8f32; // 53° incidence: F ≈ 0.09
    let f = fresnel_f64((h as f64).asin().to_degrees(), 1.0, 1.5) as f32;
    let (mut reflected, mut refracted) = (0, 0);
    for sample in 0..400 {
        let (px, py) = (3, 9);
        let xi = branch_random(px, py, sample, 0);
        if (xi - f).abs() < 1e-3 {
            continue;
        }
        let path: PathTrace = r
            .trace_ray(v([0.0, h, 0.0]), Vec3::NEG_Z, (px, py), sample, 1)
            .unwrap();
        let d1 = path.rays[1].dir;
        if xi < f {
            let n = unit(path.rays[1].origin - v([0.0, 0.0, -5.0]));
            assert_close(
                d1,
                Vec3::from(reflect(Vec3A::NEG_Z, n.into())),
                1e-4,
                "reflect",
            );
            reflected += 1;
        } else {
            assert!(d1.z < -0.5 && d1.y < 0.0, "refracted inward: {d1}");
            refracted += 1;
        }
    }
    assert!(reflected > 10 && refracted > 300, "{reflected} {refracted}");
}

#[test]
fn inside_glass_past_the_critical_angle_every_sample_reflects() {
    let r = glass_sphere(Vec3::ONE);
    let centre = v([0.0, 0.0, -5.0]);
    for sample in 0..64 {
        // from inside, hitting the surface where sin θ = 0.9 > 1/1.5
        let path = r
            .trace_ray(v([0.0, 0.9, -5.0]), Vec3::NEG_Z, (1, 2), sample, 1)
            .unwrap();
        let p1 = path.rays[1].origin;
        assert!((p1 - centre).length() < 1.0, "stays inside");
        let n = unit(p1 - centre);
        let want = Vec3::from(reflect(Vec3A::NEG_Z, (-n).into()));
        assert_close(path.rays[1].dir, want, 1e-5, "TIR");
        assert!(path.rays[1].dir.y < -0.7, "reflected back inward");
    }
    // just below the critical angle (sin θ = 0.6): most samples leave the sphere
    let leaving = (0..64)
        .filter(|&sample| {
            let path = r
                .trace_ray(v([0.0, 0.6, -5.0]), Vec3::NEG_Z, (1, 2), sample, 1)
                .unwrap();
            (path.rays[1].origin - centre).length() > 1.0
        })
        .count();
    assert!(leaving > 48, "{leaving} of 64 refracted out");
}
