//! What the GPU-against-CPU image tests share: the image size and the CPU reference's image.

use srt_scene::Scene;
use srt_trace::{RenderSettings, RenderedImage, Tracer};

/// Width of the compared images.
pub const WIDTH: u32 = 320;
/// Height of the compared images.
pub const HEIGHT: u32 = 180;

/// The CPU reference's image of `scene` (one sample per pixel).
pub fn cpu_image(scene: &Scene) -> RenderedImage {
    Tracer::new(scene).render(
        RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            samples: 1,
        },
        &|_| {},
    )
}
