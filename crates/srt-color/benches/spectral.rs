//! Benchmarks of spectral surface colour: building the Jakob–Hanika coefficient table, one fresh
//! fit, a table lookup and one reflected-light display colour (the per-point cost for a renderer).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use srt_color::spectral::Reflectance;
use srt_color::{
    CoefficientTable, ToneMap, fit_rgb, reflected_display_rgb, srgb_coefficient_table,
};

/// `CoefficientTable::build` at the default resolution, on all cores.
fn bench_table_build(c: &mut Criterion) {
    let mut group = c.benchmark_group("spectral_table");
    group.sample_size(10);
    group.bench_function(
        format!("build_{}", CoefficientTable::DEFAULT_RESOLUTION),
        |b| b.iter(|| CoefficientTable::build(black_box(CoefficientTable::DEFAULT_RESOLUTION))),
    );
    group.finish();
}

/// One fresh fit, one table lookup, and one reflected display colour.
fn bench_per_colour(c: &mut Criterion) {
    let rgb = DVec3::new(0.6, 0.25, 0.05);
    c.bench_function("fit_rgb", |b| b.iter(|| fit_rgb(black_box(rgb))));
    let table = srgb_coefficient_table();
    c.bench_function("table_lookup", |b| b.iter(|| table.lookup(black_box(rgb))));
    let reflectance = Reflectance::new(table.lookup(rgb).expect("rgb is in [0, 1]"));
    c.bench_function("reflected_display_rgb", |b| {
        b.iter(|| {
            reflected_display_rgb(
                ToneMap::Luminance,
                black_box(&reflectance),
                6504.0,
                black_box(0.9),
                black_box(1.3),
                1.0,
            )
        });
    });
}

criterion_group!(benches, bench_table_build, bench_per_colour);
criterion_main!(benches);
