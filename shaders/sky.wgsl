// sky.wgsl — the sky, in two passes (mirror: crates/srt-trace/src/sky.rs).
//
// 1. `sky_stars` (compute, one invocation per star): the star's aberrated direction and Doppler
//    factor (distant_source_image, Eq. 4), its colour (the colour table at D·T, weighted by its
//    magnitude and, with the searchlight effect, by 1/D² for its shrunken solid angle) and its
//    tent splat over the four pixels around its exact image position, added to `star_light` in
//    fixed point: integer additions are exact and commute, so the sum does not depend on the
//    order in which invocations run.
// 2. `sky_compose_vertex`, `sky_compose` (a full-screen triangle): background + the sky image
//    (looked up along the pixel's viewing ray taken back into the sky's frame, its light
//    Doppler-shifted like a surface's) + star light, clamped, into the colour target; the object
//    passes then draw over it.

@group(0) @binding(0) var<uniform> frame_uniforms: FrameUniforms;
@group(0) @binding(1) var lut_table: texture_2d<f32>;

@group(1) @binding(0) var<uniform> sky: SkyUniforms;
@group(1) @binding(1) var<storage, read> stars: array<Star>;
// Star light per pixel and channel (row-major, 3 per pixel) in units of 1/STAR_LIGHT_SCALE.
@group(1) @binding(2) var<storage, read_write> star_light: array<atomic<u32>>;
// The same buffer, read by the compose pass.
@group(1) @binding(3) var<storage, read> star_light_total: array<u32>;
// The equirectangular sky image, linear RGB (1 × 1 black without one).
@group(1) @binding(4) var sky_image: texture_2d<f32>;

override WORKGROUP_SIZE: u32;
// The colour temperature of a sky image's light (srt_scene::sky::SKY_IMAGE_WHITE_K).
override SKY_IMAGE_WHITE_K: f32;

const PI: f32 = 3.14159265358979;

// Fixed-point units per unit of display colour: 2⁻¹⁴ ≈ 6e-5 per added contribution (a 64th of
// an 8-bit step), and up to 2¹⁸ full contributions per pixel before the u32 sum wraps.
const STAR_LIGHT_SCALE: f32 = 16384.0;

// The display colour a star adds (mirror of srt_trace::star_colour).
fn star_colour(star: Star, doppler: f32) -> vec3<f32> {
    var d = doppler;
    var solid_angle = 1.0;
    if (frame_uniforms.effects == EFFECTS_GEOMETRY) {
        d = 1.0;
    } else if (frame_uniforms.effects == EFFECTS_SEARCHLIGHT) {
        solid_angle = 1.0 / (doppler * doppler);
    }
    let weight = pow(10.0, -0.4 * (star.magnitude.x - sky.beta_saturation.w));
    let colour = lut_sample(lut_table, frame_uniforms.lut, d * star.direction_temperature.w).rgb;
    return weight * solid_angle * colour;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn sky_stars(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * WORKGROUP_SIZE;
    if (i >= sky.counts.x) {
        return;
    }
    let star = stars[i];
    let rest = normalize(sky.direction_map * star.direction_temperature.xyz);
    let image = distant_source_image(sky.beta_saturation.xyz, rest);
    let projected = project_direction(image.direction);
    if (projected.z == 0.0) {
        return;
    }
    let colour = star_colour(star, image.doppler);
    let size = frame_uniforms.viewport.xy;
    let corner = projected.xy - vec2<f32>(0.5);
    let base = floor(corner);
    let fraction = corner - base;
    for (var k = 0u; k < 4u; k++) {
        let offset = vec2<f32>(f32(k & 1u), f32(k >> 1u));
        let p = base + offset;
        if (any(p < vec2<f32>(0.0)) || any(p >= size)) {
            continue;
        }
        let w = select(1.0 - fraction, fraction, offset == vec2<f32>(1.0));
        // One contribution of 1 or more saturates the pixel whatever else is added, as the
        // clamped CPU sum does; clamping it keeps the integer sum from wrapping.
        let added = min(w.x * w.y * colour, vec3<f32>(1.0));
        let index = 3u * (u32(p.y) * u32(size.x) + u32(p.x));
        for (var c = 0u; c < 3u; c++) {
            atomicAdd(&star_light[index + c], u32(round(added[c] * STAR_LIGHT_SCALE)));
        }
    }
}

@vertex
fn sky_compose_vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the viewport.
    let corner = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(2.0 * corner - vec2<f32>(1.0), 0.5, 1.0);
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

// The display colour the sky image shows along the viewing direction `direction` in S (mirror
// of srt_trace::sky_image_colour): the light of a black body at SKY_IMAGE_WHITE_K filtered by the
// texel, seen with Doppler factor D — the paper's colour: 𝒢 × colour table at D·T; spectral
// colour: the texel's spectrum under that black body, shifted by D, its largest channel s
// carried as exposure × s.
fn sky_image_colour(direction: vec3<f32>) -> vec3<f32> {
    if (sky.counts.w == 0u) {
        return vec3<f32>(0.0);
    }
    let back = distant_source_image(-sky.beta_saturation.xyz, normalize(direction));
    let world = normalize(sky.direction_unmap * back.direction);
    let radiance = sky_image_sample(world) * sky.image.x;
    var doppler = 1.0 / back.doppler;
    if (frame_uniforms.effects == EFFECTS_GEOMETRY) {
        doppler = 1.0;
    }
    if (frame_uniforms.colour == SURFACE_COLOUR_PAPER) {
        let t = doppler * SKY_IMAGE_WHITE_K;
        return grey_value(vec4<f32>(radiance, 1.0)) * lut_sample(lut_table, frame_uniforms.lut, t).rgb;
    }
    let brightness = max(max(radiance.x, radiance.y), radiance.z);
    if (!(brightness > 0.0)) {
        return vec3<f32>(0.0);
    }
    let view = SpectralView(frame_uniforms.tone_map, frame_uniforms.exposure * brightness, frame_uniforms.searchlight_ln_y);
    return spectral_linear_reflected_display(radiance / brightness, -1.0, -1.0, SKY_IMAGE_WHITE_K, 1.0, doppler, view);
}

@fragment
fn sky_compose(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let index = 3u * (u32(position.y) * u32(frame_uniforms.viewport.x) + u32(position.x));
    let light = vec3<f32>(
        f32(star_light_total[index]),
        f32(star_light_total[index + 1u]),
        f32(star_light_total[index + 2u]),
    ) / STAR_LIGHT_SCALE;
    let image = sky_image_colour(view_direction(position.xy));
    let colour = frame_uniforms.background.rgb + image + light;
    return vec4<f32>(clamp(colour, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}
