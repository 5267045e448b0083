//! Procedural textures (the checkerboard of Fig. 7 and 10) and texture images read from files
//! or from bytes.
//!
//! Colours are display sRGB components in [0, 1], stored as RGBA8 texels like every
//! [`Texture`]: row 0 is the top of the image (texture coordinate v = 0).

use std::io::Cursor;
use std::path::Path;

use image::{ImageFormat, ImageReader, Limits};
use srt_color::quantize_8bit;

use crate::input_file::{self, FileKind};
use crate::limits::{Budget, MAX_IMAGE_DECODE_BYTES, MAX_TEXTURE_SIDE};
use crate::mesh::Texture;

/// Default number of checker squares along each edge of a texture.
pub const DEFAULT_CHECKER_SQUARES: u32 = 8;

/// The most checker squares along an edge a scene may ask for.
pub const MAX_CHECKER_SQUARES: u32 = 1024;

/// The most frames a flipbook texture may have (each is also charged to the texel budget).
pub const MAX_FRAMES: usize = 1024;

/// Default checker colours: white and black (the grey value 𝒢 of Eq. 18 is then 1 and 0).
pub const DEFAULT_CHECKER_COLORS: [[f64; 3]; 2] = [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]];

/// An opaque RGBA8 texel from an sRGB colour with components in [0, 1].
#[must_use]
pub fn texel(color: [f64; 3]) -> [u8; 4] {
    let [r, g, b] = color.map(quantize_8bit);
    [r, g, b, 255]
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
    Texture::still(
        size,
        size,
        texels,
        format!("checker texture ({squares} × {squares} squares)"),
    )
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
    Texture::still(1, 1, vec![texel(color)], "solid colour".to_owned())
}

/// Decodes an encoded image (the format is guessed from the content, `extension` — without the
/// dot — is the fallback), charging its texels to `budget` only if it decodes.
///
/// The size in the image's header is checked before anything is decoded: at most
/// [`MAX_TEXTURE_SIDE`] texels per side and what is left of the budget's texels; the decoder
/// may allocate at most [`MAX_IMAGE_DECODE_BYTES`].
///
/// # Errors
/// A message saying why the bytes are not a usable image, or why it is too large.
pub fn decode_checked(
    bytes: &[u8],
    extension: Option<&str>,
    budget: &mut Budget,
) -> Result<image::DynamicImage, String> {
    let reader = || {
        let mut reader = ImageReader::new(Cursor::new(bytes));
        if let Some(format) = extension.and_then(ImageFormat::from_extension) {
            reader.set_format(format);
        }
        reader.with_guessed_format().map_err(|e| e.to_string())
    };
    let (width, height) = reader()?.into_dimensions().map_err(|e| e.to_string())?;
    if width == 0 || height == 0 {
        return Err("the image has no texels".to_owned());
    }
    if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "the image is {width} × {height} texels, more than {MAX_TEXTURE_SIDE} per side"
        ));
    }
    let mut charged = budget.clone();
    charged
        .charge_texels(width, height)
        .map_err(|e| format!("the image is too large: {e}"))?;
    let mut decoder = reader()?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    limits.max_alloc = Some(MAX_IMAGE_DECODE_BYTES);
    decoder.limits(limits);
    let image = decoder.decode().map_err(|e| e.to_string())?;
    if (image.width(), image.height()) != (width, height) {
        return Err("the image's size differs from its header's".to_owned());
    }
    *budget = charged;
    Ok(image)
}

/// Decodes an encoded image (PNG, JPEG, BMP or TGA) into a texture named `source`, charging its
/// texels to `budget` ([`decode_checked`]).
///
/// # Errors
/// A message saying why the bytes are not a usable image, or why it is too large.
pub fn decode_image(
    bytes: &[u8],
    extension: Option<&str>,
    source: &str,
    budget: &mut Budget,
) -> Result<Texture, String> {
    let rgba = decode_checked(bytes, extension, budget)?.into_rgba8();
    Ok(Texture::still(
        rgba.width(),
        rgba.height(),
        rgba.pixels().map(|p| p.0).collect(),
        source.to_owned(),
    ))
}

/// Reads (through [`input_file::read`]) and decodes the image file at `path`, charging its
/// texels to `budget`.
///
/// # Errors
/// A message saying why the file cannot be read or decoded.
pub fn load_image(path: &Path, budget: &mut Budget) -> Result<Texture, String> {
    let bytes = input_file::read(path, FileKind::Image).map_err(|e| e.to_string())?;
    decode_image(
        &bytes,
        path.extension().and_then(|e| e.to_str()),
        &path.display().to_string(),
        budget,
    )
}

/// A flipbook of `frames` (still images of one size, in order) advancing `frame_rate` frames per
/// unit of proper time, named `source`.
///
/// # Errors
/// If there are no frames or their sizes differ (the message names the first that differs).
pub fn flipbook(frames: &[Texture], frame_rate: f64, source: String) -> Result<Texture, String> {
    let first = frames.first().ok_or("it has no frames")?;
    if let Some(other) = frames
        .iter()
        .find(|f| (f.width, f.height) != (first.width, first.height))
    {
        return Err(format!(
            "its frames differ in size: {} is {}×{}, {} is {}×{}",
            first.source, first.width, first.height, other.source, other.width, other.height
        ));
    }
    let count = u32::try_from(frames.len()).map_err(|_| "it has too many frames")?;
    Ok(Texture {
        width: first.width,
        height: first.height * count,
        texels: frames
            .iter()
            .flat_map(|f| f.texels.iter().copied())
            .collect(),
        source,
        frames: count,
        frame_rate,
    })
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
        let mut budget = Budget::new();
        assert!(decode_image(b"nope", None, "x", &mut budget).is_err());
        assert!(load_image(Path::new("/nonexistent/image.png"), &mut budget).is_err());
        assert!(texel([f64::NAN, 2.0, -1.0]) == [0, 255, 0, 255]);
    }
}
