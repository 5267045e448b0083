// types.wgsl — data shared by every pass. Each struct has a #[repr(C)] twin in
// crates/srt-gpu/src/types.rs; tests/layout.rs compares their layouts field by field through
// naga, and tests/reflect.rs checks that every const below equals its Rust twin.

// FrameUniforms.effects (srt_gpu::types::EffectsCode).
const EFFECTS_GEOMETRY: u32 = 0u;
const EFFECTS_DOPPLER: u32 = 1u;
const EFFECTS_SEARCHLIGHT: u32 = 2u;

// FrameUniforms.colour (srt_gpu::types::SurfaceColourCode): how lit surfaces are coloured.
const SURFACE_COLOUR_PAPER: u32 = 0u;
const SURFACE_COLOUR_SPECTRAL: u32 = 1u;

// FrameUniforms.tone_map (srt_gpu::types::ToneMapCode): the tone map of spectral colour.
const TONE_MAP_LUMINANCE: u32 = 0u;
const TONE_MAP_SEARCHLIGHT: u32 = 1u;

// FrameUniforms.footprint_shape (srt_gpu::types::FootprintCode).
const FOOTPRINT_HULL: u32 = 0u;
const FOOTPRINT_RECTANGLE: u32 = 1u;

// Bits of PartUniforms.flags (srt_gpu::types::PartFlags).
const PART_TEXTURED: u32 = 1u;
const PART_VERTEX_COLOURS: u32 = 2u;
// Back faces may be culled: the mesh is a closed solid with outward fronts and the observer is
// outside it (decided per frame on the CPU, srt_gpu::culling).
const PART_CULL_BACK_FACES: u32 = 4u;
// The part is the box holding its object (the ray tracer's): its fragments' hits lie anywhere
// inside it, so its footprints' nearest depth is bounded over all its corners.
const PART_ENCLOSING_BOX: u32 = 8u;

// Most points of a footprint's convex hull (srt_gpu::types::FOOTPRINT_HULL_POINTS).
const FOOTPRINT_HULL_POINTS: u32 = 6u;
// Vertices drawn per footprint (srt_gpu::types::FOOTPRINT_VERTICES): a fan of
// FOOTPRINT_HULL_POINTS − 2 triangles around hull point 0, so that the largest hull is covered;
// the spare triangles of smaller hulls are degenerate. The LRT draws this many vertices per
// triangle, and the proxy pass counts them into the indirect draw.
const FOOTPRINT_VERTICES: u32 = 3u * (FOOTPRINT_HULL_POINTS - 2u);
// A rectangle, stored as four hull points, is the fan's first two triangles.
const_assert FOOTPRINT_VERTICES >= 6u;

// A part's draw_args (proxy.wgsl writes it, lrt.wgsl reads it; twins of
// srt_gpu::types::DRAW_ARGS_*): two indirect draws, each (vertex count, instance count, first
// vertex, first instance). [DRAW_ARGS_FOOTPRINT_VERTICES] is the LRT visibility pass's footprint
// draw: its vertex count grows to the end of the last triangle with a footprint on screen.
// [DRAW_ARGS_SHADE_VERTICES] is the LRT shading pass's rectangle: 6 vertices once any footprint
// is on screen. So a part wholly off screen or behind the camera draws nothing in either pass.
// [DRAW_ARGS_PIECES_TAKEN] counts the piece slots taken (or asked for, once they run out).
// [DRAW_ARGS_BOUND..+4] is the part's screen bound, the union of its footprints' rectangles in
// whole pixels: (!min x, !min y, max x, max y), so that all four grow by atomicMax from 0,
// which reads as empty (min > max).
const DRAW_ARGS_FOOTPRINT_VERTICES: u32 = 0u;
const DRAW_ARGS_SHADE_VERTICES: u32 = 4u;
const DRAW_ARGS_PIECES_TAKEN: u32 = 8u;
const DRAW_ARGS_BOUND: u32 = 9u;
const DRAW_ARGS_WORDS: u32 = 13u;

// How the picture's points map to viewing directions (FrameUniforms.projection; twins of
// srt_gpu::types::ProjectionCode, after srt_scene::Projection): the pinhole, the full sphere
// (longitude across, latitude up) and the azimuthal equidistant fisheye.
const PROJECTION_PERSPECTIVE: u32 = 0u;
const PROJECTION_EQUIRECTANGULAR: u32 = 1u;
const PROJECTION_FISHEYE: u32 = 2u;

const PI: f32 = 3.14159265358979;

// Per image: camera, observer, light, shading and colour-table parameters.
struct FrameUniforms {
    // S → clip space (NDC depth in [0, 1], y up).
    view_projection: mat4x4<f32>,
    // Unit viewing direction of the camera, w = 0.
    camera_forward: vec4<f32>,
    // Camera right axis scaled by tan(fov/2)·aspect and the target's share of the picture's
    // width; w: the target's centre in the picture in units of this axis (0 for a whole
    // picture; srt_gpu::projection::TargetCamera).
    camera_right: vec4<f32>,
    // Camera up axis scaled by tan(fov/2) and the target's share of the picture's height; w as
    // camera_right's.
    camera_up: vec4<f32>,
    // Observer position in S (xyz); w is 0 (ct_obs is in each object's Frame.observer_rest).
    observer: vec4<f32>,
    // Light position in S (xyz) and its Planck temperature in kelvin (w).
    light: vec4<f32>,
    // Phong factors: ambient, diffuse, specular, shininess.
    shading: vec4<f32>,
    // Background as the output holds it: the display colour, or its radiance (the colour
    // sRGB-decoded), alpha 0 (no object seen; objects write alpha 1); for the seen-event
    // outputs, what a pixel that sees no object holds (0, and −1 as the object index).
    background: vec4<f32>,
    // Colour table: ln T_min, ln T_max, texel count, unused.
    lut: vec4<f32>,
    // Viewport width, height in pixels and their reciprocals.
    viewport: vec4<f32>,
    // The whole picture's width and height in pixels and the target's first column and row in
    // it: the target itself (width, height, 0, 0) unless it holds a window of a larger picture
    // (a tile, srt_gpu::projection::ImageWindow). The proxy pass judges footprints against the
    // picture, so that a tile draws the footprints the whole picture would.
    picture: vec4<f32>,
    // One of EFFECTS_*.
    effects: u32,
    // One of FOOTPRINT_*.
    footprint_shape: u32,
    // Depth written per LRT fragment is apparent distance × depth_scale.
    depth_scale: f32,
    // One of SURFACE_COLOUR_*.
    colour: u32,
    // One of TONE_MAP_* (spectral colour; the paper's colour uses the colour table).
    tone_map: u32,
    // Multiplier on the light before the tone map (spectral colour).
    exposure: f32,
    // ln Y(1500 K), the searchlight tone map's divisor (srt_color::searchlight_reference_ln_y).
    searchlight_ln_y: f32,
    // One of OUTPUT_* (light.wgsl): display colours or radiance.
    output: u32,
    // One of PROJECTION_*: how the picture's points map to viewing directions (camera.wgsl).
    projection: u32,
    // Half the fisheye's field of view in radians (PROJECTION_FISHEYE; 0 otherwise).
    fisheye_half_fov: f32,
    // A stereo pair's eye separation (srt_scene::Stereo; camera.wgsl's eye_point), or −1 for
    // one picture from the observer.
    eye_separation: f32,
    // Unused: keeps `radiance` on its 16-byte boundary.
    projection_padding: u32,
    // How light becomes radiance (light.wgsl, arriving_radiance): ln Y of the lamp's black body,
    // 1/g, 1 where brightness follows luminance else 0, the largest value the target holds.
    radiance: vec4<f32>,
    // The lamp's strength and the moving lights (shadows.wgsl): in this buffer, not one of their
    // own, to keep the shading pass within eight storage buffers.
    lights: LightUniforms,
}

// Per object: its rest frame and drawing style.
struct ObjectUniforms {
    frame: Frame,
    // x: wireframe edge width in S′ units (≤ 0: draw the surface); yzw unused.
    style: vec4<f32>,
    // Spectral colour (srt_scene::SurfaceOptics): ultraviolet and infrared reflectances (< 0:
    // none), emission temperature in kelvin (≤ 0: the object does not glow) and brightness.
    optics: vec4<f32>,
    // Its time, for the seen-event outputs (srt_trace::SeenEvent): x its index in scene order,
    // y its rest_time_shift (rest coordinates' ct′ − its proper time), z the world time ct_W of
    // the rest coordinates' origin event; w unused.
    time: vec4<f32>,
    // The time row of rest coordinates → W: ct_W of a rest event e′ is dot(world_time, e′) + time.z.
    world_time: vec4<f32>,
    // The emission's blinking (srt_scene::Blink): x the period in proper time (0: steady), y the
    // duty; zw unused.
    blink: vec4<f32>,
    // Its clock face (srt_scene::Clock, clock.wgsl): rate, offset, dial, and w 1 if it has one.
    clock: vec4<f32>,
    // The clock's face colour (rgb, sRGB-encoded as texels are).
    clock_face: vec4<f32>,
    // The clock's ink colour.
    clock_ink: vec4<f32>,
    // Its motion within its rest frame (srt_physics::motion::Motion; motion.wgsl, filled by
    // srt_gpu::motion::MotionUniforms): x unused (the kind is motion.wgsl's MOTION_VARIANT); y the spin rate ω or the thrust's
    // proper acceleration α; z the spin phase ω·ct′₀ (mod 2π) or the thrust's elapsed time
    // ct′₀ − ct₀, ct′₀ the object's S′ time at the observation event; w the thrust's final
    // rapidity (< 0: it never ends).
    motion: vec4<f32>,
    // The unit spin axis or thrust direction (xyz), and the body's reach (w): a spinning body's
    // largest distance from its centre, otherwise its box's diagonal.
    motion_axis: vec4<f32>,
    // The spin centre (xyz); w unused.
    motion_centre: vec4<f32>,
    // The body's box at rest, lower corner (xyz); a spinning body's lowest height along its axis
    // from the centre (w).
    motion_low: vec4<f32>,
    // The body's box at rest, upper corner (xyz); a spinning body's highest height (w).
    motion_high: vec4<f32>,
    // In a wide projection, the rectangle of the whole picture (pixels: min x, min y, max x,
    // max y) where the object may be seen (srt_gpu::culling::ball_wide_bound): its box's
    // footprint there.
    view_bound: vec4<f32>,
}

// How a body moves in its rest frame: the value of motion.wgsl's MOTION_VARIANT
// (srt_gpu::motion::MotionCode).
const MOTION_REST: u32 = 0u;
const MOTION_SPIN: u32 = 1u;
const MOTION_THRUST: u32 = 2u;

// Per mesh part: its material.
struct PartUniforms {
    // Base colour factor (sRGB-encoded, as stored in files).
    base_color: vec4<f32>,
    // PART_* bits.
    flags: u32,
    triangle_count: u32,
    // The part's number in the scene, from 1 (0 marks "no triangle" in the visibility pass).
    id: u32,
    // A flipbook texture (srt_scene::Texture): frames stacked from the top (1: a still image),
    // one frame's height in the base level, frames per unit of proper time.
    frames: u32,
    frame_height: u32,
    frame_rate: f32,
    padding: vec2<u32>,
}

// One vertex in S′.
struct Vertex {
    position: vec4<f32>,
    normal: vec4<f32>,
    color: vec4<f32>,
    // Texture coordinates in xy.
    uv: vec4<f32>,
}

// Entries of the ray tracer's traversal stack (srt_gpu::types::BVH_STACK_SIZE).
const BVH_STACK_SIZE: u32 = 64u;

// One node of a batch's BVH in S′ (srt_gpu::bvh::PartBvh).
struct BvhNode {
    // Lower corner of the (widened) box.
    min: vec3<f32>,
    // Triangles in this leaf; 0 for an inner node.
    primitive_count: u32,
    // Upper corner of the (widened) box.
    max: vec3<f32>,
    // An inner node's first child (the second follows it); a leaf's first primitive entry.
    first: u32,
}

// One triangle of an object as the ray tracer reads it, in its BVH's leaf order
// (srt_gpu::types::GpuRtTriangle): corners in S′ and the id the visibility pass writes.
struct RtTriangle {
    p0: vec3<f32>,
    // The batch's part id (PartUniforms.id).
    part: u32,
    p1: vec3<f32>,
    // The triangle's number in its batch.
    triangle: u32,
    p2: vec3<f32>,
    padding: u32,
}

// Most lights on their own worldlines (srt_gpu::types::MAX_MOVING_LIGHTS, srt_scene's).
const MAX_MOVING_LIGHTS: u32 = 8u;

// One light on its own worldline (srt_scene::MovingLight; twin of srt_gpu::types::GpuMovingLight):
// it rests at the origin of its frame, whose worldline in S is offset + β·ct.
struct MovingLight {
    // The frame's offset a (xyz) and the light's Planck temperature in its rest frame (w).
    offset_temperature: vec4<f32>,
    // β (xyz) and γ (w).
    beta_gamma: vec4<f32>,
    // The strength (x: irradiance at unit distance in its frame, in units of the lamp's diffuse
    // light) and 1 − β², computed in f64 (y); zw unused.
    strength: vec4<f32>,
}

// Per image: the lamp's strength and the moving lights (srt_gpu::shadows::light_uniforms).
struct LightUniforms {
    // The lamp's strength (x: a factor on all its light, srt_scene::Light::strength); yzw unused.
    lamp: vec4<f32>,
    // Moving lights in use (x), shadow casters in shadow_scene (y), the rows of shadow_scene
    // where the BVH nodes (z) and the triangles (w) begin.
    counts: vec4<u32>,
    moving: array<MovingLight, MAX_MOVING_LIGHTS>,
}

// One shadow caster as shadow_scene holds it (twin of srt_gpu::types::GpuShadowObject), in
// SHADOW_OBJECT_ROWS rows of vec4<u32>.
struct ShadowObject {
    // Λ_−β of its rest frame: S four-vectors → S′.
    observer_to_rest: mat4x4<f32>,
    // Its frame's offset a (xyz), 0.
    offset: vec4<f32>,
    // Its BVH's root node (x), 1 if it emits light and casts no shadow (y), its index in scene
    // order (z); w unused.
    bvh: vec4<u32>,
}

// Rows (vec4<u32>) of shadow_scene per ShadowObject, BvhNode and triangle (RtTriangle's layout)
// (srt_gpu::types::SHADOW_*_ROWS).
const SHADOW_OBJECT_ROWS: u32 = 6u;
const SHADOW_NODE_ROWS: u32 = 2u;
const SHADOW_TRIANGLE_ROWS: u32 = 3u;

// The image-space footprint of one apparent triangle (srt_proxy::Footprint) as the proxy pass
// stores it and the visibility passes draw it: the convex polygon drawn, in pixels (a
// rectangle is stored as its four corners), and what names and orders it; 64 bytes.
struct Footprint {
    hull: array<vec2<f32>, FOOTPRINT_HULL_POINTS>,
    // The triangle of the batch it is a footprint of (itself, or a piece of it).
    triangle: u32,
    // The depth the footprint is drawn at: at most that of any hit its fragments can find
    // (proxy.wgsl, nearest_depth), so that the visibility passes may declare the depth they
    // write "greater or equal" (srt_gpu::shaders::ConservativeDepth).
    nearest_depth: f32,
    // The hull's valid points (FOOTPRINT_HULL_LEN; 0 for a footprint that draws nothing: a
    // culled back face, or a triangle nothing of which is on screen) and the flags
    // FOOTPRINT_WHOLE_SCREEN and FOOTPRINT_PIECES_OVERFLOWED.
    flags: u32,
    padding: u32,
}

// Footprint.flags: the bits that hold the hull's number of valid points (at most
// FOOTPRINT_HULL_POINTS).
const FOOTPRINT_HULL_LEN: u32 = 7u;
const_assert FOOTPRINT_HULL_POINTS <= FOOTPRINT_HULL_LEN;
// Footprint.flags: a whole-screen footprint.
const FOOTPRINT_WHOLE_SCREEN: u32 = 8u;
// Footprint.flags: in a triangle's own slot, the batch's piece slots ran out while its pieces
// were stored, and the footprint is the rectangle holding all of them (proxy.wgsl,
// split_footprint).
const FOOTPRINT_PIECES_OVERFLOWED: u32 = 16u;

// One star of the sky (srt_scene::Star), at rest in the world frame W.
struct Star {
    // Unit direction observer → star in W (xyz) and black-body temperature in kelvin (w).
    direction_temperature: vec4<f32>,
    // Visual magnitude at rest (x); yzw unused.
    magnitude: vec4<f32>,
}

// Per image: how the sky moves and how bright its stars are.
struct SkyUniforms {
    // Velocity of W relative to S (xyz); the saturation magnitude (w): a star of it at rest fills
    // one pixel with its full colour.
    beta_saturation: vec4<f32>,
    // Number of stars (x), the sky image's width (y) and height (z), 1 if there is an image (w).
    counts: vec4<u32>,
    // Directions at rest in W → directions in S before aberration (the identity except in the
    // measured view), and its inverse.
    direction_map: mat3x3<f32>,
    direction_unmap: mat3x3<f32>,
    // The sky image's brightness factor (x); yzw unused.
    image: vec4<f32>,
    // Supersampling (x): each output pixel is x × x target pixels, and a star lights every
    // target pixel of the output pixels around it (srt_trace::star_layer's tent at the output's
    // size), as the CPU reference adds it to every sample of them; yzw unused.
    supersampling: vec4<u32>,
}

// The kernel probes of probe.wgsl (srt_gpu::probe).

// One set of arguments for every physics kernel.
struct PhysicsProbeInput {
    frame: Frame,
    // An event in S (ct, x, y, z) for to_rest.
    event: vec4<f32>,
    // An event in S′ (ct′, x′, y′, z′) for to_observer.
    rest_event: vec4<f32>,
    // A point at rest in S′ (xyz) for emission_event, apparent_position and apparent_tangent;
    // the ray parameter s for apparent_distance (w).
    point: vec4<f32>,
    // A direction in S′ (xyz) for apparent_tangent; w unused.
    direction: vec4<f32>,
    // A viewing direction in S (xyz, any length) for backward_ray; w unused.
    view: vec4<f32>,
    // A propagation direction in S (xyz) for doppler_factor; w unused.
    propagation: vec4<f32>,
    // A propagation direction in S′ (xyz) for aberrate with the frame's β; w unused.
    direction_rest: vec4<f32>,
    // Incident propagation direction (xyz) for reflection_doppler; w unused.
    incident: vec4<f32>,
    // Outgoing propagation direction (xyz) for reflection_doppler; w unused.
    outgoing: vec4<f32>,
}

// Every physics kernel's result for one PhysicsProbeInput.
struct PhysicsProbeOutput {
    to_observer: vec4<f32>,
    to_rest: vec4<f32>,
    emission_event: vec4<f32>,
    // xyz; w = 0.
    apparent_position: vec4<f32>,
    // xyz; w = 0.
    apparent_tangent: vec4<f32>,
    // xyz; w = 0.
    aberrate: vec4<f32>,
    // backward_ray(frame, view): origin (xyz) and ct_origin (w).
    ray_origin: vec4<f32>,
    // backward_ray(frame, view): direction (xyz); w = 0.
    ray_direction: vec4<f32>,
    // doppler_factor, reflection_doppler, apparent_distance (along the ray above at s),
    // lorentz_factor.
    scalars: vec4<f32>,
}

// One set of arguments of the spectral kernels (spectral.wgsl).
struct SpectralProbeInput {
    // sRGB-encoded surface colour (xyz), as shading hands it over; light temperature in kelvin
    // (w), also the emitter's temperature.
    rgb_temperature: vec4<f32>,
    // D_in, D_out, exposure, TONE_MAP_* as a float.
    factors: vec4<f32>,
    // Ultraviolet and infrared reflectances (< 0: none); emission brightness (z); unused (w).
    bands: vec4<f32>,
}

// The spectral kernels' results for one SpectralProbeInput.
struct SpectralProbeOutput {
    // spectral_reflected_display (xyz), w = 0.
    reflected: vec4<f32>,
    // spectral_emitted_display at temperature rgb_temperature.w, D_out, brightness (xyz), w = 0.
    emitted: vec4<f32>,
}
