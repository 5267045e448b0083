//! The CPU tracer's BVH ([`FlatBvh`]: built by [`crate::sah`], laid out flat with f32 boxes
//! rounded outwards) and its walk along a ray: nearer subtree first, on a stack that lives on
//! the call's own stack frame, pruned by a bound the visitor lowers as it finds hits. An
//! object's triangles and a velocity group's objects are both found through it
//! ([`crate::prepared`], [`crate::group`]); a spinning body's pieces query it by box.
//!
//! A walk visits every leaf whose box the ray enters no farther than the bound at the time, so
//! whatever a visitor keeps of the leaves it is given — the nearest hit, ties to the lowest
//! index — is what a search of every leaf keeps, whatever tree the builder made.

use crate::sah::{self, FlatNode, LEAF};
use glam::DVec3;

/// Subtrees a walk keeps on its own stack frame before it spills to the heap (the `bvh`
/// crate's tree of 1.92 M triangles, before `sah.rs`, was about 40 levels deep).
const INLINE_DEPTH: usize = 64;

/// Where the ray `origin` + s · direction (s ≥ 0; `inverse_direction` = 1 / direction per
/// component) enters the box [`lo`, `hi`] (0 when it starts inside), `None` when it misses it:
/// the slab test. Conservative: where rounding gives NaN (an origin on a slab's plane with a
/// direction parallel to it) the box counts as met.
#[inline]
pub(crate) fn box_entry(
    origin: DVec3,
    inverse_direction: DVec3,
    lo: DVec3,
    hi: DVec3,
) -> Option<f64> {
    let to_lo = (lo - origin) * inverse_direction;
    let to_hi = (hi - origin) * inverse_direction;
    let near = to_lo.min(to_hi).max_element().max(0.0);
    let far = to_lo.max(to_hi).min_element();
    if near > far { None } else { Some(near) }
}

/// A child of a [`FlatBvh`] node: a node's index, or a leaf's with [`LEAF`] set.
type Child = u32;

impl FlatNode {
    /// Where the ray enters the box of child `k` ([`box_entry`], in f64 on the f32 box).
    #[inline]
    fn entry(&self, k: usize, origin: DVec3, inverse_direction: DVec3) -> Option<f64> {
        let widen = |v: [f32; 3]| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
        box_entry(
            origin,
            inverse_direction,
            widen(self.lo[k]),
            widen(self.hi[k]),
        )
    }

    /// Whether the box of child `k` meets the box [`lo`, `hi`].
    fn overlaps(&self, k: usize, lo: DVec3, hi: DVec3) -> bool {
        (0..3).all(|axis| {
            f64::from(self.lo[k][axis]) <= hi[axis] && f64::from(self.hi[k][axis]) >= lo[axis]
        })
    }
}

/// A binary BVH as the walks read it: built by [`sah::build`], then laid out as one array of
/// [`FlatNode`]s, depth first, the leaves numbered in the order the layout meets them (so that
/// neighbouring leaves lie side by side in what their items index).
///
/// Its boxes are the builder's, rounded outwards to f32: every box holds the f64 boxes of the
/// leaves below it, so a walk enters every leaf the f64 boxes would have let it enter (and,
/// rarely, a few more at their rims).
pub(crate) struct FlatBvh {
    nodes: Vec<FlatNode>,
    /// The root: node 0, or the only leaf.
    root: Child,
}

impl FlatBvh {
    /// Builds the BVH over `count` boxes, box `i` being `box_of(i)` (its lower and upper
    /// corner), and returns it with its leaf order: leaf `k` of the walks is box `order[k]`;
    /// `None` for no boxes.
    pub(crate) fn build(
        count: usize,
        box_of: impl Fn(usize) -> (DVec3, DVec3) + Sync,
    ) -> Option<(Self, Vec<u32>)> {
        let tree = sah::build(count, box_of)?;
        let bvh = Self {
            nodes: tree.nodes,
            root: tree.root,
        };
        Some((bvh, tree.order))
    }

    /// Calls `visit(leaf)` for every leaf whose box meets the box [`lo`, `hi`] (and perhaps a
    /// few more at the rims of theirs; a visitor tests its item's own box).
    pub(crate) fn overlapping(&self, lo: DVec3, hi: DVec3, mut visit: impl FnMut(usize)) {
        let mut pending = vec![self.root];
        while let Some(child) = pending.pop() {
            if child & LEAF != 0 {
                visit((child & !LEAF) as usize);
                continue;
            }
            let node = &self.nodes[child as usize];
            for k in [1, 0] {
                if node.overlaps(k, lo, hi) {
                    pending.push(node.child[k]);
                }
            }
        }
    }
}

/// Subtrees waiting to be walked, with where the ray enters their boxes.
struct Pending {
    inline: [(Child, f64); INLINE_DEPTH],
    len: usize,
    spilled: Vec<(Child, f64)>,
}

impl Pending {
    const fn new() -> Self {
        Self {
            inline: [(0, 0.0); INLINE_DEPTH],
            len: 0,
            spilled: Vec::new(),
        }
    }

    #[inline]
    fn push(&mut self, entry: (Child, f64)) {
        if self.len < INLINE_DEPTH {
            self.inline[self.len] = entry;
            self.len += 1;
        } else {
            self.spilled.push(entry);
        }
    }

    #[inline]
    fn pop(&mut self) -> Option<(Child, f64)> {
        if let Some(entry) = self.spilled.pop() {
            return Some(entry);
        }
        self.len = self.len.checked_sub(1)?;
        Some(self.inline[self.len])
    }
}

/// Walks `bvh` along the ray `origin` + s · direction (`inverse_direction` = 1 / direction per
/// component), nearer subtree first, and calls `visit(leaf, bound)` for every leaf whose box
/// the ray enters no farther than `bound`; `visit` returns the bound from then on (the
/// nearest hit found so far, say). The root's box is not tested: a caller tests the object's
/// own box first.
#[inline]
pub(crate) fn nearest_first(
    bvh: &FlatBvh,
    origin: DVec3,
    inverse_direction: DVec3,
    mut bound: f64,
    mut visit: impl FnMut(usize, f64) -> f64,
) {
    let mut pending = Pending::new();
    let mut current = bvh.root;
    loop {
        if current & LEAF != 0 {
            bound = visit((current & !LEAF) as usize, bound);
        } else {
            let node = &bvh.nodes[current as usize];
            let entry = |k: usize| {
                node.entry(k, origin, inverse_direction)
                    .filter(|&e| e <= bound)
                    .map(|e| (node.child[k], e))
            };
            match (entry(0), entry(1)) {
                (Some(l), Some(r)) => {
                    // The nearer is walked now, the farther later.
                    let (near, far) = if l.1 <= r.1 { (l, r) } else { (r, l) };
                    pending.push(far);
                    current = near.0;
                    continue;
                }
                (Some(only), None) | (None, Some(only)) => {
                    current = only.0;
                    continue;
                }
                (None, None) => {}
            }
        }
        // The next waiting subtree the ray enters no farther than the bound.
        loop {
            let Some((child, entry)) = pending.pop() else {
                return;
            };
            if entry <= bound {
                current = child;
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sah::{f32_above, f32_below};

    /// On a row of cubes along the ray (and some beside it), the walk finds the nearest cube
    /// the ray meets as a search of all does, visits no cube it misses, and, once its visitor
    /// bounds it at the first hit, visits few cubes beyond it.
    #[test]
    fn the_walk_finds_the_nearest_and_prunes_beyond_its_bound() {
        // Unit cubes, each leaf holding its centre.
        let given: Vec<DVec3> = (0..200)
            .map(|i| DVec3::new(f64::from(i % 20) * 2.0, f64::from(i / 20) * 3.0, 0.0))
            .collect();
        let cubes: Vec<(DVec3, DVec3)> = given.iter().map(|&c| (c - 0.5, c + 0.5)).collect();
        let (bvh, order) = FlatBvh::build(cubes.len(), |i| cubes[i]).unwrap();
        let centres: Vec<DVec3> = order.iter().map(|&i| given[i as usize]).collect();
        let origin = DVec3::new(-5.0, 0.0, 0.0);
        let direction = DVec3::X;
        let inverse = direction.recip();
        let entries: Vec<Option<f64>> = (centres.iter())
            .map(|&centre| box_entry(origin, inverse, centre - 0.5, centre + 0.5))
            .collect();
        let nearest = (entries.iter().enumerate())
            .filter_map(|(i, e)| e.map(|e| (e, i)))
            .min_by(|a, b| a.partial_cmp(b).unwrap())
            .unwrap();
        assert_eq!(centres[nearest.1], DVec3::ZERO);
        let mut visited = Vec::new();
        let mut best: Option<(f64, usize)> = None;
        nearest_first(&bvh, origin, inverse, f64::INFINITY, |leaf, bound| {
            visited.push(leaf);
            let entry = entries[leaf].expect("only cubes the ray meets are visited");
            if best.is_none_or(|b| (entry, leaf) < b) {
                best = Some((entry, leaf));
            }
            bound.min(entry)
        });
        assert_eq!(best, Some(nearest));
        assert!(visited.len() <= 3, "visited {visited:?}");
        // Unbounded, every cube on the ray (the first row, 20 of them) is visited once.
        let mut all: Vec<DVec3> = Vec::new();
        nearest_first(&bvh, origin, inverse, f64::INFINITY, |leaf, bound| {
            all.push(centres[leaf]);
            bound
        });
        all.sort_by(|a, b| a.x.total_cmp(&b.x));
        let row: Vec<DVec3> = (0..20)
            .map(|i| DVec3::new(f64::from(i) * 2.0, 0.0, 0.0))
            .collect();
        assert_eq!(all, row);
    }

    /// The f32 boxes hold the f64 boxes they are made from, at any scale, and the box query
    /// finds every leaf whose f64 box meets the query box (a cube beside the query box, an f64
    /// ulp apart, may be found too).
    #[test]
    fn the_f32_boxes_hold_their_f64_boxes_and_the_box_query_finds_every_overlap() {
        for x in [0.1, -0.1, 1.0 / 3.0, 1e-30, -7.123_456_789_012_345e12, 0.0] {
            assert!(
                f64::from(f32_below(x)) <= x && f64::from(f32_above(x)) >= x,
                "{x}"
            );
        }
        let boxes: Vec<(DVec3, DVec3)> = (0..64)
            .map(|i| {
                let centre = DVec3::new(f64::from(i % 8) * 1.1, f64::from(i / 8) * 0.7, 0.1);
                (centre - 0.3, centre + 0.3)
            })
            .collect();
        let (bvh, order) = FlatBvh::build(boxes.len(), |i| boxes[i]).unwrap();
        let items: Vec<usize> = order.iter().map(|&i| i as usize).collect();
        let (lo, hi) = (DVec3::new(1.0, 0.5, 0.0), DVec3::new(2.9, 2.0, 0.2));
        let mut found = Vec::new();
        bvh.overlapping(lo, hi, |leaf| found.push(items[leaf]));
        found.sort_unstable();
        let expected: Vec<usize> = (0..64)
            .filter(|&i| boxes[i].0.cmple(hi).all() && boxes[i].1.cmpge(lo).all())
            .collect();
        assert!(!expected.is_empty());
        assert_eq!(found, expected);
    }

    /// A walk deeper than its inline stack spills to the heap and still visits every leaf.
    #[test]
    fn a_walk_past_its_inline_depth_visits_every_leaf() {
        let mut pending = Pending::new();
        for i in 0..(INLINE_DEPTH + 10) {
            pending.push((i as Child, 0.0));
        }
        let mut popped = Vec::new();
        while let Some((i, _)) = pending.pop() {
            popped.push(i);
        }
        popped.sort_unstable();
        assert_eq!(
            popped,
            (0..(INLINE_DEPTH + 10) as Child).collect::<Vec<_>>()
        );
    }
}
