// surface.wgsl — relativistic shading (Eq. 17–18), moving lights included (with shadows.wgsl),
// and the barycentric coordinates of a pixel's neighbours' rays (the ray–triangle test itself
// is triangle.wgsl's): the f32 mirror of crates/srt-trace (shade.rs and Tracer::shade).

// What this variant of the shader shades (srt_gpu::shaders::ObjectVariant): compiled in, because
// a software rasteriser runs every side of a branch its pixels do not all take, and these sides
// are long. The SURFACE_COLOUR_* code of the frame (its FrameUniforms.colour); whether the part
// may have a texture (TEXTURED_VARIANT), the object a clock face (CLOCK_VARIANT) or wireframe
// edges (WIREFRAME_VARIANT), and whether the frame may write seen events (SEEN_VARIANT), each
// still checked against the part's flags, the object's uniforms or the frame's output where
// compiled in.
override SURFACE_COLOUR_VARIANT: u32;
override TEXTURED_VARIANT: bool;
override CLOCK_VARIANT: bool;
override WIREFRAME_VARIANT: bool;
override SEEN_VARIANT: bool;

// The offset (in S) from the observer of the eye the shaded pixel's ray leaves from: 0 but in
// a stereo pair, where the shading pass sets it per pixel (lrt.wgsl's `shaded`, camera.wgsl's
// eye_offset); the directions towards the observer start there.
var<private> stereo_eye: vec3<f32>;

// Where rays from one origin meet the plane of a triangle (Eq. 16 by Cramer's rule with
// unnormalised spans σ = p1 − p0, τ = p2 − p0, as srt_trace::plane_hit solves it): for a ray along
// d, ζ = d·zeta / d·det and ξ = d·xi / d·det (the triple products σ·(d×τ) = d·(τ×σ),
// b·(d×τ) = d·(τ×b), d·(b×σ) with b = origin − p0), so the same coordinates for any positive or
// negative multiple of d. For several rays from the origin `origin` (a pixel's neighbours) at the
// cost of three dot products each; whether a ray meets the triangle is triangle.wgsl's question.
struct PlaneRays {
    zeta: vec3<f32>,
    xi: vec3<f32>,
    det: vec3<f32>,
}

fn plane_rays(origin: vec3<f32>, p: array<vec3<f32>, 3>) -> PlaneRays {
    let sigma = p[1] - p[0];
    let tau = p[2] - p[0];
    let b = origin - p[0];
    return PlaneRays(cross(tau, b), cross(b, sigma), cross(tau, sigma));
}

// (ζ, ξ) where the ray from the PlaneRays' origin along a multiple of `direction` meets the
// plane, and whether it does (not parallel).
fn plane_barycentric(plane: PlaneRays, direction: vec3<f32>) -> TriangleHit {
    let det = dot(direction, plane.det);
    return TriangleHit(det != 0.0, 0.0, dot(direction, plane.zeta) / det, dot(direction, plane.xi) / det);
}

// The texture coordinates of triangle `t`'s corners (read once where several points of the
// triangle are wanted: on a software rasteriser every storage read is a bounds-checked gather).
fn triangle_uvs(t: u32) -> array<vec2<f32>, 3> {
    return array<vec2<f32>, 3>(
        vertices[indices[3u * t]].uv.xy,
        vertices[indices[3u * t + 1u]].uv.xy,
        vertices[indices[3u * t + 2u]].uv.xy,
    );
}

// Texture coordinates interpolated between the corners' `uvs` at barycentric (ζ, ξ).
fn uv_at(uvs: array<vec2<f32>, 3>, zeta: f32, xi: f32) -> vec2<f32> {
    return (1.0 - zeta - xi) * uvs[0] + zeta * uvs[1] + xi * uvs[2];
}

// Interpolated texture coordinates of triangle `t` at barycentric (ζ, ξ).
fn triangle_uv(t: u32, zeta: f32, xi: f32) -> vec2<f32> {
    return uv_at(triangle_uvs(t), zeta, xi);
}

// Where a surface point is in its texture: its coordinates and their differences to the
// neighbouring pixels' points (x, then y), which choose the filter's footprint.
struct SurfaceUv {
    uv: vec2<f32>,
    ddx: vec2<f32>,
    ddy: vec2<f32>,
}

// Size of one frame in mip level `level` of the part's texture: the base frame size halved
// `level` times, at least 1 (as srt_scene::mip::MipChain makes them). Derived from the base size
// rather than asked of the texture per level: llvmpipe answers textureDimensions with a level
// that differs between the pixels it shades together with one pixel's level.
fn part_level_size(level: i32) -> vec2<i32> {
    let base = vec2<u32>(textureDimensions(part_texture).x, part.frame_height);
    return vec2<i32>(max(base >> vec2<u32>(u32(level)), vec2<u32>(1u)));
}

// The flipbook frame the part's texture shows at proper time `proper_time`, 0 for a still image
// (mirror of srt_scene::Texture::frame_at).
fn part_frame(proper_time: f32) -> u32 {
    let count = f32(part.frames);
    let shown = floor(proper_time * part.frame_rate);
    let frame = shown - floor(shown / count) * count;
    if (!(frame >= 0.0)) {
        return 0u;
    }
    return u32(frame) % part.frames;
}

// Texel `texel` (non-negative) of frame `frame` of mip level `level` of the part's texture, the
// frame `size` texels large, wrapped within the frame (repeat addressing): the mirror of
// srt_trace::texture::texel. Only non-negative coordinates reach `%`: GLSL, which wgpu's GL
// backend runs, leaves `%` of a negative number undefined (llvmpipe's GL returned wrong texels
// for them).
fn part_texel(level: i32, frame: u32, size: vec2<i32>, texel: vec2<i32>) -> vec4<f32> {
    return textureLoad(part_texture, texel % size + vec2<i32>(0, i32(frame) * size.y), level);
}

// Bilinear sample of frame `frame` of mip level `level` at `uv`, texel centres at
// half-integers: the mirror of srt_trace::texture::bilinear. The lower texel is wrapped into the
// frame while still a float.
fn part_bilinear(level: i32, frame: u32, uv: vec2<f32>) -> vec4<f32> {
    let size = part_level_size(level);
    let extent = vec2<f32>(size);
    let p = uv * extent - 0.5;
    let p0 = floor(p);
    let f = p - p0;
    let i = vec2<i32>(p0 - extent * floor(p0 / extent));
    let j = i + 1;
    let top = mix(part_texel(level, frame, size, i), part_texel(level, frame, size, vec2<i32>(j.x, i.y)), f.x);
    let bottom = mix(part_texel(level, frame, size, vec2<i32>(i.x, j.y)), part_texel(level, frame, size, j), f.x);
    return mix(top, bottom, f.y);
}

// Trilinear sample of the part's texture at `uv` with the derivatives `ddx`, `ddy` of the
// texture coordinates per pixel: the mirror of srt_trace::texture::sample_trilinear, filtered
// here in f32 rather than by the sampler hardware, whose level of detail and weights are
// implementation-defined (NVIDIA's differ from the reference by up to 12/255 at texel edges).
fn sample_part_texture(uv: vec2<f32>, ddx: vec2<f32>, ddy: vec2<f32>, frame: u32) -> vec4<f32> {
    let size = vec2<f32>(part_level_size(0));
    let rho = max(length(ddx * size), length(ddy * size));
    var lod = 0.0;
    if (rho > 0.0 && rho < 3.0e38) {
        lod = clamp(log2(rho), 0.0, f32(textureNumLevels(part_texture) - 1u));
    }
    let lower = i32(floor(lod));
    let fraction = lod - floor(lod);
    // The two levels are visited in a loop whose counter is the same for every pixel shaded
    // together, so each texel fetch asks one level for all of them: llvmpipe (Vulkan and GL)
    // fetched some pixels' texels from a neighbouring pixel's level when each asked its own.
    var colour = vec4<f32>(0.0);
    for (var level = 0; level <= lower + 1; level++) {
        if (level == lower) {
            colour += (1.0 - fraction) * part_bilinear(level, frame, uv);
        } else if (level == lower + 1 && fraction > 0.0) {
            colour += fraction * part_bilinear(level, frame, uv);
        }
    }
    return colour;
}

// Surface colour (texel or clock face × base × vertex colour, or the wireframe pattern) of
// triangle `t` at (ζ, ξ), whose place in the texture is `uv` (read only where the part is
// textured or wears a clock); a clock shows the object's proper time `proper_time` there.
fn surface_albedo(t: u32, zeta: f32, xi: f32, uv: SurfaceUv, proper_time: f32) -> vec4<f32> {
    let w = vec3<f32>(1.0 - zeta - xi, zeta, xi);
    let wireframe = object.style.x;
    if (WIREFRAME_VARIANT && wireframe > 0.0) {
        let p = triangle_corners(t);
        let twice_area = length(cross(p[1] - p[0], p[2] - p[0]));
        let heights = twice_area / vec3<f32>(length(p[2] - p[1]), length(p[0] - p[2]), length(p[1] - p[0]));
        let near_edge = any(w * heights < vec3<f32>(wireframe));
        return select(vec4<f32>(1.0), vec4<f32>(0.0, 0.0, 0.0, 1.0), near_edge);
    }
    var albedo = part.base_color;
    if (part_has(PART_VERTEX_COLOURS)) {
        let c = w.x * vertices[indices[3u * t]].color + w.y * vertices[indices[3u * t + 1u]].color
            + w.z * vertices[indices[3u * t + 2u]].color;
        albedo *= c;
    }
    if (has_clock()) {
        albedo *= clock_albedo(uv.uv, uv.ddx, uv.ddy, proper_time);
    } else if (part_is_textured()) {
        albedo *= sample_part_texture(uv.uv, uv.ddx, uv.ddy, part_frame(proper_time));
    }
    return albedo;
}

// Where a surface point's light is received: its emission event in S, the event the observer
// sees (srt_trace::SurfacePoint::event), and the same event in the rest coordinates of the
// object being shaded (where the shadow test of that object starts, shadows.wgsl).
struct Receiver {
    event: vec4<f32>,
    rest: vec4<f32>,
}

// The frame a surface point is shaded in (mirror of srt_trace::SurfaceState): the velocity of
// its local rest frame relative to S, its unit normal there (the zero vector: the triangle's
// interpolated vertex normal, for a body at rest in S′) and the proper time its clock shows.
// For a body at rest in S′ the local rest frame is S′ (resting_frame); a spinning or thrusting
// body's points have their own (motion.wgsl, moving_frame).
struct LocalFrame {
    beta: vec3<f32>,
    normal: vec3<f32>,
    proper_time: f32,
}

// The local frame of a point of a body at rest in S′ whose clock shows `proper_time`.
fn resting_frame(proper_time: f32) -> LocalFrame {
    return LocalFrame(object.frame.beta_gamma.xyz, vec3<f32>(0.0), proper_time);
}

// (f_diff, f_spec) of Eq. 18 for the unit directions (in S′) `to_light` and `to_observer` on a
// surface with the unit normal `normal` (facing the observer); 0 where the light is behind it
// (mirror of srt_trace's phong_terms).
fn phong_terms(normal: vec3<f32>, to_light: vec3<f32>, to_observer: vec3<f32>) -> vec2<f32> {
    let cos_light = dot(normal, to_light);
    var diffuse = 0.0;
    var specular = 0.0;
    let s = frame_uniforms.shading;
    if (cos_light > 0.0) {
        let reflected = 2.0 * cos_light * normal - to_light;
        diffuse = s.y * cos_light;
        specular = s.z * pow(max(dot(reflected, to_observer), 0.0), s.w);
    }
    return vec2<f32>(diffuse, specular);
}

// The lamp's light a surface point sends to the observer (§4.2), or an emitter's own: Phong in
// S′ with aberrated directions and the Doppler factors of Eq. 17 — D_in light → surface, D_out
// surface → observer (both 1 for geometry only). The paper's colour: the colour table at
// D_in·D_out·T_light with f_ar (Eq. 18); spectral colour (spectral.wgsl): the albedo's
// reflectance spectrum under the black body at D_in·T_light, shifted by D_out, its factor
// f_amb + f_diff + f_spec. The lamp's light is all times its strength (LightUniforms.lamp.x).
// An emitting object sends its black body at D_out·T_e instead, while it shines at the object's
// proper time (emitter_shines). All of it in the point's local rest frame `local`. What the
// moving lights' terms reuse comes with it (SurfaceLamp).
struct SurfaceLamp {
    light: Arriving,
    // Whether the light is the object's own emission (no reflected light is added to it).
    emits: bool,
    // The surface's unit normal in the local rest frame, facing the observer.
    normal: vec3<f32>,
    // The unit direction towards the observer there.
    to_observer: vec3<f32>,
    // D_out, and the grey value of Eq. 18 (the paper's colour).
    d_out: f32,
    grey: f32,
}

fn surface_lamp(t: u32, zeta: f32, xi: f32, apparent: vec3<f32>, albedo: vec4<f32>, local: LocalFrame) -> SurfaceLamp {
    let beta = local.beta;
    let incident = normalize(apparent - frame_uniforms.light.xyz);
    let outgoing = normalize(frame_uniforms.observer.xyz + stereo_eye - apparent);
    let relativistic = frame_uniforms.effects != EFFECTS_GEOMETRY;
    var d_in = 1.0;
    var d_out = 1.0;
    // D_in · D_out in one expression (Eq. 17), as the paper's colour always used it.
    var combined = 1.0;
    if (relativistic) {
        d_in = receiver_doppler(beta, incident);
        d_out = doppler_factor(beta, outgoing);
        combined = reflection_doppler(beta, incident, outgoing);
    }
    let spectral = SURFACE_COLOUR_VARIANT == SURFACE_COLOUR_SPECTRAL;
    let optics = object.optics;
    if (optics.z > 0.0 && emitter_shines(local.proper_time)) {
        var light: Arriving;
        if (spectral) {
            light = spectrum_light(spectral_emitted(optics.z, d_out), optics.w);
        } else {
            light = table_light(optics.w, d_out * optics.z);
        }
        return SurfaceLamp(light, true, vec3<f32>(0.0), vec3<f32>(0.0), d_out, 0.0);
    }
    let to_light = -normalize(aberrate(-beta, incident));
    let to_observer = normalize(aberrate(-beta, outgoing));
    let w = vec3<f32>(1.0 - zeta - xi, zeta, xi);
    var normal = local.normal;
    if (all(normal == vec3<f32>(0.0))) {
        normal = normalize(w.x * vertices[indices[3u * t]].normal.xyz + w.y * vertices[indices[3u * t + 1u]].normal.xyz
            + w.z * vertices[indices[3u * t + 2u]].normal.xyz);
    }
    if (dot(normal, to_observer) < 0.0) {
        normal = -normal;
    }
    let phong = phong_terms(normal, to_light, to_observer);
    let geometry = frame_uniforms.lights.lamp.x * (frame_uniforms.shading.x + phong.x + phong.y);
    let grey = 0.5 * (grey_value(albedo) + 1.0);
    var lamp: Arriving;
    if (spectral) {
        let reflected = spectral_reflected(albedo.xyz, optics.x, optics.y, frame_uniforms.light.w, d_in, d_out);
        lamp = spectrum_light(reflected, geometry);
    } else {
        lamp = table_light(grey * geometry, combined * frame_uniforms.light.w);
    }
    return SurfaceLamp(lamp, false, normal, to_observer, d_out, grey);
}

// The light a surface point sends to the observer, as the frame's output holds it: the lamp's
// (surface_lamp) and each moving light's (shadows.wgsl) that the point faces and no object
// shadows: its diffuse and specular terms, from the direction its light arrives in at the
// point's emission event `receiver.event`, at D_in·T_L, with the strength s / r_L² (times
// D_in⁻² with the searchlight colour table, whose brightness holds D_in⁴ already;
// docs/physics.md, "Moving lights"): the lights are then summed as light (light.wgsl,
// LightSum). With none of them reaching the point the result is the lamp's alone, computed as
// before moving lights existed.
//
// Mirror of srt_trace::shade::arriving_unless_shadowed and Arriving::display / radiance.
fn surface_output(t: u32, zeta: f32, xi: f32, apparent: vec3<f32>, albedo: vec4<f32>, local: LocalFrame, receiver: Receiver) -> vec3<f32> {
    let surface = surface_lamp(t, zeta, xi, apparent, albedo, local);
    let lamp = surface.light;
    if (surface.emits || !MOVING_LIGHTS || frame_uniforms.lights.counts.x == 0u) {
        return arriving_output(lamp);
    }
    let beta = local.beta;
    let normal = surface.normal;
    let to_observer = surface.to_observer;
    let optics = object.optics;
    let spectral = SURFACE_COLOUR_VARIANT == SURFACE_COLOUR_SPECTRAL;
    let relativistic = frame_uniforms.effects != EFFECTS_GEOMETRY;
    let follows_luminance = relativistic && frame_uniforms.tone_map == TONE_MAP_SEARCHLIGHT;
    let own = u32(object.time.x);
    var sum = light_sum_of(lamp);
    var sources = 0u;
    for (var i = 0u; i < frame_uniforms.lights.counts.x; i++) {
        let light = frame_uniforms.lights.moving[i];
        let arriving = retarded_light(light, receiver.event);
        if (!arriving.found) {
            continue;
        }
        let terms = phong_terms(normal, -normalize(aberrate(-beta, arriving.direction)), to_observer);
        let reflected = terms.x + terms.y;
        if (!(reflected > 0.0) || !(light.strength.x > 0.0)
            || moving_light_shadowed(arriving, receiver.event, own, receiver.rest)) {
            continue;
        }
        var light_d_in = 1.0;
        if (relativistic) {
            light_d_in = arriving.source_doppler * receiver_doppler(beta, arriving.direction);
        }
        let r = arriving.source_distance;
        var strength = light.strength.x / (r * r);
        if (follows_luminance) {
            strength = light.strength.x / (r * r * light_d_in * light_d_in);
        }
        let factor = reflected * strength;
        let temperature_k = light.offset_temperature.w;
        if (spectral) {
            let l = spectral_reflected(albedo.xyz, optics.x, optics.y, temperature_k, light_d_in, surface.d_out);
            sum = light_sum_add(sum, spectrum_light(l, factor));
        } else {
            sum = light_sum_add(sum, table_light(surface.grey * factor, light_d_in * surface.d_out * temperature_k));
        }
        sources++;
    }
    if (sources == 0u) {
        return arriving_output(lamp);
    }
    return light_sum_output(sum);
}

// The pixel a surface point gives: its light (surface_output) as the colour target holds it.
fn shade(t: u32, zeta: f32, xi: f32, apparent: vec3<f32>, albedo: vec4<f32>, local: LocalFrame, receiver: Receiver) -> vec4<f32> {
    return output_pixel(surface_output(t, zeta, xi, apparent, albedo, local, receiver));
}

// Whether the current object wears a clock face (clock.wgsl).
fn has_clock() -> bool {
    return CLOCK_VARIANT && object.clock.w > 0.0;
}

// Whether the current part has a texture.
fn part_is_textured() -> bool {
    return TEXTURED_VARIANT && part_has(PART_TEXTURED);
}

// Whether the current object's emission is on at its proper time `proper_time` (mirror of
// srt_scene::Emission::shines_at): always without blinking, else while
// (τ / period) mod 1 < duty.
fn emitter_shines(proper_time: f32) -> bool {
    let blink = object.blink;
    if (blink.x <= 0.0) {
        return true;
    }
    return fract(proper_time / blink.x) < blink.y;
}

// The current object's proper time ct′ at the rest event `emission_rest` (mirror of
// srt_scene::Object::proper_time).
fn proper_time_at(emission_rest: vec4<f32>) -> f32 {
    return emission_rest.x - object.time.y;
}

// What a pixel sees of time at the emission event `emission_rest` (rest coordinates) on the
// current object, the point's local frame `local`, as the seen-event outputs write it (mirror of srt_trace::SeenEvent):
// OUTPUT_SEEN_EVENT (world time ct_W, the object's proper time, the apparent distance, the
// Doppler factor of the light towards the observer), or OUTPUT_SEEN_OBJECT (its index in x).
fn seen_pixel(emission_rest: vec4<f32>, local: LocalFrame) -> vec4<f32> {
    if (frame_uniforms.output == OUTPUT_SEEN_OBJECT) {
        return vec4<f32>(object.time.x, 0.0, 0.0, 0.0);
    }
    let event = to_observer(object.frame, emission_rest);
    let towards_observer = frame_uniforms.observer.xyz + stereo_eye - event.yzw;
    return vec4<f32>(
        dot(object.world_time, emission_rest) + object.time.z,
        local.proper_time,
        length(towards_observer),
        doppler_factor(local.beta, normalize(towards_observer)),
    );
}

// Whether the frame writes what pixels see of time rather than light.
fn writes_seen_events() -> bool {
    return SEEN_VARIANT
        && (frame_uniforms.output == OUTPUT_SEEN_EVENT || frame_uniforms.output == OUTPUT_SEEN_OBJECT);
}
