//! The top level's per-frame update for 1,000 and 10,000 moving objects (issue 15's
//! targets: under 1 ms and under 5 ms on two cores): a full build, and a refit of the same
//! leaves after every box moved a little, in both layouts. `cargo bench -p steadyray-accel
//! --bench top_level`.

// criterion_group! defines a public function it does not document.
#![allow(missing_docs)]

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use steadyray_accel::{Bounds, TopLayout, TopLevel};

/// `n` boxes of about 0.2 m scattered over a 20 m cube, from a fixed seed, shifted by `t`
/// seconds of a slow drift (each box its own direction).
fn boxes(n: usize, t: f32) -> Vec<Bounds> {
    let mut state = 0x9e37_79b9u32;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1 << 24) as f32
    };
    (0..n)
        .map(|_| {
            let c = Vec3::new(next(), next(), next()) * 20.0 - 10.0;
            let v = Vec3::new(next(), next(), next()) - 0.5;
            let c = c + v * t;
            Bounds {
                min: c - 0.1,
                max: c + 0.1,
            }
        })
        .collect()
}

fn top_level(c: &mut Criterion) {
    let mut group = c.benchmark_group("top level");
    for n in [1_000, 10_000] {
        let still = boxes(n, 0.0);
        let moved = boxes(n, 0.1);
        for (name, layout) in [("cpu", TopLayout::Cpu), ("gpu", TopLayout::Gpu)] {
            group.bench_with_input(BenchmarkId::new(format!("build {name}"), n), &n, |b, _| {
                b.iter(|| TopLevel::build(black_box(&still), layout).unwrap())
            });
            let mut top = TopLevel::build(&still, layout).unwrap();
            group.bench_with_input(BenchmarkId::new(format!("refit {name}"), n), &n, |b, _| {
                let mut flip = false;
                b.iter(|| {
                    flip = !flip;
                    let frame = if flip { &moved } else { &still };
                    top.update(black_box(frame)).unwrap()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, top_level);
criterion_main!(benches);
