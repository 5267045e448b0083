//! Times the viewer's frames headless: a scene (the `teaser` unless `scene=NAME` is given) moved
//! to each observation time by the viewer's editor (`Editor::set_time`, what playback and
//! coasting flight do every frame) and rendered through the viewer's own path (srt-gpu passes,
//! then the blit into the displayed texture), waiting for the GPU after each frame. Prints the
//! edit's and the render's time, so a frame's cost can be set against the renderer's alone.
//!
//! `cargo run -p srt-viewer --example frame_times -- [exact|lrt|rt|polygon|split] [WIDTHxHEIGHT] [scene=NAME] CT...`
//! e.g. `-- exact 1213x880 0 1 2 3` (the size of the view in a 1600×900 window), or
//! `-- exact 1213x880 scene=flythrough 0 1 2 3` (the observer flying at 0.9c).

use std::time::Instant;

use srt_scene::{UploadKey, View};
use srt_viewer::view::{PaneScene, SceneView};
use srt_viewer::{Pane, ViewMethod};

fn main() -> anyhow::Result<()> {
    let mut arguments = std::env::args().skip(1);
    let method = match arguments.next().as_deref() {
        Some("lrt") => ViewMethod::Lrt,
        Some("rt") => ViewMethod::Rt,
        Some("polygon") => ViewMethod::Polygon,
        Some("image-based") => ViewMethod::ImageBased,
        Some("split") => ViewMethod::Split,
        _ => ViewMethod::Exact,
    };
    let size = arguments.next().unwrap_or_else(|| "1213x880".to_owned());
    let (width, height) = size
        .split_once('x')
        .ok_or_else(|| anyhow::anyhow!("size as WIDTHxHEIGHT"))?;
    let size = (width.parse()?, height.parse()?);
    let mut rest: Vec<String> = arguments.collect();
    let scene = match rest.first().and_then(|a| a.strip_prefix("scene=")) {
        Some(name) => {
            let name = name.to_owned();
            rest.remove(0);
            name
        }
        None => "teaser".to_owned(),
    };
    let times: Vec<f64> = rest.iter().map(|a| a.parse()).collect::<Result<_, _>>()?;
    let ctx = srt_gpu::GpuContext::new()?;
    println!(
        "{} — {scene}, {}, {}x{} px",
        ctx.adapter_summary(),
        method.label(),
        size.0,
        size.1
    );
    let (mut editor, _) = srt_viewer::open_arguments(&[scene])?;
    let mut view = SceneView::new(&ctx);
    view.upload(&ctx, editor.scene(), editor.structure_version())?;
    for ct in times {
        let edit_start = Instant::now();
        editor.set_time(ct)?;
        let edit = edit_start.elapsed();
        let scene = editor.scene();
        let key = UploadKey::new(View::Seen, scene, editor.structure_version());
        let panes: Vec<PaneScene<'_>> = Pane::row(&[View::Seen], method)
            .iter()
            .map(|pane| PaneScene {
                scene,
                key: &key,
                method: pane.method,
            })
            .collect();
        let start = Instant::now();
        view.render(&ctx, None, &panes, size)?;
        ctx.wait()?;
        let render = start.elapsed();
        println!(
            "ct = {ct}: {:.1} ms (edit {:.3} ms, render {:.1} ms)",
            (edit + render).as_secs_f64() * 1e3,
            edit.as_secs_f64() * 1e3,
            render.as_secs_f64() * 1e3
        );
    }
    Ok(())
}
