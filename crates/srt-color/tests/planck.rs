//! Planck's law (Eq. 10) and its Doppler behaviour (Eq. 9) against published physics.

use proptest::prelude::*;
use srt_color::{SECOND_RADIATION_CONSTANT, planck_radiance};

/// Wien's displacement constant b in m·K (CODATA 2018, exact to the digits given).
const WIEN_B: f64 = 2.897_771_955e-3;
/// Stefan–Boltzmann constant σ in W·m⁻²·K⁻⁴ (CODATA 2018).
const STEFAN_BOLTZMANN: f64 = 5.670_374_419e-8;

/// Wavelength of the maximum of L(·, T), by golden-section search around b/T.
fn numerical_peak(temperature_k: f64) -> f64 {
    let guess = WIEN_B / temperature_k;
    let (mut a, mut b) = (0.5 * guess, 2.0 * guess);
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    while (b - a) > 1e-9 * guess {
        let c = b - ratio * (b - a);
        let d = a + ratio * (b - a);
        if planck_radiance(c, temperature_k) > planck_radiance(d, temperature_k) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

#[test]
fn peak_follows_wiens_displacement_law() {
    for t in [300.0, 1500.0, 5772.0, 6000.0, 10_000.0, 1e5] {
        let peak = numerical_peak(t);
        let wien = WIEN_B / t;
        assert!(
            (peak / wien - 1.0).abs() < 1e-3,
            "T = {t}: peak {peak}, b/T {wien}"
        );
    }
}

#[test]
fn second_radiation_constant_is_codata() {
    // c₂ = hc/k = 1.438 776 877… × 10⁻² m·K.
    assert!((SECOND_RADIATION_CONSTANT - 1.438_776_877e-2).abs() < 1e-11);
}

/// π ∫ L dλ by Simpson's rule in ln λ over 10⁻² … 10³ times the peak wavelength.
fn radiant_exitance(temperature_k: f64) -> f64 {
    let peak = WIEN_B / temperature_k;
    let (lo, hi) = ((1e-2 * peak).ln(), (1e3 * peak).ln());
    let n = 20_000;
    let h = (hi - lo) / f64::from(n);
    let integrand = |s: f64| {
        let l = s.exp();
        planck_radiance(l, temperature_k) * l
    };
    let mut sum = integrand(lo) + integrand(hi);
    for i in 1..n {
        let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
        sum += weight * integrand(lo + f64::from(i) * h);
    }
    std::f64::consts::PI * sum * h / 3.0
}

#[test]
fn integral_obeys_the_stefan_boltzmann_law() {
    for t in [300.0, 1500.0, 6000.0, 50_000.0] {
        let exitance = radiant_exitance(t);
        let sigma_t4 = STEFAN_BOLTZMANN * t.powi(4);
        assert!(
            (exitance / sigma_t4 - 1.0).abs() < 1e-3,
            "T = {t}: {exitance} vs {sigma_t4}"
        );
    }
}

#[test]
fn approaches_rayleigh_jeans_and_wien_limits() {
    let (h, c, k) = (
        srt_color::PLANCK_CONSTANT,
        srt_color::SPEED_OF_LIGHT,
        srt_color::BOLTZMANN_CONSTANT,
    );
    // Long wavelengths: L → 2ckT/λ⁴, with relative correction ≈ x/2, x = hc/(kTλ).
    let (lambda, t) = (1.0_f64, 300.0);
    let rayleigh_jeans = 2.0 * c * k * t / lambda.powi(4);
    let x = h * c / (k * t * lambda);
    let ratio = planck_radiance(lambda, t) / rayleigh_jeans;
    assert!((ratio - (1.0 - x / 2.0)).abs() < 1e-9, "{ratio}");
    // Short wavelengths: L → 2hc²/λ⁵ · e^(−x).
    let (lambda, t) = (100e-9_f64, 300.0);
    let wien = 2.0 * h * c * c / lambda.powi(5) * (-(h * c / (k * t * lambda))).exp();
    assert!((planck_radiance(lambda, t) / wien - 1.0).abs() < 1e-12);
}

#[test]
fn doppler_example_of_fig_5() {
    // 6000 K seen with D = √(3/2) and 1/√(3/2): the paper's 7348 K and 4899 K, with the D⁵
    // searchlight factor of Eq. 9 on the radiance.
    let d = 1.5_f64.sqrt();
    assert_eq!((6000.0 * d).round(), 7348.0);
    assert_eq!((6000.0 / d).round(), 4899.0);
    let lambda = 550e-9;
    let shifted = d.powi(5) * planck_radiance(d * lambda, 6000.0);
    assert!((shifted / planck_radiance(lambda, 6000.0 * d) - 1.0).abs() < 1e-12);
    assert!(shifted > planck_radiance(lambda, 6000.0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES))]

    /// Eq. 9 with D = λ′/λ: a Doppler-shifted Planck spectrum is a Planck spectrum of temperature
    /// D·T, radiance scaled by D⁵.
    #[test]
    fn doppler_shift_of_a_planck_spectrum_is_a_planck_spectrum(
        lambda in 1e-8f64..1e-4,
        t in 10f64..1e6,
        d in 0.05f64..20.0,
    ) {
        let lhs = planck_radiance(lambda, d * t);
        let rhs = d.powi(5) * planck_radiance(d * lambda, t);
        prop_assert!(lhs.is_finite() && rhs.is_finite());
        prop_assert!((lhs - rhs).abs() <= 1e-12 * lhs.max(rhs) + 1e-300, "{lhs} vs {rhs}");
    }

    /// Hotter is brighter at every wavelength.
    #[test]
    fn radiance_increases_with_temperature(
        lambda in 1e-7f64..1e-4,
        t in 100f64..1e5,
        k in 1.001f64..10.0,
    ) {
        let cold = planck_radiance(lambda, t);
        let hot = planck_radiance(lambda, k * t);
        if cold > 0.0 {
            prop_assert!(hot > cold, "{hot} <= {cold}");
        } else {
            prop_assert!(hot >= 0.0);
        }
    }
}
