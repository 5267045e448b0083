//! Light at moving mirrors and glass, exact: the light is taken into the surface's rest frame
//! (Eq. 3, [`LightVector::boosted`]), reflected or refracted there by the ordinary laws, and
//! taken back. Nothing here is a formula of a moving mirror or a moving medium: Einstein's
//! reflection from a moving mirror (1905, §8: the reflected angle and frequency) and Fizeau's
//! drag of light by moving water (1851, the coefficient 1 − 1/n²) follow, and the tests hold
//! these functions to those published formulas.
//!
//! Directions are unit propagation directions (from the emitter onwards), as everywhere in
//! this crate; a surface's `normal_rest` is a unit normal in its rest frame, on either side.
//! This is the physics of issue 70's materials (`mirror`, `glass`); no renderer traces
//! bounced light yet.

use glam::DVec3;

use crate::light::LightVector;
use crate::lorentz::{compose_velocities, lorentz_factor};

/// `light` (described in S) after a mirror that moves with `beta` relative to S reflects it:
/// in the mirror's rest frame S′ the light keeps its frequency and its direction is mirrored in
/// the plane of the unit normal `normal_rest` (n′ − 2(n′·m)m); the result is described in S.
/// Its frequency over the incident one is the Doppler factor of the reflection: for a mirror
/// at rest, 1.
#[must_use]
pub fn reflect(light: LightVector, beta: DVec3, normal_rest: DVec3) -> LightVector {
    let rest = light.boosted(-beta);
    let mirrored = rest.direction.reflect(normal_rest);
    LightVector {
        omega: rest.omega,
        direction: mirrored,
    }
    .boosted(beta)
}

/// What happens to light that meets the boundary between two clear media at rest in the same
/// frame, in that frame ([`refract_at_rest`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Refraction {
    /// The share of the light's power reflected (Fresnel's equations, unpolarised light: the
    /// mean of the s and p reflectances); 1 for total internal reflection.
    pub reflectance: f64,
    /// The reflected light's unit direction.
    pub reflected: DVec3,
    /// The transmitted light's unit direction (Snell's law), `None` for total internal
    /// reflection.
    pub transmitted: Option<DVec3>,
}

/// Light travelling along the unit `direction` in a medium of refractive index `from_index`
/// meets a medium of index `to_index` at a boundary of unit normal `normal` (either side), all
/// at rest: Snell's law (n₁ sin θ₁ = n₂ sin θ₂) for the transmitted direction, the law of
/// reflection, and Fresnel's reflectance for unpolarised light, R = ½ (R_s + R_p) with
/// R_s = ((n₁cos θ₁ − n₂cos θ₂)/(n₁cos θ₁ + n₂cos θ₂))² and
/// R_p = ((n₁cos θ₂ − n₂cos θ₁)/(n₁cos θ₂ + n₂cos θ₁))².
#[must_use]
pub fn refract_at_rest(
    direction: DVec3,
    normal: DVec3,
    from_index: f64,
    to_index: f64,
) -> Refraction {
    // The normal facing the way the light goes, so that cos θ₁ ≥ 0.
    let along = if direction.dot(normal) < 0.0 {
        -normal
    } else {
        normal
    };
    let cos_in = direction.dot(along).min(1.0);
    let reflected = direction.reflect(along);
    let ratio = from_index / to_index;
    let sin_out_squared = ratio * ratio * (1.0 - cos_in * cos_in);
    if sin_out_squared >= 1.0 {
        return Refraction {
            reflectance: 1.0,
            reflected,
            transmitted: None,
        };
    }
    let cos_out = (1.0 - sin_out_squared).sqrt();
    // glam's Snell: the normal must face the light.
    let transmitted = direction.refract(-along, ratio);
    let (n1, n2) = (from_index, to_index);
    let s = (n1 * cos_in - n2 * cos_out) / (n1 * cos_in + n2 * cos_out);
    let p = (n1 * cos_out - n2 * cos_in) / (n1 * cos_out + n2 * cos_in);
    Refraction {
        reflectance: 0.5 * (s * s + p * p),
        reflected,
        transmitted: Some(transmitted.normalize()),
    }
}

/// Light inside a clear medium: where it goes and how fast, and its frequency, in S.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightInMedium {
    /// Its velocity in S (in units of c): the composition of the medium's velocity and the
    /// light's c/n along its direction in the medium's rest frame.
    pub velocity: DVec3,
    /// Its circular frequency in S.
    pub omega: f64,
}

/// `light` (in S, in vacuum) meeting the surface of a clear medium of refractive index `index`
/// that moves with `beta` relative to S, its unit surface normal `normal_rest` in its rest frame:
/// the reflected light (in S, vacuum), the reflectance, and the light that enters the medium (in
/// S), `None` where none does. In the medium's rest frame the boundary is at rest: the
/// frequency is kept and [`refract_at_rest`] applies.
#[must_use]
pub fn enter_medium(
    light: LightVector,
    beta: DVec3,
    normal_rest: DVec3,
    index: f64,
) -> (LightVector, f64, Option<LightInMedium>) {
    let rest = light.boosted(-beta);
    let at_rest = refract_at_rest(rest.direction, normal_rest, 1.0, index);
    let reflected = LightVector {
        omega: rest.omega,
        direction: at_rest.reflected,
    }
    .boosted(beta);
    // The light's wave four-vector in the medium's rest frame, k′ = ω′(1, n d′) (phase velocity
    // c/n), taken into S: ω = γ (ω′ + β·k′).
    let entered = at_rest.transmitted.map(|direction| LightInMedium {
        velocity: compose_velocities(beta, direction / index),
        omega: lorentz_factor(beta) * rest.omega * (1.0 + index * beta.dot(direction)),
    });
    (reflected, at_rest.reflectance, entered)
}

/// The speed in S, in units of c, of light travelling along the unit `direction_rest` (in the
/// medium's rest frame) through a clear medium of refractive index `index` that moves with
/// `beta`: c/n in the rest frame composed with the medium's velocity. Along the motion at speed
/// v this is (c/n + v)/(1 + v/(nc)) ≈ c/n + v (1 − 1/n²): Fizeau's drag.
#[must_use]
pub fn speed_in_moving_medium(direction_rest: DVec3, index: f64, beta: DVec3) -> f64 {
    compose_velocities(beta, direction_rest.normalize() / index).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    /// Asserts that `a` and `b` are less than `tolerance` apart.
    fn assert_near(a: DVec3, b: DVec3, tolerance: f64) {
        assert!(
            (a - b).length() < tolerance,
            "{a} and {b} differ by more than {tolerance}"
        );
    }

    /// Einstein 1905, §8: a mirror moving with speed β·c along its normal (the x axis), light
    /// of frequency ν meeting it at angle φ to that axis. The reflected light has
    /// ν‴ = ν (1 − 2β cos φ + β²)/(1 − β²) and cos φ‴ = −[(1 + β²) cos φ − 2β]/(1 − 2β cos φ + β²).
    fn einstein(beta: f64, cos_phi: f64) -> (f64, f64) {
        let denominator = 1.0 - 2.0 * beta * cos_phi + beta * beta;
        (
            denominator / (1.0 - beta * beta),
            -((1.0 + beta * beta) * cos_phi - 2.0 * beta) / denominator,
        )
    }

    proptest! {
        /// The reflected frequency and angle are Einstein's, for a mirror receding or
        /// approaching (the light must catch it: cos φ > β).
        #[test]
        fn a_mirror_moving_along_its_normal_reflects_as_einstein_found(
            beta in -0.99_f64..0.99,
            phi in 0.0_f64..1.5,
            azimuth in 0.0_f64..6.2,
        ) {
            prop_assume!(phi.cos() > beta + 1e-3);
            let direction = DVec3::new(
                phi.cos(),
                phi.sin() * azimuth.cos(),
                phi.sin() * azimuth.sin(),
            );
            let incident = LightVector::new(2.0, direction);
            let reflected = reflect(incident, DVec3::new(beta, 0.0, 0.0), DVec3::X);
            let (frequency_ratio, cos_reflected) = einstein(beta, phi.cos());
            prop_assert!((reflected.omega / 2.0 - frequency_ratio).abs() < 1e-11 * frequency_ratio);
            prop_assert!((reflected.direction.x - cos_reflected).abs() < 1e-11);
            // The plane of incidence is kept: the tangential direction turns neither way.
            let tangential = DVec3::new(0.0, reflected.direction.y, reflected.direction.z);
            let incident_tangential = DVec3::new(0.0, direction.y, direction.z);
            prop_assert!(tangential.cross(incident_tangential).length() < 1e-12);
            // A unit direction, to rounding that grows as 1/(1 − |β|) (the boost's cancellation).
            prop_assert!((reflected.direction.length() - 1.0).abs() < 1e-13 / (1.0 - beta.abs()));
        }

        /// Reflection is reversible in time: the reflected light sent back the way it came, at
        /// the mirror moving the other way (time reversal reverses every velocity), returns as
        /// the incident light arrived, reversed, with its frequency; for any velocity and normal.
        #[test]
        fn reflection_is_reversible(
            beta in prop::array::uniform3(-0.55_f64..0.55),
            normal in prop::array::uniform3(-1.0_f64..1.0),
            direction in prop::array::uniform3(-1.0_f64..1.0),
        ) {
            let (beta, normal, direction) =
                (DVec3::from_array(beta), DVec3::from_array(normal), DVec3::from_array(direction));
            prop_assume!(normal.length() > 0.1 && direction.length() > 0.1);
            let normal = normal.normalize();
            let incident = LightVector::new(1.0, direction);
            let out = reflect(incident, beta, normal);
            let reversed = LightVector { omega: out.omega, direction: -out.direction };
            let back = reflect(reversed, -beta, normal);
            prop_assert!((back.omega - 1.0).abs() < 1e-10);
            prop_assert!((back.direction + incident.direction).length() < 1e-10);
        }

        /// A mirror moving in its own plane reflects by the ordinary law, without Doppler
        /// shift: its surface is the same at every time.
        #[test]
        fn a_mirror_sliding_in_its_plane_reflects_as_at_rest(
            speed in -0.95_f64..0.95,
            direction in prop::array::uniform3(-1.0_f64..1.0),
        ) {
            let direction = DVec3::from_array(direction);
            prop_assume!(direction.length() > 0.1);
            let incident = LightVector::new(1.0, direction);
            let out = reflect(incident, DVec3::new(0.0, speed, 0.0), DVec3::Z);
            let expected = incident.direction.reflect(DVec3::Z);
            prop_assert!((out.omega - 1.0).abs() < 1e-12);
            prop_assert!((out.direction - expected).length() < 1e-12);
        }
    }

    /// Radar: light sent head-on at a mirror approaching at speed b returns straight back with
    /// D = (1 + b)/(1 − b), as `reflection_doppler` (Eq. 17) has it.
    #[test]
    fn head_on_radar_off_an_approaching_mirror() {
        let b = 0.6;
        let out = reflect(
            LightVector::new(1.0, DVec3::X),
            DVec3::new(-b, 0.0, 0.0),
            DVec3::X,
        );
        assert_relative_eq!(out.omega, (1.0 + b) / (1.0 - b), epsilon = 1e-12);
        assert_near(out.direction, -DVec3::X, 1e-12);
        let eq_17 = crate::light::reflection_doppler(DVec3::new(-b, 0.0, 0.0), DVec3::X, -DVec3::X);
        assert_relative_eq!(out.omega, eq_17, epsilon = 1e-12);
    }

    /// Fresnel and Snell at rest: ((n − 1)/(n + 1))² at normal incidence, no p-polarised
    /// reflection at Brewster's angle (so R = R_s/2 there), Snell's law, total internal
    /// reflection beyond the critical angle, and the reflectance rising to 1 at grazing
    /// incidence.
    #[test]
    fn glass_at_rest_follows_snell_and_fresnel() {
        let n = 1.5;
        let normal_incidence = refract_at_rest(-DVec3::Z, DVec3::Z, 1.0, n);
        assert_relative_eq!(normal_incidence.reflectance, 0.04, epsilon = 1e-15);
        assert_near(normal_incidence.transmitted.unwrap(), -DVec3::Z, 1e-15);

        let brewster = n.atan();
        let direction = DVec3::new(brewster.sin(), 0.0, -brewster.cos());
        let at_brewster = refract_at_rest(direction, DVec3::Z, 1.0, n);
        let cos_t = (1.0 - (brewster.sin() / n).powi(2)).sqrt();
        let r_s = ((brewster.cos() - n * cos_t) / (brewster.cos() + n * cos_t)).powi(2);
        assert_relative_eq!(at_brewster.reflectance, r_s / 2.0, epsilon = 1e-14);
        let out = at_brewster.transmitted.unwrap();
        assert_relative_eq!(brewster.sin(), n * out.x, epsilon = 1e-15);
        // Reflected and transmitted rays are at right angles at Brewster's angle.
        assert!(at_brewster.reflected.dot(out).abs() < 1e-15);

        let critical = (1.0 / n).asin();
        let inside = |angle: f64| DVec3::new(angle.sin(), 0.0, angle.cos());
        let below = refract_at_rest(inside(critical - 1e-6), DVec3::Z, n, 1.0);
        assert!(below.transmitted.is_some() && below.reflectance < 1.0);
        let beyond = refract_at_rest(inside(critical + 1e-6), DVec3::Z, n, 1.0);
        assert_eq!((beyond.transmitted, beyond.reflectance), (None, 1.0));

        let grazing = refract_at_rest(DVec3::new(1.0, 0.0, -1e-9).normalize(), DVec3::Z, 1.0, n);
        assert!(grazing.reflectance > 0.999_999);
    }

    /// Fizeau 1851: light along moving water (n = 1.333) at v is faster than c/n by
    /// f·v with f = 1 − 1/n² ≈ 0.437 to first order (Michelson and Morley measured 0.434 ± 0.02
    /// in 1886); exactly, (c/n + v)/(1 + v/(nc)), against the flow slower, across the flow
    /// changed only at second order.
    #[test]
    fn moving_water_drags_light_by_fresnels_coefficient() {
        let n = 1.333;
        let v = 1e-6;
        let along = speed_in_moving_medium(DVec3::X, n, DVec3::new(v, 0.0, 0.0));
        let coefficient = (along - 1.0 / n) / v;
        assert_relative_eq!(coefficient, 1.0 - 1.0 / (n * n), epsilon = 1e-6);
        assert!((coefficient - 0.437).abs() < 1e-3);
        let fast = 0.5;
        let exact = (1.0 / n + fast) / (1.0 + fast / n);
        assert_relative_eq!(
            speed_in_moving_medium(DVec3::X, n, DVec3::new(fast, 0.0, 0.0)),
            exact,
            epsilon = 1e-15
        );
        assert_relative_eq!(
            speed_in_moving_medium(-DVec3::X, n, DVec3::new(fast, 0.0, 0.0)),
            (1.0 / n - fast) / (1.0 - fast / n),
            epsilon = 1e-15
        );
        let across = speed_in_moving_medium(DVec3::Y, n, DVec3::new(v, 0.0, 0.0));
        assert!((across - 1.0 / n).abs() < 1e-11);
    }

    /// Light entering moving glass: the reflected part is the moving mirror's light scaled by
    /// Fresnel's reflectance (the same direction and frequency), and the transmitted part moves
    /// at c/n in the glass's rest frame with the frequency the glass's rest frame sees.
    #[test]
    fn light_entering_moving_glass() {
        let beta = DVec3::new(0.3, -0.2, 0.4);
        let normal = DVec3::new(0.2, 0.1, 1.0).normalize();
        let incident = LightVector::new(1.0, DVec3::new(0.1, 0.3, -1.0));
        let (reflected, reflectance, entered) = enter_medium(incident, beta, normal, 1.5);
        let mirrored = reflect(incident, beta, normal);
        assert_relative_eq!(reflected.omega, mirrored.omega, epsilon = 1e-12);
        assert_near(reflected.direction, mirrored.direction, 1e-12);
        assert!(reflectance > 0.0 && reflectance < 1.0);
        let inside = entered.expect("light enters from outside");
        let rest_velocity = compose_velocities(-beta, inside.velocity);
        assert_relative_eq!(rest_velocity.length(), 1.0 / 1.5, epsilon = 1e-12);
        // The frequency in S taken back to the rest frame is the incident light's there.
        let rest_omega = incident.boosted(-beta).omega;
        let gamma = lorentz_factor(beta);
        let k_rest = 1.5 * rest_omega * rest_velocity.normalize();
        assert_relative_eq!(
            inside.omega,
            gamma * (rest_omega + beta.dot(k_rest)),
            epsilon = 1e-12
        );
        // At rest the transmitted light goes by Snell's law at c/n with the same frequency.
        let (_, _, at_rest) = enter_medium(incident, DVec3::ZERO, normal, 1.5);
        let at_rest = at_rest.unwrap();
        assert_relative_eq!(at_rest.omega, 1.0, epsilon = 1e-15);
        let snell = refract_at_rest(incident.direction, normal, 1.0, 1.5)
            .transmitted
            .unwrap();
        assert_near(at_rest.velocity, snell / 1.5, 1e-15);
    }
}
