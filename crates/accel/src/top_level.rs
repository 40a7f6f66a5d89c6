//! The top level of the two-level BVH: a tree over a frame's objects (spheres, quads and
//! mesh instances, each a box), rebuilt or refitted every frame, whose leaves the renderer
//! tests itself (a sphere test, or a ray transformed into an instance's mesh and its
//! bottom-level [`crate::Bvh`]).
//!
//! It is built like the triangle BVH, by obvhs's PLOC builder and the same SAH collapse,
//! into the same layouts: the CPU's 8-wide nodes with AVX2 box tests, or the GPU's 4-wide
//! [`GpuNode`]s, whose leaves are ranges of [`TopLevel::leaf_order`]. The builder's
//! parameters favour build speed over tree quality (its trees live for one frame).
//!
//! Every box is padded a little (see [`pad`]) so that no leaf's box rejects a ray that its
//! primitive's own test, with its rounding, reports a hit for: the closest-hit query then
//! finds exactly what a loop over every leaf would, whatever the traversal order, which keeps
//! the CPU's and the GPU's answers the same.

#[cfg(target_arch = "x86_64")]
use crate::box_test::Avx;
use crate::box_test::{BoxRay, BoxTest, Portable};
use crate::build::{BvhError, GpuOut, Layout, lay_out};
use crate::gpu_node::{GPU_EMPTY, GPU_STACK_SIZE, GPU_WIDTH, GpuNode};
use crate::wide::{LEAF, STACK_SIZE, WIDTH, WideNode, finite_ray};
use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use std::mem::MaybeUninit;

/// Most objects per top-level leaf: one. Leaves of up to four traced the moving scene
/// `flyby` (a swarm out, 2 cores) at 6.7 M rays/s against 13.2 M with one: a leaf that
/// holds a floor or a wall along with small objects makes every ray that meets the floor's
/// box test those objects too (for a mesh copy, a whole bottom-level traversal). On the
/// corridor (12 objects) and `spheres` (82) one per leaf was as fast as four or faster.
const MAX_LEAF_SIZE: u32 = 1;
/// Most leaves a top level holds: CPU leaf entries keep the first position in 28 bits.
const MAX_LEAVES: usize = 1 << 28;
/// A refitted tree whose cost (total box area) grew past this multiple of its cost when
/// built is rebuilt instead.
const REFIT_LIMIT: f32 = 1.5;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The smallest corner.
    pub min: Vec3,
    /// The largest corner.
    pub max: Vec3,
}

impl Bounds {
    /// The box around `points`.
    pub fn around(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(
            Bounds {
                min: Vec3::INFINITY,
                max: Vec3::NEG_INFINITY,
            },
            |b, p| Bounds {
                min: b.min.min(p),
                max: b.max.max(p),
            },
        )
    }
}

/// `b` grown on every side by 2^-14 of its largest coordinate's magnitude plus 2^-12 of its
/// largest extent: far more than the rounding of the sphere and quad tests, of transforming
/// a ray into an instance's mesh, and of the triangle test there (all a few ulps of the
/// distances involved), and far less than the gaps between objects that matter for speed.
pub fn pad(b: Bounds) -> Bounds {
    let magnitude = b.min.abs().max(b.max.abs()).max_element();
    let extent = (b.max - b.min).max_element();
    let margin = Vec3::splat(magnitude * (1.0 / 16384.0) + extent * (1.0 / 4096.0));
    Bounds {
        min: b.min - margin,
        max: b.max + margin,
    }
}

/// Which layout a [`TopLevel`] is laid out in: the one its renderer traverses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TopLayout {
    /// 8-wide nodes for [`TopLevel::closest`] and [`TopLevel::any_hit`].
    Cpu,
    /// 4-wide [`GpuNode`]s for the WGSL traversal ([`TopLevel::gpu_nodes`]).
    Gpu,
}

/// How [`TopLevel::update`] brought the tree up to date.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Update {
    /// Same leaves: the boxes were refitted in place.
    Refit,
    /// A new tree: the leaves changed, or refitting had made the tree too slow.
    Rebuild,
}

/// The top-level tree over a frame's leaf boxes, in one layout.
#[derive(Clone, Debug)]
pub struct TopLevel {
    layout: TopLayout,
    wide: Vec<WideNode>,
    gpu: Vec<GpuNode>,
    /// Position k of the leaves' ranges holds leaf `order[k]`.
    order: Vec<u32>,
    /// The most children the GPU traversal can leave pending.
    gpu_pending: usize,
    /// Total box area (half areas of every child box) when built.
    built_cost: f32,
}

impl TopLevel {
    /// The tree over `boxes` (one per leaf, leaf i being `boxes[i]`; padded here). No boxes
    /// give an empty tree that nothing hits.
    pub fn build(boxes: &[Bounds], layout: TopLayout) -> Result<Self, BvhError> {
        if boxes.len() >= MAX_LEAVES {
            return Err(BvhError::TooManyTriangles(boxes.len()));
        }
        let mut top = TopLevel {
            layout,
            wide: Vec::new(),
            gpu: Vec::new(),
            order: Vec::new(),
            gpu_pending: 0,
            built_cost: 0.0,
        };
        if boxes.is_empty() {
            return Ok(top);
        }
        let aabbs: Vec<Aabb> = boxes
            .iter()
            .map(|&b| {
                let b = pad(b);
                Aabb::new(b.min.into(), b.max.into())
            })
            .collect();
        let params = BvhBuildParams {
            max_prims_per_leaf: MAX_LEAF_SIZE,
            ..BvhBuildParams::very_fast_build()
        };
        let bvh2: Bvh2 = obvhs::bvh2::builder::build_bvh2(&aabbs, params, &mut Default::default());
        top.order = bvh2.primitive_indices.clone();
        match layout {
            TopLayout::Cpu => {
                let mut out = WideTop { nodes: Vec::new() };
                let needed = lay_out(&bvh2, &mut out) + 1;
                if needed > STACK_SIZE {
                    return Err(BvhError::TooDeep {
                        layout: "CPU top-level",
                        needed,
                        capacity: STACK_SIZE,
                    });
                }
                top.wide = out.nodes;
            }
            TopLayout::Gpu => {
                let mut out = GpuOut { nodes: Vec::new() };
                top.gpu_pending = lay_out(&bvh2, &mut out);
                top.gpu = out.nodes;
            }
        }
        top.built_cost = top.cost();
        Ok(top)
    }

    /// Brings the tree up to date with this frame's `boxes`: refits it when there are as
    /// many leaves as before and the refitted tree is not much slower than a new one would
    /// be (its total box area at most 1.5 times what it was when built), else rebuilds it.
    pub fn update(&mut self, boxes: &[Bounds]) -> Result<Update, BvhError> {
        if boxes.len() == self.order.len() && !boxes.is_empty() {
            self.refit(boxes);
            if self.cost() <= REFIT_LIMIT * self.built_cost {
                return Ok(Update::Refit);
            }
        }
        *self = Self::build(boxes, self.layout)?;
        Ok(Update::Rebuild)
    }

    /// The number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.order.len()
    }

    /// The leaf order: position k of the leaves' ranges holds leaf `leaf_order()[k]`.
    pub fn leaf_order(&self) -> &[u32] {
        &self.order
    }

    /// The GPU layout's nodes (node 0 the root; empty for no leaves), whose leaf entries are
    /// ranges of [`TopLevel::leaf_order`]. Empty for a tree laid out for the CPU; fails like
    /// [`crate::Bvh::gpu_nodes`] when too deep for the GPU's stack.
    pub fn gpu_nodes(&self) -> Result<&[GpuNode], BvhError> {
        if self.gpu_pending > GPU_STACK_SIZE {
            return Err(BvhError::TooDeep {
                layout: "GPU top-level",
                needed: self.gpu_pending,
                capacity: GPU_STACK_SIZE,
            });
        }
        Ok(&self.gpu)
    }

    /// Recomputes every node's boxes from `boxes` (same leaves as when built), children
    /// before parents: nodes are laid out parent first.
    fn refit(&mut self, boxes: &[Bounds]) {
        let padded: Vec<Bounds> = boxes.iter().map(|&b| pad(b)).collect();
        let leaf_box = |first: usize, count: usize| {
            Bounds::around(
                self.order[first..first + count]
                    .iter()
                    .flat_map(|&i| [padded[i as usize].min, padded[i as usize].max]),
            )
        };
        for n in (0..self.wide.len()).rev() {
            for lane in 0..WIDTH {
                let child = self.wide[n].child[lane];
                let b = if child & LEAF != 0 {
                    let (first, count) = wide_leaf_range(child);
                    leaf_box(first, count)
                } else if child != 0 {
                    wide_node_box(&self.wide[child as usize])
                } else {
                    continue;
                };
                self.wide[n].set_box(lane, b.min.into(), b.max.into());
            }
        }
        for n in (0..self.gpu.len()).rev() {
            for lane in 0..GPU_WIDTH {
                let child = self.gpu[n].child[lane];
                let b = if child & crate::GPU_LEAF != 0 {
                    let first = (child & 0x07ff_ffff) as usize;
                    leaf_box(first, ((child >> 27) & 0xf) as usize)
                } else if child != GPU_EMPTY {
                    gpu_node_box(&self.gpu[child as usize])
                } else {
                    continue;
                };
                self.gpu[n].set(lane, b.min.into(), b.max.into(), child);
            }
        }
    }

    /// The total half area of every child box: the SAH cost of traversal, up to constants.
    fn cost(&self) -> f32 {
        let half_area = |min: Vec3, max: Vec3| {
            let d = (max - min).max(Vec3::ZERO);
            d.x * d.y + d.y * d.z + d.z * d.x
        };
        let wide = self.wide.iter().flat_map(|node| {
            (0..WIDTH)
                .filter(|&l| node.child[l] != 0)
                .map(move |l| half_area(lane_min(node, l), lane_max(node, l)))
        });
        let gpu = self.gpu.iter().flat_map(|node| {
            (0..GPU_WIDTH)
                .filter(|&l| node.child[l] != GPU_EMPTY)
                .map(move |l| {
                    half_area(
                        Vec3::new(node.min_x[l], node.min_y[l], node.min_z[l]),
                        Vec3::new(node.max_x[l], node.max_y[l], node.max_z[l]),
                    )
                })
        });
        wide.chain(gpu).sum()
    }

    /// The nearest leaf hit of the ray `origin + t·dir` below `t_max`, as decided by `leaf`:
    /// called with a leaf's index and the best t so far, it returns the new best t (the
    /// same when the leaf is missed or does not win). Boxes entered beyond the best t are
    /// skipped; boxes entered at exactly it are not, so that `leaf` can break ties. Returns
    /// the final best t.
    #[inline]
    pub fn closest<F: FnMut(u32, f32) -> f32>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        mut leaf: F,
    ) -> f32 {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this CPU has AVX2.
            return unsafe { self.closest_avx2(origin, dir, t_max, &mut leaf) };
        }
        self.closest_with::<Portable, F>(origin, dir, t_max, &mut leaf)
    }

    /// [`TopLevel::closest`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn closest_avx2<F: FnMut(u32, f32) -> f32>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        leaf: &mut F,
    ) -> f32 {
        self.closest_with::<Avx, F>(origin, dir, t_max, leaf)
    }

    #[inline(always)]
    fn closest_with<B: BoxTest, F: FnMut(u32, f32) -> f32>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        leaf: &mut F,
    ) -> f32 {
        let mut best = t_max;
        if self.wide.is_empty() || !finite_ray(origin, dir) {
            return best;
        }
        let br = BoxRay::new(origin, dir);
        // Uninitialised: zeroing it would cost as much as a short traversal.
        let mut stack = [MaybeUninit::<(u32, f32)>::uninit(); STACK_SIZE];
        let mut sp = 0usize;
        let mut cur = 0u32;
        loop {
            if cur & LEAF == 0 {
                let node = &self.wide[cur as usize];
                let (t_near, mask) = B::test(&br, node, best);
                if mask != 0 {
                    let mut order = [(0.0f32, 0u32); WIDTH];
                    let mut n = 0;
                    for (lane, (&d, &child)) in t_near.iter().zip(&node.child).enumerate() {
                        if mask & (1 << lane) != 0 {
                            order[n] = (d, child);
                            n += 1;
                        }
                    }
                    cur = push_all_but_nearest(&mut order[..n], &mut stack, &mut sp);
                    continue;
                }
            } else {
                let (first, count) = wide_leaf_range(cur);
                for &i in &self.order[first..first + count] {
                    best = leaf(i, best);
                }
            }
            // Pop the nearest pending child that can still hold a hit no farther than best.
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                // SAFETY: entries below `sp` were all written by the pushes above.
                let (c, d) = unsafe { stack[sp].assume_init() };
                if d <= best {
                    cur = c;
                    break;
                }
            }
        }
    }

    /// Whether `leaf` reports a hit for any leaf whose box the ray `origin + t·dir` meets
    /// on [0, t_max]; stops at the first.
    #[inline]
    pub fn any_hit<F: FnMut(u32) -> bool>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        mut leaf: F,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this CPU has AVX2.
            return unsafe { self.any_hit_avx2(origin, dir, t_max, &mut leaf) };
        }
        self.any_hit_with::<Portable, F>(origin, dir, t_max, &mut leaf)
    }

    /// [`TopLevel::any_hit`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn any_hit_avx2<F: FnMut(u32) -> bool>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        leaf: &mut F,
    ) -> bool {
        self.any_hit_with::<Avx, F>(origin, dir, t_max, leaf)
    }

    #[inline(always)]
    fn any_hit_with<B: BoxTest, F: FnMut(u32) -> bool>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        leaf: &mut F,
    ) -> bool {
        if self.wide.is_empty() || !finite_ray(origin, dir) {
            return false;
        }
        let br = BoxRay::new(origin, dir);
        let mut stack = [MaybeUninit::<u32>::uninit(); STACK_SIZE];
        let mut sp = 0usize;
        let mut cur = 0u32;
        loop {
            if cur & LEAF == 0 {
                let node = &self.wide[cur as usize];
                let (_, mut mask) = B::test(&br, node, t_max);
                while mask != 0 {
                    stack[sp].write(node.child[mask.trailing_zeros() as usize]);
                    sp += 1;
                    mask &= mask - 1;
                }
            } else {
                let (first, count) = wide_leaf_range(cur);
                if self.order[first..first + count].iter().any(|&i| leaf(i)) {
                    return true;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            // SAFETY: entries below `sp` were all written by the pushes above.
            cur = unsafe { stack[sp].assume_init() };
        }
    }
}

/// The children a ray entered, as (entry distance, child): pushes all but the nearest on
/// the stack of pending (child, distance) pairs, the farthest deepest, and returns the
/// nearest, to descend into. `hits` is not empty.
#[inline(always)]
fn push_all_but_nearest(
    hits: &mut [(f32, u32)],
    stack: &mut [MaybeUninit<(u32, f32)>; STACK_SIZE],
    sp: &mut usize,
) -> u32 {
    // Nearest last: insertion sort by descending entry distance.
    for i in 1..hits.len() {
        let mut j = i;
        while j > 0 && hits[j - 1].0 < hits[j].0 {
            hits.swap(j - 1, j);
            j -= 1;
        }
    }
    let last = hits.len() - 1;
    for &(d, c) in &hits[..last] {
        stack[*sp].write((c, d));
        *sp += 1;
    }
    hits[last].1
}

/// A CPU leaf entry: `LEAF | (count - 1) << 28 | first`.
fn wide_leaf(first: u32, count: u32) -> u32 {
    LEAF | (count - 1) << 28 | first
}

/// The (first, count) of a CPU leaf entry.
fn wide_leaf_range(entry: u32) -> (usize, usize) {
    (
        (entry & 0x0fff_ffff) as usize,
        ((entry >> 28) & 0x7) as usize + 1,
    )
}

fn lane_min(node: &WideNode, lane: usize) -> Vec3 {
    Vec3::new(
        node.bounds[0][lane],
        node.bounds[1][lane],
        node.bounds[2][lane],
    )
}

fn lane_max(node: &WideNode, lane: usize) -> Vec3 {
    Vec3::new(
        node.bounds[3][lane],
        node.bounds[4][lane],
        node.bounds[5][lane],
    )
}

/// The box around every used lane of a CPU node.
fn wide_node_box(node: &WideNode) -> Bounds {
    Bounds::around(
        (0..WIDTH)
            .filter(|&l| node.child[l] != 0)
            .flat_map(|l| [lane_min(node, l), lane_max(node, l)]),
    )
}

/// The box around every used lane of a GPU node.
fn gpu_node_box(node: &GpuNode) -> Bounds {
    Bounds::around(
        (0..GPU_WIDTH)
            .filter(|&l| node.child[l] != GPU_EMPTY)
            .flat_map(|l| {
                [
                    Vec3::new(node.min_x[l], node.min_y[l], node.min_z[l]),
                    Vec3::new(node.max_x[l], node.max_y[l], node.max_z[l]),
                ]
            }),
    )
}

/// The CPU's 8-wide top level being laid out.
struct WideTop {
    nodes: Vec<WideNode>,
}

impl Layout<WIDTH> for WideTop {
    type Node = WideNode;
    const EMPTY: WideNode = WideNode::EMPTY;

    fn nodes(&mut self) -> &mut Vec<WideNode> {
        &mut self.nodes
    }

    fn set_lane(node: &mut WideNode, lane: usize, min: [f32; 3], max: [f32; 3], child: u32) {
        node.set_box(lane, min, max);
        node.child[lane] = child;
    }

    fn leaf(&mut self, first: u32, count: u32) -> u32 {
        wide_leaf(first, count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random unit-ish boxes in a 40 m cube, from a fixed seed.
    fn boxes(n: usize, seed: u32) -> Vec<Bounds> {
        let mut state = seed;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        };
        (0..n)
            .map(|_| {
                let c = Vec3::new(next(), next(), next()) * 40.0 - 20.0;
                let h = Vec3::new(next(), next(), next()) * 0.8 + 0.1;
                Bounds {
                    min: c - h,
                    max: c + h,
                }
            })
            .collect()
    }

    /// Whether the ray meets box `b` on [0, t_max], by the slab test in f64, and where.
    fn slab(b: &Bounds, o: Vec3A, d: Vec3A, t_max: f32) -> Option<f64> {
        let (mut near, mut far) = (0.0f64, f64::from(t_max));
        for a in 0..3 {
            let (o, d) = (f64::from(o[a]), f64::from(d[a]));
            let (lo, hi) = (f64::from(b.min[a]), f64::from(b.max[a]));
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (t0, t1) = ((lo - o) / d, (hi - o) / d);
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        (near <= far).then_some(near)
    }

    fn rays(n: usize) -> Vec<(Vec3A, Vec3A)> {
        let mut state = 77u32;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32 * 2.0 - 1.0
        };
        (0..n)
            .map(|_| {
                let o = Vec3A::new(next(), next(), next()) * 30.0;
                let d = Vec3A::new(next(), next(), next()).normalize_or(Vec3A::X);
                (o, d)
            })
            .collect()
    }

    /// The closest and any-hit queries find what a loop over every leaf finds, when the
    /// leaves are the padded boxes themselves, after a build and after refits.
    #[test]
    fn queries_match_a_loop_over_every_leaf() {
        let mut leaves = boxes(3000, 5);
        let mut top = TopLevel::build(&leaves, TopLayout::Cpu).unwrap();
        for round in 0..3 {
            let padded: Vec<Bounds> = leaves.iter().map(|&b| pad(b)).collect();
            let mut hits = 0;
            for (o, d) in rays(2000) {
                let t_max = 35.0;
                // The nearest box entry, ties to the lowest index.
                let want = padded
                    .iter()
                    .enumerate()
                    .filter_map(|(i, b)| slab(b, o, d, t_max).map(|t| (t as f32, i as u32)))
                    .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let mut got: Option<(f32, u32)> = None;
                let best = top.closest(o, d, t_max, |i, best| {
                    match slab(&padded[i as usize], o, d, t_max).map(|t| t as f32) {
                        Some(t) if t < best || (t == best && got.is_some_and(|g| i < g.1)) => {
                            got = Some((t, i));
                            t
                        }
                        _ => best,
                    }
                });
                assert_eq!(got, want, "round {round}, ray {o} {d}");
                assert_eq!(best, want.map_or(t_max, |w| w.0));
                let any = top.any_hit(o, d, t_max, |i| {
                    slab(&padded[i as usize], o, d, t_max).is_some()
                });
                assert_eq!(any, want.is_some());
                hits += usize::from(want.is_some());
            }
            assert!(hits > 200, "too few hits ({hits}) to compare");
            // Move every box a little: refit.
            for b in &mut leaves {
                let shift = Vec3::new(0.3, -0.2, 0.1) * (round as f32 + 1.0);
                b.min += shift;
                b.max += shift;
            }
            assert_eq!(top.update(&leaves).unwrap(), Update::Refit);
        }
        // A different leaf count rebuilds.
        leaves.pop();
        assert_eq!(top.update(&leaves).unwrap(), Update::Rebuild);
        assert_eq!(top.leaf_count(), leaves.len());
    }

    #[test]
    fn refitting_far_apart_boxes_rebuilds() {
        let leaves = boxes(500, 9);
        let mut top = TopLevel::build(&leaves, TopLayout::Gpu).unwrap();
        assert!(!top.gpu_nodes().unwrap().is_empty());
        // Scatter the leaves over a space 50 times larger: the old tree's boxes balloon.
        let scattered: Vec<Bounds> = boxes(500, 1234)
            .iter()
            .map(|b| Bounds {
                min: b.min * 50.0,
                max: b.max * 50.0,
            })
            .collect();
        assert_eq!(top.update(&scattered).unwrap(), Update::Rebuild);
        // The GPU tree's root covers every (padded) leaf after a refit too.
        let mut moved = scattered.clone();
        for b in &mut moved {
            b.min.y += 1.0;
            b.max.y += 1.0;
        }
        assert_eq!(top.update(&moved).unwrap(), Update::Refit);
        let root = gpu_node_box(&top.gpu_nodes().unwrap()[0]);
        for b in &moved {
            let p = pad(*b);
            assert!(root.min.cmple(p.min).all() && root.max.cmpge(p.max).all());
        }
    }

    /// A ray that is not finite meets no leaf (its box tests would enter every box).
    #[test]
    fn rays_that_are_not_finite_meet_nothing() {
        let top = TopLevel::build(&boxes(3000, 5), TopLayout::Cpu).unwrap();
        let nan = Vec3A::new(f32::NAN, 0.0, f32::NAN);
        for (o, d) in [(Vec3A::ZERO, nan), (nan, Vec3A::X)] {
            assert_eq!(top.closest(o, d, 35.0, |_, _| 0.0), 35.0);
            assert!(!top.any_hit(o, d, 35.0, |_| true));
        }
    }

    #[test]
    fn empty_and_single_leaf_trees() {
        let empty = TopLevel::build(&[], TopLayout::Cpu).unwrap();
        assert_eq!(empty.closest(Vec3A::ZERO, Vec3A::X, 9.0, |_, b| b), 9.0);
        assert!(!empty.any_hit(Vec3A::ZERO, Vec3A::X, 9.0, |_| true));
        let one = [Bounds {
            min: Vec3::new(2.0, -1.0, -1.0),
            max: Vec3::new(3.0, 1.0, 1.0),
        }];
        let top = TopLevel::build(&one, TopLayout::Cpu).unwrap();
        assert_eq!(top.closest(Vec3A::ZERO, Vec3A::X, 9.0, |_, _| 2.5), 2.5);
        assert!(!top.any_hit(Vec3A::ZERO, Vec3A::NEG_X, 9.0, |_| true));
    }
}
