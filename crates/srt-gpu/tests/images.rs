//! GPU images against the exact CPU reference: every built-in scene with local ray tracing (must
//! agree) and the polygon baseline (reported, expected to differ).

use srt_gpu::{FootprintShape, GpuRenderer, Method, context_or_skip};
use srt_scene::builtin_scenes;
use srt_trace::compare::compare;
use srt_trace::{RenderSettings, Tracer};

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

#[test]
fn lrt_matches_the_cpu_reference_on_every_builtin_scene() {
    let Some(ctx) = context_or_skip("lrt_matches_the_cpu_reference_on_every_builtin_scene") else {
        return;
    };
    for builtin in builtin_scenes() {
        let (scene, _) = builtin.build().unwrap();
        let reference = Tracer::new(&scene).render(
            RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                samples: 1,
            },
            &|_| {},
        );
        let mut renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
        renderer.set_fragment_counting(true);
        let mut line = format!("scene={}", builtin.name);
        for (method, shape) in [
            (Method::Lrt, FootprintShape::Hull),
            (Method::Lrt, FootprintShape::Rectangle),
            (Method::Polygon, FootprintShape::Hull),
        ] {
            let (image, stats) = renderer.render(&ctx, &scene, method, shape).unwrap();
            let mismatch = compare(&reference, &image.to_rgb8(), 2, 1);
            line += &format!(
                " {}/{:?}: mismatch={:.5} max={} fragments={:?}",
                method.name(),
                shape,
                mismatch.fraction(),
                mismatch.max_difference,
                stats.fragments
            );
            if method == Method::Lrt {
                assert!(mismatch.fraction() <= 0.001, "{line}");
            }
        }
        println!("{line}");
    }
    ctx.take_errors().unwrap();
}

/// The LRT pass counts its fragments only when asked to, and then shades at least one per
/// covered pixel and runs more than it shades (footprints are conservative); counting changes
/// no pixel.
#[test]
fn fragments_are_counted_only_when_measuring() {
    let Some(ctx) = context_or_skip("fragments_are_counted_only_when_measuring") else {
        return;
    };
    let (scene, _) = builtin_scenes()
        .iter()
        .find(|b| b.name == "fig4")
        .expect("fig4 is built in")
        .build()
        .unwrap();
    let mut renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
    let render = |renderer: &GpuRenderer| {
        renderer
            .render(&ctx, &scene, Method::Lrt, FootprintShape::Hull)
            .unwrap()
    };
    let (plain, stats) = render(&renderer);
    assert_eq!(stats.fragments, None);
    renderer.set_fragment_counting(true);
    let (counted, stats) = render(&renderer);
    let covered = plain.to_rgb8().iter().filter(|p| **p != [0, 0, 0]).count() as u64;
    let fragments = stats.fragments.expect("counting");
    assert!(
        covered > 0 && fragments.shaded >= covered && fragments.run > fragments.shaded,
        "{fragments:?}, {covered} covered"
    );
    assert_eq!(plain.to_rgb8(), counted.to_rgb8());
    renderer.set_fragment_counting(false);
    assert_eq!(render(&renderer).1.fragments, None);
}
