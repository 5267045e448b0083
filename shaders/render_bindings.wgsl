// render_bindings.wgsl — resources shared by the proxy, LRT and polygon passes (groups 0–2;
// each pass declares its own group 3). Their Rust description is in
// crates/srt-gpu/src/pipelines.rs (slots); tests/reflect.rs checks it against these
// declarations.
//
// The per-frame, per-object and per-part values (and the sky's) are read-only storage buffers,
// not uniform buffers. Mesa 22.3's lavapipe (Debian 12's Vulkan driver on a CPU) "inlines" the
// values of a uniform buffer that decide a branch into the shader and, keeping no variant,
// clones, optimises and compiles the shader again at every bind group bound while such a buffer
// is: once per object part in every pass, about 280 ms of a 45-object flythrough frame
// (docs/performance-log.md, 2026-11-26). It never inlines storage buffers. On the GL backend
// they are declared uniform instead (srt_gpu::shaders::BlockSpace, which says why). The
// reflection test (crates/srt-gpu/tests/reflect.rs) checks both declarations against the
// layouts and that no render pass binds another uniform buffer.

@group(0) @binding(0) var<storage, read> frame_uniforms: FrameUniforms;
@group(0) @binding(1) var lut_table: texture_2d<f32>;

@group(1) @binding(0) var<storage, read> object: ObjectUniforms;

@group(2) @binding(0) var<storage, read> part: PartUniforms;
@group(2) @binding(1) var<storage, read> vertices: array<Vertex>;
@group(2) @binding(2) var<storage, read> indices: array<u32>;
@group(2) @binding(3) var part_texture: texture_2d<f32>;

// Whether `flag` (one of the PART_* bits of types.wgsl) is set for the current part.
fn part_has(flag: u32) -> bool {
    return (part.flags & flag) != 0u;
}

// Rest-frame corners of triangle `t` of the current part.
fn triangle_corners(t: u32) -> array<vec3<f32>, 3> {
    return array<vec3<f32>, 3>(
        vertices[indices[3u * t]].position.xyz,
        vertices[indices[3u * t + 1u]].position.xyz,
        vertices[indices[3u * t + 2u]].position.xyz,
    );
}
