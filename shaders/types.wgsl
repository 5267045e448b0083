// types.wgsl — data shared by every pass. Each struct has a #[repr(C)] twin in
// crates/srt-gpu/src/types.rs; a test compares their layouts field by field through naga.

// Per image: camera, observer, light, shading and colour-table parameters.
struct FrameUniforms {
    // S → clip space (NDC depth in [0, 1], y up).
    view_projection: mat4x4<f32>,
    // Unit viewing direction of the camera, w = 0.
    camera_forward: vec4<f32>,
    // Camera right axis scaled by tan(fov/2)·aspect, w = 0.
    camera_right: vec4<f32>,
    // Camera up axis scaled by tan(fov/2), w = 0.
    camera_up: vec4<f32>,
    // Observer position in S (xyz) and observation time ct_obs (w).
    observer: vec4<f32>,
    // Light position in S (xyz) and its Planck temperature in kelvin (w).
    light: vec4<f32>,
    // Phong factors: ambient, diffuse, specular, shininess.
    shading: vec4<f32>,
    // Background display colour (rgb), alpha 1.
    background: vec4<f32>,
    // Colour table: ln T_min, ln T_max, texel count, unused.
    lut: vec4<f32>,
    // Viewport width, height in pixels and their reciprocals.
    viewport: vec4<f32>,
    // Effects (0 geometry, 1 doppler, 2 searchlight), footprint shape (0 hull, 1 rectangle),
    // unused, unused.
    modes: vec4<u32>,
    // Depth written per fragment is apparent distance × depth_scale.x; yzw unused.
    depth_scale: vec4<f32>,
}

// Per object: its rest frame and drawing style.
struct ObjectUniforms {
    frame: Frame,
    // x: wireframe edge width in S′ units (≤ 0: draw the surface); yzw unused.
    style: vec4<f32>,
}

// Per mesh part: its material.
struct PartUniforms {
    // Base colour factor (sRGB-encoded, as stored in files).
    base_color: vec4<f32>,
    // x: 1 if the part has a texture; y: 1 if its vertices carry colours; z: triangle count;
    // w: 1 if back faces may be culled: the mesh is a closed solid with outward fronts and the
    // observer is outside it (decided per frame on the CPU).
    flags: vec4<u32>,
}

// One vertex in S′.
struct Vertex {
    position: vec4<f32>,
    normal: vec4<f32>,
    color: vec4<f32>,
    // Texture coordinates in xy.
    uv: vec4<f32>,
}

// The image-space footprint of one apparent triangle (srt_proxy::Footprint), in pixels.
struct Footprint {
    hull: array<vec2<f32>, 6>,
    // Rectangle min.xy, max.xy.
    rect: vec4<f32>,
    hull_len: u32,
    whole_screen: u32,
    padding: vec2<u32>,
}
