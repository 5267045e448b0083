//! Benchmark of the §4.1 footprint of one triangle (seeded random triangles).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use glam::dcamera::rh::proj::directx::perspective;
use glam::dcamera::rh::view::look_at_mat4;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use srt_physics::{Event, Frame};
use srt_proxy::{Viewport, footprint};
use std::hint::black_box;

fn bench_footprint(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed);
    let mut point = || {
        DVec3::new(
            rng.random_range(-2.5..2.5),
            rng.random_range(-2.5..2.5),
            rng.random_range(-2.5..2.5),
        )
    };
    let triangles: Vec<[DVec3; 3]> = (0..1024).map(|_| [point(), point(), point()]).collect();
    let frame =
        Frame::new(DVec3::new(0.0, 0.0, 0.95), DVec3::new(0.0, 0.0, -30.0)).expect("valid frame");
    let observer = Event::new(0.0, DVec3::new(0.0, 0.0, 10.0));
    let view_projection = perspective(60f64.to_radians(), 16.0 / 9.0, 0.1, 1000.0)
        * look_at_mat4(observer.position, DVec3::ZERO, DVec3::Y);
    let viewport = Viewport {
        width: 1280.0,
        height: 720.0,
    };
    let mut group = c.benchmark_group("proxy");
    group.throughput(Throughput::Elements(triangles.len() as u64));
    group.bench_function("footprint_x1024", |b| {
        b.iter(|| {
            triangles
                .iter()
                .map(|&t| {
                    footprint(&frame, black_box(t), observer, view_projection, viewport)
                        .rect
                        .area()
                })
                .sum::<f64>()
        });
    });
    group.finish();
}

criterion_group!(benches, bench_footprint);
criterion_main!(benches);
