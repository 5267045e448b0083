//! The three pictures of a moving object (docs/physics.md, "Three pictures"): what is *seen*
//! (the apparent picture of light travel time and aberration, Eq. 5–8), what is *measured*
//! (every material point where it is at the observer's time ct_obs in S: Lorentz-contracted) and
//! the *Newtonian* picture (the rest shape, uncontracted, where its origin is at ct_obs).
//!
//! The measured and Newtonian pictures are exact transformations of a [`Scene`] into a scene of
//! objects at rest in S (β = 0), which every renderer draws without light-travel distortion and
//! with Doppler factor 1. The geometry of both is independent of ct_obs; only each object's
//! offset moves with it.

use glam::{DMat3, DMat4, DVec3};
use srt_physics::motion::Motion;
use srt_physics::{Frame, FrameError};

use crate::mesh::MeshError;
use crate::scene::{Object, Scene};
use crate::sky::Sky;

/// Which picture of the scene to render.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum View {
    /// The apparent picture: what a camera records (the scene unchanged).
    #[default]
    Seen,
    /// Every point where it is at S time ct_obs: Lorentz-contracted along β, at rest.
    Measured,
    /// The rest shape, uncontracted, translated to where its origin is at S time ct_obs.
    Newtonian,
}

/// Why a scene could not be brought into a view.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ViewError {
    /// The object's new frame is invalid (a non-finite offset).
    #[error("object {object}: {source}")]
    Frame {
        /// The object's name.
        object: String,
        /// What was wrong.
        source: FrameError,
    },
    /// The measured picture of a spinning or thrusting body (each point would need its own
    /// S′ time) is not drawn.
    #[error(
        "object {object}: the measured view of a spinning or thrusting object is not drawn; \
         try seen or newtonian"
    )]
    MeasuredMotion {
        /// The object's name.
        object: String,
    },
    /// The transformed mesh is invalid (non-finite positions).
    #[error("object {object}: {source}")]
    Mesh {
        /// The object's name.
        object: String,
        /// What was wrong.
        source: MeshError,
    },
}

crate::choice!(View, "view", {
    Seen => "seen",
        "what a camera sees: light travel time, aberration, Doppler (the paper's picture)";
    Measured => "measured",
        "what is measured: every point where it is at ct_obs in S, Lorentz-contracted, no Doppler";
    Newtonian => "newtonian",
        "the Newtonian picture: the rest shape, uncontracted, where it is at ct_obs, no Doppler";
});

impl View {
    /// `scene` as this view shows it at its observation time `scene.observer.ct`: unchanged for
    /// [`View::Seen`], otherwise every object replaced by one at rest in S (see the module doc).
    ///
    /// # Errors
    /// [`ViewError`] if a transformed position or offset is not finite.
    pub fn apply(self, scene: &Scene) -> Result<Scene, ViewError> {
        let mut viewed = scene.clone();
        if self == Self::Seen {
            return Ok(viewed);
        }
        let ct = scene.observer.time;
        for object in &mut viewed.objects {
            self.apply_to_object(object, ct)?;
        }
        self.apply_to_sky(&mut viewed.sky);
        Ok(viewed)
    }

    /// Brings the sky into this view (not [`View::Seen`]): at rest in S, so without aberration
    /// and Doppler shift; a direction at infinity is where it points in W (Newtonian) or,
    /// measured, where the contraction by 1/γ along W's velocity takes it (`direction_map`).
    fn apply_to_sky(self, sky: &mut Sky) {
        if self == Self::Measured
            && let Ok(world) = Frame::new(sky.beta, DVec3::ZERO)
        {
            sky.direction_map = measured_shape(&world, 0.0) * sky.direction_map;
        }
        sky.beta = DVec3::ZERO;
    }

    /// Replaces `object` by its static picture at S time `ct` (not [`View::Seen`]).
    fn apply_to_object(self, object: &mut Object, ct: f64) -> Result<(), ViewError> {
        let frame = object.frame;
        let mut origin_now = frame.event_at_time(DVec3::ZERO, ct).position;
        if !object.motion.is_rest() {
            if self == Self::Measured {
                return Err(ViewError::MeasuredMotion {
                    object: object.name.clone(),
                });
            }
            // Newtonian: the rest shape, turned as far as a spin has turned it and placed where
            // a thrust has carried its origin, at the S′ time of the origin's event at S time
            // `ct`.
            let (rest_ct, placement) = newtonian_placement(object, ct);
            // A spin turns the shape about its centre within the frame; a thrust carries the
            // shape's origin along.
            let carried = match object.motion {
                Motion::Thrust(_) => object
                    .motion
                    .position(DVec3::ZERO, object.proper_time(rest_ct)),
                Motion::Rest | Motion::Spin(_) => DVec3::ZERO,
            };
            origin_now = frame
                .to_observer(srt_physics::Event::new(rest_ct, carried))
                .position;
            let name = object.name.clone();
            for part in &mut object.parts {
                part.mesh =
                    part.mesh
                        .clone()
                        .transformed(placement)
                        .map_err(|source| ViewError::Mesh {
                            object: name.clone(),
                            source,
                        })?;
            }
            object.motion = Motion::Rest;
        }
        if self == Self::Measured {
            let shape = DMat4::from_mat3(measured_shape(&frame, ct));
            for part in &mut object.parts {
                part.mesh =
                    part.mesh
                        .clone()
                        .transformed(shape)
                        .map_err(|source| ViewError::Mesh {
                            object: object.name.clone(),
                            source,
                        })?;
            }
        }
        object.frame = Frame::new(DVec3::ZERO, origin_now).map_err(|source| ViewError::Frame {
            object: object.name.clone(),
            source,
        })?;
        Ok(())
    }
}

/// The rest-coordinates time of the event of the moving body's origin that S sees at S time
/// `ct`, and the rest-frame transformation of its Newtonian picture there: the spin's rotation
/// about its centre (a thrust keeps the rest shape, carried with its origin).
fn newtonian_placement(object: &Object, ct: f64) -> (f64, DMat4) {
    let frame = object.frame;
    let s_time = |rest_ct: f64| {
        let body_ct = object.proper_time(rest_ct);
        frame
            .to_observer(srt_physics::Event::new(
                rest_ct,
                object.motion.position(DVec3::ZERO, body_ct),
            ))
            .ct
    };
    // The origin's S time grows with its rest time (its worldline is timelike): bisect.
    let (mut lo, mut hi) = (ct - 1e9, ct + 1e9);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if s_time(mid) < ct {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let rest_ct = 0.5 * (lo + hi);
    let placement = match object.motion {
        Motion::Spin(spin) => {
            let turn = DMat4::from_quat(spin.rotation(object.proper_time(rest_ct)));
            DMat4::from_translation(spin.centre()) * turn * DMat4::from_translation(-spin.centre())
        }
        Motion::Rest | Motion::Thrust(_) => DMat4::IDENTITY,
    };
    (rest_ct, placement)
}

/// The linear map L taking a rest-frame offset x′ (from the S′ origin) to the offset, in S, of the
/// measured positions at S time `ct`: x(x′) − x(0) with x from
/// [`Frame::event_at_time`]. The map is affine, so its columns are the images of the unit
/// vectors; it equals I + (1/γ − 1) β̂β̂ᵀ, a contraction by 1/γ along β. Normals transform with
/// L^{−T} ([`Mesh::transformed`](crate::Mesh::transformed)).
fn measured_shape(frame: &Frame, ct: f64) -> DMat3 {
    let origin = frame.event_at_time(DVec3::ZERO, ct).position;
    let image = |axis: DVec3| frame.event_at_time(axis, ct).position - origin;
    DMat3::from_cols(image(DVec3::X), image(DVec3::Y), image(DVec3::Z))
}
