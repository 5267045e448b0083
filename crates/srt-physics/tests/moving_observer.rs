//! A moving observer: boosts composed as matrices, checked against what does not use matrices —
//! the textbook velocity-composition formula, the closed-form Thomas–Wigner angle (Rhodes and
//! Semon, Am. J. Phys. 72, 943 (2004), Eq. 3; Thomas precession in the slow limit), and viewing
//! rays transformed by aberration (Eq. 4) instead of by the composed frame.

use glam::{DMat3, DMat4, DVec3, DVec4};
use proptest::prelude::*;
use srt_physics::{
    Event, Frame, MovingObserver, Poincare, aberrate, boost_and_rotation, lorentz_factor,
    lorentz_matrix,
};

use crate::common;
use common::{event, point, unit_vector, velocity};

/// Velocity composition written out (Einstein; e.g. Jackson, Classical Electrodynamics, 3rd
/// ed., Eq. 11.31 generalised to any angle): the velocity in S of a body moving with `u` in a
/// frame that moves with `v` relative to S.
fn composition_formula(v: DVec3, u: DVec3) -> DVec3 {
    let gamma = lorentz_factor(v);
    (u / gamma + v + gamma / (gamma + 1.0) * v.dot(u) * v) / (1.0 + v.dot(u))
}

/// The Thomas–Wigner angle of Λ_a Λ_b (Rhodes and Semon 2004, Eq. 3):
/// cos θ = (1 + γ + γ_a + γ_b)² / ((1 + γ)(1 + γ_a)(1 + γ_b)) − 1, γ = γ_a γ_b (1 + a·b).
fn wigner_angle(a: DVec3, b: DVec3) -> f64 {
    let (ga, gb) = (lorentz_factor(a), lorentz_factor(b));
    let g = ga * gb * (1.0 + a.dot(b));
    let cos = (1.0 + g + ga + gb).powi(2) / ((1.0 + g) * (1.0 + ga) * (1.0 + gb)) - 1.0;
    cos.clamp(-1.0, 1.0).acos()
}

/// Angle and unit axis of a rotation matrix: the antisymmetric part is 2 sin θ times the axis,
/// the trace 1 + 2 cos θ (zero axis for the identity).
fn angle_axis(r: DMat3) -> (f64, DVec3) {
    let cos = (r.col(0).x + r.col(1).y + r.col(2).z - 1.0) / 2.0;
    let axis = DVec3::new(
        r.col(1).z - r.col(2).y,
        r.col(2).x - r.col(0).z,
        r.col(0).y - r.col(1).x,
    );
    ((axis.length() / 2.0).atan2(cos), axis.normalize_or_zero())
}

fn block_rotation(r: DMat3) -> DMat4 {
    DMat4::from_cols(
        DVec4::X,
        DVec4::new(0.0, r.col(0).x, r.col(0).y, r.col(0).z),
        DVec4::new(0.0, r.col(1).x, r.col(1).y, r.col(1).z),
        DVec4::new(0.0, r.col(2).x, r.col(2).y, r.col(2).z),
    )
}

fn close_vec(a: DVec3, b: DVec3, tolerance: f64) -> bool {
    (a - b).length() <= tolerance * a.length().max(b.length()).max(1.0)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 512,
        ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)
    })]

    /// Λ_a Λ_b = Λ_w diag(1, R): the split reproduces the product, R is a proper rotation.
    #[test]
    fn boost_and_rotation_reassemble_the_product(a in velocity(0.99), b in velocity(0.99)) {
        let product = lorentz_matrix(a) * lorentz_matrix(b);
        let (w, r) = boost_and_rotation(product);
        let rebuilt = lorentz_matrix(w) * block_rotation(r);
        let scale = lorentz_factor(a) * lorentz_factor(b);
        prop_assert!(rebuilt.abs_diff_eq(product, 1e-12 * scale * scale));
        prop_assert!((r.transpose() * r).abs_diff_eq(DMat3::IDENTITY, 1e-12 * scale * scale));
        prop_assert!((r.determinant() - 1.0).abs() < 1e-12 * scale * scale);
    }

    /// The velocity part of Λ_a Λ_b is the relativistic composition of b (the body) in a frame
    /// moving with a, by the formula, not by a matrix.
    #[test]
    fn the_boost_part_is_the_composed_velocity(a in velocity(0.99), b in velocity(0.99)) {
        let (w, _) = boost_and_rotation(lorentz_matrix(a) * lorentz_matrix(b));
        prop_assert!(close_vec(w, composition_formula(a, b), 1e-12),
            "{w:?} vs {:?}", composition_formula(a, b));
    }

    /// The rotation part is the Thomas–Wigner rotation: the closed-form angle, about an axis
    /// along a × b (always the same sense).
    #[test]
    fn the_rotation_part_is_the_wigner_rotation(a in velocity(0.99), b in velocity(0.99)) {
        let (_, r) = boost_and_rotation(lorentz_matrix(a) * lorentz_matrix(b));
        let (angle, axis) = angle_axis(r);
        let expected = wigner_angle(a, b);
        prop_assert!((angle - expected).abs() < 1e-6, "{angle} vs {expected}");
        let normal = a.cross(b);
        if angle > 1e-6 && normal.length() > 1e-6 {
            // R rotates by θ about −(a × b): from b's direction towards a's.
            prop_assert!((axis + normal.normalize()).length() < 1e-6, "axis {axis:?}, a×b {normal:?}");
        }
    }

    /// The observer's rest frame: its worldline (ct, x_E + β_o (ct − ct_E)) in W is at rest at
    /// x_E in S, and S's clock is the observer's proper time.
    #[test]
    fn the_observer_rests_in_its_frame(beta in velocity(0.99), e in event(10.0), tau in -10.0..10.0f64) {
        let observer = MovingObserver::new(beta, e).unwrap();
        let gamma = lorentz_factor(beta);
        // The world event at proper time tau after E on the observer's worldline.
        let later = Event::new(e.ct + gamma * tau, e.position + gamma * tau * beta);
        let seen = observer.to_observer(later);
        prop_assert!(close_vec(seen.position, e.position, 1e-12 * gamma));
        prop_assert!((seen.ct - (e.ct + tau)).abs() < 1e-11 * gamma * gamma);
    }

    /// Every rest event of an object maps to the same event in S whether it goes through the
    /// world frame (S′ → W → S) or through the object's frame relative to the observer (the
    /// boost of `frame` after the Wigner rotation and the clock shift).
    #[test]
    fn the_relative_frame_maps_worldlines_exactly(beta_o in velocity(0.99), beta in velocity(0.99),
            offset in point(10.0), e in event(10.0), rest in event(10.0)) {
        let observer = MovingObserver::new(beta_o, e).unwrap();
        let world = Frame::new(beta, offset).unwrap();
        let relative = observer.relative_frame(&world).unwrap();
        let through_world = observer.to_observer(world.to_observer(rest));
        let rotated = Event::new(rest.ct + relative.rest_time_shift, relative.rotation * rest.position);
        let direct = relative.frame.to_observer(rotated);
        let scale = lorentz_factor(beta_o) * lorentz_factor(beta);
        let tolerance = 1e-12 * scale * scale * 100.0;
        prop_assert!((through_world.ct - direct.ct).abs() <= tolerance * through_world.ct.abs().max(1.0));
        prop_assert!(close_vec(through_world.position, direct.position, tolerance));
    }

    /// What the renderers use: the backward viewing ray in the object's rest frame. Through the
    /// relative frame (composed matrices) it equals the ray found by aberrating the incoming
    /// light into W (Eq. 4, the observer moving with β_o) and transforming it with the object's
    /// world frame, rotated by R.
    #[test]
    fn viewing_rays_agree_with_aberration_into_the_world(beta_o in velocity(0.99),
            beta in velocity(0.99), offset in point(10.0), e in event(10.0), view in unit_vector()) {
        let observer = MovingObserver::new(beta_o, e).unwrap();
        let world = Frame::new(beta, offset).unwrap();
        let relative = observer.relative_frame(&world).unwrap();
        let via_relative = relative.frame.backward_ray(e, view);
        let propagation_world = aberrate(beta_o, -view);
        let via_world = world.backward_ray(e, -propagation_world);
        let scale = lorentz_factor(beta_o) * lorentz_factor(beta);
        let tolerance = 1e-12 * scale * scale * 100.0;
        prop_assert!(close_vec(via_relative.direction, relative.rotation * via_world.direction, tolerance));
        prop_assert!(close_vec(via_relative.origin, relative.rotation * via_world.origin, tolerance));
        prop_assert!((via_relative.ct_origin - (via_world.ct_origin + relative.rest_time_shift)).abs()
            <= tolerance * via_world.ct_origin.abs().max(1.0));
    }

    /// Composing a frame with its own transformation and then the inverse is the identity
    /// (the group law of [`Poincare::then`]).
    #[test]
    fn poincare_composition_follows_the_group_law(beta in velocity(0.99), offset in point(10.0),
            x in event(10.0)) {
        let frame = Frame::new(beta, offset).unwrap();
        let forward = Poincare::of_frame(&frame);
        let back = Poincare {
            lorentz: frame.observer_to_rest_matrix(),
            translation: -(frame.observer_to_rest_matrix()
                * DVec4::new(0.0, offset.x, offset.y, offset.z)),
        };
        let round_trip = forward.then(&back).apply(x);
        let gamma = lorentz_factor(beta);
        prop_assert!(close_vec(round_trip.position, x.position, 1e-12 * gamma * gamma * 10.0));
        prop_assert!((round_trip.ct - x.ct).abs() < 1e-11 * gamma * gamma * x.ct.abs().max(10.0));
        prop_assert_eq!(frame.to_observer(x), forward.apply(x));
    }
}

/// Two perpendicular boosts: cos θ = (γ_a + γ_b)/(1 + γ_a γ_b) (the perpendicular case of the
/// closed form; Rhodes and Semon 2004, Eq. 4), e.g. two boosts of 0.6c: cos θ = 2.5/2.5625.
#[test]
fn perpendicular_boosts_of_six_tenths() {
    let a = DVec3::new(0.6, 0.0, 0.0);
    let b = DVec3::new(0.0, 0.6, 0.0);
    let (w, r) = boost_and_rotation(lorentz_matrix(a) * lorentz_matrix(b));
    let (angle, axis) = angle_axis(r);
    assert!(
        (angle.cos() - 2.5 / 2.5625).abs() < 1e-14,
        "{}",
        angle.cos()
    );
    assert!(
        (angle.to_degrees() - 12.680_383).abs() < 1e-5,
        "{}",
        angle.to_degrees()
    );
    assert!((axis - DVec3::NEG_Z).length() < 1e-12);
    // Composed speed: b contracted by 1/γ_a, plus a: (0.6, 0.48, 0), |w|² = 0.36 + 0.2304.
    assert!((w - DVec3::new(0.6, 0.48, 0.0)).length() < 1e-15);
}

/// Slow boosts: the Thomas rotation angle tends to ½|a × b| (c = 1; the Thomas precession,
/// Jackson §11.8).
#[test]
fn slow_boosts_rotate_by_half_the_cross_product() {
    let a = DVec3::new(1e-3, 0.0, 0.0);
    let b = DVec3::new(0.0, 2e-3, 0.0);
    let (_, r) = boost_and_rotation(lorentz_matrix(a) * lorentz_matrix(b));
    let (angle, _) = angle_axis(r);
    let thomas = 0.5 * a.cross(b).length();
    assert!((angle / thomas - 1.0).abs() < 1e-5, "{angle} vs {thomas}");
}

/// Collinear boosts do not rotate, and an object moving with the observer is at rest in S.
#[test]
fn collinear_and_comoving_cases() {
    let a = DVec3::new(0.3, 0.4, 0.0);
    let (w, r) = boost_and_rotation(lorentz_matrix(a) * lorentz_matrix(a * 1.5));
    assert!((r - DMat3::IDENTITY).abs_diff_eq(DMat3::ZERO, 1e-14));
    assert!(w.cross(a).length() < 1e-15);

    let e = Event::new(2.0, DVec3::new(0.0, -3.0, 1.0));
    let observer = MovingObserver::new(DVec3::new(0.0, 0.95, 0.0), e).unwrap();
    let companion = Frame::new(DVec3::new(0.0, 0.95, 0.0), DVec3::new(1.0, 0.0, 0.0)).unwrap();
    let relative = observer.relative_frame(&companion).unwrap();
    assert!(relative.frame.beta().length() < 1e-14);
    assert!((relative.rotation - DMat3::IDENTITY).abs_diff_eq(DMat3::ZERO, 1e-13));
}
