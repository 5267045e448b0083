//! Relativistic flight: the worldline of an observer driven by a proper acceleration, integrated
//! exactly, one step of proper time at a time.
//!
//! The state is an event and a four-velocity u = γ(1, β) in the world frame W, and the proper
//! time τ elapsed (c = 1, so τ, ct and lengths share one unit). A step applies a constant proper
//! acceleration α along a direction n̂ fixed in the observer's instantaneous rest frame S (the
//! frame [`MovingObserver`](crate::MovingObserver) uses: reached from W by the pure boost
//! Λ_−β, axes parallel to W's). In S the step is hyperbolic motion (Rindler, *Relativity:
//! Special, General, and Cosmological*, 2nd ed., §3.8; Misner, Thorne & Wheeler, *Gravitation*,
//! §6.2):
//!
//! ```text
//! u_S(τ) = (cosh ατ, sinh ατ n̂),   Δx_S(τ) = (sinh(ατ)/α, (cosh(ατ) − 1)/α n̂),
//! ```
//!
//! so along a fixed direction the rapidity grows linearly, φ = φ₀ + ατ. Both four-vectors are
//! brought back to W by the boost Λ_β of Eq. 2: u_W = Λ_β u_S, Δx_W = Λ_β Δx_S. Velocities are
//! never added; a change of direction composes boosts as matrices, as `observer.rs` does, so
//! steps of any size give the same worldline for a constant acceleration along a fixed axis.

use glam::{DMat4, DVec3, DVec4};

use crate::event::Event;
use crate::frame::FrameError;
use crate::light::doppler_factor;
use crate::lorentz::validate_beta;
use crate::velocity::FourVelocity;

/// Below this |α dτ| the hyperbolic functions are replaced by their Taylor series' leading
/// terms (relative error below 10⁻¹⁶).
const SMALL_ANGLE: f64 = 1e-8;

/// The worldline state of a flying observer, in the world frame W.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Worldline {
    /// The observer's current event (ct, x) in W.
    pub event: Event,
    /// The four-velocity u = γ(1, β) in W, as a column (γ, γβ) stored (x, y, z, w).
    pub four_velocity: DVec4,
    /// Proper time cτ elapsed on the observer's clock since the flight started.
    pub proper_time: f64,
}

impl Worldline {
    /// An observer at `event` moving with `beta` through W, its clock at τ = 0.
    ///
    /// # Errors
    /// [`FrameError`] for a velocity that is not finite or not below the speed of light, or an
    /// event that is not finite.
    pub fn new(event: Event, beta: DVec3) -> Result<Self, FrameError> {
        let beta = validate_beta(beta)?;
        if !event.is_finite() {
            return Err(FrameError::NonFinite {
                what: "observation event",
            });
        }
        let gamma = 1.0 / (1.0 - beta.length_squared()).sqrt();
        Ok(Self {
            event,
            four_velocity: gamma * DVec4::new(1.0, beta.x, beta.y, beta.z),
            proper_time: 0.0,
        })
    }

    /// The spatial part γβ of the four-velocity.
    #[must_use]
    pub fn spatial_velocity(&self) -> DVec3 {
        DVec3::new(
            self.four_velocity.y,
            self.four_velocity.z,
            self.four_velocity.w,
        )
    }

    /// The velocity β = (γβ)/γ through W (|β| < 1 while γβ is below about 10⁸).
    #[must_use]
    pub fn beta(&self) -> DVec3 {
        self.spatial_velocity() / self.four_velocity.x
    }

    /// The Lorentz factor γ, the time part of the four-velocity.
    #[must_use]
    pub fn gamma(&self) -> f64 {
        self.four_velocity.x
    }

    /// The rapidity φ = arsinh |γβ| (= artanh |β|, accurate also when |β| is close to 1).
    #[must_use]
    pub fn rapidity(&self) -> f64 {
        self.spatial_velocity().length().asinh()
    }

    /// Doppler factors of light from sources at rest in W, received straight ahead (along the
    /// direction of motion) and straight behind: √((1+β)/(1−β)) and its inverse. In the
    /// observer's frame the sources move with −β, so this is [`doppler_factor`] of Eq. 4 with
    /// the light propagating along ∓β̂. At rest both are 1.
    #[must_use]
    pub fn doppler_ahead_and_behind(&self) -> (f64, f64) {
        let beta = self.beta();
        let ahead = beta.try_normalize().unwrap_or(DVec3::X);
        (doppler_factor(-beta, -ahead), doppler_factor(-beta, ahead))
    }

    /// The worldline after `dtau` of proper time under the proper acceleration `acceleration`
    /// (its length α in 1/length, c = 1; its direction n̂ in the instantaneous rest frame S),
    /// by the hyperbolic-motion step of the module doc. A zero acceleration coasts: the event
    /// moves by u dτ. A `dtau` that is negative or not finite, or an acceleration that is not
    /// finite, leaves the worldline unchanged.
    #[must_use]
    pub fn advance(&self, acceleration: DVec3, dtau: f64) -> Self {
        if !(dtau.is_finite() && dtau > 0.0 && acceleration.is_finite()) {
            return *self;
        }
        let alpha = acceleration.length();
        let direction = acceleration.try_normalize().unwrap_or(DVec3::ZERO);
        let angle = alpha * dtau;
        // sinh(ατ)/α = τ·sinh(x)/x and (cosh(ατ) − 1)/α = τ·2 sinh²(x/2)/x with x = ατ, written
        // so that they stay exact as α → 0.
        let (time, distance) = if angle < SMALL_ANGLE {
            (dtau, 0.5 * angle * dtau)
        } else {
            let half = (0.5 * angle).sinh();
            (angle.sinh() / alpha, 2.0 * half * half / alpha)
        };
        let boost = boost_of_four_velocity(self.four_velocity);
        let (cosh, sinh) = (angle.cosh(), angle.sinh());
        let velocity_rest = DVec4::new(
            cosh,
            sinh * direction.x,
            sinh * direction.y,
            sinh * direction.z,
        );
        let step_rest = DVec4::new(
            time,
            distance * direction.x,
            distance * direction.y,
            distance * direction.z,
        );
        let four_velocity = boost * velocity_rest;
        let step = boost * step_rest;
        let event = Event::from_four_vector(self.event.to_four_vector() + step);
        Self {
            event,
            four_velocity: on_mass_shell(four_velocity),
            proper_time: self.proper_time + dtau,
        }
    }

    /// The worldline after `dtau` of proper time braking with proper acceleration `alpha`
    /// (> 0) against the motion through W, and whether it has come to rest. Braking is
    /// collinear, so the rapidity falls linearly (φ₀ − ατ) and rest is reached after
    /// τ = φ₀/α exactly; the rest of the step is spent at rest.
    #[must_use]
    pub fn brake(&self, alpha: f64, dtau: f64) -> (Self, bool) {
        if !(dtau.is_finite() && dtau > 0.0 && alpha.is_finite() && alpha > 0.0) {
            return (*self, self.spatial_velocity() == DVec3::ZERO);
        }
        let Some(direction) = self.spatial_velocity().try_normalize() else {
            return (self.advance(DVec3::ZERO, dtau), true);
        };
        let to_rest = self.rapidity() / alpha;
        if to_rest > dtau {
            return (self.advance(-alpha * direction, dtau), false);
        }
        let mut stopped = self.advance(-alpha * direction, to_rest);
        stopped.four_velocity = DVec4::new(1.0, 0.0, 0.0, 0.0);
        (stopped.advance(DVec3::ZERO, dtau - to_rest), true)
    }

    /// The worldline with its rapidity limited to `max_rapidity` (the direction of motion
    /// kept): an engine cut-off, so that a renderer in f32 still resolves 1 − |β|.
    #[must_use]
    pub fn with_rapidity_at_most(&self, max_rapidity: f64) -> Self {
        if self.rapidity() <= max_rapidity || !max_rapidity.is_finite() {
            return *self;
        }
        let spatial = self.spatial_velocity().normalize_or_zero() * max_rapidity.max(0.0).sinh();
        Self {
            four_velocity: on_mass_shell(DVec4::new(0.0, spatial.x, spatial.y, spatial.z)),
            ..*self
        }
    }
}

/// The boost Λ_β of Eq. 2 written with the four-velocity u = (γ, γβ) instead of β
/// ([`FourVelocity::boost`], γ taken from the spatial part): equal to `lorentz_matrix(β)`, but γ
/// is not recomputed from 1 − β·β, which loses precision as |β| → 1.
fn boost_of_four_velocity(u: DVec4) -> DMat4 {
    FourVelocity::from_spatial(DVec3::new(u.y, u.z, u.w)).boost()
}

/// The four-velocity with its time part recomputed from its spatial part, γ = √(1 + |γβ|²), so
/// that u·u = 1 holds to rounding however many steps were taken.
fn on_mass_shell(u: DVec4) -> DVec4 {
    let spatial = DVec3::new(u.y, u.z, u.w);
    DVec4::new(
        (1.0 + spatial.length_squared()).sqrt(),
        spatial.x,
        spatial.y,
        spatial.z,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coasting_moves_by_the_four_velocity() {
        let start =
            Worldline::new(Event::new(1.0, DVec3::ZERO), DVec3::new(0.6, 0.0, 0.0)).unwrap();
        let later = start.advance(DVec3::ZERO, 0.8);
        // γ = 1.25: 0.8 of proper time is 1 of world time, 0.6 of distance.
        assert!((later.event.ct - 2.0).abs() < 1e-15);
        assert!((later.event.position.x - 0.6).abs() < 1e-15);
        assert!((later.proper_time - 0.8).abs() < 1e-15);
        assert_eq!(later.beta(), start.beta());
    }

    #[test]
    fn the_boost_of_a_four_velocity_is_eq_2() {
        let beta = DVec3::new(0.3, -0.5, 0.6);
        let w = Worldline::new(Event::new(0.0, DVec3::ZERO), beta).unwrap();
        let difference = boost_of_four_velocity(w.four_velocity) - crate::lorentz_matrix(beta);
        assert!(difference.to_cols_array().iter().all(|d| d.abs() < 1e-12));
    }

    #[test]
    fn bad_steps_change_nothing() {
        let start = Worldline::new(Event::new(0.0, DVec3::ZERO), DVec3::ZERO).unwrap();
        assert_eq!(start.advance(DVec3::X, f64::NAN), start);
        assert_eq!(start.advance(DVec3::X, -1.0), start);
        assert_eq!(start.advance(DVec3::splat(f64::INFINITY), 1.0), start);
        assert!(Worldline::new(Event::new(0.0, DVec3::ZERO), DVec3::X).is_err());
    }

    #[test]
    fn braking_stops_exactly_at_rest() {
        let start =
            Worldline::new(Event::new(0.0, DVec3::ZERO), DVec3::new(0.0, 0.8, 0.0)).unwrap();
        let phi = start.rapidity();
        let (half, stopped) = start.brake(1.0, 0.5 * phi);
        assert!(!stopped);
        assert!((half.rapidity() - 0.5 * phi).abs() < 1e-12);
        let (rest, stopped) = half.brake(1.0, phi);
        assert!(stopped);
        assert_eq!(rest.beta(), DVec3::ZERO);
        assert!((rest.proper_time - 1.5 * phi).abs() < 1e-12);
    }

    #[test]
    fn looking_ahead_is_blue_shifted() {
        let flying =
            Worldline::new(Event::new(0.0, DVec3::ZERO), DVec3::new(0.0, 0.0, 0.6)).unwrap();
        let (ahead, behind) = flying.doppler_ahead_and_behind();
        assert!((ahead - 2.0).abs() < 1e-12);
        assert!((behind - 0.5).abs() < 1e-12);
    }
}
