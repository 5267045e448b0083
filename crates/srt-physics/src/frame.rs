//! Inertial frames of moving objects: the Poincaré transformation (Eq. 1), emission events on the
//! observer's backward light cone (Eq. 5–7), apparent positions (Eq. 8) and viewing rays in the
//! rest frame (the transformation step of §4.2).

use glam::{DMat4, DVec3, DVec4};

use crate::event::Event;
use crate::light::Aberration;
use crate::lorentz::{lorentz_factor, lorentz_matrix, validate_beta};

/// Why a [`Frame`] could not be built.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FrameError {
    /// A velocity or offset component is NaN or infinite.
    #[error("the {what} has a component that is not a finite number")]
    NonFinite {
        /// Which input was not finite ("velocity" or "offset").
        what: &'static str,
    },
    /// |β| ≥ 1: nothing with mass reaches the speed of light.
    #[error("speed |β| = {speed} is not below the speed of light (it must be < 1)")]
    Superluminal {
        /// The offending speed |β| in units of c.
        speed: f64,
    },
}

/// The rest frame S′ of an object, moving with velocity β relative to the observer's frame S;
/// its origin is at `offset` (the paper's **a**) at t = t′ = 0 (Fig. 2).
///
/// Holds Λ_β and Λ_−β so that per-point transformations cost one matrix product each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    beta: DVec3,
    offset: DVec3,
    gamma: f64,
    /// The aberration of light from S into S′ (velocity −β), for [`Frame::rest_direction`].
    to_rest_aberration: Aberration,
    rest_to_observer: DMat4,
    observer_to_rest: DMat4,
}

/// A backward viewing ray expressed in an object's rest frame S′.
///
/// The light that reaches the observer along a viewing direction travels, in S′, along a straight
/// line; followed backwards from the observation event it is `origin + s·direction` at time
/// `ct_origin − s` for s ≥ 0 (c = 1). A static object in S′ is hit by a plain 3D ray test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestRay {
    /// The observer's position in S′ at the observation event (Eq. 5).
    pub origin: DVec3,
    /// Unit direction from the observer back along the incoming light, in S′.
    pub direction: DVec3,
    /// The observation time in S′ (Eq. 5).
    pub ct_origin: f64,
}

impl RestRay {
    /// The event, in S′, at which the light now at the observer was at ray parameter `s` (Eq. 7:
    /// ct′ = ct′_obs − s for a point at distance s from the observer).
    #[must_use]
    pub fn event_at(&self, s: f64) -> Event {
        Event::new(self.ct_origin - s, self.origin + s * self.direction)
    }
}

impl Frame {
    /// The frame moving with `beta` (in units of c) whose origin is at `offset` at t = t′ = 0.
    ///
    /// # Errors
    /// [`FrameError::NonFinite`] for NaN or infinite input, [`FrameError::Superluminal`] for
    /// |β| ≥ 1.
    pub fn new(beta: DVec3, offset: DVec3) -> Result<Self, FrameError> {
        let beta = validate_beta(beta)?;
        if !offset.is_finite() {
            return Err(FrameError::NonFinite { what: "offset" });
        }
        Ok(Self {
            beta,
            offset,
            gamma: lorentz_factor(beta),
            to_rest_aberration: Aberration::new(-beta),
            rest_to_observer: lorentz_matrix(beta),
            observer_to_rest: lorentz_matrix(-beta),
        })
    }

    /// The frame's velocity β relative to S, in units of c.
    #[must_use]
    pub const fn beta(&self) -> DVec3 {
        self.beta
    }

    /// Where the frame's origin is in S at t = 0.
    #[must_use]
    pub const fn offset(&self) -> DVec3 {
        self.offset
    }

    /// The frame's Lorentz factor γ.
    #[must_use]
    pub const fn gamma(&self) -> f64 {
        self.gamma
    }

    /// Λ_β: the Lorentz matrix taking S′ four-vectors to S (Eq. 2).
    #[must_use]
    pub const fn rest_to_observer_matrix(&self) -> DMat4 {
        self.rest_to_observer
    }

    /// Λ_−β: the Lorentz matrix taking S four-vectors to S′ (Eq. 2).
    #[must_use]
    pub const fn observer_to_rest_matrix(&self) -> DMat4 {
        self.observer_to_rest
    }

    fn offset_event(&self) -> DVec4 {
        DVec4::new(0.0, self.offset.x, self.offset.y, self.offset.z)
    }

    /// Poincaré transformation of an event from S′ to S: x = Λ_β x′ + a (Eq. 1).
    #[must_use]
    pub fn to_observer(&self, rest_event: Event) -> Event {
        Event::from_four_vector(
            self.rest_to_observer * rest_event.to_four_vector() + self.offset_event(),
        )
    }

    /// Poincaré transformation of an event from S to S′: x′ = Λ_−β (x − a) (Eq. 1; Eq. 5 for the
    /// observation event).
    #[must_use]
    pub fn to_rest(&self, observer_event: Event) -> Event {
        Event::from_four_vector(
            self.observer_to_rest * (observer_event.to_four_vector() - self.offset_event()),
        )
    }

    /// The event, in S, at which the material point `point` (at rest in S′) is at S time `ct`:
    /// Eq. 1–2 give ct = γ(ct′ + β·x′), so ct′ = ct/γ − β·x′, and (ct′, x′) is mapped to S with
    /// Eq. 1. Its position is where the point is *measured* at that time (Lorentz-contracted
    /// along β, simultaneous in S).
    #[must_use]
    pub fn event_at_time(&self, point: DVec3, ct: f64) -> Event {
        let ct_rest = ct / self.gamma - self.beta.dot(point);
        self.to_observer(Event::new(ct_rest, point))
    }

    /// The event, in S′, at which light must leave the point `point` (at rest in S′) to reach the
    /// observer at the observation event `observer` (given in S): the intersection of the point's
    /// worldline with the observer's backward light cone (Eq. 5–7),
    /// ct′_p = ct′_obs − ‖x′_p − x′_obs‖.
    ///
    /// Non-finite input gives non-finite output; callers validate geometry once when it is loaded.
    #[must_use]
    pub fn emission_event(&self, point: DVec3, observer: Event) -> Event {
        let observer_rest = self.to_rest(observer);
        let distance = (point - observer_rest.position).length();
        Event::new(observer_rest.ct - distance, point)
    }

    /// The apparent position in S of `point` (at rest in S′): where the observer sees it at the
    /// observation event, x_p = Λ_β x′_p + a with x′_p the emission event (Eq. 8). This is the
    /// photo-object map R of §3.2.
    ///
    /// Its distance from the observer equals the light's travel time, ct_obs − ct_p.
    #[must_use]
    pub fn apparent_position(&self, point: DVec3, observer: Event) -> DVec3 {
        self.to_observer(self.emission_event(point, observer))
            .position
    }

    /// The derivative of the apparent position (Eq. 8) of `point + s·direction` with respect to s
    /// at s = 0: the tangent, in S, of the photo-object of a straight line through `point`.
    ///
    /// Differentiating Eq. 7 gives d(ct′)/ds = −direction·(x′ − x′_obs)/‖x′ − x′_obs‖; the tangent
    /// is the spatial part of Λ_β (d(ct′)/ds, direction). Undefined (non-finite) when `point` is
    /// the observer's own position in S′.
    #[must_use]
    pub fn apparent_tangent(&self, point: DVec3, direction: DVec3, observer: Event) -> DVec3 {
        let observer_rest = self.to_rest(observer);
        let from_observer = point - observer_rest.position;
        let dct = -direction.dot(from_observer) / from_observer.length();
        let d = self.rest_to_observer * DVec4::new(dct, direction.x, direction.y, direction.z);
        DVec3::new(d.y, d.z, d.w)
    }

    /// The apparent distance (in S) of the point at parameter `s` along the backward ray `ray`
    /// of this frame: the light travel time ct_obs − ct_emission = γ s (1 − β·d′), with d′ the
    /// ray's direction. Follows from Eq. 8 applied to the emission event (ct′_obs − s,
    /// x′_obs + s d′), because Λ_β maps the observer's rest-frame event back to ct_obs. Free of
    /// the cancellation in ct_obs − ct_emission, which matters in `f32`.
    #[must_use]
    pub fn apparent_distance(&self, ray: &RestRay, s: f64) -> f64 {
        self.gamma * s * (1.0 - self.beta.dot(ray.direction))
    }

    /// The backward viewing ray in S′ for an observer at the observation event `observer` (in S)
    /// looking along `view_direction` (in S, need not be normalised): Eq. 3 applied to the
    /// incoming light and Eq. 5 to the observer (Algorithm 1, "Transform d and x_obs into S′").
    #[must_use]
    pub fn backward_ray(&self, observer: Event, view_direction: DVec3) -> RestRay {
        let observer_rest = self.to_rest(observer);
        RestRay {
            origin: observer_rest.position,
            direction: self.rest_direction(view_direction),
            ct_origin: observer_rest.ct,
        }
    }

    /// The unit direction in S′ back along the light seen looking along `view_direction` (in S,
    /// need not be normalised): Eq. 3 applied to the incoming light. It depends on the velocity
    /// alone, so a renderer computes it once per ray for all objects moving alike. Inlined
    /// across crates: the CPU tracer calls it for every ray and velocity.
    #[must_use]
    #[inline]
    pub fn rest_direction(&self, view_direction: DVec3) -> DVec3 {
        // Light arrives travelling opposite to the viewing direction; in S′ it travels along the
        // aberrated direction, and we follow it backwards.
        let propagation = -view_direction.normalize();
        -self.to_rest_aberration.apply(propagation).normalize()
    }

    /// [`Frame::rest_direction`] of each of `view_directions`, written over `rest` (as long):
    /// the same bits as one by one, computed [`DIRECTION_LANES`] at a time side by side, so
    /// that the square roots and divisions of two directions share a vector instruction.
    ///
    /// # Panics
    /// If `rest` is not as long as `view_directions`.
    pub fn rest_directions(&self, view_directions: &[DVec3], rest: &mut [DVec3]) {
        assert_eq!(
            view_directions.len(),
            rest.len(),
            "a rest direction per view"
        );
        for (views, rest) in
            (view_directions.chunks(DIRECTION_LANES)).zip(rest.chunks_mut(DIRECTION_LANES))
        {
            // Unused lanes stay 0 (their NaNs are never read).
            let mut lanes = [[0.0; DIRECTION_LANES]; 3];
            for (i, view) in views.iter().enumerate() {
                [lanes[0][i], lanes[1][i], lanes[2][i]] = view.to_array();
            }
            negate_normalised(&mut lanes);
            self.to_rest_aberration.apply_lanes(&mut lanes);
            negate_normalised(&mut lanes);
            for (i, direction) in rest.iter_mut().enumerate() {
                *direction = DVec3::new(lanes[0][i], lanes[1][i], lanes[2][i]);
            }
        }
    }
}

/// How many directions [`Frame::rest_directions`] computes side by side.
pub const DIRECTION_LANES: usize = 64;

/// Each direction of `lanes` replaced by `-direction.normalize()`, glam's operations in glam's
/// order (v · (1 / √(v·v)), then negated), so the bits are the same.
fn negate_normalised<const N: usize>([x, y, z]: &mut [[f64; N]; 3]) {
    for i in 0..N {
        let length_recip = 1.0 / ((x[i] * x[i]) + (y[i] * y[i]) + (z[i] * z[i])).sqrt();
        x[i] = -(x[i] * length_recip);
        y[i] = -(y[i] * length_recip);
        z[i] = -(z[i] * length_recip);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    proptest! {
        /// The directions computed side by side are those computed one by one, bit for bit,
        /// for any velocity and any number of directions (partial batches included).
        #[test]
        fn rest_directions_side_by_side_are_the_same_bits(
            beta in prop::array::uniform3(-0.57_f64..0.57),
            views in prop::collection::vec(prop::array::uniform3(-3.0_f64..3.0), 0..150),
        ) {
            let frame = Frame::new(DVec3::from_array(beta), DVec3::ZERO).expect("|β| < 1");
            let views: Vec<DVec3> = (views.into_iter().map(DVec3::from_array))
                .filter(|view| view.length() > 1e-3)
                .collect();
            let mut rest = vec![DVec3::ZERO; views.len()];
            frame.rest_directions(&views, &mut rest);
            for (view, rest) in views.iter().zip(&rest) {
                let one = frame.rest_direction(*view);
                prop_assert_eq!(one.to_array().map(f64::to_bits), rest.to_array().map(f64::to_bits));
            }
        }
    }

    #[test]
    fn rejects_superluminal_and_non_finite() {
        assert_eq!(
            Frame::new(DVec3::new(0.0, 1.0, 0.0), DVec3::ZERO),
            Err(FrameError::Superluminal { speed: 1.0 })
        );
        assert!(matches!(
            Frame::new(DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)),
            Err(FrameError::NonFinite { what: "offset" })
        ));
    }

    #[test]
    fn frame_at_rest_sees_the_point_where_it_is() {
        let frame = Frame::new(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)).unwrap();
        let p = frame.apparent_position(DVec3::new(0.5, 0.0, 0.0), Event::new(7.0, DVec3::ZERO));
        assert_relative_eq!(p.x, 1.5, epsilon = 1e-15);
        assert_relative_eq!(p.y, 2.0, epsilon = 1e-15);
        assert_relative_eq!(p.z, 3.0, epsilon = 1e-15);
    }

    #[test]
    fn approaching_point_is_seen_farther_away_than_it_is() {
        // Point moves along +x towards the observer at x = 10 and passes x = 0 at t = 0.
        let b = 0.5;
        let frame = Frame::new(DVec3::new(b, 0.0, 0.0), DVec3::ZERO).unwrap();
        let observer = Event::new(0.0, DVec3::new(10.0, 0.0, 0.0));
        let p = frame.apparent_position(DVec3::ZERO, observer);
        // Emitted at x_e = b t_e with 10 − x_e = −t_e  ⇒  t_e = −10/(1−b) = −20, x_e = −10.
        assert_relative_eq!(p.x, -10.0, epsilon = 1e-12);
    }
}
