//! Fig. 13 of the paper, redrawn: a model passing the observer at 0.99c, already behind it while
//! the observer looks diagonally ahead to the right, drawn by the image-based method (a cube
//! map of 2048² per face, the paper's), the polygon method and exactly (the CPU reference), side
//! by side, and the image-based picture again at smaller cube maps: its error falls as the cube
//! map grows. The embedded spider stands in for the paper's Tie-Interceptor. Printed with it:
//! the image-based method's error against the exact picture by cube map size, on this case and
//! on the flythrough (docs/performance.md quotes both).

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use image::{Rgb, RgbImage};
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_scene::Scene;
use srt_scene::builtin::find_builtin;
use srt_trace::compare::compare;
use srt_trace::{RenderSettings, RenderedImage, Tracer};

use super::write_panel_grid;
use crate::validate::{EDGE_MARGIN, TOLERANCE};

/// A panel's size (the paper's 1280 × 720 halved).
const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;

/// The cube map sizes of the error table; the paper's 2048 is the figure's first panel.
const CUBE_SIZES: [u32; 6] = [128, 256, 512, 1024, 2048, 4096];

/// Writes `fig13_image_based.png` and prints the image-based method's error by cube map size;
/// without a GPU adapter the figure is skipped with a note (a failure where
/// `SRT_REQUIRE_GPU=1`).
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(error) if std::env::var("SRT_REQUIRE_GPU").as_deref() != Ok("1") => {
            println!("SKIPPED fig13_image_based.png: no GPU adapter ({error})");
            return Ok(Vec::new());
        }
        Err(error) => return Err(error).context("fig13_image_based.png needs a GPU adapter"),
    };
    let passing = passing_spider()?;
    let exact = exact_image(&passing);
    let mut panels = Vec::new();
    let mut errors = Vec::new();
    for size in CUBE_SIZES {
        let (image, error) = image_based(&ctx, &passing, size, &exact)?;
        errors.push(error);
        panels.push((
            image,
            format!(
                "image-based, {size}² per face: {:.1} % of pixels differ",
                100.0 * error
            ),
        ));
    }
    let polygon = gpu_image(&ctx, &passing, Method::Polygon)?;
    let polygon_error = compare(&exact, &polygon, TOLERANCE, EDGE_MARGIN).fraction();
    let paper = CUBE_SIZES.iter().position(|&s| s == 2048).context("2048")?;
    let mut grid = vec![
        panels[paper].clone(),
        (
            to_image(&polygon),
            format!(
                "polygon (§3.2): {:.1} % of pixels differ",
                100.0 * polygon_error
            ),
        ),
        (
            to_image(&exact.to_rgb8()),
            "exact (local ray tracing)".to_owned(),
        ),
    ];
    grid.extend(panels[1..4].iter().cloned());
    let path = out_dir.join("fig13_image_based.png");
    write_panel_grid(
        &path,
        "Fig. 13: the spider at 0.99c has passed the observer, who looks diagonally to the right",
        &grid,
        3,
    )?;
    let flythrough = find_builtin("flythrough")
        .context("flythrough is built in")?
        .build()?
        .0;
    let flythrough_exact = exact_image(&flythrough);
    let mut flythrough_errors = Vec::new();
    for size in CUBE_SIZES {
        flythrough_errors.push(image_based(&ctx, &flythrough, size, &flythrough_exact)?.1);
    }
    println!(
        "image-based error (fraction of {WIDTH}x{HEIGHT} pixels differing by more than {TOLERANCE}/255, silhouettes' neighbours left out) on {}:",
        ctx.adapter_summary()
    );
    println!("| cube map side | Fig. 13 case | flythrough |");
    println!("|---:|---:|---:|");
    for ((size, error), fly) in CUBE_SIZES.iter().zip(&errors).zip(&flythrough_errors) {
        println!("| {size} | {error:.4} | {fly:.4} |");
    }
    println!("| polygon | {polygon_error:.4} | |");
    Ok(vec![path])
}

/// The embedded spider flying towards −y at 0.99c, 1.2 units past the observer at ct = 0 and
/// 1.5 to its right, the observer at the origin looking along (1, 0.5, 0), its right.
fn passing_spider() -> anyhow::Result<Scene> {
    let builtin = find_builtin("spider").context("spider is built in")?;
    let mut description = builtin.description();
    description.observer.position = [0.0; 3];
    description.observer.look_at = None;
    description.observer.direction = Some([1.0, 0.5, 0.0]);
    description.observer.fov_y_deg = 60.0;
    // The lamp at the observer.
    description.light = None;
    let spider = description
        .objects
        .first_mut()
        .context("the spider scene has its spider")?;
    spider.beta = [0.0, -0.99, 0.0];
    spider.offset = [1.5, -1.2, -0.3];
    Ok(builtin.build_description(&description)?.0)
}

/// The CPU reference's picture of `scene`.
fn exact_image(scene: &Scene) -> RenderedImage {
    let settings = RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        samples: 1,
    };
    Tracer::new(scene).render(settings, &|_| {})
}

/// `scene` drawn by `method` on the GPU, 8-bit.
fn gpu_image(ctx: &GpuContext, scene: &Scene, method: Method) -> anyhow::Result<Vec<[u8; 3]>> {
    let renderer = GpuRenderer::new(ctx, scene, WIDTH, HEIGHT)?;
    let (image, _) = renderer.render(ctx, scene, method, FootprintShape::Hull)?;
    Ok(image.to_rgb8())
}

/// The image-based picture of `scene` with cube maps of `size` texels a side, and the fraction
/// of its pixels told apart from `exact`.
fn image_based(
    ctx: &GpuContext,
    scene: &Scene,
    size: u32,
    exact: &RenderedImage,
) -> anyhow::Result<(RgbImage, f64)> {
    let mut scene = scene.clone();
    scene.cube_map_size = size;
    let rgb = gpu_image(ctx, &scene, Method::ImageBased)?;
    let error = compare(exact, &rgb, TOLERANCE, EDGE_MARGIN).fraction();
    Ok((to_image(&rgb), error))
}

/// An 8-bit picture as an image.
fn to_image(rgb: &[[u8; 3]]) -> RgbImage {
    RgbImage::from_fn(WIDTH, HEIGHT, |x, y| Rgb(rgb[(y * WIDTH + x) as usize]))
}
