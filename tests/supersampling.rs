//! The GPU's supersampled picture is the CPU reference's where it matters most for a sky: a
//! star lights every sample of the output pixels around it on both, so that a bright star
//! clamps the same way (the GPU used to put a star's whole light, times the samples, into one
//! target pixel, which clamped it to a fraction of its brightness: 2.6 % of the flythrough's
//! pixels 8 steps dimmer at 25 samples).

use std::sync::atomic::AtomicBool;

use crate::common::builtin_scene;
use srt::engine::{Backend, Engine, Frame};
use srt::software::Job;
use srt_gpu::Method;
use srt_trace::{Output, RenderSettings, Tracer};

#[test]
fn supersampled_stars_are_as_bright_on_the_gpu_as_on_the_cpu() {
    if srt_gpu::context_or_skip("supersampled_stars_are_as_bright_on_the_gpu_as_on_the_cpu")
        .is_none()
    {
        return;
    }
    let scene = builtin_scene("flythrough");
    for samples in [4, 25] {
        let settings = RenderSettings {
            width: 700,
            height: 60,
            samples,
        };
        let frame = Frame::new(&scene);
        let mut gpu = Engine::choose(Backend::Gpu, Method::Auto, &Job::still(settings), &frame)
            .unwrap()
            .engine;
        let never = AtomicBool::new(false);
        let drawn = gpu
            .render(&frame, settings, Output::Display, &|_| {}, &never)
            .unwrap()
            .unwrap();
        let reference = Tracer::new(&scene).render(settings, &|_| {});
        let steps = |a: f64, b: f64| ((a - b).abs() * 255.0).round();
        let far_off = (drawn.iter().zip(&reference.pixels))
            .filter(|(g, c)| (0..3).any(|k| steps(g[k], c[k]) > 8.0))
            .count();
        // The rest are silhouettes, sampled on a grid here and spread on the CPU.
        assert!(
            far_off * 100 < drawn.len(),
            "{samples} samples: {far_off} of {} pixels differ by more than 8 steps",
            drawn.len()
        );
    }
}
