//! The GPU temperature lookup table: layout, sampling rule, clamping and interpolation error.

use proptest::prelude::*;
use srt_color::{LutError, TemperatureLut, ToneMap};

fn default_lut(tone_map: ToneMap) -> TemperatureLut {
    TemperatureLut::with_defaults(tone_map)
}

#[test]
fn layout_is_uniform_in_log_temperature_with_exact_ends() {
    let lut = TemperatureLut::build(ToneMap::Luminance, 5, 100.0, 1e6).expect("valid");
    assert_eq!(lut.size(), 5);
    assert_eq!(lut.texels().len(), 5);
    assert_eq!(
        (lut.t_min(), lut.t_max(), lut.tone_map()),
        (100.0, 1e6, ToneMap::Luminance)
    );
    let temperatures: Vec<f64> = (0..5).map(|i| lut.texel_temperature(i)).collect();
    assert_eq!(temperatures[0], 100.0);
    assert_eq!(temperatures[4], 1e6);
    for (i, want) in [(1, 1e3), (2, 1e4), (3, 1e5)] {
        assert!(
            (temperatures[i] / want - 1.0).abs() < 1e-12,
            "{temperatures:?}"
        );
    }
    for (i, texel) in lut.texels().iter().enumerate() {
        let exact = ToneMap::Luminance.display_rgb(temperatures[i]).as_vec3();
        assert_eq!(texel[..3], exact.to_array());
        assert_eq!(texel[3], 1.0);
    }
}

#[test]
fn sampling_at_a_texel_temperature_returns_that_texel_exactly() {
    for tone_map in ToneMap::ALL {
        let lut = default_lut(tone_map);
        for i in 0..lut.size() {
            assert_eq!(
                lut.sample(lut.texel_temperature(i)),
                lut.texels()[i],
                "{tone_map:?}, texel {i}"
            );
        }
    }
}

#[test]
fn sampling_clamps_beyond_the_range() {
    let lut = default_lut(ToneMap::Luminance);
    let first = lut.texels()[0];
    let last = *lut.texels().last().expect("not empty");
    assert_ne!(first, last);
    for t in [
        99.0,
        1.0,
        1e-30,
        0.0,
        -5.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        assert_eq!(lut.sample(t), first, "T = {t}");
    }
    for t in [1.0e6 * 1.0001, 1e9, f64::MAX] {
        assert_eq!(lut.sample(t), last, "T = {t}");
    }
}

#[test]
fn sampling_interpolates_linearly_in_log_temperature() {
    let lut = TemperatureLut::build(ToneMap::Searchlight, 3, 1000.0, 4000.0).expect("valid");
    // Texels at 1000, 2000 and 4000 K; √2 · 1000 K is half way between the first two in ln T.
    let s = lut.sample(1000.0 * 2f64.sqrt());
    let (a, b) = (lut.texels()[0], lut.texels()[1]);
    for k in 0..3 {
        assert!((s[k] - 0.5 * (a[k] + b[k])).abs() < 1e-6);
    }
    assert_ne!(a, b);
}

#[test]
fn texture_coordinate_is_the_gpu_rule() {
    let lut = default_lut(ToneMap::Luminance);
    let n = lut.size() as f32;
    assert_eq!(lut.texture_coordinate(100.0), 0.5 / n);
    assert!((lut.texture_coordinate(1e6) - (1.0 - 0.5 / n)).abs() < 1e-7);
    assert!((lut.texture_coordinate(1e4) - 0.5).abs() < 1e-7);
    assert_eq!(lut.texture_coordinate(1.0), 0.5 / n);
    assert_eq!(lut.texture_coordinate(f64::NAN), 0.5 / n);
    assert_eq!(lut.texture_coordinate(1e12), lut.texture_coordinate(1e6));
}

/// What a linearly filtered, clamp-to-edge 1D texture returns at coordinate `s` (in f64).
fn gpu_filter(lut: &TemperatureLut, s: f32) -> [f64; 4] {
    let n = lut.size();
    let x = (f64::from(s) * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
    let i = x.floor() as usize;
    let t = x - i as f64;
    let (a, b) = (lut.texels()[i], lut.texels()[(i + 1).min(n - 1)]);
    std::array::from_fn(|k| (1.0 - t) * f64::from(a[k]) + t * f64::from(b[k]))
}

proptest! {
    #![proptest_config(ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES))]

    #[test]
    fn texture_coordinate_is_monotone(a in 1.0f64..1e7, k in 1.0f64..100.0) {
        let lut = TemperatureLut::build(ToneMap::Luminance, 256, 100.0, 1e6).expect("valid");
        prop_assert!(lut.texture_coordinate(a) <= lut.texture_coordinate(a * k));
    }

    /// `sample` is what the GPU's filter returns at `texture_coordinate`, up to f32 rounding of
    /// the coordinate.
    #[test]
    fn sample_agrees_with_filtering_at_the_texture_coordinate(t in 50.0f64..2e6) {
        let lut = TemperatureLut::build(ToneMap::Searchlight, 256, 100.0, 1e6).expect("valid");
        let cpu = lut.sample(t);
        let gpu = gpu_filter(&lut, lut.texture_coordinate(t));
        for k in 0..4 {
            prop_assert!((f64::from(cpu[k]) - gpu[k]).abs() < 1e-4, "{cpu:?} vs {gpu:?}");
        }
    }
}

/// Largest channel error of `lut.sample` against the exact tone map, over `per_interval` points
/// inside every texel interval; returned separately for intervals where a channel leaves 0 (an
/// "onset", one texel exactly 0 and the next not) and for all others.
fn interpolation_error(lut: &TemperatureLut, per_interval: usize) -> (f64, f64, usize) {
    let (mut smooth, mut onset, mut onsets) = (0.0f64, 0.0f64, 0);
    for i in 0..lut.size() - 1 {
        let (a, b) = (lut.texels()[i], lut.texels()[i + 1]);
        let is_onset = (0..3).any(|k| (a[k] == 0.0) != (b[k] == 0.0));
        onsets += usize::from(is_onset);
        let (lo, hi) = (
            lut.texel_temperature(i).ln(),
            lut.texel_temperature(i + 1).ln(),
        );
        for j in 1..per_interval {
            let t = (lo + (hi - lo) * j as f64 / per_interval as f64).exp();
            let exact = lut.tone_map().display_rgb(t);
            let got = lut.sample(t);
            let error = (0..3)
                .map(|k| (f64::from(got[k]) - exact[k]).abs())
                .fold(0.0, f64::max);
            if is_onset {
                onset = onset.max(error);
            } else {
                smooth = smooth.max(error);
            }
        }
    }
    (smooth, onset, onsets)
}

#[test]
fn default_size_meets_its_documented_error_bounds() {
    let (lo, hi) = TemperatureLut::DEFAULT_RANGE_K;
    for tone_map in ToneMap::ALL {
        let lut = default_lut(tone_map);
        assert_eq!(
            (lut.size(), lut.t_min(), lut.t_max()),
            (TemperatureLut::DEFAULT_SIZE, lo, hi)
        );
        let (smooth, onset, onsets) = interpolation_error(&lut, 16);
        println!("{tone_map:?}: max error {smooth:.5} (smooth), {onset:.5} at {onsets} onsets");
        assert!(smooth < 1.0 / 255.0, "{tone_map:?}: smooth error {smooth}");
        assert!(onset < 0.01, "{tone_map:?}: onset error {onset}");
        assert!(onsets <= 3, "{tone_map:?}: {onsets} onset intervals");
    }
}

#[test]
fn half_the_default_size_is_not_enough() {
    let (lo, hi) = TemperatureLut::DEFAULT_RANGE_K;
    let worst = ToneMap::ALL
        .into_iter()
        .map(|tone_map| {
            let lut = TemperatureLut::build(tone_map, TemperatureLut::DEFAULT_SIZE / 2, lo, hi)
                .expect("valid");
            let (smooth, onset, _) = interpolation_error(&lut, 16);
            smooth.max(onset)
        })
        .fold(0.0, f64::max);
    assert!(worst > 0.01, "{worst}");
}

#[test]
fn build_rejects_bad_parameters() {
    let build = |size, lo, hi| TemperatureLut::build(ToneMap::Luminance, size, lo, hi);
    assert_eq!(
        build(0, 100.0, 1e6),
        Err(LutError::TooFewTexels { size: 0 })
    );
    assert_eq!(
        build(1, 100.0, 1e6),
        Err(LutError::TooFewTexels { size: 1 })
    );
    assert_eq!(
        build(8193, 100.0, 1e6),
        Err(LutError::TooManyTexels { size: 8193 })
    );
    assert_eq!(
        build(usize::MAX, 100.0, 1e6),
        Err(LutError::TooManyTexels { size: usize::MAX })
    );
    for (lo, hi) in [
        (0.0, 1e6),
        (-1.0, 1e6),
        (100.0, 100.0),
        (1e6, 100.0),
        (100.0, f64::INFINITY),
    ] {
        assert_eq!(
            build(16, lo, hi),
            Err(LutError::InvalidRange {
                t_min_k: lo,
                t_max_k: hi
            })
        );
    }
    assert!(matches!(
        build(16, f64::NAN, 1e6),
        Err(LutError::InvalidRange { .. })
    ));
    assert!(build(2, 100.0, 100.000_001).is_ok());
    assert!(build(TemperatureLut::MAX_SIZE, 100.0, 1e6).is_ok());
    let message = build(1, 100.0, 1e6).expect_err("too small").to_string();
    assert!(message.contains("at least 2"), "{message}");
}
