// sky.wgsl — the stars of the sky, in two passes (mirror: crates/srt-trace/src/sky.rs).
//
// 1. `sky_stars` (compute, one invocation per star): the star's aberrated direction and Doppler
//    factor (distant_source_image, Eq. 4), its colour (the colour table at D·T, weighted by its
//    magnitude and, with the searchlight effect, by 1/D² for its shrunken solid angle) and its
//    tent splat over the four pixels around its exact image position, added to `star_light` in
//    fixed point: integer additions are exact and commute, so the sum does not depend on the
//    order in which invocations run.
// 2. `sky_compose_vertex`, `sky_compose` (a full-screen triangle): background + star light,
//    clamped, into the colour target; the object passes then draw over it.

@group(0) @binding(0) var<uniform> frame_uniforms: FrameUniforms;
@group(0) @binding(1) var lut_table: texture_2d<f32>;

@group(1) @binding(0) var<uniform> sky: SkyUniforms;
@group(1) @binding(1) var<storage, read> stars: array<Star>;
// Star light per pixel and channel (row-major, 3 per pixel) in units of 1/STAR_LIGHT_SCALE.
@group(1) @binding(2) var<storage, read_write> star_light: array<atomic<u32>>;
// The same buffer, read by the compose pass.
@group(1) @binding(3) var<storage, read> star_light_total: array<u32>;

override WORKGROUP_SIZE: u32;

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

// Pixel position (x right, y down, pixel centres at half-integers) of the direction `d` in S in
// xy; z = 1 in front of the camera, 0 behind (mirror of srt_trace::project).
fn project_direction(d: vec3<f32>) -> vec3<f32> {
    let forward = frame_uniforms.camera_forward.xyz;
    let right = frame_uniforms.camera_right.xyz;
    let up = frame_uniforms.camera_up.xyz;
    let depth = dot(d, forward);
    if (depth <= 0.0) {
        return vec3<f32>(0.0);
    }
    // camera_right and camera_up are scaled by tan(fov/2)·aspect and tan(fov/2).
    let ndc = vec2<f32>(dot(d, right) / (depth * dot(right, right)), dot(d, up) / (depth * dot(up, up)));
    return vec3<f32>(
        0.5 * (ndc.x + 1.0) * frame_uniforms.viewport.x,
        0.5 * (1.0 - ndc.y) * frame_uniforms.viewport.y,
        1.0,
    );
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn sky_stars(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * WORKGROUP_SIZE;
    if (i >= sky.counts.x) {
        return;
    }
    let star = stars[i];
    let image = distant_source_image(sky.beta_saturation.xyz, star.direction_temperature.xyz);
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

@fragment
fn sky_compose(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let index = 3u * (u32(position.y) * u32(frame_uniforms.viewport.x) + u32(position.x));
    let light = vec3<f32>(
        f32(star_light_total[index]),
        f32(star_light_total[index + 1u]),
        f32(star_light_total[index + 2u]),
    ) / STAR_LIGHT_SCALE;
    return vec4<f32>(clamp(frame_uniforms.background.rgb + light, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}
