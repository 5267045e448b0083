// lrt.wgsl — local ray tracing (§4.2, Algorithm 1) in two passes over the footprints of the
// proxy pass, drawn as FOOTPRINT_VERTICES vertices per triangle (WebGPU has no geometry
// shader). In both, every fragment traces its own viewing ray in the triangle's rest frame S′
// (Eq. 3, 5, 15–16).
//
// 1. Visibility (`lrt_visibility`): a hit writes the apparent distance (Eq. 7–8) as depth and the
//    triangle's id (part id, triangle) — the depth test keeps the nearest.
// 2. Part depth (`id_depth_vertex`, `id_depth`): one rectangle, the frame's screen bound (the
//    union of every footprint's rectangle, `frame_bound`), writes per pixel the depth of the part
//    the visibility pass kept there (`part_depth`; 0 where none, and outside the rectangle,
//    where no footprint reached, the target stays cleared to 0).
// 3. Shading (`part_bound_vertex`, `lrt_shade`): one rectangle per part, its screen bound, drawn
//    at the part's depth with the depth test "equal": only the pixels where the visibility pass
//    kept a triangle of this part pass, and they pass before the fragment shader runs, so the
//    rest of the rectangle costs no shading (on a software rasteriser a fragment that ran and
//    then stopped cost almost as much as one shaded). Each pixel is shaded once, however deep
//    the model, and the footprints are rasterised once.
//
// Mirror: crates/srt-trace (Tracer::trace and Tracer::shade for a single triangle).

@group(3) @binding(0) var<storage, read> footprints: array<Footprint>;
// Fragments run by the visibility pass ([0]), fragments shaded by the shading pass ([1]), and
// visibility fragments whose hit came out nearer than the depth their footprint was drawn at
// ([2]: Footprint.nearest_depth, which must bound it; a test requires none).
@group(3) @binding(1) var<storage, read_write> fragment_count: array<atomic<u32>, 3>;
// Whether fragments are counted in fragment_count: set at pipeline creation by
// srt_gpu::shaders::lrt(counting), true only for measurements (global atomics per fragment
// contend on a real GPU).
override COUNT_FRAGMENTS: bool;
// The part's draw arguments and screen bound written by the proxy pass (types.wgsl's
// DRAW_ARGS_*): the shading pass draws the bound.
@group(3) @binding(2) var<storage, read> part_draw_args: array<u32, DRAW_ARGS_WORDS>;
// The triangle the visibility pass kept at each pixel: (part id, triangle), (0, 0) for none.
// Bound only for the shading pass (the visibility pass renders into it).
@group(0) @binding(2) var visible_ids: texture_2d<u32>;
// The frame's screen bound written by the proxy pass (see proxy.wgsl): the part-depth pass
// draws it. Bound only for the part-depth and shading passes.
@group(0) @binding(13) var<storage, read> frame_bound: array<u32, 4>;

// What a fragment of the visibility passes (LRT's and the ray tracer's) or of LRT's shading pass
// needs of its draw, read once per vertex and carried flat rather than read per fragment: Mesa's
// llvmpipe reads a storage buffer in a fragment shader one lane at a time, and these reads were
// most of an LRT visibility fragment's cost (docs/performance-log.md, 2026-11-27, fourth entry).
// Flat varyings carry the values bit for bit, so every fragment computes what it did from the
// buffers. A hardware GPU pays for these varyings on every footprint vertex instead: there the
// entry points `*_lean` carry only LeanVarying and each fragment reads the rest (full_varying;
// srt_gpu::pipelines::Varyings picks per adapter).
struct LrtVarying {
    @builtin(position) position: vec4<f32>,
    // The footprint's triangle and the part's id.
    @location(0) @interpolate(flat) triangle_part: vec2<u32>,
    // The triangle's corners in S′ (LRT's footprints; zero for the ray tracer's boxes).
    @location(1) @interpolate(flat) corner0: vec3<f32>,
    @location(2) @interpolate(flat) corner1: vec3<f32>,
    @location(3) @interpolate(flat) corner2: vec3<f32>,
    // The camera (ViewCamera): forward and the depth scale, right and 1/width, up and 1/height.
    @location(4) @interpolate(flat) forward_depth_scale: vec4<f32>,
    @location(5) @interpolate(flat) right_inverse_width: vec4<f32>,
    @location(6) @interpolate(flat) up_inverse_height: vec4<f32>,
    // The object's frame as the ray and the depth need it: β and γ, the observation event in S′.
    @location(7) @interpolate(flat) beta_gamma: vec4<f32>,
    @location(8) @interpolate(flat) observer_rest: vec4<f32>,
}

// What a fragment of the lean entry points receives: the position and (triangle, part id).
struct LeanVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) triangle_part: vec2<u32>,
}

// The lean varyings of `v`.
fn lean_varying(v: LrtVarying) -> LeanVarying {
    return LeanVarying(v.position, v.triangle_part);
}

// The varyings the flat entry points would have received, read from the buffers: the triangle's
// corners where `with_corners` (LRT's visibility; the ray tracer's boxes and the shading pass's
// bounds name no triangle). The same values, bit for bit.
fn full_varying(in: LeanVarying, with_corners: bool) -> LrtVarying {
    var corners = NO_CORNERS;
    if (with_corners) {
        corners = triangle_corners(in.triangle_part.x);
    }
    return draw_varying(in.position, in.triangle_part.x, corners);
}

struct VisibilityOutput {
    @location(0) id: vec2<u32>,
    @builtin(frag_depth) depth: f32,
}

// Footprint corner `v` (0 to FOOTPRINT_VERTICES − 1: the fan of the hull, a rectangle's two
// triangles first) in pixels; the fan's spare triangles are degenerate at hull point 0.
fn footprint_corner(f: Footprint, v: u32) -> vec2<f32> {
    let triangle = v / 3u;
    let corner = v % 3u;
    if (triangle + 2u >= (f.flags & FOOTPRINT_HULL_LEN)) {
        return f.hull[0];
    }
    return f.hull[select(0u, triangle + corner, corner > 0u)];
}

// Vertex `index` of the footprints, with the draw's flat data; the triangle's corners where
// `with_corners` (LRT; the ray tracer's box names no triangle).
fn footprint_vertex(index: u32, with_corners: bool) -> LrtVarying {
    // A triangle's own slot or a piece of a split triangle: the footprint names the triangle.
    let f = footprints[index / FOOTPRINT_VERTICES];
    let pixel = footprint_corner(f, index % FOOTPRINT_VERTICES);
    let ndc = vec2<f32>(2.0 * pixel.x * frame_uniforms.viewport.z - 1.0, 1.0 - 2.0 * pixel.y * frame_uniforms.viewport.w);
    var corners = NO_CORNERS;
    if (with_corners) {
        corners = triangle_corners(f.triangle);
    }
    return draw_varying(vec4<f32>(ndc, f.nearest_depth, 1.0), f.triangle, corners);
}

// The corners a draw that names no triangle carries.
const NO_CORNERS = array<vec3<f32>, 3>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));

// The varyings of a vertex at `position` of a draw for triangle `triangle` with corners
// `corners`: the part's id, the camera and the object's frame.
fn draw_varying(position: vec4<f32>, triangle: u32, corners: array<vec3<f32>, 3>) -> LrtVarying {
    let camera = frame_camera();
    return LrtVarying(
        position,
        vec2<u32>(triangle, part.id),
        corners[0],
        corners[1],
        corners[2],
        vec4<f32>(camera.forward, frame_uniforms.depth_scale),
        vec4<f32>(camera.right, camera.inverse_size.x),
        vec4<f32>(camera.up, camera.inverse_size.y),
        object.frame.beta_gamma,
        object.frame.observer_rest,
    );
}

// The LRT visibility pass's vertices: footprints of triangles.
@vertex
fn lrt_vertex(@builtin(vertex_index) index: u32) -> LrtVarying {
    return footprint_vertex(index, true);
}

// lrt_vertex with lean varyings (the fragment reads the corners).
@vertex
fn lrt_vertex_lean(@builtin(vertex_index) index: u32) -> LeanVarying {
    return lean_varying(footprint_vertex(index, false));
}

// The ray tracer's visibility pass's vertices: the footprints of objects' boxes.
@vertex
fn box_vertex(@builtin(vertex_index) index: u32) -> LrtVarying {
    return footprint_vertex(index, false);
}

// box_vertex with lean varyings.
@vertex
fn box_vertex_lean(@builtin(vertex_index) index: u32) -> LeanVarying {
    return lean_varying(footprint_vertex(index, false));
}

// The backward viewing ray through the fragment's pixel in S′ (backward_ray with view_direction),
// from the draw's flat data.
fn varying_ray(in: LrtVarying) -> RestRay {
    let camera = ViewCamera(
        in.forward_depth_scale.xyz,
        in.right_inverse_width.xyz,
        in.up_inverse_height.xyz,
        vec2<f32>(in.right_inverse_width.w, in.up_inverse_height.w),
    );
    // A stereo pair's ray leaves from its eye; one picture's (every other frame's, on the hot
    // path of every visibility fragment) from the observer, with no more work.
    var observer_rest = in.observer_rest;
    if (is_stereo()) {
        observer_rest += rest_displacement(in.beta_gamma, eye_offset(in.position.xy));
    }
    return backward_ray_of(in.beta_gamma, observer_rest, camera_view_direction(camera, in.position.xy));
}

// A backward viewing ray in S′, the rest-frame corners of a triangle and the ray's hit with it.
struct LrtHit {
    ray: RestRay,
    corners: array<vec3<f32>, 3>,
    hit: TriangleHit,
}

// `ray`'s hit with the triangle `corners`, with both.
fn ray_hit(ray: RestRay, corners: array<vec3<f32>, 3>) -> LrtHit {
    return LrtHit(ray, corners, intersect_triangle(ray.origin, ray.direction, corners));
}

@fragment
fn lrt_visibility(in: LrtVarying) -> VisibilityOutput {
    return lrt_visible(in);
}

@fragment
fn lrt_visibility_lean(in: LeanVarying) -> VisibilityOutput {
    return lrt_visible(full_varying(in, true));
}

// The LRT visibility fragment: its ray's hit with the footprint's triangle, or a discard.
fn lrt_visible(in: LrtVarying) -> VisibilityOutput {
    if (COUNT_FRAGMENTS) {
        atomicAdd(&fragment_count[0], 1u);
    }
    let h = ray_hit(varying_ray(in), array<vec3<f32>, 3>(in.corner0, in.corner1, in.corner2));
    if (!h.hit.found) {
        discard;
    }
    return visible(in, vec2<u32>(in.triangle_part.y, in.triangle_part.x), h.ray, h.hit.distance);
}

// What the visibility passes (this one and rt.wgsl's) write for the triangle `id` (part id,
// triangle) hit at `distance` along `ray`: the id, and its apparent distance (Eq. 7–8) as depth.
fn visible(in: LrtVarying, id: vec2<u32>, ray: RestRay, distance: f32) -> VisibilityOutput {
    var out: VisibilityOutput;
    out.id = id;
    out.depth = clamp(apparent_distance_of(in.beta_gamma, ray, distance) * in.forward_depth_scale.w, 0.0, 1.0);
    if (COUNT_FRAGMENTS && out.depth < in.position.z) {
        atomicAdd(&fragment_count[2], 1u);
    }
    return out;
}

// Parts' ids per depth unit: part `id` is drawn and kept at depth id / 2²⁴, exact in f32 for every
// id below 2²⁴ (ids count from 1; 0, the cleared depth, is "no part").
const PART_DEPTH_UNITS: f32 = 16777216.0;

// The depth at which part `id` is shaded (see the header: step 2 writes it, step 3 tests it).
fn part_depth(id: u32) -> f32 {
    return f32(id) / PART_DEPTH_UNITS;
}

// Corner `v` (0 to 5) of the screen bound (!min x, !min y, max x, max y) as two triangles at
// depth `depth`; an empty bound (min > max) is made degenerate.
fn bound_corner(bound: vec4<u32>, v: u32, depth: f32) -> vec4<f32> {
    let lo = vec2<f32>(f32(~bound.x), f32(~bound.y));
    let hi = vec2<f32>(f32(bound.z), f32(bound.w));
    let far = select(lo, hi, all(lo < hi));
    let corners = array<vec2<f32>, 6>(lo, vec2<f32>(far.x, lo.y), far, lo, far, vec2<f32>(lo.x, far.y));
    let pixel = corners[min(v, 5u)];
    let ndc = vec2<f32>(2.0 * pixel.x * frame_uniforms.viewport.z - 1.0, 1.0 - 2.0 * pixel.y * frame_uniforms.viewport.w);
    return vec4<f32>(ndc, depth, 1.0);
}

// The frame's screen bound (step 2): only where some footprint reached can a part be kept.
@vertex
fn id_depth_vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return bound_corner(vec4<u32>(frame_bound[0], frame_bound[1], frame_bound[2], frame_bound[3]), v, 0.0);
}

// The depth of the part the visibility pass kept at this pixel (step 2).
@fragment
fn id_depth(@builtin(position) position: vec4<f32>) -> @builtin(frag_depth) f32 {
    return part_depth(textureLoad(visible_ids, vec2<i32>(position.xy), 0).x);
}

// The part's screen bound as two triangles, drawn by the shading pass (after the ray tracer:
// the bound of the object's box).
@vertex
fn part_bound_vertex(@builtin(vertex_index) v: u32) -> LrtVarying {
    return part_bound_varying(v);
}

// part_bound_vertex with lean varyings.
@vertex
fn part_bound_vertex_lean(@builtin(vertex_index) v: u32) -> LeanVarying {
    return lean_varying(part_bound_varying(v));
}

// Corner `v` of the part's screen bound, with the draw's varyings.
fn part_bound_varying(v: u32) -> LrtVarying {
    let b = DRAW_ARGS_BOUND;
    let bound = vec4<u32>(part_draw_args[b], part_draw_args[b + 1u], part_draw_args[b + 2u], part_draw_args[b + 3u]);
    return draw_varying(bound_corner(bound, v, part_depth(part.id)), 0u, NO_CORNERS);
}

@fragment
fn lrt_shade(in: LrtVarying) -> @location(0) vec4<f32> {
    return shaded(in);
}

@fragment
fn lrt_shade_lean(in: LeanVarying) -> @location(0) vec4<f32> {
    return shaded(full_varying(in, false));
}

// The viewing direction through the pixel `step` away from `pixel` (from the same eye of a
// stereo pair), for texture differentials; beyond a fisheye's rim, `pixel`'s own (no footprint
// that way, as the CPU takes it).
fn neighbour_direction(pixel: vec2<f32>, step: vec2<f32>) -> vec3<f32> {
    let neighbour = neighbour_view_direction(pixel, step);
    if (all(neighbour == vec3<f32>(0.0))) {
        return view_direction(pixel);
    }
    return neighbour;
}

// The colour of the shading pass's fragment: the kept triangle's, shaded.
fn shaded(in: LrtVarying) -> vec4<f32> {
    let pixel = in.position.xy;
    // The eye this pixel's ray leaves from (surface.wgsl's directions towards the observer).
    stereo_eye = eye_offset(pixel);
    // The depth test let only this part's pixels through (the header's step 3). The counting
    // variant's atomic is a side effect, which makes the test run after the shader: there the id
    // decides (and only there: a discard would keep the test late in the normal variant too).
    let kept = textureLoad(visible_ids, vec2<i32>(pixel), 0).xy;
    if (COUNT_FRAGMENTS) {
        if (kept.x != part.id) {
            discard;
        }
        atomicAdd(&fragment_count[1], 1u);
    }
    let t = kept.y;
    // The same computation as in the visibility pass, so the same hit; for a spinning or
    // thrusting body the same march (motion.wgsl), on the kept triangle alone.
    let h = ray_hit(varying_ray(in), triangle_corners(t));
    var corners = h.corners;
    var hit = h.hit;
    let moving = motion_kind() != MOTION_REST;
    if (moving) {
        hit = moving_hit_on(h.ray, h.corners);
        corners = moving_corners(h.corners, hit.distance);
    }
    let emission = vec4<f32>(h.ray.ct_origin - hit.distance, h.ray.origin + hit.distance * h.ray.direction);
    var local = resting_frame(proper_time_at(emission));
    if (moving) {
        local = moving_frame(t, hit.zeta, hit.xi, hit.distance, emission);
    }
    if (writes_seen_events()) {
        return seen_pixel(emission, local);
    }
    // Texture coordinates, and their differentials from the neighbouring pixels' rays (as the
    // CPU does), on the triangle where it is at the event.
    var uv = SurfaceUv(vec2<f32>(0.0), vec2<f32>(0.0), vec2<f32>(0.0));
    if (part_is_textured() || has_clock()) {
        let uvs = triangle_uvs(t);
        uv.uv = uv_at(uvs, hit.zeta, hit.xi);
        if (object.style.x <= 0.0) {
            // The neighbours' rays start where this pixel's does; only their directions differ.
            let plane = plane_rays(h.ray.origin, corners);
            let hx = plane_barycentric(plane, rest_propagation_unscaled(object.frame, neighbour_direction(pixel, vec2<f32>(1.0, 0.0))));
            let hy = plane_barycentric(plane, rest_propagation_unscaled(object.frame, neighbour_direction(pixel, vec2<f32>(0.0, 1.0))));
            uv.ddx = select(vec2<f32>(0.0), uv_at(uvs, hx.zeta, hx.xi) - uv.uv, hx.found);
            uv.ddy = select(vec2<f32>(0.0), uv_at(uvs, hy.zeta, hy.xi) - uv.uv, hy.found);
        }
    }
    let event = to_observer(object.frame, emission);
    let albedo = surface_albedo(t, hit.zeta, hit.xi, uv, local.proper_time);
    return shade(t, hit.zeta, hit.xi, event.yzw, albedo, local, Receiver(event, emission));
}
