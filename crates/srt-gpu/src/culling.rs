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
