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
//!   between it is a hyperbola arc in a plane ([`ThrustArc`]): b(s) = x(s) + (X(s) − u(s))·â with
//!   X = √(u² − v²), so the signed distance to a triangle's plane is L(s) + (n·â)·X(s), L linear,
//!   and its zeros are the roots of a quadratic (squared, the spurious roots dropped by sign,
//!   then polished by Newton's method on the unsquared distance). Pieces serve only to take
//!   candidates from the BVH: each piece's box is exact (the arc lies in the parallelogram of
//!   its linear part and the range of X, which is concave), not an estimate.
//!
//! The nearest crossing wins. On a spinning body's piece a triangle's plane crossed twice (a
//! tangential graze within one piece) is missed; the pieces keep that to grazing incidence. A
//! thrust's crossings are all found.

use glam::{DVec3, DVec4};
use srt_physics::motion::{
    Motion, SPIN_PIECE_ANGLE, Spin, THRUST_NEWTON_STEPS, THRUST_PIECES_PER_SIZE, Thrust,
};
use srt_physics::{FourVelocity, RestRay};

use crate::intersect::TriangleHit;
use crate::prepared::PreparedObject;

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
        let helix = Helix {
            spin,
            ray,
            shift,
            pad,
        };
        self.march(&helix, from, to, pieces as usize)
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
        let arc = ThrustArc::new(thrust, ray, start);
        // The end hyperplane v·cosh η_e = u·sinh η_e, crossed at s₂ (none without an end).
        let end_at = if end.is_finite() {
            let (c, s) = (end.cosh(), end.sinh());
            (start * c - arc.u0 * s) / (c + arc.w * s)
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
        // Beyond the horizon (u ≤ v) no body point is met.
        let (from, to) = (end_at.max(0.0).max(arc.horizon()), start.min(limit));
        // Every point has moved at most v = ct′ − ct₀ along â by S′ time ct′ (its speed is
        // below 1): the ray can only meet the body during the thrust inside the body's box
        // swept that far along â.
        let reach = (start - from).max(0.0);
        let (mut lo, mut hi) = self.bounds;
        let sweep = reach * direction;
        lo = lo.min(lo + sweep);
        hi = hi.max(hi + sweep);
        // Only the stretch of the ray inside that box is searched.
        let inside = slab(ray, lo, hi)
            .map(|(near, far)| (from.max(near), to.min(far)))
            .filter(|&(a, b)| from < to && a <= b);
        if let Some((from, to)) = inside {
            let (whole_lo, whole_hi) = arc.piece_box(from, to);
            let extent = (whole_hi - whole_lo).length();
            let pieces = (extent / self.reach.max(1e-9) * THRUST_PIECES_PER_SIZE)
                .ceil()
                .clamp(1.0, MAX_PIECES as f64);
            let found = self.march(&arc, from, to, pieces as usize);
            if found.is_some() {
                return found;
            }
        }
        // Before the start the body rests where it was built: the ray itself.
        self.closest_hit_between(ray, start.max(0.0), limit)
    }

    /// The nearest crossing of the body-space curve `curve` with the body's triangles for s in
    /// [`from`, `to`], cut into `pieces` pieces met with the BVH one by one, nearest first.
    fn march(
        &self,
        curve: &impl MarchedCurve,
        from: f64,
        to: f64,
        pieces: usize,
    ) -> Option<Crossing> {
        let (bvh, triangles) = self.bvh.as_deref()?;
        let at = |k: usize| from + (to - from) * (k as f64) / (pieces as f64);
        let mut previous: Option<Piece> = None;
        for k in 1..=pieces {
            let piece = curve.piece(previous.as_ref(), at(k - 1), at(k));
            let (lo, hi) = (piece.lo, piece.hi);
            let mut best: Option<Crossing> = None;
            bvh.overlapping(lo, hi, |leaf| {
                let leaf = &triangles[leaf];
                let corners = leaf.corners;
                // The crossing is a point of the piece, in its box, and of the triangle, in
                // the triangle's box: where the two are apart there is none to look for.
                let (low, high) = (
                    corners[0].min(corners[1]).min(corners[2]),
                    corners[0].max(corners[1]).max(corners[2]),
                );
                if !(low.cmple(hi).all() && high.cmpge(lo).all()) {
                    return;
                }
                let Some(hit) = curve.crossing(&piece, corners) else {
                    return;
                };
                let closer = best.is_none_or(|(part, triangle, h)| {
                    (hit.distance, leaf.part, leaf.triangle) < (h.distance, part, triangle)
                });
                if closer {
                    best = Some((leaf.part, leaf.triangle, hit));
                }
            });
            if best.is_some() {
                return best;
            }
            previous = Some(piece);
        }
        None
    }
}

/// A moving body's curve b(s) in body space, as [`PreparedObject::march`] meets it piece by
/// piece.
trait MarchedCurve {
    /// The piece of the curve for s in [`a`, `b`], with a box that holds it; `previous` is the
    /// piece that ends at `a`, if any.
    fn piece(&self, previous: Option<&Piece>, a: f64, b: f64) -> Piece;
    /// The nearest crossing of the curve with the triangle `corners` on `piece`.
    fn crossing(&self, piece: &Piece, corners: [DVec3; 3]) -> Option<TriangleHit>;
}

/// One piece s ∈ [a, b] of a curve: the box [lo, hi] that holds it, and (a helix's) its points
/// at both ends.
struct Piece {
    a: f64,
    b: f64,
    lo: DVec3,
    hi: DVec3,
    begin: DVec3,
    end: DVec3,
}

/// A spinning body's curve (a helix about the axis): each piece bounded by its chord's box
/// padded by `pad`, the sagitta bound of a piece's length (see the module documentation).
struct Helix<'a> {
    spin: &'a Spin,
    ray: &'a RestRay,
    shift: f64,
    pad: f64,
}

impl Helix<'_> {
    /// The body point on the backward ray at parameter `s`.
    fn point(&self, s: f64) -> DVec3 {
        let ray = self.ray;
        self.spin
            .body_point(ray.origin + s * ray.direction, ct_at(ray, self.shift, s))
    }
}

impl MarchedCurve for Helix<'_> {
    fn piece(&self, previous: Option<&Piece>, a: f64, b: f64) -> Piece {
        let begin = previous.map_or_else(|| self.point(a), |piece| piece.end);
        let end = self.point(b);
        let margin = self.pad + 1e-12 * (1.0 + begin.abs().max_element());
        Piece {
            a,
            b,
            lo: begin.min(end) - margin,
            hi: begin.max(end) + margin,
            begin,
            end,
        }
    }

    /// The sign change of the signed distance to the triangle's plane over the piece,
    /// bisected to the f64 limit, if the point is in the triangle (edges included).
    fn crossing(&self, piece: &Piece, corners: [DVec3; 3]) -> Option<TriangleHit> {
        let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        let height = |p: DVec3| normal.dot(p - corners[0]);
        let (mut lo, mut hi) = (piece.a, piece.b);
        let (mut at_lo, at_hi) = (height(piece.begin), height(piece.end));
        if at_lo * at_hi > 0.0 {
            return None;
        }
        if at_lo != 0.0 {
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let at_mid = height(self.point(mid));
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
        let (zeta, xi) = barycentric(self.point(distance), corners)?;
        Some(TriangleHit { distance, zeta, xi })
    }
}

/// A thrusting body's curve while it accelerates: with u(s) = x(s)·â + 1/α = u₀ + w·s and
/// v(s) = ct′(s) − ct₀ = v₀ − s, the body point is b(s) = x(s) + (X(s) − u(s))·â, X = √(u² − v²)
/// (`Thrust::body_point` with x(s) = o + s·d), defined where u > v (this side of the horizon).
/// Its part x(s) − u(s)·â is linear in s and X is concave (u² − v² is a quadratic with leading
/// coefficient w² − 1 ≤ 0), so the arc is a plane convex curve.
#[derive(Debug, Clone, Copy)]
struct ThrustArc {
    /// The ray's origin o and unit direction d in the rest coordinates.
    origin: DVec3,
    direction: DVec3,
    /// The thrust's direction â.
    axis: DVec3,
    /// u₀ = o·â + 1/α, w = d·â, v₀ = ct′(0) − ct₀.
    u0: f64,
    w: f64,
    v0: f64,
}

impl ThrustArc {
    /// The arc of `ray` (whose S′ time at s = 0 is `start` after the thrust's start).
    fn new(thrust: &Thrust, ray: &RestRay, start: f64) -> Self {
        let axis = thrust.direction();
        Self {
            origin: ray.origin,
            direction: ray.direction,
            axis,
            u0: ray.origin.dot(axis) + 1.0 / thrust.alpha(),
            w: ray.direction.dot(axis),
            v0: start,
        }
    }

    /// u(s) − v(s), positive this side of the horizon.
    fn above_horizon(&self, s: f64) -> f64 {
        (self.u0 - self.v0) + (self.w + 1.0) * s
    }

    /// u(s)² − v(s)² = X(s)².
    fn rindler_square(&self, s: f64) -> f64 {
        self.above_horizon(s) * ((self.u0 + self.v0) + (self.w - 1.0) * s)
    }

    /// X(s), 0 at and beyond the horizon.
    fn rindler(&self, s: f64) -> f64 {
        self.rindler_square(s).max(0.0).sqrt()
    }

    /// The parameter where the ray reaches the horizon (u = v; u − v grows with s), −∞ where it
    /// is never below it, +∞ where it never leaves it.
    fn horizon(&self) -> f64 {
        if self.w > -1.0 {
            (self.v0 - self.u0) / (self.w + 1.0)
        } else if self.u0 > self.v0 {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        }
    }

    /// The linear part of b(s): x(s) − u(s)·â.
    fn linear_part(&self, s: f64) -> DVec3 {
        self.origin + s * self.direction - (self.u0 + self.w * s) * self.axis
    }

    /// The body point at `s` (this side of the horizon).
    fn point(&self, s: f64) -> DVec3 {
        self.linear_part(s) + self.rindler(s) * self.axis
    }

    /// The box of the parallelogram that holds the arc for s in [`a`, `b`]: its linear part's
    /// ends, each shifted along â by X's least and greatest values there (the ends, and the
    /// vertex of u² − v² where it lies between them).
    fn piece_box(&self, a: f64, b: f64) -> (DVec3, DVec3) {
        let (xa, xb) = (self.rindler(a), self.rindler(b));
        let mut high = xa.max(xb);
        let curvature = self.w * self.w - 1.0;
        if curvature < 0.0 {
            let vertex = (self.u0 * self.w + self.v0) / -curvature;
            if vertex > a && vertex < b {
                high = high.max(self.rindler(vertex));
            }
        }
        let low = xa.min(xb);
        let (la, lb) = (self.linear_part(a), self.linear_part(b));
        let corners = [
            la + low * self.axis,
            la + high * self.axis,
            lb + low * self.axis,
            lb + high * self.axis,
        ];
        let (lo, hi) = corners[1..]
            .iter()
            .fold((corners[0], corners[0]), |(lo, hi), &c| {
                (lo.min(c), hi.max(c))
            });
        let margin = 1e-12 * (1.0 + lo.abs().max(hi.abs()).max_element());
        (lo - margin, hi + margin)
    }
}

impl MarchedCurve for ThrustArc {
    fn piece(&self, _previous: Option<&Piece>, a: f64, b: f64) -> Piece {
        let (lo, hi) = self.piece_box(a, b);
        Piece {
            a,
            b,
            lo,
            hi,
            begin: DVec3::ZERO,
            end: DVec3::ZERO,
        }
    }

    /// The distance of b(s) to the triangle's plane, n·(b(s) − p₀) = L(s) + m·X(s) with
    /// m = n·â and L(s) = l₀ + l₁·s, vanishes where m²·X² = L² and −m·L ≥ 0: the roots of
    /// m²(u² − v²) − L² = 0, a quadratic, that keep the sign, each polished by Newton's method
    /// on L + m·X; the nearest in [a, b] this side of the horizon whose point lies in the
    /// triangle is the crossing.
    fn crossing(&self, piece: &Piece, corners: [DVec3; 3]) -> Option<TriangleHit> {
        let (a, b) = (piece.a, piece.b);
        let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        let m = normal.dot(self.axis);
        let l0 = normal.dot(self.origin - corners[0]) - m * self.u0;
        let l1 = normal.dot(self.direction) - m * self.w;
        let mut roots = if m == 0.0 {
            [(l1 != 0.0).then(|| -l0 / l1), None]
        } else {
            let mm = m * m;
            quadratic_roots(
                mm * (self.w * self.w - 1.0) - l1 * l1,
                2.0 * (mm * (self.u0 * self.w + self.v0) - l0 * l1),
                mm * (self.u0 - self.v0) * (self.u0 + self.v0) - l0 * l0,
            )
        };
        if let [Some(r0), Some(r1)] = roots
            && r1 < r0
        {
            roots = [Some(r1), Some(r0)];
        }
        roots.into_iter().flatten().find_map(|root| {
            // A root of the squared equation with m·X = +L is not a crossing.
            if !(root >= a && root <= b) || m * (l0 + l1 * root) > 0.0 {
                return None;
            }
            let mut s = root;
            for _ in 0..THRUST_NEWTON_STEPS {
                let x = self.rindler(s);
                let u = self.u0 + self.w * s;
                let slope = l1 + m * (u * self.w + (self.v0 - s)) / x;
                let next = s - (l0 + l1 * s + m * x) / slope;
                if !(x > 0.0 && next >= a && next <= b) {
                    break;
                }
                s = next;
            }
            if self.above_horizon(s) <= 0.0 {
                return None;
            }
            let (zeta, xi) = barycentric(self.point(s), corners)?;
            Some(TriangleHit {
                distance: s,
                zeta,
                xi,
            })
        })
    }
}

/// The real roots of a·s² + b·s + c (the linear root where a = 0), in the cancellation-free form.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if a == 0.0 {
        return [(b != 0.0).then(|| -c / b), None];
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + discriminant.sqrt().copysign(b));
    if q == 0.0 {
        return [Some(0.0), None];
    }
    [Some(q / a), Some(c / q)]
}

/// The ray parameters (near, far) between which the whole line `ray` is inside the box
/// [`lo`, `hi`], if it meets it (near taken a little early and far a little late, so that a
/// point on a face is not cut off by rounding; NaN from a parallel direction on a slab's plane
/// counts as meeting).
fn slab(ray: &RestRay, lo: DVec3, hi: DVec3) -> Option<(f64, f64)> {
    let inverse = ray.direction.recip();
    let (a, b) = ((lo - ray.origin) * inverse, (hi - ray.origin) * inverse);
    let near = a.min(b).max_element();
    // (An infinite near stays as it is: a parallel ray outside a slab meets nothing.)
    let near = if near.is_finite() {
        near - (near.abs() * 1e-12 + 1e-12)
    } else {
        near
    };
    let far = a.max(b).min_element() * (1.0 + 1e-12) + 1e-12;
    (near <= far || near.is_nan() || far.is_nan()).then_some((near, far))
}

/// The object's S′ time at ray parameter `s`.
fn ct_at(ray: &RestRay, shift: f64, s: f64) -> f64 {
    ray.ct_origin - s - shift
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
/// point's velocity in that frame and `normal` its normal 4-vector there (time and space
/// parts, orthogonal to the point's four-velocity).
///
/// Both are taken without going through β ⊕ v, which rounds to |β| = 1 for a point moving
/// forward on a body at |β| = 1 − 10⁻¹⁶ (the rim of a rolling wheel): the velocity is the
/// four-velocity Λ_β γ_v(1, v) (Eq. 2–3), and the normal is the point's own, Λ_−v·n (a modest
/// boost), turned by the Wigner rotation of Λ_β·Λ_v = Λ_(β ⊕ v)·R — rather than Λ_−(β⊕v)·Λ_β·n,
/// whose entries of order γ² cancel to an O(1) result.
pub(crate) fn local_rest_frame(
    frame_beta: DVec3,
    velocity: FourVelocity,
    normal: DVec4,
) -> (FourVelocity, DVec3) {
    let frame = FourVelocity::from_beta(frame_beta);
    let own = velocity.reversed().boost() * normal;
    let own = DVec3::new(own.y, own.z, own.w);
    (
        frame.compose(velocity),
        (frame.wigner_rotation(velocity) * own).normalize(),
    )
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
            thrust.four_velocity(body, ct).boost() * DVec4::new(0.0, normal.x, normal.y, normal.z)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A unit vector from three components in [−1, 1] (None if too short to normalise).
    fn unit(v: [f64; 3]) -> Option<DVec3> {
        let v = DVec3::from(v);
        (v.length() > 0.1).then(|| v.normalize())
    }

    /// A thrust without end along `axis` with proper acceleration `alpha` from S′ time 0, the
    /// backward ray from `origin` along `direction` observed at S′ time `ct`, and its arc with
    /// the stretch where it is this side of the horizon and the thrust has begun.
    fn arc_case(
        axis: DVec3,
        alpha: f64,
        origin: [f64; 3],
        direction: DVec3,
        ct: f64,
    ) -> (Thrust, RestRay, ThrustArc, f64, f64) {
        let thrust = Thrust::new(alpha * axis, 0.0, f64::INFINITY).unwrap();
        let ray = RestRay {
            origin: DVec3::from(origin),
            direction,
            ct_origin: ct,
        };
        let arc = ThrustArc::new(&thrust, &ray, ct - thrust.start());
        let (from, to) = (arc.horizon().max(0.0), ct);
        (thrust, ray, arc, from, to)
    }

    /// A thrust, a backward ray and its arc with the stretch of the arc (`arc_case`), where the
    /// thrust's and the ray's directions can be normalised and the stretch is not empty.
    fn arc_cases() -> impl Strategy<Value = (Thrust, RestRay, ThrustArc, f64, f64)> {
        (
            prop::array::uniform3(-1.0f64..1.0),
            0.05f64..2.0,
            prop::array::uniform3(-5.0f64..5.0),
            prop::array::uniform3(-1.0f64..1.0),
            0.0f64..20.0,
        )
            .prop_filter_map(
                "a degenerate direction or an empty stretch",
                |(axis, alpha, origin, direction, ct)| {
                    let (axis, direction) = (unit(axis)?, unit(direction)?);
                    let case = arc_case(axis, alpha, origin, direction, ct);
                    (case.3 < case.4).then_some(case)
                },
            )
    }

    /// The slab test's entry is taken a little early and its exit a little late; a ray
    /// parallel to a slab meets the box if it lies on the slab's face (NaN, counted as meeting)
    /// and not if it lies outside it, an infinite entry included.
    #[test]
    fn the_slab_is_wide_by_rounding_units_and_refuses_parallel_rays_outside() {
        let (lo, hi) = (DVec3::splat(-1.0), DVec3::splat(1.0));
        let ray = |origin: [f64; 3], direction: [f64; 3]| RestRay {
            origin: DVec3::from(origin),
            direction: DVec3::from(direction).normalize(),
            ct_origin: 0.0,
        };
        let (near, far) = slab(&ray([3.0, 0.3, 0.0], [-1.0, 0.0, 0.0]), lo, hi).unwrap();
        assert!(near < 2.0 && near > 2.0 - 1e-9, "{near}");
        assert!(far > 4.0 && far < 4.0 + 1e-9, "{far}");
        assert!(slab(&ray([3.0, 0.3, 1.0], [-1.0, 0.0, 0.0]), lo, hi).is_some());
        assert_eq!(slab(&ray([3.0, 1.5, 0.0], [-1.0, 0.0, 0.0]), lo, hi), None);
        assert_eq!(slab(&ray([3.0, -1.5, 0.0], [-1.0, 0.0, 0.0]), lo, hi), None);
        assert_eq!(slab(&ray([0.0, 0.0, 2.0], [1.0, 0.0, 0.0]), lo, hi), None);
    }

    /// The body point at `s` by its definition (`Thrust::body_point` at the ray's event).
    fn defined_point(thrust: &Thrust, ray: &RestRay, s: f64) -> Option<DVec3> {
        thrust.body_point(ray.ct_origin - s, ray.origin + s * ray.direction)
    }

    proptest! {
        /// At everyday speeds the local rest frame is the plain product of matrices: the
        /// velocity β ⊕ v and the normal Λ_−(β⊕v)·Λ_β·n (Eq. 2), which the Wigner rotation
        /// form only keeps finite where β ⊕ v rounds to 1.
        #[test]
        fn the_local_rest_frame_is_the_product_of_boosts_at_everyday_speeds(
            frame in prop::array::uniform3(-0.57f64..0.57),
            velocity in prop::array::uniform3(-0.57f64..0.57),
            normal in prop::array::uniform3(-1.0f64..1.0),
        ) {
            let Some(normal) = unit(normal) else {
                return Ok(());
            };
            let (frame, velocity) = (DVec3::from(frame), DVec3::from(velocity));
            // A normal orthogonal to the point's four-velocity γ(1, v): time part n·v.
            let four_normal = DVec4::new(normal.dot(velocity), normal.x, normal.y, normal.z);
            let (local, found) =
                local_rest_frame(frame, FourVelocity::from_beta(velocity), four_normal);
            let composed = srt_physics::compose_velocities(frame, velocity);
            prop_assert!((local.beta() - composed).length() < 1e-12);
            let plain = srt_physics::lorentz_matrix(-composed)
                * srt_physics::lorentz_matrix(frame)
                * four_normal;
            prop_assert!(plain.x.abs() < 1e-12, "{plain}");
            let plain = DVec3::new(plain.y, plain.z, plain.w).normalize();
            prop_assert!((found - plain).length() < 1e-12, "{found} vs {plain}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Every body point of a piece, by its definition, lies in the piece's box.
        #[test]
        fn a_piece_box_holds_its_arc(case in arc_cases(), ends in (0.0f64..1.0, 0.0f64..1.0)) {
            let (thrust, ray, arc, from, to) = case;
            let (a, b) = (from + (to - from) * ends.0.min(ends.1), from + (to - from) * ends.0.max(ends.1));
            let (lo, hi) = arc.piece_box(a, b);
            for k in 0..=200 {
                let s = a + (b - a) * f64::from(k) / 200.0;
                let Some(point) = defined_point(&thrust, &ray, s) else {
                    continue;
                };
                let slack = 1e-9 * (1.0 + point.abs().max_element());
                prop_assert!(
                    point.cmpge(lo - slack).all() && point.cmple(hi + slack).all(),
                    "b({s}) = {point} outside [{lo}, {hi}]"
                );
            }
        }

        /// The crossing found with a triangle around a point of the arc is on the triangle by
        /// the definition of the body point, no later than that point, and no sampled crossing
        /// of the definition's signed distance comes before it.
        #[test]
        fn a_crossing_is_the_first_where_the_defined_body_point_meets_the_triangle(
            case in arc_cases(),
            at in 0.05f64..0.95,
            normal in prop::array::uniform3(-1.0f64..1.0),
            size in 0.05f64..2.0,
        ) {
            let (thrust, ray, arc, from, to) = case;
            let Some(normal) = unit(normal) else {
                return Ok(());
            };
            let known = from + (to - from) * at;
            let centre = defined_point(&thrust, &ray, known).unwrap();
            // A triangle in the plane through b(known) with normal `normal`, centred there.
            let tangent = normal.any_orthonormal_vector();
            let other = normal.cross(tangent);
            let corners = [0.0f64, 2.1, 4.2].map(|angle| {
                centre + size * (angle.cos() * tangent + angle.sin() * other)
            });
            let plane = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            let height = |s: f64| defined_point(&thrust, &ray, s).map(|p| plane.dot(p - corners[0]));
            // Transversal at the known point (a graze may be missed, as a piece of spin may).
            let step = 1e-6 * (to - from);
            let slope = (height(known + step).unwrap() - height(known - step).unwrap()) / (2.0 * step);
            prop_assume!(slope.abs() > 1e-3 * plane.length());
            let hit = arc.crossing(&arc.piece(None, from, to), corners);
            prop_assert!(hit.is_some(), "no crossing, though b({known}) is inside the triangle");
            let hit = hit.unwrap();
            let scale = plane.length() * (1.0 + centre.abs().max_element() + to);
            prop_assert!(hit.distance <= known + 1e-9 * (1.0 + known), "{} after {known}", hit.distance);
            prop_assert!(height(hit.distance).unwrap().abs() <= 1e-9 * scale, "off the plane");
            // In the triangle grown by 10⁻⁶ about its centre (an earlier crossing found on an
            // edge may fall either side of it by rounding).
            let grown = corners.map(|c| centre + (1.0 + 1e-6) * (c - centre));
            let point = defined_point(&thrust, &ray, hit.distance).unwrap();
            prop_assert!(barycentric(point, grown).is_some(), "the defined point is not in the triangle");
            // No earlier sign change of the definition's distance, sampled and bisected, whose
            // point is clearly inside the triangle (inside it shrunk by 10⁻⁶ about its centre:
            // a crossing on an edge may fall either side of it by rounding).
            let shrunk = corners.map(|c| centre + (1.0 - 1e-6) * (c - centre));
            let samples = 2000;
            let at_sample = |k: u32| from + (hit.distance - from) * f64::from(k) / f64::from(samples) * (1.0 - 1e-7);
            let mut previous = None;
            for k in 0..=samples {
                // None at the horizon, where the stretch may begin.
                let now = height(at_sample(k));
                if let (Some(before), Some(now)) = (previous, now)
                    && before * now < 0.0
                {
                    let (mut lo, mut hi) = (at_sample(k - 1), at_sample(k));
                    for _ in 0..100 {
                        let mid = 0.5 * (lo + hi);
                        if height(mid).is_some_and(|h| h * before > 0.0) {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    let inside = defined_point(&thrust, &ray, hi).and_then(|p| barycentric(p, shrunk));
                    prop_assert!(inside.is_none(), "an earlier crossing at s = {hi} was missed");
                }
                previous = now;
            }
        }
    }
}
