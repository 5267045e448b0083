//! The `flythrough` scene three ways (issue 10 and 11): the observer at rest in the world, then
//! flying at 0.9c through the same world and its star field — the sky crowds towards the
//! direction of flight and turns blue, the columns beside the path are seen ahead — first with the
//! paper's colour, then with spectral colour, where each surface's own colour shifts. Rendered by
//! the reference, `srt-trace`.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use srt_scene::{SurfaceColour, builtin::find_builtin};

use super::{render_panel, write_panel_grid};

const PANEL_WIDTH: u32 = 480;
const PANEL_HEIGHT: u32 = 300;

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
    let mut rendered = Vec::new();
    for (description, caption) in &panels {
        let (scene, _) = builtin.build_description(description)?;
        rendered.push((
            render_panel(&scene, PANEL_WIDTH, PANEL_HEIGHT),
            (*caption).to_owned(),
        ));
    }
    let path = out_dir.join("flythrough_sky.png");
    write_panel_grid(
        &path,
        "flythrough: the observer at rest, and flying at 0.9c through the same world and stars",
        &rendered,
        3,
    )?;
    Ok(vec![path])
}
