// image_based.wgsl — the image-based method the paper compares against (Table 1's "IB", after
// Weiskopf et al.'s texture-based special relativistic rendering): per velocity group, the
// objects are rasterised at rest into a cube map around the observation event's position in the
// group's rest frame S′ (ib_face_*), then each pixel's viewing direction is aberrated into S′,
// the cube map looked up (nearest texel) and the light Doppler-shifted (ib_lookup_*). Several
// groups compose through the depth test by apparent distance. Approximate by design: a texel
// stands for every direction it covers, so magnified parts of the picture show the cube map's
// texels (docs/performance.md measures the error against the exact image).
//
// Composed after polygon.wgsl (whose vertex and fragment work the faces reuse) and camera.wgsl.
// The face passes draw a part's triangles six times over (vertex index = face · 3 · triangles
// + the triangle's vertex), one face per pass into one layer of the cube map; the conventions
// of the faces live here alone (ib_face_basis), for the faces and for the look-up.

// The cube map of the group being composed: per texel (f, T, s, object) — the colour table
// light's factor f and the temperature T an observer at rest in S′ at the observation event
// sees, the distance s in S′ from there (= the light's travel time in S′), and the object's
// index plus 1: 0 where no object was drawn (the faces are cleared to zero, a clear value every
// backend keeps — wgpu's GL backend lost a negative one; a test draws the background through
// such texels). Layer = face (ib_face_basis).
@group(3) @binding(0) var ib_cube: texture_2d_array<f32>;

// The near plane of the faces' projection (S′ units): depth = IB_NEAR / z, reversed (the
// faces' depth test keeps the larger value), so that f32 depth keeps its relative precision
// at every distance. Surfaces nearer than this to the observation event are clipped from the
// cube map; a much smaller value would crowd the depths next to −1 where a backend maps clip
// depth to [−1, 1] (OpenGL without clip control).
const IB_NEAR: f32 = 1e-2;

// The unit basis (right, up, forward) of face `face`: +x, −x, +y, −y, +z, −z of S′ in turn.
fn ib_face_basis(face: u32) -> array<vec3<f32>, 3> {
    let axis = face / 2u;
    let sign = select(1.0, -1.0, (face & 1u) == 1u);
    var forward = vec3<f32>(0.0);
    forward[axis] = sign;
    var up = vec3<f32>(0.0, 1.0, 0.0);
    if (axis == 1u) {
        up = vec3<f32>(0.0, 0.0, -sign);
    }
    return array<vec3<f32>, 3>(cross(forward, up), up, forward);
}

// The face that sees the direction `d` (S′): the one of its largest component.
fn ib_face_of(d: vec3<f32>) -> u32 {
    let a = abs(d);
    var axis = 2u;
    if (a.x >= a.y && a.x >= a.z) {
        axis = 0u;
    } else if (a.y >= a.z) {
        axis = 1u;
    }
    return 2u * axis + select(0u, 1u, d[axis] < 0.0);
}

// The texel (column, row, face) of a cube map of `size` × `size` texels per face that sees
// the direction `d` (S′): the face's pinhole of 90°, rows from the top (its up).
fn ib_texel(d: vec3<f32>, size: u32) -> vec3<u32> {
    let face = ib_face_of(d);
    let basis = ib_face_basis(face);
    let z = dot(d, basis[2]);
    let uv = vec2<f32>(dot(d, basis[0]), dot(d, basis[1])) / z;
    let n = f32(size);
    let texel = vec2<f32>((uv.x + 1.0) * 0.5 * n, (1.0 - uv.y) * 0.5 * n);
    let last = vec2<f32>(n - 1.0);
    return vec3<u32>(vec2<u32>(clamp(floor(texel), vec2<f32>(0.0), last)), face);
}

// A vertex of the current part seen from the observation event's position in S′ through face
// (index / (3 · triangles)): its emission event's position (polygon_vertex_emission) relative
// to the observer there, projected by the face's pinhole.
@vertex
fn ib_face_vertex(@builtin(vertex_index) index: u32) -> PolygonVarying {
    let per_face = 3u * part.triangle_count;
    let face = index / per_face;
    let v = index - face * per_face;
    let emission = polygon_vertex_emission(v);
    let basis = ib_face_basis(face);
    let p = emission.yzw - object.frame.observer_rest.yzw;
    let clip = vec4<f32>(dot(p, basis[0]), dot(p, basis[1]), IB_NEAR, dot(p, basis[2]));
    return polygon_varying(v, clip, to_observer(object.frame, emission));
}

// What a cube map texel holds of the surface point fragment `in` draws: the lamp's (or its
// own emission's) colour-table light as it leaves towards the observation event, its
// temperature as an observer at rest in S′ there receives it (the light's D_out divided by the
// Doppler factor of S′ itself in that direction: the look-up multiplies that one back), the
// distance in S′ and the object's index.
@fragment
fn ib_face_fragment(in: PolygonVarying) -> @location(0) vec4<f32> {
    let point = polygon_point(in, true);
    let b = in.barycentric;
    // The face's barycentric coordinates are the rest triangle's own (a pinhole at rest draws
    // it in perspective), so the point's emission event is exact, and so is where it shows in
    // S: not the polygon method's interpolated apparent position.
    let apparent = to_observer(object.frame, point.receiver.rest).yzw;
    let lamp = surface_lamp(in.triangle, b.x, b.y, apparent, polygon_albedo(in, point), point.local).light;
    var frame_doppler = 1.0;
    if (frame_uniforms.effects != EFFECTS_GEOMETRY) {
        let outgoing = normalize(frame_uniforms.observer.xyz - apparent);
        frame_doppler = doppler_factor(object.frame.beta_gamma.xyz, outgoing);
    }
    let distance_rest = object.frame.observer_rest.x - point.receiver.rest.x;
    return vec4<f32>(lamp.factor, lamp.temperature_k / frame_doppler, distance_rest, object.time.x + 1.0);
}

struct IbLookupOutput {
    @location(0) colour: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

// A triangle covering the target (ib_lookup_fragment draws every pixel).
@vertex
fn ib_lookup_vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.5, 1.0);
}

// The group's light at the pixel at framebuffer position `position`: its viewing direction
// aberrated into S′ (backward_ray, Eq. 4), the cube map's texel there, its temperature times
// the Doppler factor of S′ in that direction (Eq. 4, time-like part), at the apparent distance
// γ s (1 − β·d′) as depth. No fragment where the texel is empty or the picture sees nothing.
@fragment
fn ib_lookup_fragment(@builtin(position) position: vec4<f32>) -> IbLookupOutput {
    let pixel = position.xy;
    let d = view_direction(pixel);
    if (sees_nothing(pixel) || all(d == vec3<f32>(0.0))) {
        discard;
    }
    let ray = backward_ray(object.frame, d);
    let texel = ib_texel(ray.direction, textureDimensions(ib_cube).x);
    let stored = textureLoad(ib_cube, texel.xy, texel.z, 0);
    if (stored.w < 0.5) {
        discard;
    }
    var doppler = 1.0;
    if (frame_uniforms.effects != EFFECTS_GEOMETRY) {
        doppler = doppler_factor(object.frame.beta_gamma.xyz, -normalize(d));
    }
    let light = table_light(stored.x, doppler * stored.y);
    let depth = apparent_distance(object.frame, ray, stored.z) * frame_uniforms.depth_scale;
    return IbLookupOutput(output_pixel(arriving_output(light)), depth);
}
