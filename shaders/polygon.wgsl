// polygon.wgsl — special relativistic polygon rendering (§3.2), the baseline the paper compares
// against: every vertex is mapped through the photo-object map R (Eq. 8) and the apparent
// triangles are rasterised as straight triangles, with attributes interpolated linearly. Only as
// exact as the mesh is fine. Shading is the same as in lrt.wgsl; moving lights light the event a
// fragment shows at its interpolated apparent position.

struct PolygonVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) triangle: u32,
    // Barycentric (ζ, ξ) in the rest triangle.
    @location(1) barycentric: vec2<f32>,
    // Apparent position in S.
    @location(2) apparent: vec3<f32>,
}

@vertex
fn polygon_vertex(@builtin(vertex_index) v: u32) -> PolygonVarying {
    let t = v / 3u;
    let k = v % 3u;
    let rest = vertices[indices[v]].position.xyz;
    let apparent = apparent_position(object.frame, rest);
    let barycentric = array<vec2<f32>, 3>(vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0));
    return PolygonVarying(frame_uniforms.view_projection * vec4<f32>(apparent, 1.0), t, barycentric[k], apparent);
}

// The emission event (rest coordinates) of the rest point a fragment draws: the method's
// approximation of what the pixel sees.
fn polygon_emission(in: PolygonVarying) -> vec4<f32> {
    let p = triangle_corners(in.triangle);
    let b = in.barycentric;
    let rest = (1.0 - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2];
    return emission_event(object.frame, rest);
}

@fragment
fn polygon_fragment(in: PolygonVarying) -> @location(0) vec4<f32> {
    if (writes_seen_events()) {
        let emission = polygon_emission(in);
        return seen_pixel(emission, resting_frame(proper_time_at(emission)));
    }
    // Only a clock, a flipbook or a blinking emission needs the fragment's proper time, and only
    // moving lights' shadows its emission event (one light-cone solve).
    let timed = object.blink.x > 0.0 || has_clock() || part.frames > 1u;
    let lit = MOVING_LIGHTS && lights.counts.x > 0u;
    var emission = vec4<f32>(0.0);
    if (timed || lit) {
        emission = polygon_emission(in);
    }
    var proper_time = 0.0;
    if (timed) {
        proper_time = proper_time_at(emission);
    }
    let uv = triangle_uv(in.triangle, in.barycentric.x, in.barycentric.y);
    let uv_ddx = dpdx(uv);
    let uv_ddy = dpdy(uv);
    let albedo = surface_albedo(in.triangle, in.barycentric.x, in.barycentric.y, uv_ddx, uv_ddy, proper_time);
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
