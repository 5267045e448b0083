//! Tristimulus values (Eq. 11), chromaticity and the BT.709 matrix (Eq. 12) against published
//! colorimetry.

use glam::DVec3;
use srt_color::{blackbody_xyz, chromaticity, cie_1931, xyz_to_linear_rgb};

/// Planckian-locus chromaticities (CIE 15:2004: illuminant A is the Planckian radiator at
/// 2856 K; 6504 K is the Planckian temperature nearest D65).
#[test]
fn planckian_chromaticities_match_published_values() {
    for (t, want) in [(2856.0, (0.4476, 0.4074)), (6504.0, (0.3135, 0.3236))] {
        let xy = chromaticity(blackbody_xyz(t));
        assert!(
            (xy.x - want.0).abs() < 5e-4 && (xy.y - want.1).abs() < 5e-4,
            "T = {t}: got ({:.5}, {:.5}), want {want:?}",
            xy.x,
            xy.y
        );
    }
}

#[test]
fn planckian_locus_runs_from_red_to_blue() {
    // x falls monotonically with temperature along the locus.
    let mut previous = f64::INFINITY;
    for t in [
        1000.0, 1500.0, 2000.0, 3000.0, 5000.0, 10_000.0, 30_000.0, 1e6,
    ] {
        let xy = chromaticity(blackbody_xyz(t));
        assert!(xy.x < previous, "x({t}) = {}", xy.x);
        previous = xy.x;
    }
    // The T → ∞ limit of the locus is near (0.240, 0.234).
    let limit = chromaticity(blackbody_xyz(1e9));
    assert!(
        (limit.x - 0.2399).abs() < 2e-3 && (limit.y - 0.2342).abs() < 2e-3,
        "{limit}"
    );
}

#[test]
fn blackbody_xyz_is_the_absolute_riemann_sum() {
    // Y(6000 K) = Σ L(λ) ȳ(λ) · 1 nm; the sum of ȳ over the table is 106.857 (CIE), and L varies
    // by less than a factor 2 across the visible band at 6000 K, so Y lies between those bounds.
    let y = blackbody_xyz(6000.0).y;
    let sum_ybar: f64 = cie_1931().iter().map(|s| s.ybar).sum();
    assert!((sum_ybar - 106.857).abs() < 0.01, "Σȳ = {sum_ybar}");
    let l_min = srt_color::planck_radiance(700e-9, 6000.0);
    let l_max = srt_color::planck_radiance(483e-9, 6000.0);
    assert!(
        y > 0.8 * l_min * sum_ybar * 1e-9 && y < l_max * sum_ybar * 1e-9,
        "Y = {y}"
    );
    assert_eq!(blackbody_xyz(0.0), DVec3::ZERO);
    assert_eq!(blackbody_xyz(f64::NAN), DVec3::ZERO);
    assert_eq!(blackbody_xyz(-5.0), DVec3::ZERO);
}

#[test]
fn d65_white_maps_to_unit_rgb() {
    let rgb = xyz_to_linear_rgb(DVec3::new(0.950_47, 1.0, 1.088_83));
    assert!((rgb - DVec3::ONE).abs().max_element() < 2e-3, "{rgb}");
}

#[test]
fn bt709_primaries_map_to_unit_vectors() {
    // The BT.709 red primary has chromaticity (0.64, 0.33) and luminance 0.2126 for unit R.
    let red = DVec3::new(0.4124, 0.2126, 0.0193);
    let rgb = xyz_to_linear_rgb(red);
    assert!((rgb - DVec3::X).abs().max_element() < 2e-3, "{rgb}");
    let blue = DVec3::new(0.1805, 0.0722, 0.9505);
    assert!((xyz_to_linear_rgb(blue) - DVec3::Z).abs().max_element() < 2e-3);
}

#[test]
fn chromaticity_of_equal_energy_white_is_one_third() {
    let xy = chromaticity(DVec3::splat(2.0));
    assert!((xy.x - 1.0 / 3.0).abs() < 1e-15 && (xy.y - 1.0 / 3.0).abs() < 1e-15);
    assert!(chromaticity(DVec3::ZERO).is_nan());
}
