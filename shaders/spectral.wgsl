// spectral.wgsl — spectral surface colour in f32, the GPU mirror of crates/srt-color's spectral
// path (docs/colour.md): the Jakob–Hanika coefficient table (spectral/table.rs lookup), the
// sigmoid polynomial with its out-of-domain and band policy (spectral/sigmoid.rs,
// spectral/reflect.rs Reflectance::evaluate), the reflected and emitted black-body light summed
// over the CIE 1931 table (reflect.rs reflected_light, emitted_light; Eq. 9–11, 17) and the tone
// maps of Fig. 6 with exposure (tonemap.rs ToneMap::display_rgb_xyz; Eq. 12–13).
//
// Composed into the shaders that shade (lrt, polygon) and the probe. The tables are the CPU's,
// uploaded once per renderer (srt_gpu::spectral), bound in group 0 of those passes.

// The Jakob–Hanika table in one array (srt_gpu::spectral::spectral_words; one binding, not two,
// to stay within eight storage buffers per stage): a header of SPECTRAL_HEADER_WORDS words (n,
// the coefficient table's brightness scale entries, then the CIE table's first and last
// wavelengths in nm, as f32), the scale z₀ … z_{n−1} (CoefficientTable::scale), then the 3 · n³
// texels of (c₀, c₁, c₂), three words each, in CoefficientTable::texels' layout. Read only
// through the accessors below.
@group(0) @binding(8) var<storage, read> spectral_tables: array<f32>;
// Words before the scale (srt_gpu::spectral::SPECTRAL_HEADER_WORDS).
const SPECTRAL_HEADER_WORDS: u32 = 3u;

// The CIE 1931 2° table, rows 360–830 nm at 1 nm (srt_color::cie_1931), one texel per row:
// (x̄, ȳ, z̄, 1/λ in nm⁻¹) (srt_gpu::spectral::cie_texels). A texture, not part of
// spectral_tables: every spectral sum reads all its rows, and llvmpipe reads a storage buffer in
// a fragment shader one lane at a time but fetches a texel for all lanes at once.
@group(0) @binding(9) var spectral_cie: texture_2d<f32>;

// Where each part of spectral_tables starts, and the CIE table's grid, read once per shading
// call rather than once per CIE row.
struct SpectralLayout {
    // n, the brightness scale's entries (the coefficient table's resolution).
    resolution: u32,
    // The word of the coefficient table's first texel.
    texels_at: u32,
    // c, the CIE table's rows.
    rows: u32,
    // The CIE table's first and last wavelengths (nm): the domain the reflectance model was
    // fitted on.
    domain: vec2<f32>,
}

// The layout of spectral_tables from its header and the CIE texture's width.
fn spectral_layout() -> SpectralLayout {
    let resolution = u32(spectral_tables[0]);
    let domain = vec2<f32>(spectral_tables[1], spectral_tables[2]);
    let rows = textureDimensions(spectral_cie).x;
    return SpectralLayout(resolution, SPECTRAL_HEADER_WORDS + resolution, rows, domain);
}

// z_k of the brightness scale.
fn coefficient_scale(k: u32) -> f32 {
    return spectral_tables[SPECTRAL_HEADER_WORDS + k];
}

// Row `s` of the CIE table: x̄, ȳ, z̄ and 1/λ (nm⁻¹).
fn cie_row(s: u32) -> vec4<f32> {
    return textureLoad(spectral_cie, vec2<u32>(s, 0u), 0);
}

// Values Rust owns, set at pipeline creation (srt_gpu::shaders): c₂ = hc/k in m·K and 2hc²
// (Eq. 10), x_max = hc/(kλT) at the maximum of Planck's law in λ (Wien's displacement law,
// srt_color::WIEN_X), the CIE table's step Δλ in m (Eq. 11), and the band edges of the
// reflectance policy (srt_color::spectral::{ULTRAVIOLET_BELOW_NM, INFRARED_ABOVE_NM}).
override SECOND_RADIATION_CONSTANT: f32;
override RADIANCE_CONSTANT: f32;
override WIEN_X: f32;
override CIE_1931_STEP_M: f32;
override ULTRAVIOLET_BELOW_NM: f32;
override INFRARED_ABOVE_NM: f32;

// Largest natural-log gain applied to XYZ normalised by its largest component: e^80 keeps
// Eq. 12 finite in f32, and beyond it every channel the light has saturates on the CPU too (its
// cap, 600, applies to the unnormalised XYZ in f64).
const MAX_LN_GAIN_F32: f32 = 80.0;

// How spectral light becomes a display colour: the tone map (TONE_MAP_*), the exposure, and
// ln Y(1500 K), the searchlight tone map's divisor (srt_color::searchlight_reference_ln_y).
struct SpectralView {
    tone_map: u32,
    exposure: f32,
    searchlight_ln_y: f32,
}

// A surface reflectance spectrum: a Jakob–Hanika sigmoid polynomial, or a grey constant, with
// optional band constants (srt_color::Reflectance).
struct Reflectance {
    // c₀, c₁, c₂ for λ in nm (unused for a grey).
    coefficients: vec3<f32>,
    // The constant reflectance of a grey colour (r = g = b), or −1.
    grey: f32,
    // Reflectance below ULTRAVIOLET_BELOW_NM, or −1 for the model's.
    ultraviolet: f32,
    // Reflectance above INFRARED_ABOVE_NM, or −1 for the model's.
    infrared: f32,
}

// Light as relative XYZ times exp(ln_scale) (srt_color::ScaledXyz), with the light a perfect
// white reflector would send in its place; valid = false for an apparent temperature that is
// not positive and finite (the CPU's errors, which it shows as black).
struct SpectralLight {
    light: vec3<f32>,
    white: vec3<f32>,
    ln_scale: f32,
    valid: bool,
}

// Coefficient (c) of texel `index` of the coefficient table laid out as `tables`.
fn coefficient_texel(tables: SpectralLayout, index: u32) -> vec3<f32> {
    let at = tables.texels_at + 3u * index;
    return vec3<f32>(spectral_tables[at], spectral_tables[at + 1u], spectral_tables[at + 2u]);
}

// Jakob–Hanika coefficients of linear sRGB `rgb` in [0, 1]³ by table lookup and trilinear
// interpolation (Jakob & Hanika 2019 §5; mirror of CoefficientTable::lookup): greys are exact
// constants, otherwise m = the largest channel, z = rgb[m] on the nonlinear brightness scale,
// x, y the other two channels over z.
fn coefficient_lookup(rgb: vec3<f32>, ultraviolet: f32, infrared: f32) -> Reflectance {
    if (rgb.x == rgb.y && rgb.y == rgb.z) {
        return Reflectance(vec3<f32>(0.0), rgb.x, ultraviolet, infrared);
    }
    var m = 2u;
    if (rgb.x > rgb.y) {
        if (rgb.x > rgb.z) {
            m = 0u;
        }
    } else if (rgb.y > rgb.z) {
        m = 1u;
    }
    let tables = spectral_layout();
    let n = tables.resolution;
    let z = rgb[m];
    let last = f32(n - 1u);
    let x = rgb[(m + 1u) % 3u] / z * last;
    let y = rgb[(m + 2u) % 3u] / z * last;
    let i = min(u32(floor(x)), n - 2u);
    let j = min(u32(floor(y)), n - 2u);
    // k: the last scale entry ≤ z (binary search, as partition_point), at most n − 2.
    var lo = 0u;
    var hi = n;
    while (lo < hi) {
        let mid = (lo + hi) / 2u;
        if (coefficient_scale(mid) <= z) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    let k = min(max(lo, 1u) - 1u, n - 2u);
    let t = vec3<f32>(
        x - f32(i),
        y - f32(j),
        (z - coefficient_scale(k)) / (coefficient_scale(k + 1u) - coefficient_scale(k)),
    );
    var sum = vec3<f32>(0.0);
    for (var corner = 0u; corner < 8u; corner++) {
        let d = vec3<u32>(corner & 1u, (corner >> 1u) & 1u, (corner >> 2u) & 1u);
        let w = select(1.0 - t, t, d == vec3<u32>(1u));
        let index = ((m * n + k + d.z) * n + j + d.y) * n + i + d.x;
        sum += (w.x * w.y * w.z) * coefficient_texel(tables, index);
    }
    return Reflectance(sum, -1.0, ultraviolet, infrared);
}

// The sigmoid S(x) = ½ + x / (2√(1 + x²)) of Jakob & Hanika 2019 §3 (srt_color::sigmoid); |x| is
// capped where S is 0 or 1 in f32 anyway, so x² cannot overflow.
fn spectral_sigmoid(x: f32) -> f32 {
    let c = clamp(x, -1.0e18, 1.0e18);
    return 0.5 + 0.5 * c * inverseSqrt(1.0 + c * c);
}

// R(λ) under the policy of reflect.rs: the band constant where one applies, else the model at λ
// held to `domain`, the CIE table's (the fitted) one (mirror of Reflectance::evaluate).
fn reflectance_evaluate(r: Reflectance, wavelength_nm: f32, domain: vec2<f32>) -> f32 {
    if (r.ultraviolet >= 0.0 && wavelength_nm < ULTRAVIOLET_BELOW_NM) {
        return r.ultraviolet;
    }
    if (r.infrared >= 0.0 && wavelength_nm > INFRARED_ABOVE_NM) {
        return r.infrared;
    }
    if (r.grey >= 0.0) {
        return r.grey;
    }
    let l = clamp(wavelength_nm, domain.x, domain.y);
    let c = r.coefficients;
    return spectral_sigmoid((c.x * l + c.y) * l + c.z);
}

// ln(eˣ − 1) for x > 0: x + ln(1 − e^(−x)) on the Wien side, a series for e^x − 1 near 0.
fn ln_expm1(x: f32) -> f32 {
    if (x >= 1.0) {
        return x + log(1.0 - exp(-x));
    }
    if (x < 0.25) {
        return log(x * (1.0 + x / 2.0 * (1.0 + x / 3.0 * (1.0 + x / 4.0 * (1.0 + x / 5.0 * (1.0 + x / 6.0))))));
    }
    return log(exp(x) - 1.0);
}

// ln L(λ, T), Planck's law (Eq. 10) in the logarithmic domain, λ in nm: ln 2hc² − 5 ln λ −
// ln(e^(c₂/λT) − 1) (mirror of srt_color's ln_planck_radiance).
fn ln_planck(wavelength_nm: f32, temperature_k: f32) -> f32 {
    let wavelength_m = wavelength_nm * 1.0e-9;
    let x = SECOND_RADIATION_CONSTANT / wavelength_m / temperature_k;
    return log(RADIANCE_CONSTANT) - 5.0 * log(wavelength_m) - ln_expm1(x);
}

// The largest ln L(λ, T) over the CIE table's wavelengths (planck_weights' ln_max): L is
// unimodal in λ with its peak at c₂/(x_max T) (Wien), so the maximum over the 1 nm grid lies on
// one of the two grid wavelengths around the peak, held to the table's `domain`.
fn ln_planck_max(temperature_k: f32, domain: vec2<f32>) -> f32 {
    let first = domain.x;
    let last = domain.y;
    let peak = clamp(SECOND_RADIATION_CONSTANT / (WIEN_X * temperature_k) * 1.0e9, first, last);
    return max(ln_planck(floor(peak), temperature_k), ln_planck(min(floor(peak) + 1.0, last), temperature_k));
}

// Planck's law relative to its largest value on the CIE grid at one temperature (mirror of
// srt_color's PlanckWeights, whose documentation derives the form): what every sample of a
// spectral sum shares.
struct PlanckWeights {
    // ln L_max, the largest ln L(λ, T) on the grid.
    ln_max: f32,
    // c₂/T in nm: x = c₂/(λT) = x_per_inverse_nm / λ.
    x_per_inverse_nm: f32,
    // λₗ, the table's longest wavelength, in nm.
    longest_nm: f32,
    // 1/λₗ in nm⁻¹.
    inverse_longest_nm: f32,
    // e^(−xₗ).
    exp_minus_x_longest: f32,
    // L(λₗ)/L_max · g(xₗ).
    longest_factor: f32,
}

// g(x) = 1 − e^(−x) for x ≥ 0 given e^(−x): by subtraction from x = ¼ up, else the series of
// −expm1(−x), chosen without a branch (a software rasteriser runs both sides of one).
fn one_minus_exp_minus(x: f32, exp_minus_x: f32) -> f32 {
    let series = x * (1.0 - x / 2.0 * (1.0 - x / 3.0 * (1.0 - x / 4.0 * (1.0 - x / 5.0 * (1.0 - x / 6.0)))));
    return select(series, 1.0 - exp_minus_x, x >= 0.25);
}

// The weights at `temperature_k` over the grid `domain` (nm).
fn planck_weights(temperature_k: f32, domain: vec2<f32>) -> PlanckWeights {
    let ln_max = ln_planck_max(temperature_k, domain);
    let x_per_inverse_nm = SECOND_RADIATION_CONSTANT * 1.0e9 / temperature_k;
    let x_longest = x_per_inverse_nm / domain.y;
    let exp_minus_x_longest = exp(-x_longest);
    let longest_weight = exp(ln_planck(domain.y, temperature_k) - ln_max);
    return PlanckWeights(
        ln_max,
        x_per_inverse_nm,
        domain.y,
        1.0 / domain.y,
        exp_minus_x_longest,
        longest_weight * one_minus_exp_minus(x_longest, exp_minus_x_longest),
    );
}

// L(λ, T) / L_max at the wavelength whose reciprocal (nm⁻¹) is `inverse` (Eq. 10): (λₗ/λ)⁵ ·
// e^(−(x − xₗ)) · g(xₗ)/g(x) · L(λₗ)/L_max, one exponential.
fn planck_weight(weights: PlanckWeights, inverse: f32) -> f32 {
    let x = weights.x_per_inverse_nm * inverse;
    let beyond = exp(-(weights.x_per_inverse_nm * (inverse - weights.inverse_longest_nm)));
    let ratio = weights.longest_nm * inverse;
    let ratio_squared = ratio * ratio;
    return weights.longest_factor * (ratio_squared * ratio_squared * ratio) * beyond
        / one_minus_exp_minus(x, weights.exp_minus_x_longest * beyond);
}

// Whether `t` is a positive finite f32 (read from the bits, as lut_is_positive_finite).
fn spectral_is_positive_finite(t: f32) -> bool {
    let bits = bitcast<u32>(t);
    return bits != 0u && bits < 0x7f800000u;
}

// Σ R(D_out·λ) · B(λ, D_in·D_out·T) · σ(λ) over the CIE table (Eq. 9–11 and 17: the surface sees
// the black body at D_in·T, the observer sees the surface shifted by D_out), with Planck relative
// to its maximum: mirror of srt_color::reflected_light.
fn reflected_light(r: Reflectance, temperature_k: f32, d_in: f32, d_out: f32) -> SpectralLight {
    let apparent = temperature_k * d_in * d_out;
    if (!(spectral_is_positive_finite(apparent) && d_in > 0.0 && d_out > 0.0)) {
        return SpectralLight(vec3<f32>(0.0), vec3<f32>(0.0), 0.0, false);
    }
    let tables = spectral_layout();
    let domain = tables.domain;
    let weights = planck_weights(apparent, domain);
    // The rows are evenly spaced (srt_gpu::spectral's tests), so a row's wavelength is computed.
    let step_nm = (domain.y - domain.x) / f32(tables.rows - 1u);
    var light = vec3<f32>(0.0);
    var white = vec3<f32>(0.0);
    for (var s = 0u; s < tables.rows; s++) {
        let wavelength_nm = domain.x + f32(s) * step_nm;
        let row = cie_row(s);
        let radiance = planck_weight(weights, row.w) * row.xyz;
        light += reflectance_evaluate(r, d_out * wavelength_nm, domain) * radiance;
        white += radiance;
    }
    return SpectralLight(light, white, weights.ln_max + log(CIE_1931_STEP_M), true);
}

// sRGB encoding of one linear component, Eq. 13 (srt_color::srgb_encode) for c ≥ 0.
fn spectral_srgb_encode(c: f32) -> f32 {
    if (c <= 0.0031308) {
        return 12.92 * c;
    }
    return 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

// sRGB decoding of one component, the inverse of Eq. 13 (srt_color::srgb_decode).
fn spectral_srgb_decode(c: f32) -> f32 {
    if (c <= 12.92 * 0.0031308) {
        return c / 12.92;
    }
    return pow((c + 0.055) / 1.055, 2.4);
}

// Display sRGB in [0, 1] of `l` through the tone map of `view` with the logarithm of the
// exposure `ln_exposure` (`view.exposure` is not read here): XYZ / Y_white (luminance) or
// XYZ / Y(1500 K) (searchlight), times the exposure → Eq. 12 → clamp negatives → Eq. 13 → (searchlight: 0.6 log₁₀(C + 1)) → clamp to [0, 1] (Fig. 6;
// mirror of ToneMap::display_rgb_xyz). XYZ is normalised by its largest component first so
// that f32 neither overflows nor underflows; the gain is capped at MAX_LN_GAIN_F32.
fn spectral_tone_map(l: SpectralLight, view: SpectralView, ln_exposure: f32) -> vec3<f32> {
    let largest = max(l.light.x, max(l.light.y, l.light.z));
    let luminance = view.tone_map == TONE_MAP_LUMINANCE;
    if (!l.valid || !(largest > 0.0) || (luminance && !(l.white.y > 0.0))) {
        return vec3<f32>(0.0);
    }
    var ln_gain = ln_exposure + log(largest);
    if (luminance) {
        ln_gain -= log(l.white.y);
    } else {
        ln_gain += l.ln_scale - view.searchlight_ln_y;
    }
    return spectral_encode(l.light / largest * exp(min(ln_gain, MAX_LN_GAIN_F32)), luminance);
}

// The tone map's last steps for XYZ already scaled (spectral_tone_map): Eq. 12 → clamp
// negatives → Eq. 13 → (searchlight, unless `luminance`: 0.6 log₁₀(C + 1)) → clamp to [0, 1].
fn spectral_encode(xyz: vec3<f32>, luminance: bool) -> vec3<f32> {
    let linear = max(xyz_to_linear_bt709(xyz), vec3<f32>(0.0));
    var encoded = vec3<f32>(
        spectral_srgb_encode(linear.x),
        spectral_srgb_encode(linear.y),
        spectral_srgb_encode(linear.z),
    );
    if (!luminance) {
        encoded = 0.6 * log(encoded + 1.0) / log(10.0);
    }
    return clamp(encoded, vec3<f32>(0.0), vec3<f32>(1.0));
}

// Display sRGB in [0, 1] of lights summed as XYZ (light.wgsl's LightSum): `xyz` · e^`ln_scale`,
// already over the whites' luminance for the luminance map, absolute for the searchlight map,
// through `view` (mirror of ToneMap::display_rgb_xyz_sum's tone map: the sum against a white of
// luminance 1). Normalised by its largest component as in spectral_tone_map.
fn spectral_sum_display(xyz: vec3<f32>, ln_scale: f32, view: SpectralView) -> vec3<f32> {
    let largest = max(xyz.x, max(xyz.y, xyz.z));
    if (!(view.exposure > 0.0) || !(largest > 0.0)) {
        return vec3<f32>(0.0);
    }
    let luminance = view.tone_map == TONE_MAP_LUMINANCE;
    var ln_gain = log(view.exposure) + log(largest) + ln_scale;
    if (!luminance) {
        ln_gain -= view.searchlight_ln_y;
    }
    return spectral_encode(xyz / largest * exp(min(ln_gain, MAX_LN_GAIN_F32)), luminance);
}

// Linear BT.709 of CIE XYZ, Eq. 12 with the matrix as printed in the paper
// (srt_color::XYZ_TO_LINEAR_BT709).
fn xyz_to_linear_bt709(xyz: vec3<f32>) -> vec3<f32> {
    let to_rgb = mat3x3<f32>(
        vec3<f32>(3.2405, -0.9693, 0.0556),
        vec3<f32>(-1.5372, 1.8760, -0.2040),
        vec3<f32>(-0.4985, 0.0416, 1.0573),
    );
    return to_rgb * xyz;
}

// Black-body light at `temperature_k` reflected by a surface of sRGB-encoded colour `albedo`
// with band constants `ultraviolet`, `infrared` (< 0: none), seen under D_in and D_out: the
// reflectance of srt-trace's shade (table lookup of the decoded colour), then reflected_light.
fn spectral_reflected(
    albedo: vec3<f32>,
    ultraviolet: f32,
    infrared: f32,
    temperature_k: f32,
    d_in: f32,
    d_out: f32,
) -> SpectralLight {
    let decoded = vec3<f32>(
        spectral_srgb_decode(albedo.x),
        spectral_srgb_decode(albedo.y),
        spectral_srgb_decode(albedo.z),
    );
    return spectral_linear_reflected(decoded, ultraviolet, infrared, temperature_k, d_in, d_out);
}

// spectral_reflected of a linear-light colour `linear` (clamped to [0, 1]³).
fn spectral_linear_reflected(
    linear: vec3<f32>,
    ultraviolet: f32,
    infrared: f32,
    temperature_k: f32,
    d_in: f32,
    d_out: f32,
) -> SpectralLight {
    let r = coefficient_lookup(clamp(linear, vec3<f32>(0.0), vec3<f32>(1.0)), ultraviolet, infrared);
    return reflected_light(r, temperature_k, d_in, d_out);
}

// The light of a black-body emitter at `temperature_k` and brightness 1 seen with Doppler factor
// `d_out` (Eq. 9): the light of a white reflector lit by it, which is also its luminance white
// (mirror of srt_color::emitted_light). Invalid where it has no luminance (the CPU's error).
fn spectral_emitted(temperature_k: f32, d_out: f32) -> SpectralLight {
    var l = reflected_light(Reflectance(vec3<f32>(0.0), 1.0, -1.0, -1.0), temperature_k, 1.0, d_out);
    l.valid = l.valid && l.white.y > 0.0;
    return l;
}

// Display sRGB in [0, 1] of the light `l` through `view`, whose exposure is the renderer's times
// the light's factor: black for an exposure that is not positive (mirror of
// ToneMap::display_rgb_xyz's refusal, which the CPU shows as black).
fn spectral_display(l: SpectralLight, view: SpectralView) -> vec3<f32> {
    if (!(view.exposure > 0.0)) {
        return vec3<f32>(0.0);
    }
    return spectral_tone_map(l, view, log(view.exposure));
}

// Display sRGB of spectral_reflected(…) through `view` (whose exposure is the renderer's times
// the Phong factor): mirror of srt_color::reflected_display_rgb after the table lookup of
// srt-trace's shade.
fn spectral_reflected_display(
    albedo: vec3<f32>,
    ultraviolet: f32,
    infrared: f32,
    temperature_k: f32,
    d_in: f32,
    d_out: f32,
    view: SpectralView,
) -> vec3<f32> {
    return spectral_display(spectral_reflected(albedo, ultraviolet, infrared, temperature_k, d_in, d_out), view);
}

// Display sRGB of a black-body emitter at `temperature_k` with `brightness`, seen with Doppler
// factor `d_out` through `view` (mirror of srt_color::emitted_display_rgb).
fn spectral_emitted_display(temperature_k: f32, brightness: f32, d_out: f32, view: SpectralView) -> vec3<f32> {
    if (!(brightness > 0.0)) {
        return vec3<f32>(0.0);
    }
    let scaled = SpectralView(view.tone_map, view.exposure * brightness, view.searchlight_ln_y);
    return spectral_display(spectral_emitted(temperature_k, d_out), scaled);
}
