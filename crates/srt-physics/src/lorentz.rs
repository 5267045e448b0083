//! The Lorentz boost matrix (Eq. 2), the Lorentz factor, rapidity and velocity composition.

use glam::{DMat4, DVec3, DVec4};

use crate::FrameError;

/// Checks that `beta` is a physical velocity: finite and |β| < 1.
///
/// # Errors
/// [`FrameError::NonFinite`] if a component is NaN or infinite, [`FrameError::Superluminal`] if
/// |β| ≥ 1.
pub fn validate_beta(beta: DVec3) -> Result<DVec3, FrameError> {
    if !beta.is_finite() {
        return Err(FrameError::NonFinite { what: "velocity" });
    }
    let speed = beta.length();
    if speed >= 1.0 {
        return Err(FrameError::Superluminal { speed });
    }
    Ok(beta)
}

/// The Lorentz factor γ = 1/√(1 − β·β) (below Eq. 2).
///
/// Returns `inf` for |β| = 1 and NaN beyond; use [`validate_beta`] on untrusted input.
#[must_use]
pub fn lorentz_factor(beta: DVec3) -> f64 {
    1.0 / (1.0 - beta.length_squared()).sqrt()
}

/// The rapidity η = artanh |β|: collinear boosts add rapidities.
#[must_use]
pub fn rapidity(beta: DVec3) -> f64 {
    beta.length().atanh()
}

/// The Lorentz matrix Λ_β of Eq. 2, acting on column vectors ordered (ct, x, y, z).
///
/// ```text
/// Λ_β = ⎛ γ     γβᵀ                 ⎞
///       ⎝ γβ    1₃ + γ²/(γ+1) β βᵀ  ⎠
/// ```
///
/// Λ_β maps coordinates of S′ (moving with β relative to S) to S; Λ_−β is its inverse (Eq. 1, 3).
/// Requires |β| < 1 (see [`validate_beta`]).
#[must_use]
pub fn lorentz_matrix(beta: DVec3) -> DMat4 {
    let gamma = lorentz_factor(beta);
    let k = gamma * gamma / (gamma + 1.0);
    let g = gamma * beta;
    // glam matrices are column-major: each DVec4 below is one column.
    DMat4::from_cols(
        DVec4::new(gamma, g.x, g.y, g.z),
        DVec4::new(
            g.x,
            1.0 + k * beta.x * beta.x,
            k * beta.y * beta.x,
            k * beta.z * beta.x,
        ),
        DVec4::new(
            g.y,
            k * beta.x * beta.y,
            1.0 + k * beta.y * beta.y,
            k * beta.z * beta.y,
        ),
        DVec4::new(
            g.z,
            k * beta.x * beta.z,
            k * beta.y * beta.z,
            1.0 + k * beta.z * beta.z,
        ),
    )
}

/// Relativistic composition of velocities: the velocity in S of a body that moves with `u`
/// relative to a frame S′, where S′ itself moves with `v` relative to S.
///
/// This is the spatial part of Λ_v (1, u)ᵀ divided by its time part (Eq. 3 applied to the body's
/// four-velocity), i.e. (u ⊕ v) = [u/γ_v + v + γ_v/(γ_v+1) (v·u) v] / (1 + v·u). Both inputs must
/// satisfy |β| < 1; the result then does too.
#[must_use]
pub fn compose_velocities(v: DVec3, u: DVec3) -> DVec3 {
    let four_velocity = lorentz_matrix(v) * DVec4::new(1.0, u.x, u.y, u.z);
    DVec3::new(four_velocity.y, four_velocity.z, four_velocity.w) / four_velocity.x
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn rest_frame_boost_is_identity() {
        assert_eq!(lorentz_matrix(DVec3::ZERO), DMat4::IDENTITY);
    }

    #[test]
    fn boost_along_x_matches_textbook_form() {
        let b = 0.6;
        let m = lorentz_matrix(DVec3::new(b, 0.0, 0.0));
        let gamma = 1.25;
        assert_relative_eq!(m.col(0).x, gamma, epsilon = 1e-15);
        assert_relative_eq!(m.col(0).y, gamma * b, epsilon = 1e-15);
        assert_relative_eq!(m.col(1).x, gamma * b, epsilon = 1e-15);
        assert_relative_eq!(m.col(1).y, gamma, epsilon = 1e-15);
        assert_relative_eq!(m.col(2).z, 1.0, epsilon = 1e-15);
    }

    #[test]
    fn validate_rejects_bad_velocities() {
        assert!(validate_beta(DVec3::new(1.0, 0.0, 0.0)).is_err());
        assert!(validate_beta(DVec3::new(0.8, 0.7, 0.0)).is_err());
        assert!(validate_beta(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
        assert!(validate_beta(DVec3::new(0.0, f64::INFINITY, 0.0)).is_err());
        assert!(validate_beta(DVec3::new(0.0, 0.0, -0.999_999)).is_ok());
    }

    #[test]
    fn collinear_composition_adds_rapidities() {
        let v = DVec3::new(0.5, 0.0, 0.0);
        let u = DVec3::new(0.5, 0.0, 0.0);
        assert_relative_eq!(compose_velocities(v, u).x, 0.8, epsilon = 1e-15);
    }
}
