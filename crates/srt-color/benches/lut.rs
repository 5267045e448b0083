//! Benchmarks of the colour pipeline: building the GPU lookup table and one Eq. 11 integral.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use srt_color::{TemperatureLut, ToneMap, blackbody_xyz};

/// `TemperatureLut::build` at the default size and range, for both tone maps.
fn bench_lut_build(c: &mut Criterion) {
    let (t_min, t_max) = TemperatureLut::DEFAULT_RANGE_K;
    for tone_map in ToneMap::ALL {
        c.bench_function(
            &format!(
                "lut_build_{}_{}",
                tone_map.name(),
                TemperatureLut::DEFAULT_SIZE
            ),
            |b| {
                b.iter(|| {
                    TemperatureLut::build(
                        black_box(tone_map),
                        black_box(TemperatureLut::DEFAULT_SIZE),
                        black_box(t_min),
                        black_box(t_max),
                    )
                });
            },
        );
    }
}

/// One black-body XYZ integral (471 Planck evaluations) at fixed temperatures.
fn bench_blackbody_xyz(c: &mut Criterion) {
    for temperature in [1500.0, 6500.0] {
        c.bench_function(&format!("blackbody_xyz_{temperature}K"), |b| {
            b.iter(|| blackbody_xyz(black_box(temperature)));
        });
    }
}

/// Sampling the default table at a fixed set of temperatures.
fn bench_lut_sample(c: &mut Criterion) {
    let lut = TemperatureLut::with_defaults(ToneMap::Luminance);
    let temperatures: Vec<f64> = (0..1024).map(|i| 100.0 * 1.009_f64.powi(i)).collect();
    c.bench_function("lut_sample_1024", |b| {
        b.iter(|| {
            temperatures
                .iter()
                .map(|&t| lut.sample(black_box(t))[0])
                .sum::<f32>()
        });
    });
}

criterion_group!(
    benches,
    bench_lut_build,
    bench_blackbody_xyz,
    bench_lut_sample
);
criterion_main!(benches);
