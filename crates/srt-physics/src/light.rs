//! Light four-vectors: Doppler shift and aberration (Eq. 3–4), reflection Doppler (Eq. 17).

use glam::{DVec3, DVec4};

use crate::lorentz::{lorentz_factor, lorentz_matrix};

/// A light four-vector k = ω(1, n): circular frequency ω and unit propagation direction n
/// (from emitter towards receiver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightVector {
    /// Circular frequency ω (any unit; only ratios matter here).
    pub omega: f64,
    /// Unit propagation direction n.
    pub direction: DVec3,
}

impl LightVector {
    /// Light of circular frequency `omega` propagating along `direction` (normalised here).
    #[must_use]
    pub fn new(omega: f64, direction: DVec3) -> Self {
        Self {
            omega,
            direction: direction.normalize(),
        }
    }

    /// The four-vector column ω(1, n) = (ω, ωnₓ, ωn_y, ωn_z).
    #[must_use]
    pub fn to_four_vector(self) -> DVec4 {
        self.omega * DVec4::new(1.0, self.direction.x, self.direction.y, self.direction.z)
    }

    /// The light vector of a null four-vector column (ω, ωn).
    #[must_use]
    pub fn from_four_vector(k: DVec4) -> Self {
        Self {
            omega: k.x,
            direction: DVec3::new(k.y, k.z, k.w) / k.x,
        }
    }

    /// The same light described in S, when `self` describes it in S′ moving with `beta` relative
    /// to S: k = Λ_β k′ (Eq. 3). `boosted(-beta)` is the inverse, k′ = Λ_−β k.
    #[must_use]
    pub fn boosted(self, beta: DVec3) -> Self {
        Self::from_four_vector(lorentz_matrix(beta) * self.to_four_vector())
    }
}

/// Doppler factor D = ω_S / ω_S′ = 1 / (γ (1 − β·n)) of light that reaches an observer at rest
/// in S travelling along the unit vector `propagation` (given in S) from a source moving with
/// `beta`.
///
/// This is the time-like part of Eq. 4, ω = ω′γ(1 + β·n′), rewritten with the direction n in S
/// instead of n′ in S′ (the two agree through the aberration formula, see [`aberrate`]). D > 1
/// is a blue shift: a source approaching head-on at speed b gives √((1+b)/(1−b)).
#[must_use]
pub fn doppler_factor(beta: DVec3, propagation: DVec3) -> f64 {
    1.0 / (lorentz_factor(beta) * (1.0 - beta.dot(propagation)))
}

/// Aberration: the propagation direction in S of light that propagates along the unit vector
/// `direction_rest` in S′, where S′ moves with `beta` relative to S.
///
/// The space-like part of Eq. 4 divided by its time-like part:
/// n = [γβ + n′ + γ²/(γ+1)(β·n′)β] / (γ(1 + β·n′)). `aberrate(-beta, n)` inverts it.
#[must_use]
pub fn aberrate(beta: DVec3, direction_rest: DVec3) -> DVec3 {
    Aberration::new(beta).apply(direction_rest)
}

/// [`aberrate`] for one velocity β, its factors γ and γ²/(γ+1) computed once: a renderer
/// aberrates every ray with it (the same results, bit for bit, as [`aberrate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aberration {
    beta: DVec3,
    gamma: f64,
    /// γ²/(γ+1), the factor of (β·n′)β in Eq. 4.
    along: f64,
}

impl Aberration {
    /// The aberration of light from a frame S′ moving with `beta` relative to S.
    #[must_use]
    pub fn new(beta: DVec3) -> Self {
        let gamma = lorentz_factor(beta);
        Self {
            beta,
            gamma,
            along: gamma * gamma / (gamma + 1.0),
        }
    }

    /// The propagation direction in S of light propagating along `direction_rest` in S′
    /// ([`aberrate`], Eq. 4).
    #[must_use]
    #[inline]
    pub fn apply(&self, direction_rest: DVec3) -> DVec3 {
        let (beta, gamma) = (self.beta, self.gamma);
        let b_dot_n = beta.dot(direction_rest);
        let spatial = gamma * beta + direction_rest + self.along * b_dot_n * beta;
        spatial / (gamma * (1.0 + b_dot_n))
    }

    /// [`Aberration::apply`] to each direction of `lanes` (x, y and z of many directions side by
    /// side), the same bits as one by one: each lane's operations are [`Aberration::apply`]'s in
    /// its order, so the compiler may compute two lanes per vector instruction.
    pub fn apply_lanes<const N: usize>(&self, [x, y, z]: &mut [[f64; N]; 3]) {
        let (beta, gamma, along) = (self.beta, self.gamma, self.along);
        let gamma_beta = gamma * beta;
        for i in 0..N {
            let b_dot_n = (beta.x * x[i]) + (beta.y * y[i]) + (beta.z * z[i]);
            let scale = along * b_dot_n;
            let denominator = gamma * (1.0 + b_dot_n);
            x[i] = (gamma_beta.x + x[i] + scale * beta.x) / denominator;
            y[i] = (gamma_beta.y + y[i] + scale * beta.y) / denominator;
            z[i] = (gamma_beta.z + z[i] + scale * beta.z) / denominator;
        }
    }
}

/// Doppler factor D = ω_R / ω_S = γ (1 − β·n) with which a receiver moving with `beta` through
/// S sees light that propagates along the unit vector `propagation` (given in S) from a source
/// at rest in S: the time-like part of Eq. 3, ω′ = γ ω (1 − β·n). It is the first factor of
/// Eq. 17 ([`reflection_doppler`] = this × [`doppler_factor`]`(beta, outgoing)`).
#[must_use]
pub fn receiver_doppler(beta: DVec3, propagation: DVec3) -> f64 {
    lorentz_factor(beta) * (1.0 - beta.dot(propagation))
}

/// Where a source at infinity is seen from S, and with which Doppler factor: a star of a sky at
/// rest in a frame S′ that moves with `beta` relative to S, in the unit direction
/// `direction_rest` (observer → star, in S′).
///
/// Its light propagates along −`direction_rest` in S′; Eq. 4 ([`aberrate`]) gives the
/// propagation direction n in S, the star is seen in the direction −n, and
/// D = [`doppler_factor`]`(beta, n)`. For an observer moving with speed b through the sky's frame
/// (β = −b·û) and a star at angle θ from û, the star is seen at θ′ with
/// cos θ′ = (cos θ + b)/(1 + b cos θ) and D = γ(1 + b cos θ).
#[must_use]
pub fn distant_source_image(beta: DVec3, direction_rest: DVec3) -> (DVec3, f64) {
    let propagation = aberrate(beta, -direction_rest).normalize();
    (-propagation, doppler_factor(beta, propagation))
}

/// Combined Doppler factor of light from a source at rest in S that is reflected by a surface
/// moving with `beta` and then received by an observer at rest in S (Eq. 17).
///
/// `incident` is the unit propagation direction light → surface, `outgoing` the unit propagation
/// direction surface → observer, both in S. In this crate's convention (D = ω_received /
/// ω_emitted): D = (1 − β·n_in) / (1 − β·n_out). The paper writes the reciprocal because it
/// divides the light temperature by D; here the apparent temperature is D·T. Radar check: light
/// from the observer hitting an object approaching head-on at speed b returns with
/// D = (1 + b)/(1 − b).
#[must_use]
pub fn reflection_doppler(beta: DVec3, incident: DVec3, outgoing: DVec3) -> f64 {
    (1.0 - beta.dot(incident)) / (1.0 - beta.dot(outgoing))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn head_on_approach_is_blue_shifted() {
        let b = 0.2;
        // Source moves along -x towards an observer at the origin; light travels along -x too.
        let d = doppler_factor(DVec3::new(-b, 0.0, 0.0), DVec3::new(-1.0, 0.0, 0.0));
        assert_relative_eq!(d, ((1.0 + b) / (1.0 - b)).sqrt(), epsilon = 1e-15);
    }

    #[test]
    fn eq_17_is_the_product_of_the_receiver_and_source_factors() {
        let beta = DVec3::new(0.3, -0.5, 0.2);
        let incident = DVec3::new(1.0, 2.0, -0.5).normalize();
        let outgoing = DVec3::new(-0.2, 0.4, 1.0).normalize();
        assert_relative_eq!(
            receiver_doppler(beta, incident) * doppler_factor(beta, outgoing),
            reflection_doppler(beta, incident, outgoing),
            epsilon = 1e-14
        );
    }

    #[test]
    fn stars_crowd_ahead_of_a_moving_observer() {
        // Observer moving along +x at b through the sky: a star at 90° is seen ahead, at
        // cos θ′ = b, with D = γ.
        let b = 0.6;
        let (seen, d) = distant_source_image(DVec3::new(-b, 0.0, 0.0), DVec3::Y);
        assert_relative_eq!(seen.x, b, epsilon = 1e-15);
        assert_relative_eq!(seen.length(), 1.0, epsilon = 1e-15);
        assert_relative_eq!(d, 1.25, epsilon = 1e-15);
    }

    #[test]
    fn transverse_doppler_is_time_dilation() {
        // Light received perpendicular to the motion *in S* is red-shifted by 1/γ.
        let beta = DVec3::new(0.6, 0.0, 0.0);
        assert_relative_eq!(doppler_factor(beta, DVec3::Y), 0.8, epsilon = 1e-15);
    }
}
