//! The triangle BVH of steadyray.
//!
//! [`Bvh::build`] runs obvhs's PLOC builder (parallel locally-ordered clustering, with
//! reinsertion and SAH leaf collapse) over a mesh's triangles and lays the tree out twice
//! over one leaf order of the triangles:
//!
//! - a 4-wide tree of 128-byte [`GpuNode`]s, one cache line each, which the GPU backend
//!   uploads and traverses in WGSL (`crates/render-gpu/src/shaders/traversal.wgsl`);
//! - an 8-wide tree with structure-of-arrays child boxes and leaves of four triangles in
//!   structure-of-arrays lanes, which [`Bvh::closest`] and [`Bvh::any_hit`] traverse on the
//!   CPU (with AVX2, or AVX-512, where the CPU has it).
//!
//! [`TopLevel`] is the top level of the renderers' two-level BVH: a tree over a frame's
//! objects (spheres, quads, mesh instances), rebuilt or refitted every frame, in either
//! layout; each mesh's [`Bvh`] is its bottom level.
//!
//! Triangles are intersected with the watertight test of Woop, Benthin and Wald
//! ([`WatertightRay`]); box tests are widened by a few ulps so that the BVH finds exactly
//! the hits a brute-force loop over all triangles finds, ties included (the lowest input
//! index wins among hits at the same t).

mod box_test;
mod build;
mod child_order;
mod gpu_node;
mod top_level;
mod tri4;
mod watertight;
mod wide;

pub use build::BvhError;
pub use gpu_node::{GPU_EMPTY, GPU_LEAF, GPU_STACK_SIZE, GPU_WIDTH, GpuNode};
pub use top_level::{Bounds, TopLayout, TopLevel, Update, pad};
pub use watertight::{T_MIN, TriangleVerts, WatertightRay};
#[cfg(target_arch = "x86_64")]
pub use wide::{X86Level, x86_level};

use glam::{Vec3, Vec3A};
use wide::Wide;

/// Which compiled form of the CPU traversal ([`Bvh::closest`], [`Bvh::any_hit`]) this CPU
/// runs: "avx512" (the AVX2 code compiled for AVX-512's 32 vector registers), "avx2", or
/// "portable" lane loops. All find the same hits; they differ in speed, which is why
/// throughput reports name it.
pub fn cpu_traversal_simd() -> &'static str {
    wide::simd_name()
}

/// A BVH over a list of triangles (the "input order"), in two layouts over one leaf order.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    gpu: Vec<GpuNode>,
    gpu_pending: usize,
    wide: Wide,
}

impl Bvh {
    /// Builds the BVH of `tris` (corners in world space; they must be finite). Zero-area
    /// triangles may be included: they are never hit. No triangles gives an empty BVH
    /// that nothing hits.
    pub fn build(tris: &[[Vec3; 3]]) -> Result<Self, BvhError> {
        let build::Layouts {
            gpu,
            gpu_pending,
            wide,
        } = build::build(&build::to_verts(tris))?;
        Ok(Self {
            gpu,
            gpu_pending,
            wide,
        })
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.wide.ids.len()
    }

    /// The 4-wide tree for the GPU; node 0 is the root. Empty for an empty BVH. Fails with
    /// [`BvhError::TooDeep`] when its traversal could leave more children pending than the
    /// GPU's stack holds ([`GPU_STACK_SIZE`]; the bunny subdivided to 17.8 M triangles
    /// needs 48).
    pub fn gpu_nodes(&self) -> Result<&[GpuNode], BvhError> {
        if self.gpu_pending > GPU_STACK_SIZE {
            return Err(BvhError::TooDeep {
                layout: "GPU",
                needed: self.gpu_pending,
                capacity: GPU_STACK_SIZE,
            });
        }
        Ok(&self.gpu)
    }

    /// The leaf order: position k of the leaves' triangle ranges holds input triangle
    /// `leaf_order()[k]`.
    pub fn leaf_order(&self) -> &[u32] {
        &self.wide.ids
    }

    /// The nodes of the CPU's 8-wide tree (a size measure).
    pub fn wide_node_count(&self) -> usize {
        self.wide.nodes.len()
    }

    /// The nearest hit of the ray `origin + t·dir` on t in (T_MIN, t_max): its t and the
    /// input index of the triangle. Among hits at the same t the lowest index wins, and a
    /// hit exactly at t_max is not taken, as in a brute-force loop over the input. The ray
    /// must be finite (a NaN would enter every box): a scene's rays reach here through
    /// [`TopLevel`], which lets a ray that is not finite meet nothing.
    #[inline]
    pub fn closest(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<(f32, u32)> {
        self.wide.closest(origin, dir, t_max)
    }

    /// Whether the ray `origin + t·dir` hits any triangle on t in (T_MIN, t_max). The ray
    /// must be finite, as for [`Bvh::closest`].
    #[inline]
    pub fn any_hit(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        self.wide.any_hit(origin, dir, t_max)
    }
}
