// motion.wgsl — bodies that spin or thrust within their rest frame S′ (docs/physics.md,
// "Spinning and accelerating bodies"): the f32 mirror of crates/srt-trace/src/moving.rs and of
// srt_physics::motion. The object's motion is in ObjectUniforms.motion* (srt_gpu::motion).
//
// In the object's rest coordinates the backward ray is x(s) = o + s·d at S′ time ct′₀ − s
// (ct′₀ the object's S′ time at the observation event). The body point found on it,
// b(s) (`spin_curve`, `arc_point`), is a curve in body space met with the body's static triangles:
// - spin: the curve is cut into pieces of at most MOTION_SPIN_PIECE_ANGLE of rotation within
//   the ball the body sweeps and the slab of its heights along the axis; each piece is bounded
//   by its chord's box padded by (2|ω| + ω²R)·Δs²/8;
// - thrust: after the end (coasting) the curve is a straight line (an exact ray test), during
//   the thrust a hyperbola arc (ThrustArc) searched in pieces (MOTION_THRUST_PIECES_PER_SIZE per
//   body size of its extent, each bounded exactly by its parallelogram), only where the box
//   swept by the body meets the ray, and before the start it is the ray itself.
// On a spinning body's piece, a triangle is crossed where the signed distance of b(s) to its plane
// changes sign, narrowed by the Illinois method to f32 precision (MOTION_CROSSING_STEPS steps at
// most; srt-trace bisects to the f64 limit); on a thrust's arc, where a quadratic
// vanishes (arc_crossing). The nearest crossing of the first piece that has one wins.
//
// rt.wgsl's visibility pass takes each piece's candidates from the BVH (moving_nearest_hit);
// the shading pass, which knows the triangle the visibility pass kept, repeats the same pieces
// on that triangle alone (moving_hit_on) and so finds the same crossing, then shades it in the
// point's local rest frame (moving_frame) with the point's own proper time.

// Most rotation of a spinning body per piece, in radians (srt_gpu::motion::SPIN_PIECE_ANGLE).
override MOTION_SPIN_PIECE_ANGLE: f32;
// Pieces of a thrust's accelerating stretch per body size (srt_gpu::motion::THRUST_PIECES_PER_SIZE).
override MOTION_THRUST_PIECES_PER_SIZE: f32;
// Most pieces of one curved stretch (srt_gpu::motion::MAX_PIECES).
const MOTION_MAX_PIECES: u32 = 4096u;
// Most steps of the search for one crossing (srt_gpu::motion::CROSSING_STEPS).
const MOTION_CROSSING_STEPS: u32 = 48u;
// Width, relative to the ray parameter, at which a crossing's bracket is taken as found: two
// f32 rounding units (2 · 2⁻²³), where bisection would stop at neighbouring floats.
const MOTION_CROSSING_WIDTH: f32 = 2.4e-7;
// Newton steps polishing each root of a thrust's crossing (srt_gpu::motion::NEWTON_STEPS).
const MOTION_NEWTON_STEPS: u32 = 2u;
// Pieces of a spinning body's march taken together first (srt_gpu::motion::PIECES_PER_GROUP):
// where the group's padded box meets nothing the search could find, its pieces are skipped.
const MOTION_PIECES_PER_GROUP: u32 = 8u;

// The MOTION_* code this variant of the shader draws (srt_gpu::shaders::lrt, ::polygon): one
// variant per code, each object drawn by its own, so that the other kinds' code is compiled out.
// A software rasteriser runs every side of a branch its pixels do not all take, so a branch on
// the object's kind read at run time cost every object the spinning and the thrusting bodies'
// searches.
override MOTION_VARIANT: u32;

// The current object's MOTION_* code.
fn motion_kind() -> u32 {
    return MOTION_VARIANT;
}

// `v` turned right-handedly by `angle` about the spin axis (Rodrigues' formula).
fn spin_turn(v: vec3<f32>, angle: f32) -> vec3<f32> {
    let k = object.motion_axis.xyz;
    let c = cos(angle);
    let s = sin(angle);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0 - c));
}

// The angle ω·ct′ the spinning body has turned by at ray parameter s.
fn spin_angle(s: f32) -> f32 {
    return object.motion.z - object.motion.y * s;
}

// Where the body point `body` of a thrusting body is when `elapsed` has passed since the start
// (mirror of srt_physics::motion::Thrust::position).
fn thrust_position(body: vec3<f32>, elapsed: f32) -> vec3<f32> {
    if (elapsed <= 0.0) {
        return body;
    }
    let direction = object.motion_axis.xyz;
    let alpha = object.motion.y;
    let end = object.motion.w;
    let height = dot(body, direction);
    let x = 1.0 / alpha + height;
    let eta = asinh(elapsed / x);
    if (end < 0.0 || eta <= end) {
        return body + (x * cosh(eta) - 1.0 / alpha - height) * direction;
    }
    return body + ((x * cosh(end) - 1.0 / alpha - height) + (elapsed - x * sinh(end)) * tanh(end)) * direction;
}

// b(s) of a spinning body: the body point on the backward ray at parameter s (mirror of
// Spin::body_point at the ray's event; a thrust's is arc_point).
fn spin_curve(ray: RestRay, s: f32) -> vec3<f32> {
    let x = ray.origin + s * ray.direction;
    let centre = object.motion_centre.xyz;
    return centre + spin_turn(x - centre, -spin_angle(s));
}

// Where a ray meets a moving body, stretch by stretch (see the header), nearest first.
struct MotionPlan {
    // A thrust's coasting stretch s ∈ (0, coast_end) (none where coast_end ≤ 0): the body-space
    // line line_origin + σ·line_direction, σ = s·speed.
    coast_end: f32,
    line_origin: vec3<f32>,
    line_direction: vec3<f32>,
    speed: f32,
    // The marched stretch [lower, to] in `pieces` pieces (0: none), padded by `pad` (spin; −1
    // for a thrust, whose pieces are bounded exactly).
    lower: f32,
    to: f32,
    pieces: u32,
    pad: f32,
    // The straight stretch before a thrust: s ≥ rest_from (none where < 0).
    rest_from: f32,
}

// The box [lo, hi] meets the line `ray` between near (a little early) and far (a little late) if
// near ≤ far: a point on a face is not cut off by rounding.
fn motion_slab(ray: RestRay, lo: vec3<f32>, hi: vec3<f32>) -> vec2<f32> {
    let inverse = safe_inverse(ray.direction);
    let a = (lo - ray.origin) * inverse;
    let b = (hi - ray.origin) * inverse;
    let l = min(a, b);
    let h = max(a, b);
    let near = max(max(l.x, l.y), l.z);
    let far = min(min(h.x, h.y), h.z);
    return vec2<f32>(near - 1e-5 * (1.0 + abs(near)), far + 1e-5 * (1.0 + abs(far)));
}

// The stretches of `ray` on which the current (moving) object is searched (mirror of
// PreparedObject::spin_hit and thrust_hit up to their marches).
fn motion_plan(ray: RestRay) -> MotionPlan {
    var plan = MotionPlan(0.0, vec3<f32>(0.0), vec3<f32>(0.0), 1.0, 0.0, 0.0, 0u, 0.0, -1.0);
    let reach = object.motion_axis.w;
    if (motion_kind() == MOTION_SPIN) {
        let axis = object.motion_axis.xyz;
        let to_origin = ray.origin - object.motion_centre.xyz;
        let half = dot(to_origin, ray.direction);
        let discriminant = half * half - (dot(to_origin, to_origin) - reach * reach);
        if (discriminant < 0.0) {
            return plan;
        }
        let root = sqrt(discriminant);
        var lower = max(-half - root, 0.0);
        var to = -half + root;
        // The rotation keeps every height along the axis: only the slab of the body's heights.
        let low = object.motion_low.w;
        let high = object.motion_high.w;
        let pad = 1e-5 * (1.0 + reach);
        let height = dot(to_origin, axis);
        let climb = dot(ray.direction, axis);
        if (climb == 0.0) {
            if (height < low - pad || height > high + pad) {
                return plan;
            }
        } else {
            let a = (low - pad - height) / climb;
            let b = (high + pad - height) / climb;
            lower = max(lower, min(a, b));
            to = min(to, max(a, b));
        }
        if (lower > to) {
            return plan;
        }
        let omega = abs(object.motion.y);
        var pieces = 1.0;
        if (omega > 0.0) {
            pieces = clamp(ceil((to - lower) * omega / MOTION_SPIN_PIECE_ANGLE), 1.0, f32(MOTION_MAX_PIECES));
        }
        let step = (to - lower) / pieces;
        plan.lower = lower;
        plan.to = to;
        plan.pieces = u32(pieces);
        plan.pad = (2.0 * omega + omega * omega * reach) * step * step / 8.0;
        return plan;
    }
    // Thrust: v(s) = ct′(s) − ct₀ = start − s; u(s) = x_∥(s) + 1/α.
    let direction = object.motion_axis.xyz;
    let alpha = object.motion.y;
    let end = object.motion.w;
    let start = object.motion.z;
    let arc = thrust_arc(ray);
    var end_at = -3.0e38;
    if (end >= 0.0) {
        let c = cosh(end);
        let sh = sinh(end);
        end_at = (start * c - arc.u0 * sh) / (c + arc.w * sh);
        if (end_at > 0.0) {
            // Coasting: b(s) = x⊥(s) + (u(s)·cosh η_e − v(s)·sinh η_e − 1/α)·â, linear in s.
            let b0 = ray.origin - dot(ray.origin, direction) * direction + (arc.u0 * c - start * sh - 1.0 / alpha) * direction;
            let x1 = ray.origin + ray.direction;
            let u1 = dot(x1, direction) + 1.0 / alpha;
            let b1 = x1 - dot(x1, direction) * direction + (u1 * c - (start - 1.0) * sh - 1.0 / alpha) * direction;
            let slope = b1 - b0;
            plan.speed = length(slope);
            plan.line_origin = b0;
            plan.line_direction = slope / plan.speed;
            plan.coast_end = end_at;
        }
    }
    // Beyond the horizon (u ≤ v) no body point is met.
    let lower = max(max(end_at, 0.0), arc_horizon(arc));
    let to = start;
    // No point moves faster than light: during the thrust the body stays in its box swept by
    // the elapsed time along â.
    let sweep = max(start - lower, 0.0) * direction;
    let lo = min(object.motion_low.xyz, object.motion_low.xyz + sweep);
    let hi = max(object.motion_high.xyz, object.motion_high.xyz + sweep);
    // Only the stretch of the ray inside that box is searched.
    let span = motion_slab(ray, lo, hi);
    let inside = vec2<f32>(max(lower, span.x), min(to, span.y));
    if (lower < to && inside.x <= inside.y) {
        let whole = arc_box(ray, arc, inside.x, inside.y);
        let extent = length(whole.hi - whole.lo);
        plan.lower = inside.x;
        plan.to = inside.y;
        plan.pieces = u32(clamp(ceil(extent / max(reach, 1e-9) * MOTION_THRUST_PIECES_PER_SIZE), 1.0, f32(MOTION_MAX_PIECES)));
        plan.pad = -1.0;
    }
    plan.rest_from = max(start, 0.0);
    return plan;
}

// One piece [a, b] of the marched stretch and a box [lo, hi] that holds the curve there;
// a spinning body's `begin` and `end` are b(a) and b(b), `end` the next piece's start.
struct MotionPiece {
    a: f32,
    b: f32,
    lo: vec3<f32>,
    hi: vec3<f32>,
    begin: vec3<f32>,
    end: vec3<f32>,
}

// The curve where the plan's march starts (piece 1's start; a spinning body's, which its pieces
// carry on).
fn motion_march_start(ray: RestRay, plan: MotionPlan) -> vec3<f32> {
    if (motion_kind() == MOTION_SPIN) {
        return spin_curve(ray, plan.lower);
    }
    return vec3<f32>(0.0);
}

// Piece `k` (from 1) of the plan's march, `start` the curve at its start (the previous piece's
// `end`; mirror of PreparedObject::march with Helix::piece or ThrustArc::piece). A
// thrust's pieces are bounded by its arc alone: their `begin` and `end` are not evaluated.
fn motion_piece(ray: RestRay, plan: MotionPlan, k: u32, start: vec3<f32>) -> MotionPiece {
    let width = plan.to - plan.lower;
    let count = f32(plan.pieces);
    let a = plan.lower + width * f32(k - 1u) / count;
    let b = plan.lower + width * f32(k) / count;
    if (motion_kind() == MOTION_THRUST) {
        let bounds = arc_box(ray, thrust_arc(ray), a, b);
        return MotionPiece(a, b, bounds.lo, bounds.hi, start, start);
    }
    let pb = spin_curve(ray, b);
    let pa = start;
    // f32 rounding of the curve: a few units in the last place of the ray's coordinates.
    let scale = max(max(abs(ray.origin.x), abs(ray.origin.y)), abs(ray.origin.z)) + abs(b)
        + max(max(abs(pa.x), abs(pa.y)), abs(pa.z));
    let margin = plan.pad + 1e-5 * (1.0 + scale);
    return MotionPiece(a, b, min(pa, pb) - vec3<f32>(margin), max(pa, pb) + vec3<f32>(margin), pa, pb);
}

// Pieces `first` to `last` of a spinning body's march taken together (motion_group): the box
// [lo, hi] holds the curve over all of them (its chord's box padded by the sagitta bound for
// their span, as motion_piece pads one piece), and `end` is the curve at the last one's end,
// exactly as motion_piece computes it there.
struct MotionGroup {
    last: u32,
    lo: vec3<f32>,
    hi: vec3<f32>,
    end: vec3<f32>,
}

// The group of pieces starting at piece `first` (from 1; a multiple of MOTION_PIECES_PER_GROUP
// plus one) of a spinning body's march, `start` the curve at its start. A search may skip the
// group's pieces where nothing it looks for meets the box: every crossing on them is a point of
// the curve inside it. Only for spin (a thrust's few pieces are each bounded exactly).
fn motion_group(ray: RestRay, plan: MotionPlan, first: u32, start: vec3<f32>) -> MotionGroup {
    let last = min(first + MOTION_PIECES_PER_GROUP - 1u, plan.pieces);
    let count = f32(plan.pieces);
    let b = plan.lower + (plan.to - plan.lower) * f32(last) / count;
    let end = spin_curve(ray, b);
    let span = f32(last - first + 1u);
    let scale = max(max(abs(ray.origin.x), abs(ray.origin.y)), abs(ray.origin.z)) + abs(b)
        + max(max(abs(start.x), abs(start.y)), abs(start.z));
    let margin = plan.pad * span * span + 1e-5 * (1.0 + scale);
    return MotionGroup(last, min(start, end) - vec3<f32>(margin), max(start, end) + vec3<f32>(margin), end);
}

// Whether the march of `plan` takes its pieces in groups first (a spinning body's).
fn motion_grouped(plan: MotionPlan) -> bool {
    return motion_kind() == MOTION_SPIN && plan.pad >= 0.0;
}

// Where the curve crosses the triangle `corners` on the piece `piece`, if the triangle's box
// meets the piece's (mirror of PreparedObject::march's candidate test). A spinning body:
// the sign change of the signed distance to its plane, narrowed by the Illinois method (the
// same bracket as srt-trace's Helix::crossing, which bisects in f64), if the point is in the
// triangle, edges included; a thrust: arc_crossing.
fn motion_crossing(ray: RestRay, piece: MotionPiece, corners: array<vec3<f32>, 3>) -> TriangleHit {
    let none = TriangleHit(false, 0.0, 0.0, 0.0);
    // The crossing is a point of the piece's curve, in its box, and of the triangle, in the
    // triangle's box: where the two boxes are apart there is none to look for.
    let low = min(min(corners[0], corners[1]), corners[2]);
    let high = max(max(corners[0], corners[1]), corners[2]);
    if (!(all(low <= piece.hi) && all(high >= piece.lo))) {
        return none;
    }
    if (motion_kind() == MOTION_THRUST) {
        return arc_crossing(ray, thrust_arc(ray), piece.a, piece.b, corners);
    }
    let normal = cross(corners[1] - corners[0], corners[2] - corners[0]);
    var at_lo = dot(normal, piece.begin - corners[0]);
    let at_hi = dot(normal, piece.end - corners[0]);
    if ((at_lo > 0.0 && at_hi > 0.0) || (at_lo < 0.0 && at_hi < 0.0)) {
        return none;
    }
    var lo = piece.a;
    var hi = piece.b;
    if (at_lo != 0.0) {
        // The Illinois method: regula falsi on the bracket [lo, hi], the value at an end kept
        // twice in a row halved, so that both ends close in on the crossing.
        var f_lo = at_lo;
        var f_hi = at_hi;
        var kept = 0;
        for (var i = 0u; i < MOTION_CROSSING_STEPS; i++) {
            var mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            if (!(mid > lo && mid < hi)) {
                mid = 0.5 * (lo + hi);
            }
            if (mid <= lo || mid >= hi || hi - lo <= MOTION_CROSSING_WIDTH * max(abs(lo), abs(hi))) {
                break;
            }
            let at_mid = dot(normal, spin_curve(ray, mid) - corners[0]);
            if ((at_mid < 0.0) == (at_lo < 0.0) && at_mid != 0.0) {
                lo = mid;
                f_lo = at_mid;
                if (kept == 1) {
                    f_hi *= 0.5;
                }
                kept = 1;
            } else {
                hi = mid;
                f_hi = at_mid;
                if (kept == -1) {
                    f_lo *= 0.5;
                }
                kept = -1;
            }
        }
    } else {
        hi = lo;
    }
    let distance = select(hi, lo, at_lo == 0.0);
    return triangle_point_hit(spin_curve(ray, distance), corners, distance);
}

// The hit at `distance` where `point` (in the triangle's plane) lies in the triangle `corners`,
// edges included, with its barycentric weights (mirror of srt-trace's moving::barycentric).
fn triangle_point_hit(point: vec3<f32>, corners: array<vec3<f32>, 3>, distance: f32) -> TriangleHit {
    let e1 = corners[1] - corners[0];
    let e2 = corners[2] - corners[0];
    let v = point - corners[0];
    let d00 = dot(e1, e1);
    let d01 = dot(e1, e2);
    let d11 = dot(e2, e2);
    let d20 = dot(v, e1);
    let d21 = dot(v, e2);
    let denominator = d00 * d11 - d01 * d01;
    if (denominator <= 0.0) {
        return TriangleHit(false, 0.0, 0.0, 0.0);
    }
    let zeta = (d11 * d20 - d01 * d21) / denominator;
    let xi = (d00 * d21 - d01 * d20) / denominator;
    let inside = zeta >= 0.0 && xi >= 0.0 && zeta + xi <= 1.0;
    return TriangleHit(inside, distance, zeta, xi);
}

// A thrusting body's curve while it accelerates (mirror of srt-trace's moving::ThrustArc): with
// u(s) = x(s)·â + 1/α = u0 + w·s and v(s) = ct′(s) − ct₀ = v0 − s, the body point is
// b(s) = x(s) + (X(s) − u(s))·â, X = √(u² − v²), this side of the horizon (u > v); its part
// x(s) − u(s)·â is linear and X is concave.
struct ThrustArc {
    u0: f32,
    w: f32,
    v0: f32,
}

// The arc of the backward ray `ray` of the current (thrusting) object.
fn thrust_arc(ray: RestRay) -> ThrustArc {
    let axis = object.motion_axis.xyz;
    return ThrustArc(dot(ray.origin, axis) + 1.0 / object.motion.y, dot(ray.direction, axis), object.motion.z);
}

// u(s) − v(s), positive this side of the horizon.
fn arc_above_horizon(arc: ThrustArc, s: f32) -> f32 {
    return (arc.u0 - arc.v0) + (arc.w + 1.0) * s;
}

// X(s), 0 at and beyond the horizon.
fn arc_rindler(arc: ThrustArc, s: f32) -> f32 {
    return sqrt(max(arc_above_horizon(arc, s) * ((arc.u0 + arc.v0) + (arc.w - 1.0) * s), 0.0));
}

// The ray parameter where the ray reaches the horizon (u = v), ∓3e38 where it never is below it /
// never leaves it.
fn arc_horizon(arc: ThrustArc) -> f32 {
    if (arc.w > -1.0) {
        return (arc.v0 - arc.u0) / (arc.w + 1.0);
    }
    return select(3.0e38, -3.0e38, arc.u0 > arc.v0);
}

// The linear part of b(s): x(s) − u(s)·â.
fn arc_linear_part(ray: RestRay, arc: ThrustArc, s: f32) -> vec3<f32> {
    return ray.origin + s * ray.direction - (arc.u0 + arc.w * s) * object.motion_axis.xyz;
}

// The body point at `s` (this side of the horizon).
fn arc_point(ray: RestRay, arc: ThrustArc, s: f32) -> vec3<f32> {
    return arc_linear_part(ray, arc, s) + arc_rindler(arc, s) * object.motion_axis.xyz;
}

// A box [lo, hi] in body space.
struct BoxBounds {
    lo: vec3<f32>,
    hi: vec3<f32>,
}

// The box of the parallelogram that holds the arc for s in [a, b] (its linear part's ends shifted
// along â by X's least and greatest values there), widened by f32 rounding.
fn arc_box(ray: RestRay, arc: ThrustArc, a: f32, b: f32) -> BoxBounds {
    let axis = object.motion_axis.xyz;
    let xa = arc_rindler(arc, a);
    let xb = arc_rindler(arc, b);
    var high = max(xa, xb);
    let curvature = arc.w * arc.w - 1.0;
    if (curvature < 0.0) {
        let apex = (arc.u0 * arc.w + arc.v0) / -curvature;
        if (apex > a && apex < b) {
            high = max(high, arc_rindler(arc, apex));
        }
    }
    let low = min(xa, xb);
    let la = arc_linear_part(ray, arc, a);
    let lb = arc_linear_part(ray, arc, b);
    let lo = min(min(la, lb) + low * axis, min(la, lb) + high * axis);
    let hi = max(max(la, lb) + low * axis, max(la, lb) + high * axis);
    let scale = max(max(abs(ray.origin.x), abs(ray.origin.y)), abs(ray.origin.z)) + abs(b)
        + max(max(max(abs(lo.x), abs(lo.y)), abs(lo.z)), max(max(abs(hi.x), abs(hi.y)), abs(hi.z)));
    let margin = 1e-5 * (1.0 + scale);
    return BoxBounds(lo - vec3<f32>(margin), hi + vec3<f32>(margin));
}

// The real roots of a·s² + b·s + c (the linear root where a = 0), `count` of them, in the
// cancellation-free form (mirror of srt-trace's moving::quadratic_roots).
struct Roots {
    count: u32,
    values: vec2<f32>,
}

fn quadratic_roots(a: f32, b: f32, c: f32) -> Roots {
    if (a == 0.0) {
        return Roots(select(0u, 1u, b != 0.0), vec2<f32>(-c / b, 0.0));
    }
    let discriminant = b * b - 4.0 * a * c;
    if (discriminant < 0.0) {
        return Roots(0u, vec2<f32>(0.0));
    }
    let root = sqrt(discriminant);
    let q = -0.5 * (b + select(root, -root, b < 0.0));
    if (q == 0.0) {
        return Roots(1u, vec2<f32>(0.0));
    }
    return Roots(2u, vec2<f32>(q / a, c / q));
}

// The nearest crossing of the arc with the triangle `corners` for s in [a, b] (mirror of
// ThrustArc::crossing): the distance to the plane L(s) + m·X(s) (m = n·â, L linear) vanishes
// where m²·X² = L² and −m·L ≥ 0, a quadratic's roots that keep the sign, each polished by Newton
// steps on L + m·X; the nearest this side of the horizon whose point is in the triangle.
fn arc_crossing(ray: RestRay, arc: ThrustArc, a: f32, b: f32, corners: array<vec3<f32>, 3>) -> TriangleHit {
    let none = TriangleHit(false, 0.0, 0.0, 0.0);
    let normal = cross(corners[1] - corners[0], corners[2] - corners[0]);
    let m = dot(normal, object.motion_axis.xyz);
    let l0 = dot(normal, ray.origin - corners[0]) - m * arc.u0;
    let l1 = dot(normal, ray.direction) - m * arc.w;
    var roots = Roots(0u, vec2<f32>(0.0));
    if (m == 0.0) {
        roots = Roots(select(0u, 1u, l1 != 0.0), vec2<f32>(-l0 / l1, 0.0));
    } else {
        let mm = m * m;
        roots = quadratic_roots(
            mm * (arc.w * arc.w - 1.0) - l1 * l1,
            2.0 * (mm * (arc.u0 * arc.w + arc.v0) - l0 * l1),
            mm * (arc.u0 - arc.v0) * (arc.u0 + arc.v0) - l0 * l0,
        );
    }
    if (roots.count == 2u && roots.values.y < roots.values.x) {
        roots.values = roots.values.yx;
    }
    for (var i = 0u; i < roots.count; i++) {
        let root = roots.values[i];
        // A root of the squared equation with m·X = +L is not a crossing.
        if (!(root >= a && root <= b) || m * (l0 + l1 * root) > 0.0) {
            continue;
        }
        var s = root;
        for (var k = 0u; k < MOTION_NEWTON_STEPS; k++) {
            let x = arc_rindler(arc, s);
            let u = arc.u0 + arc.w * s;
            let slope = l1 + m * (u * arc.w + (arc.v0 - s)) / x;
            let next = s - (l0 + l1 * s + m * x) / slope;
            if (!(x > 0.0 && next >= a && next <= b)) {
                break;
            }
            s = next;
        }
        if (arc_above_horizon(arc, s) <= 0.0) {
            continue;
        }
        let hit = triangle_point_hit(arc_point(ray, arc, s), corners, s);
        if (hit.found) {
            return hit;
        }
    }
    return none;
}

// The crossing of the backward ray `ray` with the triangle `corners` of the moving body that the
// visibility pass found (moving_nearest_hit in rt.wgsl): the same stretches and pieces, the
// triangle alone tested.
fn moving_hit_on(ray: RestRay, corners: array<vec3<f32>, 3>) -> TriangleHit {
    let plan = motion_plan(ray);
    if (plan.coast_end > 0.0) {
        var h = intersect_triangle(plan.line_origin, plan.line_direction, corners);
        if (h.found && h.distance < plan.coast_end * plan.speed) {
            h.distance /= plan.speed;
            return h;
        }
    }
    var start = motion_march_start(ray, plan);
    let low = min(min(corners[0], corners[1]), corners[2]);
    let high = max(max(corners[0], corners[1]), corners[2]);
    for (var k = 1u; k <= plan.pieces; k++) {
        if (motion_grouped(plan) && k % MOTION_PIECES_PER_GROUP == 1u) {
            let group = motion_group(ray, plan, k, start);
            if (!(all(low <= group.hi) && all(high >= group.lo))) {
                start = group.end;
                k = group.last;
                continue;
            }
        }
        let piece = motion_piece(ray, plan, k, start);
        start = piece.end;
        let h = motion_crossing(ray, piece, corners);
        if (h.found) {
            return h;
        }
    }
    if (plan.rest_from >= 0.0) {
        let h = intersect_triangle(ray.origin, ray.direction, corners);
        if (h.found && h.distance >= plan.rest_from) {
            return h;
        }
    }
    return TriangleHit(false, 0.0, 0.0, 0.0);
}

// The Lorentz boost Λ_β of srt_physics::lorentz_matrix: four-vectors of a frame moving with β
// → S.
fn lorentz_boost(beta: vec3<f32>) -> mat4x4<f32> {
    let gamma = lorentz_factor(beta);
    let k = gamma * gamma / (gamma + 1.0);
    let g = gamma * beta;
    return mat4x4<f32>(
        vec4<f32>(gamma, g),
        vec4<f32>(g.x, vec3<f32>(1.0, 0.0, 0.0) + k * beta.x * beta),
        vec4<f32>(g.y, vec3<f32>(0.0, 1.0, 0.0) + k * beta.y * beta),
        vec4<f32>(g.z, vec3<f32>(0.0, 0.0, 1.0) + k * beta.z * beta),
    );
}

// Where the body point `body` is at the S′ time ct′₀ − s, s a backward ray's parameter (mirror
// of Motion::position).
fn motion_position(body: vec3<f32>, s: f32) -> vec3<f32> {
    if (motion_kind() == MOTION_SPIN) {
        let centre = object.motion_centre.xyz;
        return centre + spin_turn(body - centre, spin_angle(s));
    }
    return thrust_position(body, object.motion.z - s);
}

// The corners `corners` of a moving body's triangle where they are at ray parameter s (for the
// texture differentials, as srt-trace places them).
fn moving_corners(corners: array<vec3<f32>, 3>, s: f32) -> array<vec3<f32>, 3> {
    var placed = corners;
    for (var k = 0u; k < 3u; k++) {
        placed[k] = motion_position(corners[k], s);
    }
    return placed;
}

// The local rest frame of the point (ζ, ξ) of triangle `t` of the moving body, met at ray
// parameter s at the rest event `emission` (mirror of Tracer::surface_at with moving.rs's
// moving_normal and local_rest_frame, and Motion::proper_time).
fn moving_frame(t: u32, zeta: f32, xi: f32, s: f32, emission: vec4<f32>) -> LocalFrame {
    let w = vec3<f32>(1.0 - zeta - xi, zeta, xi);
    let v0 = vertices[indices[3u * t]];
    let v1 = vertices[indices[3u * t + 1u]];
    let v2 = vertices[indices[3u * t + 2u]];
    let body = w.x * v0.position.xyz + w.y * v1.position.xyz + w.z * v2.position.xyz;
    let normal = normalize(w.x * v0.normal.xyz + w.y * v1.normal.xyz + w.z * v2.normal.xyz);
    // The object's S′ time at the event.
    let ct = proper_time_at(emission);
    var velocity = vec3<f32>(0.0);
    var four_normal = vec4<f32>(0.0, normal);
    var proper_time = ct;
    if (motion_kind() == MOTION_SPIN) {
        let centre = object.motion_centre.xyz;
        let axis = object.motion_axis.xyz;
        let omega = object.motion.y;
        let angle = spin_angle(s);
        velocity = omega * cross(axis, spin_turn(body - centre, angle));
        let n = spin_turn(normal, angle);
        four_normal = vec4<f32>(dot(n, velocity), n);
        let r = body - centre;
        let speed = abs(omega) * length(r - dot(r, axis) * axis);
        proper_time = ct * sqrt(max(1.0 - speed * speed, 0.0));
    } else {
        let elapsed = object.motion.z - s;
        if (elapsed > 0.0) {
            let direction = object.motion_axis.xyz;
            let end = object.motion.w;
            let x = 1.0 / object.motion.y + dot(body, direction);
            let eta = asinh(elapsed / x);
            let started = ct - elapsed;
            if (end < 0.0 || eta <= end) {
                velocity = tanh(eta) * direction;
                proper_time = started + x * eta;
            } else {
                velocity = tanh(end) * direction;
                proper_time = started + x * end + (elapsed - x * sinh(end)) / cosh(end);
            }
            four_normal = lorentz_boost(velocity) * vec4<f32>(0.0, normal);
        }
    }
    // The point's four-velocity and normal in S, then the normal in its own rest frame.
    let to_observer = object.frame.rest_to_observer;
    let gamma = 1.0 / sqrt(1.0 - dot(velocity, velocity));
    let four_velocity = to_observer * vec4<f32>(gamma, gamma * velocity);
    let beta = four_velocity.yzw / four_velocity.x;
    let local = lorentz_boost(-beta) * (to_observer * four_normal);
    return LocalFrame(beta, normalize(local.yzw), proper_time);
}
