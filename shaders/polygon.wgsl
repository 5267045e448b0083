// polygon.wgsl — special relativistic polygon rendering (§3.2), the baseline the paper compares
// against: every vertex is mapped through the photo-object map R (Eq. 8) and the apparent
// triangles are rasterised as straight triangles, with attributes interpolated linearly. Only as
// exact as the mesh is fine. Shading is the same as in lrt.wgsl; moving lights light the event a
// fragment shows at its interpolated apparent position.
//
// A body that spins or thrusts in its rest frame (motion.wgsl) is drawn the same way, vertex by
// vertex: each vertex shows the emission event of its material point on the observer's past
// light cone, ct′ = ct′_obs − |x(ct′) − o| with x the point's worldline (motion_position),
// found by a fixed-point step and secant steps (polygon_light_cone), then mapped to S as a point
// at rest is.
// A fragment shows the body point interpolated in the rest triangle, as for a body at rest: the
// emission event of that point (the same solve), shaded in the point's local rest frame there
// (moving_frame), with its own proper time.

// Most steps of a vertex's light-cone solve. The fixed-point step s ← g(s) = |x(ct′_obs − s) − o|
// shrinks the error by the point's speed v < 1 (|g′| ≤ v); a receding thrust's points near c
// make that slow, so steps after the first are secant steps on f(s) = g(s) − s (whose slope
// lies in [−1 − v, −1 + v]: never 0), falling back to the fixed-point step where the slope
// estimate is not that of a light-cone solve (rounding).
const POLYGON_LIGHT_CONE_STEPS: u32 = 32u;
// The solve stops where |f(s)| ≤ this fraction of (1 + s): a few f32 ulps, the precision of
// |x − o| itself.
const POLYGON_LIGHT_CONE_TOLERANCE: f32 = 4e-7;

struct PolygonVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) triangle: u32,
    // Barycentric (ζ, ξ) in the rest triangle.
    @location(1) barycentric: vec2<f32>,
    // Apparent position in S.
    @location(2) apparent: vec3<f32>,
    // Texture coordinates, for their screen derivatives only (polygon_uv).
    @location(3) uv: vec2<f32>,
}

// The backward ray parameter s of the emission event of the moving body's point `body` on the
// observer's past light cone: the root of f(s) = |x(ct′_obs − s) − o| − s (see the header and
// POLYGON_LIGHT_CONE_STEPS).
fn polygon_light_cone(body: vec3<f32>) -> f32 {
    let observer = object.frame.observer_rest.yzw;
    var previous = distance(body, observer);
    var previous_f = distance(motion_position(body, previous), observer) - previous;
    var s = previous + previous_f;
    for (var i = 0u; i < POLYGON_LIGHT_CONE_STEPS; i++) {
        let f = distance(motion_position(body, s), observer) - s;
        if (abs(f) <= POLYGON_LIGHT_CONE_TOLERANCE * (1.0 + s)) {
            break;
        }
        let slope = (f - previous_f) / (s - previous);
        var next = s + f;
        if (s != previous && slope < -1e-3) {
            next = s - f / slope;
        }
        if (!(next >= 0.0)) {
            next = s + f;
        }
        previous = s;
        previous_f = f;
        s = next;
    }
    return s;
}

// The emission event (rest coordinates) of the moving body's point `body` on the observer's past
// light cone: at S′ time ct′_obs − s, where the point is then.
fn polygon_moving_emission(body: vec3<f32>) -> vec4<f32> {
    let s = polygon_light_cone(body);
    return vec4<f32>(object.frame.observer_rest.x - s, motion_position(body, s));
}

// The emission event (rest coordinates) vertex `v` of the current part shows: its point's on
// the observer's past light cone (Eq. 7 for a body at rest, polygon_moving_emission else).
fn polygon_vertex_emission(v: u32) -> vec4<f32> {
    let rest = vertices[indices[v]].position.xyz;
    if (motion_kind() == MOTION_REST) {
        return emission_event(object.frame, rest);
    }
    return polygon_moving_emission(rest);
}

// The varyings of vertex `v` at the clip position `position`, its emission event in S
// (to_observer of polygon_vertex_emission) `event`.
fn polygon_varying(v: u32, position: vec4<f32>, event: vec4<f32>) -> PolygonVarying {
    let barycentric = array<vec2<f32>, 3>(vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0));
    return PolygonVarying(position, v / 3u, barycentric[v % 3u], event.yzw, vertices[indices[v]].uv.xy);
}

// Each vertex at its apparent position, the photo-object map R (Eq. 8), through the camera.
@vertex
fn polygon_vertex(@builtin(vertex_index) v: u32) -> PolygonVarying {
    let event = to_observer(object.frame, polygon_vertex_emission(v));
    return polygon_varying(v, frame_uniforms.view_projection * vec4<f32>(event.yzw, 1.0), event);
}

// The surface point a polygon fragment draws (the method's approximation of what the pixel
// sees): where it shows in S, its local rest frame and the events it is lit at.
struct PolygonPoint {
    apparent: vec3<f32>,
    local: LocalFrame,
    receiver: Receiver,
}

// The point of fragment `in`. For a body at rest: the interpolated apparent position, its
// emission event (Receiver.rest) solved only where asked (`with_emission`) or where a clock,
// a flipbook, a blinking emission (its proper time) or moving lights (its event in S) need it.
// For a spinning or thrusting body: the emission event of its interpolated body point, in the
// point's local rest frame there with its own proper time (motion.wgsl's moving_frame, which
// takes the event's backward ray parameter s = ct′_obs − ct′).
fn polygon_point(in: PolygonVarying, with_emission: bool) -> PolygonPoint {
    let b = in.barycentric;
    if (motion_kind() != MOTION_REST) {
        let p = triangle_corners(in.triangle);
        let body = (1.0 - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2];
        let s = polygon_light_cone(body);
        let emission = vec4<f32>(object.frame.observer_rest.x - s, motion_position(body, s));
        let local = moving_frame(in.triangle, b.x, b.y, s, emission);
        let event = to_observer(object.frame, emission);
        return PolygonPoint(event.yzw, local, Receiver(event, emission));
    }
    let timed = object.blink.x > 0.0 || has_clock() || part.frames > 1u;
    let lit = MOVING_LIGHTS && frame_uniforms.lights.counts.x > 0u;
    var emission = vec4<f32>(0.0);
    if (timed || lit || with_emission) {
        let p = triangle_corners(in.triangle);
        emission = emission_event(object.frame, (1.0 - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2]);
    }
    var proper_time = 0.0;
    if (timed || with_emission) {
        proper_time = proper_time_at(emission);
    }
    // The event the fragment shows, where the method draws it: on the observer's past light
    // cone at the interpolated apparent position (the shadow test of the object itself starts
    // from the interpolated rest point, which lies on its surface).
    var receiver = Receiver(vec4<f32>(0.0), emission);
    if (lit) {
        let observer_ct = to_observer(object.frame, object.frame.observer_rest).x;
        receiver.event = vec4<f32>(observer_ct - distance(in.apparent, frame_uniforms.observer.xyz), in.apparent);
    }
    return PolygonPoint(in.apparent, resting_frame(proper_time), receiver);
}

// The fragment's texture coordinates, interpolated, and their screen derivatives. The
// derivatives are taken of the interpolated varying, not of the coordinates read from the
// vertex buffer here: llvmpipe's helper invocations at a triangle's edges do not read storage
// buffers, so derivatives of what they read jumped to the coarsest mip level along every edge.
fn polygon_uv(in: PolygonVarying) -> SurfaceUv {
    let uv = triangle_uv(in.triangle, in.barycentric.x, in.barycentric.y);
    return SurfaceUv(uv, dpdx(in.uv), dpdy(in.uv));
}

// The albedo of the point `point` fragment `in` draws (surface_albedo at its proper time).
fn polygon_albedo(in: PolygonVarying, point: PolygonPoint) -> vec4<f32> {
    return surface_albedo(in.triangle, in.barycentric.x, in.barycentric.y, polygon_uv(in), point.local.proper_time);
}

@fragment
fn polygon_fragment(in: PolygonVarying) -> @location(0) vec4<f32> {
    let point = polygon_point(in, writes_seen_events());
    if (writes_seen_events()) {
        return seen_pixel(point.receiver.rest, point.local);
    }
    let b = in.barycentric;
    return shade(in.triangle, b.x, b.y, point.apparent, polygon_albedo(in, point), point.local, point.receiver);
}
