//! The WGSL kernels agree with their `f64` CPU originals within tolerances derived from `f32`
//! rounding analysis (see `srt_gpu::probe`): the physics of `physics.wgsl` against
//! `srt-physics`, and `lut_sample` of `colour.wgsl` against `TemperatureLut::sample`.

use glam::DVec4;
use srt_color::{TemperatureLut, ToneMap};
use srt_gpu::probe::{
    self, PHYSICS_KERNELS, PhysicsProbeResult, compare_physics, lut_max_step,
    lut_position_tolerance, lut_tolerance, reference, relative_error, run_lut_probe,
    run_physics_probe, seeded_cases,
};

const CASES: usize = 4096;

#[test]
fn physics_kernels_match_the_cpu() {
    let Some(ctx) = srt_gpu::context_or_skip("physics_kernels_match_the_cpu") else {
        return;
    };
    println!("adapter: {}", ctx.adapter_summary());
    let cases = seeded_cases(0x5eed, CASES);
    let results = run_physics_probe(&ctx, &cases).unwrap();
    assert_eq!(results.len(), cases.len());
    let errors = compare_physics(&cases, &results);
    assert_eq!(errors.len(), PHYSICS_KERNELS.len());
    for error in &errors {
        println!("{error}");
    }
    let failed: Vec<String> = errors
        .iter()
        .filter(|e| !e.passes())
        .map(|e| e.to_string())
        .collect();
    assert!(
        failed.is_empty(),
        "kernels outside their tolerance:\n{}",
        failed.join("\n")
    );
    ctx.take_errors().unwrap();
}

#[test]
fn physics_probe_handles_no_cases() {
    let Some(ctx) = srt_gpu::context_or_skip("physics_probe_handles_no_cases") else {
        return;
    };
    assert!(run_physics_probe(&ctx, &[]).unwrap().is_empty());
    assert!(
        run_lut_probe(
            &ctx,
            &TemperatureLut::with_defaults(ToneMap::Luminance),
            &[]
        )
        .unwrap()
        .is_empty()
    );
    ctx.take_errors().unwrap();
}

#[test]
fn physics_probe_is_exact_where_the_physics_is_trivial() {
    // β = 0: Λ = I exactly in f32, so every kernel is exact up to the rounding of sums, and a
    // point at the observer's distance d is seen at d with D = 1.
    let Some(ctx) = srt_gpu::context_or_skip("physics_probe_is_exact_where_the_physics_is_trivial")
    else {
        return;
    };
    let mut cases = seeded_cases(7, 64);
    for case in &mut cases {
        case.frame = srt_physics::Frame::new(glam::DVec3::ZERO, case.frame.offset()).unwrap();
    }
    let results = run_physics_probe(&ctx, &cases).unwrap();
    for (case, gpu) in cases.iter().zip(&results) {
        assert_eq!(gpu.lorentz_factor, 1.0);
        assert_eq!(gpu.doppler_factor, 1.0);
        assert_eq!(gpu.reflection_doppler, 1.0);
        let cpu = reference(case);
        let scale = probe::case_scale(case);
        let position = relative_error(
            gpu.apparent_position.extend(0.0),
            cpu.apparent_position.extend(0.0),
            scale,
        );
        assert!(position <= 4.0 * probe::F32_UNIT_ROUNDOFF, "{position:e}");
    }
    ctx.take_errors().unwrap();
}

#[test]
fn comparison_is_zero_for_the_reference_and_flags_a_wrong_result() {
    // No GPU: guards compare_physics against passing vacuously.
    let cases = seeded_cases(11, 32);
    let mut results: Vec<PhysicsProbeResult> = cases.iter().map(reference).collect();
    assert!(
        compare_physics(&cases, &results)
            .iter()
            .all(|e| e.worst_relative == 0.0 && e.passes())
    );
    results[5].apparent_position.x += 0.01 * probe::case_scale(&cases[5]);
    results[9].doppler_factor *= 1.0 + 1e-3;
    results[3].backward_ray.direction.y = f64::NAN;
    let errors = compare_physics(&cases, &results);
    let find = |name: &str| errors.iter().find(|e| e.kernel == name).unwrap();
    assert!(!find("apparent_position").passes() && find("apparent_position").worst_case == 5);
    assert!(!find("doppler_factor").passes() && find("doppler_factor").worst_case == 9);
    assert!(find("backward_ray").worst_relative.is_nan() && !find("backward_ray").passes());
    assert!(find("to_rest").passes());
    assert_eq!(relative_error(DVec4::ZERO, DVec4::ZERO, 0.0), 0.0);
}

#[test]
fn seeded_cases_are_reproducible_and_span_the_documented_ranges() {
    let a = seeded_cases(42, 1000);
    assert_eq!(a, seeded_cases(42, 1000));
    assert_ne!(a, seeded_cases(43, 1000));
    let max_speed = a
        .iter()
        .map(|c| c.frame.beta().length())
        .fold(0.0, f64::max);
    assert!(
        (max_speed - probe::SEEDED_MAX_SPEED).abs() < 1e-7,
        "{max_speed}"
    );
    assert!(
        a.iter().all(|c| c.point.abs().max_element() <= 10.0
            && c.observer.position.abs().max_element() <= 20.0)
    );
    assert!(a.iter().all(|c| probe::case_scale(c) <= 40.0));
    // Every primary input is an f32 value, so the GPU sees what the CPU sees.
    assert!(
        a.iter()
            .all(|c| c.ray_parameter == f64::from(c.ray_parameter as f32)
                && c.point.to_array().iter().all(|&x| x == f64::from(x as f32)))
    );
    let d = probe::SEEDED_MAX_DOPPLER;
    let s = probe::SEEDED_MAX_SPEED;
    assert!((d * d - (1.0 + s) / (1.0 - s)).abs() < 1e-9);
    assert!((probe::SEEDED_MAX_DOPPLER_SQUARED - (1.0 + s) / (1.0 - s)).abs() < 1e-9);
}

/// Temperatures that exercise every branch of the sampling rule for `lut`: every texel
/// temperature, the geometric midpoints between neighbours, seeded ones from far below to far
/// above the range, and the special values.
fn lut_temperatures(lut: &TemperatureLut) -> Vec<f32> {
    let n = lut.size();
    let mut t: Vec<f32> = (0..n).map(|i| lut.texel_temperature(i) as f32).collect();
    t.extend(
        (1..n).map(|i| (lut.texel_temperature(i - 1) * lut.texel_temperature(i)).sqrt() as f32),
    );
    let (lo, hi) = ((lut.t_min() / 100.0).ln(), (lut.t_max() * 100.0).ln());
    let mut state = 0x1234_5678_u64;
    t.extend((0..8192).map(|_| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let r = (state >> 11) as f64 / (1u64 << 53) as f64;
        (lo + r * (hi - lo)).exp() as f32
    }));
    let (t_min, t_max) = (lut.t_min() as f32, lut.t_max() as f32);
    t.extend([
        0.0,
        -0.0,
        -1.0,
        -f32::MAX,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        f32::MIN_POSITIVE,
        1e-45,
        t_min,
        t_max,
        t_min.next_down(),
        t_min.next_up(),
        t_max.next_down(),
        t_max.next_up(),
    ]);
    t
}

#[test]
fn lut_sample_matches_the_cpu_table() {
    let Some(ctx) = srt_gpu::context_or_skip("lut_sample_matches_the_cpu_table") else {
        return;
    };
    for (tone_map, size) in [
        (ToneMap::Luminance, 4096),
        (ToneMap::Searchlight, 4096),
        (ToneMap::Luminance, 256),
    ] {
        let (t_min, t_max) = TemperatureLut::DEFAULT_RANGE_K;
        let lut = TemperatureLut::build(tone_map, size, t_min, t_max).unwrap();
        let temperatures = lut_temperatures(&lut);
        let gpu = run_lut_probe(&ctx, &lut, &temperatures).unwrap();
        assert_eq!(gpu.len(), temperatures.len());
        let tolerance = lut_tolerance(&lut);
        let (mut worst, mut worst_at) = (0.0f32, 0.0f32);
        for (&t, g) in temperatures.iter().zip(&gpu) {
            let cpu = lut.sample(f64::from(t));
            let error = (0..4).map(|k| (g[k] - cpu[k]).abs()).fold(0.0, f32::max);
            assert!(
                error <= tolerance,
                "{tone_map:?}/{size}: T = {t:e} K: GPU {g:?}, CPU {cpu:?} (error {error:e} > {tolerance:e})"
            );
            if error > worst {
                (worst, worst_at) = (error, t);
            }
        }
        println!(
            "lut_sample {}/{size}: {} temperatures, worst channel error {worst:.2e} at T = {worst_at:e} K \
             ({:.4} texels at the steepest step {:.4}), tolerance {tolerance:.2e} ({:.4} texels)",
            tone_map.name(),
            temperatures.len(),
            f64::from(worst) / f64::from(lut_max_step(&lut)),
            lut_max_step(&lut),
            lut_position_tolerance(&lut),
        );
        // Outside the positive finite numbers the rule gives texel 0, above the range the last.
        let specials = run_lut_probe(
            &ctx,
            &lut,
            &[f32::NAN, -1.0, 0.0, f32::INFINITY, f32::MAX, 1e9],
        )
        .unwrap();
        let last = *lut.texels().last().unwrap();
        assert_eq!(
            specials,
            [
                lut.texels()[0],
                lut.texels()[0],
                lut.texels()[0],
                lut.texels()[0],
                last,
                last
            ]
        );
    }
    ctx.take_errors().unwrap();
}

#[test]
fn spectral_kernels_match_the_cpu() {
    let Some(ctx) = srt_gpu::context_or_skip("spectral_kernels_match_the_cpu") else {
        return;
    };
    let cases = probe::spectral_seeded_cases(0x5eed, 512);
    let results = probe::run_spectral_probe(&ctx, &cases).unwrap();
    let [reflected, emitted] = probe::compare_spectral(&cases, &results);
    println!("spectral: reflected {reflected:?}, emitted {emitted:?}");
    for (what, (worst, case)) in [("reflected", reflected), ("emitted", emitted)] {
        assert!(
            worst <= probe::SPECTRAL_TOLERANCE,
            "{what}: {worst:.3e} at {:?}: GPU {:?}, CPU {:?}",
            cases[case],
            results[case],
            cases[case].reference()
        );
    }
    // The cases are not all black: the comparison is not vacuous.
    let lit = results.iter().filter(|r| r[0].max_element() > 0.1).count();
    assert!(lit > cases.len() / 4, "only {lit} lit cases");
    assert!(probe::run_spectral_probe(&ctx, &[]).unwrap().is_empty());
    ctx.take_errors().unwrap();
}
