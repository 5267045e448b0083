// proxy.wgsl — §4.1: the conservative image-space footprint of every apparent triangle of one
// mesh part, one invocation per triangle. The f32 mirror of crates/srt-proxy (f64), with one
// addition: the result is dilated by FOOTPRINT_MARGIN pixels to absorb f32 rounding, so that it
// stays conservative (the validation checks it against the f64 footprint).

@group(3) @binding(0) var<storage, read_write> footprints: array<Footprint>;
// The part's screen bound, the union of its footprints' rectangles in whole pixels, for the LRT
// shading pass: (!min x, !min y, max x, max y) so that all four grow by atomicMax from the
// cleared value 0 (which reads as empty: min > max).
@group(3) @binding(1) var<storage, read_write> part_bound: array<atomic<u32>, 4>;
// The arguments of the part's two indirect draws, each (vertex count, instance count, first
// vertex, first instance); the CPU writes (0, 1, 0, 0) to both before the pass. [0..4] is the
// footprint draw of the LRT visibility pass: its vertex count grows to the end of the last
// triangle with a footprint on screen (FOOTPRINT_VERTICES per triangle). [4..8] is the LRT
// shading pass's rectangle: 6 vertices once any footprint is on screen. So a part wholly off
// screen or behind the camera draws nothing in either pass.
@group(3) @binding(2) var<storage, read_write> draw_args: array<atomic<u32>, 8>;

// Invocations per workgroup: set at pipeline creation from srt_gpu::shaders::WORKGROUP_SIZE.
override WORKGROUP_SIZE: u32;
// How many chord lengths a tangent intersection may lie from its chord's midpoint before the
// footprint is taken to be the whole screen: set at pipeline creation from
// srt_proxy::MAX_TANGENT_REACH.
override MAX_TANGENT_REACH: f32;
// Clip-space w at or below which a point counts as at or behind the camera.
const MIN_CLIP_W: f32 = 1e-6;
// Outward dilation of rectangle and hull, in pixels.
const FOOTPRINT_MARGIN: f32 = 0.25;

// Pixel position of a point in S (xy) and whether it is in front of the camera (z = 1).
fn project_point(p: vec3<f32>) -> vec3<f32> {
    let clip = frame_uniforms.view_projection * vec4<f32>(p, 1.0);
    if (!(clip.w > MIN_CLIP_W)) {
        return vec3<f32>(0.0);
    }
    let ndc = clip.xy / clip.w;
    let pixel = vec2<f32>((ndc.x + 1.0) * 0.5 * frame_uniforms.viewport.x, (1.0 - ndc.y) * 0.5 * frame_uniforms.viewport.y);
    if (!(abs(pixel.x) < 1e30 && abs(pixel.y) < 1e30)) {
        return vec3<f32>(0.0);
    }
    return vec3<f32>(pixel, 1.0);
}

// Intersection of the coplanar lines a + s·ta and b + t·tb; the midpoint when parallel.
fn tangent_intersection(a: vec3<f32>, ta: vec3<f32>, b: vec3<f32>, tb: vec3<f32>) -> vec3<f32> {
    let n = cross(ta, tb);
    let n2 = dot(n, n);
    if (n2 <= 1e-12 * dot(ta, ta) * dot(tb, tb)) {
        return 0.5 * (a + b);
    }
    let s = dot(cross(b - a, tb), n) / n2;
    return a + s * ta;
}

// Whether a → b → c turns counter-clockwise (y-up reading) by more than rounding: the cross
// product (b − a) × (c − a) must exceed HULL_COLLINEAR·|b − a|·|c − a|. Tested exactly against
// 0, a compiler that contracts u.x·v.y − u.y·v.x into a fused multiply-add (NVIDIA's does;
// llvmpipe's does not) leaves one product's rounding error where the cross product of two
// equal vectors is 0, so duplicate points stayed in the hull and their zero-length edges made
// its dilation NaN (seen in `cargo xtask validate` on an H100 for degenerate triangles). The
// tolerance, four f32 rounding units, is above that error; a point it drops lies within
// HULL_COLLINEAR·|b − a| of the line a → c, far inside FOOTPRINT_MARGIN.
const HULL_COLLINEAR: f32 = 2.4e-7;
fn turns_left(a: vec2<f32>, b: vec2<f32>, c: vec2<f32>) -> bool {
    let u = b - a;
    let v = c - a;
    return u.x * v.y - u.y * v.x > HULL_COLLINEAR * length(u) * length(v);
}

// The footprint whose rectangle and hull are the rectangle from `lo` to `hi`.
fn rectangle_footprint(lo: vec2<f32>, hi: vec2<f32>) -> Footprint {
    var f: Footprint;
    f.rect = vec4<f32>(lo, hi);
    f.hull[0] = lo;
    f.hull[1] = vec2<f32>(hi.x, lo.y);
    f.hull[2] = hi;
    f.hull[3] = vec2<f32>(lo.x, hi.y);
    f.hull_len = 4u;
    f.whole_screen = 0u;
    return f;
}

fn whole_screen_footprint() -> Footprint {
    var f = rectangle_footprint(vec2<f32>(0.0), frame_uniforms.viewport.xy);
    f.whole_screen = 1u;
    return f;
}

// The footprint of a triangle the tangent construction cannot bound (a point at or behind the
// camera, or an ill-conditioned tangent intersection): the rectangle of the on-screen part of its
// swept prism, clamped to the screen (srt_proxy::swept_prism and srt_proxy::visible_rect, whose
// documentation proves it conservative); empty when nothing of it can be seen, the whole screen
// when the prism may reach the camera.
fn swept_footprint(rest: array<vec3<f32>, 3>) -> Footprint {
    let beta = object.frame.beta_gamma.xyz;
    let observer = frame_uniforms.observer.xyz;
    var emission: array<vec4<f32>, 3>;
    var start: array<vec3<f32>, 3>;
    var slope: array<vec3<f32>, 3>;
    var latest_corner = -3.0e38;
    for (var i = 0u; i < 3u; i++) {
        emission[i] = to_observer(object.frame, emission_event(object.frame, rest[i]));
        // Where the corner is at ct = 0, and the gradient −n/(1 + n·β) of its emission time.
        start[i] = emission[i].yzw - beta * emission[i].x;
        let to_point = emission[i].yzw - observer;
        let reach = length(to_point);
        if (!(reach > 0.0)) {
            return whole_screen_footprint();
        }
        let n = to_point / reach;
        slope[i] = -n / (1.0 + dot(n, beta));
        latest_corner = max(latest_corner, emission[i].x);
    }
    var latest = 3.0e38;
    for (var i = 0u; i < 3u; i++) {
        var highest = -3.0e38;
        for (var j = 0u; j < 3u; j++) {
            highest = max(highest, emission[i].x + dot(slope[i], start[j] - start[i]));
        }
        latest = min(latest, highest);
    }
    latest = max(latest, latest_corner);
    var clip: array<vec4<f32>, 6>;
    var lo = vec4<f32>(3.0e38);
    var hi = vec4<f32>(-3.0e38);
    // Signed distances to the camera plane and the four side planes of the view pyramid: a
    // plane with all six points behind it hides the prism.
    var all_beyond = vec4<bool>(true);
    var all_behind = true;
    for (var k = 0u; k < 6u; k++) {
        let p = select(emission[k % 3u].yzw, start[k % 3u] + beta * latest, k >= 3u);
        let c = frame_uniforms.view_projection * vec4<f32>(p, 1.0);
        clip[k] = c;
        lo = min(lo, c);
        hi = max(hi, c);
        all_beyond = all_beyond & (vec4<f32>(c.w - c.x, c.w + c.x, c.w - c.y, c.w + c.y) < vec4<f32>(0.0));
        all_behind = all_behind && c.w < 0.0;
    }
    if (all_behind || any(all_beyond)) {
        return Footprint();
    }
    let clearance = max(max(max(lo.x, -hi.x), max(lo.y, -hi.y)), lo.w);
    if (!(clearance > 0.0 && clearance < 3.0e38)) {
        return whole_screen_footprint();
    }
    let near = 0.5 * clearance;
    var pixels_lo = vec2<f32>(3.0e38);
    var pixels_hi = vec2<f32>(-3.0e38);
    for (var a = 0u; a < 6u; a++) {
        if (clip[a].w < near) {
            continue;
        }
        for (var b = 0u; b < 7u; b++) {
            // b = 6 stands for the point a itself; b < 6 for the crossing towards a point behind.
            var c = clip[a];
            if (b < 6u) {
                if (clip[b].w >= near) {
                    continue;
                }
                c = clip[a] + (clip[b] - clip[a]) * ((near - clip[a].w) / (clip[b].w - clip[a].w));
            }
            let w = max(c.w, near);
            let pixel = vec2<f32>((c.x / w + 1.0) * 0.5 * frame_uniforms.viewport.x, (1.0 - c.y / w) * 0.5 * frame_uniforms.viewport.y);
            pixels_lo = min(pixels_lo, pixel);
            pixels_hi = max(pixels_hi, pixel);
        }
    }
    let screen = frame_uniforms.viewport.xy;
    let rect_lo = max(pixels_lo - FOOTPRINT_MARGIN, vec2<f32>(0.0));
    let rect_hi = min(pixels_hi + FOOTPRINT_MARGIN, screen);
    if (!all(rect_lo < rect_hi)) {
        return Footprint();
    }
    return rectangle_footprint(rect_lo, rect_hi);
}

// Stores footprint `f` of triangle `t`, grows the part's screen bound by its rectangle clamped
// to the screen and the draw's vertex count past `t` (an empty footprint adds nothing).
fn store_footprint(t: u32, f: Footprint) {
    footprints[t] = f;
    let screen = frame_uniforms.viewport.xy;
    let lo = max(floor(f.rect.xy), vec2<f32>(0.0));
    let hi = min(ceil(f.rect.zw), screen);
    if (f.hull_len == 0u || !all(lo < hi)) {
        return;
    }
    atomicMax(&draw_args[0], (t + 1u) * FOOTPRINT_VERTICES);
    atomicMax(&draw_args[4], 6u);
    atomicMax(&part_bound[0], ~u32(lo.x));
    atomicMax(&part_bound[1], ~u32(lo.y));
    atomicMax(&part_bound[2], u32(hi.x));
    atomicMax(&part_bound[3], u32(hi.y));
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn footprint_main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    // Large parts are dispatched as a 2D grid of workgroups.
    let t = id.x + id.y * groups.x * WORKGROUP_SIZE;
    if (t >= part.triangle_count) {
        return;
    }
    let rest = triangle_corners(t);
    // Back-face culling in S′, exact for closed meshes: every viewing ray starts at the
    // observer's rest-frame position, so a triangle facing away from it is hidden behind the
    // rest of the solid. An empty footprint draws nothing.
    if (part_has(PART_CULL_BACK_FACES) && dot(cross(rest[1] - rest[0], rest[2] - rest[0]), object.frame.observer_rest.yzw - rest[0]) <= 0.0) {
        store_footprint(t, Footprint());
        return;
    }
    var corners: array<vec3<f32>, 3>;
    for (var i = 0u; i < 3u; i++) {
        corners[i] = apparent_position(object.frame, rest[i]);
    }
    // Six points P1, G12, P2, G23, P3, G31, projected.
    var points: array<vec2<f32>, 6>;
    for (var i = 0u; i < 3u; i++) {
        let j = (i + 1u) % 3u;
        let edge = rest[j] - rest[i];
        let ti = apparent_tangent(object.frame, rest[i], edge);
        let tj = apparent_tangent(object.frame, rest[j], -edge);
        let g = tangent_intersection(corners[i], ti, corners[j], tj);
        let pp = project_point(corners[i]);
        let pg = project_point(g);
        // A tangent intersection far beyond its chord is ill-conditioned in f32: whole screen.
        let far = length(g - 0.5 * (corners[i] + corners[j])) > MAX_TANGENT_REACH * length(corners[j] - corners[i]);
        if (pp.z == 0.0 || pg.z == 0.0 || far) {
            store_footprint(t, swept_footprint(rest));
            return;
        }
        points[2u * i] = pp.xy;
        points[2u * i + 1u] = pg.xy;
    }
    var f: Footprint;
    var lo = points[0];
    var hi = points[0];
    for (var i = 1u; i < 6u; i++) {
        lo = min(lo, points[i]);
        hi = max(hi, points[i]);
    }
    f.rect = vec4<f32>(lo - FOOTPRINT_MARGIN, hi + FOOTPRINT_MARGIN);
    // Andrew's monotone chain on six points: insertion sort by (x, y), then both chains.
    // No array is indexed before the bound that makes the index valid has been tested in an
    // earlier statement: `a && b[i - 1]` may be evaluated in full by a shader compiler (naga
    // emits both operands for GLSL, and an out-of-range read there is undefined behaviour that
    // llvmpipe's GLSL compiler optimised into a wrong sort, hence wrong hulls on wgpu's GL
    // backend).
    for (var i = 1u; i < 6u; i++) {
        let p = points[i];
        var j = i;
        while (j > 0u) {
            let q = points[j - 1u];
            if (!(q.x > p.x || (q.x == p.x && q.y > p.y))) {
                break;
            }
            points[j] = q;
            j--;
        }
        points[j] = p;
    }
    var chain: array<vec2<f32>, 12>;
    var k = 0u;
    for (var i = 0u; i < 6u; i++) {
        while (k >= 2u) {
            if (turns_left(chain[k - 2u], chain[k - 1u], points[i])) {
                break;
            }
            k--;
        }
        chain[k] = points[i];
        k++;
    }
    let lower = k + 1u;
    for (var n = 0u; n < 5u; n++) {
        let i = 4u - n;
        while (k >= lower) {
            if (turns_left(chain[k - 2u], chain[k - 1u], points[i])) {
                break;
            }
            k--;
        }
        chain[k] = points[i];
        k++;
    }
    let len = min(k - 1u, FOOTPRINT_HULL_POINTS);
    if (len < 3u) {
        // Degenerate in f32: fall back to the (dilated, hence non-empty) rectangle.
        f = rectangle_footprint(f.rect.xy, f.rect.zw);
    } else {
        // Dilate: move each vertex along its miter so both adjacent edges shift outward.
        for (var i = 0u; i < len; i++) {
            let prev = chain[(i + len - 1u) % len];
            let here = chain[i];
            let next = chain[(i + 1u) % len];
            let e1 = normalize(here - prev);
            let e2 = normalize(next - here);
            // Outward normals of a counter-clockwise polygon (y-up reading): (e.y, −e.x).
            let n1 = vec2<f32>(e1.y, -e1.x);
            let n2 = vec2<f32>(e2.y, -e2.x);
            let miter = (n1 + n2) / max(1.0 + dot(n1, n2), 1e-3);
            f.hull[i] = here + FOOTPRINT_MARGIN * miter;
        }
        f.hull_len = len;
    }
    f.whole_screen = 0u;
    store_footprint(t, f);
}
