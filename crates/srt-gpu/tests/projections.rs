//! The wide projections (equirectangular, fisheye) on the GPU: the ray tracer, and so `auto`,
//! traces every pixel's ray in the projection — behind the observer included — and equals the
//! CPU reference under validate's rules; the pinhole-only methods refuse with the reason; a
//! picture drawn in tiles is the whole picture.

use std::sync::atomic::AtomicBool;

use srt_gpu::projection::ImageWindow;
use srt_gpu::{FootprintShape, GpuRenderer, Method, context_or_skip};
use srt_scene::{Projection, Scene, builtin_scenes};
use srt_trace::compare::{compare, compare_seen};
use srt_trace::{RenderSettings, Tracer};

/// validate's rules: a pixel differs beyond 2 steps, pixels beside a silhouette are not
/// compared, and at most 0.1 % may differ.
const TOLERANCE: u8 = 2;
const EDGE_MARGIN: u32 = 1;
const MAX_MISMATCH: f64 = 0.001;

/// A built-in scene in `projection`.
fn scene_in(name: &str, projection: Projection) -> Scene {
    let built = builtin_scenes().iter().find(|b| b.name == name).unwrap();
    let mut scene = built.build().unwrap().0;
    scene.observer.projection = projection;
    scene
}

/// The CPU reference's picture of `scene`, `width` × `height`, one sample per pixel.
fn cpu_image(scene: &Scene, width: u32, height: u32) -> srt_trace::RenderedImage {
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    Tracer::new(scene).render(settings, &|_| {})
}

/// The ray tracer's and `auto`'s pictures of `scene` are the CPU's `reference` under
/// validate's rules.
fn assert_traced_as_the_cpu(
    ctx: &srt_gpu::GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    reference: &srt_trace::RenderedImage,
    case: &str,
) {
    for method in [Method::Rt, Method::Auto] {
        let (image, _) = renderer
            .render(ctx, scene, method, FootprintShape::Hull)
            .unwrap_or_else(|e| panic!("{case} {method:?}: {e}"));
        let mismatch = compare(reference, &image.to_rgb8(), TOLERANCE, EDGE_MARGIN);
        assert!(
            mismatch.fraction() <= MAX_MISMATCH,
            "{case} {method:?}: {mismatch:?}"
        );
    }
}

/// The projections and the picture sizes they are drawn at.
fn projections() -> [(Projection, u32, u32); 3] {
    [
        (Projection::Equirectangular, 192, 96),
        (Projection::Fisheye { fov_deg: 180.0 }, 112, 112),
        (Projection::Fisheye { fov_deg: 220.0 }, 112, 112),
    ]
}

/// The ray tracer and `auto` draw every projection as the CPU does (display colours, and what
/// each pixel sees of time, the object channel −1 outside a fisheye's circle), for a starry sky
/// passing the observer (flythrough), bodies passing beside and behind the camera (teaser) and
/// a rolling wheel (a body moving in its frame).
#[test]
fn the_ray_tracer_draws_every_projection_as_the_cpu_does() {
    let Some(ctx) = context_or_skip("the_ray_tracer_draws_every_projection_as_the_cpu_does") else {
        return;
    };
    for name in ["flythrough", "teaser", "rolling-wheel"] {
        for (projection, width, height) in projections() {
            let scene = scene_in(name, projection);
            let settings = RenderSettings {
                width,
                height,
                samples: 1,
            };
            let tracer = Tracer::new(&scene);
            let reference = tracer.render(settings, &|_| {});
            let renderer = GpuRenderer::new(&ctx, &scene, width, height).unwrap();
            let case = format!("{name} {projection}");
            assert_traced_as_the_cpu(&ctx, &renderer, &scene, &reference, &case);
            let events = tracer
                .render_seen_events(width, height, &|_| {}, &AtomicBool::new(false))
                .unwrap();
            let seen = renderer
                .render_seen(&ctx, &scene, Method::Rt, FootprintShape::Hull)
                .unwrap();
            let mismatch = compare_seen(&reference, &events, &seen, 1e-3, EDGE_MARGIN);
            assert!(
                mismatch.fraction() <= MAX_MISMATCH,
                "{name} {projection} seen events: {mismatch:?}"
            );
            if matches!(projection, Projection::Fisheye { .. }) {
                // The corners lie outside the circle: nothing seen there.
                for index in [0, width as usize - 1, seen.len() - 1] {
                    assert_eq!(seen[index][4], -1.0, "{name} {projection} pixel {index}");
                }
            }
        }
    }
}

/// The full sphere shows what lies behind the observer: the teaser's objects passing behind it
/// are drawn at the picture's left and right edges (longitude ±180°), on the GPU as on the CPU.
#[test]
fn the_full_sphere_draws_what_is_behind_the_observer() {
    let Some(ctx) = context_or_skip("the_full_sphere_draws_what_is_behind_the_observer") else {
        return;
    };
    let (width, height) = (192, 96);
    let mut scene = scene_in("fig4", Projection::Equirectangular);
    // Turn the observer round: the model is now behind it.
    scene.observer.direction = -scene.observer.direction;
    let reference = cpu_image(&scene, width, height);
    let renderer = GpuRenderer::new(&ctx, &scene, width, height).unwrap();
    let (image, _) = renderer
        .render(&ctx, &scene, Method::Auto, FootprintShape::Hull)
        .unwrap();
    let covered_at = |x: u32| (0..height).any(|y| reference.coverage[(y * width + x) as usize] > 0);
    assert!(
        covered_at(0) && covered_at(width - 1) && !covered_at(width / 2),
        "the model is seen at the edges only"
    );
    let mismatch = compare(&reference, &image.to_rgb8(), TOLERANCE, EDGE_MARGIN);
    assert!(mismatch.fraction() <= MAX_MISMATCH, "{mismatch:?}");
}

/// A stereo pair on the GPU is the CPU's: side by side through the pinhole (teaser, the
/// flythrough's stars split between the eyes) and top-bottom as omni-directional stereo (the
/// flythrough, the rolling wheel), by the ray tracer and `auto`, under validate's rules.
#[test]
fn the_ray_tracer_draws_stereo_pairs_as_the_cpu_does() {
    let Some(ctx) = context_or_skip("the_ray_tracer_draws_stereo_pairs_as_the_cpu_does") else {
        return;
    };
    let cases = [
        ("teaser", Projection::Perspective, 192, 54),
        ("flythrough", Projection::Perspective, 192, 54),
        ("flythrough", Projection::Equirectangular, 128, 128),
        ("rolling-wheel", Projection::Equirectangular, 128, 128),
    ];
    for (name, projection, width, height) in cases {
        let mut scene = scene_in(name, projection);
        scene.observer.stereo = Some(srt_scene::Stereo {
            eye_separation: 1.5,
        });
        let reference = cpu_image(&scene, width, height);
        let renderer = GpuRenderer::new(&ctx, &scene, width, height).unwrap();
        let case = format!("{name} {projection} stereo");
        assert_traced_as_the_cpu(&ctx, &renderer, &scene, &reference, &case);
        for method in [Method::Lrt, Method::Polygon] {
            let why = method.cannot_draw(&scene).unwrap();
            assert!(why.contains("--method rt"), "{why}");
        }
    }
}

/// The local ray tracer and the polygon method draw through the pinhole: they refuse a wide
/// projection, naming it and what to use instead.
#[test]
fn the_pinhole_methods_refuse_a_wide_projection() {
    for (projection, ..) in projections() {
        let scene = scene_in("fig4", projection);
        for method in [Method::Lrt, Method::Polygon] {
            let why = method.cannot_draw(&scene).unwrap();
            assert!(
                why.contains(projection.name()) && why.contains("--method rt"),
                "{why}"
            );
        }
        for method in [Method::Rt, Method::Auto] {
            assert_eq!(method.cannot_draw(&scene), None);
        }
    }
}

/// A wide picture drawn in overlapping tiles is the whole picture to one 8-bit step: each tile's
/// pixels take their directions from their place in the whole picture (stars included).
#[test]
fn tiles_of_a_wide_picture_are_the_whole_picture() {
    let Some(ctx) = context_or_skip("tiles_of_a_wide_picture_are_the_whole_picture") else {
        return;
    };
    let (width, height, tile_width, tile_height) = (160u32, 80u32, 64u32, 48u32);
    for projection in [
        Projection::Equirectangular,
        Projection::Fisheye { fov_deg: 220.0 },
    ] {
        let scene = scene_in("flythrough", projection);
        let whole_renderer = GpuRenderer::new(&ctx, &scene, width, height).unwrap();
        let (whole, _) = whole_renderer
            .render(&ctx, &scene, Method::Auto, FootprintShape::Hull)
            .unwrap();
        let mut renderer = GpuRenderer::new(&ctx, &scene, tile_width, tile_height).unwrap();
        let mut tiled = vec![[0.0_f32; 4]; (width * height) as usize];
        for left in [0, tile_width, width - tile_width] {
            for top in [0, height - tile_height] {
                renderer.set_window(Some(ImageWindow {
                    left,
                    top,
                    image_width: width,
                    image_height: height,
                }));
                let (tile, _) = renderer
                    .render(&ctx, &scene, Method::Auto, FootprintShape::Hull)
                    .unwrap();
                for y in 0..tile_height {
                    for x in 0..tile_width {
                        tiled[((top + y) * width + left + x) as usize] =
                            tile.pixels[(y * tile_width + x) as usize];
                    }
                }
            }
        }
        let steps = (whole.pixels.iter().zip(&tiled))
            .flat_map(|(w, t)| (0..3).map(move |c| (w[c] - t[c]).abs() * 255.0))
            .fold(0.0_f32, f32::max);
        assert!(
            steps <= 1.0,
            "{projection}: a tile's pixel differs by {steps} steps"
        );
    }
}
