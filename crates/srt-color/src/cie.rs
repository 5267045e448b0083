//! The CIE 1931 2° standard observer and the tristimulus values of a black body (Eq. 11).
//!
//! The colour-matching functions x̄, ȳ, z̄ are tabulated at 1 nm from 360 nm to 830 nm in
//! `data/cie1931_2deg_1nm.csv` (CIE 018:2019 / CIE 15:2004, as distributed by CVRL and
//! colour-science); the table is compiled into the crate and parsed once, on first use.

use std::sync::LazyLock;

use glam::{DVec2, DVec3};

use crate::planck::{SECOND_RADIATION_CONSTANT, WIEN_X, ln_planck_radiance};

/// The CSV text of the CIE 1931 2° colour-matching functions, 360–830 nm at 1 nm.
const CIE_1931_CSV: &str = include_str!("../data/cie1931_2deg_1nm.csv");

/// Shortest tabulated wavelength in nm.
pub const CIE_1931_MIN_NM: f64 = 360.0;
/// Longest tabulated wavelength in nm.
pub const CIE_1931_MAX_NM: f64 = 830.0;
/// Spacing of the table and of the integration in Eq. 11, in metres (1 nm).
pub const CIE_1931_STEP_M: f64 = 1e-9;

/// One row of the CIE 1931 2° colour-matching-function table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CmfSample {
    /// Wavelength λ in nanometres.
    pub wavelength_nm: f64,
    /// x̄(λ).
    pub xbar: f64,
    /// ȳ(λ), the photopic luminous efficiency function V(λ).
    pub ybar: f64,
    /// z̄(λ).
    pub zbar: f64,
}

impl CmfSample {
    /// (x̄, ȳ, z̄) as a vector: the XYZ tristimulus values of unit monochromatic light at this
    /// wavelength (the σⱼ(λ) of Eq. 11).
    #[must_use]
    pub fn tristimulus(&self) -> DVec3 {
        DVec3::new(self.xbar, self.ybar, self.zbar)
    }

    /// The wavelength in metres.
    #[must_use]
    pub fn wavelength_m(&self) -> f64 {
        self.wavelength_nm * 1e-9
    }
}

static CIE_1931: LazyLock<Vec<CmfSample>> = LazyLock::new(|| parse_cmf_csv(CIE_1931_CSV));

/// A row of the CIE table with what Planck's law needs of its wavelength at every temperature,
/// computed once rather than in every spectral sum ([`PlanckWeights::weight`]).
pub(crate) struct SpectralRow {
    /// The table's row.
    pub(crate) sample: CmfSample,
    /// 1/λ in nm⁻¹.
    inverse_nm: f64,
    /// (λₗ/λ)⁵, λₗ the table's longest wavelength.
    longest_ratio_pow5: f64,
}

static SPECTRAL_ROWS: LazyLock<Vec<SpectralRow>> = LazyLock::new(|| {
    let table = cie_1931();
    let longest_nm = table[table.len() - 1].wavelength_nm;
    table
        .iter()
        .map(|&sample| {
            let inverse_nm = 1.0 / sample.wavelength_nm;
            SpectralRow {
                sample,
                inverse_nm,
                longest_ratio_pow5: (longest_nm * inverse_nm).powi(5),
            }
        })
        .collect()
});

/// The CIE table's rows with their wavelength terms of Planck's law: what a spectral sum
/// iterates over.
pub(crate) fn spectral_rows() -> &'static [SpectralRow] {
    &SPECTRAL_ROWS
}

/// Parses the embedded table: `#` comment lines, one header line, then `λ,x̄,ȳ,z̄` rows.
///
/// The input is compiled in and checked by tests, so a malformed line is a build defect and
/// panics with the offending line.
fn parse_cmf_csv(text: &str) -> Vec<CmfSample> {
    parse_csv_table::<4>(text, "wavelength_nm,xbar,ybar,zbar")
        .into_iter()
        .map(|[wavelength_nm, xbar, ybar, zbar]| CmfSample {
            wavelength_nm,
            xbar,
            ybar,
            zbar,
        })
        .collect()
}

/// Parses an embedded numeric CSV table: `#` comment lines, the header line `header`, then rows
/// of `N` numbers.
///
/// Only for tables compiled into the crate and covered by tests: a malformed line is a build
/// defect and panics with the offending line.
pub(crate) fn parse_csv_table<const N: usize>(text: &str, header: &str) -> Vec<[f64; N]> {
    let mut rows = text
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && !line.starts_with('#'));
    let found = rows.next();
    assert_eq!(found, Some(header), "unexpected embedded table header");
    rows.map(|line| {
        let fields: Vec<f64> = line
            .split(',')
            .map(|field| {
                field.trim().parse().unwrap_or_else(|e| {
                    panic!("bad number {field:?} in embedded table line {line:?}: {e}")
                })
            })
            .collect();
        fields
            .try_into()
            .unwrap_or_else(|_| panic!("embedded table line {line:?} does not have {N} fields"))
    })
    .collect()
}

/// The CIE 1931 2° colour-matching functions, 471 rows from 360 nm to 830 nm at 1 nm.
///
/// # Panics
///
/// Never in practice: the table is compiled into the crate and its parse is covered by tests.
#[must_use]
pub fn cie_1931() -> &'static [CmfSample] {
    &CIE_1931
}

/// CIE 1931 XYZ tristimulus values of a black body of temperature `temperature_k`, Eq. 11.
///
/// Σⱼ(T) = Σ over λ of L(λ, T) · σⱼ(λ) · Δλ over the table's wavelengths (360–830 nm,
/// Δλ = 1 nm), with L from Eq. 10 in W·sr⁻¹·m⁻³. The scale is therefore absolute: XYZ are
/// radiance-weighted integrals in W·sr⁻¹·m⁻² (multiply Y by 683 lm/W for luminance in cd/m²).
/// A non-positive or non-finite temperature gives zero; so does a temperature so low that the
/// visible radiance underflows (below about 20 K).
#[must_use]
pub fn blackbody_xyz(temperature_k: f64) -> DVec3 {
    let (relative, ln_scale) = blackbody_xyz_relative(temperature_k);
    relative * ln_scale.exp()
}

/// A CIE XYZ tristimulus value stored as `relative · exp(ln_scale)`, so that the light of any
/// positive finite temperature, however faint or bright, is representable without overflow or
/// underflow (the tone maps only need ratios, Fig. 6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaledXyz {
    /// XYZ up to the common factor `exp(ln_scale)`.
    pub relative: DVec3,
    /// Natural logarithm of the factor that turns `relative` into absolute XYZ (W·sr⁻¹·m⁻²).
    pub ln_scale: f64,
}

impl ScaledXyz {
    /// Black: zero XYZ.
    pub const BLACK: Self = Self {
        relative: DVec3::ZERO,
        ln_scale: 0.0,
    };

    /// The absolute XYZ, `relative · exp(ln_scale)` (0 or ∞ where that leaves `f64`'s range).
    #[must_use]
    pub fn xyz(&self) -> DVec3 {
        self.relative * self.ln_scale.exp()
    }

    /// Natural logarithm of the absolute luminance Y, `-inf` for black.
    #[must_use]
    pub fn ln_y(&self) -> f64 {
        self.relative.y.ln() + self.ln_scale
    }
}

/// The Planck radiance of Eq. 10 at the wavelengths of [`cie_1931`] relative to its largest
/// value there, `L(λᵢ, T) = wᵢ · exp(ln_max)`: the weights every spectral sum at one temperature
/// shares (Eq. 11).
///
/// Every weight lies in [0, 1] and the largest is 1 (to rounding), so sums against the table
/// neither overflow nor underflow. L is unimodal in λ with its peak at c₂/(x_max T) (Wien's
/// displacement law, [`WIEN_X`]), so `ln_max` is found among the grid wavelengths around the
/// peak rather than over the whole table. Each weight is then taken relative to the table's
/// longest wavelength λₗ, where x = c₂/(λT) is smallest (x ≥ xₗ):
///
/// L(λ)/L(λₗ) = (λₗ/λ)⁵ · e^(−(x − xₗ)) · g(xₗ)/g(x), with g(x) = 1 − e^(−x),
///
/// one exponential per wavelength (e^(−x) = e^(−xₗ) · e^(−(x − xₗ))) and no logarithm, in a
/// range where neither factor overflows at any temperature; the GPU mirror (spectral.wgsl's
/// `planck_weight`) computes the same form in f32.
pub(crate) struct PlanckWeights {
    /// ln L_max, the largest ln L(λᵢ, T) on the grid.
    ln_max: f64,
    /// c₂/T in nm: x = c₂/(λT) = `x_per_inverse_nm` / λ with λ in nm.
    x_per_inverse_nm: f64,
    /// 1/λₗ in nm⁻¹, λₗ the table's longest wavelength.
    inverse_longest_nm: f64,
    /// e^(−xₗ).
    exp_minus_x_longest: f64,
    /// L(λₗ)/L_max · g(xₗ).
    longest_factor: f64,
}

/// g(x) = 1 − e^(−x) for x ≥ 0 given e^(−x): by subtraction where that loses at most a few
/// bits (x ≥ ¼), else as −expm1(−x).
fn one_minus_exp_minus(x: f64, exp_minus_x: f64) -> f64 {
    if x >= 0.25 {
        1.0 - exp_minus_x
    } else {
        -(-x).exp_m1()
    }
}

impl PlanckWeights {
    /// The weights at `temperature_k`; `None` unless it is positive and finite and the visible
    /// radiance is representable in logarithms.
    pub(crate) fn new(temperature_k: f64) -> Option<Self> {
        if !(temperature_k.is_finite() && temperature_k > 0.0) {
            return None;
        }
        let table = cie_1931();
        let last = table.len() - 1;
        let peak_nm = SECOND_RADIATION_CONSTANT / (WIEN_X * temperature_k) * 1e9;
        // The grid rows around the peak, held to the table (both neighbours of an unrounded
        // peak, and one more against rounding in the peak's position).
        let below = ((peak_nm - CIE_1931_MIN_NM).floor().max(0.0) as usize).min(last);
        let ln_max = [below.saturating_sub(1), below, (below + 1).min(last)]
            .into_iter()
            .map(|i| ln_planck_radiance(table[i].wavelength_m(), temperature_k))
            .fold(f64::NEG_INFINITY, f64::max);
        if !ln_max.is_finite() {
            return None;
        }
        let longest = table[last];
        let x_per_inverse_nm = SECOND_RADIATION_CONSTANT * 1e9 / temperature_k;
        let x_longest = x_per_inverse_nm / longest.wavelength_nm;
        let exp_minus_x_longest = (-x_longest).exp();
        let longest_weight =
            (ln_planck_radiance(longest.wavelength_m(), temperature_k) - ln_max).exp();
        Some(Self {
            ln_max,
            x_per_inverse_nm,
            inverse_longest_nm: 1.0 / longest.wavelength_nm,
            exp_minus_x_longest,
            longest_factor: longest_weight * one_minus_exp_minus(x_longest, exp_minus_x_longest),
        })
    }

    /// ln L_max: `L(λᵢ, T) = weight(λᵢ) · exp(ln_max)`.
    pub(crate) fn ln_max(&self) -> f64 {
        self.ln_max
    }

    /// L(λ, T) / L_max at the table's row `row` (Eq. 10, in the form of the type's
    /// documentation).
    pub(crate) fn weight(&self, row: &SpectralRow) -> f64 {
        let inverse = row.inverse_nm;
        let x = self.x_per_inverse_nm * inverse;
        let beyond = (-(self.x_per_inverse_nm * (inverse - self.inverse_longest_nm))).exp();
        self.longest_factor * row.longest_ratio_pow5 * beyond
            / one_minus_exp_minus(x, self.exp_minus_x_longest * beyond)
    }
}

/// [`blackbody_xyz`] as a [`ScaledXyz`], with the largest spectral term of `relative` equal to 1
/// (Eq. 11 without overflow or underflow). Invalid temperatures give [`ScaledXyz::BLACK`] with
/// `ln_scale = -inf`.
#[must_use]
pub fn blackbody_xyz_scaled(temperature_k: f64) -> ScaledXyz {
    let (relative, ln_scale) = blackbody_xyz_relative(temperature_k);
    ScaledXyz { relative, ln_scale }
}

/// [`blackbody_xyz`] split as `relative · exp(ln_scale)`, with the largest spectral term of
/// `relative` equal to 1, so that ratios such as X/Y are available at any positive finite
/// temperature (Eq. 11 without overflow or underflow). Returns `(ZERO, -inf)` for invalid input.
pub(crate) fn blackbody_xyz_relative(temperature_k: f64) -> (DVec3, f64) {
    let Some(weights) = PlanckWeights::new(temperature_k) else {
        return (DVec3::ZERO, f64::NEG_INFINITY);
    };
    let relative = spectral_rows()
        .iter()
        .map(|row| weights.weight(row) * row.sample.tristimulus())
        .sum::<DVec3>();
    (relative, weights.ln_max() + CIE_1931_STEP_M.ln())
}

/// Chromaticity coordinates (x, y) = (X, Y) / (X + Y + Z) of a tristimulus value.
///
/// Returns (NaN, NaN) when X + Y + Z is zero (black has no chromaticity).
#[must_use]
pub fn chromaticity(xyz: DVec3) -> DVec2 {
    let sum = xyz.x + xyz.y + xyz.z;
    DVec2::new(xyz.x / sum, xyz.y / sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_has_471_rows_from_360_to_830_nm_at_1_nm() {
        let table = cie_1931();
        assert_eq!(table.len(), 471);
        for (i, row) in table.iter().enumerate() {
            assert_eq!(row.wavelength_nm, CIE_1931_MIN_NM + i as f64);
        }
        assert_eq!(table.last().map(|r| r.wavelength_nm), Some(CIE_1931_MAX_NM));
    }

    #[test]
    fn table_values_match_published_anchor_points() {
        // CIE 15:2004 Table T.4 (1 nm 2° observer) at 555 nm, where ȳ peaks at 1.
        let row = cie_1931()
            .iter()
            .find(|r| r.wavelength_nm == 555.0)
            .copied();
        let row = row.expect("555 nm is tabulated");
        assert!((row.ybar - 1.0).abs() < 1e-6);
        assert!((row.xbar - 0.512_05).abs() < 1e-4);
        assert!((row.zbar - 0.005_749_999).abs() < 1e-5);
        // ȳ is the largest at 555 nm.
        let peak = cie_1931()
            .iter()
            .max_by(|a, b| a.ybar.total_cmp(&b.ybar))
            .copied();
        assert_eq!(peak.map(|r| r.wavelength_nm), Some(555.0));
    }

    #[test]
    fn parser_rejects_malformed_tables() {
        assert!(
            std::panic::catch_unwind(|| parse_cmf_csv("# c\nwrong,header\n1,2,3,4\n")).is_err()
        );
        assert!(
            std::panic::catch_unwind(|| parse_cmf_csv("wavelength_nm,xbar,ybar,zbar\n1,2,3\n"))
                .is_err()
        );
        assert!(
            std::panic::catch_unwind(|| parse_cmf_csv("wavelength_nm,xbar,ybar,zbar\n1,2,x,4\n"))
                .is_err()
        );
        let ok = parse_cmf_csv("# c\nwavelength_nm,xbar,ybar,zbar\n360,1,2,3\n");
        assert_eq!(
            ok,
            vec![CmfSample {
                wavelength_nm: 360.0,
                xbar: 1.0,
                ybar: 2.0,
                zbar: 3.0
            }]
        );
    }

    #[test]
    fn relative_form_matches_the_absolute_one() {
        for t in [800.0, 1500.0, 6500.0, 1e5] {
            let (rel, ln_scale) = blackbody_xyz_relative(t);
            let abs = blackbody_xyz(t);
            let direct = cie_1931()
                .iter()
                .map(|s| crate::planck_radiance(s.wavelength_m(), t) * s.tristimulus() * 1e-9)
                .sum::<DVec3>();
            assert!((abs - direct).abs().max_element() <= 1e-12 * direct.max_element());
            assert!(
                (rel * ln_scale.exp() - direct).abs().max_element() <= 1e-12 * direct.max_element()
            );
        }
    }

    /// The weights by definition: exp(ln L(λᵢ) − max over every row of ln L).
    fn weights_by_definition(temperature_k: f64) -> (Vec<f64>, f64) {
        let ln: Vec<f64> = cie_1931()
            .iter()
            .map(|s| ln_planck_radiance(s.wavelength_m(), temperature_k))
            .collect();
        let ln_max = ln.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (ln.iter().map(|l| (l - ln_max).exp()).collect(), ln_max)
    }

    #[test]
    fn planck_weights_agree_with_their_definition() {
        // 1 K to 10¹⁰ K in steps of 10^0.05: both sides of the table's ends (the peak leaves
        // 360–830 nm below 3 490 K and above 8 050 K) and of x = ¼ (g's two forms).
        for i in 0..=200 {
            let t = 10f64.powf(f64::from(i) * 0.05);
            let weights = PlanckWeights::new(t).expect("positive finite temperature");
            let (want, ln_max) = weights_by_definition(t);
            assert!(
                (weights.ln_max() - ln_max).abs() <= 1e-12 * ln_max.abs().max(1.0),
                "T {t}"
            );
            for (row, want) in spectral_rows().iter().zip(want) {
                let got = weights.weight(row);
                assert!(
                    (got - want).abs() <= 1e-12,
                    "T {t}, λ {}: {got} vs {want}",
                    row.sample.wavelength_nm
                );
            }
        }
        assert!(PlanckWeights::new(0.0).is_none());
        assert!(PlanckWeights::new(f64::INFINITY).is_none());
    }

    proptest::proptest! {
        #[test]
        fn planck_weights_peak_at_one(log_t in 0.0_f64..12.0) {
            let weights = PlanckWeights::new(10f64.powf(log_t)).expect("positive finite");
            let largest = spectral_rows().iter().map(|row| weights.weight(row)).fold(0.0, f64::max);
            proptest::prop_assert!((largest - 1.0).abs() <= 1e-12, "largest weight {}", largest);
        }
    }

    #[test]
    fn relative_form_survives_where_the_absolute_one_underflows() {
        assert_eq!(blackbody_xyz(5.0), DVec3::ZERO);
        let (rel, _) = blackbody_xyz_relative(5.0);
        assert!(rel.y > 0.0 && rel.is_finite());
        assert_eq!(blackbody_xyz_relative(0.0).0, DVec3::ZERO);
        assert_eq!(blackbody_xyz_relative(f64::NAN).0, DVec3::ZERO);
    }
}
