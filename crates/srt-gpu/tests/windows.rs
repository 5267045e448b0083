//! A render target holding a window of a larger picture (a tile, `GpuRenderer::set_window`)
//! draws the same rays through its pixels as the whole picture: tiles put together are the
//! whole picture's image, for every method, with a sky of stars and moving bodies.

use srt_gpu::projection::ImageWindow;
use srt_gpu::{FootprintShape, GpuRenderer, Method, context_or_skip};
use srt_scene::builtin_scenes;
use srt_trace::compare::compare;

/// The whole picture's size and a tile's: 3 × 3 tiles, the last column and row moved back
/// inside the picture (overlapping), as srt's tiling places them.
const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
const TILE_WIDTH: u32 = 64;
const TILE_HEIGHT: u32 = 40;

/// The tiles' top-left corners.
fn corners() -> Vec<(u32, u32)> {
    let starts = |size: u32, tile: u32| {
        let mut starts: Vec<u32> = (0..size).step_by(tile as usize).collect();
        if let Some(last) = starts.last_mut() {
            *last = (*last).min(size - tile);
        }
        starts
    };
    let tops = starts(HEIGHT, TILE_HEIGHT);
    starts(WIDTH, TILE_WIDTH)
        .into_iter()
        .flat_map(|left| tops.iter().map(move |&top| (left, top)))
        .collect()
}

/// 8-bit display colours of a GPU image's pixels.
fn rgb8(pixels: &[[f32; 4]]) -> Vec<[u8; 3]> {
    (pixels.iter())
        .map(|c| [0, 1, 2].map(|k| (c[k].clamp(0.0, 1.0) * 255.0).round() as u8))
        .collect()
}

/// The exact methods' tiles are the whole picture to one 8-bit step in every pixel (their rays
/// and footprints are the whole picture's; only f32 rounding of the moved camera differs). The
/// polygon method rasterises triangles through the window's matrix, and pixels on triangle
/// edges may fall the other way: its tiles stay as close to the CPU reference as its whole
/// picture (validate's rule, with a quarter more differing pixels allowed).
#[test]
fn tiles_put_together_are_the_whole_picture() {
    let Some(ctx) = context_or_skip("tiles_put_together_are_the_whole_picture") else {
        return;
    };
    let mut drawn = 0;
    for name in ["fig4", "teaser", "flythrough", "rolling-wheel"] {
        let built = builtin_scenes().iter().find(|b| b.name == name).unwrap();
        let scene = built.build().unwrap().0;
        let settings = srt_trace::RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            samples: 1,
        };
        let reference = srt_trace::Tracer::new(&scene).render(settings, &|_| {});
        let whole_renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
        let mut renderer = GpuRenderer::new(&ctx, &scene, TILE_WIDTH, TILE_HEIGHT).unwrap();
        for method in [Method::Lrt, Method::Rt, Method::Auto, Method::Polygon] {
            if method.cannot_draw(&scene).is_some() {
                continue;
            }
            let (whole, _) = whole_renderer
                .render(&ctx, &scene, method, FootprintShape::Hull)
                .unwrap();
            let mut tiled = vec![[0.0_f32; 4]; (WIDTH * HEIGHT) as usize];
            for (left, top) in corners() {
                renderer.set_window(Some(ImageWindow {
                    left,
                    top,
                    image_width: WIDTH,
                    image_height: HEIGHT,
                }));
                let (tile, _) = renderer
                    .render(&ctx, &scene, method, FootprintShape::Hull)
                    .unwrap();
                for y in 0..TILE_HEIGHT {
                    for x in 0..TILE_WIDTH {
                        tiled[((top + y) * WIDTH + left + x) as usize] =
                            tile.pixels[(y * TILE_WIDTH + x) as usize];
                    }
                }
            }
            let case = format!("{name} {method:?}");
            let (whole, tiled) = (rgb8(&whole.pixels), rgb8(&tiled));
            if method.is_exact() {
                let steps = (whole.iter().zip(&tiled))
                    .flat_map(|(w, t)| (0..3).map(|c| w[c].abs_diff(t[c])))
                    .max()
                    .unwrap();
                assert!(
                    steps <= 1,
                    "{case}: a tile's pixel differs by {steps} steps"
                );
            } else {
                let on_whole = compare(&reference, &whole, 2, 1);
                let on_tiles = compare(&reference, &tiled, 2, 1);
                assert!(
                    on_tiles.differing * 4 <= on_whole.differing * 5 + on_whole.compared / 1000,
                    "{case}: tiles {on_tiles:?}, whole picture {on_whole:?}"
                );
            }
            drawn += 1;
        }
    }
    assert!(drawn >= 13, "{drawn} scene and method pairs drawn");
}
