// A clock face showing a reading (mirror of srt_trace::clock): a ring with twelve ticks, a slow
// hand (one turn per `dial` units of reading), a fast hand (one turn per unit) and the reading in
// seven-segment digits with one decimal, in a texture's unit square (u right, v down), each shape
// a signed distance turned into ink coverage over the pixel's footprint.

// Ring radius and half width, where the ticks start, tick half width (srt_trace::clock::CLOCK_DIAL).
const CLOCK_DIAL: vec4<f32> = vec4<f32>(0.45, 0.012, 0.37, 0.012);
// Slow hand length and half width, fast hand length and half width (CLOCK_HANDS).
const CLOCK_HANDS: vec4<f32> = vec4<f32>(0.24, 0.022, 0.38, 0.011);
// Digit row height, cell pitch, glyph half width and half height (CLOCK_DIGITS).
const CLOCK_DIGITS: vec4<f32> = vec4<f32>(-0.2, 0.11, 0.04, 0.07);
// Stroke half width, hub radius, decimal point radius, smallest footprint (CLOCK_STROKES).
const CLOCK_STROKES: vec4<f32> = vec4<f32>(0.009, 0.03, 0.012, 1e-4);
// Seven-segment patterns of 0–9, bits a b c d e f g (CLOCK_SEGMENTS).
const CLOCK_SEGMENTS: array<u32, 10> = array<u32, 10>(0x3fu, 0x06u, 0x5bu, 0x4fu, 0x66u, 0x6du, 0x7du, 0x07u, 0x7fu, 0x6fu);
const CLOCK_TAU: f32 = 6.283185307179586;

// Ink coverage of a shape at signed distance `distance` over a pixel of width `footprint`.
fn clock_cover(distance: f32, footprint: f32) -> f32 {
    return clamp(0.5 - distance / footprint, 0.0, 1.0);
}

// Signed distance from `p` to the box of half size `half_size` centred at 0.
fn clock_box(p: vec2<f32>, half_size: vec2<f32>) -> f32 {
    let d = abs(p) - half_size;
    return length(max(d, vec2<f32>(0.0))) + min(max(d.x, d.y), 0.0);
}

// Coverage of the reading's digits at `q` (from the face's centre, y up).
fn clock_digits_ink(q: vec2<f32>, reading: f32, footprint: f32) -> f32 {
    let row = CLOCK_DIGITS.x;
    let pitch = CLOCK_DIGITS.y;
    let half_width = CLOCK_DIGITS.z;
    let half_height = CLOCK_DIGITS.w;
    let stroke = CLOCK_STROKES.x;
    let left = -2.5 * pitch;
    let point = vec2<f32>(left + 4.0 * pitch, row - half_height + stroke);
    var ink = clock_cover(length(q - point) - CLOCK_STROKES.z, footprint);
    let cell = floor((q.x - left) / pitch);
    if (cell < 0.0 || cell >= 5.0) {
        return ink;
    }
    let tenths = floor(abs(reading) * 10.0 + 0.5);
    let shown = tenths - floor(tenths / 10000.0) * 10000.0;
    // Leading zeros are left out; the sign goes just before the first digit shown.
    var first_digit = 3.0;
    if (shown >= 1000.0) {
        first_digit = 1.0;
    } else if (shown >= 100.0) {
        first_digit = 2.0;
    }
    var table = CLOCK_SEGMENTS;
    var segments = 0u;
    if (cell < first_digit) {
        segments = select(0u, 0x40u, cell == first_digit - 1.0 && reading < 0.0 && shown > 0.0);
    } else {
        var places = array<f32, 4>(1000.0, 100.0, 10.0, 1.0);
        let place = places[u32(cell) - 1u];
        let digit = floor(shown / place) - floor(shown / (10.0 * place)) * 10.0;
        segments = table[u32(digit)];
    }
    let local = vec2<f32>(q.x - left - (cell + 0.5) * pitch, q.y - row);
    let horizontal = vec2<f32>(half_width, stroke);
    let vertical = vec2<f32>(stroke, 0.5 * half_height);
    let side = half_width - stroke;
    let top = half_height - stroke;
    var centres = array<vec2<f32>, 7>(
        vec2<f32>(0.0, top),
        vec2<f32>(side, 0.5 * half_height),
        vec2<f32>(side, -0.5 * half_height),
        vec2<f32>(0.0, -top),
        vec2<f32>(-side, -0.5 * half_height),
        vec2<f32>(-side, 0.5 * half_height),
        vec2<f32>(0.0, 0.0),
    );
    for (var bit = 0u; bit < 7u; bit++) {
        if ((segments & (1u << bit)) != 0u) {
            // Segments a, d and g lie along x, the others along y.
            let across = bit == 0u || bit == 3u || bit == 6u;
            let half_size = select(vertical, horizontal, across);
            ink = max(ink, clock_cover(clock_box(local - centres[bit], half_size), footprint));
        }
    }
    return ink;
}

// How much ink covers a pixel of width `footprint` at `q` (from the face's centre, y up) of a
// face showing `reading` with `dial` units per turn of the slow hand (srt_trace::clock::clock_ink).
fn clock_ink(q: vec2<f32>, reading: f32, dial: f32, footprint: f32) -> f32 {
    let radius = length(q);
    var ink = clock_cover(abs(radius - CLOCK_DIAL.x) - CLOCK_DIAL.y, footprint);
    let step = CLOCK_TAU / 12.0;
    let tick = floor(atan2(q.x, q.y) / step + 0.5) * step;
    let along = q.x * sin(tick) + q.y * cos(tick);
    let across = q.x * cos(tick) - q.y * sin(tick);
    let tick_box = clock_box(
        vec2<f32>(along - 0.5 * (CLOCK_DIAL.z + CLOCK_DIAL.x), across),
        vec2<f32>(0.5 * (CLOCK_DIAL.x - CLOCK_DIAL.z), CLOCK_DIAL.w),
    );
    ink = max(ink, clock_cover(tick_box, footprint));
    let angles = vec2<f32>(CLOCK_TAU * fract(reading / dial), CLOCK_TAU * fract(reading));
    let lengths = vec2<f32>(CLOCK_HANDS.x, CLOCK_HANDS.z);
    let half_widths = vec2<f32>(CLOCK_HANDS.y, CLOCK_HANDS.w);
    for (var hand = 0u; hand < 2u; hand++) {
        let direction = vec2<f32>(sin(angles[hand]), cos(angles[hand]));
        let nearest = direction * clamp(dot(q, direction), 0.0, lengths[hand]);
        ink = max(ink, clock_cover(length(q - nearest) - half_widths[hand], footprint));
    }
    ink = max(ink, clock_cover(radius - CLOCK_STROKES.y, footprint));
    return max(ink, clock_digits_ink(q, reading, footprint));
}

// The current object's clock face at texture coordinates `uv` (repeating), showing its reading
// at proper time `proper_time`, with `uv_ddx`, `uv_ddy` the change of `uv` to the neighbouring
// pixels (srt_trace::clock::clock_albedo).
fn clock_albedo(uv: vec2<f32>, uv_ddx: vec2<f32>, uv_ddy: vec2<f32>, proper_time: f32) -> vec4<f32> {
    let footprint = max(max(length(uv_ddx), length(uv_ddy)), CLOCK_STROKES.w);
    let within = uv - floor(uv);
    let q = vec2<f32>(within.x - 0.5, 0.5 - within.y);
    let clock = object.clock;
    let reading = clock.x * proper_time + clock.y;
    let ink = clock_ink(q, reading, clock.z, footprint);
    return vec4<f32>(mix(object.clock_face.rgb, object.clock_ink.rgb, ink), 1.0);
}
