//! Reference-renderer throughput (rays per second) at 1280×720, one sample per pixel, on the
//! built-in `fig10-cube50`, `teaser` and `flythrough` scenes and on the 2CylinderEngine model of
//! Debian's assimp-testmodels (skipped with a printed notice when that package is not
//! installed): the frames `cargo xtask bench` times on the GPU, for docs/performance.md's
//! comparison of the two.

use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use srt_scene::builtin::find_builtin;
use srt_scene::{Scene, SceneDescription};
use srt_trace::{RenderSettings, Tracer};

const SETTINGS: RenderSettings = RenderSettings {
    width: 1280,
    height: 720,
    samples: 1,
};
/// The engine model, in the assimp corpus ([`srt_scene::corpus`]).
const ENGINE: &str = "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

fn bench_scene(c: &mut Criterion, name: &str, scene: &Scene) {
    let tracer = Tracer::new(scene);
    let mut group = c.benchmark_group("trace");
    group.sample_size(10);
    group.throughput(Throughput::Elements(u64::from(
        SETTINGS.width * SETTINGS.height,
    )));
    group.bench_function(format!("{name}_1280x720"), |b| {
        b.iter(|| tracer.render(SETTINGS, &|_| {}));
    });
    group.finish();
}

fn bench_render(c: &mut Criterion) {
    for name in ["fig10-cube50", "teaser", "flythrough"] {
        let (scene, _) = find_builtin(name)
            .expect("built-in scene")
            .build()
            .expect("valid scene");
        bench_scene(c, name, &scene);
    }
    let engine = srt_scene::corpus::folder().join(ENGINE);
    if engine.exists() {
        let description = SceneDescription::for_model(&engine, DVec3::new(0.0, 0.9, 0.0));
        let (scene, _) = description
            .build(Path::new("/"))
            .expect("the engine model loads");
        bench_scene(c, "2CylinderEngine", &scene);
    } else {
        println!(
            "SKIPPED 2CylinderEngine: {} not found; {}",
            engine.display(),
            srt_scene::corpus::HOW_TO_GET_IT
        );
    }
}

criterion_group!(benches, bench_render);
criterion_main!(benches);
