//! How the GPU draws a picture larger than it can hold at once: in tiles, each a window of the
//! supersampled picture ([`srt_gpu::projection::ImageWindow`]: the same ray through each pixel
//! as in the whole picture), all of one size so that the render targets are made once. A row
//! of tiles is a band of the picture (`Engine::band_rows` in the engine module); the last column and
//! the last row of tiles are moved back inside the picture and overlap their neighbours.
//!
//! A tile is at most the adapter's largest texture a side, and a tile with the band it fills
//! holds at most [`GPU_TILE_BYTES`] of host memory, so that the GPU draws every size srt
//! accepts within `MEMORY_BOUND` (the engine module). A picture that fits one tile is drawn whole,
//! without a window, exactly as before tiles existed.

use std::ops::Range;

use srt_gpu::projection::ImageWindow;

/// Bands of a picture written a band at a time, and rows of tiles, are whole multiples of this
/// many rows: an EXR's ZIP blocks of 16 scan lines.
pub const BAND_ROW_MULTIPLE: u32 = 16;

/// Host memory per pixel of the GPU's target while it draws and reads back a frame: 86 bytes
/// measured on lavapipe (`srt render --backend gpu` at 4096×2048: 880 MB, 339 MB at 2048×1024;
/// a software adapter's textures live in host memory), rounded up. A hardware GPU keeps its
/// textures in its own memory and holds less here.
pub const GPU_BYTES_PER_TARGET_PIXEL: u64 = 96;

/// Host memory per output pixel of a band's layers drawn by the GPU: the display colours and
/// the radiance (three f64 each) and the time channels (five f32), with their copies.
pub const GPU_BYTES_PER_OUTPUT_PIXEL: u64 = 72;

/// The most host memory one tile's target and the band it fills may hold (1.5 GiB, leaving the
/// rest of `MEMORY_BOUND` (the engine module) to the scene): 3840×2160 at one sample is one tile.
pub const GPU_TILE_BYTES: u64 = 3 << 29;

/// The tile size, in output pixels, of a `width` × `height` picture drawn at `scale`× the size
/// (supersampling).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tiling {
    /// The picture's width in output pixels.
    pub width: u32,
    /// The picture's height in output pixels.
    pub height: u32,
    /// Each output pixel is `scale` × `scale` target pixels.
    pub scale: u32,
    /// A tile's width in output pixels.
    pub tile_width: u32,
    /// A tile's height in output pixels: a multiple of [`BAND_ROW_MULTIPLE`] unless it is the
    /// picture's height.
    pub tile_height: u32,
}

impl Tiling {
    /// The tiles of a `width` × `height` picture drawn at `scale`× on an adapter whose limits
    /// allow a target of (w, h) pixels where `fits(w, h)`: as wide as the picture where the
    /// adapter allows, as tall as [`GPU_TILE_BYTES`] and the adapter allow (halved until it
    /// fits, in whole [`BAND_ROW_MULTIPLE`]s, then narrower). A tile that fits nowhere comes
    /// out as the smallest tried; making its targets reports the limit.
    #[must_use]
    pub fn new(width: u32, height: u32, scale: u32, fits: impl Fn(u32, u32) -> bool) -> Self {
        let scale = scale.max(1);
        let whole_blocks = |rows: u32| (rows / BAND_ROW_MULTIPLE).max(1) * BAND_ROW_MULTIPLE;
        let mut tile_width = width.max(1);
        loop {
            let per_row =
                u64::from(tile_width) * u64::from(scale * scale) * GPU_BYTES_PER_TARGET_PIXEL
                    + u64::from(width) * GPU_BYTES_PER_OUTPUT_PIXEL;
            let rows = u32::try_from(GPU_TILE_BYTES / per_row.max(1)).unwrap_or(u32::MAX);
            let mut tile_height = if rows >= height {
                height
            } else {
                whole_blocks(rows)
            };
            let tile_fits = |tile_height: u32| fits(tile_width * scale, tile_height * scale);
            while !tile_fits(tile_height) && tile_height > BAND_ROW_MULTIPLE {
                tile_height = whole_blocks(tile_height / 2);
            }
            if tile_fits(tile_height) || tile_width == 1 {
                return Self {
                    width,
                    height,
                    scale,
                    tile_width,
                    tile_height: tile_height.min(height),
                };
            }
            tile_width = tile_width.div_ceil(2);
        }
    }

    /// The window of the picture at `scale`× the output size that `tile` is.
    #[must_use]
    pub const fn window(&self, tile: &TilePart, scale: u32) -> ImageWindow {
        ImageWindow {
            left: tile.left * scale,
            top: tile.top * scale,
            image_width: self.width * scale,
            image_height: self.height * scale,
        }
    }

    /// Whether one tile is the whole picture.
    #[must_use]
    pub const fn is_whole(&self) -> bool {
        self.tile_width == self.width && self.tile_height == self.height
    }

    /// The tiles that cover the rows `rows` (output pixels) across the picture's width: each
    /// tile's top-left corner in output pixels, and the part of it the rows take, as
    /// (`tile_rows`, `tile_columns`) ranges within the tile and (`rows`, `columns`) within the
    /// picture.
    pub fn tiles_over(&self, rows: Range<u32>) -> Vec<TilePart> {
        let mut parts = Vec::new();
        let mut first_row = rows.start;
        while first_row < rows.end {
            let top = first_row.min(self.height - self.tile_height);
            let last_row = (top + self.tile_height).min(rows.end);
            let mut first_column = 0;
            while first_column < self.width {
                let left = first_column.min(self.width - self.tile_width);
                let last_column = left + self.tile_width;
                parts.push(TilePart {
                    left,
                    top,
                    rows: first_row..last_row,
                    columns: first_column..last_column,
                });
                first_column = last_column;
            }
            first_row = last_row;
        }
        parts
    }
}

/// One tile and the part of the picture it gives ([`Tiling::tiles_over`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TilePart {
    /// The tile's first column in the picture (output pixels).
    pub left: u32,
    /// The tile's first row in the picture.
    pub top: u32,
    /// The picture rows taken from this tile.
    pub rows: Range<u32>,
    /// The picture columns taken from this tile.
    pub columns: Range<u32>,
}

/// The rows `rows` of a picture `tiling` describes, put together from its tiles: `draw` gives a
/// tile's pixels (its whole size, row-major) for a [`TilePart`].
///
/// # Errors
/// The first error of `draw`.
pub fn assemble<T: Copy + Default>(
    tiling: &Tiling,
    rows: Range<u32>,
    mut draw: impl FnMut(&TilePart) -> anyhow::Result<Vec<T>>,
) -> anyhow::Result<Vec<T>> {
    let width = tiling.width as usize;
    let mut band = vec![T::default(); width * rows.len()];
    for part in tiling.tiles_over(rows.clone()) {
        let tile = draw(&part)?;
        let tile_width = tiling.tile_width as usize;
        for y in part.rows.clone() {
            let from =
                (y - part.top) as usize * tile_width + (part.columns.start - part.left) as usize;
            let to = (y - rows.start) as usize * width + part.columns.start as usize;
            let count = part.columns.len();
            band[to..to + count].copy_from_slice(&tile[from..from + count]);
        }
    }
    Ok(band)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tiles cover every pixel of a band exactly once, stay inside the picture, and are all of
    /// one size; a picture within the limits is one tile.
    #[test]
    fn tiles_cover_the_picture_once_within_the_limits() {
        // A software adapter's limits: 16384 a side, 2^23 pixels of star light.
        let adapter = |max_side: u32, max_pixels: u64| {
            move |w: u32, h: u32| {
                w <= max_side && h <= max_side && u64::from(w) * u64::from(h) <= max_pixels
            }
        };
        assert!(Tiling::new(1920, 1080, 1, adapter(8192, 1 << 23)).is_whole());
        assert!(Tiling::new(3840, 2160, 1, adapter(16384, 1 << 23)).is_whole());
        for (width, height, scale, max_side, max_pixels) in [
            (16384, 8192, 1, 16384, 1 << 23),
            (4096, 600, 5, 8192, 1 << 23),
            (3500, 300, 5, 16384, 1 << 23),
            (1000, 333, 3, 512, 1 << 30),
            (70, 50, 32, 512, 1 << 30),
        ] {
            let fits = adapter(max_side, max_pixels);
            let tiling = Tiling::new(width, height, scale, fits);
            assert!(
                fits(tiling.tile_width * scale, tiling.tile_height * scale),
                "{tiling:?}"
            );
            let target =
                u64::from(tiling.tile_width * scale) * u64::from(tiling.tile_height * scale);
            let band = u64::from(width) * u64::from(tiling.tile_height);
            assert!(
                target * GPU_BYTES_PER_TARGET_PIXEL + band * GPU_BYTES_PER_OUTPUT_PIXEL
                    <= GPU_TILE_BYTES.max(16 * band * GPU_BYTES_PER_OUTPUT_PIXEL),
                "{tiling:?}"
            );
            assert!(
                tiling.tile_height == height
                    || tiling.tile_height.is_multiple_of(BAND_ROW_MULTIPLE)
            );
            let mut seen = vec![0u8; (width * height) as usize];
            for band in (0..height).step_by(tiling.tile_height as usize) {
                let rows = band..(band + tiling.tile_height).min(height);
                for part in tiling.tiles_over(rows.clone()) {
                    assert!(part.left + tiling.tile_width <= width, "{part:?}");
                    assert!(part.top + tiling.tile_height <= height, "{part:?}");
                    assert!(part.columns.start >= part.left && part.rows.start >= part.top);
                    for y in part.rows.clone() {
                        for x in part.columns.clone() {
                            seen[(y * width + x) as usize] += 1;
                        }
                    }
                }
            }
            assert!(seen.iter().all(|&n| n == 1), "{tiling:?}");
        }
    }

    /// A band put together from tiles is the picture's rows: each tile here is a window of a
    /// known picture.
    #[test]
    fn assembled_tiles_are_the_picture() {
        let tiling = Tiling::new(70, 45, 1, |w, h| w <= 32 && h <= 32);
        assert!(!tiling.is_whole());
        let picture = |x: u32, y: u32| y * 1000 + x;
        for rows in [0..45, 16..32, 40..45] {
            let band = assemble(&tiling, rows.clone(), |part| {
                let mut tile = Vec::new();
                for y in part.top..part.top + tiling.tile_height {
                    for x in part.left..part.left + tiling.tile_width {
                        tile.push(picture(x, y));
                    }
                }
                Ok(tile)
            })
            .unwrap();
            let wanted: Vec<u32> = rows
                .flat_map(|y| (0..70).map(move |x| picture(x, y)))
                .collect();
            assert_eq!(band, wanted);
        }
    }
}
