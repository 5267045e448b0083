//! The two tone maps of Fig. 6 and the colour tables, checked against the paper's statements.

use glam::DVec3;
use srt_color::{ToneMap, colour_table};

/// Temperatures spaced geometrically from `lo` to `hi`.
fn geometric(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
}

#[test]
fn searchlight_maps_1500_k_to_dark_red() {
    // §3.3: "A temperature of about 1500 K is now mapped to a dark red color": red first,
    // dark, no blue.
    let c = ToneMap::Searchlight.display_rgb(1500.0);
    assert!(
        c.x > 1.5 * c.y && c.y > c.z && c.z == 0.0 && c.x < 0.4,
        "not dark red: {c}"
    );
    // A snapshot of this implementation's value (the paper gives no number), so that a change
    // of it is seen; the check of the paper's statement is the one above.
    assert!(
        (c.x - 0.26).abs() < 0.01 && (c.y - 0.14).abs() < 0.01,
        "snapshot changed: {c}"
    );
}

#[test]
fn searchlight_maps_3600_k_and_above_to_white() {
    // §3.3: "temperatures above 3600 K are mapped to white".
    let at_3600 = ToneMap::Searchlight.display_rgb(3600.0);
    assert!(at_3600.min_element() > 0.97, "{at_3600}");
    for t in geometric(3700.0, 1e6, 200) {
        assert_eq!(ToneMap::Searchlight.display_rgb(t), DVec3::ONE, "T = {t}");
    }
    // …and not below: 3000 K is still visibly tinted.
    assert!(ToneMap::Searchlight.display_rgb(3000.0).z < 0.85);
}

#[test]
fn searchlight_fades_to_black_when_cold_and_brightens_monotonically() {
    assert!(ToneMap::Searchlight.display_rgb(1000.0).max_element() < 0.01);
    assert!(ToneMap::Searchlight.display_rgb(700.0).max_element() < 1e-4);
    let mut previous = DVec3::ZERO;
    for t in geometric(100.0, 1e6, 2000) {
        let c = ToneMap::Searchlight.display_rgb(t);
        assert!(c.cmpge(previous).all(), "T = {t}: {c} after {previous}");
        previous = c;
    }
}

#[test]
fn luminance_keeps_full_brightness() {
    // Dividing by Y leaves some linear channel ≥ 1, so the brightest channel saturates at every
    // temperature: the top row of Fig. 6 (left) is fully bright.
    for t in geometric(100.0, 1e6, 500) {
        let c = ToneMap::Luminance.display_rgb(t);
        assert_eq!(c.max_element(), 1.0, "T = {t}: {c}");
        assert!(c.min_element() >= 0.0);
    }
}

#[test]
fn luminance_runs_red_orange_white_light_blue() {
    let red = ToneMap::Luminance.display_rgb(1000.0);
    assert!(red.x == 1.0 && red.y < 0.3 && red.z == 0.0, "1000 K: {red}");
    let orange = ToneMap::Luminance.display_rgb(1500.0);
    assert!(
        orange.x == 1.0 && (0.5..0.8).contains(&orange.y) && orange.z == 0.0,
        "1500 K: {orange}"
    );
    let white = ToneMap::Luminance.display_rgb(6504.0);
    assert!(white.min_element() > 0.97, "6504 K: {white}");
    let blue = ToneMap::Luminance.display_rgb(26_000.0);
    assert!(
        blue.z == 1.0 && blue.y > blue.x && blue.x < 0.9,
        "26000 K: {blue}"
    );
    // Hue moves monotonically: red/blue ratio falls with temperature.
    let mut previous = f64::INFINITY;
    for t in geometric(2000.0, 1e6, 300) {
        let c = ToneMap::Luminance.display_rgb(t);
        let ratio = c.x / c.z;
        assert!(ratio <= previous, "T = {t}");
        previous = ratio;
    }
}

#[test]
fn tone_maps_differ_only_in_brightness_handling() {
    // Both see the same hue at 1500 K: red above green above blue.
    for tone_map in ToneMap::ALL {
        let c = tone_map.display_rgb(1500.0);
        assert!(c.x > c.y && c.y > c.z, "{tone_map:?}: {c}");
    }
    assert_ne!(
        ToneMap::Luminance.display_rgb(1500.0),
        ToneMap::Searchlight.display_rgb(1500.0)
    );
    assert_eq!(ToneMap::default(), ToneMap::Luminance);
}

#[test]
fn colour_table_layout() {
    let (w, h) = (26, 11);
    for tone_map in ToneMap::ALL {
        let table = colour_table(tone_map, 1000.0, 26_000.0, w, h);
        assert_eq!(table.len(), w * h);
        for i in 0..w {
            let t = 1000.0 + 1000.0 * i as f64;
            let exact = tone_map.display_rgb(t).as_vec3().to_array();
            assert_eq!(table[i], exact, "top row, column {i}");
            assert_eq!(table[(h - 1) * w + i], [0.0; 3], "bottom row, column {i}");
            let middle = table[5 * w + i];
            for k in 0..3 {
                assert!(
                    (middle[k] - 0.5 * exact[k]).abs() < 1e-6,
                    "f = 0.5, column {i}"
                );
            }
        }
    }
    assert!(colour_table(ToneMap::Luminance, 1000.0, 2000.0, 0, 5).is_empty());
    assert!(colour_table(ToneMap::Luminance, 1000.0, 2000.0, 5, 0).is_empty());
    let single = colour_table(ToneMap::Luminance, 1000.0, 2000.0, 1, 1);
    assert_eq!(
        single,
        vec![ToneMap::Luminance.display_rgb(1000.0).as_vec3().to_array()]
    );
}
