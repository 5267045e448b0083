// Showing a frame: copies the renderer's display colours (sRGB-encoded floats) into an 8-bit
// target, quantised as the CPU reference quantises them (srt_color::quantize_8bit: clamp to
// [0, 1], times 255, rounded half up), so that a window or a web page shows the bytes the PNG
// holds. Mirror: srt-gpu's `display` module.

@group(0) @binding(0) var display_source: texture_2d<f32>;

@vertex
fn display_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the whole target.
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn display_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let colour = textureLoad(display_source, vec2<i32>(position.xy), 0).rgb;
    let levels = floor(clamp(colour, vec3<f32>(0.0), vec3<f32>(1.0)) * 255.0 + 0.5);
    return vec4<f32>(levels / 255.0, 1.0);
}
