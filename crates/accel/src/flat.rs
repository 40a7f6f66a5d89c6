//! The flattened binary BVH layout shared by the CPU and the GPU: each inner node holds the
//! boxes of both its children (so a traversal step tests two boxes with one 64-byte load,
//! as in Aila and Laine, "Understanding the Efficiency of Ray Traversal on GPUs", 2009).

use bytemuck::{Pod, Zeroable};

/// An inner node of the flattened binary BVH: the boxes of its two children and, per child,
/// either an inner node (`count == 0`, `first` is its index in the node array) or a leaf
/// (`count > 0` triangles starting at leaf-order position `first`). Node 0 is the root.
///
/// `#[repr(C)]` and 64 bytes: the GPU reads it as four `vec4`s (`BvhNode` in the WGSL).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FlatNode {
    pub left_min: [f32; 3],
    pub left_first: u32,
    pub left_max: [f32; 3],
    pub left_count: u32,
    pub right_min: [f32; 3],
    pub right_first: u32,
    pub right_max: [f32; 3],
    pub right_count: u32,
}

/// One child of a [`FlatNode`] while building: its box and what it points at.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FlatChild {
    pub min: [f32; 3],
    pub max: [f32; 3],
    pub first: u32,
    pub count: u32,
}

impl FlatNode {
    /// The node with children `left` and `right`.
    pub(crate) fn new(left: FlatChild, right: FlatChild) -> Self {
        Self {
            left_min: left.min,
            left_first: left.first,
            left_max: left.max,
            left_count: left.count,
            right_min: right.min,
            right_first: right.first,
            right_max: right.max,
            right_count: right.count,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_is_four_vec4s() {
        assert_eq!(std::mem::size_of::<FlatNode>(), 64);
        assert_eq!(std::mem::offset_of!(FlatNode, right_min), 32);
    }
}
