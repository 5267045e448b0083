//! Requests beyond the adapter's limits are refused before anything is allocated, with a typed
//! error that names the limit (`GpuError::ExceedsLimit`), and leave the device usable.

use srt_gpu::{FootprintShape, GpuError, GpuRenderer, Method, context_or_skip};
use srt_scene::builtin_scenes;

fn fig7() -> srt_scene::Scene {
    let fig7 = builtin_scenes().iter().find(|b| b.name == "fig7").unwrap();
    fig7.build().unwrap().0
}

#[test]
fn an_image_wider_than_the_texture_limit_is_a_typed_error() {
    let Some(ctx) = context_or_skip("an_image_wider_than_the_texture_limit_is_a_typed_error")
    else {
        return;
    };
    let scene = fig7();
    let max = ctx.device.limits().max_texture_dimension_2d;
    // `srt render fig7 --width 16384 --height 2 --samples 4` asks for 2× supersampling.
    for width in [max + 1, 32_768.max(max + 1)] {
        let error = GpuRenderer::new(&ctx, &scene, width, 4)
            .err()
            .expect("wider than the adapter allows");
        let message = error.to_string();
        let GpuError::ExceedsLimit {
            requested,
            limit,
            limit_name,
            adapter,
            ..
        } = error
        else {
            panic!("not ExceedsLimit: {message}");
        };
        assert_eq!(
            (requested, limit, limit_name),
            (u64::from(width), u64::from(max), "max_texture_dimension_2d")
        );
        assert_eq!(adapter, ctx.adapter_info.name);
        assert!(
            message.contains(&format!("{width} × 4 render target"))
                && message.contains("max_texture_dimension_2d"),
            "{message}"
        );
        println!("{message}");
    }
    // Nothing was created, so wgpu has nothing to complain about.
    ctx.take_errors().unwrap();
}

#[test]
fn resizing_beyond_the_limit_keeps_the_renderer_usable() {
    let Some(ctx) = context_or_skip("resizing_beyond_the_limit_keeps_the_renderer_usable") else {
        return;
    };
    let scene = fig7();
    let mut renderer = GpuRenderer::new(&ctx, &scene, 32, 16).unwrap();
    let max = ctx.device.limits().max_texture_dimension_2d;
    let error = renderer.resize(&ctx, 8, max + 1).unwrap_err();
    assert!(
        matches!(
            error,
            GpuError::ExceedsLimit {
                limit_name: "max_texture_dimension_2d",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(renderer.size(), (32, 16));
    let (image, _) = renderer
        .render(&ctx, &scene, Method::Lrt, FootprintShape::Hull)
        .unwrap();
    assert_eq!(image.pixels.len(), 32 * 16);
    renderer.resize(&ctx, 24, 8).unwrap();
    let (image, _) = renderer
        .render(&ctx, &scene, Method::Polygon, FootprintShape::Hull)
        .unwrap();
    assert_eq!(
        (image.width, image.height, image.pixels.len()),
        (24, 8, 24 * 8)
    );
    ctx.take_errors().unwrap();
}
