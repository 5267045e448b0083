//! Property tests of the relativistic transforms, plus checks against independent
//! implementations (matrix exponential of the boost generator, a light-cone solve done in S).

use approx::assert_relative_eq;
use glam::{DMat4, DVec3, DVec4};
use proptest::prelude::*;
use srt_physics::{
    Event, Frame, LightVector, aberrate, compose_velocities, doppler_factor, lorentz_factor,
    lorentz_matrix, minkowski_interval, rapidity, reflection_doppler,
};

use crate::common;
use common::{event, point, unit_vector, velocity};

/// Relative closeness of two scalars, with an absolute floor for values near zero.
fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1.0)
}

fn close_vec(a: DVec3, b: DVec3, rel: f64) -> bool {
    (a - b).length() <= rel * a.length().max(b.length()).max(1.0)
}

/// Minkowski metric η = diag(−1, 1, 1, 1) applied as a quadratic form.
fn interval(v: DVec4) -> f64 {
    -v.x * v.x + v.y * v.y + v.z * v.z + v.w * v.w
}

/// Boost matrix computed independently of Eq. 2: exp(η K) with K the boost generator along n,
/// summed as a power series.
fn boost_by_exponential(beta: DVec3) -> DMat4 {
    let speed = beta.length();
    if speed == 0.0 {
        return DMat4::IDENTITY;
    }
    let n = beta / speed;
    let eta = speed.atanh();
    let generator = DMat4::from_cols(
        DVec4::new(0.0, n.x, n.y, n.z),
        DVec4::new(n.x, 0.0, 0.0, 0.0),
        DVec4::new(n.y, 0.0, 0.0, 0.0),
        DVec4::new(n.z, 0.0, 0.0, 0.0),
    ) * eta;
    let mut term = DMat4::IDENTITY;
    let mut sum = DMat4::IDENTITY;
    for k in 1..200 {
        term = term * generator * (1.0 / f64::from(k));
        sum += term;
    }
    sum
}

/// Apparent position computed independently, entirely in S: the point's worldline in S is
/// x(t) = a + x′_⊥ + x′_∥/γ + β ct (length contraction plus motion; simultaneity shift
/// accounted for through the emission time); solve ‖x(t_e) − x_obs‖ = ct_obs − ct_e.
fn apparent_position_in_s(beta: DVec3, offset: DVec3, rest: DVec3, observer: Event) -> DVec3 {
    let gamma = lorentz_factor(beta);
    let speed2 = beta.length_squared();
    // Position at S-time t = 0 of the point at rest at `rest` in S′: a + `rest` contracted by
    // 1/γ along β (the t = 0 slice is the ct′ = −β·rest slice of S′).
    let contracted = if speed2 > 0.0 {
        rest - (1.0 - 1.0 / gamma) * rest.dot(beta) / speed2 * beta
    } else {
        rest
    };
    let x0 = offset + contracted;
    // ‖x0 + β ct − x_obs‖² = (ct_obs − ct)², ct < ct_obs. Let u = x0 − x_obs.
    let u = x0 - observer.position;
    // (β·β − 1) ct² + 2 (u·β + ct_obs) ct + u·u − ct_obs² = 0
    let qa = speed2 - 1.0;
    let qb = 2.0 * (u.dot(beta) + observer.ct);
    let qc = u.length_squared() - observer.ct * observer.ct;
    let disc = (qb * qb - 4.0 * qa * qc).sqrt();
    // One root lies on the past light cone, the other on the future one: take the earlier.
    let ct = ((-qb + disc) / (2.0 * qa)).min((-qb - disc) / (2.0 * qa));
    x0 + beta * ct
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 512,
        ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)
    })]

    #[test]
    fn boost_and_inverse_boost_cancel(beta in velocity(0.999)) {
        let product = lorentz_matrix(beta) * lorentz_matrix(-beta);
        let gamma = lorentz_factor(beta);
        prop_assert!(product.abs_diff_eq(DMat4::IDENTITY, 1e-12 * gamma * gamma));
    }

    #[test]
    fn boost_matches_matrix_exponential(beta in velocity(0.99)) {
        let eq2 = lorentz_matrix(beta);
        let exp = boost_by_exponential(beta);
        let scale = lorentz_factor(beta);
        for c in 0..4 {
            for r in 0..4 {
                prop_assert!(close(eq2.col(c)[r], exp.col(c)[r], 1e-9 * scale),
                    "Λ[{r}][{c}] = {} vs exp: {}", eq2.col(c)[r], exp.col(c)[r]);
            }
        }
    }

    #[test]
    fn minkowski_interval_is_preserved(beta in velocity(0.99), offset in point(10.0),
                                       a in event(10.0), b in event(10.0)) {
        let frame = Frame::new(beta, offset).unwrap();
        let before = minkowski_interval(a, b);
        let after = minkowski_interval(frame.to_rest(a), frame.to_rest(b));
        let scale = 400.0 * frame.gamma() * frame.gamma();
        prop_assert!((before - after).abs() <= 1e-12 * scale, "{before} vs {after}");
        // Poincaré round trip.
        let back = frame.to_observer(frame.to_rest(a));
        prop_assert!((back.ct - a.ct).abs() < 1e-9 && (back.position - a.position).length() < 1e-9);
    }

    #[test]
    fn null_vectors_stay_null(beta in velocity(0.999), n in unit_vector(), omega in 0.1..10.0f64) {
        let k = LightVector::new(omega, n).to_four_vector();
        let boosted = lorentz_matrix(beta) * k;
        let scale = boosted.x * boosted.x;
        prop_assert!(interval(boosted).abs() <= 1e-12 * scale);
        prop_assert!(boosted.x > 0.0, "light keeps positive frequency");
    }

    #[test]
    fn emission_event_is_on_the_backward_light_cone(beta in velocity(0.99), offset in point(10.0),
                                                   p in point(5.0), obs in event(10.0)) {
        let frame = Frame::new(beta, offset).unwrap();
        let emission_rest = frame.emission_event(p, obs);
        let emission = frame.to_observer(emission_rest);
        let scale = (emission.position - obs.position).length_squared().max(1.0);
        prop_assert!(minkowski_interval(emission, obs).abs() <= 1e-10 * scale);
        prop_assert!(emission.ct <= obs.ct, "light is emitted before it is seen");
        prop_assert!(emission_rest.ct <= frame.to_rest(obs).ct);
        // Its distance from the observer is the light travel time.
        let distance = (frame.apparent_position(p, obs) - obs.position).length();
        prop_assert!(close(distance, obs.ct - emission.ct, 1e-10));
    }

    #[test]
    fn apparent_position_matches_a_solve_in_s(beta in velocity(0.99), offset in point(10.0),
                                              p in point(5.0), obs in event(10.0)) {
        let frame = Frame::new(beta, offset).unwrap();
        let ours = frame.apparent_position(p, obs);
        let independent = apparent_position_in_s(beta, offset, p, obs);
        prop_assert!(close_vec(ours, independent, 1e-9), "{ours} vs {independent}");
    }

    #[test]
    fn measured_positions_are_simultaneous_in_s_and_on_the_worldline(beta in velocity(0.99),
            offset in point(10.0), p in point(5.0), ct in -10.0..10.0f64) {
        let frame = Frame::new(beta, offset).unwrap();
        let event = frame.event_at_time(p, ct);
        prop_assert!(close(event.ct, ct, 1e-12), "{} vs {ct}", event.ct);
        // Independently: the point moves with β through its position at t = 0 in S.
        let at_zero = frame.event_at_time(p, 0.0).position;
        prop_assert!(close_vec(event.position, at_zero + beta * ct, 1e-10));
        // And it is the rest point: back in S′ it sits at p.
        prop_assert!(close_vec(frame.to_rest(event).position, p, 1e-10));
    }

    #[test]
    fn a_rod_along_beta_is_measured_contracted_by_gamma(n in unit_vector(), speed in 0.0..0.99f64,
            offset in point(10.0), start in point(5.0), length in 0.1..10.0f64,
            ct in -10.0..10.0f64) {
        let frame = Frame::new(n * speed, offset).unwrap();
        let a = frame.event_at_time(start, ct).position;
        let b = frame.event_at_time(start + length * n, ct).position;
        let gamma = 1.0 / (1.0 - speed * speed).sqrt();
        prop_assert!(close((b - a).length(), length / gamma, 1e-10));
        prop_assert!(close_vec(b - a, (length / gamma) * n, 1e-10), "along β");
        // A rod across β keeps its length.
        let across = n.any_orthonormal_vector();
        let c = frame.event_at_time(start + length * across, ct).position;
        prop_assert!(close((c - a).length(), length, 1e-10));
    }

    #[test]
    fn collinear_boosts_add_rapidities(n in unit_vector(), a in 0.0..0.99f64, b in 0.0..0.99f64) {
        let composed = compose_velocities(n * a, n * b);
        prop_assert!(close(rapidity(composed), a.atanh() + b.atanh(), 1e-9));
        prop_assert!(close_vec(composed.normalize_or_zero(), n, 1e-12) || composed.length() < 1e-12);
        // Composition is a group law on boost matrices for collinear velocities.
        let product = lorentz_matrix(n * a) * lorentz_matrix(n * b);
        let scale = lorentz_factor(composed);
        prop_assert!(product.abs_diff_eq(lorentz_matrix(composed), 1e-9 * scale));
    }

    #[test]
    fn composed_velocities_stay_subluminal(v in velocity(0.999), u in velocity(0.999)) {
        prop_assert!(compose_velocities(v, u).length() < 1.0);
    }

    #[test]
    fn doppler_and_aberration_are_the_two_parts_of_eq_4(beta in velocity(0.99), n_rest in unit_vector(),
                                                        omega in 0.1..10.0f64) {
        let rest = LightVector::new(omega, n_rest);
        let seen = rest.boosted(beta);
        // Time-like part: ω = ω′ γ (1 + β·n′).
        let gamma = lorentz_factor(beta);
        prop_assert!(close(seen.omega, omega * gamma * (1.0 + beta.dot(n_rest)), 1e-12));
        // Space-like part: the aberrated direction.
        let n = aberrate(beta, n_rest);
        prop_assert!(close_vec(seen.direction, n, 1e-9));
        prop_assert!((n.length() - 1.0).abs() < 1e-9);
        // The closed form in S-directions agrees with the ratio of frequencies.
        prop_assert!(close(doppler_factor(beta, n), seen.omega / omega, 1e-9));
        // Aberration with −β undoes it.
        prop_assert!(close_vec(aberrate(-beta, n), n_rest, 1e-9));
    }

    #[test]
    fn reflection_doppler_is_absorption_then_emission(beta in velocity(0.99), n_in in unit_vector(),
                                                      n_out in unit_vector()) {
        // Absorb in S′ (ω′ = ω / D(β, n_in)) and re-emit (ω = ω′ D(β, n_out)).
        let expected = doppler_factor(beta, n_out) / doppler_factor(beta, n_in);
        prop_assert!(close(reflection_doppler(beta, n_in, n_out), expected, 1e-12));
    }

    #[test]
    fn apparent_tangent_matches_finite_differences(beta in velocity(0.95), offset in point(10.0),
                                                   p in point(5.0), e in unit_vector(), obs in event(10.0)) {
        let frame = Frame::new(beta, offset).unwrap();
        let rest_obs = frame.to_rest(obs).position;
        prop_assume!((p - rest_obs).length() > 0.5);
        let h = 1e-5;
        let fd = (frame.apparent_position(p + h * e, obs) - frame.apparent_position(p - h * e, obs)) / (2.0 * h);
        let exact = frame.apparent_tangent(p, e, obs);
        prop_assert!(close_vec(fd, exact, 1e-6), "{fd} vs {exact}");
    }

    #[test]
    fn backward_ray_reaches_the_apparent_position(beta in velocity(0.99), offset in point(10.0),
                                                  p in point(5.0), obs in event(10.0)) {
        // The ray through the apparent direction of p passes through p in S′, and the event on
        // the ray at p is p's emission event.
        let frame = Frame::new(beta, offset).unwrap();
        let seen = frame.apparent_position(p, obs);
        prop_assume!((seen - obs.position).length() > 1e-3);
        let ray = frame.backward_ray(obs, seen - obs.position);
        let s = (p - ray.origin).dot(ray.direction);
        let closest = ray.origin + s * ray.direction;
        prop_assert!((closest - p).length() <= 1e-9 * (1.0 + s.abs()), "misses by {}", (closest - p).length());
        let emission = frame.emission_event(p, obs);
        prop_assert!(close(ray.event_at(s).ct, emission.ct, 1e-9));
        // The closed-form apparent distance is the light travel time in S.
        let travel = obs.ct - frame.to_observer(ray.event_at(s)).ct;
        prop_assert!(close(frame.apparent_distance(&ray, s), travel, 1e-9));
        prop_assert!(close(frame.apparent_distance(&ray, s), (seen - obs.position).length(), 1e-9));
    }
}

#[test]
fn radar_echo_from_a_head_on_approach() {
    for b in [0.1, 0.5, 0.9, 0.99] {
        // Object at +x approaching the observer (at the origin) with speed b.
        let beta = DVec3::new(-b, 0.0, 0.0);
        let d = reflection_doppler(beta, DVec3::X, -DVec3::X);
        assert_relative_eq!(d, (1.0 + b) / (1.0 - b), max_relative = 1e-14);
    }
}

#[test]
fn published_doppler_temperatures() {
    // §3.3 / Fig. 5: 6000 K at 0.2c, approaching → 7348 K, receding → 4899 K. The text's
    // "√3/2" is a typo for √(3/2) = √((1+b)/(1−b)) with b = 0.2.
    let b = 0.2;
    let approaching = doppler_factor(DVec3::new(-b, 0.0, 0.0), -DVec3::X);
    let receding = doppler_factor(DVec3::new(b, 0.0, 0.0), -DVec3::X);
    assert_relative_eq!(approaching, 1.5f64.sqrt(), max_relative = 1e-14);
    assert_eq!((6000.0 * approaching).round(), 7348.0);
    assert_eq!((6000.0 * receding).round(), 4899.0);
}
