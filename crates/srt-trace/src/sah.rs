//! The CPU tracer's BVH builder: a binary tree over boxes, split top-down where the surface area
//! heuristic (SAH) of 16 bins on each of the three axes is least, subtrees built on rayon's
//! threads, laid out depth first so that the leaves come in the order of the boxes it returns
//! ([`build`]). It works on the leaves' boxes rounded outwards to f32, the precision the walks'
//! nodes keep ([`FlatNode`]), so every node's box holds the f64 boxes below it.
//!
//! It replaced the `bvh` crate's builder (6 buckets on the longest axis only, the leaves' boxes
//! recomputed and pushed into per-bucket vectors at every level): on the 2CylinderEngine's
//! 121 496 triangles that one took 56–74 ms, and its trees were walked more slowly
//! (docs/performance.md, "Issue 69, second round"). Which tree is built changes no picture:
//! every walk visits each leaf its ray enters no farther than its bound, and every visitor
//! breaks ties by the leaves' own numbers, not by the tree ([`crate::walk`]).

use glam::{DVec3, Vec3A};
use rayon::prelude::*;

/// The flag of a child that is a leaf (its number in the leaf order below it); a child without
/// it is an inner node's index.
pub(crate) const LEAF: u32 = 1 << 31;

/// Bins per axis of the SAH search.
const BINS: usize = 16;

/// Nodes of at most this many leaves are split by sorting them along each axis and weighing
/// every split (exactly the SAH's best), which costs less than filling the bins.
const SORTED_LEAVES: usize = 16;

/// Subtrees of fewer leaves than this are built on the thread that meets them; larger ones
/// hand one side to rayon.
const PARALLEL_LEAVES: usize = 4096;

/// An inner node of a [`Tree`]: its two children (a node's index, or a leaf's number with
/// [`LEAF`]) and their boxes in f32, rounded outwards (each holds the f64 boxes of the leaves
/// below it), one cache line. The walks read it ([`crate::walk`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct FlatNode {
    /// The children's boxes' lower corners.
    pub(crate) lo: [[f32; 3]; 2],
    /// The children's boxes' upper corners.
    pub(crate) hi: [[f32; 3]; 2],
    /// The children.
    pub(crate) child: [u32; 2],
}

/// A BVH as [`build`] makes it: the inner nodes depth first (the root at 0, each node's left
/// subtree right after it), and which box each leaf is, leaves numbered as the layout meets
/// them.
#[derive(Debug)]
pub(crate) struct Tree {
    /// The inner nodes (one fewer than the leaves).
    pub(crate) nodes: Vec<FlatNode>,
    /// The root: node 0, or the only leaf.
    pub(crate) root: u32,
    /// `order[leaf]` is the index, in what [`build`] was given, of leaf `leaf`'s box.
    pub(crate) order: Vec<u32>,
}

/// The largest f32 no greater than `x` (`x` itself where it is one).
pub(crate) fn f32_below(x: f64) -> f32 {
    let rounded = x as f32;
    if f64::from(rounded) > x {
        rounded.next_down()
    } else {
        rounded
    }
}

/// The smallest f32 no less than `x`.
pub(crate) fn f32_above(x: f64) -> f32 {
    let rounded = x as f32;
    if f64::from(rounded) < x {
        rounded.next_up()
    } else {
        rounded
    }
}

/// Leaves in a bin or a subtree: how many, the union of their boxes and the box of their
/// centres (f32; the boxes rounded outwards, so every union holds the f64 boxes).
#[derive(Debug, Clone, Copy)]
struct Bounds {
    count: usize,
    lo: Vec3A,
    hi: Vec3A,
    centre_lo: Vec3A,
    centre_hi: Vec3A,
}

impl Bounds {
    const EMPTY: Self = Self {
        count: 0,
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
        centre_lo: Vec3A::INFINITY,
        centre_hi: Vec3A::NEG_INFINITY,
    };

    /// These bounds with `leaf` added.
    #[inline]
    fn add(&mut self, leaf: &Leaf) {
        self.count += 1;
        self.lo = self.lo.min(leaf.lo());
        self.hi = self.hi.max(leaf.hi());
        let centre = leaf.centre();
        self.centre_lo = self.centre_lo.min(centre);
        self.centre_hi = self.centre_hi.max(centre);
    }

    /// The union of two bounds.
    fn join(self, other: Self) -> Self {
        Self {
            count: self.count + other.count,
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
            centre_lo: self.centre_lo.min(other.centre_lo),
            centre_hi: self.centre_hi.max(other.centre_hi),
        }
    }

    /// Half the surface area of the box (what the SAH weighs a side by).
    fn half_area(&self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// A leaf as the builder reads it: its box, rounded outwards to f32, and its index in what
/// [`build`] was given (28 bytes). The builder reorders the leaves themselves, so that a
/// subtree's are side by side in memory.
#[derive(Debug, Clone, Copy)]
struct Leaf {
    lo: [f32; 3],
    index: u32,
    hi: [f32; 3],
}

impl Leaf {
    /// The box's lower corner.
    #[inline]
    fn lo(&self) -> Vec3A {
        Vec3A::from_array(self.lo)
    }

    /// The box's upper corner.
    #[inline]
    fn hi(&self) -> Vec3A {
        Vec3A::from_array(self.hi)
    }

    /// The centre of the leaf's box (twice it: only order and spread matter to the builder).
    #[inline]
    fn centre(&self) -> Vec3A {
        self.lo() + self.hi()
    }
}

/// The bounds of `leaves`.
fn bounds_of(leaves: &[Leaf]) -> Bounds {
    let mut bounds = Bounds::EMPTY;
    for leaf in leaves {
        bounds.add(leaf);
    }
    bounds
}

/// Builds the BVH over `count` boxes, box `i` being `box_of(i)` (its lower and upper corner);
/// `None` for none. Deterministic: the same tree on any number of threads.
pub(crate) fn build(count: usize, box_of: impl Fn(usize) -> (DVec3, DVec3) + Sync) -> Option<Tree> {
    if count == 0 {
        return None;
    }
    u32::try_from(count)
        .ok()
        .filter(|&n| n < LEAF)
        .expect("fewer than 2³¹ leaves");
    // On all threads: the pages these first touch are cleared by the kernel, which costs as
    // much as the work here.
    let mut leaves: Vec<Leaf> = (0..count)
        .into_par_iter()
        .map(|index| {
            let (lo, hi) = box_of(index);
            Leaf {
                lo: lo.to_array().map(f32_below),
                index: index as u32,
                hi: hi.to_array().map(f32_above),
            }
        })
        .collect();
    let mut nodes = Vec::with_capacity(count - 1);
    nodes.par_extend(rayon::iter::repeat_n(FlatNode::default(), count - 1));
    let bounds = bounds_of(&leaves);
    let root = subtree(&mut leaves, &mut nodes, (0, 0), bounds);
    let order = leaves.par_iter().map(|leaf| leaf.index).collect();
    Some(Tree { nodes, root, order })
}

/// Builds the subtree over `leaves` (reordered into its leaf order) into `nodes` (one fewer
/// than them), whose first is node `first_node` of the tree and whose first leaf is leaf
/// `first_leaf`, the leaves' bounds being `bounds`; returns the subtree's root as a child.
fn subtree(
    leaves: &mut [Leaf],
    nodes: &mut [FlatNode],
    (first_node, first_leaf): (u32, u32),
    bounds: Bounds,
) -> u32 {
    if leaves.len() == 1 {
        return LEAF | first_leaf;
    }
    let (left_bounds, right_bounds) = split(leaves, &bounds);
    let (count, left_count) = (leaves.len(), left_bounds.count);
    let (leaves_left, leaves_right) = leaves.split_at_mut(left_count);
    let (node, below) = nodes.split_first_mut().expect("a node per split");
    let (nodes_left, nodes_right) = below.split_at_mut(left_count - 1);
    let left_at = (first_node + 1, first_leaf);
    let right_at = (
        first_node + left_count as u32,
        first_leaf + left_count as u32,
    );
    let mut build_left = move || subtree(leaves_left, nodes_left, left_at, left_bounds);
    let mut build_right = move || subtree(leaves_right, nodes_right, right_at, right_bounds);
    let (left, right) = if count >= PARALLEL_LEAVES {
        rayon::join(build_left, build_right)
    } else {
        (build_left(), build_right())
    };
    *node = FlatNode {
        lo: [left_bounds.lo, right_bounds.lo].map(|v| v.to_array()),
        hi: [left_bounds.hi, right_bounds.hi].map(|v| v.to_array()),
        child: [left, right],
    };
    first_node
}

/// Splits `leaves` (two or more, with bounds `bounds`) in two where the SAH is least (over 16
/// bins per axis, or every split of a few leaves sorted along each axis), reordering them left
/// side first, and returns the two sides' bounds; where every centre is the same point, in the
/// middle.
fn split(leaves: &mut [Leaf], bounds: &Bounds) -> (Bounds, Bounds) {
    if leaves.len() <= SORTED_LEAVES {
        return split_sorted(leaves, bounds);
    }
    let extent = bounds.centre_hi - bounds.centre_lo;
    // Bins per unit of the centres' extent, 0 along an axis where they do not spread.
    let scale = Vec3A::select(extent.cmpgt(Vec3A::ZERO), BINS as f32 / extent, Vec3A::ZERO);
    // Clamped as floats (the top centre to the last bin; a NaN, 0 × ∞ on a vanishing extent,
    // casts to 0), then cast: one instruction a lane.
    let last = Vec3A::splat((BINS - 1) as f32);
    let bins_of = |leaf: &Leaf| -> [usize; 3] {
        (((leaf.centre() - bounds.centre_lo) * scale).min(last))
            .to_array()
            .map(|bin| bin as i32 as usize)
    };
    let mut bins = [[Bounds::EMPTY; BINS]; 3];
    for leaf in leaves.iter() {
        let bin = bins_of(leaf);
        for (axis, axis_bins) in bins.iter_mut().enumerate() {
            axis_bins[bin[axis]].add(leaf);
        }
    }
    // The least cost: (cost, axis, the first bin on the right, the two sides' bounds).
    let mut best: Option<(f32, usize, usize, Bounds, Bounds)> = None;
    for (axis, axis_bins) in bins.iter().enumerate() {
        if scale[axis] == 0.0 {
            continue;
        }
        let mut right_of = [Bounds::EMPTY; BINS];
        let mut right = Bounds::EMPTY;
        for k in (1..BINS).rev() {
            right = right.join(axis_bins[k]);
            right_of[k] = right;
        }
        let mut left = Bounds::EMPTY;
        for k in 1..BINS {
            left = left.join(axis_bins[k - 1]);
            let right = right_of[k];
            if left.count == 0 || right.count == 0 {
                continue;
            }
            let cost =
                left.half_area() * left.count as f32 + right.half_area() * right.count as f32;
            if best.is_none_or(|(least, ..)| cost < least) {
                best = Some((cost, axis, k, left, right));
            }
        }
    }
    match best {
        Some((_, axis, first_right, left, right)) => {
            partition(leaves, |leaf| bins_of(leaf)[axis] < first_right);
            (left, right)
        }
        None => halves(leaves),
    }
}

/// [`split`] for at most [`SORTED_LEAVES`] leaves: along each axis where their centres spread,
/// sorted by centre, every split between neighbours weighed.
fn split_sorted(leaves: &mut [Leaf], bounds: &Bounds) -> (Bounds, Bounds) {
    let count = leaves.len();
    let extent = bounds.centre_hi - bounds.centre_lo;
    // The leaves' positions in `leaves`, sorted along each axis.
    let mut sorted = [[0_u8; SORTED_LEAVES]; 3];
    // The least cost: (cost, axis, how many on the left).
    let mut best: Option<(f32, usize, usize)> = None;
    for (axis, order) in sorted.iter_mut().enumerate() {
        if extent[axis] <= 0.0 {
            continue;
        }
        let order = &mut order[..count];
        for (k, position) in order.iter_mut().enumerate() {
            *position = k as u8;
        }
        order.sort_unstable_by(|&a, &b| {
            let centre = |k: u8| leaves[usize::from(k)].centre()[axis];
            centre(a).total_cmp(&centre(b)).then(a.cmp(&b))
        });
        let mut right_area = [0.0_f32; SORTED_LEAVES];
        let mut right = Bounds::EMPTY;
        for k in (1..count).rev() {
            right.add(&leaves[usize::from(order[k])]);
            right_area[k] = right.half_area();
        }
        let mut left = Bounds::EMPTY;
        for k in 1..count {
            left.add(&leaves[usize::from(order[k - 1])]);
            let cost = left.half_area() * k as f32 + right_area[k] * (count - k) as f32;
            if best.is_none_or(|(least, ..)| cost < least) {
                best = Some((cost, axis, k));
            }
        }
    }
    let Some((_, axis, left_count)) = best else {
        return halves(leaves);
    };
    let mut was = [leaves[0]; SORTED_LEAVES];
    was[..count].copy_from_slice(leaves);
    for (leaf, &position) in leaves.iter_mut().zip(&sorted[axis][..count]) {
        *leaf = was[usize::from(position)];
    }
    let (left, right) = leaves.split_at(left_count);
    (bounds_of(left), bounds_of(right))
}

/// The split of leaves whose centres are one point (or that no SAH split divides): in the
/// middle, as they come.
fn halves(leaves: &[Leaf]) -> (Bounds, Bounds) {
    let (left, right) = leaves.split_at(leaves.len() / 2);
    (bounds_of(left), bounds_of(right))
}

/// Reorders `leaves` so that those for which `left` holds come first (in no particular order
/// within each side, the same for the same input).
fn partition(leaves: &mut [Leaf], left: impl Fn(&Leaf) -> bool) {
    let (mut start, mut end) = (0, leaves.len());
    while start < end {
        if left(&leaves[start]) {
            start += 1;
        } else {
            end -= 1;
            leaves.swap(start, end);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Checks the tree's shape: every leaf once, in layout order; every inner node reached once,
    /// depth first; each child's box holds the boxes of the leaves below it.
    fn assert_well_formed(boxes: &[(DVec3, DVec3)], tree: &Tree) {
        let mut sorted = tree.order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..boxes.len() as u32).collect::<Vec<_>>());
        assert_eq!(tree.nodes.len(), boxes.len() - 1);
        // (child, the box it must lie in), depth first, left first.
        let (mut next_leaf, mut next_node) = (0, 0);
        let widen = |v: [f32; 3]| DVec3::from_array(v.map(f64::from));
        let mut pending = vec![(tree.root, DVec3::NEG_INFINITY, DVec3::INFINITY)];
        while let Some((child, lo, hi)) = pending.pop() {
            if child & LEAF != 0 {
                assert_eq!(child & !LEAF, next_leaf, "leaves in layout order");
                let (leaf_lo, leaf_hi) = boxes[tree.order[next_leaf as usize] as usize];
                assert!(leaf_lo.cmpge(lo).all() && leaf_hi.cmple(hi).all());
                next_leaf += 1;
                continue;
            }
            assert_eq!(child, next_node, "nodes depth first");
            next_node += 1;
            let node = &tree.nodes[child as usize];
            for k in [1, 0] {
                let (child_lo, child_hi) = (widen(node.lo[k]), widen(node.hi[k]));
                assert!(child_lo.cmpge(lo).all() && child_hi.cmple(hi).all());
                pending.push((node.child[k], child_lo, child_hi));
            }
        }
        assert_eq!(next_leaf as usize, boxes.len());
        assert_eq!(next_node as usize, tree.nodes.len());
    }

    proptest! {
        /// Any boxes, repeated points and all: a well-formed tree whose boxes hold their
        /// leaves' boxes.
        #[test]
        fn every_tree_holds_each_box_once_below_boxes_that_hold_it(
            corners in prop::collection::vec(
                (prop::array::uniform3(-4i32..4), prop::array::uniform3(0i32..3)),
                1..300,
            )
        ) {
            let boxes: Vec<(DVec3, DVec3)> = (corners.iter())
                .map(|(at, size)| {
                    let lo = DVec3::from_array(at.map(|v| f64::from(v) * 0.25));
                    (lo, lo + DVec3::from_array(size.map(f64::from)))
                })
                .collect();
            let tree = build(boxes.len(), |i| boxes[i]).expect("a tree");
            assert_well_formed(&boxes, &tree);
        }
    }

    /// Enough leaves to build on several threads: the same tree as on one.
    #[test]
    fn the_tree_does_not_depend_on_the_threads() {
        let boxes: Vec<(DVec3, DVec3)> = (0..20_000_u32)
            .map(|i| {
                let f = f64::from(i);
                let at = DVec3::new((f * 0.618_034).fract(), (f * 0.414_214).fract(), f * 1e-4);
                (at, at + 0.001)
            })
            .collect();
        let many = build(boxes.len(), |i| boxes[i]).expect("a tree");
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a pool")
            .install(|| build(boxes.len(), |i| boxes[i]).expect("a tree"));
        assert_well_formed(&boxes, &many);
        assert_eq!(many.order, one.order);
        assert_eq!(many.root, one.root);
        assert_eq!(many.nodes, one.nodes);
    }

    /// Two separate clusters are split apart at the root.
    #[test]
    fn the_root_separates_two_clusters() {
        let boxes: Vec<(DVec3, DVec3)> = (0..64)
            .map(|i| {
                let x = if i % 2 == 0 { 0.0 } else { 100.0 } + f64::from(i) * 0.01;
                let lo = DVec3::new(x, 0.0, 0.0);
                (lo, lo + 0.005)
            })
            .collect();
        let tree = build(boxes.len(), |i| boxes[i]).expect("a tree");
        let root = &tree.nodes[0];
        assert!(root.hi[0][0] < 1.0 && root.lo[1][0] > 99.0, "{root:?}");
    }
}
