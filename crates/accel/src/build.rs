//! Building: obvhs's PLOC builder (with reinsertion and leaf collapse) over the triangles'
//! boxes, then the two layouts, both collapsed from that binary tree by SAH over the same
//! leaves: the 8-wide tree for the CPU and the 4-wide [`GpuNode`] tree for the GPU.

use crate::gpu_node::{GPU_WIDTH, GpuNode};
use crate::tri4::Tri4;
use crate::watertight::TriangleVerts;
use crate::wide::{LEAF, STACK_SIZE, WIDTH, Wide, WideNode};
use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;

/// Most triangles per leaf: one [`Tri4`] block.
const MAX_LEAF_SIZE: u32 = 4;
/// Most triangles a BVH holds: leaf-order positions and node indices stay below 2^27.
const MAX_TRIANGLES: usize = 1 << 27;

/// Why a BVH could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BvhError {
    /// More triangles than a BVH index holds.
    #[error("{0} triangles are more than the BVH holds (2^27)")]
    TooManyTriangles(usize),
    #[error(
        "the BVH is too deep: its {layout} traversal could need {needed} stack entries, more than it has ({capacity})"
    )]
    /// A tree deeper than a traversal's stack.
    TooDeep {
        /// The traversal (its layout).
        layout: &'static str,
        /// The stack entries the tree could need.
        needed: usize,
        /// The stack entries the traversal has.
        capacity: usize,
    },
}

/// The PLOC tree of obvhs over `tris`' boxes (input indices in its primitive order).
fn build_bvh2(tris: &[TriangleVerts]) -> Bvh2 {
    let boxes: Vec<Aabb> = tris
        .iter()
        .map(|t| {
            let mut b = Aabb::from_point(Vec3A::from_array(t[0]));
            b.extend(Vec3A::from_array(t[1]));
            b.extend(Vec3A::from_array(t[2]));
            b
        })
        .collect();
    // The slow preset (spatial pre-splits, wider PLOC search, more reinsertion) traced
    // the bunny views of `steadyray raybench` fastest for about twice the medium build time.
    let params = BvhBuildParams {
        max_prims_per_leaf: MAX_LEAF_SIZE,
        reinsertion_batch_ratio: reinsertion_ratio(tris.len()),
        ..BvhBuildParams::slow_build()
    };
    obvhs::bvh2::builder::build_bvh2(&boxes, params, &mut Default::default())
}

/// The share of nodes obvhs tries to reinsert elsewhere in the tree (its passes may revisit
/// a node). Reinserting every node once (1.0, against the slow preset's 0.2) cut the
/// bunny's bounce rays from 7.34 to 7.07 wide-node tests and from 1.80 to 1.70 leaf tests
/// per ray, and traced 4 % more rays per second, for 2.5 times the build time. Above
/// 2^18 triangles the ratio falls with the size, down to the preset's 0.2, so that a
/// million triangles still build in under two seconds on two cores.
fn reinsertion_ratio(triangles: usize) -> f32 {
    ((1 << 18) as f32 / triangles.max(1) as f32).clamp(0.2, 1.0)
}

/// A wide layout being written: its nodes, and how a lane and a leaf child are written.
/// `W` is its width.
pub(crate) trait Layout<const W: usize> {
    type Node: Copy;
    /// A node with every lane unused.
    const EMPTY: Self::Node;
    fn nodes(&mut self) -> &mut Vec<Self::Node>;
    /// Sets lane `lane` of `node` to `child` with the box [`min`, `max`].
    fn set_lane(node: &mut Self::Node, lane: usize, min: [f32; 3], max: [f32; 3], child: u32);
    /// The child entry of the leaf of the `count` triangles from leaf-order position `first`.
    fn leaf(&mut self, first: u32, count: u32) -> u32;
}

/// The CPU's 8-wide tree being laid out: its nodes and leaf blocks, and the triangles and
/// input indices in leaf order that the blocks are cut from.
struct WideOut<'a> {
    nodes: Vec<WideNode>,
    leaves: Vec<Tri4>,
    leaf_tris: &'a [TriangleVerts],
    ids: &'a [u32],
}

impl Layout<WIDTH> for WideOut<'_> {
    type Node = WideNode;
    const EMPTY: WideNode = WideNode::EMPTY;

    fn nodes(&mut self) -> &mut Vec<WideNode> {
        &mut self.nodes
    }

    fn set_lane(node: &mut WideNode, lane: usize, min: [f32; 3], max: [f32; 3], child: u32) {
        node.set_box(lane, min, max);
        node.child[lane] = child;
    }

    /// Appends the block of the leaf's triangles; the entry is its index.
    fn leaf(&mut self, first: u32, count: u32) -> u32 {
        let range = first as usize..(first + count) as usize;
        self.leaves
            .push(Tri4::new(&self.leaf_tris[range.clone()], &self.ids[range]));
        LEAF | (self.leaves.len() - 1) as u32
    }
}

/// A GPU 4-wide tree being laid out; its leaves are ranges in leaf order (triangles of a
/// mesh's tree, objects of the top level).
pub(crate) struct GpuOut {
    pub nodes: Vec<GpuNode>,
}

impl Layout<GPU_WIDTH> for GpuOut {
    type Node = GpuNode;
    const EMPTY: GpuNode = GpuNode::EMPTY;

    fn nodes(&mut self) -> &mut Vec<GpuNode> {
        &mut self.nodes
    }

    fn set_lane(node: &mut GpuNode, lane: usize, min: [f32; 3], max: [f32; 3], child: u32) {
        node.set(lane, min, max, child);
    }

    fn leaf(&mut self, first: u32, count: u32) -> u32 {
        GpuNode::leaf(first, count)
    }
}

/// How the binary tree becomes the wide one, chosen by dynamic programming as in Ylitie,
/// Karras and Laine, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide
/// BVHs" (HPG 2017): for each binary node and each k in 1..=WIDTH, the least SAH cost of
/// covering its subtree with at most k wide-tree children. The leaves are obvhs's, each
/// counted once however they are grouped, so the cost is the total surface area of the wide
/// nodes. Against opening the largest child first, this filled the bunny's wide nodes to
/// 5.9 children from 4.4 and cut their number by 31 %. `W` is the wide tree's width.
struct Collapse<const W: usize> {
    cost: Vec<[f32; W]>,
    /// 0: the node itself is one child (a leaf, or an inner wide node); j > 0: its left
    /// child is covered by at most j children and its right by at most k - j.
    split: Vec<[u8; W]>,
    /// For an inner node that is a wide node: how many of its W lanes cover the left child.
    lanes_left: Vec<u8>,
}

impl<const W: usize> Collapse<W> {
    fn new(bvh2: &Bvh2) -> Self {
        let mut collapse = Collapse {
            cost: vec![[0.0; W]; bvh2.nodes.len()],
            split: vec![[0; W]; bvh2.nodes.len()],
            lanes_left: vec![0; bvh2.nodes.len()],
        };
        collapse.fill(bvh2, 0);
        collapse
    }

    /// Fills the tables of node `n` and its subtree.
    fn fill(&mut self, bvh2: &Bvh2, n: usize) {
        let node = &bvh2.nodes[n];
        if node.prim_count > 0 {
            return;
        }
        let (l, r) = (node.first_index as usize, node.first_index as usize + 1);
        self.fill(bvh2, l);
        self.fill(bvh2, r);
        // Per k: the least cost of covering both halves with k children, and how many of
        // them cover the left half.
        let mut spread = [(f32::INFINITY, 0u8); W];
        for (k, best) in spread.iter_mut().enumerate().skip(1) {
            for j in 1..=k {
                let c = self.cost[l][j - 1] + self.cost[r][k - j];
                if c < best.0 {
                    *best = (c, j as u8);
                }
            }
        }
        self.cost[n][0] = node.aabb.half_area() + spread[W - 1].0;
        self.lanes_left[n] = spread[W - 1].1;
        for (k, &(c, j)) in spread.iter().enumerate().skip(1) {
            let fewer = self.cost[n][k - 1];
            (self.cost[n][k], self.split[n][k]) = if c < fewer {
                (c, j)
            } else {
                (fewer, self.split[n][k - 1])
            };
        }
    }

    /// The wide-tree children covering node `n` with at most `k` of them, appended to `out`.
    fn children(&self, bvh2: &Bvh2, n: usize, k: usize, out: &mut Vec<usize>) {
        let j = self.split[n][k - 1] as usize;
        if j == 0 {
            out.push(n);
        } else {
            let l = bvh2.nodes[n].first_index as usize;
            self.children(bvh2, l, j, out);
            self.children(bvh2, l + 1, k - j, out);
        }
    }

    /// The (at most W) children of the wide node covering binary inner node `i`.
    fn wide_children(&self, bvh2: &Bvh2, i: usize) -> Vec<usize> {
        let first = bvh2.nodes[i].first_index as usize;
        let j = self.lanes_left[i] as usize;
        let mut kids = Vec::with_capacity(W);
        self.children(bvh2, first, j, &mut kids);
        self.children(bvh2, first + 1, W - j, &mut kids);
        kids
    }
}

/// Appends the wide node covering binary inner node `i` with the children `collapse` chose,
/// its subtree after it; returns its index. `pending` is the most children a traversal can
/// leave on its stack below the root: per node on a path down, all its children but the one
/// entered.
fn emit<const W: usize, L: Layout<W>>(
    bvh2: &Bvh2,
    collapse: &Collapse<W>,
    i: usize,
    out: &mut L,
    pending: &mut usize,
) -> u32 {
    let slot = out.nodes().len();
    out.nodes().push(L::EMPTY);
    let mut node = L::EMPTY;
    let kids = collapse.wide_children(bvh2, i);
    let mut below = 0;
    for (lane, &k) in kids.iter().enumerate() {
        let n = &bvh2.nodes[k];
        let child = if n.prim_count > 0 {
            out.leaf(n.first_index, n.prim_count)
        } else {
            let mut p = 0;
            let c = emit(bvh2, collapse, k, out, &mut p);
            below = below.max(p);
            c
        };
        L::set_lane(&mut node, lane, n.aabb.min.into(), n.aabb.max.into(), child);
    }
    *pending = kids.len() - 1 + below;
    out.nodes()[slot] = node;
    slot as u32
}

/// Lays out the tree `bvh2` as layout `out`; returns the most children its traversal can
/// leave pending. A root that is a leaf becomes one node with that leaf in its first lane.
pub(crate) fn lay_out<const W: usize, L: Layout<W>>(bvh2: &Bvh2, out: &mut L) -> usize {
    let root = &bvh2.nodes[0];
    if root.prim_count == 0 {
        let mut pending = 0;
        emit(bvh2, &Collapse::new(bvh2), 0, out, &mut pending);
        return pending;
    }
    let mut node = L::EMPTY;
    let leaf = out.leaf(root.first_index, root.prim_count);
    L::set_lane(
        &mut node,
        0,
        root.aabb.min.into(),
        root.aabb.max.into(),
        leaf,
    );
    out.nodes().push(node);
    0
}

/// The two layouts of a tree.
pub(crate) struct Layouts {
    pub gpu: Vec<GpuNode>,
    /// The most children the GPU traversal can leave on its stack (see [`emit`]).
    pub gpu_pending: usize,
    pub wide: Wide,
}

/// Both layouts of the tree over `tris` (input order), or empty ones for no triangles.
/// Fails when the CPU traversal's stack could overflow; the GPU's limit is checked where the
/// GPU layout is asked for ([`crate::Bvh::gpu_nodes`]), so that a tree too deep for the GPU
/// still serves the CPU.
pub(crate) fn build(tris: &[TriangleVerts]) -> Result<Layouts, BvhError> {
    if tris.len() >= MAX_TRIANGLES {
        return Err(BvhError::TooManyTriangles(tris.len()));
    }
    if tris.is_empty() {
        return Ok(Layouts {
            gpu: Vec::new(),
            gpu_pending: 0,
            wide: Wide::default(),
        });
    }
    let bvh2 = build_bvh2(tris);
    let ids = bvh2.primitive_indices.clone();
    let leaf_tris: Vec<TriangleVerts> = ids.iter().map(|&i| tris[i as usize]).collect();
    let mut out = WideOut {
        nodes: Vec::new(),
        leaves: Vec::new(),
        leaf_tris: &leaf_tris,
        ids: &ids,
    };
    // The CPU's traversal pushes every child it will visit and pops the one it enters.
    let needed = lay_out(&bvh2, &mut out) + 1;
    if needed > STACK_SIZE {
        return Err(BvhError::TooDeep {
            layout: "CPU",
            needed,
            capacity: STACK_SIZE,
        });
    }
    let mut gpu = GpuOut { nodes: Vec::new() };
    let gpu_pending = lay_out(&bvh2, &mut gpu);
    let (nodes, leaves) = (out.nodes, out.leaves);
    Ok(Layouts {
        gpu: gpu.nodes,
        gpu_pending,
        wide: Wide { nodes, leaves, ids },
    })
}

/// `tris` as plain arrays for the watertight test.
pub(crate) fn to_verts(tris: &[[Vec3; 3]]) -> Vec<TriangleVerts> {
    tris.iter().map(|t| t.map(|v| v.to_array())).collect()
}
