//! Relativistic flight (`flight.rs`) against what does not step: the closed form of hyperbolic
//! motion (Rindler, *Relativity*, 2nd ed., §3.8: from rest, ct = sinh(ατ)/α,
//! x = (cosh(ατ) − 1)/α, rapidity ατ), boosts composed as matrices (`observer.rs`), and the
//! invariants every step must keep (|β| < 1, u·u = 1, dτ² = dct² − dx² when coasting).

use glam::{DVec3, DVec4};
use proptest::prelude::*;
use srt_physics::flight::Worldline;
use srt_physics::{Event, Poincare, boost_and_rotation, lorentz_matrix};

use crate::common;
use common::{event, unit_vector, velocity};

/// u·u with the signature (+, −, −, −).
fn norm(u: DVec4) -> f64 {
    u.x * u.x - u.y * u.y - u.z * u.z - u.w * u.w
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)
    })]

    /// From rest at the origin, a constant proper acceleration along a fixed axis gives the
    /// hyperbolic worldline, in one step or in many.
    #[test]
    fn constant_acceleration_is_hyperbolic_motion(
        axis in unit_vector(),
        alpha in 0.01..3.0f64,
        tau in 0.0..4.0f64,
        steps in 1usize..40,
    ) {
        let start = Worldline::new(Event::new(0.0, DVec3::ZERO), DVec3::ZERO).unwrap();
        let dtau = tau / steps as f64;
        let end = (0..steps).fold(start, |w, _| w.advance(alpha * axis, dtau));
        let (ct, x) = ((alpha * tau).sinh() / alpha, ((alpha * tau).cosh() - 1.0) / alpha);
        let scale = 1.0 + ct;
        prop_assert!((end.rapidity() - alpha * tau).abs() < 1e-9 * (1.0 + alpha * tau));
        prop_assert!((end.event.ct - ct).abs() < 1e-9 * scale);
        prop_assert!((end.event.position - x * axis).length() < 1e-9 * scale);
        prop_assert!((end.proper_time - tau).abs() < 1e-12 * (1.0 + tau));
        if tau > 0.0 {
            prop_assert!((end.beta().normalize() - axis).length() < 1e-9);
        }
    }

    /// Whatever the steps, the speed stays below light and the four-velocity normalised.
    #[test]
    fn the_speed_stays_below_light(
        beta in velocity(0.99),
        pushes in proptest::collection::vec((unit_vector(), 0.0..5.0f64, 0.0..2.0f64), 1..20),
    ) {
        let mut w = Worldline::new(Event::new(0.0, DVec3::ZERO), beta).unwrap();
        for (direction, alpha, dtau) in pushes {
            w = w.advance(alpha * direction, dtau).with_rapidity_at_most(8.0);
            prop_assert!(w.beta().length() < 1.0);
            prop_assert!(w.rapidity() <= 8.0 + 1e-12);
            prop_assert!((norm(w.four_velocity) - 1.0).abs() < 1e-9 * w.gamma() * w.gamma());
            prop_assert!(w.event.is_finite());
        }
    }

    /// Two pushes in perpendicular directions of the rest frame give the four-velocity of the
    /// product of the two boosts, Λ_β₁ Λ_β₂ (1, 0), composed by `Poincare::then`, and the
    /// velocity `boost_and_rotation` reads off that product.
    #[test]
    fn perpendicular_pushes_compose_as_boost_matrices(
        phi1 in 0.0..3.0f64,
        phi2 in 0.0..3.0f64,
        alpha in 0.1..2.0f64,
    ) {
        let start = Worldline::new(Event::new(0.0, DVec3::ZERO), DVec3::ZERO).unwrap();
        let end = start
            .advance(alpha * DVec3::X, phi1 / alpha)
            .advance(alpha * DVec3::Y, phi2 / alpha);
        let boost = |beta: DVec3| Poincare { lorentz: lorentz_matrix(beta), translation: DVec4::ZERO };
        let first = boost(phi1.tanh() * DVec3::X);
        let second = boost(phi2.tanh() * DVec3::Y);
        // The second push acts in the rest frame reached by the first: S₂ → S₁ → W.
        let composed = second.then(&first);
        let expected = composed.lorentz * DVec4::new(1.0, 0.0, 0.0, 0.0);
        let scale = expected.x;
        prop_assert!((end.four_velocity - expected).length() < 1e-9 * scale);
        let (w, _rotation) = boost_and_rotation(composed.lorentz);
        prop_assert!((end.beta() - w).length() < 1e-9);
    }

    /// Coasting is uniform motion: proper time is the Minkowski length of the step.
    #[test]
    fn coasting_keeps_the_velocity_and_ages_by_the_interval(
        start in event(10.0),
        beta in velocity(0.999),
        dtau in 0.0..10.0f64,
    ) {
        let w = Worldline::new(start, beta).unwrap();
        let later = w.advance(DVec3::ZERO, dtau);
        prop_assert!((later.beta() - beta).length() < 1e-12);
        let dct = later.event.ct - start.ct;
        let dx = (later.event.position - start.position).length();
        prop_assert!(((dct * dct - dx * dx).max(0.0).sqrt() - dtau).abs() < 1e-7 * (1.0 + dct));
    }

    /// Braking always ends at rest, after exactly φ/α of proper time.
    #[test]
    fn braking_takes_rapidity_over_acceleration(beta in velocity(0.999), alpha in 0.1..5.0f64) {
        let w = Worldline::new(Event::new(0.0, DVec3::ZERO), beta).unwrap();
        let phi = w.rapidity();
        let (almost, stopped) = w.brake(alpha, 0.999 * phi / alpha);
        prop_assert!(!stopped || phi == 0.0);
        prop_assert!(almost.rapidity() <= phi * 0.0011 + 1e-12);
        let (rest, stopped) = almost.brake(alpha, phi / alpha);
        prop_assert!(stopped);
        prop_assert_eq!(rest.beta(), DVec3::ZERO);
    }
}
