//! Stars at infinity seen by a moving observer (`distant_source_image`) against the closed-form
//! aberration and Doppler formulas for a star at angle θ from the direction of motion.

use proptest::prelude::*;
use srt_physics::{distant_source_image, lorentz_factor};

use crate::common;

proptest! {
    #![proptest_config(ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES))]

    #[test]
    fn aberration_and_doppler_follow_the_closed_form(
        speed in 0.0f64..0.999,
        theta in 0.0f64..std::f64::consts::PI,
        azimuth in 0.0f64..std::f64::consts::TAU,
        motion in common::unit_vector(),
    ) {
        let p = motion.any_orthonormal_vector();
        let q = motion.cross(p);
        let star = theta.cos() * motion
            + theta.sin() * (azimuth.cos() * p + azimuth.sin() * q);
        // The observer moves with `speed` along `motion`: the sky moves with −speed·motion.
        let beta = -speed * motion;
        let (seen, doppler) = distant_source_image(beta, star);
        let expected_cos = (theta.cos() + speed) / (1.0 + speed * theta.cos());
        prop_assert!((seen.length() - 1.0).abs() < 1e-12);
        prop_assert!((seen.dot(motion) - expected_cos).abs() < 1e-9);
        let gamma = lorentz_factor(beta);
        let expected_doppler = gamma * (1.0 + speed * theta.cos());
        prop_assert!((doppler - expected_doppler).abs() <= 1e-9 * expected_doppler);
        // The star stays in the plane of the motion and its rest direction (same azimuth).
        let side = star - star.dot(motion) * motion;
        if side.length() > 1e-6 {
            prop_assert!(seen.dot(side.normalize()) >= -1e-12);
            prop_assert!(seen.cross(star).dot(motion).abs() < 1e-9);
        }
        // Seen from the sky's frame again (the inverse boost), the star is where it was.
        let (back, back_doppler) = distant_source_image(-beta, seen);
        prop_assert!((back - star).length() < 1e-9);
        prop_assert!((doppler * back_doppler - 1.0).abs() < 1e-9);
    }
}
