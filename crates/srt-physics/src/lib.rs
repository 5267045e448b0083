//! Exact special relativity for rendering, in `f64`.
//!
//! This crate implements §3.1–3.2 and the Doppler parts of §4.2 of Müller, Grottel and Weiskopf,
//! *Special Relativistic Visualization by Local Ray Tracing* (IEEE TVCG 2010). Equation numbers in
//! the documentation are the paper's.
//!
//! Conventions (see `docs/physics.md`):
//! - units with c = 1; an event is (ct, x, y, z) and four-vector matrices act on column vectors in
//!   that order;
//! - S is the observer's frame; every object rests in its own frame S′ that moves with velocity
//!   β (|β| < 1) relative to S and whose origin is at `offset` (the paper's **a**) at t = t′ = 0;
//!   an observer moving through a world frame W is brought into this setting by
//!   [`MovingObserver`] (boosts composed as matrices, Wigner rotation included);
//! - a light four-vector is k = ω(1, n) with n the *propagation* direction (emitter → receiver);
//! - a Doppler factor is D = ω_received / ω_emitted, so D > 1 is a blue shift.
//!
//! ```
//! use glam::DVec3;
//! use srt_physics::{Event, Frame};
//!
//! // A cube corner moving towards an observer at the origin at 0.9c.
//! let frame = Frame::new(DVec3::new(0.0, 0.0, 0.9), DVec3::new(0.0, 0.0, -20.0))?;
//! let observer = Event::new(0.0, DVec3::ZERO);
//! let seen_at = frame.apparent_position(DVec3::new(1.0, 1.0, 1.0), observer);
//! // Light left the corner long ago, when it was much farther away than it is "now".
//! assert!(seen_at.z < -20.0);
//! # Ok::<(), srt_physics::FrameError>(())
//! ```

mod event;
pub mod flight;
mod frame;
mod light;
mod lorentz;
pub mod motion;
mod observer;
pub mod optics;
mod retarded;
mod velocity;

pub use event::{Event, minkowski_interval};
pub use frame::{DIRECTION_LANES, Frame, FrameError, RestRay};
pub use light::{
    Aberration, LightVector, aberrate, distant_source_image, doppler_factor, receiver_doppler,
    reflection_doppler,
};
pub use lorentz::{compose_velocities, lorentz_factor, lorentz_matrix, rapidity, validate_beta};
pub use observer::{MovingObserver, Poincare, RelativeFrame, boost_and_rotation};
pub use retarded::RetardedLight;
pub use velocity::FourVelocity;

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
