//! The documentation figures, each reproducing one of the paper's figures from the library crates
//! or showing what srt adds to them.

mod colorchecker;
mod fig4;
mod fig5;
mod fig6;
mod fig8;
mod sky;
mod time;
mod wheel;

use std::path::{Path, PathBuf};

use image::{Rgb, RgbImage};
use srt_color::quantize_8bit;
use srt_scene::Scene;
use srt_trace::{RenderSettings, Tracer};

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
