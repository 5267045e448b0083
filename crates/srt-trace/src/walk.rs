//! The CPU tracer's walk of a BVH (built by the `bvh` crate) along a ray: nearer subtree
//! first, on a stack that lives on the call's own stack frame, pruned by a bound the visitor
//! lowers as it finds hits. An object's triangles and a velocity group's objects are both found
//! through it ([`crate::prepared`], [`crate::group`]).
//!
//! It replaces the crate's `nearest_traverse_iterator`, which keeps a binary heap (allocated
//! for every walk) and tests boxes through nalgebra's generic slab test: the two made up a
//! quarter of the teaser's CPU time. A walk visits every leaf whose box the ray enters no
//! farther than the bound at the time, so whatever a visitor keeps of the leaves it is given —
//! the nearest hit, ties to the lowest index — is what a search of every leaf keeps.

use bvh::aabb::{Aabb, Bounded};
use bvh::bounding_hierarchy::BHShape;
use bvh::bvh::{Bvh, BvhNode};
use glam::DVec3;
use nalgebra::Point3;

/// A leaf of a BVH the walk searches: `item` in the box [`lo`, `hi`] it was made with (the
/// `bvh` crate's leaf traits, for its builder).
#[derive(Debug, Clone)]
pub(crate) struct BoxLeaf<T> {
    aabb: Aabb<f64, 3>,
    /// What the leaf stands for.
    pub(crate) item: T,
    node: usize,
}

impl<T> BoxLeaf<T> {
    /// The leaf of `item` in the box [`lo`, `hi`].
    pub(crate) fn new(lo: DVec3, hi: DVec3, item: T) -> Self {
        Self {
            aabb: aabb(lo, hi),
            item,
            node: 0,
        }
    }
}

/// The `bvh` crate's box [`lo`, `hi`].
pub(crate) fn aabb(lo: DVec3, hi: DVec3) -> Aabb<f64, 3> {
    Aabb::with_bounds(Point3::new(lo.x, lo.y, lo.z), Point3::new(hi.x, hi.y, hi.z))
}

impl<T> Bounded<f64, 3> for BoxLeaf<T> {
    fn aabb(&self) -> Aabb<f64, 3> {
        self.aabb
    }
}

impl<T> BHShape<f64, 3> for BoxLeaf<T> {
    fn set_bh_node_index(&mut self, index: usize) {
        self.node = index;
    }

    fn bh_node_index(&self) -> usize {
        self.node
    }
}

/// Subtrees a walk keeps on its own stack frame before it spills to the heap: a BVH of
/// 1.92 M triangles built by the crate is about 40 levels deep.
const INLINE_DEPTH: usize = 64;

/// Where the ray `origin` + s · direction (s ≥ 0; `inverse_direction` = 1 / direction per
/// component) enters the box [`lo`, `hi`] (0 when it starts inside), `None` when it misses it:
/// the slab test. Conservative: where rounding gives NaN (an origin on a slab's plane with a
/// direction parallel to it) the box counts as met.
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

/// [`box_entry`] of a `bvh` crate box.
fn aabb_entry(aabb: &Aabb<f64, 3>, origin: DVec3, inverse_direction: DVec3) -> Option<f64> {
    let lo = DVec3::new(aabb.min.x, aabb.min.y, aabb.min.z);
    let hi = DVec3::new(aabb.max.x, aabb.max.y, aabb.max.z);
    box_entry(origin, inverse_direction, lo, hi)
}

/// Subtrees waiting to be walked, with where the ray enters their boxes.
struct Pending {
    inline: [(usize, f64); INLINE_DEPTH],
    len: usize,
    spilled: Vec<(usize, f64)>,
}

impl Pending {
    const fn new() -> Self {
        Self {
            inline: [(0, 0.0); INLINE_DEPTH],
            len: 0,
            spilled: Vec::new(),
        }
    }

    fn push(&mut self, entry: (usize, f64)) {
        if self.len < INLINE_DEPTH {
            self.inline[self.len] = entry;
            self.len += 1;
        } else {
            self.spilled.push(entry);
        }
    }

    fn pop(&mut self) -> Option<(usize, f64)> {
        if let Some(entry) = self.spilled.pop() {
            return Some(entry);
        }
        self.len = self.len.checked_sub(1)?;
        Some(self.inline[self.len])
    }
}

/// Walks `bvh` along the ray `origin` + s · direction (`inverse_direction` = 1 / direction per
/// component), nearer subtree first, and calls `visit(shape, bound)` for every leaf whose box
/// the ray enters no farther than `bound`; `visit` returns the bound from then on (the
/// nearest hit found so far, say). The root's box is not tested: a caller tests the object's
/// own box first.
pub(crate) fn nearest_first(
    bvh: &Bvh<f64, 3>,
    origin: DVec3,
    inverse_direction: DVec3,
    mut bound: f64,
    mut visit: impl FnMut(usize, f64) -> f64,
) {
    if bvh.nodes.is_empty() {
        return;
    }
    let mut pending = Pending::new();
    pending.push((0, 0.0));
    while let Some((index, entry)) = pending.pop() {
        if entry > bound {
            continue;
        }
        match &bvh.nodes[index] {
            BvhNode::Leaf { shape_index, .. } => bound = visit(*shape_index, bound),
            BvhNode::Node {
                child_l_index,
                child_l_aabb,
                child_r_index,
                child_r_aabb,
                ..
            } => {
                let left = aabb_entry(child_l_aabb, origin, inverse_direction)
                    .filter(|&e| e <= bound)
                    .map(|e| (*child_l_index, e));
                let right = aabb_entry(child_r_aabb, origin, inverse_direction)
                    .filter(|&e| e <= bound)
                    .map(|e| (*child_r_index, e));
                // The nearer is pushed last, so it is walked first.
                match (left, right) {
                    (Some(l), Some(r)) if l.1 <= r.1 => {
                        pending.push(r);
                        pending.push(l);
                    }
                    (Some(l), Some(r)) => {
                        pending.push(l);
                        pending.push(r);
                    }
                    (Some(only), None) | (None, Some(only)) => pending.push(only),
                    (None, None) => {}
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a row of cubes along the ray (and some beside it), the walk finds the nearest cube
    /// the ray meets as a search of all does, visits no cube it misses, and, once its visitor
    /// bounds it at the first hit, visits few cubes beyond it.
    #[test]
    fn the_walk_finds_the_nearest_and_prunes_beyond_its_bound() {
        // Unit cubes, each leaf holding its centre.
        let mut cubes: Vec<BoxLeaf<DVec3>> = (0..200)
            .map(|i| {
                let centre = DVec3::new(f64::from(i % 20) * 2.0, f64::from(i / 20) * 3.0, 0.0);
                BoxLeaf::new(centre - 0.5, centre + 0.5, centre)
            })
            .collect();
        let bvh = Bvh::build(&mut cubes);
        let origin = DVec3::new(-5.0, 0.0, 0.0);
        let direction = DVec3::X;
        let inverse = direction.recip();
        let entries: Vec<Option<f64>> = (cubes.iter())
            .map(|cube| aabb_entry(&cube.aabb(), origin, inverse))
            .collect();
        let nearest = (entries.iter().enumerate())
            .filter_map(|(i, e)| e.map(|e| (e, i)))
            .min_by(|a, b| a.partial_cmp(b).unwrap())
            .unwrap();
        assert_eq!(nearest.1, 0);
        let mut visited = Vec::new();
        let mut best: Option<(f64, usize)> = None;
        nearest_first(&bvh, origin, inverse, f64::INFINITY, |shape, bound| {
            visited.push(shape);
            let entry = entries[shape].expect("only cubes the ray meets are visited");
            if best.is_none_or(|b| (entry, shape) < b) {
                best = Some((entry, shape));
            }
            bound.min(entry)
        });
        assert_eq!(best, Some(nearest));
        assert!(visited.len() <= 3, "visited {visited:?}");
        // Unbounded, every cube on the ray (the first row, 20 of them) is visited once.
        let mut all = Vec::new();
        nearest_first(&bvh, origin, inverse, f64::INFINITY, |shape, bound| {
            all.push(shape);
            bound
        });
        all.sort_unstable();
        assert_eq!(all, (0..20).collect::<Vec<_>>());
    }

    /// A walk deeper than its inline stack spills to the heap and still visits every leaf.
    #[test]
    fn a_walk_past_its_inline_depth_visits_every_leaf() {
        let mut pending = Pending::new();
        for i in 0..(INLINE_DEPTH + 10) {
            pending.push((i, 0.0));
        }
        let mut popped = Vec::new();
        while let Some((i, _)) = pending.pop() {
            popped.push(i);
        }
        popped.sort_unstable();
        assert_eq!(popped, (0..INLINE_DEPTH + 10).collect::<Vec<_>>());
    }
}
