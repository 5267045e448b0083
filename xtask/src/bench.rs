//! `cargo xtask bench`: the paper's Table 1 on the current adapter at 1280×720 — median frame
//! time of local ray tracing and of the polygon method, their ratio, and the overdraw of the LRT
//! footprints (fragments shaded per pixel actually covered) with rectangles and with hulls.
//! Prints one line per scene and rewrites the table in `docs/performance.md`.

use std::path::Path;
use std::time::Instant;

use anyhow::Context as _;
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_scene::Scene;
use srt_trace::{RenderSettings, Tracer};

use crate::cases::{Case, builtin_cases, model_case};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 720;
const WARM_UP: u32 = 3;
const TABLE_START: &str = "<!-- table1:start (written by cargo xtask bench) -->";
const TABLE_END: &str = "<!-- table1:end -->";

/// One row of Table 1.
struct Row {
    scene: String,
    triangles: usize,
    lrt_ms: f64,
    polygon_ms: f64,
    overdraw_rect: f64,
    overdraw_hull: f64,
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Median frame time in ms: GPU timestamps where supported, else wall clock of render + readback.
fn frame_time(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    method: Method,
    frames: u32,
) -> anyhow::Result<(f64, bool)> {
    for _ in 0..WARM_UP {
        renderer.render(ctx, scene, method, FootprintShape::Hull)?;
    }
    let mut times = Vec::new();
    let mut timestamps = true;
    for _ in 0..frames {
        let start = Instant::now();
        let (_, stats) = renderer.render(ctx, scene, method, FootprintShape::Hull)?;
        let wall = start.elapsed().as_secs_f64() * 1e3;
        timestamps &= stats.gpu_time_ms.is_some();
        times.push(stats.gpu_time_ms.unwrap_or(wall));
    }
    Ok((median(times), timestamps))
}

fn measure(ctx: &GpuContext, case: &Case, frames: u32) -> anyhow::Result<Row> {
    let scene = &case.scene;
    let renderer = GpuRenderer::new(ctx, scene, WIDTH, HEIGHT)?;
    let (lrt_ms, _) = frame_time(ctx, &renderer, scene, Method::Lrt, frames)?;
    let (polygon_ms, _) = frame_time(ctx, &renderer, scene, Method::Polygon, frames)?;
    let covered = Tracer::new(scene)
        .render(
            RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                samples: 1,
            },
            &|_| {},
        )
        .coverage
        .iter()
        .filter(|&&c| c != 0)
        .count()
        .max(1) as f64;
    let fragments = |shape| -> anyhow::Result<f64> {
        Ok(renderer
            .render(ctx, scene, Method::Lrt, shape)?
            .1
            .fragments_shaded
            .context("the renderer counts fragments")? as f64)
    };
    Ok(Row {
        scene: case.name.clone(),
        triangles: scene.triangle_count(),
        lrt_ms,
        polygon_ms,
        overdraw_rect: fragments(FootprintShape::Rectangle)? / covered,
        overdraw_hull: fragments(FootprintShape::Hull)? / covered,
    })
}

/// Runs the benchmark and updates `docs/performance.md`.
///
/// # Errors
/// No GPU, missing models, or an unwritable document.
pub fn run(workspace: &Path, frames: u32) -> anyhow::Result<()> {
    let ctx =
        GpuContext::new().context("cargo xtask bench needs a GPU adapter (software ones count)")?;
    let adapter = ctx.adapter_summary();
    println!("adapter: {adapter}");
    let builtins = builtin_cases()?;
    let builtin = |name: &str| {
        builtins.iter().find(|c| c.name == name).map(|c| Case {
            name: c.name.clone(),
            scene: c.scene.clone(),
        })
    };
    let cases = [
        builtin("fig10-cube50"),
        builtin("fig10-cube200"),
        Some(model_case("OBJ/spider.obj", 0.9)?),
        Some(model_case(
            "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
            0.9,
        )?),
        builtin("teaser"),
    ];
    let timing = if ctx.timestamps {
        "GPU timestamp queries"
    } else {
        "wall clock of render + readback"
    };
    let mut rows = Vec::new();
    for case in cases.into_iter().flatten() {
        let row = measure(&ctx, &case, frames)?;
        println!(
            "scene={} tris={} lrt_ms={:.2} polygon_ms={:.2} ratio={:.2} overdraw_rect={:.2} overdraw_hull={:.2}",
            row.scene,
            row.triangles,
            row.lrt_ms,
            row.polygon_ms,
            row.lrt_ms / row.polygon_ms,
            row.overdraw_rect,
            row.overdraw_hull
        );
        rows.push(row);
    }
    let mut table = format!(
        "{TABLE_START}\nAdapter: {adapter}. 1280×720, median of {frames} frames after {WARM_UP} warm-up frames, timed by {timing}.\n\n\
         | scene | triangles | LRT ms | polygon ms | LRT / polygon | overdraw (rectangle) | overdraw (hull) |\n|---|---:|---:|---:|---:|---:|---:|\n"
    );
    for r in &rows {
        table += &format!(
            "| {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |\n",
            r.scene,
            r.triangles,
            r.lrt_ms,
            r.polygon_ms,
            r.lrt_ms / r.polygon_ms,
            r.overdraw_rect,
            r.overdraw_hull
        );
    }
    table += TABLE_END;
    let doc = workspace.join("docs/performance.md");
    let text =
        std::fs::read_to_string(&doc).with_context(|| format!("cannot read {}", doc.display()))?;
    let updated = match (text.find(TABLE_START), text.find(TABLE_END)) {
        (Some(a), Some(b)) if a < b => {
            format!("{}{table}{}", &text[..a], &text[b + TABLE_END.len()..])
        }
        _ => format!("{text}\n{table}\n"),
    };
    std::fs::write(&doc, updated).with_context(|| format!("cannot write {}", doc.display()))?;
    println!("updated {}", doc.display());
    Ok(())
}
