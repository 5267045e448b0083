//! Ray–triangle intersection in the rest frame S′ (Eq. 15–16).

use glam::{DVec2, DVec3};

/// Where a ray meets a triangle: x′ = x′₁ + ζ(x′₂ − x′₁) + ξ(x′₃ − x′₁) = origin + ψ·direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleHit {
    /// Distance ψ along the (unit) ray direction.
    pub distance: f64,
    /// Barycentric weight ζ of the second corner.
    pub zeta: f64,
    /// Barycentric weight ξ of the third corner.
    pub xi: f64,
}

impl TriangleHit {
    /// The three barycentric weights (1 − ζ − ξ, ζ, ξ).
    #[must_use]
    pub fn weights(&self) -> [f64; 3] {
        [1.0 - self.zeta - self.xi, self.zeta, self.xi]
    }
}

/// Solves Eq. 16, A·(ζ, ξ, ψ)ᵀ = b with A = (σ τ −d′) and b = x′_obs − x′₁, by Cramer's rule:
/// where the line `origin + ψ·direction` meets the plane of the triangle, inside or not.
///
/// Unlike the paper, the span vectors σ = x′₂ − x′₁ and τ = x′₃ − x′₁ are *not* normalised, so
/// that ζ and ξ are barycentric coordinates, as its normal interpolation (§4.2) requires.
/// `None` for lines parallel to the plane and degenerate triangles.
#[must_use]
pub fn plane_hit(origin: DVec3, direction: DVec3, corners: [DVec3; 3]) -> Option<TriangleHit> {
    let sigma = corners[1] - corners[0];
    let tau = corners[2] - corners[0];
    let b = origin - corners[0];
    // det(σ, τ, −d) = −d · (σ × τ) = σ · (d × τ)
    let p = direction.cross(tau);
    let det = sigma.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let q = b.cross(sigma);
    Some(TriangleHit {
        distance: tau.dot(q) / det,
        zeta: b.dot(p) / det,
        xi: direction.dot(q) / det,
    })
}

/// a·b − c·d to within about an ulp of the exact value (Kahan's difference of products with a
/// fused multiply-add), so that its sign is right wherever the exact value is not 0.
fn difference_of_products(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let w = c * d;
    let e = (-c).mul_add(d, w);
    let f = a.mul_add(b, -w);
    f + e
}

/// The edge function of the directed edge p → q of points in the ray's sheared frame (the ray
/// at their origin): p.x·q.y − p.y·q.x, evaluated on the two points in one order whichever way
/// round they are given, so that two triangles sharing the edge get exactly opposite values.
fn edge_function(p: DVec2, q: DVec2) -> f64 {
    let swapped = q.x < p.x || (q.x == p.x && q.y < p.y);
    let (first, second) = if swapped { (q, p) } else { (p, q) };
    let e = difference_of_products(first.x, second.y, first.y, second.x);
    if swapped { -e } else { e }
}

/// A ray set up for Woop, Benthin and Wald's watertight test (JCGT 2(1), 2013): its origin and
/// direction, the axis its direction is largest along (kz) and the two others, and the shear
/// that takes its direction to that axis. Made once per ray, used for every triangle it meets.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ShearedRay {
    origin: DVec3,
    direction: DVec3,
    axes: [usize; 3],
    shear: DVec2,
}

impl ShearedRay {
    /// The ray from `origin` along `direction`.
    #[inline]
    pub(crate) fn new(origin: DVec3, direction: DVec3) -> Self {
        let size = direction.abs();
        let kz = if size.x > size.y && size.x > size.z {
            0
        } else if size.y > size.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        Self {
            origin,
            direction,
            axes: [kx, ky, kz],
            shear: DVec2::new(direction[kx], direction[ky]) / direction[kz],
        }
    }

    /// Whether the ray passes through the triangle, edges and corners included: the
    /// watertight test, whose edge functions two triangles sharing an edge evaluate alike, so
    /// that a ray through a shared edge or corner of a closed mesh meets at least one of them.
    /// GPU twin: shaders/triangle.wgsl.
    #[inline]
    fn passes_through(&self, corners: &[DVec3; 3]) -> bool {
        let [kx, ky, kz] = self.axes;
        let sheared = |corner: DVec3| {
            let a = corner - self.origin;
            DVec2::new(a[kx] - self.shear.x * a[kz], a[ky] - self.shear.y * a[kz])
        };
        let [a, b, c] = corners.map(sheared);
        let (u, v, w) = (
            edge_function(b, c),
            edge_function(c, a),
            edge_function(a, b),
        );
        let mixed = (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0);
        !mixed && u + v + w != 0.0
    }

    /// The hit of the ray at ψ > 0 with the triangle (edges included, both faces): where
    /// the watertight test finds the ray through the triangle, [`plane_hit`]'s distance and
    /// barycentrics, ahead of the origin.
    #[inline]
    pub(crate) fn intersect(&self, corners: &[DVec3; 3]) -> Option<TriangleHit> {
        if !self.passes_through(corners) {
            return None;
        }
        plane_hit(self.origin, self.direction, *corners).filter(|h| h.distance > 0.0)
    }
}

/// The hit of the ray `origin + ψ·direction`, ψ > 0, with the triangle (edges included, both
/// faces): [`ShearedRay::intersect`] of the ray made for this one triangle.
#[must_use]
pub fn intersect_triangle(
    origin: DVec3,
    direction: DVec3,
    corners: [DVec3; 3],
) -> Option<TriangleHit> {
    ShearedRay::new(origin, direction).intersect(&corners)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const TRI: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    #[test]
    fn hits_inside_and_reports_barycentrics() {
        let hit = intersect_triangle(DVec3::new(0.25, 0.5, 2.0), -DVec3::Z, TRI).unwrap();
        assert_relative_eq!(hit.distance, 2.0);
        assert_relative_eq!(hit.zeta, 0.25);
        assert_relative_eq!(hit.xi, 0.5);
        // From behind, too.
        assert!(intersect_triangle(DVec3::new(0.25, 0.5, -2.0), DVec3::Z, TRI).is_some());
    }

    #[test]
    fn misses_outside_behind_and_parallel() {
        assert!(intersect_triangle(DVec3::new(0.8, 0.8, 1.0), -DVec3::Z, TRI).is_none());
        assert!(intersect_triangle(DVec3::new(0.2, 0.2, 1.0), DVec3::Z, TRI).is_none());
        assert!(intersect_triangle(DVec3::new(0.2, 0.2, 1.0), DVec3::X, TRI).is_none());
        let degenerate = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
        assert!(intersect_triangle(DVec3::new(0.5, 0.0, 1.0), -DVec3::Z, degenerate).is_none());
    }
}
