//! The `flythrough` scene three ways (issue 10 and 11): the observer at rest in the world, then
//! flying at 0.9c through the same world and its star field — the sky crowds towards the
//! direction of flight and turns blue, the columns beside the path are seen ahead — first with the
//! paper's colour, then with spectral colour, where each surface's own colour shifts. Rendered by
//! the reference, `srt-trace`.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use image::imageops;
use srt_scene::{SurfaceColour, builtin::find_builtin};

use super::render_panel;
use crate::plot::{BLACK, Canvas, WHITE};

const PANEL_WIDTH: u32 = 480;
const PANEL_HEIGHT: u32 = 300;
const TITLE_HEIGHT: u32 = 50;
const CAPTION_HEIGHT: u32 = 40;

/// Writes `flythrough_sky.png`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let builtin = find_builtin("flythrough").context("flythrough is a built-in scene")?;
    let flying = builtin.description();
    let mut at_rest = flying.clone();
    at_rest.observer.beta = [0.0; 3];
    let mut spectral = flying.clone();
    spectral.render.colour = SurfaceColour::Spectral;
    let panels = [
        (at_rest, "at rest in the world"),
        (flying, "0.9c, the paper's colour"),
        (spectral, "0.9c, spectral colour"),
    ];
    let mut canvas = Canvas::new(
        3 * PANEL_WIDTH + 40,
        PANEL_HEIGHT + TITLE_HEIGHT + CAPTION_HEIGHT,
        WHITE,
    );
    canvas.text(
        20.0,
        12.0,
        20.0,
        BLACK,
        "flythrough: the observer at rest, and flying at 0.9c through the same world and stars",
    );
    for (index, (description, caption)) in panels.iter().enumerate() {
        let (scene, _) = builtin.build_description(description)?;
        let panel = render_panel(&scene, PANEL_WIDTH, PANEL_HEIGHT);
        let left = 10 + index as u32 * (PANEL_WIDTH + 10);
        imageops::replace(
            canvas.image_mut(),
            &panel,
            i64::from(left),
            i64::from(TITLE_HEIGHT),
        );
        canvas.text_centred(
            left as f32 + PANEL_WIDTH as f32 / 2.0,
            (TITLE_HEIGHT + PANEL_HEIGHT + 10) as f32,
            18.0,
            BLACK,
            caption,
        );
    }
    let path = out_dir.join("flythrough_sky.png");
    canvas.save(&path)?;
    Ok(vec![path])
}
