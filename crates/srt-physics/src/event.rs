//! Events (points in spacetime) and the Minkowski interval.

use glam::{DVec3, DVec4};

/// A point in spacetime, (ct, x, y, z) in some frame (c = 1 units, so `ct` is a length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// Time coordinate multiplied by the speed of light.
    pub ct: f64,
    /// Spatial coordinates.
    pub position: DVec3,
}

impl Event {
    /// An event at time `ct` and place `position`.
    #[must_use]
    pub const fn new(ct: f64, position: DVec3) -> Self {
        Self { ct, position }
    }

    /// The event as a four-vector column (ct, x, y, z), stored in a `DVec4` as (x, y, z, w).
    #[must_use]
    pub const fn to_four_vector(self) -> DVec4 {
        DVec4::new(self.ct, self.position.x, self.position.y, self.position.z)
    }

    /// The event whose four-vector column is (ct, x, y, z) = (v.x, v.y, v.z, v.w).
    #[must_use]
    pub const fn from_four_vector(v: DVec4) -> Self {
        Self {
            ct: v.x,
            position: DVec3::new(v.y, v.z, v.w),
        }
    }

    /// Whether every coordinate is finite.
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.ct.is_finite() && self.position.is_finite()
    }
}

/// The Minkowski interval −(Δct)² + |Δx|² between two events, the left side of Eq. 6.
///
/// Zero for events joined by a light ray, negative for time-like, positive for space-like
/// separation. Invariant under every Lorentz and Poincaré transformation.
#[must_use]
pub fn minkowski_interval(a: Event, b: Event) -> f64 {
    let dt = a.ct - b.ct;
    -dt * dt + (a.position - b.position).length_squared()
}
