//! Procedural textures (the checkerboard of Fig. 7 and 10) and texture images read from files
//! or from bytes.
//!
//! Colours are display sRGB components in [0, 1], stored as RGBA8 texels like every
//! [`Texture`]: row 0 is the top of the image (texture coordinate v = 0).

use std::io::Cursor;
use std::path::Path;

use image::{ImageFormat, ImageReader};

use crate::mesh::Texture;

/// Default number of checker squares along each edge of a texture.
pub const DEFAULT_CHECKER_SQUARES: u32 = 8;

/// The most checker squares along an edge a scene may ask for.
pub const MAX_CHECKER_SQUARES: u32 = 1024;

/// Default checker colours: white and black (the grey value 𝒢 of Eq. 18 is then 1 and 0).
pub const DEFAULT_CHECKER_COLORS: [[f64; 3]; 2] = [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]];

/// A component in [0, 1] as an 8-bit value (clamped; NaN gives 0).
fn to_u8(component: f64) -> u8 {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "clamped to 0..=255"
    )]
    let value = (component.clamp(0.0, 1.0) * 255.0).round() as u8;
    if component.is_nan() { 0 } else { value }
}

/// An opaque RGBA8 texel from an sRGB colour with components in [0, 1].
#[must_use]
pub fn texel(color: [f64; 3]) -> [u8; 4] {
    [to_u8(color[0]), to_u8(color[1]), to_u8(color[2]), 255]
}

/// A square checkerboard texture of `texels` × `texels` texels with `squares` × `squares`
/// squares; the top-left square has `color_a`, its neighbours `color_b`.
///
/// `texels` is raised to at least `squares` (and to at least 1), `squares` to at least 1. Square
/// boundaries fall on texel boundaries when `texels` is a multiple of `squares`.
#[must_use]
pub fn checker(texels: u32, squares: u32, color_a: [f64; 3], color_b: [f64; 3]) -> Texture {
    let squares = squares.max(1);
    let size = texels.max(squares).max(1);
    let (a, b) = (texel(color_a), texel(color_b));
    let square_of = |i: u32| u64::from(i) * u64::from(squares) / u64::from(size);
    let texels = (0..size)
        .flat_map(|row| {
            (0..size).map(move |column| {
                if (square_of(row) + square_of(column)) % 2 == 0 {
                    a
                } else {
                    b
                }
            })
        })
        .collect();
    Texture {
        width: size,
        height: size,
        texels,
        source: format!("checker texture ({squares} × {squares} squares)"),
    }
}

/// The texel resolution used for a checkerboard of `squares` squares per edge in scenes: a
/// multiple of `squares` with at least 32 texels per square and at least 512 texels, at most
/// 4096 (unless that is fewer than `squares`).
#[must_use]
pub fn checker_resolution(squares: u32) -> u32 {
    let squares = squares.max(1);
    let per_square = (512_u32.div_ceil(squares)).max(32);
    let wanted = squares.saturating_mul(per_square);
    if wanted <= 4096 {
        wanted
    } else {
        (4096 / squares).max(1) * squares
    }
}

/// A 1 × 1 texture of one colour.
#[must_use]
pub fn solid(color: [f64; 3]) -> Texture {
    Texture {
        width: 1,
        height: 1,
        texels: vec![texel(color)],
        source: "solid colour".to_owned(),
    }
}

/// Decodes an encoded image (PNG, JPEG, BMP or TGA; the format is guessed from the content,
/// `extension` — without the dot — is the fallback) into a texture named `source`.
///
/// # Errors
/// A message saying why the bytes are not a usable image.
pub fn decode_image(
    bytes: &[u8],
    extension: Option<&str>,
    source: &str,
) -> Result<Texture, String> {
    let mut reader = ImageReader::new(Cursor::new(bytes));
    if let Some(format) = extension.and_then(ImageFormat::from_extension) {
        reader.set_format(format);
    }
    let reader = reader.with_guessed_format().map_err(|e| e.to_string())?;
    let image = reader.decode().map_err(|e| e.to_string())?;
    let rgba = image.into_rgba8();
    let (width, height) = rgba.dimensions();
    if width == 0 || height == 0 {
        return Err("the image has no texels".to_owned());
    }
    let texels = rgba.pixels().map(|p| p.0).collect();
    Ok(Texture {
        width,
        height,
        texels,
        source: source.to_owned(),
    })
}

/// Reads and decodes the image file at `path`.
///
/// # Errors
/// A message saying why the file cannot be read or decoded.
pub fn load_image(path: &Path) -> Result<Texture, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    decode_image(
        &bytes,
        path.extension().and_then(|e| e.to_str()),
        &path.display().to_string(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates() {
        let t = checker(8, 4, [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]);
        assert_eq!((t.width, t.height, t.texels.len()), (8, 8, 64));
        let at = |x: usize, y: usize| t.texels[y * 8 + x];
        assert_eq!(at(0, 0), [255, 255, 255, 255]);
        assert_eq!(at(1, 1), [255, 255, 255, 255]);
        assert_eq!(at(2, 0), [0, 0, 0, 255]);
        assert_eq!(at(0, 2), [0, 0, 0, 255]);
        assert_eq!(at(2, 2), [255, 255, 255, 255]);
        let white = t.texels.iter().filter(|&&c| c[0] == 255).count();
        assert_eq!(white, 32);
    }

    #[test]
    fn checker_handles_degenerate_sizes() {
        let t = checker(0, 0, [0.5; 3], [0.0; 3]);
        assert_eq!((t.width, t.texels.len()), (1, 1));
        assert_eq!(t.texels[0], [128, 128, 128, 255]);
        assert_eq!(checker(2, 5, [1.0; 3], [0.0; 3]).width, 5);
    }

    #[test]
    fn resolutions_are_multiples_of_the_squares() {
        for squares in [1, 3, 8, 10, 100, 1000] {
            let r = checker_resolution(squares);
            assert_eq!(r % squares, 0, "{squares}");
            assert!(
                r >= 512.min(squares * 32) && r <= 4096.max(squares),
                "{squares}: {r}"
            );
        }
    }

    #[test]
    fn bad_images_are_errors() {
        assert!(decode_image(b"nope", None, "x").is_err());
        assert!(load_image(Path::new("/nonexistent/image.png")).is_err());
        assert!(texel([f64::NAN, 2.0, -1.0]) == [0, 255, 0, 255]);
    }
}
