//! Benchmarks of the per-point physics: apparent position (Eq. 5–8) and its tangent.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use srt_physics::{Event, Frame};
use std::hint::black_box;

fn seeded_points(count: usize) -> Vec<DVec3> {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed);
    (0..count)
        .map(|_| {
            DVec3::new(
                rng.random_range(-5.0..5.0),
                rng.random_range(-5.0..5.0),
                rng.random_range(-5.0..5.0),
            )
        })
        .collect()
}

fn bench_apparent_position(c: &mut Criterion) {
    let frame = Frame::new(DVec3::new(0.0, 0.95, 0.0), DVec3::ZERO).expect("valid frame");
    let observer = Event::new(5.12, DVec3::new(2.0, 5.0, 0.2));
    let points = seeded_points(1024);
    let mut group = c.benchmark_group("physics");
    group.throughput(criterion::Throughput::Elements(points.len() as u64));
    group.bench_function("apparent_position_x1024", |b| {
        b.iter(|| {
            let mut acc = DVec3::ZERO;
            for &p in &points {
                acc += frame.apparent_position(black_box(p), observer);
            }
            acc
        });
    });
    group.bench_function("apparent_tangent_x1024", |b| {
        b.iter(|| {
            let mut acc = DVec3::ZERO;
            for &p in &points {
                acc += frame.apparent_tangent(black_box(p), DVec3::X, observer);
            }
            acc
        });
    });
    group.finish();
}

criterion_group!(benches, bench_apparent_position);
criterion_main!(benches);
