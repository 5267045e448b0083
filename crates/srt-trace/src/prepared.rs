//! What the reference tracer prepares of each object before any ray: its parts, one BVH over
//! all their triangles in its rest frame S′ (where it is static), its bounds and its motion; and
//! the nearest [`Hit`] a backward ray finds on it (Eq. 5, 15–16). `moving.rs` adds the search of
//! a spinning or thrusting body's triangles to the same object.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{DVec3, DVec4};
use rayon::prelude::*;
use srt_physics::motion::Motion;
use srt_physics::{Event, Frame, RestRay};
use srt_scene::mip::MipChain;
use srt_scene::{Object, Part, Texture};

use crate::intersect::{ShearedRay, TriangleHit};
use crate::shared::{ObjectBvh, PartTriangle, SharedBvhs};
use crate::walk::{FlatBvh, box_entry, nearest_first};

/// The mip chains of a scene's textures, each made once however many parts share its texture
/// (the scene's builder shares one texture among the parts that describe the same one).
#[derive(Default)]
pub(crate) struct MipChains(HashMap<*const Texture, Arc<MipChain>>);

impl MipChains {
    /// The chain of `texture`, made on first use.
    fn of(&mut self, texture: &Arc<Texture>) -> Arc<MipChain> {
        Arc::clone(
            self.0
                .entry(Arc::as_ptr(texture))
                .or_insert_with(|| Arc::new(MipChain::new(texture))),
        )
    }
}

/// One part's material: its filtered texture and base colour.
pub(crate) struct PreparedPart<'a> {
    pub(crate) part: &'a Part,
    pub(crate) texture: Option<Arc<MipChain>>,
    pub(crate) base_color: DVec4,
}

impl<'a> PreparedPart<'a> {
    fn new(part: &'a Part, chains: &mut MipChains) -> Self {
        let [r, g, b, a] = part.material.base_color.map(f64::from);
        Self {
            part,
            texture: part.material.texture.as_ref().map(|t| chains.of(t)),
            base_color: DVec4::new(r, g, b, a),
        }
    }
}

/// One rigid object: its frame, its parts and one BVH over the triangles of all of them (in
/// its rest frame S′, where it is static), so a ray walks one hierarchy per object, not one per
/// part.
pub(crate) struct PreparedObject<'a> {
    pub(crate) frame: Frame,
    /// The observation event in the object's rest frame S′ (the start of every backward ray).
    pub(crate) observer_rest: Event,
    pub(crate) parts: Vec<PreparedPart<'a>>,
    /// The BVH over the triangles of all parts and its leaves' triangles (shared with the
    /// objects whose triangles are the same, [`SharedBvhs`]); `None` for an object without
    /// triangles.
    pub(crate) bvh: Option<Arc<ObjectBvh>>,
    /// How the body moves in its rest coordinates (the BVH holds it at S′ time 0).
    pub(crate) motion: Motion,
    /// The rest coordinates' clock lead over the object's S′ time.
    rest_time_shift: f64,
    /// A spinning body's largest distance from its spin centre; otherwise its size (the
    /// diagonal of its box).
    pub(crate) reach: f64,
    /// A spinning body's extent along its axis (from the centre): a slab it never leaves.
    pub(crate) axial: (f64, f64),
    /// The box around all its triangles (padded like theirs): a ray that misses it, or meets
    /// it only beyond a nearer hit, is not traced through the BVH.
    pub(crate) bounds: (DVec3, DVec3),
    pub(crate) wireframe: Option<f64>,
}

impl<'a> PreparedObject<'a> {
    pub(crate) fn new(
        object: &'a Object,
        observer: Event,
        chains: &mut MipChains,
        bvhs: &mut SharedBvhs<'a>,
    ) -> Self {
        let meshes = || object.parts.iter().map(|part| &part.mesh);
        let extent = object.body_extent();
        let (lo, hi) = extent.bounds;
        // Pad boxes a little so that flat (axis-aligned) triangles never have zero-thickness
        // boxes, which slab tests can miss.
        let pad = 1e-9 * (hi - lo).length().max(1.0);
        // Built over the triangles' boxes (triangle `i` of the object counted through its parts
        // in turn), their corners copied in leaf order after.
        let build = || -> Option<ObjectBvh> {
            let starts: Vec<usize> = (meshes())
                .scan(0, |start, mesh| {
                    let first = *start;
                    *start += mesh.triangles().len();
                    Some(first)
                })
                .collect();
            let count = meshes().map(|mesh| mesh.triangles().len()).sum();
            // The part and the triangle within it of the object's triangle `i`.
            let id = |i: usize| {
                let part = starts.partition_point(|&start| start <= i) - 1;
                (part as u32, (i - starts[part]) as u32)
            };
            let corners = |(part, triangle): (u32, u32)| {
                object.parts[part as usize]
                    .mesh
                    .triangle_positions(triangle as usize)
            };
            let (bvh, order) = FlatBvh::build(count, |i| {
                let [a, b, c] = corners(id(i));
                (a.min(b).min(c) - pad, a.max(b).max(c) + pad)
            })?;
            let triangles = (order.par_iter())
                .map(|&leaf| {
                    let (part, triangle) = id(leaf as usize);
                    PartTriangle {
                        corners: corners((part, triangle)),
                        part,
                        triangle,
                    }
                })
                .collect();
            Some((bvh, triangles))
        };
        let bvh = bvhs.of(&object.parts, pad, build);
        Self {
            frame: object.frame,
            observer_rest: object.frame.to_rest(observer),
            parts: (object.parts.iter())
                .map(|part| PreparedPart::new(part, chains))
                .collect(),
            bvh,
            motion: object.motion,
            rest_time_shift: object.rest_time_shift,
            reach: extent.reach,
            axial: extent.axial.unwrap_or((f64::NEG_INFINITY, f64::INFINITY)),
            bounds: (lo - pad, hi + pad),
            wireframe: object.wireframe,
        }
    }

    /// Closest hit along a rest-frame ray of the body at rest, at distance `from` or more and
    /// no farther than `limit` (beyond it a hit may still be returned; nothing beyond is
    /// searched for): (part, triangle, hit). Of hits at the same distance the one with the
    /// lowest (part, triangle) wins, whatever the traversal order.
    pub(crate) fn closest_hit_between(
        &self,
        ray: &RestRay,
        from: f64,
        limit: f64,
    ) -> Option<(u32, u32, TriangleHit)> {
        let (bvh, triangles) = &**self.bvh.as_ref()?;
        let sheared = ShearedRay::new(ray.origin, ray.direction);
        let mut best: Option<(u32, u32, TriangleHit)> = None;
        // Nothing beyond the best hit (or `limit`) is searched for.
        nearest_first(
            bvh,
            ray.origin,
            ray.direction.recip(),
            limit,
            |leaf, bound| {
                let leaf = &triangles[leaf];
                if let Some(hit) = sheared
                    .intersect(&leaf.corners)
                    .filter(|hit| hit.distance >= from)
                {
                    let closer = best.is_none_or(|(part, triangle, b)| {
                        (hit.distance, leaf.part, leaf.triangle) < (b.distance, part, triangle)
                    });
                    if closer {
                        best = Some((leaf.part, leaf.triangle, hit));
                    }
                }
                best.map_or(bound, |(_, _, hit)| hit.distance.min(bound))
            },
        );
        best
    }

    /// Whether the body crosses the null segment from the rest-frame event `at` back to the
    /// earlier event `source` strictly between its ends (a margin of 10⁻⁹ of the segment's
    /// scale at each end keeps the surface point the segment starts on, and the light it ends
    /// at, out of it). At rest the body is tested along the straight segment; a spinning or
    /// thrusting one as a backward ray is ([`PreparedObject::closest_hit_moving`]).
    pub(crate) fn blocks(&self, at: Event, source: Event) -> bool {
        let (from, to) = (at.position, source.position);
        let (Some((bvh, triangles)), length) = (self.bvh.as_deref(), (to - from).length()) else {
            return false;
        };
        let direction = (to - from) / length;
        let margin = 1e-9 * (1.0 + length + from.abs().max_element());
        if length <= 2.0 * margin || length.is_nan() {
            return false;
        }
        if !self.motion.is_rest() {
            let ray = RestRay {
                origin: from,
                direction,
                ct_origin: at.ct,
            };
            return (self.closest_hit_moving(&ray, self.rest_time_shift, length - margin))
                .is_some_and(|(_, _, hit)| {
                    hit.distance > margin && hit.distance < length - margin
                });
        }
        let (lo, hi) = self.bounds;
        if box_entry(from, direction.recip(), lo, hi).is_none_or(|entry| entry > length) {
            return false;
        }
        // The walk stops (its bound below every entry) at the first triangle crossed.
        let sheared = ShearedRay::new(from, direction);
        let mut crossed = false;
        nearest_first(bvh, from, direction.recip(), length, |leaf, bound| {
            crossed = (sheared.intersect(&triangles[leaf].corners))
                .is_some_and(|hit| hit.distance > margin && hit.distance < length - margin);
            if crossed { f64::NEG_INFINITY } else { bound }
        });
        crossed
    }

    /// Whether a ray from `origin` (`inverse_direction` = 1 / its direction per component) can
    /// meet this object no farther than `limit` along it: a body at rest only if it meets its
    /// box by then; a moving one always (its search bounds itself).
    pub(crate) fn may_be_met(&self, origin: DVec3, inverse_direction: DVec3, limit: f64) -> bool {
        let (lo, hi) = self.bounds;
        !self.motion.is_rest()
            || box_entry(origin, inverse_direction, lo, hi).is_some_and(|entry| entry <= limit)
    }

    /// The hit of this object (number `index` in the scene) along `ray`, searched no farther
    /// than `limit` along it, if it is seen in front of `best`, the closest hit of the objects
    /// searched so far: nearer, or as near and of a lower index, so that the result does not
    /// depend on the order objects are searched in.
    pub(crate) fn closest_hit_seen(
        &self,
        index: usize,
        ray: &RestRay,
        limit: f64,
        best: Option<&Hit>,
    ) -> Option<Hit> {
        let (part, triangle, rest_hit) =
            self.closest_hit_moving(ray, self.rest_time_shift, limit)?;
        let apparent_distance = self.frame.apparent_distance(ray, rest_hit.distance);
        let seen =
            best.is_none_or(|b| (apparent_distance, index) < (b.apparent_distance, b.object));
        seen.then(|| {
            let emission_rest = ray.event_at(rest_hit.distance);
            Hit {
                object: index,
                part: part as usize,
                triangle: triangle as usize,
                rest_hit,
                ray: *ray,
                emission_rest,
                emission: self.frame.to_observer(emission_rest),
                apparent_distance,
                eye: DVec3::ZERO,
            }
        })
    }
}

/// The closest surface point along one viewing direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Index of the object in the scene.
    pub object: usize,
    /// Index of the part within the object.
    pub part: usize,
    /// Index of the triangle within the part's mesh.
    pub triangle: usize,
    /// Barycentric hit data in S′.
    pub rest_hit: TriangleHit,
    /// The backward ray in S′ that found it.
    pub ray: RestRay,
    /// Emission event in S′ (Eq. 7).
    pub emission_rest: Event,
    /// Emission event in S (Eq. 8): its position is the apparent position.
    pub emission: Event,
    /// Apparent distance from the observer (= light travel time, ct_obs − ct_emission).
    pub apparent_distance: f64,
    /// The offset (in S) from the observer of the eye whose ray found it: zero but for a
    /// stereo pair ([`srt_scene::Stereo`]).
    pub eye: DVec3,
}
