// light.wgsl — the light a pass draws at a pixel and the value it writes for it: the mirror of
// srt_trace::Arriving. A light is shown as a display colour through the frame's tone map
// (Arriving::display) or measured as radiance, linear BT.709 before any tone map, in the unit of
// srt-color's `radiance` module (Arriving::radiance, RadianceScale); FrameUniforms.output says
// which. The two are computed from the same light, never one from the other.
//
// Composed after colour.wgsl and spectral.wgsl into the passes that shade (lrt, polygon) and the
// sky; reads `frame_uniforms` and `lut_table` (whose row 1 is the radiance table). LightSum adds
// the lights of several sources (surface.wgsl's moving lights).

// FrameUniforms.output: display colours (twin of srt_gpu::types::OutputCode::DISPLAY).
const OUTPUT_DISPLAY: u32 = 0u;
// FrameUniforms.output: radiance (twin of srt_gpu::types::OutputCode::RADIANCE).
const OUTPUT_RADIANCE: u32 = 1u;
// FrameUniforms.output: what each pixel sees of time (surface.wgsl's seen_pixel): emission ct_W,
// proper time, apparent distance, Doppler factor (twin of OutputCode::SEEN_EVENT).
const OUTPUT_SEEN_EVENT: u32 = 2u;
// FrameUniforms.output: the seen object's index in x (twin of OutputCode::SEEN_OBJECT).
const OUTPUT_SEEN_OBJECT: u32 = 3u;

// Arriving.kind: a colour-table light factor · C(temperature_k) (Arriving::Table).
const ARRIVING_TABLE: u32 = 0u;
// Arriving.kind: a spectrum times its geometric factor (Arriving::Spectrum).
const ARRIVING_SPECTRUM: u32 = 1u;
// Arriving.kind: no light (Arriving::Dark).
const ARRIVING_DARK: u32 = 2u;

// The light a pass draws somewhere (srt_trace::Arriving).
struct Arriving {
    // One of ARRIVING_*.
    kind: u32,
    // k of a colour-table light; the geometric factor of a spectrum.
    factor: f32,
    // The apparent temperature T of a colour-table light.
    temperature_k: f32,
    // The light of a spectrum, with its luminance white.
    spectrum: SpectralLight,
}

// No light.
fn dark_light() -> Arriving {
    return Arriving(ARRIVING_DARK, 0.0, 0.0, SpectralLight(vec3<f32>(0.0), vec3<f32>(0.0), 0.0, false));
}

// The colour-table light `factor` · C(`temperature_k`).
fn table_light(factor: f32, temperature_k: f32) -> Arriving {
    var light = dark_light();
    light.kind = ARRIVING_TABLE;
    light.factor = factor;
    light.temperature_k = temperature_k;
    return light;
}

// The spectrum `spectrum` times `factor`; no light where the spectrum is invalid (the CPU's
// errors, which it shows as black).
fn spectrum_light(spectrum: SpectralLight, factor: f32) -> Arriving {
    var light = dark_light();
    if (spectrum.valid) {
        light.kind = ARRIVING_SPECTRUM;
        light.factor = factor;
        light.spectrum = spectrum;
    }
    return light;
}

// Display colour (sRGB-encoded, not clamped) of `light`: the colour table, spectra through the
// tone map with the frame's exposure (mirror of Arriving::display).
fn arriving_display(light: Arriving) -> vec3<f32> {
    if (light.kind == ARRIVING_TABLE) {
        return light.factor * lut_sample(lut_table, frame_uniforms.lut, light.temperature_k).rgb;
    }
    if (light.kind == ARRIVING_SPECTRUM) {
        let exposure = frame_uniforms.exposure * light.factor;
        return spectral_display(light.spectrum, SpectralView(frame_uniforms.tone_map, exposure, frame_uniforms.searchlight_ln_y));
    }
    return vec3<f32>(0.0);
}

// The light of several sources on one surface point (the lamp's and the moving lights':
// srt_trace::Arriving::Tables and Spectra), as the frame's output is formed from it: the sum of
// the colour-table lights' displays, or of every light's radiance (`value`); with spectral
// colour on display, the spectra summed as XYZ before the tone map, each over its own white's Y
// for the luminance map and absolute for the searchlight map (ToneMap::display_rgb_xyz_sum):
// Σ XYZ_i · e^(ln_i − reference) with reference the largest ln_i, held as `xyz` and `reference`
// (so that f32 holds every term's scale).
struct LightSum {
    value: vec3<f32>,
    xyz: vec3<f32>,
    reference: f32,
    // Spectra in `xyz`.
    spectra: u32,
}

// The sum holding `light` alone.
fn light_sum_of(light: Arriving) -> LightSum {
    return light_sum_add(LightSum(vec3<f32>(0.0), vec3<f32>(0.0), 0.0, 0u), light);
}

// `sum` with `light` added: no light, a spectrum with no positive factor, or (luminance map) no
// luminance white adds nothing.
fn light_sum_add(sum: LightSum, light: Arriving) -> LightSum {
    var total = sum;
    if (frame_uniforms.output == OUTPUT_RADIANCE || light.kind == ARRIVING_TABLE) {
        total.value += arriving_output(light);
        return total;
    }
    let l = light.spectrum;
    let luminance = frame_uniforms.tone_map == TONE_MAP_LUMINANCE;
    if (light.kind != ARRIVING_SPECTRUM || !(light.factor > 0.0) || (luminance && !(l.white.y > 0.0))) {
        return total;
    }
    // ln of the light's scale with its factor, over its white's luminance (whose scale is the
    // light's) for the luminance map.
    var ln = l.ln_scale + log(light.factor);
    if (luminance) {
        ln = log(light.factor) - log(l.white.y);
    }
    if (total.spectra == 0u) {
        total.xyz = l.light;
        total.reference = ln;
    } else if (ln > total.reference) {
        total.xyz = total.xyz * exp(total.reference - ln) + l.light;
        total.reference = ln;
    } else {
        total.xyz += l.light * exp(ln - total.reference);
    }
    total.spectra++;
    return total;
}

// The value the frame writes for the lights of `sum` (FrameUniforms.output), before
// output_pixel (mirror of Arriving::display and Arriving::radiance of several sources).
fn light_sum_output(sum: LightSum) -> vec3<f32> {
    if (frame_uniforms.output == OUTPUT_RADIANCE || frame_uniforms.colour != SURFACE_COLOUR_SPECTRAL) {
        return sum.value;
    }
    if (sum.spectra == 0u) {
        return vec3<f32>(0.0);
    }
    let view = SpectralView(frame_uniforms.tone_map, frame_uniforms.exposure, frame_uniforms.searchlight_ln_y);
    return spectral_sum_display(sum.xyz, sum.reference, view);
}

// Whether every component of `v` is finite (read from the bits, so that a compiler assuming no
// NaN or ∞ cannot fold the test away).
fn all_finite(v: vec3<f32>) -> bool {
    let exponents = bitcast<vec3<u32>>(v) & vec3<u32>(0x7f800000u);
    return all(exponents != vec3<u32>(0x7f800000u));
}

// ln of (just under) the largest finite f32.
const LN_LARGEST_F32: f32 = 88.7228;

// `rgb` × e^`ln_gain`, each channel computed in the log domain and its magnitude held under f32's
// largest value, so that a gain beyond f32's range (a nearly invisible lamp's unit,
// docs/colour.md) gives that value rather than ∞ (the CPU's EXR holds such channels at the same
// limit); a zero channel stays 0. output_pixel then holds the pixel to the colour target's range.
fn scaled_radiance(rgb: vec3<f32>, ln_gain: f32) -> vec3<f32> {
    let magnitude = exp(min(log(abs(rgb)) + ln_gain, vec3<f32>(LN_LARGEST_F32)));
    return select(magnitude, -magnitude, rgb < vec3<f32>(0.0));
}

// Radiance (linear BT.709, exposure left out) of `light`, with FrameUniforms.radiance = (ln Y of
// the lamp's black body, 1/g, 1 where brightness follows luminance (the searchlight effect) else
// 0, the largest value the colour target holds): mirror of Arriving::radiance, i.e.
// RadianceScale::of_table_light and of_spectrum.
fn arriving_radiance(light: Arriving) -> vec3<f32> {
    let scale = frame_uniforms.radiance;
    let follows_luminance = scale.z > 0.0;
    if (!(light.factor > 0.0)) {
        return vec3<f32>(0.0);
    }
    let ln_factor = log(light.factor * scale.y);
    if (light.kind == ARRIVING_TABLE) {
        let texel = radiance_table_sample(lut_table, frame_uniforms.lut, light.temperature_k);
        var ln_brightness = 0.0;
        if (follows_luminance) {
            ln_brightness = texel.w - scale.x;
        }
        return scaled_radiance(texel.rgb, ln_factor + ln_brightness);
    }
    if (light.kind == ARRIVING_SPECTRUM) {
        let l = light.spectrum;
        var ln_reference = scale.x;
        if (!follows_luminance) {
            if (!(l.white.y > 0.0)) {
                return vec3<f32>(0.0);
            }
            ln_reference = l.ln_scale + log(l.white.y);
        }
        return scaled_radiance(xyz_to_linear_bt709(l.light), l.ln_scale - ln_reference + ln_factor);
    }
    return vec3<f32>(0.0);
}

// The value the frame writes for `light` (FrameUniforms.output), before output_pixel.
fn arriving_output(light: Arriving) -> vec3<f32> {
    if (frame_uniforms.output == OUTPUT_RADIANCE) {
        return arriving_radiance(light);
    }
    return arriving_display(light);
}

// A pixel's value as the colour target stores it: display colours clamped to [0, 1] (as the CPU
// clamps them), radiance held within ± FrameUniforms.radiance.w (the colour target's largest
// finite value: half floats end at 65504).
fn output_pixel(value: vec3<f32>) -> vec4<f32> {
    if (frame_uniforms.output == OUTPUT_RADIANCE) {
        let limit = vec3<f32>(frame_uniforms.radiance.w);
        return vec4<f32>(clamp(value, -limit, limit), 1.0);
    }
    return vec4<f32>(clamp(value, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}
