//! The sRGB transfer curve, Eq. 13.

use proptest::prelude::*;
use srt_color::{SRGB_LINEAR_THRESHOLD, srgb_encode};

#[test]
fn known_values() {
    assert_eq!(srgb_encode(0.0), 0.0);
    assert!((srgb_encode(1.0) - 1.0).abs() < 1e-15);
    assert!((srgb_encode(0.5) - 0.7354).abs() < 1e-4);
    assert!((srgb_encode(0.18) - 0.4614).abs() < 1e-4);
    assert!((srgb_encode(0.002) - 0.02584).abs() < 1e-9);
}

#[test]
fn nearly_continuous_at_the_threshold() {
    // Eq. 13's published constants leave a jump of about −2.9 × 10⁻⁸ at 0.0031308.
    let below = srgb_encode(SRGB_LINEAR_THRESHOLD);
    let above = srgb_encode(SRGB_LINEAR_THRESHOLD * (1.0 + 1e-15));
    assert!((below - above).abs() < 1e-7, "{below} vs {above}");
    assert!((below - 0.040_449_936).abs() < 1e-9);
}

proptest! {
    #![proptest_config(ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES))]

    /// Monotone, up to the threshold's 3 × 10⁻⁸ jump.
    #[test]
    fn monotone(a in -1.0f64..20.0, delta in 0.0f64..1.0) {
        let b = a + delta;
        prop_assert!(srgb_encode(b) >= srgb_encode(a) - 3e-8);
    }

    /// Strictly increasing away from the threshold.
    #[test]
    fn strictly_increasing_on_each_segment(a in 0.0f64..1.0, delta in 1e-6f64..0.1) {
        let b = a + delta;
        prop_assume!(a > SRGB_LINEAR_THRESHOLD || b <= SRGB_LINEAR_THRESHOLD);
        prop_assert!(srgb_encode(b) > srgb_encode(a));
    }
}
