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

/// The number of rows of the CIE 1931 table, 360–830 nm at 1 nm.
pub const CIE_1931_ROWS: usize = 471;

/// [`CIE_1931_ROWS`] rounded up to whole groups of eight SIMD lanes: the length of every column of
/// [`SpectralColumns`].
pub(crate) const PADDED_ROWS: usize = CIE_1931_ROWS.div_ceil(8) * 8;

/// One value per row of the CIE table, padded ([`SpectralColumns`]).
pub(crate) type Column = [f64; PADDED_ROWS];

/// The CIE table as columns, with what Planck's law needs of each wavelength at every temperature
/// computed once rather than in every spectral sum ([`PlanckWeights::fractions`]).
///
/// Columns rather than rows, padded to [`PADDED_ROWS`], so that a sum computes each of its terms
/// in a loop the compiler turns into SIMD instructions. The padding rows repeat the longest
/// wavelength with zero colour-matching functions: they add exactly nothing to any sum.
pub(crate) struct SpectralColumns {
    /// λ in nm.
    pub(crate) wavelength_nm: Column,
    /// 1/λ in nm⁻¹.
    inverse_nm: Column,
    /// (λₗ/λ)⁵, λₗ the table's longest wavelength.
    longest_ratio_pow5: Column,
    /// x̄, ȳ and z̄ (the σⱼ of Eq. 11).
    tristimulus: [Column; 3],
}

static SPECTRAL_COLUMNS: LazyLock<Box<SpectralColumns>> = LazyLock::new(|| {
    let table = cie_1931();
    let longest = table[table.len() - 1];
    let row = |i: usize| {
        table.get(i).copied().unwrap_or(CmfSample {
            xbar: 0.0,
            ybar: 0.0,
            zbar: 0.0,
            ..longest
        })
    };
    let column = |value: &dyn Fn(CmfSample) -> f64| std::array::from_fn(|i| value(row(i)));
    Box::new(SpectralColumns {
        wavelength_nm: column(&|s| s.wavelength_nm),
        inverse_nm: column(&|s| 1.0 / s.wavelength_nm),
        longest_ratio_pow5: column(&|s| (longest.wavelength_nm / s.wavelength_nm).powi(5)),
        tristimulus: [
            column(&|s| s.xbar),
            column(&|s| s.ybar),
            column(&|s| s.zbar),
        ],
    })
});

/// The CIE table's columns with their wavelength terms of Planck's law: what a spectral sum
/// iterates over.
pub(crate) fn spectral_columns() -> &'static SpectralColumns {
    &SPECTRAL_COLUMNS
}

/// The number of partial sums a spectral sum keeps, one per SIMD lane it may use.
const SUM_LANES: usize = 8;

const _: () = assert!(PADDED_ROWS >= CIE_1931_ROWS && PADDED_ROWS.is_multiple_of(SUM_LANES));

/// Σ R(λ) · L(λ, T)/L_max · σⱼ(λ) over the CIE table (Eq. 11 with a reflectance) and the same
/// sum with R = 1 (the black body itself), as `(light, white)`. `reflectance` fills R at each
/// row's wavelength as a numerator and a denominator (untouched both stay 1), so that each row
/// takes one division: 1/(g(x) · denominator), with Planck's g of [`PlanckWeights`].
///
/// Each term is computed in a loop over the columns that the compiler vectorises, and the sum
/// keeps [`SUM_LANES`] partial sums, row i adding to partial sum i mod 8, added in a fixed order
/// at the end. On x86-64 processors with AVX-512 or AVX2 the same code runs compiled for those
/// instructions (chosen at run time; without fused multiply-add, so every rounding is the same
/// as in the SSE2 build): the same result at any thread count, on any machine.
pub(crate) fn planck_sums(
    weights: &PlanckWeights,
    reflectance: impl FnOnce(&Column, &mut Column, &mut Column),
) -> (DVec3, DVec3) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            #[allow(unsafe_code)]
            // SAFETY: the processor has AVX-512F, checked just above.
            return unsafe { planck_sums_avx512(weights, reflectance) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            #[allow(unsafe_code)]
            // SAFETY: the processor has AVX2, checked just above.
            return unsafe { planck_sums_avx2(weights, reflectance) };
        }
    }
    planck_sums_inline(weights, reflectance)
}

/// [`planck_sums`] compiled for AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn planck_sums_avx512(
    weights: &PlanckWeights,
    reflectance: impl FnOnce(&Column, &mut Column, &mut Column),
) -> (DVec3, DVec3) {
    planck_sums_inline(weights, reflectance)
}

/// [`planck_sums`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn planck_sums_avx2(
    weights: &PlanckWeights,
    reflectance: impl FnOnce(&Column, &mut Column, &mut Column),
) -> (DVec3, DVec3) {
    planck_sums_inline(weights, reflectance)
}

/// [`planck_sums`]' body, inlined into each of its instruction-set variants.
#[inline(always)]
fn planck_sums_inline(
    weights: &PlanckWeights,
    reflectance: impl FnOnce(&Column, &mut Column, &mut Column),
) -> (DVec3, DVec3) {
    let columns = spectral_columns();
    let (mut planck_numerator, mut planck_denominator) = ([0.0; PADDED_ROWS], [0.0; PADDED_ROWS]);
    weights.fractions(columns, &mut planck_numerator, &mut planck_denominator);
    let (mut numerator, mut denominator) = ([1.0; PADDED_ROWS], [1.0; PADDED_ROWS]);
    reflectance(&columns.wavelength_nm, &mut numerator, &mut denominator);
    // The white's term: L/L_max = N/g = N · d / (g · d); the light's: L/L_max · R = N · n / (g · d).
    let (mut white_term, mut light_term) = ([0.0; PADDED_ROWS], [0.0; PADDED_ROWS]);
    let rows = white_term
        .iter_mut()
        .zip(&mut light_term)
        .zip(planck_numerator.iter().zip(&planck_denominator))
        .zip(numerator.iter().zip(&denominator));
    for (((white, light), (&planck_numerator, &g)), (&numerator, &denominator)) in rows {
        let inverse = 1.0 / (g * denominator);
        *white = planck_numerator * denominator * inverse;
        *light = planck_numerator * numerator * inverse;
    }
    let (mut light, mut white) = ([[0.0; SUM_LANES]; 3], [[0.0; SUM_LANES]; 3]);
    for (j, sigma) in columns.tristimulus.iter().enumerate() {
        for ((sigma, white_term), light_term) in sigma
            .chunks_exact(SUM_LANES)
            .zip(white_term.chunks_exact(SUM_LANES))
            .zip(light_term.chunks_exact(SUM_LANES))
        {
            for lane in 0..SUM_LANES {
                light[j][lane] += light_term[lane] * sigma[lane];
                white[j][lane] += white_term[lane] * sigma[lane];
            }
        }
    }
    let total = |partial: [[f64; SUM_LANES]; 3]| {
        DVec3::from_array(partial.map(|lanes| lanes.into_iter().sum()))
    };
    (total(light), total(white))
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

/// The x from which [`one_minus_exp_minus`] subtracts.
const ONE_MINUS_EXP_BY_SUBTRACTION_FROM: f64 = 0.25;

/// g(x) = 1 − e^(−x) for x ≥ 0 given e^(−x): by subtraction where that loses at most a few
/// bits (x ≥ ¼), else by its series x · Σₖ (−x)ᵏ/(k + 1)! to k = 12 (the remainder is below
/// 10⁻¹⁷ relative for x < ¼; the GPU mirror uses a series too). Both forms are computed and one
/// is selected, without a branch, so that a loop over wavelengths vectorises.
#[inline(always)]
fn one_minus_exp_minus(x: f64, exp_minus_x: f64) -> f64 {
    let by_subtraction = 1.0 - exp_minus_x;
    let by_series = x * horner(-x, &INVERSE_FACTORIALS[1..]);
    if x >= ONE_MINUS_EXP_BY_SUBTRACTION_FROM {
        by_subtraction
    } else {
        by_series
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

    /// L(λ, T) / L_max at every row of `columns` as `numerator / g` (Eq. 10, in the form of the
    /// type's documentation), in a loop the compiler vectorises ([`exp_minus`]); the division
    /// is left to the sum.
    #[inline(always)]
    pub(crate) fn fractions(
        &self,
        columns: &SpectralColumns,
        numerator: &mut Column,
        g: &mut Column,
    ) {
        // g(x) by subtraction alone unless x < ¼ somewhere: at the longest wavelength, where x
        // is smallest, above about 69 000 K.
        if self.x_per_inverse_nm * self.inverse_longest_nm >= ONE_MINUS_EXP_BY_SUBTRACTION_FROM {
            self.fill_fractions(columns, numerator, g, |_, exp_minus_x| 1.0 - exp_minus_x);
        } else {
            self.fill_fractions(columns, numerator, g, one_minus_exp_minus);
        }
    }

    /// [`PlanckWeights::fractions`] with `one_minus_exp_minus(x, e^(−x))` = 1 − e^(−x).
    #[inline(always)]
    fn fill_fractions(
        &self,
        columns: &SpectralColumns,
        numerator: &mut Column,
        g: &mut Column,
        one_minus_exp_minus: impl Fn(f64, f64) -> f64,
    ) {
        let rows = numerator
            .iter_mut()
            .zip(g)
            .zip(columns.inverse_nm.iter().zip(&columns.longest_ratio_pow5));
        for ((numerator, g), (&inverse, &ratio_pow5)) in rows {
            let beyond = exp_minus(self.x_per_inverse_nm * (inverse - self.inverse_longest_nm));
            *g = one_minus_exp_minus(
                self.x_per_inverse_nm * inverse,
                self.exp_minus_x_longest * beyond,
            );
            *numerator = self.longest_factor * ratio_pow5 * beyond;
        }
    }
}

/// 1/k! for k = 0 … 13: the Taylor coefficients of eˣ that [`exp_minus`] and
/// [`one_minus_exp_minus`] sum.
const INVERSE_FACTORIALS: [f64; 14] = {
    let (mut coefficients, mut factorial) = ([1.0; 14], 1.0);
    let mut k = 1;
    while k < coefficients.len() {
        factorial *= k as f64; // exact: 13! < 2⁵³
        coefficients[k] = 1.0 / factorial;
        k += 1;
    }
    coefficients
};

/// Σₖ `coefficients[k]` · zᵏ by Horner's rule.
#[inline(always)]
fn horner(z: f64, coefficients: &[f64]) -> f64 {
    coefficients.iter().rev().fold(0.0, |sum, &c| sum * z + c)
}

/// e^(−y) for y ≥ 0, within a few units in the last place of `f64::exp`, in straight-line
/// arithmetic that the compiler vectorises in a loop (`f64::exp` is a library call it cannot).
///
/// The usual reduction: y = n ln 2 + r with n = round(y / ln 2) and |r| ≤ ln 2 / 2, ln 2 split
/// into a high part whose products with n are exact and a low part (the values of fdlibm's
/// `e_exp.c`); e^(−r) by its Taylor series to degree 13 (the remainder is below 5 · 10⁻¹⁸
/// relative); then the factor 2^(−n) is built in the exponent bits. Where y ≥ 708.75 (n = 1023;
/// e^(−y) < 2.3 · 10⁻³⁰⁸) and for NaN the result is 0: a spectral sum's terms are relative to the
/// largest, 1, so nothing that small can change it.
#[inline(always)]
pub(crate) fn exp_minus(y: f64) -> f64 {
    /// ln 2's leading 32 bits (6.93147180369123816490e-1).
    const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    /// ln 2 − `LN2_HI` (1.90821492927058770002e-10).
    const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    /// 1.5 · 2⁵²: adding it rounds a value below 2⁵¹ to an integer held in the low bits.
    const ROUNDING_SHIFTER: f64 = 6_755_399_441_055_744.0;
    /// Where y is held: n = round(y / ln 2) = 1023 there, exponent bits 0, a factor of zero.
    const ZERO_FROM: f64 = 709.0;
    let y = if y < ZERO_FROM { y } else { ZERO_FROM };
    let shifted = y * std::f64::consts::LOG2_E + ROUNDING_SHIFTER;
    let n = shifted - ROUNDING_SHIFTER;
    let z = n * LN2_HI - y + n * LN2_LO; // −r
    let series = horner(z, &INVERSE_FACTORIALS);
    let n_bits = shifted.to_bits().wrapping_sub(ROUNDING_SHIFTER.to_bits());
    let two_to_minus_n = f64::from_bits((1023_u64.wrapping_sub(n_bits)) << 52);
    series * two_to_minus_n
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
    let (_, relative) = planck_sums(&weights, |_, _, _| {});
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

    /// The distance between two positive finite doubles in units in the last place.
    fn ulps_apart(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn the_table_has_its_rows_and_the_padding_adds_nothing() {
        assert_eq!(cie_1931().len(), CIE_1931_ROWS);
        let columns = spectral_columns();
        for row in CIE_1931_ROWS..PADDED_ROWS {
            assert!(columns.tristimulus.iter().all(|sigma| sigma[row] == 0.0));
            assert_eq!(columns.wavelength_nm[row], CIE_1931_MAX_NM);
        }
        assert_eq!(INVERSE_FACTORIALS[13], 1.0 / 6_227_020_800.0);
    }

    #[test]
    fn exp_minus_agrees_with_the_standard_library() {
        // Every y on a grid of 2⁻¹⁰ from 0 to where e^(−y) leaves the normal range, and a seeded
        // random sample: the largest distance from f64::exp, in units in the last place.
        let mut rng = rand_like_lcg(0x5eed);
        let worst = (0..=725_000)
            .map(|i| f64::from(i) / 1024.0)
            .chain((0..200_000).map(|_| rng() * 708.0))
            .filter(|&y| y < 708.0)
            .map(|y| ulps_apart(exp_minus(y), (-y).exp()))
            .max()
            .expect("a non-empty sample");
        println!("exp_minus: worst {worst} ulp from f64::exp");
        assert!(worst <= 2, "{worst} ulp");
        assert_eq!(exp_minus(0.0), 1.0);
        for y in [708.75, 709.0, 1e6, f64::INFINITY, f64::NAN] {
            assert_eq!(exp_minus(y), 0.0, "y {y}");
        }
    }

    #[test]
    fn one_minus_exp_minus_agrees_with_expm1() {
        // Both forms, on both sides of x = ¼: the largest distance from −expm1(−x) in units in
        // the last place.
        let worst = (1..=400_000)
            .map(|i| f64::from(i) * 1e-6)
            .chain((0..=300).map(|i| 10f64.powf(-f64::from(i) / 10.0)))
            .map(|x| ulps_apart(one_minus_exp_minus(x, (-x).exp()), -(-x).exp_m1()))
            .max()
            .expect("a non-empty sample");
        println!("one_minus_exp_minus: worst {worst} ulp from expm1");
        assert!(worst <= 4, "{worst} ulp");
    }

    /// A small seeded generator of uniform values in [0, 1) (the crate has no `rand`).
    fn rand_like_lcg(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1_u64 << 53) as f64
        }
    }

    #[test]
    fn every_instruction_set_sums_alike() {
        // planck_sums chooses AVX-512 or AVX2 code at run time where the processor has them: each
        // build the processor can run must give the portable build's sums to the bit (no fused
        // multiply-add). Where it has neither, only the portable build is compared with itself.
        for t in [300.0, 1500.0, 6504.0, 40_000.0, 1e6] {
            let weights = PlanckWeights::new(t).expect("positive finite temperature");
            let reflect =
                |wavelengths: &Column, numerators: &mut Column, denominators: &mut Column| {
                    for ((n, d), w) in numerators.iter_mut().zip(denominators).zip(wavelengths) {
                        (*n, *d) = crate::spectral::sigmoid::sigmoid_fraction(0.02 * (w - 560.0));
                    }
                };
            let portable = planck_sums_inline(&weights, reflect);
            assert_eq!(planck_sums(&weights, reflect), portable, "T {t}");
            #[cfg(target_arch = "x86_64")]
            {
                if std::arch::is_x86_feature_detected!("avx512f") {
                    #[allow(unsafe_code)]
                    // SAFETY: the processor has AVX-512F, checked just above.
                    let sums = unsafe { planck_sums_avx512(&weights, reflect) };
                    assert_eq!(sums, portable, "AVX-512, T {t}");
                }
                if std::arch::is_x86_feature_detected!("avx2") {
                    #[allow(unsafe_code)]
                    // SAFETY: the processor has AVX2, checked just above.
                    let sums = unsafe { planck_sums_avx2(&weights, reflect) };
                    assert_eq!(sums, portable, "AVX2, T {t}");
                }
            }
        }
    }

    /// [`PlanckWeights::fractions`] divided out at every row of the table, in its order (the padding lane left out).
    fn row_weights(weights: &PlanckWeights) -> Vec<f64> {
        let (mut numerator, mut g) = ([0.0; PADDED_ROWS], [0.0; PADDED_ROWS]);
        weights.fractions(spectral_columns(), &mut numerator, &mut g);
        numerator
            .iter()
            .zip(g)
            .take(CIE_1931_ROWS)
            .map(|(n, g)| n / g)
            .collect()
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
            for ((sample, got), want) in cie_1931().iter().zip(row_weights(&weights)).zip(want) {
                assert!(
                    (got - want).abs() <= 1e-12,
                    "T {t}, λ {}: {got} vs {want}",
                    sample.wavelength_nm
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
            let largest = row_weights(&weights).into_iter().fold(0.0, f64::max);
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
