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

@vertex
fn polygon_vertex(@builtin(vertex_index) v: u32) -> PolygonVarying {
    let t = v / 3u;
    let k = v % 3u;
    let rest = vertices[indices[v]].position.xyz;
    var apparent = vec3<f32>(0.0);
    if (motion_kind() == MOTION_REST) {
        apparent = apparent_position(object.frame, rest);
    } else {
        apparent = to_observer(object.frame, polygon_moving_emission(rest)).yzw;
    }
    let barycentric = array<vec2<f32>, 3>(vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0));
    return PolygonVarying(frame_uniforms.view_projection * vec4<f32>(apparent, 1.0), t, barycentric[k], apparent);
}

// The emission event (rest coordinates) of the rest point a fragment draws: the method's
// approximation of what the pixel sees.
fn polygon_emission(in: PolygonVarying) -> vec4<f32> {
    let p = triangle_corners(in.triangle);
    let b = in.barycentric;
    let rest = (1.0 - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2];
    if (motion_kind() != MOTION_REST) {
        return polygon_moving_emission(rest);
    }
    return emission_event(object.frame, rest);
}

// The fragment's texture coordinates, interpolated, and their screen derivatives.
fn polygon_uv(in: PolygonVarying) -> SurfaceUv {
    let uv = triangle_uv(in.triangle, in.barycentric.x, in.barycentric.y);
    return SurfaceUv(uv, dpdx(uv), dpdy(uv));
}

@fragment
fn polygon_fragment(in: PolygonVarying) -> @location(0) vec4<f32> {
    if (motion_kind() != MOTION_REST) {
        return polygon_moving_fragment(in);
    }
    if (writes_seen_events()) {
        let emission = polygon_emission(in);
        return seen_pixel(emission, resting_frame(proper_time_at(emission)));
    }
    // Only a clock, a flipbook or a blinking emission needs the fragment's proper time, and only
    // moving lights' shadows its emission event (one light-cone solve).
    let timed = object.blink.x > 0.0 || has_clock() || part.frames > 1u;
    let lit = MOVING_LIGHTS && frame_uniforms.lights.counts.x > 0u;
    var emission = vec4<f32>(0.0);
    if (timed || lit) {
        emission = polygon_emission(in);
    }
    var proper_time = 0.0;
    if (timed) {
        proper_time = proper_time_at(emission);
    }
    let albedo = surface_albedo(in.triangle, in.barycentric.x, in.barycentric.y, polygon_uv(in), proper_time);
    // The event the fragment shows, where the method draws it: on the observer's past light
    // cone at the interpolated apparent position (the shadow test of the object itself starts
    // from the interpolated rest point, which lies on its surface).
    var receiver = Receiver(vec4<f32>(0.0), emission);
    if (lit) {
        let observer_ct = to_observer(object.frame, object.frame.observer_rest).x;
        receiver.event = vec4<f32>(observer_ct - distance(in.apparent, frame_uniforms.observer.xyz), in.apparent);
    }
    return shade(in.triangle, in.barycentric.x, in.barycentric.y, in.apparent, albedo, resting_frame(proper_time), receiver);
}

// A fragment of a spinning or thrusting body: the emission event of its interpolated body
// point, shaded in the point's local rest frame there with its own proper time (motion.wgsl's
// moving_frame, which takes the event's backward ray parameter s = ct′_obs − ct′).
fn polygon_moving_fragment(in: PolygonVarying) -> vec4<f32> {
    let p = triangle_corners(in.triangle);
    let b = in.barycentric;
    let body = (1.0 - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2];
    let s = polygon_light_cone(body);
    let emission = vec4<f32>(object.frame.observer_rest.x - s, motion_position(body, s));
    let local = moving_frame(in.triangle, in.barycentric.x, in.barycentric.y, s, emission);
    if (writes_seen_events()) {
        return seen_pixel(emission, local);
    }
    let albedo = surface_albedo(in.triangle, in.barycentric.x, in.barycentric.y, polygon_uv(in), local.proper_time);
    let event = to_observer(object.frame, emission);
    return shade(in.triangle, in.barycentric.x, in.barycentric.y, event.yzw, albedo, local, Receiver(event, emission));
}
