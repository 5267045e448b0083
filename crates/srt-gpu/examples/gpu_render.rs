//! Renders a scene with the GPU local ray tracer, headless, writes it as a PNG and compares it
//! with the exact CPU reference (srt-trace).
//!
//! `cargo run --release -p srt-gpu --example gpu_render -- [SCENE] [OUT.png]`: SCENE is a
//! built-in scene's name (`fig10-cube50` by default), a scene file or a model; the picture goes
//! to OUT.png, by default SCENE-gpu.png in the current folder. Any adapter wgpu finds will do,
//! Mesa's software lavapipe and llvmpipe included (`WGPU_BACKEND=vulkan` or `gl` chooses).

use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_scene::SceneSource;
use srt_trace::{RenderSettings, Tracer, compare::compare};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut arguments = std::env::args().skip(1);
    let name = arguments
        .next()
        .unwrap_or_else(|| "fig10-cube50".to_owned());
    let scene = SceneSource::resolve(&name)?.load(None)?.scene;
    let output = arguments
        .next()
        .unwrap_or_else(|| format!("{}-gpu.png", scene.name));
    let (width, height) = (640, 360);

    // Upload the scene once; each frame runs the footprint (proxy) compute pass, draws the
    // footprints with a ray test per fragment in the triangle's rest frame, and shades.
    let context = GpuContext::new()?;
    let renderer = GpuRenderer::new(&context, &scene, width, height)?;
    let (image, _stats) = renderer.render(&context, &scene, Method::Auto, FootprintShape::Hull)?;
    let rgb = image.to_rgb8();
    image::RgbImage::from_raw(width, height, rgb.concat())
        .expect("one colour per pixel")
        .save(&output)?;
    println!("wrote {output} on {}", context.adapter_summary());

    // The same picture from the exact CPU renderer, one sample per pixel centre.
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    let reference = Tracer::new(&scene).render(settings, &|_| {});
    let mismatch = compare(&reference, &rgb, 2, 1);
    println!(
        "{} of {} pixels away from silhouettes differ from the CPU reference by more than 2/255 (at most {}/255)",
        mismatch.differing, mismatch.compared, mismatch.max_difference
    );
    Ok(())
}
