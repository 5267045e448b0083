//! From CIE XYZ to display values: the BT.709 matrix (Eq. 12) and the sRGB transfer curve (Eq. 13).

use glam::{DMat3, DVec3};

/// The XYZ → linear BT.709 RGB matrix of Eq. 12, exactly as printed in the paper.
///
/// Rows (R, G, B): (3.2405, −1.5372, −0.4985), (−0.9693, 1.8760, 0.0416),
/// (0.0556, −0.2040, 1.0573). glam matrices are column-major, so the constructor below lists the
/// columns, i.e. the printed matrix transposed.
pub const XYZ_TO_LINEAR_BT709: DMat3 = DMat3::from_cols(
    DVec3::new(3.2405, -0.9693, 0.0556),
    DVec3::new(-1.5372, 1.8760, -0.2040),
    DVec3::new(-0.4985, 0.0416, 1.0573),
);

/// Linear BT.709 RGB of a CIE XYZ tristimulus value, Eq. 12.
///
/// The result is not clamped: colours outside the BT.709 gamut have negative components, and
/// bright ones components above 1.
#[must_use]
pub fn xyz_to_linear_rgb(xyz: DVec3) -> DVec3 {
    XYZ_TO_LINEAR_BT709 * xyz
}

/// The linear segment's upper end in Eq. 13.
pub const SRGB_LINEAR_THRESHOLD: f64 = 0.003_130_8;
/// The offset a = 0.055 of Eq. 13.
pub const SRGB_OFFSET: f64 = 0.055;

/// sRGB encoding of one linear component, Eq. 13.
///
/// `C_sRGB` = 12.92 C for C ≤ 0.0031308, (1 + a) C^(1/2.4) − a otherwise, with a = 0.055. Inputs
/// above 1 follow the power segment unclamped (the searchlight tone map relies on that).
/// Negative inputs fall on the linear segment and come out negative (12.92 C); the tone maps clamp
/// negatives to 0 before encoding. NaN stays NaN.
#[must_use]
pub fn srgb_encode(linear: f64) -> f64 {
    if linear <= SRGB_LINEAR_THRESHOLD {
        12.92 * linear
    } else {
        (1.0 + SRGB_OFFSET) * linear.powf(1.0 / 2.4) - SRGB_OFFSET
    }
}

/// Inverse of [`srgb_encode`]: the linear component of an sRGB-encoded value (for writing
/// linear-light images). Values at or below 12.92 × 0.0031308 take the linear segment.
#[must_use]
pub fn srgb_decode(encoded: f64) -> f64 {
    if encoded <= 12.92 * SRGB_LINEAR_THRESHOLD {
        encoded / 12.92
    } else {
        ((encoded + SRGB_OFFSET) / (1.0 + SRGB_OFFSET)).powf(2.4)
    }
}

/// An encoded display value in [0, 1] as an 8-bit code: clamped, scaled by 255 and rounded to
/// the nearest code (how every 8-bit image, texture and figure of srt is quantised).
#[must_use]
pub fn quantize_8bit(value: f64) -> u8 {
    // After the clamp the product lies in [0, 255]: its integer part and its fraction (exact:
    // x − ⌊x⌋ rounds nowhere below 2⁵²) give `round`'s result, halves away from zero, without
    // the library call `round` is where the CPU lacks SSE 4.1. NaN (never produced by the
    // renderers) gives 0, as `round` and the cast do.
    let scaled = value.clamp(0.0, 1.0) * 255.0;
    let whole = scaled as u8;
    whole + u8::from(scaled - f64::from(whole) >= 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The code is `round`'s, halves away from zero, on every code's neighbourhood, every
    /// halfway point and the values beside it, and out of range and NaN.
    #[test]
    fn quantize_rounds_as_round_does() {
        let reference = |value: f64| (value.clamp(0.0, 1.0) * 255.0).round() as u8;
        let mut values = vec![-1.0, 0.0, 1.0, 2.0, f64::NAN, f64::INFINITY, 0.5 / 255.0];
        for code in 0..=255_u32 {
            for offset in [-0.5, -0.25, 0.0, 0.25, 0.5] {
                let value = (f64::from(code) + offset) / 255.0;
                values.extend([value, value.next_down(), value.next_up()]);
            }
        }
        for i in 0..100_000 {
            values.push(f64::from(i) / 99_999.0);
        }
        for value in values {
            assert_eq!(quantize_8bit(value), reference(value), "{value:e}");
        }
    }

    #[test]
    fn decode_inverts_encode() {
        for i in 0..=1000 {
            let linear = f64::from(i) / 1000.0;
            assert!(
                (srgb_decode(srgb_encode(linear)) - linear).abs() < 1e-12,
                "{linear}"
            );
        }
    }

    #[test]
    fn matrix_rows_are_the_printed_rows() {
        assert_eq!(
            XYZ_TO_LINEAR_BT709.row(0),
            DVec3::new(3.2405, -1.5372, -0.4985)
        );
        assert_eq!(
            XYZ_TO_LINEAR_BT709.row(1),
            DVec3::new(-0.9693, 1.8760, 0.0416)
        );
        assert_eq!(
            XYZ_TO_LINEAR_BT709.row(2),
            DVec3::new(0.0556, -0.2040, 1.0573)
        );
    }

    #[test]
    fn pure_x_maps_to_the_first_column() {
        assert_eq!(
            xyz_to_linear_rgb(DVec3::X),
            DVec3::new(3.2405, -0.9693, 0.0556)
        );
    }

    #[test]
    fn negative_inputs_stay_on_the_linear_segment() {
        assert_eq!(srgb_encode(-0.5), -6.46);
        assert!(srgb_encode(f64::NAN).is_nan());
    }

    #[test]
    fn quantize_8bit_rounds_to_the_nearest_code_and_clamps() {
        assert_eq!(quantize_8bit(0.0), 0);
        assert_eq!(quantize_8bit(1.0), 255);
        assert_eq!(quantize_8bit(-0.5), 0);
        assert_eq!(quantize_8bit(7.0), 255);
        assert_eq!(quantize_8bit(127.49 / 255.0), 127);
        assert_eq!(quantize_8bit(127.51 / 255.0), 128);
    }
}
