// sky.wgsl — the sky, in two passes (mirror: crates/srt-trace/src/sky.rs).
//
// 1. `sky_star_peaks` and `sky_stars` (compute, one invocation per star each): the star's
//    aberrated direction and Doppler factor (distant_source_image, Eq. 4), its light (the colour
//    table at D·T, weighted by its magnitude and, with the searchlight effect, by 1/D² for its
//    shrunken solid angle) as the frame's output holds it (light.wgsl: display colour or
//    radiance) and its tent splat over the four pixels around its exact image position. The
//    first pass finds each pixel's largest contribution (its peak), the second adds every
//    contribution to `star_light` in fixed point scaled to that peak: integer additions are exact
//    and commute, so the sum does not depend on the order in which invocations run, and a pixel
//    keeps 24 bits of precision whatever the range of light across the image (radiance spans
//    many orders of magnitude).
// 2. `sky_compose` (a full-screen triangle): background + the sky image (looked up along the
//    pixel's viewing ray taken back into the sky's frame, its light Doppler-shifted like a
//    surface's) + star light, as output_pixel writes it, into the colour target: in a pass of
//    its own (`sky_compose_vertex`), or in the object pass after the objects, only where none is
//    seen (`sky_behind_polygons_vertex`, `sky_where_unseen_vertex`), so that the pixels the
//    objects cover are not composed for nothing.

// Read-only storage, not uniform, as in render_bindings.wgsl (which says why).
@group(0) @binding(0) var<storage, read> frame_uniforms: FrameUniforms;
@group(0) @binding(1) var lut_table: texture_2d<f32>;

@group(1) @binding(0) var<storage, read> sky: SkyUniforms;
@group(1) @binding(1) var<storage, read> stars: array<Star>;
// Star light per pixel (row-major, STAR_LIGHT_WORDS_PER_PIXEL words each): the peak (the f32
// bits of the largest channel magnitude any contribution has there: non-negative floats order
// as their bits), then R, G, B as i32 sums in units of 2^(e − STAR_LIGHT_BITS), 2^e the power of
// two just above the peak.
@group(1) @binding(2) var<storage, read_write> star_light: array<atomic<u32>>;
// The same buffer, read by the compose pass.
@group(1) @binding(3) var<storage, read> star_light_total: array<u32>;
// The equirectangular sky image, linear RGB (1 × 1 black without one).
@group(1) @binding(4) var sky_image: texture_2d<f32>;

override WORKGROUP_SIZE: u32;
// The colour temperature of a sky image's light (srt_scene::sky::SKY_IMAGE_WHITE_K).
override SKY_IMAGE_WHITE_K: f32;

// u32 words of star light per pixel: the peak, then R, G, B (twin of
// srt_gpu::sky::STAR_LIGHT_WORDS_PER_PIXEL).
const STAR_LIGHT_WORDS_PER_PIXEL: u32 = 4u;

// Bits of a pixel's fixed point below its peak's power of two: each contribution is under 2²⁴
// units, so 127 of the largest fit an i32 sum, and each is resolved to 2⁻²⁴ of the peak.
const STAR_LIGHT_BITS: i32 = 24;

// Peaks below 2⁻¹⁰⁰ count as no light (their scale 2^(STAR_LIGHT_BITS − e) must stay within f32).
const STAR_LIGHT_SMALLEST_PEAK: f32 = 7.8886091e-31;

// The light a star adds (mirror of srt_trace::star_light).
fn star_arriving(star: Star, doppler: f32) -> Arriving {
    var d = doppler;
    var solid_angle = 1.0;
    if (frame_uniforms.effects == EFFECTS_GEOMETRY) {
        d = 1.0;
    } else if (frame_uniforms.effects == EFFECTS_SEARCHLIGHT) {
        solid_angle = 1.0 / (doppler * doppler);
    }
    let weight = pow(10.0, -0.4 * (star.magnitude.x - sky.beta_saturation.w));
    return table_light(weight * solid_angle, d * star.direction_temperature.w);
}

// Where a star lands and what it adds: the output pixel of its splat's lower corner (output
// pixels are sky.supersampling.x target pixels a side), the tent weights' fractions, and its
// light as the frame's output holds it; visible = false when it is behind the camera (or there
// is no star: invocation_splat).
struct StarSplat {
    visible: bool,
    base: vec2<f32>,
    fraction: vec2<f32>,
    light: vec3<f32>,
    // The target pixels it may light (min x, min y, max x, max y): its eye's picture.
    bounds: vec4<f32>,
}

// The splat of star `i` in the picture of `eye` (0: the whole picture; −1, +1: that eye's half
// of a stereo pair; see StarSplat).
fn star_splat(i: u32, eye: f32) -> StarSplat {
    let star = stars[i];
    let rest = normalize(sky.direction_map * star.direction_temperature.xyz);
    let image = distant_source_image(sky.beta_saturation.xyz, rest);
    let projected = project_direction(image.direction, eye);
    let corner = projected.xy / f32(sky.supersampling.x) - vec2<f32>(0.5);
    let base = floor(corner);
    let light = arriving_output(star_arriving(star, image.doppler));
    return StarSplat(projected.z != 0.0, base, corner - base, light, eye_bounds(eye));
}

// Target pixel `k` of the splat `s`, and what the star adds there; index = −1 outside the
// image.
struct SplatPixel {
    index: i32,
    added: vec3<f32>,
}

// How many target pixels a splat lights: the four output pixels of the tent, each of
// sky.supersampling.x² target pixels.
fn splat_pixel_count() -> u32 {
    let scale = sky.supersampling.x;
    return 4u * scale * scale;
}

// Target pixel `k` (below splat_pixel_count()) of the splat `s` (see SplatPixel): the star adds
// its output pixel's tent weight of its light to each target pixel of that output pixel.
fn splat_pixel(s: StarSplat, k: u32) -> SplatPixel {
    let scale = sky.supersampling.x;
    let corner = k / (scale * scale);
    let sub = k % (scale * scale);
    let offset = vec2<f32>(f32(corner & 1u), f32(corner >> 1u));
    let p = (s.base + offset) * f32(scale) + vec2<f32>(f32(sub % scale), f32(sub / scale));
    let size = frame_uniforms.viewport.xy;
    if (any(p < max(s.bounds.xy, vec2<f32>(0.0))) || any(p >= min(s.bounds.zw, size))) {
        return SplatPixel(-1, vec3<f32>(0.0));
    }
    let w = select(1.0 - s.fraction, s.fraction, offset == vec2<f32>(1.0));
    return SplatPixel(i32(u32(p.y) * u32(size.x) + u32(p.x)), w.x * w.y * s.light);
}

// The exponent e of the power of two 2^e just above `peak` (≥ STAR_LIGHT_SMALLEST_PEAK, a
// normal f32 m·2^(e−1) with m in [1, 2)), read from its bits.
fn peak_exponent(peak: f32) -> i32 {
    return i32((bitcast<u32>(peak) >> 23u) & 0xffu) - 126;
}

// The splat of the star invocation `id` handles (see StarSplat): one per star, or per star and
// eye of a stereo pair (the pass is dispatched for twice the stars); not visible past the last.
fn invocation_splat(id: vec3<u32>, groups: vec3<u32>) -> StarSplat {
    let i = id.x + id.y * groups.x * WORKGROUP_SIZE;
    let count = sky.counts.x;
    let eyes = select(1u, 2u, is_stereo());
    if (i >= count * eyes) {
        return StarSplat(false, vec2<f32>(0.0), vec2<f32>(0.0), vec3<f32>(0.0), vec4<f32>(0.0));
    }
    var eye = 0.0;
    if (is_stereo()) {
        eye = select(-1.0, 1.0, i >= count);
    }
    return star_splat(i % count, eye);
}

// Pass 1: each pixel's peak, the largest channel magnitude of any star's contribution there.
@compute @workgroup_size(WORKGROUP_SIZE)
fn sky_star_peaks(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = invocation_splat(id, groups);
    if (!s.visible) {
        return;
    }
    for (var k = 0u; k < splat_pixel_count(); k++) {
        let pixel = splat_pixel(s, k);
        let magnitude = abs(pixel.added);
        let peak = max(magnitude.x, max(magnitude.y, magnitude.z));
        if (pixel.index >= 0 && peak >= STAR_LIGHT_SMALLEST_PEAK && all_finite(magnitude)) {
            atomicMax(&star_light[STAR_LIGHT_WORDS_PER_PIXEL * u32(pixel.index)], bitcast<u32>(peak));
        }
    }
}

// Pass 2: every contribution added in its pixel's fixed point.
@compute @workgroup_size(WORKGROUP_SIZE)
fn sky_stars(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = invocation_splat(id, groups);
    if (!s.visible) {
        return;
    }
    for (var k = 0u; k < splat_pixel_count(); k++) {
        let pixel = splat_pixel(s, k);
        if (pixel.index < 0) {
            continue;
        }
        let first = STAR_LIGHT_WORDS_PER_PIXEL * u32(pixel.index);
        let peak = bitcast<f32>(atomicLoad(&star_light[first]));
        if (!(peak >= STAR_LIGHT_SMALLEST_PEAK) || !all_finite(pixel.added)) {
            continue;
        }
        let scale = exp2(f32(STAR_LIGHT_BITS - peak_exponent(peak)));
        for (var c = 0u; c < 3u; c++) {
            atomicAdd(&star_light[first + 1u + c], bitcast<u32>(i32(round(pixel.added[c] * scale))));
        }
    }
}

// The star light of pixel `pixel` (row-major index) in units of output.
fn star_light_at(pixel: u32) -> vec3<f32> {
    let first = STAR_LIGHT_WORDS_PER_PIXEL * pixel;
    let peak = bitcast<f32>(star_light_total[first]);
    if (!(peak >= STAR_LIGHT_SMALLEST_PEAK)) {
        return vec3<f32>(0.0);
    }
    let sums = vec3<f32>(
        f32(bitcast<i32>(star_light_total[first + 1u])),
        f32(bitcast<i32>(star_light_total[first + 2u])),
        f32(bitcast<i32>(star_light_total[first + 3u])),
    );
    return sums * exp2(f32(peak_exponent(peak) - STAR_LIGHT_BITS));
}

// Corner `v` (0 to 2) of one triangle covering the viewport, at depth `depth`.
fn viewport_triangle(v: u32, depth: f32) -> vec4<f32> {
    let corner = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(2.0 * corner - vec2<f32>(1.0), depth, 1.0);
}

// The compose triangle in a pass of its own (srt_gpu::sky::SkyPlacement::OwnPass).
@vertex
fn sky_compose_vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return viewport_triangle(v, 0.5);
}

// The compose triangle in the polygon pass, after the objects (SkyPlacement::BehindPolygons):
// at the far plane, the depth the pass clears to, under the depth test "equal", so that only
// the pixels no triangle was drawn over are composed.
@vertex
fn sky_behind_polygons_vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return viewport_triangle(v, 1.0);
}

// The compose triangle in the exact methods' shading pass (SkyPlacement::WhereUnseen): at
// depth 0, lrt.wgsl's part_depth of "no part", under the depth test "equal", so that only the
// pixels where the visibility pass kept nothing are composed.
@vertex
fn sky_where_unseen_vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return viewport_triangle(v, 0.0);
}

// Texture coordinates of the unit direction `d` in W (mirror of SkyImage::uv):
// u = ½ + atan2(y, x)/2π wrapped to [0, 1), v = ½ − asin(z)/π.
fn sky_image_uv(d: vec3<f32>) -> vec2<f32> {
    let u = 0.5 + atan2(d.y, d.x) / (2.0 * PI);
    let v = 0.5 - asin(clamp(d.z, -1.0, 1.0)) / PI;
    return vec2<f32>(u - floor(u), v);
}

// The image's texel at column `i` (wrapped) and row `j` (at most the last).
fn sky_image_texel(i: f32, j: f32, size: vec2<f32>) -> vec3<f32> {
    let column = i - size.x * floor(i / size.x);
    let row = min(j, size.y - 1.0);
    return textureLoad(sky_image, vec2<i32>(i32(column), i32(row)), 0).rgb;
}

// Radiance in the unit direction `d` in W: bilinear between the texel centres around it,
// wrapping in longitude, clamped at the poles (mirror of SkyImage::sample).
fn sky_image_sample(d: vec3<f32>) -> vec3<f32> {
    let size = vec2<f32>(f32(sky.counts.y), f32(sky.counts.z));
    let uv = sky_image_uv(d);
    let x = uv.x * size.x - 0.5;
    let y = clamp(uv.y * size.y - 0.5, 0.0, size.y - 1.0);
    let x0 = floor(x);
    let y0 = floor(y);
    let f = vec2<f32>(x - x0, y - y0);
    let top = (1.0 - f.x) * sky_image_texel(x0, y0, size) + f.x * sky_image_texel(x0 + 1.0, y0, size);
    let bottom = (1.0 - f.x) * sky_image_texel(x0, y0 + 1.0, size) + f.x * sky_image_texel(x0 + 1.0, y0 + 1.0, size);
    return (1.0 - f.y) * top + f.y * bottom;
}

// The light the sky image shows along the viewing direction `direction` in S (mirror of
// srt_trace::sky_image_light): the light of a black body at SKY_IMAGE_WHITE_K filtered by the
// texel, seen with Doppler factor D — the paper's colour: 𝒢 × the colour table at D·T; spectral
// colour: the texel's spectrum under that black body, shifted by D, its largest channel s its
// factor.
fn sky_image_light(direction: vec3<f32>) -> Arriving {
    if (sky.counts.w == 0u) {
        return dark_light();
    }
    let back = distant_source_image(-sky.beta_saturation.xyz, normalize(direction));
    let world = normalize(sky.direction_unmap * back.direction);
    let radiance = sky_image_sample(world) * sky.image.x;
    var doppler = 1.0 / back.doppler;
    if (frame_uniforms.effects == EFFECTS_GEOMETRY) {
        doppler = 1.0;
    }
    if (frame_uniforms.colour == SURFACE_COLOUR_PAPER) {
        return table_light(grey_value(vec4<f32>(radiance, 1.0)), doppler * SKY_IMAGE_WHITE_K);
    }
    let brightness = max(max(radiance.x, radiance.y), radiance.z);
    if (!(brightness > 0.0)) {
        return dark_light();
    }
    let reflected = spectral_linear_reflected(radiance / brightness, -1.0, -1.0, SKY_IMAGE_WHITE_K, 1.0, doppler);
    return spectrum_light(reflected, brightness);
}

@fragment
fn sky_compose(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    // Where no object is seen, the seen-event outputs write their "nothing" (the background).
    if (frame_uniforms.output == OUTPUT_SEEN_EVENT || frame_uniforms.output == OUTPUT_SEEN_OBJECT) {
        return frame_uniforms.background;
    }
    // Alpha 0: no object is seen here (srt_gpu::GpuImage::pixels).
    let unseen = vec4<f32>(1.0, 1.0, 1.0, 0.0);
    // Outside a fisheye's circle the picture sees nothing: the background alone.
    if (sees_nothing(position.xy)) {
        return unseen * output_pixel(frame_uniforms.background.rgb);
    }
    let stars = star_light_at(u32(position.y) * u32(frame_uniforms.viewport.x) + u32(position.x));
    let image = arriving_output(sky_image_light(view_direction(position.xy)));
    return unseen * output_pixel(frame_uniforms.background.rgb + image + stars);
}
