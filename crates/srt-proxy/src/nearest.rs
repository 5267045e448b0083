//! A lower bound of the apparent distance over a convex set of points at rest in S′: the depth at
//! which a footprint may be rasterised so that every hit its fragments find lies at or behind it
//! (the GPU's visibility passes declare their written depth "greater or equal", so that a GPU
//! may reject a fragment before running it; `shaders/proxy.wgsl` mirrors this in f32).
//!
//! The apparent distance of a point w′ (relative to the observer's rest-frame position) is
//! r(w′) = γ (|w′| − β·w′) ([`Frame::apparent_distance`], from Eq. 8 at the emission event
//! (ct′_obs − |w′|, w′)). For every unit vector u, |w′| ≥ u·w′ (Cauchy–Schwarz), so
//! r(w′) ≥ γ (u − β)·w′: a linear function, whose least value over the convex hull of some
//! points is at one of them. Each choice of u gives a bound; [`nearest_apparent_distance`] takes
//! the best of the directions to the points and to their centroid, which for a set seen under a
//! small angle θ is within γ |w′| θ²/2 of the true least distance.

use glam::DVec3;
use srt_physics::{Event, Frame};

/// A lower bound (≥ 0) of the apparent distance, seen from the observation event `observer`, of
/// every point of the convex hull of `points` (at rest in `frame`): see the module
/// documentation. 0 for no points.
#[must_use]
pub fn nearest_apparent_distance(frame: &Frame, points: &[DVec3], observer: Event) -> f64 {
    let origin = frame.to_rest(observer).position;
    let offsets: Vec<DVec3> = points.iter().map(|&p| p - origin).collect();
    if offsets.is_empty() {
        return 0.0;
    }
    let centroid = offsets.iter().sum::<DVec3>() / offsets.len() as f64;
    let beta = frame.beta();
    offsets
        .iter()
        .chain([&centroid])
        .filter_map(|w| w.try_normalize())
        .map(|u| {
            offsets
                .iter()
                .map(|&w| (u - beta).dot(w))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
        * frame.gamma()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use srt_physics::RestRay;

    /// The apparent distance of `point` (at rest in `frame`) seen from `observer`, through the
    /// backward ray that meets it (the definition the bound must stay below).
    fn apparent_distance(frame: &Frame, point: DVec3, observer: Event) -> f64 {
        let rest = frame.to_rest(observer);
        let offset = point - rest.position;
        let ray = RestRay {
            origin: rest.position,
            direction: offset.normalize(),
            ct_origin: rest.ct,
        };
        frame.apparent_distance(&ray, offset.length())
    }

    fn coordinate() -> impl Strategy<Value = f64> {
        -20.0..20.0f64
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn velocity() -> impl Strategy<Value = DVec3> {
        (point(), 0.0..0.995f64).prop_map(|(d, speed)| d.normalize_or(DVec3::X) * speed)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// No point of the triangle (corners, edges, inside) is seen nearer than the bound.
        #[test]
        fn no_point_of_a_triangle_is_nearer_than_the_bound(
            corners in [point(), point(), point()],
            beta in velocity(),
            offset in point(),
            ct in -10.0..10.0f64,
            weights in proptest::collection::vec((0.0..1.0f64, 0.0..1.0f64), 32),
        ) {
            let frame = Frame::new(beta, offset).unwrap();
            let observer = Event::new(ct, DVec3::ZERO);
            let bound = nearest_apparent_distance(&frame, &corners, observer);
            prop_assert!(bound >= 0.0);
            let mut samples: Vec<DVec3> = corners.to_vec();
            samples.extend(weights.iter().map(|&(a, b)| {
                let (a, b) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
                corners[0] + a * (corners[1] - corners[0]) + b * (corners[2] - corners[0])
            }));
            for p in samples {
                let r = apparent_distance(&frame, p, observer);
                prop_assert!(bound <= r * (1.0 + 1e-12) + 1e-12, "bound {bound} > {r} at {p}");
            }
        }

        /// A triangle seen under a small angle is bounded within γ|w′|θ²/2 of its nearest
        /// corner (the bound is tight where the GPU needs it: small, far triangles).
        #[test]
        fn a_small_far_triangle_is_bounded_tightly(
            centre in point(),
            corners in [point(), point(), point()],
            beta in velocity(),
        ) {
            let frame = Frame::new(beta, DVec3::ZERO).unwrap();
            let observer = Event::new(0.0, DVec3::ZERO);
            let origin = frame.to_rest(observer).position;
            // A triangle 10⁻³ of the way to `centre`, moved 50 further off.
            let far = origin + (centre - origin).normalize_or(DVec3::Y) * 50.0;
            let triangle = corners.map(|c| far + c * 1e-3 / 20.0);
            let bound = nearest_apparent_distance(&frame, &triangle, observer);
            let nearest = triangle
                .iter()
                .map(|&p| apparent_distance(&frame, p, observer))
                .fold(f64::INFINITY, f64::min);
            let theta = 2e-3 * 3f64.sqrt() / 50.0;
            prop_assert!(bound <= nearest * (1.0 + 1e-12));
            prop_assert!(
                nearest - bound <= frame.gamma() * 51.0 * theta * theta,
                "bound {bound}, nearest corner {nearest}"
            );
        }
    }

    #[test]
    fn the_observer_inside_the_hull_gets_zero() {
        let frame = Frame::new(DVec3::new(0.5, 0.0, 0.0), DVec3::ZERO).unwrap();
        let observer = Event::new(0.0, DVec3::ZERO);
        let cube: Vec<DVec3> = (0..8)
            .map(|k| {
                DVec3::new(
                    f64::from(k & 1) * 2.0 - 1.0,
                    f64::from(k >> 1 & 1) * 2.0 - 1.0,
                    f64::from(k >> 2 & 1) * 2.0 - 1.0,
                )
            })
            .collect();
        assert_eq!(nearest_apparent_distance(&frame, &cube, observer), 0.0);
        assert_eq!(nearest_apparent_distance(&frame, &[], observer), 0.0);
    }

    #[test]
    fn a_point_is_bounded_by_its_own_distance() {
        let frame = Frame::new(DVec3::new(0.0, 0.9, 0.0), DVec3::new(1.0, 2.0, 3.0)).unwrap();
        let observer = Event::new(4.0, DVec3::new(-1.0, 0.5, 0.0));
        let p = DVec3::new(3.0, -2.0, 7.0);
        let bound = nearest_apparent_distance(&frame, &[p], observer);
        approx::assert_relative_eq!(
            bound,
            apparent_distance(&frame, p, observer),
            max_relative = 1e-12
        );
    }
}
