//! The order the closest-hit traversal of a mesh's 8-wide tree ([`crate::Bvh::closest`])
//! enters the children a ray meets: nearest first, the others pending on a stack, farthest
//! deepest. (The top-level tree keeps a per-lane gather and an insertion sort: with this
//! order the corridor's and `flyby`'s frames took 7 and 10 % longer.)
//!
//! A child the ray enters is one [`ChildKey`]: the bits of its entry distance above, its
//! child entry below. Entry distances are never negative (the box test starts them at 0),
//! and non-negative floats order as their bits do, so keys order as their distances, and
//! one integer comparison with a conditional move sorts two of them without a branch.
//! Nodes where the ray meets two to four children, most of those of incoherent rays, are
//! sorted by such fixed sequences of comparisons in registers; before, an insertion sort
//! through memory took a data-dependent branch per comparison.
//!
//! Which of the children with equal distances is entered first does not change the hit:
//! the traversal skips a child only when its distance exceeds the best hit's, and among
//! hits at the same t the lowest input index wins wherever it is found.

use crate::wide::{STACK_SIZE, WIDTH};
use std::mem::MaybeUninit;

/// A child the ray enters: `distance.to_bits() << 32 | child entry`.
pub(crate) type ChildKey = u64;

/// The key of child entry `child` entered at `distance` (not negative, not NaN).
#[inline(always)]
pub(crate) fn child_key(distance: f32, child: u32) -> ChildKey {
    (u64::from(distance.to_bits()) << 32) | u64::from(child)
}

/// The child entry of `key`.
#[inline(always)]
fn key_child(key: ChildKey) -> u32 {
    key as u32
}

/// The entry distance of `key`.
#[inline(always)]
fn key_distance(key: ChildKey) -> f32 {
    f32::from_bits((key >> 32) as u32)
}

/// `(a, b)` in ascending order, without a branch.
#[inline(always)]
fn ordered(a: ChildKey, b: ChildKey) -> (ChildKey, ChildKey) {
    (a.min(b), a.max(b))
}

/// `keys` sorted farthest first: [`Pending::enter`]'s sort for five or more children (rare),
/// out of line.
#[inline(never)]
fn sort_descending(keys: &mut [ChildKey]) {
    for i in 1..keys.len() {
        let mut j = i;
        while j > 0 && keys[j - 1] < keys[j] {
            keys.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// The storage of [`Pending`]'s stack: a local array of the traversal, left uninitialised
/// (`[MaybeUninit::uninit(); STACK_SIZE]`), since zeroing it would cost as much as a
/// short traversal. Held in [`Pending`] itself, it was zeroed at every ray.
pub(crate) type PendingStack = [MaybeUninit<ChildKey>; STACK_SIZE];

/// The children pending on a closest-hit traversal's stack.
pub(crate) struct Pending<'s> {
    stack: &'s mut PendingStack,
    len: usize,
}

impl<'s> Pending<'s> {
    /// An empty stack over `stack`.
    #[inline(always)]
    pub fn new(stack: &'s mut PendingStack) -> Self {
        Self { stack, len: 0 }
    }

    #[inline(always)]
    fn push(&mut self, key: ChildKey) {
        self.stack[self.len].write(key);
        self.len += 1;
    }

    /// The children of one node that the ray enters: the lanes set in `lanes` (not empty),
    /// with entry distances `near` and child entries `child`. Pushes all but the nearest,
    /// the farthest deepest, and returns the nearest's child entry, to descend into.
    #[inline(always)]
    pub fn enter(&mut self, near: &[f32; WIDTH], child: &[u32; WIDTH], mut lanes: u32) -> u32 {
        debug_assert!(lanes != 0);
        if lanes & (lanes - 1) == 0 {
            // One child: its entry straight from the node, which does not wait for the
            // distances.
            return child[lanes.trailing_zeros() as usize];
        }
        let mut take_lowest = || {
            let lane = lanes.trailing_zeros() as usize;
            lanes &= lanes - 1;
            (child_key(near[lane], child[lane]), lanes == 0)
        };
        let (a, _) = take_lowest();
        let (b, last) = take_lowest();
        if last {
            let (a, b) = ordered(a, b);
            self.push(b);
            return key_child(a);
        }
        let (c, last) = take_lowest();
        if last {
            let (a, b) = ordered(a, b);
            let (a, c) = ordered(a, c);
            let (b, c) = ordered(b, c);
            self.push(c);
            self.push(b);
            return key_child(a);
        }
        let (d, mut last) = take_lowest();
        if last {
            let (a, b) = ordered(a, b);
            let (c, d) = ordered(c, d);
            let (a, c) = ordered(a, c);
            let (b, d) = ordered(b, d);
            let (b, c) = ordered(b, c);
            self.push(d);
            self.push(c);
            self.push(b);
            return key_child(a);
        }
        let mut all = [a, b, c, d, 0, 0, 0, 0];
        let mut n = 4;
        while !last {
            (all[n], last) = take_lowest();
            n += 1;
        }
        sort_descending(&mut all[..n]);
        for &key in &all[..n - 1] {
            self.push(key);
        }
        key_child(all[n - 1])
    }

    /// Pops children until one can still hold a hit no farther than `best` (its entry
    /// distance is at most `best`); returns its child entry, or `None` when none is left.
    #[inline(always)]
    pub fn pop_within(&mut self, best: f32) -> Option<u32> {
        while self.len > 0 {
            self.len -= 1;
            // SAFETY: entries below `len` were all written by `push`.
            let key = unsafe { self.stack[self.len].assume_init() };
            if key_distance(key) <= best {
                return Some(key_child(key));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every subset of up to eight children, at distances with ties: the nearest is entered
    /// and the rest pop nearest first, as a full sort of the keys gives them.
    #[test]
    fn children_are_entered_nearest_first() {
        let distances = [0.5f32, 0.0, 2.0, 0.5, 1e-30, 7.0, f32::INFINITY, 2.0];
        let child: [u32; WIDTH] = std::array::from_fn(|lane| 100 + lane as u32);
        for lanes in 1u32..256 {
            let mut want: Vec<ChildKey> = (0..WIDTH)
                .filter(|&lane| lanes & (1 << lane) != 0)
                .map(|lane| child_key(distances[lane], child[lane]))
                .collect();
            want.sort_unstable();
            let mut stack = [MaybeUninit::uninit(); STACK_SIZE];
            let mut pending = Pending::new(&mut stack);
            let mut got = vec![pending.enter(&distances, &child, lanes)];
            while let Some(child) = pending.pop_within(f32::INFINITY) {
                got.push(child);
            }
            let want: Vec<u32> = want.into_iter().map(key_child).collect();
            assert_eq!(got, want, "lanes {lanes:#b}");
        }
    }

    /// Children farther than the best hit are skipped when popped.
    #[test]
    fn farther_children_are_skipped() {
        let near: [f32; WIDTH] = std::array::from_fn(|lane| lane as f32);
        let child: [u32; WIDTH] = std::array::from_fn(|lane| lane as u32);
        let mut stack = [MaybeUninit::uninit(); STACK_SIZE];
        let mut pending = Pending::new(&mut stack);
        assert_eq!(pending.enter(&near, &child, 0b1111_0001), 0);
        assert_eq!(pending.pop_within(5.5), Some(4));
        assert_eq!(pending.pop_within(5.0), Some(5));
        assert_eq!(pending.pop_within(5.0), None);
    }
}
