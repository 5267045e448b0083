// proxy.wgsl — §4.1: the conservative image-space footprint of every apparent triangle of one
// mesh part, one invocation per triangle. The f32 mirror of crates/srt-proxy (f64), with two
// additions: every footprint is dilated by FOOTPRINT_MARGIN pixels to absorb f32 rounding, so
// that it stays conservative (the validation checks it against the f64 apparent triangle); and
// the pieces of a split triangle (srt_proxy::split_pieces, a list there) are stored in footprint
// slots shared by the batch, or bounded by one rectangle when those run out.

// One footprint per triangle of the batch ([0, part.triangle_count)), then slots for the pieces
// of split triangles (split_footprint), taken in turn by draw_args[DRAW_ARGS_PIECES_TAKEN]. Each footprint names its
// triangle, so the LRT pass draws all of them in one draw.
@group(3) @binding(0) var<storage, read_write> footprints: array<Footprint>;

// A footprint as this pass makes it (srt_proxy::Footprint): the hull (a rectangle as its four
// corners) and, apart from what is stored (types.wgsl's Footprint), the rectangle of the six
// points, which bounds the triangle's image and so the screen bounds the footprint grows.
struct ProxyFootprint {
    hull: array<vec2<f32>, FOOTPRINT_HULL_POINTS>,
    // Rectangle min.xy, max.xy (zero for the zero value, which draws nothing).
    rect: vec4<f32>,
    // Valid hull points; 0 for a footprint that draws nothing.
    hull_len: u32,
    whole_screen: bool,
    // In a triangle's own slot: the piece slots ran out (split_footprint).
    pieces_overflowed: bool,
}
// The frame's screen bound, the union of every footprint's rectangle in whole pixels (of every
// part the pass is run over), for the LRT part-depth pass: (!min x, !min y, max x, max y) as
// draw_args[DRAW_ARGS_BOUND..] holds the part's. One buffer for the whole frame, cleared to 0
// (empty) before the pass.
@group(3) @binding(1) var<storage, read_write> frame_bound: array<atomic<u32>, 4>;
// The part's draw arguments and screen bound (types.wgsl's DRAW_ARGS_* say which word is
// what); the CPU writes both draws as (0, 1, 0, 0), no piece taken and an empty bound before the
// pass.
@group(3) @binding(2) var<storage, read_write> draw_args: array<atomic<u32>, DRAW_ARGS_WORDS>;

// Invocations per workgroup: set at pipeline creation from srt_gpu::shaders::WORKGROUP_SIZE.
override WORKGROUP_SIZE: u32;
// How many chord lengths a tangent intersection may lie from its chord's midpoint before the
// footprint is taken to be the whole screen: set at pipeline creation from
// srt_proxy::MAX_TANGENT_REACH.
override MAX_TANGENT_REACH: f32;
// How far from the screen's centre, in screen sizes, a footprint point may lie before the
// triangle is split instead: set from srt_proxy::MAX_SCREEN_REACH.
override MAX_SCREEN_REACH: f32;
// How many times split_footprint may halve a triangle (srt_proxy::MAX_SPLIT_DEPTH).
const MAX_SPLIT_DEPTH: u32 = 8u;
// The fraction of the screen above which a piece is split again, the hull-to-corners area
// ratio above which a hull is loose, and the fraction of near_bound at which a swept prism is
// clipped: set at pipeline creation from srt_proxy::SPLIT_AREA_FRACTION,
// srt_proxy::LOOSE_HULL_FACTOR and srt_proxy::NEAR_CLIP_FRACTION.
override SPLIT_AREA_FRACTION: f32;
override LOOSE_HULL_FACTOR: f32;
override NEAR_CLIP_FRACTION: f32;
// Clip-space w at or below which a point counts as at or behind the camera.
const MIN_CLIP_W: f32 = 1e-6;
// Outward dilation of rectangle and hull, in pixels.
const FOOTPRINT_MARGIN: f32 = 0.25;

// The whole picture's rectangle (min.xy, max.xy) in the target's pixels: the target itself
// unless it holds a window of a larger picture (frame_uniforms.picture). The "screen" every
// footprint rule below measures against, so that a tile's footprints are the whole picture's.
fn picture_rect() -> vec4<f32> {
    let lo = -frame_uniforms.picture.zw;
    return vec4<f32>(lo, lo + frame_uniforms.picture.xy);
}

// Pixel position of a point in S (xy) and whether it is in front of the camera and within
// MAX_SCREEN_REACH screens of the picture's centre (z = 1).
fn project_point(p: vec3<f32>) -> vec3<f32> {
    let clip = frame_uniforms.view_projection * vec4<f32>(p, 1.0);
    if (!(clip.w > MIN_CLIP_W)) {
        return vec3<f32>(0.0);
    }
    let ndc = clip.xy / clip.w;
    let screen = frame_uniforms.viewport.xy;
    let pixel = vec2<f32>((ndc.x + 1.0) * 0.5 * screen.x, (1.0 - ndc.y) * 0.5 * screen.y);
    let picture = picture_rect();
    let offset = abs(pixel - 0.5 * (picture.xy + picture.zw));
    if (!(max(offset.x, offset.y) <= MAX_SCREEN_REACH * max(frame_uniforms.picture.x, frame_uniforms.picture.y))) {
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
fn rectangle_footprint(lo: vec2<f32>, hi: vec2<f32>) -> ProxyFootprint {
    var f: ProxyFootprint;
    f.rect = vec4<f32>(lo, hi);
    f.hull[0] = lo;
    f.hull[1] = vec2<f32>(hi.x, lo.y);
    f.hull[2] = hi;
    f.hull[3] = vec2<f32>(lo.x, hi.y);
    f.hull_len = 4u;
    return f;
}

fn whole_screen_footprint() -> ProxyFootprint {
    let picture = picture_rect();
    var f = rectangle_footprint(picture.xy, picture.zw);
    f.whole_screen = true;
    return f;
}

// The six points P1, G12, P2, G23, P3, G31 of the apparent image of the rest triangle `rest`,
// projected to pixels (srt_proxy::tangent_footprint); false when one of them is at or behind
// the camera or more than MAX_SCREEN_REACH screens out, or a tangent intersection lies more
// than MAX_TANGENT_REACH chord lengths away (ill-conditioned in f32).
fn tangent_outline(rest: array<vec3<f32>, 3>, points: ptr<function, array<vec2<f32>, 6>>) -> bool {
    var corners: array<vec3<f32>, 3>;
    for (var i = 0u; i < 3u; i++) {
        corners[i] = apparent_position(object.frame, rest[i]);
    }
    for (var i = 0u; i < 3u; i++) {
        let j = (i + 1u) % 3u;
        let edge = rest[j] - rest[i];
        let ti = apparent_tangent(object.frame, rest[i], edge);
        let tj = apparent_tangent(object.frame, rest[j], -edge);
        let g = tangent_intersection(corners[i], ti, corners[j], tj);
        let pp = project_point(corners[i]);
        let pg = project_point(g);
        let far = length(g - 0.5 * (corners[i] + corners[j])) > MAX_TANGENT_REACH * length(corners[j] - corners[i]);
        if (pp.z == 0.0 || pg.z == 0.0 || far) {
            return false;
        }
        (*points)[2u * i] = pp.xy;
        (*points)[2u * i + 1u] = pg.xy;
    }
    return true;
}

// The six points of the swept prism of the rest triangle `rest` in clip space
// (srt_proxy::swept_prism, whose documentation proves that their convex hull holds the apparent
// triangle); false when the observer is at a corner's apparent position.
fn swept_prism_clip(rest: array<vec3<f32>, 3>, clip: ptr<function, array<vec4<f32>, 6>>) -> bool {
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
            return false;
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
    for (var k = 0u; k < 6u; k++) {
        let p = select(emission[k % 3u].yzw, start[k % 3u] + beta * latest, k >= 3u);
        (*clip)[k] = frame_uniforms.view_projection * vec4<f32>(p, 1.0);
    }
    return true;
}

// What near_bound returns for a hull nothing of which is on screen.
const NEAR_HIDDEN: f32 = -1.0;
// Relative size below which a plane's distance from the camera is taken for f32 rounding (the
// f64 srt_proxy uses 1e-9).
const PLANE_TOLERANCE: f32 = 1e-4;

// srt_proxy::near_bound in f32: the largest lower bound on clip w of the on-screen points of
// the convex hull of `clip`, NEAR_HIDDEN when none is on screen, 0 when no plane keeps the hull
// off the camera. Candidate planes (through the camera in (x, y, w)): x = 0, y = 0, w = 0, the
// view pyramid's four faces, and the planes through any three of the points, both ways round.
// The cone's extent along a direction is widened by PLANE_TOLERANCE·|n|, so that rounding can
// only lower the bound.
fn near_bound(clip: ptr<function, array<vec4<f32>, 6>>) -> f32 {
    var points: array<vec3<f32>, 6>;
    var reach = 0.0;
    for (var i = 0u; i < 6u; i++) {
        points[i] = (*clip)[i].xyw;
        reach = max(reach, length(points[i]));
    }
    if (!(reach < 3.0e38)) {
        return 0.0;
    }
    var best = 0.0;
    for (var candidate = 0u; candidate < 50u; candidate++) {
        var n: vec3<f32>;
        if (candidate < 10u) {
            let fixed = array<vec3<f32>, 10>(
                vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(-1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0),
                vec3<f32>(0.0, -1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0, 0.0, -1.0),
                vec3<f32>(1.0, 0.0, -1.0), vec3<f32>(-1.0, 0.0, -1.0), vec3<f32>(0.0, 1.0, -1.0),
                vec3<f32>(0.0, -1.0, -1.0));
            n = fixed[candidate];
        } else {
            // The 20 triples a < b < c of six points, each both ways round.
            let triple = (candidate - 10u) / 2u;
            let packed = array<u32, 20>(
                0x012u, 0x013u, 0x014u, 0x015u, 0x023u, 0x024u, 0x025u, 0x034u, 0x035u, 0x045u,
                0x123u, 0x124u, 0x125u, 0x134u, 0x135u, 0x145u, 0x234u, 0x235u, 0x245u, 0x345u);
            let abc = packed[triple];
            let a = points[abc >> 8u];
            let b = points[(abc >> 4u) & 15u];
            let c = points[abc & 15u];
            n = cross(b - a, c - a) * select(1.0, -1.0, candidate % 2u == 1u);
        }
        var m = 3.0e38;
        for (var i = 0u; i < 6u; i++) {
            m = min(m, dot(n, points[i]));
        }
        let size = length(n);
        if (!(m > PLANE_TOLERANCE * size * reach)) {
            continue;
        }
        let widest = abs(n.x) + abs(n.y) + n.z + PLANE_TOLERANCE * size;
        if (widest <= 0.0) {
            return NEAR_HIDDEN;
        }
        best = max(best, m / widest);
    }
    return best;
}

// The rectangle (min.xy, max.xy, in pixels, clamped to the screen) of the hull of `clip`
// clipped at w = near (srt_proxy::visible_rect): its points with w ≥ near and the crossings of
// w = near by the segments between points on either side. Empty (min ≥ max) when none.
fn clipped_rect(clip: ptr<function, array<vec4<f32>, 6>>, near: f32) -> vec4<f32> {
    var pixels_lo = vec2<f32>(3.0e38);
    var pixels_hi = vec2<f32>(-3.0e38);
    for (var a = 0u; a < 6u; a++) {
        if ((*clip)[a].w < near) {
            continue;
        }
        for (var b = 0u; b < 7u; b++) {
            // b = 6 stands for the point a itself; b < 6 for the crossing towards a point behind.
            var c = (*clip)[a];
            if (b < 6u) {
                if ((*clip)[b].w >= near) {
                    continue;
                }
                c = (*clip)[a] + ((*clip)[b] - (*clip)[a]) * ((near - (*clip)[a].w) / ((*clip)[b].w - (*clip)[a].w));
            }
            let w = max(c.w, near);
            let pixel = vec2<f32>((c.x / w + 1.0) * 0.5 * frame_uniforms.viewport.x, (1.0 - c.y / w) * 0.5 * frame_uniforms.viewport.y);
            pixels_lo = min(pixels_lo, pixel);
            pixels_hi = max(pixels_hi, pixel);
        }
    }
    let picture = picture_rect();
    return vec4<f32>(max(pixels_lo, picture.xy), min(pixels_hi, picture.zw));
}

// Area of a clamped rectangle (min.xy, max.xy); 0 when empty.
fn rect_area(r: vec4<f32>) -> f32 {
    let size = max(r.zw - r.xy, vec2<f32>(0.0));
    return size.x * size.y;
}

// Area of the polygon of the first `len` points of `points`.
fn polygon_area(points: array<vec2<f32>, 6>, len: u32) -> f32 {
    var twice = 0.0;
    for (var i = 0u; i < len; i++) {
        let a = points[i];
        let b = points[(i + 1u) % len];
        twice += a.x * b.y - a.y * b.x;
    }
    return 0.5 * abs(twice);
}

// The paper's footprint of the six points P1, G12, P2, G23, P3, G31 (pixels): their rectangle
// and convex hull, both dilated by FOOTPRINT_MARGIN.
fn hull_footprint(six: array<vec2<f32>, 6>) -> ProxyFootprint {
    var points = six;
    var f: ProxyFootprint;
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
        return rectangle_footprint(f.rect.xy, f.rect.zw);
    }
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
    return f;
}

// srt_proxy::Footprint::worth_splitting: footprint `f` of the six points `six` covers more than
// SPLIT_AREA_FRACTION of the screen and its hull is loose (LOOSE_HULL_FACTOR times the area of
// the triangle of the projected corners).
fn worth_splitting(f: ProxyFootprint, six: array<vec2<f32>, 6>) -> bool {
    let picture = picture_rect();
    let screen = frame_uniforms.picture.xy;
    let on_screen = vec4<f32>(max(f.rect.xy, picture.xy), min(f.rect.zw, picture.zw));
    if (!(rect_area(on_screen) > SPLIT_AREA_FRACTION * screen.x * screen.y)) {
        return false;
    }
    var hull: array<vec2<f32>, 6>;
    for (var i = 0u; i < 6u; i++) {
        hull[i] = f.hull[i];
    }
    let corners = array<vec2<f32>, 6>(six[0], six[2], six[4], vec2<f32>(0.0), vec2<f32>(0.0), vec2<f32>(0.0));
    return polygon_area(hull, f.hull_len) > LOOSE_HULL_FACTOR * polygon_area(corners, 3u);
}

// The halves of `piece` across the midpoint of its longest edge (srt_proxy's bisect).
fn bisect(piece: array<vec3<f32>, 3>) -> array<array<vec3<f32>, 3>, 2> {
    var longest = 0u;
    var length = -1.0;
    for (var i = 0u; i < 3u; i++) {
        let edge = piece[(i + 1u) % 3u] - piece[i];
        if (dot(edge, edge) > length) {
            length = dot(edge, edge);
            longest = i;
        }
    }
    let a = piece[longest];
    let b = piece[(longest + 1u) % 3u];
    let c = piece[(longest + 2u) % 3u];
    let middle = 0.5 * (a + b);
    return array<array<vec3<f32>, 3>, 2>(array<vec3<f32>, 3>(a, middle, c), array<vec3<f32>, 3>(middle, b, c));
}

// The footprint `f` as the visibility passes draw it: with the paper's rectangle footprints
// (FOOTPRINT_RECTANGLE) its rectangle, as four hull points; else its hull.
fn drawn_footprint(f: ProxyFootprint) -> ProxyFootprint {
    if (frame_uniforms.footprint_shape != FOOTPRINT_RECTANGLE || f.hull_len == 0u) {
        return f;
    }
    var r = rectangle_footprint(f.rect.xy, f.rect.zw);
    r.whole_screen = f.whole_screen;
    r.pieces_overflowed = f.pieces_overflowed;
    return r;
}

// The rectangle of the points of `f`'s hull: what the visibility passes draw of it lies inside.
fn hull_bounds(f: ProxyFootprint) -> vec4<f32> {
    var lo = f.hull[0];
    var hi = f.hull[0];
    for (var i = 1u; i < f.hull_len; i++) {
        lo = min(lo, f.hull[i]);
        hi = max(hi, f.hull[i]);
    }
    return vec4<f32>(lo, hi);
}

// Stores footprint `f` of triangle `triangle` in slot `slot` as it is drawn (drawn_footprint),
// grows the part's and the frame's screen bounds by its rectangle clamped to the screen and the
// draw's vertex count past `slot` (an empty footprint adds nothing).
fn store_footprint(slot: u32, triangle: u32, f: ProxyFootprint) {
    let drawn = drawn_footprint(f);
    var flags = drawn.hull_len;
    if (f.whole_screen) {
        flags |= FOOTPRINT_WHOLE_SCREEN;
    }
    if (f.pieces_overflowed) {
        flags |= FOOTPRINT_PIECES_OVERFLOWED;
    }
    footprints[slot] = Footprint(drawn.hull, triangle, footprint_depth, flags, 0u);
    let screen = frame_uniforms.viewport.xy;
    let lo = max(floor(f.rect.xy), vec2<f32>(0.0));
    let hi = min(ceil(f.rect.zw), screen);
    if (f.hull_len == 0u || !all(lo < hi)) {
        return;
    }
    atomicMax(&draw_args[DRAW_ARGS_FOOTPRINT_VERTICES], (slot + 1u) * FOOTPRINT_VERTICES);
    atomicMax(&draw_args[DRAW_ARGS_SHADE_VERTICES], 6u);
    let bound = vec4<u32>(~u32(lo.x), ~u32(lo.y), u32(hi.x), u32(hi.y));
    for (var k = 0u; k < 4u; k++) {
        atomicMax(&draw_args[DRAW_ARGS_BOUND + k], bound[k]);
        atomicMax(&frame_bound[k], bound[k]);
    }
}

// How far a footprint's nearest depth is lowered below the bound, as a fraction of
// γ·|w′|·(1 + |β|): the size of the terms from which the visibility passes compute a hit's
// depth γ s (1 − β·d′) in f32, so that their rounding (and the cancellation in 1 − β·d′ when
// looking along β) cannot put a hit in front of its footprint.
const NEAREST_MARGIN: f32 = 1e-4;
// How much further, in depth units, for the rasteriser's own rounding of a footprint's depth:
// the GL backend maps depth to [−1, 1] and back (about 10⁻⁸ seen on llvmpipe's GL).
const RASTER_DEPTH_MARGIN: f32 = 1e-6;

// The depth this invocation's footprints are drawn at (Footprint.nearest_depth), set by
// footprint_main before any is stored.
var<private> footprint_depth: f32;

// The depth the footprints of the triangle with corners `rest` (in S′) are drawn at: a lower
// bound of its apparent distance (of the whole part's for an enclosing box, whose fragments'
// hits lie inside it), less the margins above, in depth units.
fn nearest_depth(rest: array<vec3<f32>, 3>) -> f32 {
    var distance: f32;
    if (part_has(PART_ENCLOSING_BOX)) {
        distance = box_nearest_distance();
    } else {
        distance = triangle_nearest_distance(rest);
    }
    return clamp(distance * frame_uniforms.depth_scale - RASTER_DEPTH_MARGIN, 0.0, 1.0);
}

// The bounds below, as srt_proxy::nearest_apparent_distance, which proves them: for |u| ≤ 1,
// r(w′) = γ (|w′| − β·w′) ≥ γ (u − β)·w′, which is linear and so least over a convex hull at
// one of its points; u runs over the directions to the points and to their centroid. Each is
// lowered by NEAREST_MARGIN of γ·|w′|·(1 + |β|) and is at least 0.

// w′ / |w′|, or 0 for w′ = 0 (|u| ≤ 1 is all the bound needs).
fn bound_direction(w: vec3<f32>) -> vec3<f32> {
    return w * inverseSqrt(max(dot(w, w), 1e-30));
}

// The bound's last step: γ·(best − margin), at least 0, for points within `reach` of the
// observer.
fn lowered_bound(best: f32, reach: f32) -> f32 {
    let beta_gamma = object.frame.beta_gamma;
    return max(beta_gamma.w * (best - NEAREST_MARGIN * reach * (1.0 + length(beta_gamma.xyz))), 0.0);
}

// The bound over the triangle with corners `corners` (in S′).
fn triangle_nearest_distance(corners: array<vec3<f32>, 3>) -> f32 {
    let origin = object.frame.observer_rest.yzw;
    let beta = object.frame.beta_gamma.xyz;
    let w0 = corners[0] - origin;
    let w1 = corners[1] - origin;
    let w2 = corners[2] - origin;
    let axes = array<vec3<f32>, 4>(w0, w1, w2, w0 + w1 + w2);
    var best = 0.0;
    for (var i = 0u; i < 4u; i++) {
        let u = bound_direction(axes[i]) - beta;
        best = max(best, min(min(dot(u, w0), dot(u, w1)), dot(u, w2)));
    }
    return lowered_bound(best, max(max(length(w0), length(w1)), length(w2)));
}

// The bound over the part's corners (an enclosing box: its 8 vertices).
fn box_nearest_distance() -> f32 {
    let origin = object.frame.observer_rest.yzw;
    let beta = object.frame.beta_gamma.xyz;
    let count = min(arrayLength(&vertices), 8u);
    var corners: array<vec3<f32>, 8>;
    var centroid = vec3<f32>(0.0);
    var reach = 0.0;
    for (var k = 0u; k < count; k++) {
        corners[k] = vertices[k].position.xyz - origin;
        centroid += corners[k];
        reach = max(reach, length(corners[k]));
    }
    var best = 0.0;
    for (var i = 0u; i <= count; i++) {
        let axis = select(centroid, corners[min(i, count - 1u)], i < count);
        let u = bound_direction(axis) - beta;
        var least = 3.0e38;
        for (var k = 0u; k < count; k++) {
            least = min(least, dot(u, corners[k]));
        }
        best = max(best, least);
    }
    return lowered_bound(best, reach);
}

// Stores `f` as a piece of triangle `t` in the next free piece slot; false when none is left.
fn store_piece(t: u32, f: ProxyFootprint) -> bool {
    let slot = part.triangle_count + atomicAdd(&draw_args[DRAW_ARGS_PIECES_TAKEN], 1u);
    if (slot >= arrayLength(&footprints)) {
        return false;
    }
    store_footprint(slot, t, f);
    return true;
}

// Pieces on split_footprint's stack: each halving replaces one by two.
const SPLIT_STACK: u32 = MAX_SPLIT_DEPTH + 1u;

// Splits triangle `t` (corners `rest` in S′) as srt_proxy::split_pieces does, whose
// documentation says why the pieces are conservative, and stores them: the first in the
// triangle's own slot, the others in piece slots. When the piece slots run out, the triangle's
// own slot gets the rectangle holding all its pieces as drawn instead (srt_proxy::split_footprint); when
// a piece MAX_SPLIT_DEPTH deep may reach the camera, the whole screen.
fn split_footprint(t: u32, rest: array<vec3<f32>, 3>) {
    let picture = picture_rect();
    let split_area = SPLIT_AREA_FRACTION * frame_uniforms.picture.x * frame_uniforms.picture.y;
    var stack: array<array<vec3<f32>, 3>, SPLIT_STACK>;
    var depths: array<u32, SPLIT_STACK>;
    stack[0] = rest;
    depths[0] = 0u;
    var size = 1u;
    var union_lo = vec2<f32>(3.0e38);
    var union_hi = vec2<f32>(-3.0e38);
    var own = ProxyFootprint();
    var kept = 0u;
    var all_stored = true;
    while (size > 0u) {
        size--;
        let piece = stack[size];
        let depth = depths[size];
        var f: ProxyFootprint;
        var split = false;
        var points: array<vec2<f32>, 6>;
        if (tangent_outline(piece, &points)) {
            f = hull_footprint(points);
            split = worth_splitting(f, points);
        } else {
            var clip: array<vec4<f32>, 6>;
            var bound = 0.0;
            if (swept_prism_clip(piece, &clip)) {
                bound = near_bound(&clip);
            }
            if (bound == NEAR_HIDDEN) {
                continue;
            }
            var rect = vec4<f32>(0.0);
            if (bound > 0.0) {
                rect = clipped_rect(&clip, NEAR_CLIP_FRACTION * bound);
            }
            split = bound == 0.0 || rect_area(rect) > split_area;
            if (!split || depth == MAX_SPLIT_DEPTH) {
                if (bound == 0.0) {
                    store_footprint(t, t, whole_screen_footprint());
                    return;
                }
                if (!all(rect.xy < rect.zw)) {
                    continue;
                }
                let lo = max(rect.xy - FOOTPRINT_MARGIN, picture.xy);
                let hi = min(rect.zw + FOOTPRINT_MARGIN, picture.zw);
                f = rectangle_footprint(lo, hi);
            }
        }
        if (split && depth < MAX_SPLIT_DEPTH) {
            let halves = bisect(piece);
            stack[size] = halves[0];
            stack[size + 1u] = halves[1];
            depths[size] = depth + 1u;
            depths[size + 1u] = depth + 1u;
            size += 2u;
            continue;
        }
        // A kept piece: skip it when nothing of it is on this target.
        let lo = max(f.rect.xy, vec2<f32>(0.0));
        let hi = min(f.rect.zw, frame_uniforms.viewport.xy);
        if (!all(lo < hi)) {
            continue;
        }
        // The fallback holds what the piece would have drawn.
        let drawn = hull_bounds(drawn_footprint(f));
        union_lo = min(union_lo, max(drawn.xy, vec2<f32>(0.0)));
        union_hi = max(union_hi, min(drawn.zw, frame_uniforms.viewport.xy));
        if (kept == 0u) {
            own = f;
        } else if (all_stored) {
            all_stored = store_piece(t, f);
        }
        kept++;
    }
    if (!all_stored) {
        own = rectangle_footprint(union_lo, union_hi);
        own.pieces_overflowed = true;
    }
    store_footprint(t, t, own);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn footprint_main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    // Large parts are dispatched as a 2D grid of workgroups.
    let t = id.x + id.y * groups.x * WORKGROUP_SIZE;
    if (t >= part.triangle_count) {
        return;
    }
    let rest = triangle_corners(t);
    // A wide projection has no screen-space footprint of the pinhole: only the ray tracer's
    // boxes come here (srt_gpu::Method::cannot_draw), and the box's first triangle covers the
    // rectangle of the picture where the object may be seen (object.view_bound), so that each
    // pixel there traces the object's BVH once, whatever its direction.
    // A stereo pair's rays leave from two eyes: the same, over the whole picture, drawn at
    // depth 0 (the bound is the observer's, not the eyes').
    let stereo = frame_uniforms.eye_separation >= 0.0;
    if (frame_uniforms.projection != PROJECTION_PERSPECTIVE || stereo) {
        footprint_depth = select(nearest_depth(rest), 0.0, stereo);
        if (t == 0u) {
            let picture = picture_rect();
            let bound = object.view_bound - vec4<f32>(frame_uniforms.picture.zw, frame_uniforms.picture.zw);
            store_footprint(t, t, rectangle_footprint(max(bound.xy, picture.xy), min(bound.zw, picture.zw)));
        } else {
            store_footprint(t, t, ProxyFootprint());
        }
        return;
    }
    // Back-face culling in S′, exact for closed meshes: every viewing ray starts at the
    // observer's rest-frame position, so a triangle facing away from it is hidden behind the
    // rest of the solid. An empty footprint draws nothing.
    if (part_has(PART_CULL_BACK_FACES) && dot(cross(rest[1] - rest[0], rest[2] - rest[0]), object.frame.observer_rest.yzw - rest[0]) <= 0.0) {
        store_footprint(t, t, ProxyFootprint());
        return;
    }
    footprint_depth = nearest_depth(rest);
    // Six points P1, G12, P2, G23, P3, G31, projected: the paper's footprint, unless it cannot
    // be made or is loose and large.
    var points: array<vec2<f32>, 6>;
    if (tangent_outline(rest, &points)) {
        let f = hull_footprint(points);
        if (!worth_splitting(f, points)) {
            store_footprint(t, t, f);
            return;
        }
    }
    split_footprint(t, rest);
}
