//! Objects that spin or thrust in their rest frame (srt-physics `motion`): where a backward
//! light ray meets the moving body, and the local rest frame a surface point is shaded in.
//!
//! In the object's rest coordinates the backward ray is the straight null line
//! x(s) = o + s·d at S′ time ct′(s) = ct′_o − s. The body point found on it at each s,
//! b(s) = `Motion::body_point`, is a curve in body space (a helix for spin, a hyperbola-bent
//! line during a thrust) met with the body's static mesh and BVH:
//! - **spin**: the curve is cut into pieces of at most 0.05 rad of rotation within the ball the
//!   body sweeps; each piece is bounded by the box of its chord padded by the curve's largest
//!   sagitta, (2|ω| + ω²R)·Δs²/8 (|b″| ≤ 2|ω|·|d| + ω²·R); the BVH gives the triangles whose
//!   boxes meet it, and on each the signed distance of b(s) to the triangle's plane is bracketed
//!   and bisected to the f64 limit;
//! - **thrust**: before the start (s ≥ s₁) and after the end (s ≤ s₂, coasting: the body is at
//!   rest in its final frame) the curve is a straight line, met by the exact BVH ray test; in
//!   between it is marched in pieces as above, each padded by four times its midpoint's
//!   deviation from the chord.
//!
//! The nearest crossing wins. A piece crossing one triangle's plane twice (a tangential graze
//! within one piece) is missed; the pieces keep that to grazing incidence.

use bvh::aabb::Aabb;
use glam::{DMat4, DVec3, DVec4};
use nalgebra::Point3;
use srt_physics::motion::{Motion, Spin, Thrust};
use srt_physics::{RestRay, lorentz_matrix};

use crate::intersect::TriangleHit;
use crate::render::PreparedObject;

/// Most rotation of a spinning body per piece of a curved ray, in radians.
const SPIN_PIECE_ANGLE: f64 = 0.05;
/// Pieces of a thrusting body's curved stretch of ray per its size.
const THRUST_PIECES_PER_SIZE: f64 = 48.0;
/// Most pieces of one curved stretch of ray.
const MAX_PIECES: usize = 1 << 16;

/// A triangle's crossing on a curved ray: (part, triangle, hit at ray parameter s).
pub(crate) type Crossing = (u32, u32, TriangleHit);

impl PreparedObject<'_> {
    /// The nearest crossing of the backward ray `ray` (in the object's rest coordinates) with
    /// the moving body, no farther than `limit`; `shift` is the rest coordinates' clock lead
    /// over the object's S′ time.
    pub(crate) fn closest_hit_moving(
        &self,
        ray: &RestRay,
        shift: f64,
        limit: f64,
    ) -> Option<Crossing> {
        match self.motion {
            Motion::Rest => self.closest_hit_between(ray, 0.0, limit),
            Motion::Spin(spin) => self.spin_hit(&spin, ray, shift, limit),
            Motion::Thrust(thrust) => self.thrust_hit(&thrust, ray, shift, limit),
        }
    }

    /// A spinning body: march the helix within the ball it sweeps.
    fn spin_hit(&self, spin: &Spin, ray: &RestRay, shift: f64, limit: f64) -> Option<Crossing> {
        let radius = self.reach;
        let to_origin = ray.origin - spin.centre();
        let half = to_origin.dot(ray.direction);
        let discriminant = half * half - (to_origin.length_squared() - radius * radius);
        if discriminant < 0.0 {
            return None;
        }
        let root = discriminant.sqrt();
        let (mut from, mut to) = ((-half - root).max(0.0), (-half + root).min(limit));
        // The rotation keeps every point's height along the axis: the ray meets the body only
        // within the slab of its heights.
        let (low, high) = self.axial;
        let pad = 1e-12 * (1.0 + radius);
        let height = to_origin.dot(spin.axis());
        let climb = ray.direction.dot(spin.axis());
        if climb == 0.0 {
            if height < low - pad || height > high + pad {
                return None;
            }
        } else {
            let (a, b) = ((low - pad - height) / climb, (high + pad - height) / climb);
            from = from.max(a.min(b));
            to = to.min(a.max(b));
        }
        if from > to {
            return None;
        }
        let omega = spin.rate().abs();
        let pieces = if omega > 0.0 {
            ((to - from) * omega / SPIN_PIECE_ANGLE)
                .ceil()
                .clamp(1.0, MAX_PIECES as f64)
        } else {
            1.0
        };
        let step = (to - from) / pieces;
        let pad = (2.0 * omega + omega * omega * radius) * step * step / 8.0;
        let curve =
            |s: f64| Some(spin.body_point(ray.origin + s * ray.direction, ct_at(ray, shift, s)));
        self.march(&curve, from, to, pieces as usize, |_, _, _| pad)
    }

    /// A thrusting body: coasting (a straight line in body space), accelerating (marched),
    /// before the start (the ray itself), nearest first.
    fn thrust_hit(
        &self,
        thrust: &Thrust,
        ray: &RestRay,
        shift: f64,
        limit: f64,
    ) -> Option<Crossing> {
        let (direction, alpha, end) = (thrust.direction(), thrust.alpha(), thrust.final_rapidity());
        // v(s) = ct′(s) − ct₀ = s₁ − s; u(s) = x_∥(s) + 1/α.
        let start = ct_at(ray, shift, 0.0) - thrust.start();
        let u0 = ray.origin.dot(direction) + 1.0 / alpha;
        let along = ray.direction.dot(direction);
        // The end hyperplane v·cosh η_e = u·sinh η_e, crossed at s₂ (none without an end).
        let end_at = if end.is_finite() {
            let (c, s) = (end.cosh(), end.sinh());
            (start * c - u0 * s) / (c + along * s)
        } else {
            f64::NEG_INFINITY
        };
        if end_at > 0.0 {
            // Coasting: b(s) = x⊥(s) + (u(s)·cosh η_e − v(s)·sinh η_e − 1/α)·â, linear in s.
            let (c, s) = (end.cosh(), end.sinh());
            let body = |s_ray: f64| {
                let x = ray.origin + s_ray * ray.direction;
                let u = x.dot(direction) + 1.0 / alpha;
                let v = start - s_ray;
                x - x.dot(direction) * direction + (u * c - v * s - 1.0 / alpha) * direction
            };
            let (origin, slope) = (body(0.0), body(1.0) - body(0.0));
            let speed = slope.length();
            let line = RestRay {
                origin,
                direction: slope / speed,
                ct_origin: ray.ct_origin,
            };
            if let Some((part, triangle, mut hit)) =
                self.closest_hit_between(&line, 0.0, end_at.min(limit) * speed)
            {
                hit.distance /= speed;
                return Some((part, triangle, hit));
            }
        }
        let (from, to) = (end_at.max(0.0), start.min(limit));
        // Every point has moved at most v = ct′ − ct₀ along â by S′ time ct′ (its speed is
        // below 1): the ray can only meet the body during the thrust inside the body's box
        // swept that far along â.
        let reach = (start - from).max(0.0);
        let (mut lo, mut hi) = self.bounds;
        let sweep = reach * direction;
        lo = lo.min(lo + sweep);
        hi = hi.max(hi + sweep);
        if from < to && slab(ray, lo, hi).is_some_and(|(near, far)| near <= to && far >= from) {
            let curve =
                |s: f64| thrust.body_point(ct_at(ray, shift, s), ray.origin + s * ray.direction);
            let size = self.reach.max(1e-9);
            let length = (0..=64)
                .filter_map(|k| curve(from + (to - from) * f64::from(k) / 64.0))
                .collect::<Vec<_>>()
                .windows(2)
                .map(|w| (w[1] - w[0]).length())
                .sum::<f64>();
            let pieces = (length / size * THRUST_PIECES_PER_SIZE)
                .ceil()
                .clamp(16.0, MAX_PIECES as f64);
            let found = self.march(&curve, from, to, pieces as usize, |a, m, b| {
                4.0 * (m - 0.5 * (a + b)).length()
            });
            if found.is_some() {
                return found;
            }
        }
        // Before the start the body rests where it was built: the ray itself.
        self.closest_hit_between(ray, start.max(0.0), limit)
    }

    /// The nearest crossing of the body-space curve `curve` (defined where it returns `Some`)
    /// with the body's triangles for s in [`from`, `to`], cut into `pieces` pieces, each
    /// bounded by its chord's box padded by `pad(start, middle, end)`.
    fn march(
        &self,
        curve: &dyn Fn(f64) -> Option<DVec3>,
        from: f64,
        to: f64,
        pieces: usize,
        pad: impl Fn(DVec3, DVec3, DVec3) -> f64,
    ) -> Option<Crossing> {
        let bvh = self.bvh.as_ref()?;
        let at = |k: usize| from + (to - from) * (k as f64) / (pieces as f64);
        let mut previous = (at(0), curve(at(0)));
        for k in 1..=pieces {
            let next = (at(k), curve(at(k)));
            let ((a, pa), (b, pb)) = (previous, next);
            previous = next;
            let (Some(pa), Some(pb)) = (pa, pb) else {
                continue;
            };
            let Some(middle) = curve(0.5 * (a + b)) else {
                continue;
            };
            let margin = pad(pa, middle, pb) + 1e-12 * (1.0 + pa.abs().max_element());
            let (lo, hi) = (pa.min(pb) - margin, pa.max(pb) + margin);
            let query =
                Aabb::with_bounds(Point3::new(lo.x, lo.y, lo.z), Point3::new(hi.x, hi.y, hi.z));
            let mut best: Option<Crossing> = None;
            for leaf in bvh.traverse_iterator(&query, &self.boxes) {
                let mesh = &self.parts[leaf.part as usize].part.mesh;
                let corners = mesh.triangle_positions(leaf.triangle as usize);
                let Some(hit) = crossing(curve, a, b, corners) else {
                    continue;
                };
                let closer = best.is_none_or(|(part, triangle, h)| {
                    (hit.distance, leaf.part, leaf.triangle) < (h.distance, part, triangle)
                });
                if closer {
                    best = Some((leaf.part, leaf.triangle, hit));
                }
            }
            if best.is_some() {
                return best;
            }
        }
        None
    }
}

/// The ray parameters (near, far) between which the whole line `ray` is inside the box
/// [`lo`, `hi`], if it meets it (far taken a little late; NaN from a parallel direction on a
/// slab's plane counts as meeting).
fn slab(ray: &RestRay, lo: DVec3, hi: DVec3) -> Option<(f64, f64)> {
    let inverse = ray.direction.recip();
    let (a, b) = ((lo - ray.origin) * inverse, (hi - ray.origin) * inverse);
    let near = a.min(b).max_element();
    let far = a.max(b).min_element() * (1.0 + 1e-12) + 1e-12;
    (near <= far || near.is_nan() || far.is_nan()).then_some((near, far))
}

/// The object's S′ time at ray parameter `s`.
fn ct_at(ray: &RestRay, shift: f64, s: f64) -> f64 {
    ray.ct_origin - s - shift
}

/// Where `curve` crosses the triangle `corners` for s in [`a`, `b`]: the sign change of the
/// signed distance to its plane, bisected to the f64 limit, if the point is in the triangle
/// (edges included).
fn crossing(
    curve: &dyn Fn(f64) -> Option<DVec3>,
    a: f64,
    b: f64,
    corners: [DVec3; 3],
) -> Option<TriangleHit> {
    let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    let height = |s: f64| curve(s).map(|p| normal.dot(p - corners[0]));
    let (mut lo, mut hi) = (a, b);
    let (mut at_lo, at_hi) = (height(lo)?, height(hi)?);
    if at_lo * at_hi > 0.0 {
        return None;
    }
    if at_lo != 0.0 {
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let at_mid = height(mid)?;
            if (at_mid < 0.0) == (at_lo < 0.0) && at_mid != 0.0 {
                lo = mid;
                at_lo = at_mid;
            } else {
                hi = mid;
            }
        }
    } else {
        hi = lo;
    }
    let distance = if at_lo == 0.0 { lo } else { hi };
    let point = curve(distance)?;
    let (zeta, xi) = barycentric(point, corners)?;
    Some(TriangleHit { distance, zeta, xi })
}

/// The barycentric weights (ζ of corner 1, ξ of corner 2) of `point` projected on the
/// triangle's plane, if it lies within the triangle (edges included).
fn barycentric(point: DVec3, corners: [DVec3; 3]) -> Option<(f64, f64)> {
    let (e1, e2, v) = (
        corners[1] - corners[0],
        corners[2] - corners[0],
        point - corners[0],
    );
    let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d20, d21) = (v.dot(e1), v.dot(e2));
    let denominator = d00 * d11 - d01 * d01;
    if denominator <= 0.0 {
        return None;
    }
    let zeta = (d11 * d20 - d01 * d21) / denominator;
    let xi = (d00 * d21 - d01 * d20) / denominator;
    (zeta >= 0.0 && xi >= 0.0 && zeta + xi <= 1.0).then_some((zeta, xi))
}

/// The local rest frame a surface point of a moving body is shaded in: the velocity of that
/// frame relative to S and the surface normal in it (a pure boost from S, as
/// `srt_trace::shade` expects). `frame_beta` is the object frame's velocity, `velocity` the
/// point's velocity in that frame (units of c) and `normal` its normal 4-vector there (time and
/// space parts, orthogonal to the point's four-velocity).
pub(crate) fn local_rest_frame(
    frame_beta: DVec3,
    velocity: DVec3,
    normal: DVec4,
) -> (DVec3, DVec3) {
    let to_observer: DMat4 = lorentz_matrix(frame_beta);
    let gamma = 1.0 / (1.0 - velocity.length_squared()).sqrt();
    let four_velocity = to_observer
        * DVec4::new(
            gamma,
            gamma * velocity.x,
            gamma * velocity.y,
            gamma * velocity.z,
        );
    let beta = DVec3::new(four_velocity.y, four_velocity.z, four_velocity.w) / four_velocity.x;
    let normal_s = to_observer * normal;
    let local = lorentz_matrix(-beta) * normal_s;
    (beta, DVec3::new(local.y, local.z, local.w).normalize())
}

/// The normal four-vector (in the object frame's rest coordinates) of the surface of a body in
/// `motion` at body point `body`, S′ time `ct`, whose body-space normal is `normal`:
/// spin — the rotated normal n and time part n·u (orthogonal to the four-velocity γ(1, u));
/// thrust — the body normal in the momentarily comoving frame, where the body has its rest
/// shape, boosted into S′.
pub(crate) fn moving_normal(motion: &Motion, body: DVec3, ct: f64, normal: DVec3) -> DVec4 {
    match motion {
        Motion::Rest => DVec4::new(0.0, normal.x, normal.y, normal.z),
        Motion::Spin(spin) => {
            let n = spin.rotation(ct) * normal;
            let u = spin.velocity_at(spin.position(body, ct));
            DVec4::new(n.dot(u), n.x, n.y, n.z)
        }
        Motion::Thrust(thrust) => {
            lorentz_matrix(thrust.velocity(body, ct))
                * DVec4::new(0.0, normal.x, normal.y, normal.z)
        }
    }
}
