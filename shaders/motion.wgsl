// motion.wgsl — bodies that spin or thrust within their rest frame S′ (docs/physics.md,
// "Spinning and accelerating bodies"): the f32 mirror of crates/srt-trace/src/moving.rs and of
// srt_physics::motion. The object's motion is in ObjectUniforms.motion* (srt_gpu::motion).
//
// In the object's rest coordinates the backward ray is x(s) = o + s·d at S′ time ct′₀ − s
// (ct′₀ the object's S′ time at the observation event). The body point found on it,
// b(s) (`motion_curve`), is a curve in body space met with the body's static triangles:
// - spin: the curve is cut into pieces of at most MOTION_SPIN_PIECE_ANGLE of rotation within
//   the ball the body sweeps and the slab of its heights along the axis; each piece is bounded
//   by its chord's box padded by (2|ω| + ω²R)·Δs²/8;
// - thrust: after the end (coasting) the curve is a straight line (an exact ray test), during
//   the thrust it is marched as above (pieces of 1/MOTION_THRUST_PIECES_PER_SIZE of the body's
//   size, padded by four times the midpoint's deviation from the chord), only where the box
//   swept by the body meets the ray, and before the start it is the ray itself.
// On a piece, a triangle is crossed where the signed distance of b(s) to its plane changes sign,
// bisected (MOTION_BISECTIONS steps at most). The nearest crossing of the first piece that has one
// wins.
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
// Most bisection steps of one crossing (srt_gpu::motion::BISECTIONS).
const MOTION_BISECTIONS: u32 = 48u;
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

// A body point, or none (`found` false: beyond a thrust's Rindler horizon).
struct BodyPoint {
    found: bool,
    point: vec3<f32>,
}

// The body point of a thrusting body at `position` when `elapsed` = ct′ − ct₀ has passed since
// the start (mirror of srt_physics::motion::Thrust::body_point).
fn thrust_body_point(elapsed: f32, position: vec3<f32>) -> BodyPoint {
    let direction = object.motion_axis.xyz;
    let alpha = object.motion.y;
    let end = object.motion.w;
    if (elapsed <= 0.0) {
        return BodyPoint(true, position);
    }
    let along = dot(position, direction);
    let across = position - along * direction;
    let u = along + 1.0 / alpha;
    let v = elapsed;
    var x = 0.0;
    if (end >= 0.0 && v * cosh(end) - u * sinh(end) >= 0.0) {
        x = u * cosh(end) - v * sinh(end);
    } else if (u > v) {
        x = sqrt((u - v) * (u + v));
    } else {
        return BodyPoint(false, position);
    }
    if (!(x > 0.0)) {
        return BodyPoint(false, position);
    }
    return BodyPoint(true, across + (x - 1.0 / alpha) * direction);
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

// b(s): the body point on the backward ray at parameter s (mirror of Motion::body_point at the
// ray's event).
fn motion_curve(ray: RestRay, s: f32) -> BodyPoint {
    let x = ray.origin + s * ray.direction;
    if (motion_kind() == MOTION_SPIN) {
        let centre = object.motion_centre.xyz;
        return BodyPoint(true, centre + spin_turn(x - centre, -spin_angle(s)));
    }
    return thrust_body_point(object.motion.z - s, x);
}

// Where a ray meets a moving body, stretch by stretch (see the header), nearest first.
struct MotionPlan {
    // A thrust's coasting stretch s ∈ (0, coast_end) (none where coast_end ≤ 0): the body-space
    // line line_origin + σ·line_direction, σ = s·speed.
    coast_end: f32,
    line_origin: vec3<f32>,
    line_direction: vec3<f32>,
    speed: f32,
    // The marched stretch [lower, to] in `pieces` pieces (0: none), padded by `pad` (spin) or,
    // where pad < 0, by four times each piece's midpoint deviation (thrust).
    lower: f32,
    to: f32,
    pieces: u32,
    pad: f32,
    // The straight stretch before a thrust: s ≥ rest_from (none where < 0).
    rest_from: f32,
}

// The box [lo, hi] meets the line `ray` between near and far (a little late) if near ≤ far.
fn motion_slab(ray: RestRay, lo: vec3<f32>, hi: vec3<f32>) -> vec2<f32> {
    let inverse = safe_inverse(ray.direction);
    let a = (lo - ray.origin) * inverse;
    let b = (hi - ray.origin) * inverse;
    let l = min(a, b);
    let h = max(a, b);
    let near = max(max(l.x, l.y), l.z);
    let far = min(min(h.x, h.y), h.z);
    return vec2<f32>(near, far + 1e-5 * (1.0 + abs(far)));
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
    let u0 = dot(ray.origin, direction) + 1.0 / alpha;
    let along = dot(ray.direction, direction);
    var end_at = -3.0e38;
    if (end >= 0.0) {
        let c = cosh(end);
        let sh = sinh(end);
        end_at = (start * c - u0 * sh) / (c + along * sh);
        if (end_at > 0.0) {
            // Coasting: b(s) = x⊥(s) + (u(s)·cosh η_e − v(s)·sinh η_e − 1/α)·â, linear in s.
            let b0 = ray.origin - dot(ray.origin, direction) * direction + (u0 * c - start * sh - 1.0 / alpha) * direction;
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
    let lower = max(end_at, 0.0);
    let to = start;
    // No point moves faster than light: during the thrust the body stays in its box swept by
    // the elapsed time along â.
    let sweep = max(start - lower, 0.0) * direction;
    let lo = min(object.motion_low.xyz, object.motion_low.xyz + sweep);
    let hi = max(object.motion_high.xyz, object.motion_high.xyz + sweep);
    let span = motion_slab(ray, lo, hi);
    if (lower < to && span.x <= span.y && span.x <= to && span.y >= lower) {
        // The curve's length from 64 chords, as the reference measures it.
        var length_sum = 0.0;
        var previous = motion_curve(ray, lower);
        for (var k = 1; k <= 64; k++) {
            let next = motion_curve(ray, lower + (to - lower) * f32(k) / 64.0);
            if (next.found) {
                if (previous.found) {
                    length_sum += length(next.point - previous.point);
                }
                previous = next;
            }
        }
        let size = max(reach, 1e-9);
        plan.lower = lower;
        plan.to = to;
        plan.pieces = u32(clamp(ceil(length_sum / size * MOTION_THRUST_PIECES_PER_SIZE), 16.0, f32(MOTION_MAX_PIECES)));
        plan.pad = -1.0;
    }
    plan.rest_from = max(start, 0.0);
    return plan;
}

// One piece [a, b] of the marched stretch and the padded box of its chord, if the curve is
// defined at its ends (and, for a thrust, its middle); `end` is b(b), the next piece's start.
struct MotionPiece {
    valid: bool,
    a: f32,
    b: f32,
    lo: vec3<f32>,
    hi: vec3<f32>,
    // b(a), where the piece starts.
    begin: vec3<f32>,
    end: BodyPoint,
}

// The curve where the plan's march starts (piece 1's start).
fn motion_march_start(ray: RestRay, plan: MotionPlan) -> BodyPoint {
    return motion_curve(ray, plan.lower);
}

// Piece `k` (from 1) of the plan's march, `start` the curve at its start (the previous piece's
// `end`; mirror of PreparedObject::march).
fn motion_piece(ray: RestRay, plan: MotionPlan, k: u32, start: BodyPoint) -> MotionPiece {
    let width = plan.to - plan.lower;
    let count = f32(plan.pieces);
    let a = plan.lower + width * f32(k - 1u) / count;
    let b = plan.lower + width * f32(k) / count;
    let pb = motion_curve(ray, b);
    let pa = start;
    var piece = MotionPiece(false, a, b, vec3<f32>(0.0), vec3<f32>(0.0), pa.point, pb);
    if (!pa.found || !pb.found) {
        return piece;
    }
    var pad = plan.pad;
    if (pad < 0.0) {
        let middle = motion_curve(ray, 0.5 * (a + b));
        if (!middle.found) {
            return piece;
        }
        pad = 4.0 * length(middle.point - 0.5 * (pa.point + pb.point));
    }
    // f32 rounding of the curve: a few units in the last place of the ray's coordinates.
    let scale = max(max(abs(ray.origin.x), abs(ray.origin.y)), abs(ray.origin.z)) + abs(b)
        + max(max(abs(pa.point.x), abs(pa.point.y)), abs(pa.point.z));
    let margin = pad + 1e-5 * (1.0 + scale);
    piece.valid = true;
    piece.lo = min(pa.point, pb.point) - vec3<f32>(margin);
    piece.hi = max(pa.point, pb.point) + vec3<f32>(margin);
    return piece;
}

// Pieces `first` to `last` of a spinning body's march taken together (motion_group): the box
// [lo, hi] holds the curve over all of them (its chord's box padded by the sagitta bound for
// their span, as motion_piece pads one piece), and `end` is the curve at the last one's end,
// exactly as motion_piece computes it there.
struct MotionGroup {
    last: u32,
    lo: vec3<f32>,
    hi: vec3<f32>,
    end: BodyPoint,
}

// The group of pieces starting at piece `first` (from 1; a multiple of MOTION_PIECES_PER_GROUP
// plus one) of a spinning body's march, `start` the curve at its start. A search may skip the
// group's pieces where nothing it looks for meets the box: every crossing on them is a point of
// the curve inside it. Only for spin, whose padding is a bound (a thrust's is an estimate).
fn motion_group(ray: RestRay, plan: MotionPlan, first: u32, start: BodyPoint) -> MotionGroup {
    let last = min(first + MOTION_PIECES_PER_GROUP - 1u, plan.pieces);
    let count = f32(plan.pieces);
    let b = plan.lower + (plan.to - plan.lower) * f32(last) / count;
    let end = motion_curve(ray, b);
    let span = f32(last - first + 1u);
    let scale = max(max(abs(ray.origin.x), abs(ray.origin.y)), abs(ray.origin.z)) + abs(b)
        + max(max(abs(start.point.x), abs(start.point.y)), abs(start.point.z));
    let margin = plan.pad * span * span + 1e-5 * (1.0 + scale);
    return MotionGroup(last, min(start.point, end.point) - vec3<f32>(margin), max(start.point, end.point) + vec3<f32>(margin), end);
}

// Whether the march of `plan` takes its pieces in groups first (a spinning body's).
fn motion_grouped(plan: MotionPlan) -> bool {
    return motion_kind() == MOTION_SPIN && plan.pad >= 0.0;
}

// Where the curve crosses the triangle `corners` on the (valid) piece `piece`: the sign change
// of the signed distance to its plane, bisected, if the point is in the triangle, edges
// included (mirror of srt-trace's moving::crossing and barycentric).
fn motion_crossing(ray: RestRay, piece: MotionPiece, corners: array<vec3<f32>, 3>) -> TriangleHit {
    let none = TriangleHit(false, 0.0, 0.0, 0.0);
    let normal = cross(corners[1] - corners[0], corners[2] - corners[0]);
    var at_lo = dot(normal, piece.begin - corners[0]);
    let at_hi = dot(normal, piece.end.point - corners[0]);
    if ((at_lo > 0.0 && at_hi > 0.0) || (at_lo < 0.0 && at_hi < 0.0)) {
        return none;
    }
    var lo = piece.a;
    var hi = piece.b;
    if (at_lo != 0.0) {
        for (var i = 0u; i < MOTION_BISECTIONS; i++) {
            let mid = 0.5 * (lo + hi);
            if (mid <= lo || mid >= hi) {
                break;
            }
            let p = motion_curve(ray, mid);
            if (!p.found) {
                return none;
            }
            let at_mid = dot(normal, p.point - corners[0]);
            if ((at_mid < 0.0) == (at_lo < 0.0) && at_mid != 0.0) {
                lo = mid;
                at_lo = at_mid;
            } else {
                hi = mid;
            }
        }
    } else {
        hi = lo;
    }
    let distance = select(hi, lo, at_lo == 0.0);
    let point = motion_curve(ray, distance);
    if (!point.found) {
        return none;
    }
    let e1 = corners[1] - corners[0];
    let e2 = corners[2] - corners[0];
    let v = point.point - corners[0];
    let d00 = dot(e1, e1);
    let d01 = dot(e1, e2);
    let d11 = dot(e2, e2);
    let d20 = dot(v, e1);
    let d21 = dot(v, e2);
    let denominator = d00 * d11 - d01 * d01;
    if (denominator <= 0.0) {
        return none;
    }
    let zeta = (d11 * d20 - d01 * d21) / denominator;
    let xi = (d00 * d21 - d01 * d20) / denominator;
    let inside = zeta >= 0.0 && xi >= 0.0 && zeta + xi <= 1.0;
    return TriangleHit(inside, distance, zeta, xi);
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
        if (!piece.valid) {
            continue;
        }
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
