//! From linear sRGB to Jakob–Hanika coefficients by Gauss–Newton (Jakob & Hanika 2019, §4): the
//! reflectance's colour under CIE illuminant D65 — the white of sRGB — is matched to the target
//! colour in CIELAB, as their `rgb2spec_opt` and pbrt-v4 do.
//!
//! # Convention
//!
//! - Target: XYZ = M⁻¹ · rgb with M the BT.709 matrix of the paper's Eq. 12
//!   ([`crate::XYZ_TO_LINEAR_BT709`]); rgb is *linear* (decode sRGB first).
//! - Reflectance colour: XYZ(R) = Σ R(λ) E(λ) x̄ᵢ(λ) Δλ / Σ E(λ) ȳ(λ) Δλ over the CIE 1931 table
//!   (360–830 nm), E = D65 (`data/cie_d65_1nm.csv`), so a perfect white has Y = 1.
//! - CIELAB (CIE 15:2004 §8.2.1) relative to that perfect white under D65, [`d65_white_xyz`].
//! - The optimisation works in the normalised wavelength t = (λ − 360 nm)/470 nm for conditioning
//!   and integrates on 5 nm nodes, with the 1 nm weights gathered onto them by quadratic
//!   interpolation (the integral of the piecewise-quadratic interpolant of R); everything else in
//!   the crate, round-trip checks included, integrates R at 1 nm.

use std::sync::LazyLock;

use glam::{DMat3, DVec3};

use super::sigmoid::{SigmoidPolynomial, normalised_wavelength};
use crate::Reflectance;
use crate::cie::{cie_1931, parse_csv_table};
use crate::error::{ColourError, unit_interval};
use crate::rgb::XYZ_TO_LINEAR_BT709;

/// The CSV text of CIE illuminant D65 at 1 nm, 360–830 nm (source in the file's header).
const D65_CSV: &str = include_str!("../../data/cie_d65_1nm.csv");

/// Spacing of the optimisation's quadrature nodes in nm.
const NODE_SPACING_NM: usize = 5;

/// Largest value the largest normalised coefficient may take during the fit: a step beyond it is
/// scaled back, as in `rgb2spec_opt` (one-sided, like theirs: dark saturated colours need large
/// negative coefficients, and capping those leaves errors of several ΔE).
const COEFFICIENT_LIMIT: f64 = 200.0;

/// Lower bound on every normalised coefficient, far below anything a fit reaches; it keeps x² in
/// the fit's sigmoid finite.
const COEFFICIENT_FLOOR: f64 = 1e6;

/// Convergence threshold on the CIE76 residual ΔE*ab of a Gauss–Newton solve.
const TOLERANCE: f64 = 1e-5;

/// Relative spectral power of CIE standard illuminant D65 at `wavelength_nm`, one value per row
/// of [`cie_1931`] (360–830 nm at 1 nm; 100 at 560 nm).
#[must_use]
pub fn cie_d65() -> &'static [f64] {
    &D65
}

static D65: LazyLock<Vec<f64>> = LazyLock::new(|| {
    let rows = parse_csv_table::<2>(D65_CSV, "wavelength_nm,d65");
    assert!(
        rows.len() == cie_1931().len()
            && rows
                .iter()
                .zip(cie_1931())
                .all(|(row, cmf)| row[0] == cmf.wavelength_nm),
        "the D65 table must share the CIE 1931 table's wavelengths"
    );
    rows.into_iter().map(|[_, value]| value).collect()
});

/// Precomputed integration weights of the fit.
///
/// The nodes integrate the quadratic interpolant of R through the 5 nm nodes against the exact
/// 1 nm weights: for the sigmoids the fit produces this matches the 1 nm sum closely
/// (`tests/spectral.rs` bounds the round trip at 1 nm), at a fifth of the cost.
struct FitData {
    /// D65 · (x̄, ȳ, z̄) · Δλ / Σ D65 ȳ Δλ at each 1 nm row of the CIE table.
    weights: Vec<DVec3>,
    /// (t, weight) of the 5 nm nodes: the 1 nm weights gathered by quadratic interpolation.
    nodes: Vec<(f64, DVec3)>,
    /// XYZ of the perfect white reflector under D65 (Y = 1), the CIELAB white.
    white: DVec3,
}

static FIT_DATA: LazyLock<FitData> = LazyLock::new(|| {
    let table = cie_1931();
    let d65 = cie_d65();
    let norm: f64 = table.iter().zip(d65).map(|(s, e)| e * s.ybar).sum();
    let weights: Vec<DVec3> = table
        .iter()
        .zip(d65)
        .map(|(s, e)| e * s.tristimulus() / norm)
        .collect();
    let white = weights.iter().sum();
    // Quadratic Lagrange interpolation of R on panels of two node intervals (10 nm): each 1 nm
    // weight is shared among the panel's three nodes by the basis polynomials at its position.
    let panel = 2 * NODE_SPACING_NM;
    let last = table.len() - 1;
    assert_eq!(
        last % panel,
        0,
        "the CIE table must split into whole panels"
    );
    let mut nodes: Vec<(f64, DVec3)> = (0..=last / NODE_SPACING_NM)
        .map(|n| {
            let nm = table[n * NODE_SPACING_NM].wavelength_nm;
            (normalised_wavelength(nm), DVec3::ZERO)
        })
        .collect();
    for (i, &w) in weights.iter().enumerate() {
        // The last row belongs to the last panel (u = 1), every other row to the panel it opens.
        let p = (i / panel).min(last / panel - 1);
        let u = (i - p * panel) as f64 / panel as f64;
        let basis = [
            2.0 * (u - 0.5) * (u - 1.0),
            -4.0 * u * (u - 1.0),
            2.0 * u * (u - 0.5),
        ];
        for (k, b) in basis.into_iter().enumerate() {
            nodes[2 * p + k].1 += b * w;
        }
    }
    FitData {
        weights,
        nodes,
        white,
    }
});

/// XYZ of the perfect white reflector under D65 with Y = 1: the white point of the fit's CIELAB
/// and of [`reflectance_xyz_d65`].
#[must_use]
pub fn d65_white_xyz() -> DVec3 {
    FIT_DATA.white
}

/// XYZ of a surface with `reflectance` under D65, normalised so a perfect white has Y = 1,
/// summed at 1 nm over 360–830 nm (the fit's objective, evaluated exactly).
#[must_use]
pub fn reflectance_xyz_d65(reflectance: &Reflectance) -> DVec3 {
    cie_1931()
        .iter()
        .zip(&FIT_DATA.weights)
        .map(|(s, &w)| reflectance.evaluate(s.wavelength_nm) * w)
        .sum()
}

/// XYZ of linear BT.709/sRGB `rgb`: the inverse of the paper's Eq. 12 matrix.
#[must_use]
pub fn linear_rgb_to_xyz(rgb: DVec3) -> DVec3 {
    XYZ_TO_LINEAR_BT709.inverse() * rgb
}

/// The CIELAB nonlinearity f(t) of CIE 15:2004 §8.2.1 and its derivative.
fn lab_f(t: f64) -> (f64, f64) {
    const DELTA: f64 = 6.0 / 29.0;
    if t > DELTA * DELTA * DELTA {
        let cbrt = t.cbrt();
        (cbrt, 1.0 / (3.0 * cbrt * cbrt))
    } else {
        let slope = 1.0 / (3.0 * DELTA * DELTA);
        (t * slope + 4.0 / 29.0, slope)
    }
}

/// CIELAB (L*, a*, b*) of `xyz` relative to the white `white` (CIE 15:2004 §8.2.1).
#[must_use]
pub fn xyz_to_lab(xyz: DVec3, white: DVec3) -> DVec3 {
    lab_and_jacobian(xyz, white).0
}

/// CIELAB of `xyz` and its Jacobian ∂(L*, a*, b*)/∂(X, Y, Z).
fn lab_and_jacobian(xyz: DVec3, white: DVec3) -> (DVec3, DMat3) {
    let (fx, dx) = lab_f(xyz.x / white.x);
    let (fy, dy) = lab_f(xyz.y / white.y);
    let (fz, dz) = lab_f(xyz.z / white.z);
    let (dx, dy, dz) = (dx / white.x, dy / white.y, dz / white.z);
    let lab = DVec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
    let jacobian = DMat3::from_cols(
        DVec3::new(0.0, 500.0 * dx, 0.0),
        DVec3::new(116.0 * dy, -500.0 * dy, 200.0 * dy),
        DVec3::new(0.0, 0.0, -200.0 * dz),
    );
    (lab, jacobian)
}

/// The fit's residual Lab(R_abc) − `target_lab` on the 5 nm nodes, and its Jacobian with respect
/// to the normalised coefficients (a, b, c), analytic: ∂S/∂x = ½ (1 + x²)^(−3/2).
fn residual_and_jacobian(abc: [f64; 3], target_lab: DVec3) -> (DVec3, DMat3) {
    let data = &*FIT_DATA;
    let [a, b, c] = abc;
    let mut xyz = DVec3::ZERO;
    let mut d_xyz = [DVec3::ZERO; 3];
    for &(t, w) in &data.nodes {
        let x = (a * t + b) * t + c;
        // |x| ≤ 3 · COEFFICIENT_FLOOR here (0 ≤ t ≤ 1), so 1 + x² cannot overflow.
        let h = (1.0 + x * x).sqrt();
        xyz += (0.5 + 0.5 * x / h) * w;
        let slope = 0.5 / (h * h * h) * w;
        d_xyz[0] += t * t * slope;
        d_xyz[1] += t * slope;
        d_xyz[2] += slope;
    }
    let (lab, lab_jacobian) = lab_and_jacobian(xyz, data.white);
    let jacobian = lab_jacobian * DMat3::from_cols(d_xyz[0], d_xyz[1], d_xyz[2]);
    (lab - target_lab, jacobian)
}

/// Gauss–Newton (Jakob & Hanika 2019 §4) on the CIELAB residual from `start`, at most
/// `iterations` steps, each halved until the residual decreases. Returns the normalised
/// coefficients and the final CIE76 residual ΔE*ab.
pub(crate) fn gauss_newton(
    target_lab: DVec3,
    start: [f64; 3],
    iterations: usize,
) -> ([f64; 3], f64) {
    let mut abc = start;
    let (mut residual, mut jacobian) = residual_and_jacobian(abc, target_lab);
    for _ in 0..iterations {
        let error = residual.length();
        if error < TOLERANCE || jacobian.determinant().abs() < 1e-300 {
            break;
        }
        let step = jacobian.inverse() * residual;
        if !step.is_finite() {
            break;
        }
        let mut improved = false;
        let mut factor = 1.0;
        for _ in 0..12 {
            let mut trial = [
                abc[0] - factor * step.x,
                abc[1] - factor * step.y,
                abc[2] - factor * step.z,
            ];
            trial = trial.map(|v| v.max(-COEFFICIENT_FLOOR));
            let largest = trial.iter().fold(0.0_f64, |m, &v| m.max(v));
            if largest > COEFFICIENT_LIMIT {
                trial = trial.map(|v| v * COEFFICIENT_LIMIT / largest);
            }
            let (r, j) = residual_and_jacobian(trial, target_lab);
            if r.length() < error {
                (abc, residual, jacobian) = (trial, r, j);
                improved = true;
                break;
            }
            factor *= 0.5;
        }
        if !improved {
            break;
        }
    }
    (abc, residual.length())
}

/// CIELAB of the linear sRGB target `rgb` under the fit's convention.
pub(crate) fn target_lab(rgb: DVec3) -> DVec3 {
    xyz_to_lab(linear_rgb_to_xyz(rgb), FIT_DATA.white)
}

/// One Jakob–Hanika fit: the coefficients and how well they reproduce the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbFit {
    /// The reflectance's coefficients, λ in nm.
    pub polynomial: SigmoidPolynomial,
    /// The remaining CIE76 ΔE*ab between the target and the reflectance under D65 (on the fit's
    /// 5 nm quadrature): near 0 inside the reachable gamut, larger at the most saturated corners.
    pub residual: f64,
}

/// Number of continuation steps in [`fit_rgb`].
const CONTINUATION_STEPS: usize = 16;

/// Brightness (largest linear channel) at which [`fit_rgb`]'s continuation starts from R = ½.
const CONTINUATION_START: f64 = 0.2;

/// The Jakob–Hanika reflectance whose colour under D65 matches linear sRGB `rgb` in CIELAB, by a
/// fresh optimisation (Gauss–Newton, §4): the slow, exact path behind
/// [`crate::CoefficientTable`].
///
/// Greys (r = g = b) are the exact constants [`SigmoidPolynomial::constant`]. Other colours are
/// reached by continuation along brightness, as `rgb2spec_opt` fills its table: the colour of the
/// same hue and saturation with largest channel 0.2 is solved from zero coefficients (R = ½),
/// then the brightness moves to the target's in 16 geometric steps, each solved from the previous
/// solution.
///
/// # Errors
///
/// [`ColourError::InvalidRgb`] unless every component lies in [0, 1].
pub fn fit_rgb(rgb: DVec3) -> Result<RgbFit, ColourError> {
    for c in rgb.to_array() {
        unit_interval(c, ColourError::InvalidRgb)?;
    }
    if rgb.x == rgb.y && rgb.y == rgb.z {
        return Ok(RgbFit {
            polynomial: SigmoidPolynomial::constant(rgb.x)?,
            residual: 0.0,
        });
    }
    // Not grey, so the largest channel is positive.
    let peak = rgb.max_element();
    let hue = rgb / peak;
    let mut abc = [0.0; 3];
    let mut residual = f64::INFINITY;
    for step in 0..=CONTINUATION_STEPS {
        let s = step as f64 / CONTINUATION_STEPS as f64;
        // Geometric steps: CIELAB is most sensitive, and the steps must be finest, in the dark.
        let brightness = CONTINUATION_START * (peak / CONTINUATION_START).powf(s);
        let iterations = if step == CONTINUATION_STEPS { 200 } else { 30 };
        (abc, residual) = gauss_newton(target_lab(hue * brightness), abc, iterations);
    }
    Ok(RgbFit {
        polynomial: SigmoidPolynomial::from_normalised(abc),
        residual,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d65_table_is_normalised_at_560_nm_and_white_is_d65() {
        let d65 = cie_d65();
        assert_eq!(d65.len(), 471);
        assert!((d65[200] - 100.0).abs() < 1e-9, "560 nm");
        let white = d65_white_xyz();
        assert!((white.y - 1.0).abs() < 1e-12);
        // CIE 15:2004: D65 chromaticity (0.31272, 0.32903) for the 2° observer.
        let sum = white.element_sum();
        assert!((white.x / sum - 0.31272).abs() < 2e-4, "{white}");
        assert!((white.y / sum - 0.32903).abs() < 2e-4, "{white}");
    }

    #[test]
    fn nodes_carry_all_the_weight() {
        let total: DVec3 = FIT_DATA.nodes.iter().map(|&(_, w)| w).sum();
        assert!((total - d65_white_xyz()).abs().max_element() < 1e-12);
        assert_eq!(FIT_DATA.nodes.len(), 95);
    }

    #[test]
    fn analytic_jacobian_matches_finite_differences() {
        let abc = [-12.0, 9.0, -1.5];
        let target = DVec3::new(40.0, 10.0, -5.0);
        let (_, jacobian) = residual_and_jacobian(abc, target);
        for k in 0..3 {
            let h = 1e-6;
            let (mut plus, mut minus) = (abc, abc);
            plus[k] += h;
            minus[k] -= h;
            let numeric = (residual_and_jacobian(plus, target).0
                - residual_and_jacobian(minus, target).0)
                / (2.0 * h);
            let analytic = jacobian.col(k);
            assert!(
                (numeric - analytic).abs().max_element() < 1e-5 * analytic.abs().max_element(),
                "column {k}: {numeric} vs {analytic}"
            );
        }
    }

    #[test]
    fn lab_of_white_is_100_0_0() {
        let lab = xyz_to_lab(d65_white_xyz(), d65_white_xyz());
        assert!((lab - DVec3::new(100.0, 0.0, 0.0)).abs().max_element() < 1e-12);
    }

    #[test]
    fn fit_rejects_out_of_range_rgb() {
        for bad in [-0.1, 1.1, f64::NAN, f64::INFINITY] {
            assert!(fit_rgb(DVec3::new(0.5, bad, 0.2)).is_err());
        }
    }
}
