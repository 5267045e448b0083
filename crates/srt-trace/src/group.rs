//! Velocity groups: the objects of a scene that move with one velocity. Their rest frames
//! differ only by a translation, so a backward ray has one direction in all of them and one
//! origin up to a fixed shift per object. The group's bodies at rest are found along a ray
//! through one BVH over their boxes, shifted into the first member's rest coordinates and taken
//! nearest first: a ray past many objects (the flythrough's 45 columns and slabs) searches the
//! few whose boxes it meets before a nearer hit, not every one.
//!
//! The group's BVH only chooses which objects to search and stops the search early; each
//! object chosen is searched in its own coordinates as before ([`PreparedObject`]), so the hit
//! found does not depend on the grouping.

use glam::DVec3;
use srt_physics::{Event, Frame, RestRay};

use crate::prepared::{Hit, PreparedObject};
use crate::walk::{FlatBvh, nearest_first};

/// A backward ray's unit direction in a velocity group's rest frames and its reciprocal per
/// component (for slab tests).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct RestDirection {
    /// The unit direction.
    pub(crate) direction: DVec3,
    /// 1 / `direction`, per component.
    pub(crate) inverse: DVec3,
}

impl RestDirection {
    /// The unit `direction` and its reciprocal.
    pub(crate) fn new(direction: DVec3) -> Self {
        Self {
            direction,
            inverse: direction.recip(),
        }
    }
}

/// A velocity group of a scene's objects.
pub(crate) struct VelocityGroup {
    /// The member whose rest coordinates are the group's (its lowest index).
    first: usize,
    /// Members that spin or thrust: searched along every ray, as their bodies leave any box.
    moving: Vec<usize>,
    /// The resting members, in the order of the leaves of `bvh`.
    resting: Vec<usize>,
    /// A BVH over the resting members' boxes in the group's rest coordinates; `None` for a
    /// group of at most one resting member, whose own box test is the whole cull.
    bvh: Option<FlatBvh>,
}

impl VelocityGroup {
    /// The groups of `objects`, in the order of their first members.
    pub(crate) fn of_objects(objects: &[PreparedObject<'_>]) -> Vec<Self> {
        let mut members: Vec<Vec<usize>> = Vec::new();
        for (index, object) in objects.iter().enumerate() {
            let beta = object.frame.beta();
            match (members.iter_mut()).find(|group| objects[group[0]].frame.beta() == beta) {
                Some(group) => group.push(index),
                None => members.push(vec![index]),
            }
        }
        members
            .into_iter()
            .map(|group| Self::new(objects, &group))
            .collect()
    }

    /// The group of `members` (indices into `objects`, ascending, one velocity).
    fn new(objects: &[PreparedObject<'_>], members: &[usize]) -> Self {
        let first = members[0];
        let origin = objects[first].observer_rest.position;
        let (resting, moving): (Vec<usize>, Vec<usize>) =
            (members.iter()).partition(|&&index| objects[index].motion.is_rest());
        let boxes: Vec<(DVec3, DVec3)> = (resting.iter())
            .map(|&index| {
                let object = &objects[index];
                // The same event has coordinates shifted by `shift` in the group's rest frame
                // (the frames' Lorentz parts are equal); the box is padded well beyond the
                // rounding of the shift, so that it never culls a body the ray meets.
                let shift = origin - object.observer_rest.position;
                let (lo, hi) = object.bounds;
                let scale = 1.0 + origin.abs().max_element() + lo.abs().max(hi.abs()).max_element();
                let pad = DVec3::splat(1e-9 * scale);
                (lo + shift - pad, hi + shift + pad)
            })
            .collect();
        let (bvh, resting) = match FlatBvh::build(boxes.len(), |i| boxes[i]) {
            Some((bvh, order)) if order.len() > 1 => (
                Some(bvh),
                order.iter().map(|&leaf| resting[leaf as usize]).collect(),
            ),
            _ => (None, resting),
        };
        Self {
            first,
            moving,
            resting,
            bvh,
        }
    }

    /// The backward ray's direction in the group's rest frames for the viewing direction
    /// `view_direction` (in S): Eq. 3 ([`srt_physics::Frame::rest_direction`]), the same in
    /// every member's frame.
    pub(crate) fn rest_direction(
        &self,
        objects: &[PreparedObject<'_>],
        view_direction: DVec3,
    ) -> RestDirection {
        RestDirection::new(self.frame(objects).rest_direction(view_direction))
    }

    /// The frame whose [`srt_physics::Frame::rest_direction`] gives the group's backward rays
    /// (its first member's: every member's gives the same).
    pub(crate) fn frame<'o>(&self, objects: &'o [PreparedObject<'_>]) -> &'o Frame {
        &objects[self.first].frame
    }

    /// Searches the group's members along the backward ray whose direction in their rest
    /// frames is `direction` ([`VelocityGroup::rest_direction`]) from the observation event
    /// whose rest-frame coordinates in a member's frame are `origin_of(member)`, keeping in
    /// `best` the hit seen in front of all others so far.
    pub(crate) fn search(
        &self,
        objects: &[PreparedObject<'_>],
        RestDirection { direction, inverse }: RestDirection,
        origin_of: &impl Fn(&PreparedObject<'_>) -> Event,
        best: &mut Option<Hit>,
    ) {
        let frame = &objects[self.first].frame;
        let inverse_direction = inverse;
        // The apparent distance grows linearly along the ray (γ s (1 − β·d′), the same for
        // every member), so a hit beyond `best` need not be searched for; the bound is
        // widened by a relative 1e-12 so that rounding never prunes a closer hit.
        let along = RestRay {
            origin: DVec3::ZERO,
            direction,
            ct_origin: 0.0,
        };
        let per_unit = frame.apparent_distance(&along, 1.0);
        let limit = |best: &Option<Hit>| {
            (best.as_ref()).map_or(f64::INFINITY, |b| {
                b.apparent_distance / per_unit * (1.0 + 1e-12)
            })
        };
        let search_member = |index: usize, best: &mut Option<Hit>| {
            let object = &objects[index];
            let origin = origin_of(object);
            let limit = limit(best);
            if !object.may_be_met(origin.position, inverse_direction, limit) {
                return;
            }
            let ray = RestRay {
                origin: origin.position,
                direction,
                ct_origin: origin.ct,
            };
            if let Some(hit) = object.closest_hit_seen(index, &ray, limit, best.as_ref()) {
                *best = Some(hit);
            }
        };
        match &self.bvh {
            Some(bvh) => {
                let origin = origin_of(&objects[self.first]).position;
                // Members come nearer box first; none whose box starts beyond the best hit.
                nearest_first(bvh, origin, inverse_direction, limit(best), |member, _| {
                    search_member(self.resting[member], best);
                    limit(best)
                });
            }
            None => (self.resting.iter()).for_each(|&member| search_member(member, best)),
        }
        for &index in &self.moving {
            search_member(index, best);
        }
    }
}
