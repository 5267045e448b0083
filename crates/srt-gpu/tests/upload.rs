//! One upload serves every edit that `Scene::same_structure` accepts: a renderer uploaded for a scene
//! draws the scene with other velocities, times, effects and colours exactly as a renderer
//! uploaded for the edited scene (what the web page and other front ends rely on to skip the
//! upload when a slider moves), and `Scene::same_structure` refuses what changes the upload.

use glam::DVec3;
use srt_gpu::{FootprintShape, GpuRenderer, Method, context_or_skip};
use srt_scene::{Effects, Overrides, Scene, SceneSource, SurfaceColour};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn load(name: &str, overrides: &Overrides) -> Scene {
    SceneSource::resolve(name)
        .unwrap()
        .load_with(overrides)
        .unwrap()
        .scene
}

#[test]
fn a_kept_upload_draws_edits_as_a_fresh_one() {
    let Some(ctx) = context_or_skip("a_kept_upload_draws_edits_as_a_fresh_one") else {
        return;
    };
    let edits = [
        Overrides {
            beta: Some(DVec3::new(0.3, -0.2, 0.6)),
            ..Overrides::default()
        },
        Overrides {
            time: Some(1.5),
            effects: Some(Effects::Searchlight),
            ..Overrides::default()
        },
        Overrides {
            colour: Some(SurfaceColour::Spectral),
            ..Overrides::default()
        },
    ];
    for name in ["teaser", "clocks", "shadows", "rolling-wheel"] {
        let base = load(name, &Overrides::default());
        let kept = GpuRenderer::new(&ctx, &base, WIDTH, HEIGHT).unwrap();
        for edit in &edits {
            let edited = load(name, edit);
            assert!(
                Scene::same_structure(&base, &edited),
                "{name} with {edit:?}"
            );
            let fresh = GpuRenderer::new(&ctx, &edited, WIDTH, HEIGHT).unwrap();
            for method in [Method::Auto, Method::Polygon] {
                let draw = |renderer: &GpuRenderer| {
                    renderer
                        .render(&ctx, &edited, method, FootprintShape::Hull)
                        .unwrap()
                        .0
                        .to_rgb8()
                };
                assert!(
                    draw(&kept) == draw(&fresh),
                    "{name} with {edit:?}, {method:?}: the kept upload draws another picture"
                );
            }
        }
    }
}

#[test]
fn what_changes_the_upload_is_refused() {
    let teaser = load("teaser", &Overrides::default());
    assert!(!Scene::same_structure(
        &teaser,
        &load("fig7", &Overrides::default())
    ));
    let mut fewer = teaser.clone();
    fewer.objects.pop();
    assert!(!Scene::same_structure(&teaser, &fewer));
    let mut recoloured = teaser.clone();
    recoloured.objects[0].parts[0].material.base_color[0] *= 0.5;
    assert!(!Scene::same_structure(&teaser, &recoloured));
    let mut starry = teaser.clone();
    starry.sky = load("flythrough", &Overrides::default()).sky;
    assert_eq!(
        Scene::same_structure(&teaser, &starry),
        teaser.sky == starry.sky,
        "a sky of its own"
    );
}
