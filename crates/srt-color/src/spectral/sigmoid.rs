//! The reflectance model of Jakob & Hanika 2019 (*A Low-Dimensional Function Space for Efficient
//! Spectral Upsampling*, §3): a sigmoid of a quadratic in wavelength,
//! R(λ) = S(c₀λ² + c₁λ + c₂) with S(x) = ½ + x / (2√(1 + x²)).
//!
//! S maps the whole real line onto (0, 1), so every coefficient triple is a physically valid
//! reflectance, smooth in λ; the constant reflectances 0 and 1 are the limits c₂ → ∓∞.

use crate::error::{ColourError, unit_interval};

/// Lower end of the wavelength domain on which the model is fitted (nm): the CIE 1931 table's.
pub const MODEL_MIN_NM: f64 = crate::cie::CIE_1931_MIN_NM;
/// Upper end of the wavelength domain on which the model is fitted (nm).
pub const MODEL_MAX_NM: f64 = crate::cie::CIE_1931_MAX_NM;

/// The sigmoid S(x) = ½ + x / (2√(1 + x²)) of Jakob & Hanika 2019 §3, in [0, 1] for every x.
///
/// Exact at the limits: S(+∞) = 1, S(−∞) = 0. Beyond |x| = [`SIGMOID_SATURATES_ABOVE`],
/// x / √(1 + x²) is ±1 in f64 (it differs by 1/(2x²)) and S is 0 or 1, so `1 + x²` is only
/// formed where it cannot overflow — with a square root, not `hypot` (which took 6.6 % of the
/// CPU reference's spectral teaser in a profile, docs/performance-log.md). NaN stays NaN (the
/// checked types below never produce it).
#[must_use]
#[inline(always)]
pub fn sigmoid(x: f64) -> f64 {
    let (numerator, denominator) = sigmoid_fraction(x);
    numerator / denominator
}

/// [`sigmoid`] as a fraction: S(x) = (√(1 + x²) + x) / (2√(1 + x²)), or the limit over 1 beyond
/// [`SIGMOID_SATURATES_ABOVE`] — for sums that divide once per wavelength for several factors.
///
/// Both forms are computed and one selected, without a branch, so that a loop over wavelengths
/// vectorises. Where x is large and negative the numerator is a difference of nearly equal
/// values: S's absolute error stays within a few 10⁻¹⁷, as in ½ + x / (2√(1 + x²)).
#[inline(always)]
pub(crate) fn sigmoid_fraction(x: f64) -> (f64, f64) {
    let root = (1.0 + x * x).sqrt();
    let inside = ((root + x) * 0.5, root);
    let limit = (if x > 0.0 { 1.0 } else { 0.0 }, 1.0);
    if x.abs() > SIGMOID_SATURATES_ABOVE {
        limit
    } else {
        inside
    }
}

/// |x| beyond which [`sigmoid`] returns exactly 0 or 1: x² stays finite below it, and
/// 1/(2x²) is far below f64's precision above it.
pub const SIGMOID_SATURATES_ABOVE: f64 = 1e150;

/// The coefficients (c₀, c₁, c₂) of one Jakob–Hanika reflectance, with λ in nanometres:
/// R(λ) = S(c₀λ² + c₁λ + c₂) (the convention of pbrt-v4's `RGBSigmoidPolynomial` and
/// colour-science's `sd_Jakob2019`).
///
/// Either all three are finite, or c₀ = c₁ = 0 and c₂ = ±∞ (the constants 1 and 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SigmoidPolynomial {
    c: [f64; 3],
}

impl SigmoidPolynomial {
    /// The polynomial with coefficients `[c₀, c₁, c₂]` for λ in nm.
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidCoefficients`] if any is NaN, or infinite other than c₂ of a
    /// constant (c₀ = c₁ = 0).
    pub fn new(c: [f64; 3]) -> Result<Self, ColourError> {
        let constant = c[0] == 0.0 && c[1] == 0.0 && !c[2].is_nan();
        if c.iter().all(|v| v.is_finite()) || constant {
            Ok(Self { c })
        } else {
            Err(ColourError::InvalidCoefficients(c[0], c[1], c[2]))
        }
    }

    /// The constant reflectance ρ: c₀ = c₁ = 0, c₂ = S⁻¹(ρ) = (ρ − ½) / √(ρ(1 − ρ)), which is
    /// ∓∞ at ρ = 0 and 1 (as pbrt-v4 does for grey RGB).
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidReflectance`] unless ρ ∈ [0, 1].
    pub fn constant(reflectance: f64) -> Result<Self, ColourError> {
        let rho = unit_interval(reflectance, ColourError::InvalidReflectance)?;
        Ok(Self {
            c: [0.0, 0.0, inverse_sigmoid(rho)],
        })
    }

    /// The coefficients `[c₀, c₁, c₂]` for λ in nm.
    #[must_use]
    pub fn coefficients(&self) -> [f64; 3] {
        self.c
    }

    /// The argument x(λ) = c₀λ² + c₁λ + c₂ of the sigmoid at `wavelength_nm` (Horner form).
    #[must_use]
    #[inline(always)]
    pub fn argument(&self, wavelength_nm: f64) -> f64 {
        let [c0, c1, c2] = self.c;
        let horner = (c0 * wavelength_nm + c1) * wavelength_nm + c2;
        if c0 == 0.0 && c1 == 0.0 { c2 } else { horner }
    }

    /// [`SigmoidPolynomial::evaluate`] as a fraction ([`sigmoid_fraction`]).
    #[inline(always)]
    pub(crate) fn evaluate_fraction(&self, wavelength_nm: f64) -> (f64, f64) {
        sigmoid_fraction(self.argument(wavelength_nm))
    }

    /// The reflectance R(λ) = S(x(λ)) ∈ [0, 1] at `wavelength_nm`, the sigmoid extended to every
    /// wavelength (no out-of-domain policy: see [`crate::Reflectance`] for that).
    #[must_use]
    #[inline(always)]
    pub fn evaluate(&self, wavelength_nm: f64) -> f64 {
        sigmoid(self.argument(wavelength_nm))
    }

    /// From coefficients `[a, b, c]` of the normalised wavelength
    /// t = (λ − 360 nm) / (830 nm − 360 nm), the variable the fit works in for conditioning:
    /// a t² + b t + c expanded in λ.
    pub(crate) fn from_normalised(abc: [f64; 3]) -> Self {
        let [a, b, c] = abc;
        let scale = 1.0 / (MODEL_MAX_NM - MODEL_MIN_NM);
        let shift = MODEL_MIN_NM;
        Self {
            c: [
                a * scale * scale,
                b * scale - 2.0 * a * shift * scale * scale,
                c - b * shift * scale + a * (shift * scale) * (shift * scale),
            ],
        }
    }
}

/// S⁻¹(ρ) = (ρ − ½) / √(ρ(1 − ρ)) for ρ ∈ [0, 1], ±∞ at the ends.
pub(crate) fn inverse_sigmoid(rho: f64) -> f64 {
    if rho <= 0.0 {
        f64::NEG_INFINITY
    } else if rho >= 1.0 {
        f64::INFINITY
    } else {
        (rho - 0.5) / (rho * (1.0 - rho)).sqrt()
    }
}

/// The normalised wavelength t = (λ − 360 nm) / 470 nm of [`SigmoidPolynomial::from_normalised`].
pub(crate) fn normalised_wavelength(wavelength_nm: f64) -> f64 {
    (wavelength_nm - MODEL_MIN_NM) / (MODEL_MAX_NM - MODEL_MIN_NM)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sigmoid_limits_and_centre() {
        assert_eq!(sigmoid(0.0), 0.5);
        assert_eq!(sigmoid(f64::INFINITY), 1.0);
        assert_eq!(sigmoid(f64::NEG_INFINITY), 0.0);
        assert_eq!(sigmoid(1e300), 1.0);
        assert_eq!(sigmoid(-1e300), 0.0);
        assert!((sigmoid(1.0) - (0.5 + 0.5 / 2f64.sqrt())).abs() < 1e-15);
        assert!(sigmoid(f64::NAN).is_nan());
    }

    #[test]
    fn the_square_root_form_agrees_with_hypot_at_every_magnitude() {
        // |x| from 10⁻¹² to 10³⁰⁰ in steps of 10^0.01, both signs, across the saturation bound.
        for i in 0..=31_200 {
            let magnitude = 10f64.powf(-12.0 + f64::from(i) * 0.01);
            for x in [magnitude, -magnitude] {
                let by_hypot = 0.5 + 0.5 * x / x.hypot(1.0);
                assert!(
                    (sigmoid(x) - by_hypot).abs() <= 2.0 * f64::EPSILON,
                    "x {x}: {} vs {by_hypot}",
                    sigmoid(x)
                );
            }
        }
    }

    #[test]
    fn constant_inverts_the_sigmoid() {
        for rho in [0.0, 1e-9, 0.18, 0.5, 0.9, 1.0] {
            let p = SigmoidPolynomial::constant(rho).unwrap();
            assert!((p.evaluate(550.0) - rho).abs() < 1e-12, "{rho}");
            assert_eq!(p.evaluate(550.0), p.evaluate(3000.0));
        }
        assert!(SigmoidPolynomial::constant(-0.1).is_err());
        assert!(SigmoidPolynomial::constant(f64::NAN).is_err());
    }

    #[test]
    fn normalised_coefficients_expand_to_the_same_polynomial() {
        let abc = [-30.0, 25.0, -2.0];
        let p = SigmoidPolynomial::from_normalised(abc);
        for nm in [360.0, 455.5, 700.0, 830.0, 1500.0] {
            let t = normalised_wavelength(nm);
            let want = (abc[0] * t + abc[1]) * t + abc[2];
            assert!(
                (p.argument(nm) - want).abs() < 1e-9 * want.abs().max(1.0),
                "{nm}"
            );
        }
    }

    #[test]
    fn new_rejects_nan_and_stray_infinities() {
        assert!(SigmoidPolynomial::new([1e-4, -0.1, 5.0]).is_ok());
        assert!(SigmoidPolynomial::new([0.0, 0.0, f64::INFINITY]).is_ok());
        assert!(SigmoidPolynomial::new([f64::NAN, 0.0, 0.0]).is_err());
        assert!(SigmoidPolynomial::new([1.0, 0.0, f64::INFINITY]).is_err());
        assert!(SigmoidPolynomial::new([0.0, 0.0, f64::NAN]).is_err());
    }
}
