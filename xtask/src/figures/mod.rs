//! The documentation figures, each reproducing one of the paper's figures from the library crates
//! or showing what srt adds to them.

mod colorchecker;
mod fig13;
mod fig4;
mod fig5;
mod fig6;
mod fig8;
mod sky;
mod time;
mod wheel;
mod whole_sky;

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use image::{Rgb, RgbImage, imageops};
use srt_color::quantize_8bit;
use srt_scene::Scene;
use srt_trace::{RenderSettings, Tracer};

use crate::plot::{BLACK, Canvas, WHITE};

/// Writes every figure into `out_dir` and returns the paths written.
pub fn write_all(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    written.extend(fig4::write(out_dir)?);
    written.extend(fig5::write(out_dir)?);
    written.extend(fig6::write(out_dir)?);
    written.extend(fig8::write(out_dir)?);
    written.extend(colorchecker::write(out_dir)?);
    written.extend(sky::write(out_dir)?);
    written.extend(time::write(out_dir)?);
    written.extend(wheel::write(out_dir)?);
    written.extend(whole_sky::write(out_dir)?);
    written.extend(fig13::write(out_dir)?);
    Ok(written)
}

/// `scene` as the exact CPU reference shows it, `width` × `height`, one sample per pixel.
fn render_panel(scene: &Scene, width: u32, height: u32) -> RgbImage {
    let image = Tracer::new(scene).render(
        RenderSettings {
            width,
            height,
            samples: 1,
        },
        &|_| {},
    );
    RgbImage::from_fn(width, height, |x, y| {
        let p = image.pixels[(y * width + x) as usize];
        Rgb(p.to_array().map(quantize_8bit))
    })
}

/// Height of a panel grid's title band, pixels.
const GRID_TITLE_HEIGHT: u32 = 50;
/// Height of the caption band under each row of panels, pixels.
const GRID_CAPTION_HEIGHT: u32 = 40;
/// Space around and between panels, pixels.
const GRID_GAP: u32 = 10;

/// Saves `panels` (images of one size, each with its caption) as a grid of `columns` columns
/// under `title`, at `path`.
///
/// # Errors
/// An empty list, panels of different sizes, or an unwritable file.
fn write_panel_grid(
    path: &Path,
    title: &str,
    panels: &[(RgbImage, String)],
    columns: u32,
) -> anyhow::Result<()> {
    let (first, _) = panels.first().context("a grid needs a panel")?;
    let (width, height) = first.dimensions();
    anyhow::ensure!(
        panels
            .iter()
            .all(|(p, _)| p.dimensions() == (width, height)),
        "the panels of {} differ in size",
        path.display()
    );
    let columns = columns.min(panels.len() as u32).max(1);
    let rows = (panels.len() as u32).div_ceil(columns);
    let row_height = height + GRID_CAPTION_HEIGHT;
    let mut canvas = Canvas::new(
        columns * (width + GRID_GAP) + GRID_GAP,
        GRID_TITLE_HEIGHT + rows * row_height,
        WHITE,
    );
    canvas.text(20.0, 12.0, 20.0, BLACK, title);
    for (index, (panel, caption)) in panels.iter().enumerate() {
        let (column, row) = (index as u32 % columns, index as u32 / columns);
        let left = GRID_GAP + column * (width + GRID_GAP);
        let top = GRID_TITLE_HEIGHT + row * row_height;
        imageops::replace(canvas.image_mut(), panel, i64::from(left), i64::from(top));
        canvas.text_centred(
            left as f32 + width as f32 / 2.0,
            (top + height + 10) as f32,
            18.0,
            BLACK,
            caption,
        );
    }
    canvas.save(path)
}
