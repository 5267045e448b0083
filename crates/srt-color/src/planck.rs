//! Planck's law (Eq. 10 of the paper) and the exact SI constants it needs.
//!
//! Radiance is evaluated in the logarithmic domain, so that it neither overflows nor produces NaN
//! anywhere in its domain: deep in the Wien tail (short wavelengths, cold bodies) it underflows
//! gracefully to 0, and in the Rayleigh–Jeans tail it uses `x / expm1(x)` with its limit 1.

/// Planck's constant h in J·s (exact since the 2019 SI redefinition).
pub const PLANCK_CONSTANT: f64 = 6.626_070_15e-34;
/// Speed of light in vacuum c in m/s (exact).
pub const SPEED_OF_LIGHT: f64 = 299_792_458.0;
/// Boltzmann's constant k in J/K (exact since the 2019 SI redefinition).
pub const BOLTZMANN_CONSTANT: f64 = 1.380_649e-23;

/// The second radiation constant c₂ = hc/k in m·K, the scale of the exponent in Eq. 10.
pub const SECOND_RADIATION_CONSTANT: f64 = PLANCK_CONSTANT * SPEED_OF_LIGHT / BOLTZMANN_CONSTANT;

/// x_max = hc/(kλT) at the maximum of Planck's law in λ (Wien's displacement law): the root of
/// 5(1 − e^(−x)) = x, so that the peak lies at λ = hc/(k · x_max · T).
pub const WIEN_X: f64 = 4.965_114_231_744_276;

/// Spectral radiance of a black body, Eq. 10: L(λ, T) = 2hc²/λ⁵ · [exp(hc/(kTλ)) − 1]⁻¹.
///
/// `wavelength_m` is λ in metres, `temperature_k` is T in kelvin; the result is in
/// W·sr⁻¹·m⁻³ (per metre of wavelength). Doppler shift and searchlight effect (Eq. 9) map a Planck
/// spectrum onto a Planck spectrum: `planck_radiance(λ, D·T) == D⁵ · planck_radiance(D·λ, T)`.
///
/// Edge cases, never a panic and never NaN:
/// - a non-positive or non-finite wavelength or temperature gives 0.0;
/// - where the true value is below the smallest `f64` (cold bodies, short wavelengths) the result
///   is 0.0;
/// - where it exceeds `f64::MAX` (only for absurd temperatures, above about 10²⁹⁰ K) it is `+inf`.
#[must_use]
pub fn planck_radiance(wavelength_m: f64, temperature_k: f64) -> f64 {
    ln_planck_radiance(wavelength_m, temperature_k).exp()
}

/// Natural logarithm of [`planck_radiance`] (Eq. 10), `-inf` where the radiance is 0.
///
/// Finite for every positive finite λ and T, which lets tone maps that only need ratios of
/// radiances (Fig. 6 left) work at temperatures where the radiance itself underflows.
pub(crate) fn ln_planck_radiance(wavelength_m: f64, temperature_k: f64) -> f64 {
    let valid = |v: f64| v.is_finite() && v > 0.0;
    if !valid(wavelength_m) || !valid(temperature_k) {
        return f64::NEG_INFINITY;
    }
    // x = hc / (kTλ), computed as two divisions so that it cannot overflow through kTλ.
    let x = SECOND_RADIATION_CONSTANT / wavelength_m / temperature_k;
    if x >= 1.0 {
        // Wien side: L = 2hc²/λ⁵ · e^(−x) / (1 − e^(−x)).
        let two_h_c2 = 2.0 * PLANCK_CONSTANT * SPEED_OF_LIGHT * SPEED_OF_LIGHT;
        two_h_c2.ln() - 5.0 * wavelength_m.ln() - x - (-(-x).exp()).ln_1p()
    } else {
        // Rayleigh–Jeans side: L = 2ckT/λ⁴ · x / (eˣ − 1), the last factor → 1 as x → 0.
        let two_c_k = 2.0 * SPEED_OF_LIGHT * BOLTZMANN_CONSTANT;
        let correction = if x > 0.0 { x / x.exp_m1() } else { 1.0 };
        two_c_k.ln() + temperature_k.ln() - 4.0 * wavelength_m.ln() + correction.ln()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The textbook formula, evaluated directly (with `exp_m1`, harmless at these inputs).
    fn naive(wavelength_m: f64, temperature_k: f64) -> f64 {
        let h = PLANCK_CONSTANT;
        let c = SPEED_OF_LIGHT;
        let k = BOLTZMANN_CONSTANT;
        2.0 * h * c * c
            / wavelength_m.powi(5)
            / (h * c / (k * temperature_k * wavelength_m)).exp_m1()
    }

    #[test]
    fn agrees_with_the_textbook_formula_on_both_branches() {
        for &(l, t) in &[
            (500e-9, 6000.0),
            (2e-6, 300.0),
            (1e-3, 6000.0),
            (0.1, 1e4),
            (300e-9, 1000.0),
        ] {
            let got = planck_radiance(l, t);
            let want = naive(l, t);
            assert!(
                (got - want).abs() <= 1e-12 * want,
                "L({l}, {t}) = {got}, want {want}"
            );
        }
    }

    #[test]
    fn branches_meet_continuously_at_x_equal_one() {
        let t = 5000.0;
        let l = SECOND_RADIATION_CONSTANT / t;
        let below = planck_radiance(l * (1.0 - 1e-12), t);
        let above = planck_radiance(l * (1.0 + 1e-12), t);
        assert!((below - above).abs() <= 1e-10 * below);
    }

    #[test]
    fn degenerate_inputs_give_zero_not_nan() {
        for &(l, t) in &[
            (500e-9, 0.0),
            (500e-9, -10.0),
            (500e-9, f64::NAN),
            (500e-9, f64::INFINITY),
            (0.0, 6000.0),
            (-1e-7, 6000.0),
            (f64::NAN, 6000.0),
            (f64::INFINITY, 6000.0),
            (1e-12, 1.0),
            (380e-9, 1e-3),
            (f64::MIN_POSITIVE, 6000.0),
        ] {
            assert_eq!(planck_radiance(l, t), 0.0, "L({l}, {t})");
        }
    }

    #[test]
    fn extreme_but_valid_inputs_stay_finite_and_positive() {
        for &(l, t) in &[
            (1e300, 6000.0),
            (1e-300, 1e300),
            (500e-9, 1e30),
            (1e-3, 1e-2),
        ] {
            let ln = ln_planck_radiance(l, t);
            assert!(ln.is_finite(), "ln L({l}, {t}) = {ln}");
        }
        assert!(planck_radiance(1e300, 6000.0) >= 0.0);
        assert!(planck_radiance(500e-9, 1e30).is_finite());
    }
}
