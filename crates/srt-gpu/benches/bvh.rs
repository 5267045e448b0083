//! What the GPU ray tracer's BVH costs to build when a scene is uploaded (`ObjectBvh::build`,
//! obvhs's PLOC builder): a UV sphere of 130 320 triangles, about the 2CylinderEngine's size.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use srt_gpu::bvh::ObjectBvh;
use srt_scene::shapes::uv_sphere;

fn bench_build(c: &mut Criterion) {
    let mesh = uv_sphere(1.0, 362);
    let positions = mesh.positions();
    let triangles: Vec<[[f32; 3]; 3]> = mesh
        .triangles()
        .iter()
        .map(|t| t.map(|v| positions[v as usize].as_vec3().to_array()))
        .collect();
    let mut group = c.benchmark_group("bvh");
    group.sample_size(10);
    group.throughput(Throughput::Elements(triangles.len() as u64));
    group.bench_function(format!("build_{}_triangles", triangles.len()), |b| {
        b.iter(|| ObjectBvh::build(&triangles, || "sphere".into()).expect("shallow enough"));
    });
    group.finish();
}

criterion_group!(benches, bench_build);
criterion_main!(benches);
