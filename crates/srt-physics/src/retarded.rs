//! Light from a moving point source reaching an event: the source's **retarded event** (where
//! its worldline crosses the event's past light cone), the direction the light comes from, the
//! Doppler factor between source and receiver, and how strong the light is there.
//!
//! The source rests at the origin of its frame S_L (velocity β_L relative to S). Its retarded
//! event for a receiving event E is the paper's emission event (Eq. 5–7) with the roles of
//! object and observer taken by source and receiver: in S_L, ct_L = ct_E,L − ‖x_E,L‖, so the
//! light travels the distance r_L = ‖x_E,L‖ in the source's rest frame. In S it travels
//! r = ct_E − ct_L along the unit direction n = (x_E − x_L) / r.
//!
//! The frequency ratio receiver/source is the product of the source's Doppler factor into S
//! (Eq. 4's time part, [`FourVelocity::doppler_factor`]) and the receiver's out of S (Eq. 3's,
//! [`FourVelocity::receiver_doppler`]): D_in = γ_R(1 − β_R·n) / (γ_L(1 − β_L·n)), the first
//! factor of Eq. 17 with a moving source. Since r_L = γ_L(1 − β_L·n)·r and the distance in the receiver's frame is
//! r_R = γ_R(1 − β_R·n)·r (both the time component of the null vector (r, r·n) boosted), also
//! D_in = r_R / r_L.
//!
//! Strength: the source radiates isotropically in S_L, so the energy flux it sends through a
//! sphere of radius r_L around it there is I / r_L² (inverse square in its own frame). Near the
//! receiver the light is a plane wave, whose energy flux scales with the square of the
//! frequency ratio between frames (energy density ∝ |E|², and E scales with ω): the receiver
//! measures D_in² · I / r_L² = D_in⁴ · I / r_R². docs/physics.md ("Moving lights") derives it.

use glam::DVec3;

use crate::event::Event;
use crate::frame::Frame;
use crate::velocity::FourVelocity;

/// The light of a point source at rest at the origin of `source` (a frame relative to S) that
/// reaches one event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RetardedLight {
    /// The source's retarded event, in S: where and when the arriving light left it.
    pub source_event: Event,
    /// Unit propagation direction of the light in S (source → receiver).
    pub direction: DVec3,
    /// The distance the light travelled in the source's rest frame, r_L.
    pub source_distance: f64,
    /// The source's velocity relative to S.
    pub source_beta: DVec3,
}

impl RetardedLight {
    /// The light of the source resting at `source`'s origin that reaches `receiver` (an event in
    /// S). `None` where the receiver is on the source's worldline (no direction), or the input is
    /// not finite.
    ///
    /// The retarded event is found in S, on the worldline x(ct) = a + β·ct: with p = x_E − x(ct_E)
    /// the receiver's offset from where the source is at its time, the light travelled
    /// r = ct_E − ct_L with ‖p + β r‖ = r, the root of (1 − β²) r² − 2 (β·p) r − p² = 0 that is
    /// ≥ 0, r = (β·p + q)·γ² = p² / (q − β·p) with q = √((β·p)² + p²/γ²), each form taken where it
    /// has no cancellation. It is the S_L construction above (Eq. 5–7) without its Lorentz
    /// transformations, whose ct_L = γ(ct_L,L + β·x_L,L) loses every digit at |β| = 1 − 10⁻¹⁶
    /// when the light leaves backwards. r_L = γ_L(1 − β_L·n)·r from the source's four-velocity.
    #[must_use]
    pub fn reaching(source: &Frame, receiver: Event) -> Option<Self> {
        let beta = source.beta();
        let velocity = FourVelocity::from_beta(beta);
        let gamma = velocity.gamma();
        let offset = receiver.position - source.offset() - beta * receiver.ct;
        let ahead = beta.dot(offset);
        let q = (ahead * ahead + offset.length_squared() / (gamma * gamma)).sqrt();
        let travelled = if ahead >= 0.0 {
            (ahead + q) * gamma * gamma
        } else {
            offset.length_squared() / (q - ahead)
        };
        let direction = (offset + beta * travelled).normalize_or_zero();
        let source_distance = velocity.gamma_one_minus_dot(direction) * travelled;
        let source_ct = receiver.ct - travelled;
        let source_event = Event::new(source_ct, source.offset() + beta * source_ct);
        (source_distance > 0.0
            && source_distance.is_finite()
            && source_event.ct.is_finite()
            && source_event.position.is_finite()
            && direction != DVec3::ZERO)
            .then_some(Self {
                source_event,
                direction,
                source_distance,
                source_beta: beta,
            })
    }

    /// D_in: the frequency a receiver moving with `receiver` (its four-velocity, finite however
    /// fast) measures over the frequency the source emitted (the source's Doppler factor into S
    /// times the receiver's out of S). The source's factor 1/(γ_L(1 − β_L·n)) (Eq. 4's time
    /// part) is taken from its four-velocity ([`FourVelocity::doppler_factor`]): at
    /// |β_L| = 1 − 10⁻¹⁶ the β form's 1 − β_L·n rounds to 0 for light sent straight ahead.
    #[must_use]
    pub fn doppler_to(&self, receiver: FourVelocity) -> f64 {
        FourVelocity::from_beta(self.source_beta).doppler_factor(self.direction)
            * receiver.receiver_doppler(self.direction)
    }

    /// The energy flux a receiver moving with `receiver` measures, per unit of the source's
    /// intensity (flux at unit distance in its rest frame): D_in² / r_L².
    #[must_use]
    pub fn flux_to(&self, receiver: FourVelocity) -> f64 {
        let doppler = self.doppler_to(receiver);
        doppler * doppler / (self.source_distance * self.source_distance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::LightVector;
    use crate::lorentz::lorentz_factor;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    /// The retarded time found by bisection on the worldline x(t) = a + β·ct in S alone:
    /// ct_E − ct = ‖x_E − x(ct)‖, independent of any Lorentz transformation.
    fn retarded_by_bisection(offset: DVec3, beta: DVec3, receiver: Event) -> Event {
        let gap = |ct: f64| (receiver.ct - ct) - (receiver.position - offset - beta * ct).length();
        let (mut lo, mut hi) = (receiver.ct - 1e6, receiver.ct);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if gap(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let ct = 0.5 * (lo + hi);
        Event::new(ct, offset + beta * ct)
    }

    fn velocity() -> impl Strategy<Value = DVec3> {
        (-0.55..0.55f64, -0.55..0.55f64, -0.55..0.55f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (-20.0..20.0f64, -20.0..20.0f64, -20.0..20.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        #[test]
        fn the_retarded_event_is_on_the_worldline_and_the_past_light_cone(
            beta in velocity(), offset in point(), at in point(), ct in -30.0..30.0f64,
        ) {
            let source = Frame::new(beta, offset).unwrap();
            let receiver = Event::new(ct, at);
            prop_assume!((at - offset - beta * ct).length() > 1e-3);
            let light = RetardedLight::reaching(&source, receiver).unwrap();
            let expected = retarded_by_bisection(offset, beta, receiver);
            let scale = 1.0 + expected.ct.abs() + expected.position.length();
            prop_assert!((light.source_event.ct - expected.ct).abs() < 1e-9 * scale);
            prop_assert!((light.source_event.position - expected.position).length() < 1e-9 * scale);
            // r_L: the null vector (r, r·n) boosted into the source's frame has time part
            // γ(r − β·r n).
            let r = receiver.ct - expected.ct;
            let gamma = lorentz_factor(beta);
            assert_relative_eq!(light.source_distance, gamma * r * (1.0 - beta.dot(light.direction)),
                max_relative = 1e-9);
        }

        #[test]
        fn the_doppler_factor_is_the_photon_frequency_seen_by_the_receiver(
            source_beta in velocity(), receiver_beta in velocity(), offset in point(), at in point(),
        ) {
            prop_assume!((at - offset).length() > 1e-3);
            let source = Frame::new(source_beta, offset).unwrap();
            let light = RetardedLight::reaching(&source, Event::new(0.0, at)).unwrap();
            // The photon in S, boosted into the source's and the receiver's rest frames.
            let photon = LightVector::new(1.0, light.direction);
            let emitted = photon.boosted(-source_beta).omega;
            let received = photon.boosted(-receiver_beta).omega;
            assert_relative_eq!(light.doppler_to(FourVelocity::from_beta(receiver_beta)), received / emitted, max_relative = 1e-12);
            // D_in = r_R / r_L: the receiver's distance is the same null vector's time part in
            // its frame.
            let r = light.source_distance / (lorentz_factor(source_beta) * (1.0 - source_beta.dot(light.direction)));
            let r_receiver = lorentz_factor(receiver_beta) * r * (1.0 - receiver_beta.dot(light.direction));
            assert_relative_eq!(light.doppler_to(FourVelocity::from_beta(receiver_beta)), r_receiver / light.source_distance,
                max_relative = 1e-12);
        }
    }

    /// A source at the fastest speeds `f64` writes (along an axis, |β| = 1 − 1.1·10⁻¹⁶, and the
    /// diagonal, |β| = 1 − 3·10⁻¹⁶) lighting receivers at rest straight ahead of it, straight
    /// behind and across its path: D_in (Eq. 4's time part) is the head-on γ(1 + β), its inverse
    /// and 1/γ across, and r_L = γ(1 − β·n)·r, all finite. With the β form of the source's
    /// Doppler factor, 1 − β·n rounds to 0 on the diagonal straight ahead (D_in = ∞).
    #[test]
    fn a_source_at_the_fastest_f64_speeds_gives_finite_doppler_factors_and_distances() {
        let edge = 0.999_999_999_999_999_9;
        let diagonal = 0.577_350_269_189_625_6;
        for beta in [
            DVec3::new(edge, 0.0, 0.0),
            DVec3::new(0.0, -edge, 0.0),
            DVec3::splat(diagonal),
        ] {
            let speed = beta.length();
            let along = beta / speed;
            let gamma = 1.0 / ((1.0 - speed) * (1.0 + speed)).sqrt();
            let source = Frame::new(beta, DVec3::ZERO).unwrap();
            let velocity = FourVelocity::from_beta(beta);
            for (place, expected) in [
                (along * 10.0, gamma * (1.0 + speed)),
                (-along * 10.0, 1.0 / (gamma * (1.0 + speed))),
            ] {
                let receiver = Event::new(0.0, place);
                let light = RetardedLight::reaching(&source, receiver).unwrap();
                let doppler = light.doppler_to(FourVelocity::REST);
                assert!(
                    doppler.is_finite() && light.flux_to(FourVelocity::REST).is_finite(),
                    "{beta} to {place}: D_in = {doppler}, {light:?}"
                );
                assert_relative_eq!(doppler, expected, max_relative = 1e-6);
                // The retarded event is on the source's worldline and the receiver's past
                // light cone (at |β| = 1 − 10⁻¹⁶ behind the source: ct = −10/(1 + β) = −5).
                let r = receiver.ct - light.source_event.ct;
                let gap = receiver.position - light.source_event.position;
                assert_relative_eq!(gap.length(), r, max_relative = 1e-9);
                let on_worldline = beta * light.source_event.ct;
                assert!((light.source_event.position - on_worldline).length() <= 1e-12 * r);
                let one_minus = velocity.gamma_one_minus_dot(light.direction);
                assert_relative_eq!(light.source_distance, one_minus * r, max_relative = 1e-6);
            }
            // Light crossing the source's path at right angles in S: D_in = 1/γ.
            let across = RetardedLight {
                direction: along.any_orthonormal_vector(),
                ..RetardedLight::reaching(&source, Event::new(0.0, DVec3::ONE)).unwrap()
            };
            assert_relative_eq!(
                across.doppler_to(FourVelocity::REST),
                1.0 / gamma,
                max_relative = 1e-6
            );
        }
    }

    #[test]
    fn a_source_at_rest_lights_with_the_inverse_square() {
        let source = Frame::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 3.0)).unwrap();
        let light =
            RetardedLight::reaching(&source, Event::new(5.0, DVec3::new(4.0, 0.0, 0.0))).unwrap();
        assert_relative_eq!(light.source_event.ct, 0.0, epsilon = 1e-12);
        assert_relative_eq!(light.source_distance, 5.0, epsilon = 1e-12);
        assert_relative_eq!(
            light.flux_to(FourVelocity::REST),
            1.0 / 25.0,
            epsilon = 1e-15
        );
        assert!(
            RetardedLight::reaching(&source, Event::new(1.0, DVec3::new(0.0, 0.0, 3.0))).is_none()
        );
    }

    #[test]
    fn an_approaching_source_is_brighter_by_the_square_of_its_doppler_factor() {
        // Head-on at 0.6c: D = 2. The receiver at the origin at ct = 0; the source reached x = 4
        // at ct = 0, so the light left it at x = 10, ct = −10, and travelled r_L = 5 in the
        // source's own frame (γ(1 − β·n) r = 1.25 · 0.4 · 10).
        let source = Frame::new(DVec3::new(-0.6, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0)).unwrap();
        let light = RetardedLight::reaching(&source, Event::new(0.0, DVec3::ZERO)).unwrap();
        assert_relative_eq!(light.source_event.position.x, 10.0, epsilon = 1e-12);
        assert_relative_eq!(light.doppler_to(FourVelocity::REST), 2.0, epsilon = 1e-12);
        assert_relative_eq!(light.source_distance, 5.0, epsilon = 1e-12);
        assert_relative_eq!(
            light.flux_to(FourVelocity::REST),
            4.0 / 25.0,
            epsilon = 1e-15
        );
    }
}
