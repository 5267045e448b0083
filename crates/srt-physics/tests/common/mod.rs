//! Proptest strategies shared by the srt-physics property tests.

use glam::DVec3;
use proptest::prelude::*;
use srt_physics::Event;

/// A velocity with |β| ≤ `max_speed`, drawn uniformly in direction and speed.
pub fn velocity(max_speed: f64) -> impl Strategy<Value = DVec3> {
    (unit_vector(), 0.0..max_speed).prop_map(|(n, s)| n * s)
}

/// A unit vector (rejecting near-zero draws before normalising).
pub fn unit_vector() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("not too short", |(x, y, z)| x * x + y * y + z * z > 1e-2)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
}

/// A point in the cube of half-width `range`.
pub fn point(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// An event with time and coordinates within ±`range`.
pub fn event(range: f64) -> impl Strategy<Value = Event> {
    (-range..range, point(range)).prop_map(|(ct, p)| Event::new(ct, p))
}
