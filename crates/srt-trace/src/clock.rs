//! Drawing a clock face ([`srt_scene::Clock`]) showing a reading: a ring with twelve ticks, a slow
//! hand (one turn per `dial` units of reading), a fast hand (one turn per unit) and the reading
//! in seven-segment digits with one decimal (its last three integer digits and the sign), in a
//! texture's unit square (u right, v down). Every shape is a signed distance in texture units,
//! turned into ink coverage over the pixel's footprint there, so the face is antialiased at any
//! size. The GPU mirrors it in `shaders/clock.wgsl` (`clock_albedo`), with the same constants.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3, DVec4};
use srt_scene::Clock;

/// The dial, in texture units from the face's centre: the ring's radius and half width, the
/// radius where the ticks start (they end at the ring) and the ticks' half width (WGSL
/// `CLOCK_DIAL`).
pub const CLOCK_DIAL: [f64; 4] = [0.45, 0.012, 0.37, 0.012];

/// The hands: the slow hand's length and half width, the fast hand's (WGSL `CLOCK_HANDS`).
pub const CLOCK_HANDS: [f64; 4] = [0.24, 0.022, 0.38, 0.011];

/// The digits' row: its centre's height above the face's centre (negative: below), the pitch of
/// its five cells (three digits and the tenths after a sign, which stands just before the first
/// digit shown), a glyph's half width and half height (WGSL `CLOCK_DIGITS`).
pub const CLOCK_DIGITS: [f64; 4] = [-0.2, 0.11, 0.04, 0.07];

/// The half width of a digit's strokes, the hub's radius, the decimal point's radius and the
/// smallest footprint a pixel is given (where its neighbours' rays miss the triangle; WGSL
/// `CLOCK_STROKES`).
pub const CLOCK_STROKES: [f64; 4] = [0.009, 0.03, 0.012, 1e-4];

/// Seven-segment patterns of the digits 0–9: bits 0–6 are the segments a (top), b (top right),
/// c (bottom right), d (bottom), e (bottom left), f (top left), g (middle) (WGSL
/// `CLOCK_SEGMENTS`).
pub const CLOCK_SEGMENTS: [u32; 10] = [0x3f, 0x06, 0x5b, 0x4f, 0x66, 0x6d, 0x7d, 0x07, 0x7f, 0x6f];

/// The segment pattern of a minus sign (g alone).
const MINUS: u32 = 0x40;

/// The colour of `clock`'s face at texture coordinates `uv` (repeating) showing its reading at
/// proper time `proper_time`, with `ddx`, `ddy` the change of `uv` to the neighbouring pixels
/// (the footprint the ink is spread over): face and ink colours mixed by coverage, alpha 1.
#[must_use]
pub fn clock_albedo(clock: &Clock, uv: DVec2, ddx: DVec2, ddy: DVec2, proper_time: f64) -> DVec4 {
    let footprint = ddx.length().max(ddy.length()).max(CLOCK_STROKES[3]);
    let within = uv - uv.floor();
    let q = DVec2::new(within.x - 0.5, 0.5 - within.y);
    let ink = clock_ink(q, clock.reading(proper_time), clock.dial, footprint);
    DVec3::from(clock.face)
        .lerp(DVec3::from(clock.ink), ink)
        .extend(1.0)
}

/// How much of a pixel of width `footprint` centred at `q` (from the face's centre, y up) the
/// face's ink covers, in [0, 1], showing `reading` with `dial` units per turn of the slow hand.
#[must_use]
pub fn clock_ink(q: DVec2, reading: f64, dial: f64, footprint: f64) -> f64 {
    let cover = |distance: f64| (0.5 - distance / footprint).clamp(0.0, 1.0);
    let [ring_radius, ring_half_width, tick_start, tick_half_width] = CLOCK_DIAL;
    let [slow_length, slow_half_width, fast_length, fast_half_width] = CLOCK_HANDS;
    let radius = q.length();
    let mut ink = cover((radius - ring_radius).abs() - ring_half_width);
    // The nearest of the twelve ticks, a box along its radius.
    let step = TAU / 12.0;
    let tick = (q.x.atan2(q.y) / step + 0.5).floor() * step;
    let (along, across) = along_and_across(q, tick);
    let tick_box = box_distance(
        DVec2::new(along - 0.5 * (tick_start + ring_radius), across),
        DVec2::new(0.5 * (ring_radius - tick_start), tick_half_width),
    );
    ink = ink.max(cover(tick_box));
    for (angle, length, half_width) in [
        (TAU * fraction(reading / dial), slow_length, slow_half_width),
        (TAU * fraction(reading), fast_length, fast_half_width),
    ] {
        let direction = DVec2::new(angle.sin(), angle.cos());
        let nearest = direction * q.dot(direction).clamp(0.0, length);
        ink = ink.max(cover((q - nearest).length() - half_width));
    }
    ink = ink.max(cover(radius - CLOCK_STROKES[1]));
    ink.max(digits_ink(q, reading, footprint))
}

/// The coverage of the reading's digits at `q`.
fn digits_ink(q: DVec2, reading: f64, footprint: f64) -> f64 {
    let cover = |distance: f64| (0.5 - distance / footprint).clamp(0.0, 1.0);
    let [row, pitch, half_width, half_height] = CLOCK_DIGITS;
    let [stroke, _, point_radius, _] = CLOCK_STROKES;
    let left = -2.5 * pitch;
    // The decimal point, between the units and the tenths.
    let point = DVec2::new(left + 4.0 * pitch, row - half_height + stroke);
    let mut ink = cover((q - point).length() - point_radius);
    let cell = ((q.x - left) / pitch).floor();
    if !(0.0..5.0).contains(&cell) {
        return ink;
    }
    // Tenths of the reading's magnitude, the last four digits.
    let tenths = (reading.abs() * 10.0 + 0.5).floor();
    let shown = tenths - (tenths / 10_000.0).floor() * 10_000.0;
    let digit = |place: f64| (shown / place).floor() - (shown / (10.0 * place)).floor() * 10.0;
    // Leading zeros are left out; the sign goes just before the first digit shown.
    let first_digit = if shown >= 1000.0 {
        1.0
    } else if shown >= 100.0 {
        2.0
    } else {
        3.0
    };
    let segments = if cell < first_digit {
        if cell == first_digit - 1.0 && reading < 0.0 && shown > 0.0 {
            MINUS
        } else {
            0
        }
    } else {
        let place = [1000.0, 100.0, 10.0, 1.0][cell as usize - 1];
        CLOCK_SEGMENTS[digit(place) as usize]
    };
    let local = DVec2::new(q.x - left - (cell + 0.5) * pitch, q.y - row);
    let horizontal = DVec2::new(half_width, stroke);
    let vertical = DVec2::new(stroke, 0.5 * half_height);
    let (side, top) = (half_width - stroke, half_height - stroke);
    let boxes = [
        (DVec2::new(0.0, top), horizontal),
        (DVec2::new(side, 0.5 * half_height), vertical),
        (DVec2::new(side, -0.5 * half_height), vertical),
        (DVec2::new(0.0, -top), horizontal),
        (DVec2::new(-side, -0.5 * half_height), vertical),
        (DVec2::new(-side, 0.5 * half_height), vertical),
        (DVec2::ZERO, horizontal),
    ];
    for (bit, (centre, half_size)) in boxes.into_iter().enumerate() {
        if segments & (1 << bit) != 0 {
            ink = ink.max(cover(box_distance(local - centre, half_size)));
        }
    }
    ink
}

/// `x` − ⌊x⌋ (WGSL's `fract`).
fn fraction(x: f64) -> f64 {
    x - x.floor()
}

/// The components of `q` along the direction at `angle` clockwise from +y, and across it.
fn along_and_across(q: DVec2, angle: f64) -> (f64, f64) {
    let (sin, cos) = angle.sin_cos();
    (q.x * sin + q.y * cos, q.x * cos - q.y * sin)
}

/// Signed distance from `p` to the axis-aligned box of half size `half_size` centred at 0.
fn box_distance(p: DVec2, half_size: DVec2) -> f64 {
    let d = p.abs() - half_size;
    d.max(DVec2::ZERO).length() + d.x.max(d.y).min(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ink at `q` of a sharp (small-footprint) face showing `reading`.
    fn ink(q: DVec2, reading: f64) -> f64 {
        clock_ink(q, reading, 12.0, 1e-5)
    }

    /// Which of the five cells of the digit row show ink along the row's middle line and
    /// through the segments' centres: the pattern each cell shows, as a segment mask.
    fn shown_segments(reading: f64) -> [u32; 5] {
        let [row, pitch, half_width, half_height] = CLOCK_DIGITS;
        let stroke = CLOCK_STROKES[0];
        let (side, top) = (half_width - stroke, half_height - stroke);
        let probes = [
            (0.0, top),
            (side, 0.5 * half_height),
            (side, -0.5 * half_height),
            (0.0, -top),
            (-side, -0.5 * half_height),
            (-side, 0.5 * half_height),
            (0.0, 0.0),
        ];
        std::array::from_fn(|cell| {
            let centre = -2.5 * pitch + (cell as f64 + 0.5) * pitch;
            probes
                .iter()
                .enumerate()
                .filter(|(_, (x, y))| {
                    digits_ink(DVec2::new(centre + x, row + y), reading, 1e-5) > 0.5
                })
                .fold(0, |mask, (bit, _)| mask | (1 << bit))
        })
    }

    #[test]
    fn the_digits_read_the_reading_to_a_tenth() {
        let d = CLOCK_SEGMENTS;
        assert_eq!(shown_segments(7.34), [0, 0, 0, d[7], d[3]]);
        assert_eq!(shown_segments(-12.96), [0, MINUS, d[1], d[3], d[0]]);
        assert_eq!(shown_segments(-0.5), [0, 0, MINUS, d[0], d[5]]);
        assert_eq!(shown_segments(-0.01), [0, 0, 0, d[0], d[0]]);
        assert_eq!(shown_segments(4321.04), [0, d[3], d[2], d[1], d[0]]);
        assert_eq!(shown_segments(0.0), [0, 0, 0, d[0], d[0]]);
    }

    #[test]
    fn the_hands_point_at_the_reading() {
        let [slow_length, _, fast_length, _] = CLOCK_HANDS;
        // Reading 3.25 on a twelve-unit dial: the slow hand a little past 3 o'clock (97.5°), the
        // fast hand at a quarter turn, 3 o'clock (90°).
        let at = |degrees: f64, radius: f64| {
            let a = degrees.to_radians();
            DVec2::new(a.sin(), a.cos()) * radius
        };
        assert!(ink(at(97.5, 0.8 * slow_length), 3.25) > 0.99);
        assert!(ink(at(90.0, 0.95 * fast_length), 3.25) > 0.99);
        // Where neither hand is: at 10 o'clock inside the ticks.
        assert!(ink(at(300.0, 0.3), 3.25) < 0.01);
        // A quarter unit later the fast hand has turned to 6 o'clock.
        assert!(ink(at(180.0, 0.95 * fast_length), 3.5) > 0.99);
        assert!(ink(at(90.0, 0.95 * fast_length), 3.5) < 0.01);
    }

    #[test]
    fn coverage_spreads_over_the_footprint() {
        // Across the ring's outer edge, coverage falls from 1 to 0 over one footprint.
        let edge = CLOCK_DIAL[0] + CLOCK_DIAL[1];
        let footprint = 0.01;
        let at = |r: f64| clock_ink(DVec2::new(0.0, r), 0.5, 12.0, footprint);
        assert!((at(edge) - 0.5).abs() < 1e-9);
        assert!(at(edge - footprint) > 0.99 && at(edge + footprint) < 0.01);
    }
}
