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
        let renderer = GpuRenderer::new(&ctx, &scene, WIDTH, HEIGHT).unwrap();
        let mut line = format!("scene={}", builtin.name);
        for (method, shape) in [
            (Method::Lrt, FootprintShape::Hull),
            (Method::Lrt, FootprintShape::Rectangle),
            (Method::Polygon, FootprintShape::Hull),
        ] {
            let (image, stats) = renderer.render(&ctx, &scene, method, shape).unwrap();
            let mismatch = compare(&reference, &image.to_rgb8(), 2, 1);
            line += &format!(
                " {}/{:?}: mismatch={:.5} max={} fragments={}",
                method.name(),
                shape,
                mismatch.fraction(),
                mismatch.max_difference,
                stats.fragments_shaded
            );
            if method == Method::Lrt {
                assert!(mismatch.fraction() <= 0.001, "{line}");
            }
        }
        println!("{line}");
    }
    ctx.take_errors().unwrap();
}
