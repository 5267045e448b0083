//! The bounding volume hierarchy of one object's triangles (all its parts), in its rest frame
//! S′, for the GPU ray tracer (`--method rt`, `shaders/rt.wgsl`): built on the CPU by the
//! `obvhs` crate (PLOC with reinsertion), flattened into [`GpuBvhNode`]s, and walked on the
//! GPU by the same nearest-hit traversal as `ObjectBvh::nearest_hit`, its f32 mirror here,
//! compiled for the tests only (which compare it with a test of every triangle).
//!
//! In S′ the object is static and a pixel's backward viewing ray is a straight half-line
//! (Eq. 3, 5), so this is the reference's algorithm (srt-trace: a BVH per part, Eq. 15–16),
//! run per pixel on the GPU instead of rasterising one footprint per triangle. The boxes are
//! widened by [`ObjectBvh::margin`] so that rounding in the f32 slab test never loses a hit that
//! the triangle test would find.

use glam::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::leaf_collapser::collapse;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::ploc::PlocBuilder;
use obvhs::{Boundable, BvhBuildParams};

use crate::error::GpuError;
use crate::types::{BVH_STACK_SIZE, GpuBvhNode, GpuVertex};

/// An object's BVH as the GPU reads it.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectBvh {
    /// The nodes, root first; inner nodes have their two children at `first` and `first + 1`.
    pub nodes: Vec<GpuBvhNode>,
    /// The input's triangle numbers in leaf order: a leaf holds the triangles
    /// `primitives[first..first + count]`. The GPU gets the triangles in this order
    /// ([`ObjectBvh::in_leaf_order`]), so its leaves index them directly.
    pub primitives: Vec<u32>,
    /// Edges on the longest path from the root to a leaf.
    pub depth: usize,
    /// How far every box was widened on each side.
    pub margin: f32,
}

/// One triangle's bounds, for the builder.
struct TriangleBounds(Aabb);

impl Boundable for TriangleBounds {
    fn aabb(&self) -> Aabb {
        self.0
    }
}

/// The corners of `triangle` (indices into `vertices`), as the GPU stores them.
#[must_use]
pub fn corners(vertices: &[GpuVertex], triangle: [u32; 3]) -> [[f32; 3]; 3] {
    triangle.map(|v| {
        let p = vertices[v as usize].position;
        [p[0], p[1], p[2]]
    })
}

/// obvhs's `build_bvh2` (PLOC, reinsertion, leaf collapse, reinsertion) without its build
/// timer: std's clock does not exist in the browser's WebAssembly, where the page builds these
/// trees too.
fn build_tree(bounds: &[TriangleBounds], config: &BvhBuildParams) -> Bvh2 {
    let mut bvh = PlocBuilder::with_capacity(bounds.len()).build(
        config.ploc_search_distance,
        bounds,
        (0..bounds.len() as u32).collect(),
        config.sort_precision,
        config.search_depth_threshold,
    );
    let mut reinsertion = ReinsertionOptimizer::default();
    reinsertion.run(&mut bvh, config.reinsertion_batch_ratio, None);
    collapse(
        &mut bvh,
        config.max_prims_per_leaf.clamp(1, 255),
        config.collapse_traversal_cost,
    );
    reinsertion.run(
        &mut bvh,
        config.reinsertion_batch_ratio * config.post_collapse_reinsertion_batch_ratio_multiplier,
        None,
    );
    bvh
}

impl ObjectBvh {
    /// Builds the BVH over `triangles` (their corners; at least one triangle: the caller,
    /// [`crate::ray_tracing`], refuses objects without any).
    ///
    /// # Errors
    /// [`GpuError::BvhTooDeep`] when the tree is deeper than the GPU traversal's stack
    /// ([`BVH_STACK_SIZE`]); `what` names the object in the message.
    pub fn build(
        triangles: &[[[f32; 3]; 3]],
        what: impl FnOnce() -> String,
    ) -> Result<Self, GpuError> {
        let bounds: Vec<TriangleBounds> = triangles
            .iter()
            .map(|t| TriangleBounds(Aabb::from_points(&t.map(Vec3A::from))))
            .collect();
        // obvhs's slow preset (a wider PLOC search and four times the reinsertion batch of the
        // medium one; its pre-splitting is not used here): on lavapipe the walk dominates a
        // deep model's ray-traced frame, and these trees took the 2CylinderEngine's from about
        // 73 to 66 ms at 1920×1080, for about twice the build time (docs/performance-log.md).
        let bvh = build_tree(&bounds, &BvhBuildParams::slow_build());
        // Rounding in the slab test is relative to the coordinates: widen every box by a few
        // thousand f32 units of the largest coordinate (and never by nothing).
        let largest = bounds
            .iter()
            .map(|b| b.0.min.abs().max(b.0.max.abs()).max_element())
            .fold(0.0f32, f32::max);
        let margin = (largest * 1e-5).max(1e-30);
        let nodes: Vec<GpuBvhNode> = bvh
            .nodes
            .iter()
            .map(|n| GpuBvhNode {
                min: (n.aabb.min - margin).to_array(),
                primitive_count: n.prim_count,
                max: (n.aabb.max + margin).to_array(),
                first: n.first_index,
            })
            .collect();
        let depth = tree_depth(&nodes);
        if depth + 1 > BVH_STACK_SIZE as usize {
            return Err(GpuError::BvhTooDeep {
                what: what(),
                depth,
                limit: BVH_STACK_SIZE as usize - 1,
            });
        }
        Ok(Self {
            nodes,
            primitives: bvh.primitive_indices,
            depth,
            margin,
        })
    }

    /// `items` (one per input triangle) in leaf order.
    #[must_use]
    pub fn in_leaf_order<T: Copy>(&self, items: &[T]) -> Vec<T> {
        self.primitives.iter().map(|&t| items[t as usize]).collect()
    }

    /// The root's box (widened): every triangle lies inside it.
    #[must_use]
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        (self.nodes[0].min, self.nodes[0].max)
    }

    /// The nearest hit of the half-line `origin + ψ·direction`, ψ > 0, with the triangles: the
    /// traversal of `rt.wgsl` (`bvh_nearest_hit`) in Rust, with `hit(t)` the distance ψ at which
    /// the ray meets input triangle `t`, if it does. Returns the triangle and ψ; ties keep the
    /// triangle found first. Test code only: the GPU walks the BVH, never the CPU.
    #[cfg(test)]
    pub fn nearest_hit(
        &self,
        origin: [f32; 3],
        direction: [f32; 3],
        mut hit: impl FnMut(u32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let inverse = safe_inverse(direction);
        let mut best: Option<(u32, f32)> = None;
        let limit = |best: Option<(u32, f32)>| best.map_or(f32::MAX, |(_, d)| d);
        box_entry(&self.nodes[0], origin, inverse, f32::MAX)?;
        let mut stack = Vec::with_capacity(BVH_STACK_SIZE as usize);
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.primitive_count > 0 {
                for k in n.first..n.first + n.primitive_count {
                    // The GPU reads the triangle at k of the reordered list: the same one.
                    let t = self.primitives[k as usize];
                    if let Some(d) = hit(t)
                        && d < limit(best)
                    {
                        best = Some((t, d));
                    }
                }
            } else {
                let (a, b) = (n.first as usize, n.first as usize + 1);
                let ea = box_entry(&self.nodes[a], origin, inverse, limit(best));
                let eb = box_entry(&self.nodes[b], origin, inverse, limit(best));
                match (ea, eb) {
                    (Some(ta), Some(tb)) => {
                        let (near, far) = if ta <= tb { (a, b) } else { (b, a) };
                        stack.push(far);
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            match stack.pop() {
                Some(next) => node = next,
                None => return best,
            }
        }
    }
}

/// Edges on the longest path from the root of `nodes` to a leaf.
fn tree_depth(nodes: &[GpuBvhNode]) -> usize {
    let mut deepest = 0;
    let mut pending = vec![(0usize, 0usize)];
    while let Some((node, depth)) = pending.pop() {
        deepest = deepest.max(depth);
        let n = &nodes[node];
        if n.primitive_count == 0 {
            pending.push((n.first as usize, depth + 1));
            pending.push((n.first as usize + 1, depth + 1));
        }
    }
    deepest
}

/// 1 / direction per axis, with components nearer 0 than 10⁻²⁰ replaced by 10⁻²⁰, so that the
/// slab test meets no infinity and no 0 × ∞ (mirror of `rt.wgsl`'s `safe_inverse`).
#[cfg(test)]
fn safe_inverse(direction: [f32; 3]) -> [f32; 3] {
    direction.map(|d| 1.0 / if d.abs() < 1e-20 { 1e-20 } else { d })
}

/// Where the ray enters `node`'s box (0 if it starts inside), if it meets the box before
/// `limit` (mirror of `rt.wgsl`'s `box_entry`). The exit is taken a few rounding units late,
/// so that a ray grazing a face still enters.
#[cfg(test)]
fn box_entry(node: &GpuBvhNode, origin: [f32; 3], inverse: [f32; 3], limit: f32) -> Option<f32> {
    let (mut near, mut far) = (0.0f32, f32::MAX);
    for axis in 0..3 {
        let a = (node.min[axis] - origin[axis]) * inverse[axis];
        let b = (node.max[axis] - origin[axis]) * inverse[axis];
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    (near <= far * SLAB_TOLERANCE && near <= limit).then_some(near)
}

/// Factor on the slab test's exit distance: 1 + 2γ₃ with γₙ = nε/(1 − nε), ε = 2⁻²⁴, covers
/// the rounding of the three operations per slab (Ize 2013, "Robust BVH ray traversal"),
/// rounded up to the next f32, 1 + 8ε (the value of WGSL `override SLAB_TOLERANCE` in bvh.wgsl).
pub const SLAB_TOLERANCE: f32 = 1.000_000_5;

/// The 8 corners and 12 triangles of the box `min`–`max`, as vertices of an upload: the
/// object's stand-in in the proxy pass, whose footprints bound where the ray tracer draws.
///
/// The triangles are wound *inward*, so that the proxy pass's back-face culling, when it
/// applies ([`crate::culling::box_near_faces_cullable`]), keeps the far faces: those a ray
/// leaves the box through. Every ray that reaches into the box from outside leaves it again,
/// so their footprints suffice, and measured tighter than the near faces' (the
/// 2CylinderEngine: 2.2 against 3.0 fragments per covered pixel).
#[must_use]
pub fn box_geometry(min: [f32; 3], max: [f32; 3]) -> (Vec<GpuVertex>, Vec<[u32; 3]>) {
    let vertices = (0..8u32)
        .map(|k| {
            let pick = |axis: u32| {
                if k >> axis & 1 == 1 {
                    max[axis as usize]
                } else {
                    min[axis as usize]
                }
            };
            GpuVertex {
                position: [pick(0), pick(1), pick(2), 1.0],
                normal: [0.0; 4],
                color: [1.0; 4],
                uv: [0.0; 4],
            }
        })
        .collect();
    // Corner k has x from bit 0, y from bit 1, z from bit 2; each face's corners in turn, its
    // triangles wound so that their normals point into the box.
    let faces = [
        [0, 2, 6, 4], // x = min
        [1, 5, 7, 3], // x = max
        [0, 4, 5, 1], // y = min
        [2, 3, 7, 6], // y = max
        [0, 1, 3, 2], // z = min
        [4, 6, 7, 5], // z = max
    ];
    let triangles = faces
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    (vertices, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A ray–triangle test in f32 (Cramer's rule) for the traversal's tests, which need only
    /// some hit per triangle (triangle.wgsl's watertight test runs on the GPU in
    /// tests/watertight.rs).
    fn intersect(origin: [f32; 3], direction: [f32; 3], p: [[f32; 3]; 3]) -> Option<f32> {
        let (o, d) = (Vec3A::from(origin), Vec3A::from(direction));
        let p = p.map(Vec3A::from);
        let (sigma, tau, b) = (p[1] - p[0], p[2] - p[0], o - p[0]);
        let q1 = d.cross(tau);
        let det = sigma.dot(q1);
        if det == 0.0 {
            return None;
        }
        let q2 = b.cross(sigma);
        let (psi, zeta, xi) = (tau.dot(q2) / det, b.dot(q1) / det, d.dot(q2) / det);
        (zeta >= 0.0 && xi >= 0.0 && zeta + xi <= 1.0 && psi > 0.0).then_some(psi)
    }

    fn soup(points: &[[f32; 3]]) -> Vec<[[f32; 3]; 3]> {
        points.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
    }

    fn coordinate() -> impl Strategy<Value = f32> {
        -10.0f32..10.0
    }

    fn point() -> impl Strategy<Value = [f32; 3]> {
        [coordinate(), coordinate(), coordinate()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The traversal finds the same nearest distance as testing every triangle, for random
        /// triangle soups (small and thin triangles, shared planes) and random rays.
        #[test]
        fn traversal_equals_testing_every_triangle(
            points in prop::collection::vec(point(), 3..600),
            rays in prop::collection::vec((point(), point()), 32),
            axis_aligned in any::<bool>(),
        ) {
            let mut points = points;
            points.truncate(points.len() / 3 * 3);
            if axis_aligned {
                // Every triangle in a plane z = integer: flat boxes, rays grazing them.
                for p in &mut points {
                    p[2] = p[2].round();
                }
            }
            let triangles = soup(&points);
            let bvh = ObjectBvh::build(&triangles, || "soup".into()).unwrap();
            for (origin, target) in rays {
                let d = Vec3A::from(target) - Vec3A::from(origin);
                if d.length() < 1e-3 {
                    continue;
                }
                let direction = d.normalize().to_array();
                let hit = |t: u32| intersect(origin, direction, triangles[t as usize]);
                let every = (0..triangles.len() as u32)
                    .filter_map(|t| hit(t).map(|d| (t, d)))
                    .min_by(|a, b| a.1.total_cmp(&b.1));
                let found = bvh.nearest_hit(origin, direction, hit);
                prop_assert_eq!(found.map(|f| f.1), every.map(|e| e.1));
            }
        }
    }

    #[test]
    fn rays_through_shared_edges_and_along_faces_hit() {
        // A unit square in z = 0 as two triangles; rays straight down through its diagonal
        // and corners, and one in the plane z = 0 (parallel: no hit, like the triangle test).
        let triangles = soup(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        let bvh = ObjectBvh::build(&triangles, || "square".into()).unwrap();
        let hit = |o: [f32; 3], d: [f32; 3]| {
            bvh.nearest_hit(o, d, |t| intersect(o, d, triangles[t as usize]))
        };
        for (x, y) in [(0.5, 0.5), (0.0, 0.0), (1.0, 1.0), (0.25, 0.25), (1.0, 0.0)] {
            let found = hit([x, y, 2.0], [0.0, 0.0, -1.0]);
            assert_eq!(found.map(|f| f.1), Some(2.0), "at ({x}, {y})");
        }
        assert_eq!(hit([-1.0, 0.5, 0.0], [1.0, 0.0, 0.0]), None);
        assert_eq!(hit([0.5, 0.5, 2.0], [0.0, 0.0, 1.0]), None);
    }

    #[test]
    fn the_box_mesh_faces_inward_and_covers_the_bounds() {
        let (vertices, triangles) = box_geometry([-1.0, -2.0, -3.0], [1.0, 2.0, 3.0]);
        assert_eq!((vertices.len(), triangles.len()), (8, 12));
        let mut area = 0.0;
        for t in triangles {
            let [a, b, c] = corners(&vertices, t).map(Vec3A::from);
            let normal = (b - a).cross(c - a);
            let centre = (a + b + c) / 3.0;
            assert!(normal.dot(centre) < 0.0, "triangle {t:?} faces outward");
            area += 0.5 * normal.length();
        }
        assert!((area - 2.0 * (2.0 * 4.0 + 2.0 * 6.0 + 4.0 * 6.0)).abs() < 1e-4);
    }

    #[test]
    fn the_slab_tolerance_is_one_plus_two_gamma_three_rounded_up() {
        let epsilon = 2f64.powi(-24);
        let gamma_3 = 3.0 * epsilon / (1.0 - 3.0 * epsilon);
        let wanted = 1.0 + 2.0 * gamma_3;
        assert!(
            f64::from(SLAB_TOLERANCE) >= wanted,
            "{SLAB_TOLERANCE} < {wanted}"
        );
        let below = f32::from_bits(SLAB_TOLERANCE.to_bits() - 1);
        assert!(f64::from(below) < wanted, "{below} would do");
    }

    #[test]
    fn a_single_triangle_is_a_leaf_root() {
        let triangles = soup(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        let bvh = ObjectBvh::build(&triangles, || "one".into()).unwrap();
        assert_eq!(bvh.depth, 0);
        assert_eq!(bvh.nodes[0].primitive_count, 1);
        let (min, max) = bvh.bounds();
        assert!(min[2] < 0.0 && max[2] > 0.0, "a flat box is widened");
    }
}
