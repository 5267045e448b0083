//! The back-face culling rule, in one place: the renderer sets
//! [`PartFlags::CULL_BACK_FACES`](crate::types::PartFlags::CULL_BACK_FACES) by it every frame,
//! and `cargo xtask validate` checks every culled triangle against it.
//!
//! In S′ every viewing ray starts at the observer's rest-frame position, so the rest-frame
//! picture is an ordinary pinhole view from there: for a closed solid with outward fronts and
//! the observer outside it, a triangle facing away from the observer is hidden. The proxy pass
//! (`proxy.wgsl`) then gives such a triangle an empty footprint.

use srt_physics::{Event, Frame};
use srt_scene::Mesh;

/// Whether a mesh may have its back faces culled at all (computed once per upload).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BackFaceCulling {
    closed_outward: bool,
}

impl BackFaceCulling {
    /// The rule for `mesh`: cullable when it is a closed solid with outward fronts.
    #[must_use]
    pub fn for_mesh(mesh: &Mesh) -> Self {
        Self {
            closed_outward: mesh.is_closed_outward(),
        }
    }

    /// Whether back faces of `mesh` (the one this rule was made for), at rest in `frame`, may
    /// be culled for the observation event `observer`: the mesh is closed and the observer's
    /// rest-frame position lies outside it (winding number ≈ 0).
    #[must_use]
    pub fn applies(self, mesh: &Mesh, frame: &Frame, observer: Event) -> bool {
        self.closed_outward && mesh.winding_number(frame.to_rest(observer).position).abs() < 0.5
    }
}

/// Whether the ray tracer may cull the faces of an object's box `min`–`max` (in S′) that are
/// turned towards an observer at `observer` (S′; the box is wound inward, so the proxy pass's
/// back-face test culls those): only when the observer is outside the box by more than f32
/// rounding can blur, on the outer side of some face plane and off every face plane. A ray from
/// outside that reaches into a box leaves it again through a face turned away from its origin,
/// so the footprints of those faces then hold every pixel that sees into the box; otherwise all
/// twelve triangles are drawn.
#[must_use]
pub fn box_near_faces_cullable(min: [f32; 3], max: [f32; 3], observer: glam::DVec3) -> bool {
    let size = (0..3)
        .map(|axis| f64::from(max[axis] - min[axis]).abs())
        .fold(0.0, f64::max);
    let reach = (0..3)
        .map(|axis| f64::from(min[axis].abs().max(max[axis].abs())).max(observer[axis].abs()))
        .fold(0.0, f64::max);
    let tolerance = 1e-4 * (size + reach);
    let mut outside = false;
    for axis in 0..3 {
        let below = f64::from(min[axis]) - observer[axis];
        let above = observer[axis] - f64::from(max[axis]);
        if below.abs() <= tolerance || above.abs() <= tolerance {
            return false;
        }
        outside |= below > 0.0 || above > 0.0;
    }
    outside
}

#[cfg(test)]
mod tests {
    use super::box_near_faces_cullable;
    use glam::DVec3;

    #[test]
    fn box_faces_are_culled_only_from_clearly_outside() {
        let (min, max) = ([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]);
        assert!(box_near_faces_cullable(min, max, DVec3::new(5.0, 0.0, 0.0)));
        assert!(box_near_faces_cullable(
            min,
            max,
            DVec3::new(-3.0, 4.0, 2.0)
        ));
        assert!(!box_near_faces_cullable(min, max, DVec3::ZERO), "inside");
        assert!(
            !box_near_faces_cullable(min, max, DVec3::new(1.0 + 1e-7, 0.0, 0.0)),
            "on a face"
        );
        assert!(
            !box_near_faces_cullable(min, max, DVec3::new(5.0, 1.0, 0.0)),
            "in the plane of a face seen edge-on"
        );
    }
}
