//! The BVH finds exactly what a brute-force loop over all triangles finds: same t, same
//! triangle (the lowest index among ties), for closest and any hit, on random meshes and
//! rays, including rays starting on a surface, axis-parallel rays and degenerate triangles.

use glam::{Vec3, Vec3A};
use proptest::prelude::*;
use steadyray_accel::{Bvh, GPU_EMPTY, GPU_LEAF, GpuNode, T_MIN, WatertightRay};

fn brute_closest(tris: &[[Vec3; 3]], o: Vec3A, d: Vec3A, t_max: f32) -> Option<(f32, u32)> {
    let wr = WatertightRay::new(o, d);
    let mut best = None;
    let mut t_max = t_max;
    for (i, t) in tris.iter().enumerate() {
        if let Some(t) = wr.intersect(&t.map(|v| v.to_array()), t_max) {
            t_max = t;
            best = Some((t, i as u32));
        }
    }
    best
}

fn brute_any(tris: &[[Vec3; 3]], o: Vec3A, d: Vec3A, t_max: f32) -> bool {
    let wr = WatertightRay::new(o, d);
    tris.iter()
        .any(|t| wr.intersect(&t.map(|v| v.to_array()), t_max).is_some())
}

/// Coordinates on a coarse grid part of the time, so that vertices, box faces and ray
/// origins coincide exactly (shared edges, axis-aligned faces, rays in a box's face).
fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![(-8i32..=8).prop_map(|i| i as f32 * 0.25), -2.0f32..2.0,]
}

fn point() -> impl Strategy<Value = Vec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A triangle: random, degenerate (repeated or collinear corners), or a neighbour of the
/// previous ones sharing an edge is approximated by the grid.
fn triangle() -> impl Strategy<Value = [Vec3; 3]> {
    prop_oneof![
        6 => [point(), point(), point()],
        1 => (point(), point()).prop_map(|(a, b)| [a, b, a]),
        1 => (point(), point()).prop_map(|(a, b)| [a, b, a + 2.0 * (b - a)]),
    ]
}

/// A direction: random, or along an axis (either sign), or in a coordinate plane.
fn direction() -> impl Strategy<Value = Vec3A> {
    let axis = (0usize..3, any::<bool>()).prop_map(|(a, neg)| {
        let mut d = [0.0f32; 3];
        d[a] = if neg { -1.0 } else { 1.0 };
        Vec3A::from_array(d)
    });
    let planar = (0usize..3, -1.0f32..1.0, -1.0f32..1.0).prop_map(|(a, p, q)| {
        let mut d = [p, q, p - q];
        d[a] = 0.0;
        Vec3A::from_array(d)
    });
    let any_dir =
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_map(|(x, y, z)| Vec3A::new(x, y, z));
    prop_oneof![2 => any_dir, 1 => axis, 1 => planar]
        .prop_filter("non-zero direction", |d| d.length_squared() > 1e-6)
}

/// A ray origin: a random point, or a point on one of the triangles (barycentric).
fn origin(n: usize) -> impl Strategy<Value = (Option<usize>, Vec3, f32, f32)> {
    (prop::option::of(0..n), point(), 0.0f32..1.0, 0.0f32..1.0)
}

fn mesh() -> impl Strategy<Value = Vec<[Vec3; 3]>> {
    prop::collection::vec(triangle(), 1..120)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn bvh_equals_brute_force(
        (tris, rays) in mesh().prop_flat_map(|tris| {
            let n = tris.len();
            (Just(tris), prop::collection::vec((origin(n), direction(), prop_oneof![Just(f32::INFINITY), 0.1f32..5.0]), 1..40))
        })
    ) {
        let bvh = Bvh::build(&tris).unwrap();
        prop_assert_eq!(bvh.triangle_count(), tris.len());
        for ((on, p, a, b), d, t_max) in rays {
            let o = match on {
                Some(i) => {
                    let [v0, v1, v2] = tris[i];
                    let (a, b) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
                    v0 + a * (v1 - v0) + b * (v2 - v0)
                }
                None => p,
            };
            let o = Vec3A::from(o);
            let expected = brute_closest(&tris, o, d, t_max);
            prop_assert_eq!(bvh.closest(o, d, t_max), expected, "closest, origin {} dir {}", o, d);
            prop_assert_eq!(bvh.any_hit(o, d, t_max), brute_any(&tris, o, d, t_max), "any hit");
            if let Some((t, _)) = expected {
                prop_assert!(t > T_MIN && t < t_max);
            }
        }
    }

    /// The GPU's tree (traversed only in WGSL) holds every triangle in exactly one leaf,
    /// inside the box of every lane above it, so a traversal with conservative box tests
    /// finds every hit; the GPU tests check its hits against the CPU's.
    #[test]
    fn gpu_tree_holds_every_triangle_once_inside_its_boxes(tris in mesh()) {
        let bvh = Bvh::build(&tris).unwrap();
        let nodes = bvh.gpu_nodes().unwrap();
        let mut seen = vec![0u32; tris.len()];
        let mut reached = vec![0u32; nodes.len()];
        reached[0] = 1;
        // (node, box of the lane that leads to it)
        let mut todo = vec![(0usize, [Vec3::NEG_INFINITY, Vec3::INFINITY])];
        while let Some((i, outer)) = todo.pop() {
            let node: &GpuNode = &nodes[i];
            prop_assert_ne!(node.child[0], GPU_EMPTY, "node {} has no first child", i);
            for lane in 0..4 {
                let child = node.child[lane];
                if child == GPU_EMPTY {
                    continue;
                }
                let lo = Vec3::new(node.min_x[lane], node.min_y[lane], node.min_z[lane]);
                let hi = Vec3::new(node.max_x[lane], node.max_y[lane], node.max_z[lane]);
                prop_assert!(lo.cmpge(outer[0]).all() && hi.cmple(outer[1]).all());
                if child & GPU_LEAF == 0 {
                    reached[child as usize] += 1;
                    todo.push((child as usize, [lo, hi]));
                    continue;
                }
                let (first, count) = (child & 0x07ff_ffff, (child >> 27) & 0xf);
                prop_assert!((1..=4).contains(&count));
                for k in first..first + count {
                    let id = bvh.leaf_order()[k as usize] as usize;
                    seen[k as usize] += 1;
                    for v in tris[id] {
                        prop_assert!(v.cmpge(lo).all() && v.cmple(hi).all());
                    }
                }
            }
        }
        prop_assert!(seen.iter().all(|&n| n == 1), "leaf-order positions in leaves: {:?}", seen);
        prop_assert!(reached.iter().all(|&n| n == 1), "nodes reached: {:?}", reached);
    }
}

#[test]
fn empty_and_single_triangle() {
    let bvh = Bvh::build(&[]).unwrap();
    assert_eq!(bvh.closest(Vec3A::ZERO, Vec3A::Z, f32::INFINITY), None);
    assert!(!bvh.any_hit(Vec3A::ZERO, Vec3A::Z, f32::INFINITY));
    assert!(bvh.gpu_nodes().unwrap().is_empty());
    let tri = [
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(1.0, -1.0, 2.0),
        Vec3::new(0.0, 1.0, 2.0),
    ];
    let bvh = Bvh::build(&[tri]).unwrap();
    assert_eq!(
        bvh.closest(Vec3A::ZERO, Vec3A::Z, f32::INFINITY),
        Some((2.0, 0))
    );
    assert!(bvh.any_hit(Vec3A::ZERO, Vec3A::Z, 3.0));
    assert!(!bvh.any_hit(Vec3A::ZERO, Vec3A::Z, 2.0));
    assert_eq!(bvh.gpu_nodes().unwrap().len(), 1);
}

/// A grid of quads split into triangle pairs: every ray through the grid's interior hits,
/// including rays through shared edges and vertices (watertightness through the BVH).
#[test]
fn grid_has_no_cracks() {
    let n = 40;
    let mut tris = Vec::new();
    let p = |i: usize, j: usize| {
        let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
        Vec3::new(
            x * 2.0 - 1.0,
            y * 2.0 - 1.0,
            0.3 * (x * 7.0).sin() * (y * 5.0).cos(),
        )
    };
    for i in 0..n {
        for j in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    let bvh = Bvh::build(&tris).unwrap();
    let o = Vec3A::new(0.01, -0.02, 3.0);
    for i in 0..=200 {
        for j in 0..=200 {
            // aim at vertices and edges of the grid
            let v = p(i * n / 200, j * n / 200).lerp(
                p((i * n / 200 + 1).min(n), j * n / 200),
                (i % 5) as f32 / 5.0,
            );
            let target = Vec3A::new(v.x * 0.95, v.y * 0.95, v.z);
            let d = target - o;
            assert!(
                bvh.closest(o, d, f32::INFINITY).is_some(),
                "crack at {i},{j}"
            );
            assert_eq!(
                bvh.closest(o, d, f32::INFINITY),
                brute_closest(&tris, o, d, f32::INFINITY)
            );
        }
    }
}

/// Triangles spaced ever wider along x make a chain of a tree: too deep for the GPU's
/// 64-entry traversal stack (76 children could wait on it) but not for the CPU's. The CPU
/// keeps tracing it; asking for the GPU layout is a clear error.
#[test]
fn a_tree_too_deep_for_the_gpu_still_serves_the_cpu() {
    let tris: Vec<[Vec3; 3]> = (0..300)
        .map(|i| {
            let x = 1.3f32.powi(i);
            [
                Vec3::new(x, -1.0, -1.0),
                Vec3::new(x, 2.0, -1.0),
                Vec3::new(x, -1.0, 2.0),
            ]
        })
        .collect();
    let bvh = Bvh::build(&tris).unwrap();
    let err = bvh.gpu_nodes().unwrap_err();
    assert!(
        matches!(
            err,
            steadyray_accel::BvhError::TooDeep { layout: "GPU", .. }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("GPU traversal"), "{err}");
    for (o, d) in [
        (Vec3A::new(0.0, 0.0, 0.0), Vec3A::X),
        (Vec3A::new(1e20, 0.1, 0.2), Vec3A::X),
        (Vec3A::new(1e30, 0.3, 0.1), -Vec3A::X),
    ] {
        let expected = brute_closest(&tris, o, d, f32::INFINITY);
        assert!(expected.is_some());
        assert_eq!(bvh.closest(o, d, f32::INFINITY), expected);
    }
}
