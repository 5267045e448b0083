//! A mesh larger than the device's storage bindings allow one batch is split into slices at
//! upload, invisibly: on a device whose bindings are made small on purpose, a finely divided
//! cube is uploaded in several batches and every exact method draws it as the CPU reference
//! does (validate's rules), and as the same renderer does on the adapter's own limits.

use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method, context_or_skip};
use srt_scene::{Scene, SceneDescription, builtin_scenes};
use srt_trace::compare::compare;

use crate::common::{HEIGHT, WIDTH, cpu_image};

/// validate's rules: pixels apart by more than 2 steps, silhouettes' neighbours left out, at
/// most 0.1 % of them.
const TOLERANCE: u8 = 2;
const EDGE_MARGIN: u32 = 1;
const MAX_MISMATCH: f64 = 0.001;

/// The storage binding size of the small device, 1440 KiB: the colour tables (the spectral table
/// is 1.2 MB) and the ray tracer's triangles (1.44 MB) fit, the cube's footprints (2.9 MB) need
/// three slices.
const SMALL_BINDING: u64 = 1440 << 10;

/// Fig. 10's cube at 0.95c with 50 × 50 squares a face: 30 000 triangles in one part.
fn fine_cube() -> Scene {
    let built = builtin_scenes()
        .iter()
        .find(|b| b.name == "fig10-cube200")
        .unwrap();
    let text = built
        .toml()
        .replace("subdivisions = 10", "subdivisions = 50");
    let description = SceneDescription::from_toml_str(&text, "fine cube").unwrap();
    description.build(std::path::Path::new(".")).unwrap().0
}

#[test]
fn a_mesh_larger_than_the_bindings_draws_in_slices() {
    let Some(full) = context_or_skip("a_mesh_larger_than_the_bindings_draws_in_slices") else {
        return;
    };
    let small = GpuContext::with_limits(|limits| wgpu::Limits {
        max_storage_buffer_binding_size: SMALL_BINDING,
        ..limits
    })
    .unwrap();
    let scene = fine_cube();
    assert_eq!(scene.objects[0].parts[0].mesh.triangles().len(), 30_000);
    let reference = cpu_image(&scene);
    let sliced = GpuRenderer::new(&small, &scene, WIDTH, HEIGHT).unwrap();
    let whole = GpuRenderer::new(&full, &scene, WIDTH, HEIGHT).unwrap();
    assert_eq!(sliced.object_batches(), vec![3]);
    assert_eq!(whole.object_batches(), vec![1]);
    for method in [Method::Lrt, Method::Rt, Method::Auto] {
        let draw = |ctx: &GpuContext, renderer: &GpuRenderer| {
            let (image, _) = renderer
                .render(ctx, &scene, method, FootprintShape::Hull)
                .unwrap();
            image.to_rgb8()
        };
        let image = draw(&small, &sliced);
        let mismatch = compare(&reference, &image, TOLERANCE, EDGE_MARGIN);
        assert!(
            mismatch.fraction() <= MAX_MISMATCH,
            "{method:?} in slices: {mismatch:?} against the CPU"
        );
        let unsliced = draw(&full, &whole);
        let apart = image.iter().zip(&unsliced).filter(|(a, b)| a != b).count();
        assert!(
            apart <= image.len() / 1000,
            "{method:?}: {apart} pixels differ from the unsliced upload's"
        );
    }
}
