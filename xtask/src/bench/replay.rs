//! Recorded bench lines replayed through `auto`'s rule ([`srt_gpu::auto`]): for every line
//! whose objects' loads were recorded, the method the rule expects faster for the whole frame
//! (each method's costs summed over the objects) against the faster of LRT and RT as measured.
//! Its test holds the rule to the H200's lines (docs/measurements/2026-11-29-auto, the
//! hardware constants) and to lavapipe's, both those the constants were fitted to and the
//! committed docs/performance-results.json.

use srt_gpu::Method;
use srt_gpu::auto::{MethodCosts, ObjectLoad};

use super::results::{CaseResult, Results};

/// One line replayed: which method the rule expects faster, and the measured times.
#[derive(Debug, Clone, PartialEq)]
pub struct Replayed {
    /// The line's name and size, as the bench prints them.
    pub line: String,
    /// [`Method::Lrt`] or [`Method::Rt`].
    pub expected_faster: Method,
    /// The expected method's measured time over the faster one's (1: the right pick).
    pub over_faster: f64,
}

/// The costs of the adapter `results` were measured on: a CPU adapter's where its summary
/// names the device type `Cpu`, a hardware GPU's otherwise.
#[must_use]
pub fn costs_of(results: &Results) -> MethodCosts {
    let device_type = if results.adapter.contains(", Cpu,") {
        wgpu::DeviceType::Cpu
    } else {
        wgpu::DeviceType::DiscreteGpu
    };
    MethodCosts::for_adapter(device_type)
}

/// The line `case` replayed through `costs`, or `None` where it has no recorded loads.
#[must_use]
pub fn replay_line(case: &CaseResult, costs: &MethodCosts) -> Option<Replayed> {
    if case.objects.is_empty() {
        return None;
    }
    let loads: Vec<ObjectLoad> = case.objects.iter().map(|&o| o.into()).collect();
    let lrt: f64 = loads.iter().map(|l| costs.lrt(l)).sum();
    let rt: f64 = loads.iter().map(|l| costs.rt(l)).sum();
    let m = &case.measurement;
    let (expected_faster, ms) = if rt < lrt {
        (Method::Rt, m.rt_ms)
    } else {
        (Method::Lrt, m.lrt_ms)
    };
    Some(Replayed {
        line: format!("{} {}", case.name, case.size()),
        expected_faster,
        over_faster: ms / m.lrt_ms.min(m.rt_ms),
    })
}

/// Every line of `results` with recorded loads, replayed through `costs`.
#[must_use]
pub fn replay(results: &Results, costs: &MethodCosts) -> Vec<Replayed> {
    results
        .all_frames()
        .filter_map(|case| replay_line(case, costs))
        .collect()
}

/// One paragraph on how `auto`'s rule fares on `results`: on how many of its lines it expects
/// the faster of LRT and RT within 5 %, and the lines it does not (then the adapter's constants
/// want refitting: docs/measurements/2026-11-29-auto/fit.py).
#[must_use]
pub fn summary(results: &Results) -> String {
    let replayed = replay(results, &costs_of(results));
    let missed: Vec<String> = replayed
        .iter()
        .filter(|r| r.over_faster > TIE)
        .map(|r| format!("{} ({:.2} of the faster)", r.line, r.over_faster))
        .collect();
    let mut text = format!(
        "auto's rule expects the faster of LRT and RT (within 5 %) on {} of {} lines",
        replayed.len() - missed.len(),
        replayed.len()
    );
    if !missed.is_empty() {
        text += &format!(
            "; not on {}: refit the adapter's costs (docs/measurements/2026-11-29-auto/fit.py)",
            missed.join(", ")
        );
    }
    text
}

/// How much slower than the faster method the expected one may be: the 5 %.
const TIE: f64 = 1.05;

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::{Replayed, TIE, costs_of, replay, summary};
    use crate::bench::results::Results;
    use srt_gpu::Method;
    use srt_gpu::auto::{CPU_ADAPTER_COSTS, HARDWARE_COSTS};

    /// How far the one line no constants fit (teaser@ct=−16.36, measured at 1.055 and 1.060 of
    /// the faster on lavapipe, 1.08 on llvmpipe GL) may miss before the test calls it worse
    /// than recorded.
    const UNFITTED: f64 = 1.10;

    fn load(relative: &str) -> Results {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("..")
            .join(relative);
        Results::load(&path).unwrap()
    }

    /// The lines expected wrong by more than [`TIE`].
    fn missed(replayed: &[Replayed]) -> Vec<&Replayed> {
        replayed.iter().filter(|r| r.over_faster > TIE).collect()
    }

    /// Every recorded line of the H200 with loads (83, its sweeps included) goes to the faster
    /// method within 5 %, and every line of lavapipe's but the one no constants of this form
    /// fit (76 lines, teaser@ct=−16.36 at 1.055: RT faster by 5.5 % on a 23 ms frame, and at
    /// 1.060 again in the committed bench, measured with the rule in place), and every line but
    /// that one of llvmpipe GL's 58, measured afterwards with the rule in place; the
    /// rule chooses each method somewhere (not one answer for all), and each adapter's costs
    /// miss lines of the other's, so the test tells the constants apart.
    #[test]
    fn the_rule_picks_the_faster_method_on_every_recorded_line() {
        let measured = [
            ("h200-2026-11-27-run1.json", 26, &[][..]),
            ("h200-2026-11-27-run2.json", 2, &[]),
            ("h200-2026-11-27-run3.json", 55, &[]),
            (
                "lavapipe-2026-11-29.json",
                76,
                &["teaser@ct=-16.363636363636363 1280×720"],
            ),
            // Out of sample: llvmpipe through OpenGL, its bench's engine, cube, teaser and
            // flythrough lines measured with the rule in place.
            (
                "llvmpipe-gl-2026-11-29.json",
                58,
                &["teaser@ct=-16.363636363636363 1280×720"],
            ),
        ];
        for (file, lines, unfitted) in measured {
            let results = load(&format!("docs/measurements/2026-11-29-auto/{file}"));
            let replayed = replay(&results, &costs_of(&results));
            assert_eq!(replayed.len(), lines, "{file}");
            let missed = missed(&replayed);
            let names: Vec<&str> = missed.iter().map(|r| r.line.as_str()).collect();
            assert_eq!(names, unfitted, "{file}: {missed:#?}");
            assert!(
                missed.iter().all(|r| r.over_faster < UNFITTED),
                "{missed:#?}"
            );
            if lines > 2 {
                for method in [Method::Lrt, Method::Rt] {
                    assert!(
                        replayed.iter().any(|r| r.expected_faster == method),
                        "{file}"
                    );
                }
            }
        }
        // The committed bench (lavapipe's, recorded with the loads): the same line again.
        let committed = load("docs/performance-results.json");
        let replayed = replay(&committed, &costs_of(&committed));
        assert!(replayed.len() >= 70, "{} lines with loads", replayed.len());
        let committed_misses = missed(&replayed);
        assert!(
            committed_misses
                .iter()
                .all(|r| r.line.starts_with("teaser@ct=-16.36") && r.over_faster < UNFITTED),
            "{committed_misses:#?}"
        );
        let h200 = load("docs/measurements/2026-11-29-auto/h200-2026-11-27-run1.json");
        assert!(!missed(&replay(&h200, &CPU_ADAPTER_COSTS)).is_empty());
        assert!(
            summary(&h200).ends_with("on 26 of 26 lines"),
            "{}",
            summary(&h200)
        );
        let lavapipe = load("docs/measurements/2026-11-29-auto/lavapipe-2026-11-29.json");
        assert!(!missed(&replay(&lavapipe, &HARDWARE_COSTS)).is_empty());
    }
}
