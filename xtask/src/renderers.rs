//! One GPU renderer kept from case to case by `validate` and `bench`, as a viewer keeps one.

use anyhow::Context as _;
use srt_gpu::{GpuContext, GpuRenderer};
use srt_scene::Scene;

/// The last renderer made, kept for the next case while its scene uploads alike
/// ([`Scene::same_structure`]: the same parts, another speed or time) and resized to the next
/// case's size, as a viewer keeps one while the scene moves or the window changes: the image and
/// bench cases come in such runs (a model at three speeds, a static case at each size, a sweep's
/// frames), and a new renderer builds its BVHs again.
#[derive(Default)]
pub struct KeptRenderer {
    kept: Option<(Scene, GpuRenderer)>,
}

impl KeptRenderer {
    /// A renderer for `scene` at `size`: the kept one where it fits (resized), else a new one.
    pub fn for_scene(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        (width, height): (u32, u32),
    ) -> anyhow::Result<&mut GpuRenderer> {
        let fits = self
            .kept
            .as_ref()
            .is_some_and(|(uploaded, _)| uploaded.same_structure(scene));
        if !fits {
            self.kept = None;
            let renderer = GpuRenderer::new(ctx, scene, width, height)?;
            self.kept = Some((scene.clone(), renderer));
        }
        let (_, renderer) = self.kept.as_mut().context("a renderer was kept")?;
        renderer.resize(ctx, width, height)?;
        Ok(renderer)
    }
}
