//! Convex hull of a few 2D points (Andrew's monotone chain) and point-in-convex-polygon tests.

use glam::DVec2;

/// z-component of (b − a) × (c − a): positive when a → b → c turns counter-clockwise.
fn turn(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Writes the convex hull of `points` (at most 6) into `out`, counter-clockwise (in a y-up
/// reading of the coordinates), without collinear points, and returns how many it wrote.
///
/// Non-finite points are not expected (callers check); duplicates are fine. Returns fewer than
/// three points only when all points are collinear.
///
/// # Panics
/// If `points` has more than 6 entries.
pub fn convex_hull(points: &[DVec2], out: &mut [DVec2; 6]) -> usize {
    assert!(points.len() <= 6, "convex_hull handles at most 6 points");
    let mut sorted = [DVec2::ZERO; 6];
    let n = points.len();
    sorted[..n].copy_from_slice(points);
    let sorted = &mut sorted[..n];
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    // Lower and upper chains share a scratch buffer of 2n points.
    let mut chain = [DVec2::ZERO; 12];
    let mut k = 0;
    for &p in sorted.iter() {
        while k >= 2 && turn(chain[k - 2], chain[k - 1], p) <= 0.0 {
            k -= 1;
        }
        chain[k] = p;
        k += 1;
    }
    let lower = k + 1;
    for &p in sorted.iter().rev().skip(1) {
        while k >= lower && turn(chain[k - 2], chain[k - 1], p) <= 0.0 {
            k -= 1;
        }
        chain[k] = p;
        k += 1;
    }
    // The last point repeats the first.
    let len = k.saturating_sub(1).min(6);
    out[..len].copy_from_slice(&chain[..len]);
    len
}

/// Whether `p` lies inside the convex polygon `hull` (counter-clockwise, as from
/// [`convex_hull`]), allowing `tolerance` (same units) outside it. A two-point hull is a segment.
#[must_use]
pub fn contains(hull: &[DVec2], p: DVec2, tolerance: f64) -> bool {
    match hull {
        [] => false,
        [a] => (p - *a).length() <= tolerance,
        [a, b] => distance_to_segment(p, *a, *b) <= tolerance,
        _ => (0..hull.len()).all(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            let edge = b - a;
            // Signed distance to the left of the edge; the inside is on the left for CCW order.
            edge.perp_dot(p - a) >= -tolerance * edge.length()
        }),
    }
}

/// Euclidean distance from `p` to the segment `a`–`b`.
fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let edge = b - a;
    let t = ((p - a).dot(edge) / edge.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
    (a + t * edge - p).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_square_with_inner_points() {
        let pts = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 0.5),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.5, 0.0),
        ];
        let mut out = [DVec2::ZERO; 6];
        let n = convex_hull(&pts, &mut out);
        assert_eq!(n, 4);
        assert!(contains(&out[..n], DVec2::new(0.5, 0.5), 0.0));
        assert!(contains(&out[..n], DVec2::new(1.0, 0.5), 1e-12));
        assert!(!contains(&out[..n], DVec2::new(1.1, 0.5), 1e-3));
        // Counter-clockwise: positive signed area.
        let area: f64 = (0..n).map(|i| out[i].perp_dot(out[(i + 1) % n])).sum();
        assert!(area > 0.0);
    }

    #[test]
    fn collinear_points_give_a_segment() {
        let pts = [DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 2.0)];
        let mut out = [DVec2::ZERO; 6];
        assert_eq!(convex_hull(&pts, &mut out), 2);
        assert!(contains(&out[..2], DVec2::new(1.5, 1.5), 1e-9));
        assert!(!contains(&out[..2], DVec2::new(1.5, 1.0), 1e-3));
    }
}
