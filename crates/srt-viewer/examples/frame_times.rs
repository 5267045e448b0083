//! Times the viewer's frames headless: the `teaser` scene rendered through the viewer's own path
//! (srt-gpu passes, then the blit into the displayed texture), waiting for the GPU after each
//! frame, at a list of observation times.
//!
//! `cargo run -p srt-viewer --example frame_times -- [exact|lrt|rt|polygon|split] [WIDTHxHEIGHT] CT...`
//! e.g. `-- exact 1213x880 0 1 2 3` (the size of the view in a 1600×900 window).

use std::time::Instant;

use srt_scene::View;
use srt_viewer::view::{PaneScene, SceneView, UploadKey};
use srt_viewer::{Editor, Pane, ViewMethod};

fn main() -> anyhow::Result<()> {
    let mut arguments = std::env::args().skip(1);
    let method = match arguments.next().as_deref() {
        Some("lrt") => ViewMethod::Lrt,
        Some("rt") => ViewMethod::Rt,
        Some("polygon") => ViewMethod::Polygon,
        Some("split") => ViewMethod::Split,
        _ => ViewMethod::Exact,
    };
    let size = arguments.next().unwrap_or_else(|| "1213x880".to_owned());
    let (width, height) = size
        .split_once('x')
        .ok_or_else(|| anyhow::anyhow!("size as WIDTHxHEIGHT"))?;
    let size = (width.parse()?, height.parse()?);
    let times: Vec<f64> = arguments.map(|a| a.parse()).collect::<Result<_, _>>()?;
    let ctx = srt_gpu::GpuContext::new()?;
    println!(
        "{} — teaser, {}, {}x{} px",
        ctx.adapter_summary(),
        method.label(),
        size.0,
        size.1
    );
    let (mut editor, _) = Editor::from_arguments(&[])?;
    let mut view = SceneView::new(&ctx);
    view.upload(&ctx, editor.scene(), editor.structure_version())?;
    for ct in times {
        editor.set_time(ct)?;
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
        println!("ct = {ct}: {:.0} ms", start.elapsed().as_secs_f64() * 1e3);
    }
    Ok(())
}
