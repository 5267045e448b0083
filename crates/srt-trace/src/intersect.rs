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

/// Whether the ray at the origin of the sheared frame passes through the triangle of sheared
/// corners `a`, `b`, `c`: the watertight test's decision from its exact edge functions.
fn passes_through_sheared([a, b, c]: [DVec2; 3]) -> bool {
    let (u, v, w) = (
        edge_function(b, c),
        edge_function(c, a),
        edge_function(a, b),
    );
    let mixed = (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0);
    !mixed && u + v + w != 0.0
}

/// The sign of the edge function p.x·q.y − p.y·q.x (`true`: positive) from its plain value
/// fl(fl(p.x·q.y) − fl(p.y·q.x)), `None` where that is 0 (or NaN). Rounding is monotone:
/// p.x·q.y > p.y·q.x gives fl(p.x·q.y) ≥ fl(p.y·q.x), and a difference of floats rounds to a
/// value of its own sign, so a plain value that is not 0 has the exact value's sign — the sign
/// [`edge_function`] gives. Only where the two products round to one value is the exact
/// difference needed.
#[inline]
fn plain_edge_sign(p: DVec2, q: DVec2) -> Option<bool> {
    let value = p.x * q.y - p.y * q.x;
    if value > 0.0 {
        Some(true)
    } else if value < 0.0 {
        Some(false)
    } else {
        None
    }
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
        let [a, b, c] = self.sheared(corners);
        // Mostly the plain products decide: where no edge function's plain value is 0, their
        // signs are the exact values' ([`plain_edge_sign`]), and so is the answer; only where
        // a plain value is 0 (the ray through an edge or corner, to rounding, or a degenerate
        // triangle) is the exact test needed.
        let signs = [(b, c), (c, a), (a, b)].map(|(p, q)| plain_edge_sign(p, q));
        if let [Some(u), Some(v), Some(w)] = signs {
            return u == v && v == w;
        }
        passes_through_sheared([a, b, c])
    }

    /// The triangle's corners relative to the origin in the ray's sheared frame (the ray along
    /// its kz axis): x and y.
    #[inline]
    fn sheared(&self, corners: &[DVec3; 3]) -> [DVec2; 3] {
        let [kx, ky, kz] = self.axes;
        corners.map(|corner| {
            let a = corner - self.origin;
            DVec2::new(a[kx] - self.shear.x * a[kz], a[ky] - self.shear.y * a[kz])
        })
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
/// faces): the watertight test of the ray set up for this one triangle, then [`plane_hit`].
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

    /// The plain products' quick decision is the exact test's: on rays through triangles'
    /// corners, through points of their edges, just beside them and anywhere, of triangles
    /// large, tiny, far and degenerate; and a quick sign, where given, is the exact one, also
    /// on points nearly in line with the origin (where about one plain value in twelve is 0
    /// though the exact one is not).
    #[test]
    fn the_quick_decision_is_the_exact_ones() {
        // A small deterministic generator (xorshift), so that the test sees the same rays on
        // every machine.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1_u64 << 53) as f64 * 2.0 - 1.0
        };
        let (mut quick, mut near) = (0, 0);
        for case in 0..20_000 {
            let scale = [1.0, 1e-6, 1e6][case % 3];
            let centre = DVec3::new(next(), next(), next()) * [0.0, 10.0, 1e5][case / 3 % 3];
            let mut corners = [0; 3].map(|_| centre + scale * DVec3::new(next(), next(), next()));
            if case % 7 == 0 {
                corners[2] = corners[0] + 0.5 * (corners[1] - corners[0]);
            }
            let origin = centre + DVec3::new(next(), next(), next()) * scale * 5.0;
            let (s, t) = (next().abs(), next().abs());
            let target = match case % 4 {
                0 => corners[case / 4 % 3],
                1 => corners[0] + s * (corners[1] - corners[0]),
                2 => corners[1] + s * (corners[2] - corners[1]) + 1e-15 * scale * DVec3::X,
                _ => corners[0] + s * (corners[1] - corners[0]) + t * (corners[2] - corners[0]),
            };
            let ray = ShearedRay::new(origin, target - origin);
            let exact = passes_through_sheared(ray.sheared(&corners));
            assert_eq!(ray.passes_through(&corners), exact, "case {case}");
            let [a, b, c] = ray.sheared(&corners);
            let mut decided = true;
            for (p, q) in [(b, c), (c, a), (a, b)] {
                let exact = edge_function(p, q);
                match plain_edge_sign(p, q) {
                    Some(positive) => assert!(
                        exact != 0.0 && positive == (exact > 0.0),
                        "case {case}: quick sign {positive} of an edge function of {exact:e}"
                    ),
                    None => decided = false,
                }
            }
            (quick, near) = if decided {
                (quick + 1, near)
            } else {
                (quick, near + 1)
            };
        }
        // Both ways are taken.
        assert!(
            quick > 5_000 && near > 2_000,
            "{quick} quick, {near} near an edge"
        );
        // Points nearly in line with the origin, whose edge function is a few ulps of its
        // products or less: where the quick sign is given, it is right.
        let mut given = 0;
        for _ in 0..100_000 {
            let p = DVec2::new(next(), next()) * 10_f64.powf(6.0 * next());
            let perpendicular = DVec2::new(-p.y, p.x) * 10_f64.powf(-14.0 - 3.0 * next().abs());
            let q = p * (3.0 * next()) + perpendicular;
            let exact = edge_function(p, q);
            if let Some(positive) = plain_edge_sign(p, q) {
                assert!(
                    exact != 0.0 && positive == (exact > 0.0),
                    "{p} {q}: {exact:e}"
                );
                given += 1;
            }
        }
        assert!(given > 10_000, "the quick sign was given {given} times");
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
