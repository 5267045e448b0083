//! Motion of a rigid body within its own inertial frame S′, beyond rest: **spin** (kinematic
//! rotation about an axis) and **thrust** (Born-rigid hyperbolic acceleration, then coasting).
//! Uniform motion relative to the observer stays the business of [`Frame`](crate::Frame); a
//! body point `b` names a material point by where it is at S′ time ct′ = 0 (before any thrust),
//! and the functions here give its worldline in S′ and, back, the material point found at an
//! S′ event — what a renderer needs to meet a backward light ray with the moving body
//! (docs/physics.md, "Spinning and accelerating bodies").
//!
//! **Spin** `{ axis, rate ω, centre }`: the point b is at centre + R(axis, ω·ct′)(b − centre)
//! at S′ time ct′ (right-handed, angle ω·ct′ in radians). Its speed in S′ is |ω|·ρ, ρ its
//! distance from the axis, so every point must have ρ < 1/|ω| ([`Spin::max_radius`]). This is
//! a kinematic rotation in S′: each point moves on its circle as prescribed, which is not a
//! Born-rigid motion (Ehrenfest): the rim, measured in a co-moving frame, is longer than 2πρ.
//!
//! **Thrust** `{ proper_acceleration a, start t₀, duration τ }`: until S′ time t₀ the body rests
//! in S′; then it accelerates Born-rigidly along â = a/|a| for τ of its origin's proper time,
//! after which it coasts in its new rest frame. Born rigidity fixes each point's proper
//! acceleration: a point at height ξ = (b·â) above the origin has α/(1 + αξ) (α = |a|), so that
//! in Rindler form, with X = 1/α + ξ,
//! x_∥ + 1/α = X cosh η,  ct − ct₀ = X sinh η,  η ∈ [0, ατ]
//! (η the common rapidity; the origin's proper time is η/α). For the origin this is the closed
//! form x = (cosh(ατ) − 1)/α, ct = sinh(ατ)/α. Points with 1 + αξ ≤ 0 would lie beyond the
//! Rindler horizon and are refused ([`Thrust::horizon_height`]). After η_end = ατ every point
//! moves on with velocity tanh(η_end) â: they all stop accelerating at once in the new rest
//! frame, so the body keeps its proper length.

use glam::{DMat3, DQuat, DVec3};

use crate::event::Event;
use crate::velocity::FourVelocity;

/// Most rotation of a spinning body per piece of a curved ray, in radians: how finely the
/// moving bodies' searches cut a ray's curve in body space into pieces whose boxes ask the BVH
/// for candidates — srt-trace's, and srt-gpu's through the WGSL override
/// `MOTION_SPIN_PIECE_ANGLE` (one value for both, so that both search the same pieces).
pub const SPIN_PIECE_ANGLE: f64 = 0.05;

/// Pieces of a thrusting body's accelerating stretch of ray per its size (the extent of the arc
/// in body space over the body's reach), for srt-trace's search and srt-gpu's (WGSL
/// `MOTION_THRUST_PIECES_PER_SIZE`): only how finely the BVH is asked for candidates; each
/// piece's box is exact.
pub const THRUST_PIECES_PER_SIZE: f64 = 4.0;

/// Newton steps polishing each root of a thrust's crossing with a triangle's plane (on the
/// unsquared distance), in srt-trace's f64 search and srt-gpu's f32 one (WGSL
/// `MOTION_NEWTON_STEPS`).
pub const THRUST_NEWTON_STEPS: u32 = 2;

/// Why a [`Spin`] or [`Thrust`] could not be built.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// A parameter is NaN or infinite (a thrust's duration may be +∞).
    #[error("the {what} is not a finite number")]
    NonFinite {
        /// Which parameter.
        what: &'static str,
    },
    /// The spin axis or the acceleration is the zero vector.
    #[error("the {what} must not be the zero vector")]
    Zero {
        /// Which parameter.
        what: &'static str,
    },
    /// A thrust's duration is negative.
    #[error("the duration of a thrust must be ≥ 0, got {0}")]
    NegativeDuration(f64),
}

/// Kinematic rotation in S′ about the line through `centre` along `axis` (see the module
/// documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spin {
    axis: DVec3,
    rate: f64,
    centre: DVec3,
}

impl Spin {
    /// A spin about the unit direction of `axis` through `centre` at `rate` ω (radians per unit
    /// of ct′; negative turns the other way).
    ///
    /// # Errors
    /// [`MotionError::NonFinite`] for a non-finite input, [`MotionError::Zero`] for a zero axis.
    pub fn new(axis: DVec3, rate: f64, centre: DVec3) -> Result<Self, MotionError> {
        finite3(axis, "spin axis")?;
        finite3(centre, "spin centre")?;
        if !rate.is_finite() {
            return Err(MotionError::NonFinite { what: "spin rate" });
        }
        let axis = axis
            .try_normalize()
            .ok_or(MotionError::Zero { what: "spin axis" })?;
        Ok(Self { axis, rate, centre })
    }

    /// The unit axis.
    #[must_use]
    pub const fn axis(&self) -> DVec3 {
        self.axis
    }

    /// The rate ω in radians per unit of ct′.
    #[must_use]
    pub const fn rate(&self) -> f64 {
        self.rate
    }

    /// A point of the axis.
    #[must_use]
    pub const fn centre(&self) -> DVec3 {
        self.centre
    }

    /// The largest distance from the axis a point may have: its speed |ω|·ρ must stay below 1
    /// (∞ without rotation).
    #[must_use]
    pub fn max_radius(&self) -> f64 {
        1.0 / self.rate.abs()
    }

    /// The distance of `point` from the axis.
    #[must_use]
    pub fn radius_of(&self, point: DVec3) -> f64 {
        let r = point - self.centre;
        (r - r.dot(self.axis) * self.axis).length()
    }

    /// The rotation the body has turned by at S′ time `ct`.
    #[must_use]
    pub fn rotation(&self, ct: f64) -> DQuat {
        DQuat::from_axis_angle(self.axis, self.rate * ct)
    }

    /// Where the body point `body` is at S′ time `ct`.
    #[must_use]
    pub fn position(&self, body: DVec3, ct: f64) -> DVec3 {
        self.centre + self.rotation(ct) * (body - self.centre)
    }

    /// The velocity (units of c) in S′ of the material point at `position`: ω axis × (x − centre).
    #[must_use]
    pub fn velocity_at(&self, position: DVec3) -> DVec3 {
        self.rate * self.axis.cross(position - self.centre)
    }

    /// The body point found at `position` at S′ time `ct` (the inverse of [`Spin::position`]).
    #[must_use]
    pub fn body_point(&self, position: DVec3, ct: f64) -> DVec3 {
        self.centre + self.rotation(ct).inverse() * (position - self.centre)
    }
}

/// Born-rigid hyperbolic acceleration in S′, then coasting (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thrust {
    /// Unit direction â of the acceleration.
    direction: DVec3,
    /// α = |a|, the origin's proper acceleration.
    alpha: f64,
    /// S′ time ct₀ at which it starts.
    start: f64,
    /// The rapidity reached, α·τ (∞ for a thrust without end).
    final_rapidity: f64,
}

impl Thrust {
    /// A thrust with the origin's proper acceleration `acceleration` (per unit of ct′),
    /// starting at S′ time `start`, lasting `duration` of the origin's proper time (≥ 0,
    /// possibly +∞).
    ///
    /// # Errors
    /// [`MotionError`] for non-finite or zero acceleration, a non-finite start, a negative or
    /// NaN duration.
    pub fn new(acceleration: DVec3, start: f64, duration: f64) -> Result<Self, MotionError> {
        finite3(acceleration, "proper acceleration")?;
        if !start.is_finite() {
            return Err(MotionError::NonFinite {
                what: "thrust start",
            });
        }
        if duration.is_nan() {
            return Err(MotionError::NonFinite {
                what: "thrust duration",
            });
        }
        if duration < 0.0 {
            return Err(MotionError::NegativeDuration(duration));
        }
        let alpha = acceleration.length();
        let direction = acceleration.try_normalize().ok_or(MotionError::Zero {
            what: "proper acceleration",
        })?;
        Ok(Self {
            direction,
            alpha,
            start,
            final_rapidity: alpha * duration,
        })
    }

    /// The unit direction of the acceleration.
    #[must_use]
    pub const fn direction(&self) -> DVec3 {
        self.direction
    }

    /// The origin's proper acceleration α.
    #[must_use]
    pub const fn alpha(&self) -> f64 {
        self.alpha
    }

    /// The S′ time at which the thrust starts.
    #[must_use]
    pub const fn start(&self) -> f64 {
        self.start
    }

    /// The rapidity at the end, α·τ (∞ without end).
    #[must_use]
    pub const fn final_rapidity(&self) -> f64 {
        self.final_rapidity
    }

    /// The height ξ = −1/α of the Rindler horizon: every body point must lie above it
    /// (b·â > −1/α).
    #[must_use]
    pub fn horizon_height(&self) -> f64 {
        -1.0 / self.alpha
    }

    /// The proper acceleration of the body point `body`: α/(1 + αξ), ξ = b·â (Born rigidity).
    #[must_use]
    pub fn proper_acceleration_of(&self, body: DVec3) -> f64 {
        self.alpha / (1.0 + self.alpha * body.dot(self.direction))
    }

    /// The event in S′ of the body point `body` at rapidity `eta` (0 at the start; clamped to
    /// [0, α·τ]; its proper time since the start is X·η, X = 1/α + ξ).
    #[must_use]
    pub fn event_at_rapidity(&self, body: DVec3, eta: f64) -> Event {
        let eta = eta.clamp(0.0, self.final_rapidity);
        let height = body.dot(self.direction);
        let x = 1.0 / self.alpha + height;
        let along = x * eta.cosh() - 1.0 / self.alpha;
        Event::new(
            self.start + x * eta.sinh(),
            body + (along - height) * self.direction,
        )
    }

    /// Where the body point `body` is at S′ time `ct`: at rest before the start, on its
    /// hyperbola during the thrust, coasting at tanh(ατ) after it.
    #[must_use]
    pub fn position(&self, body: DVec3, ct: f64) -> DVec3 {
        let x = 1.0 / self.alpha + body.dot(self.direction);
        let elapsed = ct - self.start;
        if elapsed <= 0.0 {
            return body;
        }
        // Rapidity at which the point's hyperbola reaches S′ time ct: X sinh η = elapsed.
        let eta = (elapsed / x).asinh();
        if eta <= self.final_rapidity {
            return self.event_at_rapidity(body, eta).position;
        }
        let end = self.event_at_rapidity(body, self.final_rapidity);
        end.position + (ct - end.ct) * self.final_rapidity.tanh() * self.direction
    }

    /// The origin's event in S′ and its velocity (units of c) when its own clock, which reads
    /// S′ time until the start, shows `proper_time`: at rest before the start; on the hyperbola
    /// (start + sinh η / α, (cosh η − 1)/α · â), η = α (τ − start), during the thrust; coasting
    /// at tanh(ατ_end) · â after it, its clock running 1/cosh(ατ_end) as fast as S′ time. What an
    /// observer riding the thrust sees is drawn from this event and velocity alone.
    #[must_use]
    pub fn origin_at_proper_time(&self, proper_time: f64) -> (Event, DVec3) {
        let since = proper_time - self.start;
        if since <= 0.0 {
            return (Event::new(proper_time, DVec3::ZERO), DVec3::ZERO);
        }
        let eta = self.alpha * since;
        if eta <= self.final_rapidity {
            let event = self.event_at_rapidity(DVec3::ZERO, eta);
            return (event, eta.tanh() * self.direction);
        }
        let end = self.event_at_rapidity(DVec3::ZERO, self.final_rapidity);
        let coasting = since - self.final_rapidity / self.alpha;
        let (gamma, gamma_beta) = (self.final_rapidity.cosh(), self.final_rapidity.sinh());
        (
            Event::new(
                end.ct + gamma * coasting,
                end.position + gamma_beta * coasting * self.direction,
            ),
            self.final_rapidity.tanh() * self.direction,
        )
    }

    /// The velocity (units of c) in S′ of the body point `body` at S′ time `ct`.
    #[must_use]
    pub fn velocity(&self, body: DVec3, ct: f64) -> DVec3 {
        self.rapidity(body, ct).tanh() * self.direction
    }

    /// The four-velocity in S′ of the body point `body` at S′ time `ct`: sinh η · â, finite
    /// however long the thrust (where tanh η, its β, rounds to 1).
    #[must_use]
    pub fn four_velocity(&self, body: DVec3, ct: f64) -> FourVelocity {
        FourVelocity::from_rapidity(self.direction, self.rapidity(body, ct))
    }

    /// The rapidity η of the body point `body` at S′ time `ct` (X sinh η = ct − ct₀, at most
    /// α·τ; 0 before the start).
    fn rapidity(&self, body: DVec3, ct: f64) -> f64 {
        let x = 1.0 / self.alpha + body.dot(self.direction);
        let elapsed = ct - self.start;
        if elapsed <= 0.0 {
            return 0.0;
        }
        (elapsed / x).asinh().min(self.final_rapidity)
    }

    /// The body point found at the S′ event (`ct`, `position`), if any body point's worldline
    /// passes there (none below the horizon): the inverse of [`Thrust::position`].
    #[must_use]
    pub fn body_point(&self, ct: f64, position: DVec3) -> Option<DVec3> {
        let elapsed = ct - self.start;
        let along = position.dot(self.direction);
        let across = position - along * self.direction;
        if elapsed <= 0.0 {
            return Some(position);
        }
        // Rindler coordinates of the event: u = x_∥ + 1/α, v = c(t − t₀). A point X coasts
        // after the end on X(cosh η_e, sinh η_e) + σ(sinh η_e, cosh η_e), σ ≥ 0: boosting by
        // −η_e gives (X, σ).
        let (u, v) = (along + 1.0 / self.alpha, elapsed);
        let end = self.final_rapidity;
        let x = if end.is_finite() && v * end.cosh() - u * end.sinh() >= 0.0 {
            u * end.cosh() - v * end.sinh()
        } else if u > v {
            // Accelerating: on the hyperbola u² − v² = X².
            (u * u - v * v).sqrt()
        } else {
            return None; // beyond the horizon
        };
        (x > 0.0).then(|| across + (x - 1.0 / self.alpha) * self.direction)
    }
}

/// How a body moves within its rest frame S′: not at all (the paper's rigid objects), spinning
/// or thrusting. Times are the body's S′ time ct′.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Motion {
    /// At rest in S′.
    #[default]
    Rest,
    /// Kinematic rotation.
    Spin(Spin),
    /// Born-rigid acceleration, then coasting.
    Thrust(Thrust),
}

impl Motion {
    /// Whether the body rests in S′ (uniform motion relative to the observer).
    #[must_use]
    pub const fn is_rest(&self) -> bool {
        matches!(self, Self::Rest)
    }

    /// Where the body point `body` is at S′ time `ct`.
    #[must_use]
    pub fn position(&self, body: DVec3, ct: f64) -> DVec3 {
        match self {
            Self::Rest => body,
            Self::Spin(spin) => spin.position(body, ct),
            Self::Thrust(thrust) => thrust.position(body, ct),
        }
    }

    /// The velocity (units of c) in S′ of the body point `body` at S′ time `ct`.
    #[must_use]
    pub fn velocity(&self, body: DVec3, ct: f64) -> DVec3 {
        match self {
            Self::Rest => DVec3::ZERO,
            Self::Spin(spin) => spin.velocity_at(spin.position(body, ct)),
            Self::Thrust(thrust) => thrust.velocity(body, ct),
        }
    }

    /// The four-velocity in S′ of the body point `body` at S′ time `ct` (finite where its β
    /// rounds to |β| = 1).
    #[must_use]
    pub fn four_velocity(&self, body: DVec3, ct: f64) -> FourVelocity {
        match self {
            Self::Rest => FourVelocity::REST,
            Self::Spin(_) => FourVelocity::from_beta(self.velocity(body, ct)),
            Self::Thrust(thrust) => thrust.four_velocity(body, ct),
        }
    }

    /// The body point at the S′ event (`ct`, `position`), if any.
    #[must_use]
    pub fn body_point(&self, ct: f64, position: DVec3) -> Option<DVec3> {
        match self {
            Self::Rest => Some(position),
            Self::Spin(spin) => Some(spin.body_point(position, ct)),
            Self::Thrust(thrust) => thrust.body_point(ct, position),
        }
    }

    /// The proper time (as ct) a clock riding on body point `body` shows at S′ time `ct`, set
    /// to ct′ before any motion: ct′ at rest; ct′·√(1 − ω²ρ²) spinning (time dilation of its
    /// circular motion, 0 at ct′ = 0); ct₀ + X·η during a thrust (X = 1/α + ξ the point's
    /// Rindler distance, η the rapidity), then the coasting time / γ.
    #[must_use]
    pub fn proper_time(&self, body: DVec3, ct: f64) -> f64 {
        match self {
            Self::Rest => ct,
            Self::Spin(spin) => {
                let speed = spin.rate().abs() * spin.radius_of(body);
                ct * (1.0 - speed * speed).max(0.0).sqrt()
            }
            Self::Thrust(thrust) => {
                let elapsed = ct - thrust.start();
                if elapsed <= 0.0 {
                    return ct;
                }
                let x = 1.0 / thrust.alpha() + body.dot(thrust.direction());
                let eta = (elapsed / x).asinh();
                let end = thrust.final_rapidity();
                if eta <= end {
                    return thrust.start() + x * eta;
                }
                let end_ct = thrust.start() + x * end.sinh();
                thrust.start() + x * end + (ct - end_ct) / end.cosh()
            }
        }
    }

    /// The same motion in spatial coordinates turned by `rotation` (x″ = rotation · x′, the same
    /// S′ time): what an object's motion becomes in the rest coordinates of its frame relative
    /// to a moving observer, whose axes are turned by the Wigner rotation.
    #[must_use]
    pub fn rotated(&self, rotation: DMat3) -> Self {
        match *self {
            Self::Rest => Self::Rest,
            Self::Spin(spin) => Self::Spin(Spin {
                axis: rotation * spin.axis,
                centre: rotation * spin.centre,
                ..spin
            }),
            Self::Thrust(thrust) => Self::Thrust(Thrust {
                direction: rotation * thrust.direction,
                ..thrust
            }),
        }
    }
}

fn finite3(v: DVec3, what: &'static str) -> Result<(), MotionError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(MotionError::NonFinite { what })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn vector(range: f64) -> impl Strategy<Value = DVec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        // Most random points of a fast spin lie beyond its light cylinder and are rejected (3 in
        // 4): the default limit of 1024 rejects is met in a long run.
        #![proptest_config(ProptestConfig {
            max_global_rejects: 1 << 20,
            ..ProptestConfig::default()
        })]

        /// The origin's event at a proper time lies on its worldline (Thrust::position at
        /// that S′ time), its clock there reads that proper time (Motion::proper_time), and its
        /// velocity is the worldline's slope; during the thrust the event is the closed-form
        /// hyperbola (sinh(ατ)/α, (cosh(ατ) − 1)/α) after the start.
        #[test]
        fn the_origin_at_a_proper_time_rides_its_hyperbola(
            acceleration in vector(2.0), start in -5.0..5.0f64, duration in 0.0..4.0f64,
            proper_time in -10.0..10.0f64,
        ) {
            prop_assume!(acceleration.length() > 1e-2);
            let thrust = Thrust::new(acceleration, start, duration).unwrap();
            let (event, velocity) = thrust.origin_at_proper_time(proper_time);
            let scale = 1.0 + event.ct.abs() + event.position.length();
            prop_assert!((thrust.position(DVec3::ZERO, event.ct) - event.position).length() <= 1e-9 * scale);
            let clock = Motion::Thrust(thrust).proper_time(DVec3::ZERO, event.ct);
            prop_assert!((clock - proper_time).abs() <= 1e-9 * scale, "{clock} {proper_time}");
            // The step grows with the coordinates (a coasting ship is at ct ~ 10⁵ here), so that
            // rounding stays ~1e-9 of the slope; a difference across the thrust's start or end,
            // where the acceleration jumps, is no measure of the velocity and is not taken.
            let dt = 1e-7 * scale;
            let end_ct = thrust.event_at_rapidity(DVec3::ZERO, thrust.final_rapidity()).ct;
            if (event.ct - start).abs() > 2.0 * dt && (event.ct - end_ct).abs() > 2.0 * dt {
                let slope = (thrust.position(DVec3::ZERO, event.ct + dt) - thrust.position(DVec3::ZERO, event.ct - dt)) / (2.0 * dt);
                prop_assert!((slope - velocity).length() <= 1e-5, "{slope} {velocity}");
            }
            let (alpha, tau) = (thrust.alpha(), proper_time - start);
            if tau > 0.0 && tau <= duration {
                let hyperbola = Event::new(
                    start + (alpha * tau).sinh() / alpha,
                    ((alpha * tau).cosh() - 1.0) / alpha * thrust.direction(),
                );
                prop_assert!((event.ct - hyperbola.ct).abs() <= 1e-9 * scale);
                prop_assert!((event.position - hyperbola.position).length() <= 1e-9 * scale);
                prop_assert!((velocity.length() - (alpha * tau).tanh()).abs() <= 1e-12);
            }
        }

        #[test]
        fn spin_points_turn_by_the_stated_angle_below_light_speed(
            axis in vector(1.0), rate in -2.0..2.0f64, centre in vector(2.0), body in vector(3.0),
            ct in -10.0..10.0f64,
        ) {
            prop_assume!(axis.length() > 1e-3);
            let spin = Spin::new(axis, rate, centre).unwrap();
            let radius = spin.radius_of(body);
            prop_assume!(radius < spin.max_radius());
            let at = spin.position(body, ct);
            // Same distance from the axis and the same height along it.
            assert_relative_eq!(spin.radius_of(at), radius, epsilon = 1e-9);
            let unit = axis.normalize();
            assert_relative_eq!((at - centre).dot(unit), (body - centre).dot(unit), epsilon = 1e-9);
            // Turned right-handedly by ω·ct: the signed angle between the radial vectors.
            if radius > 1e-3 {
                let radial = |p: DVec3| { let r = p - centre; r - r.dot(unit) * unit };
                let (r0, r1) = (radial(body), radial(at));
                let angle = unit.dot(r0.cross(r1)).atan2(r0.dot(r1));
                let expected = (rate * ct + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                prop_assert!((angle - expected).abs() < 1e-7, "{angle} vs {expected}");
            }
            // Speed |ω| ρ < 1, and the velocity is the derivative of the position.
            let v = spin.velocity_at(at);
            prop_assert!(v.length() < 1.0);
            let h = 1e-6;
            let numeric = (spin.position(body, ct + h) - spin.position(body, ct - h)) / (2.0 * h);
            prop_assert!((numeric - v).length() < 1e-6);
            prop_assert!((spin.body_point(at, ct) - body).length() < 1e-9);
        }

        #[test]
        fn thrust_worldlines_are_born_rigid_hyperbolae(
            acceleration in vector(1.0), start in -5.0..5.0f64, duration in 0.0..6.0f64,
            body in vector(0.4), other in vector(0.4), tau in 0.0..8.0f64,
        ) {
            prop_assume!(acceleration.length() > 0.05);
            let thrust = Thrust::new(acceleration, start, duration).unwrap();
            let alpha = thrust.alpha();
            prop_assume!(body.dot(thrust.direction()) > thrust.horizon_height() * 0.9);
            prop_assume!(other.dot(thrust.direction()) > thrust.horizon_height() * 0.9);
            // The origin meets the closed form x = (cosh ατ − 1)/α, ct = sinh ατ / α.
            let eta = alpha * tau.min(duration);
            let origin = thrust.event_at_rapidity(DVec3::ZERO, alpha * tau);
            assert_relative_eq!(origin.ct - start, eta.sinh() / alpha, max_relative = 1e-12, epsilon = 1e-12);
            assert_relative_eq!(origin.position.dot(thrust.direction()), (eta.cosh() - 1.0) / alpha,
                max_relative = 1e-12, epsilon = 1e-12);
            assert_relative_eq!(thrust.position(DVec3::ZERO, origin.ct).dot(thrust.direction()),
                (eta.cosh() - 1.0) / alpha, max_relative = 1e-9, epsilon = 1e-9);
            // Proper length kept: two points at the same rapidity are simultaneous in the
            // momentary rest frame, and their distance there is their distance at rest.
            let (a, b) = (thrust.event_at_rapidity(body, eta), thrust.event_at_rapidity(other, eta));
            let (dt, dx) = (b.ct - a.ct, b.position - a.position);
            let v = eta.tanh() * thrust.direction();
            let gamma = eta.cosh();
            // In the frame moving with v: t' = γ(t − v·x); x'_∥ = γ(x_∥ − v t).
            // Round-off: each event's coordinates carry about ε (|ct| + |x|), which the boost
            // into the momentary frame multiplies by up to 2γ (γ reaches cosh 10 here).
            let size = |e: &Event| e.ct.abs() + e.position.length();
            let round_off = 64.0 * f64::EPSILON * gamma * (1.0 + size(&a).max(size(&b)));
            let t_rest = gamma * (dt - v.dot(dx));
            prop_assert!(t_rest.abs() < 1e-9 * (1.0 + dx.length()) + round_off, "{t_rest}");
            let along = dx.dot(thrust.direction());
            let rest = (dx - along * thrust.direction())
                + gamma * (along - eta.tanh() * dt) * thrust.direction();
            let proper = (other - body).length();
            prop_assert!(
                (rest.length() - proper).abs() <= 1e-9 * (1.0 + proper) + round_off,
                "{} vs {proper} (γ = {gamma}, round-off {round_off:e})",
                rest.length()
            );
            // The point's proper acceleration is α / (1 + αξ): its hyperbola's inverse radius.
            let xi = body.dot(thrust.direction());
            assert_relative_eq!(thrust.proper_acceleration_of(body), 1.0 / (1.0 / alpha + xi), max_relative = 1e-12);
            // The body point found at a point's event is that point, in all three phases.
            for ct in [start - 1.0, a.ct, a.ct + 3.0] {
                let at = thrust.position(body, ct);
                let found = thrust.body_point(ct, at).unwrap();
                prop_assert!((found - body).length() < 1e-8 * (1.0 + ct.abs()), "{found} vs {body} at {ct}");
                prop_assert!(thrust.velocity(body, ct).length() < 1.0);
            }
        }
    }

    #[test]
    fn bad_motions_are_refused() {
        assert!(Spin::new(DVec3::ZERO, 1.0, DVec3::ZERO).is_err());
        assert!(Spin::new(DVec3::Z, f64::NAN, DVec3::ZERO).is_err());
        assert!(Thrust::new(DVec3::ZERO, 0.0, 1.0).is_err());
        assert!(Thrust::new(DVec3::X, 0.0, -1.0).is_err());
        assert!(Thrust::new(DVec3::X, f64::INFINITY, 1.0).is_err());
        assert!(Thrust::new(DVec3::X, 0.0, f64::INFINITY).is_ok());
    }
}
