//! BVH throughput on the Stanford bunny (`assets/meshes/`), the view of issue 6: build
//! time, and closest-hit and any-hit rays per second for one primary ray per pixel of a
//! 480x270 image and one cosine-weighted bounce ray from each primary hit, on one thread.
//! `cargo bench -p steadyray-accel`; criterion reports rays/s as elements/s. Without the
//! mesh the benchmark says so and measures nothing.

// criterion_group! defines a public function it does not document.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec3, Vec3A};
use std::hint::black_box;
use std::path::PathBuf;
use steadyray_accel::{Bvh, T_MIN};
use steadyray_render::sampling::{cosine_direction, pcg_hash, unit_from_hash};
use steadyray_scene::Camera;
use steadyray_scene::Transform;
use steadyray_scene::mesh_import::import_mesh;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 270;

fn bunny_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/stanford-bunny.obj")
}

/// A ray as (origin, direction).
type Ray = (Vec3A, Vec3A);

/// The primary rays of the camera, and the bounce rays from their hits.
fn rays(bvh: &Bvh, tris: &[[Vec3; 3]]) -> (Vec<Ray>, Vec<Ray>) {
    let camera = Camera::look_at(
        Vec3::new(0.0869666, 0.110154, 0.1782621),
        Vec3::new(-0.0168405, 0.110154, -0.001537),
        Vec3::Y,
        45.0,
    );
    let frame = camera.frame(WIDTH, HEIGHT);
    let eye = Vec3A::from(frame.eye);
    let primary: Vec<Ray> = (0..HEIGHT)
        .flat_map(|py| (0..WIDTH).map(move |px| (px, py)))
        .map(|(px, py)| (eye, frame.ray_dir(px, py, 0.5, 0.5, WIDTH, HEIGHT).into()))
        .collect();
    let bounce = primary
        .iter()
        .enumerate()
        .filter_map(|(i, &(origin, dir))| {
            let (t, tri) = bvh.closest(origin, dir, f32::INFINITY)?;
            let [a, b, c] = tris[tri as usize].map(Vec3A::from);
            let n = (b - a).cross(c - a).normalize();
            let n = if n.dot(dir) > 0.0 { -n } else { n };
            let hash = pcg_hash(i as u32);
            let (u1, u2) = (unit_from_hash(hash), unit_from_hash(pcg_hash(hash)));
            Some((origin + t * dir + n * T_MIN, cosine_direction(n, u1, u2)))
        })
        .collect();
    (primary, bounce)
}

fn traversal(c: &mut Criterion) {
    let path = bunny_path();
    let mesh = match import_mesh(&path, &Transform::default()) {
        Ok(imported) => imported.mesh,
        Err(why) => {
            eprintln!("BVH benchmarks skipped: cannot load the bunny: {why}");
            return;
        }
    };
    let tris: Vec<[Vec3; 3]> = (0..mesh.triangles.len())
        .map(|i| mesh.triangle(i))
        .collect();
    let mut group = c.benchmark_group("bunny");
    group.sample_size(10);
    group.bench_function("build", |b| {
        b.iter(|| Bvh::build(black_box(&tris)).unwrap())
    });
    let bvh = Bvh::build(&tris).unwrap();
    let (primary, bounce) = rays(&bvh, &tris);
    for (name, set) in [("primary", &primary), ("bounce", &bounce)] {
        group.throughput(Throughput::Elements(set.len() as u64));
        group.bench_function(format!("closest/{name}"), |b| {
            b.iter(|| {
                set.iter()
                    .filter(|&&(o, d)| bvh.closest(o, d, f32::INFINITY).is_some())
                    .count()
            })
        });
        group.bench_function(format!("any_hit/{name}"), |b| {
            b.iter(|| {
                set.iter()
                    .filter(|&&(o, d)| bvh.any_hit(o, d, f32::INFINITY))
                    .count()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, traversal);
criterion_main!(benches);
