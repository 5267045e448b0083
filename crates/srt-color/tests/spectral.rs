//! Spectral surface colour (issue 11) against independent numbers: round trips through the
//! Jakob–Hanika fit and table, the grey-surface identity with the paper's shortcut, and
//! colour-science's own Jakob 2019 implementation under Doppler shifts.
//!
//! CIELAB whites: round trips use the perfect white reflector under D65 (the fit's white);
//! reflected light uses a perfect white reflector in the same place, i.e. the black body at
//! D_in · D_out · T. ΔE00 is CIEDE2000 (`support/ciede2000.rs`, checked against colour-science).

use crate::support;

use glam::DVec3;
use proptest::prelude::*;
use srt_color::spectral::{
    CoefficientTable, INFRARED_ABOVE_NM, Reflectance, ReflectedLight, SigmoidPolynomial,
    ULTRAVIOLET_BELOW_NM, d65_white_xyz, emitted_display_rgb, emitted_light, fit_rgb,
    linear_rgb_to_xyz, reflectance_xyz_d65, reflected_display_rgb, reflected_light,
    srgb_coefficient_table, xyz_to_lab,
};
use srt_color::{ColourError, ToneMap, blackbody_xyz, blackbody_xyz_scaled, srgb_decode};
use support::ciede2000::delta_e_2000;
use support::{fixture_rows, number};

/// Largest and mean of a list of differences.
fn max_mean(values: &[f64]) -> (f64, f64) {
    let max = values.iter().copied().fold(0.0, f64::max);
    (max, values.iter().sum::<f64>() / values.len() as f64)
}

/// CIELAB of reflected light relative to the perfect white reflector in the same place.
fn reflected_lab(reflected: &ReflectedLight) -> DVec3 {
    let white = reflected.white.relative / reflected.white.relative.y;
    xyz_to_lab(reflected.light.relative / reflected.white.relative.y, white)
}

/// The 6 × 6 × 6 grid of sRGB-encoded colours 0, 0.2, …, 1, as linear RGB.
fn srgb_grid() -> Vec<DVec3> {
    let level = |i: u32| srgb_decode(f64::from(i) / 5.0);
    (0..216)
        .map(|n| DVec3::new(level(n / 36), level(n / 6 % 6), level(n % 6)))
        .collect()
}

/// ΔE00 under D65 between linear `rgb` and the reflectance chosen for it by `upsample`.
fn round_trip_errors(upsample: impl Fn(DVec3) -> SigmoidPolynomial) -> Vec<f64> {
    let white = d65_white_xyz();
    srgb_grid()
        .into_iter()
        .map(|rgb| {
            let target = xyz_to_lab(linear_rgb_to_xyz(rgb), white);
            let got = reflectance_xyz_d65(&Reflectance::new(upsample(rgb)));
            delta_e_2000(target, xyz_to_lab(got, white))
        })
        .collect()
}

#[test]
fn ciede2000_agrees_with_colour_science() {
    let rows = fixture_rows("ciede2000_reference.csv");
    assert!(rows.len() >= 40);
    for row in rows {
        let lab = |k: usize| DVec3::new(number(&row, k), number(&row, k + 1), number(&row, k + 2));
        let got = delta_e_2000(lab(0), lab(3));
        let want = number(&row, 6);
        assert!((got - want).abs() < 1e-4, "{row:?}: {got}");
    }
}

#[test]
fn fresh_fits_reproduce_the_srgb_grid_within_1_de00() {
    let errors = round_trip_errors(|rgb| fit_rgb(rgb).unwrap().polynomial);
    let (max, mean) = max_mean(&errors);
    eprintln!(
        "round trip by fit: ΔE00 max {max:.4}, mean {mean:.4} over {}",
        errors.len()
    );
    assert!(max <= 1.0, "max ΔE00 {max}");
}

#[test]
fn the_table_reproduces_the_srgb_grid_within_1_de00() {
    let table = srgb_coefficient_table();
    let errors = round_trip_errors(|rgb| table.lookup(rgb).unwrap());
    let (max, mean) = max_mean(&errors);
    eprintln!(
        "round trip by table: ΔE00 max {max:.4}, mean {mean:.4} over {}",
        errors.len()
    );
    assert!(max <= 1.0, "max ΔE00 {max}");
}

#[test]
fn table_texels_are_fresh_fits_and_lookups_between_them_agree() {
    let table = srgb_coefficient_table();
    let n = table.resolution();
    let white = d65_white_xyz();
    let lab_of =
        |p: SigmoidPolynomial| xyz_to_lab(reflectance_xyz_d65(&Reflectance::new(p)), white);
    // Texels: the table holds what a fresh fit finds (same colour within 0.05 ΔE00).
    for (m, k, j, i) in [
        (0, n - 1, 0, 0),
        (1, n / 2, 3, n - 2),
        (2, 7, n - 1, 5),
        (0, 2, 1, 1),
    ] {
        let texel = table.texel(m, k, j, i).unwrap().map(f64::from);
        let fresh = fit_rgb(table.texel_rgb(m, k, j, i)).unwrap().polynomial;
        let de = delta_e_2000(
            lab_of(SigmoidPolynomial::new(texel).unwrap()),
            lab_of(fresh),
        );
        assert!(de < 0.05, "texel ({m}, {k}, {j}, {i}): ΔE00 {de}");
    }
    // Between texels: seeded pseudo-random colours, table against fresh fit.
    let mut state = 0x2019_u64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let errors: Vec<f64> = (0..300)
        .map(|_| {
            let rgb = DVec3::new(next(), next(), next());
            let de = delta_e_2000(
                lab_of(table.lookup(rgb).unwrap()),
                lab_of(fit_rgb(rgb).unwrap().polynomial),
            );
            assert!(de <= 1.0, "{rgb}: ΔE00 {de}");
            de
        })
        .collect();
    let (max, mean) = max_mean(&errors);
    eprintln!("table against fresh fit: ΔE00 max {max:.4}, mean {mean:.4} over 300 colours");
}

#[test]
fn a_grey_surface_reflects_exactly_the_shifted_black_body() {
    for rho in [0.0, 0.18, 0.5, 1.0] {
        let grey = Reflectance::grey(rho).unwrap();
        for (t, d_in, d_out) in [(6504.0, 1.0, 1.0), (3000.0, 0.7, 1.9), (5800.0, 2.5, 0.3)] {
            let reflected = reflected_light(&grey, t, d_in, d_out).unwrap();
            let want = rho * blackbody_xyz(d_in * d_out * t);
            let got = reflected.light.xyz();
            assert!(
                (got - want).abs().max_element() <= 1e-12 * want.max_element().max(1e-300),
                "ρ {rho}, T {t}, D {d_in}·{d_out}: {got} vs {want}"
            );
            let body = blackbody_xyz_scaled(d_in * d_out * t);
            assert!(
                (reflected.white.relative - body.relative)
                    .abs()
                    .max_element()
                    < 1e-12
            );
            assert!((reflected.white.ln_scale - body.ln_scale).abs() < 1e-12);
            for tone_map in ToneMap::ALL {
                let got = reflected_display_rgb(tone_map, &grey, t, d_in, d_out, 1.0).unwrap();
                let light = srt_color::ScaledXyz {
                    relative: rho * reflected.white.relative,
                    ..reflected.white
                };
                let want = tone_map
                    .display_rgb_xyz(light, reflected.white, 1.0)
                    .unwrap();
                assert!(
                    (got - want).abs().max_element() < 1e-12,
                    "{tone_map:?} ρ {rho}"
                );
                if rho == 1.0 {
                    let shortcut = tone_map.display_rgb(d_in * d_out * t);
                    assert!((got - shortcut).abs().max_element() < 1e-12, "{tone_map:?}");
                }
            }
        }
    }
}

#[test]
fn emitters_are_the_black_body_at_d_times_t() {
    for (t, d) in [(6000.0, 1.5_f64.sqrt()), (1800.0, 0.4), (9000.0, 3.0)] {
        let got = emitted_display_rgb(ToneMap::Luminance, t, 1.0, d, 1.0).unwrap();
        assert_eq!(got, ToneMap::Luminance.display_rgb(d * t));
        let light = emitted_light(t, 2.0, d).unwrap();
        let want = 2.0 * blackbody_xyz(d * t);
        assert!((light.xyz() - want).abs().max_element() <= 1e-12 * want.max_element());
    }
    // Brightness brightens under the searchlight map; zero brightness is black.
    let dim = emitted_display_rgb(ToneMap::Searchlight, 1500.0, 0.01, 1.0, 1.0).unwrap();
    let bright = emitted_display_rgb(ToneMap::Searchlight, 1500.0, 1.0, 1.0, 1.0).unwrap();
    assert!(dim.x < bright.x);
    assert_eq!(
        emitted_display_rgb(ToneMap::Searchlight, 1500.0, 0.0, 1.0, 1.0).unwrap(),
        DVec3::ZERO
    );
}

#[test]
fn agrees_with_colour_science_under_doppler_shifts() {
    let table = srgb_coefficient_table();
    let rows = fixture_rows("jakob_reference.csv");
    assert!(rows.len() >= 100);
    let (mut by_fit, mut by_table, mut by_their_coefficients) = (vec![], vec![], vec![]);
    for row in &rows {
        let rgb = DVec3::new(number(row, 2), number(row, 3), number(row, 4));
        let (d_in, d_out) = (number(row, 5), number(row, 6));
        let theirs =
            SigmoidPolynomial::new([number(row, 7), number(row, 8), number(row, 9)]).unwrap();
        let want = DVec3::new(number(row, 10), number(row, 11), number(row, 12));
        let de = |p: SigmoidPolynomial| {
            let reflected = reflected_light(&Reflectance::new(p), 6504.0, d_in, d_out).unwrap();
            delta_e_2000(reflected_lab(&reflected), want)
        };
        by_fit.push(de(fit_rgb(rgb).unwrap().polynomial));
        by_table.push(de(table.lookup(rgb).unwrap()));
        by_their_coefficients.push(de(theirs));
    }
    let report = |name: &str, errors: &[f64], bound: f64| {
        let (max, mean) = max_mean(errors);
        eprintln!(
            "against colour-science, {name}: ΔE00 max {max:.4}, mean {mean:.4} over {}",
            errors.len()
        );
        assert!(max <= bound, "{name}: max ΔE00 {max}");
    };
    // Their coefficients through our integration: checks the Doppler integral alone.
    report(
        "their coefficients, our integral",
        &by_their_coefficients,
        0.05,
    );
    report("our fit", &by_fit, 2.0);
    report("our table", &by_table, 2.0);
}

#[test]
fn band_overrides_replace_the_model_outside_the_visible() {
    let red = fit_rgb(DVec3::new(0.6, 0.05, 0.03)).unwrap().polynomial;
    let banded = Reflectance::with_bands(red, Some(0.05), Some(0.3)).unwrap();
    assert_eq!(banded.evaluate(INFRARED_ABOVE_NM + 1.0), 0.3);
    assert_eq!(banded.evaluate(ULTRAVIOLET_BELOW_NM - 1.0), 0.05);
    assert_eq!(banded.evaluate(600.0), red.evaluate(600.0));
    // D_out = 4.36: the visible window shows 1.57–3.6 µm, all infrared: a grey of 0.3.
    let infrared = reflected_light(&banded, 6504.0, 1.0, 4.36).unwrap();
    let grey = reflected_light(&Reflectance::grey(0.3).unwrap(), 6504.0, 1.0, 4.36).unwrap();
    assert!(
        (infrared.light.relative - grey.light.relative)
            .abs()
            .max_element()
            < 1e-12
    );
    // D_out = 0.2: 72–166 nm, all ultraviolet.
    let ultraviolet = reflected_light(&banded, 6504.0, 1.0, 0.2).unwrap();
    let grey = reflected_light(&Reflectance::grey(0.05).unwrap(), 6504.0, 1.0, 0.2).unwrap();
    assert!(
        (ultraviolet.light.relative - grey.light.relative)
            .abs()
            .max_element()
            < 1e-12
    );
    // Without overrides the model holds its edge values: R(830 nm) at every longer wavelength.
    let plain = Reflectance::new(red);
    assert_eq!(plain.evaluate(3400.0), red.evaluate(830.0));
    assert_eq!(plain.evaluate(100.0), red.evaluate(360.0));
    assert!(Reflectance::with_bands(red, Some(1.5), None).is_err());
    assert!(Reflectance::with_bands(red, None, Some(f64::NAN)).is_err());
}

#[test]
fn exposure_keeps_every_factor_in_range() {
    for tone_map in ToneMap::ALL {
        let mut previous = DVec3::ZERO;
        for exponent in -20..=6 {
            let exposure = 10f64.powi(exponent);
            let c = tone_map.display_rgb_exposed(4000.0, exposure).unwrap();
            assert!(c.is_finite() && c.cmpge(DVec3::ZERO).all() && c.cmple(DVec3::ONE).all());
            assert!(
                c.cmpge(previous).all(),
                "{tone_map:?} not monotone at {exposure}"
            );
            previous = c;
            let red = Reflectance::new(fit_rgb(DVec3::new(0.7, 0.1, 0.1)).unwrap().polynomial);
            let r = reflected_display_rgb(tone_map, &red, 6504.0, 0.5, 3.0, exposure).unwrap();
            assert!(r.is_finite() && r.cmpge(DVec3::ZERO).all() && r.cmple(DVec3::ONE).all());
        }
        assert_eq!(
            tone_map.display_rgb_exposed(4000.0, 1.0).unwrap(),
            tone_map.display_rgb(4000.0)
        );
        let faint = tone_map.display_rgb_exposed(4000.0, 1e-20).unwrap();
        assert!(faint.max_element() < 1e-12, "{faint}");
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                tone_map.display_rgb_exposed(4000.0, bad),
                Err(ColourError::InvalidExposure(_))
            ));
        }
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic_or_nan() {
    let grey = Reflectance::grey(0.5).unwrap();
    for bad in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            reflected_light(&grey, bad, 1.0, 1.0),
            Err(ColourError::InvalidTemperature(_))
        ));
        assert!(matches!(
            reflected_light(&grey, 6504.0, bad, 1.0),
            Err(ColourError::InvalidDoppler(_))
        ));
        assert!(matches!(
            reflected_light(&grey, 6504.0, 1.0, bad),
            Err(ColourError::InvalidDoppler(_))
        ));
        assert!(ToneMap::Luminance.display_rgb_exposed(bad, 1.0).is_err());
        assert!(emitted_light(bad, 1.0, 1.0).is_err());
    }
    assert!(matches!(
        reflected_light(&grey, 1e300, 1e10, 1e10),
        Err(ColourError::ApparentTemperatureOutOfRange(_))
    ));
    assert!(emitted_light(6000.0, -1.0, 1.0).is_err());
    assert!(emitted_light(6000.0, f64::NAN, 1.0).is_err());
    assert!(Reflectance::grey(1.01).is_err());
    assert!(fit_rgb(DVec3::new(0.1, -0.2, 0.3)).is_err());
    assert!(CoefficientTable::build(1).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)
    })]

    #[test]
    fn reflectance_always_lies_in_0_1(
        c0 in -1e-2..1e-2f64, c1 in -10.0..10.0f64, c2 in -1e3..1e3f64, nm in 1.0..1e5f64,
    ) {
        let r = Reflectance::new(SigmoidPolynomial::new([c0, c1, c2]).unwrap()).evaluate(nm);
        prop_assert!((0.0..=1.0).contains(&r), "R({nm}) = {r}");
    }

    #[test]
    fn display_colour_is_finite_for_any_doppler_factors(
        r in 0.0..=1.0f64, g in 0.0..=1.0f64, b in 0.0..=1.0f64,
        ln_d_in in -3.0..3.0f64, ln_d_out in -3.0..3.0f64, ln_exposure in -20.0..6.0f64,
    ) {
        let polynomial = srgb_coefficient_table().lookup(DVec3::new(r, g, b)).unwrap();
        let reflectance = Reflectance::new(polynomial);
        for tone_map in ToneMap::ALL {
            let c = reflected_display_rgb(
                tone_map,
                &reflectance,
                6504.0,
                10f64.powf(ln_d_in),
                10f64.powf(ln_d_out),
                10f64.powf(ln_exposure),
            )
            .unwrap();
            prop_assert!(c.is_finite() && c.cmpge(DVec3::ZERO).all() && c.cmple(DVec3::ONE).all());
        }
    }
}
