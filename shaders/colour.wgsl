// colour.wgsl — the apparent-temperature colour table, the GPU mirror of
// srt_color::TemperatureLut::sample (crates/srt-color/src/lut.rs).
//
// Interface (stable; the LRT and polygon passes call it):
//
//   fn lut_sample(table: texture_2d<f32>, params: vec4<f32>, t: f32) -> vec4<f32>
//   fn radiance_table_sample(table: texture_2d<f32>, params: vec4<f32>, t: f32) -> vec4<f32>
//
// - `table`: the LUT's N texels as row 0 of an N × 2 `rgba32float` 2D texture (2D rather than
//   1D because naga's GLSL output mistranslates `texture_1d` function parameters), bound with
//   sample type `float` (filterable: false) — no sampler: two `textureLoad`s and a lerp in f32, so no
//   `float32-filterable` feature is needed and the filter weight is not quantised. Row 1 holds
//   the radiance table over the same temperatures (srt_color::RadianceTable: the black body's
//   linear BT.709 colour at luminance 1, ln Y in alpha), read by `radiance_table_sample`.
// - `params`: (ln T_min, ln T_max, N, unused), i.e. FrameUniforms.lut; srt_gpu::lut::lut_params
//   builds it from a TemperatureLut.
// - `t`: the temperature in kelvin (D · T_light, §4.2).
//
// Rule, step for step as on the CPU: u = (ln t − ln T_min) / (ln T_max − ln T_min) clamped to
// [0, 1]; x = u (N − 1); i = ⌊x⌋ (at most N − 1); f = x − i; result (1 − f) texel[i] +
// f texel[min(i + 1, N − 1)]. A temperature that is not a positive finite number (NaN, ±∞, ≤ 0,
// −0) gives texel 0, as on the CPU. That test reads the bits rather than comparing floats, so a
// shader compiler that assumes no NaN/∞ cannot fold it away. The GPU's u differs from the CPU's
// only by f32 rounding and the GPU's `log` (a few ulp), a few thousandths of a texel (the CPU
// additionally snaps x to a texel centre within 1e-9, which f32 cannot resolve anyway).

// Whether `t` is a positive finite f32 (subnormals included): sign bit clear, exponent not all
// ones, not ±0.
fn lut_is_positive_finite(t: f32) -> bool {
    let bits = bitcast<u32>(t);
    return bits != 0u && bits < 0x7f800000u;
}

// The colour of temperature `t` in the table `table` with parameters `params` (see above).
fn lut_sample(table: texture_2d<f32>, params: vec4<f32>, t: f32) -> vec4<f32> {
    return lut_row_sample(table, params, t, 0);
}

// The radiance texel (colour at luminance 1, ln Y) of temperature `t` (row 1, see above).
fn radiance_table_sample(table: texture_2d<f32>, params: vec4<f32>, t: f32) -> vec4<f32> {
    return lut_row_sample(table, params, t, 1);
}

// Row `row` of `table` at temperature `t`, interpolated by the rule above.
fn lut_row_sample(table: texture_2d<f32>, params: vec4<f32>, t: f32, row: i32) -> vec4<f32> {
    let last = max(i32(params.z) - 1, 0);
    var u = 0.0;
    if lut_is_positive_finite(t) {
        u = clamp((log(t) - params.x) / (params.y - params.x), 0.0, 1.0);
    }
    let x = u * f32(last);
    let i = min(i32(floor(x)), last);
    let f = x - f32(i);
    let a = textureLoad(table, vec2<i32>(i, row), 0);
    let b = textureLoad(table, vec2<i32>(min(i + 1, last), row), 0);
    return (1.0 - f) * a + f * b;
}

// The weights (R, G, B) of the grey value of Eq. 18 (twin of srt_trace::GREY_WEIGHTS).
const GREY_WEIGHTS: vec3<f32> = vec3<f32>(0.3, 0.59, 0.11);

// Grey value 𝒢 = 0.3R + 0.59G + 0.11B of Eq. 18.
fn grey_value(c: vec4<f32>) -> f32 {
    return dot(c.rgb, GREY_WEIGHTS);
}
