//! The summary sentences of a run, written into `docs/performance.md` beside the table: per
//! size the range of auto / polygon, per sweep its worst and median frame, whether the goals
//! are met, and the noise of the machine (auto against LRT where both run the same code).

use std::fmt::Write as _;

use super::results::{CaseResult, Results, SweepResult, median};

/// The goal for exact (`auto`) / polygon, every line and every sweep frame: the exact image no
/// slower than the approximate one.
pub const RATIO_GOAL: f64 = 1.0;
/// The goal for pixels shaded per covered pixel.
pub const SHADED_GOAL: f64 = 1.2;

/// `ct` with at most two decimals and no trailing zeros (`-20`, `6`, `-16.36`).
#[must_use]
pub fn short(ct: f64) -> String {
    let text = format!("{ct:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" { "0" } else { text }.to_owned()
}

/// A case as the summary names it: `NAME W×H`.
fn label(case: &CaseResult) -> String {
    format!("{} {}", case.name, case.size())
}

/// The summary in Markdown: one line on the run, then a list.
#[must_use]
pub fn summary(results: &Results) -> String {
    let machine = &results.machine;
    let mut text = format!(
        "Run of {} at commit {} on {} ({}); {}, timed by {}.\n\n",
        results.date,
        results.commit,
        results.adapter,
        machine.describe(),
        results.sampling(),
        results.timing
    );
    let items = size_items(results)
        .into_iter()
        .chain(results.sweeps.iter().filter_map(sweep_item))
        .chain([
            goal_item(
                &format!("auto / polygon ≤ {RATIO_GOAL}, every line and every sweep frame"),
                results,
                |c| c.measurement.ratio(),
                RATIO_GOAL,
            ),
            goal_item(
                &format!("pixels shaded per covered pixel ≤ {SHADED_GOAL}"),
                results,
                |c| c.measurement.shaded_per_pixel,
                SHADED_GOAL,
            ),
            noise_item(results),
        ]);
    for item in items {
        let _ = writeln!(text, "- {item}");
    }
    text
}

/// Per image size of the static cases: the range of auto / polygon and the worst line.
fn size_items(results: &Results) -> Vec<String> {
    let mut sizes: Vec<(u32, u32)> = Vec::new();
    for case in &results.cases {
        if !sizes.contains(&(case.width, case.height)) {
            sizes.push((case.width, case.height));
        }
    }
    sizes
        .into_iter()
        .filter_map(|(width, height)| {
            let cases: Vec<&CaseResult> = results
                .cases
                .iter()
                .filter(|c| (c.width, c.height) == (width, height))
                .collect();
            let by_ratio = |a: &&&CaseResult, b: &&&CaseResult| {
                a.measurement.ratio().total_cmp(&b.measurement.ratio())
            };
            let best = cases.iter().min_by(by_ratio)?;
            let worst = cases.iter().max_by(by_ratio)?;
            Some(format!(
                "**Static scenes at {width}×{height}**: auto / polygon {:.2}–{:.2} over {} scenes; worst {} ({:.2}).",
                best.measurement.ratio(),
                worst.measurement.ratio(),
                cases.len(),
                worst.name,
                worst.measurement.ratio()
            ))
        })
        .collect()
}

/// A sweep's worst frame (its ct and ratio) and median ratio.
fn sweep_item(sweep: &SweepResult) -> Option<String> {
    let worst = sweep.worst_frame()?;
    Some(format!(
        "**Sweep {}** ({} frames, {}): worst frame at ct = {} (auto / polygon {:.2}), median {:.2}.",
        sweep.name,
        sweep.frames.len(),
        worst.case.size(),
        short(worst.ct),
        worst.case.measurement.ratio(),
        sweep.median_ratio()
    ))
}

/// Whether `value` stays at or below `limit` on every measured frame: "met" with the highest
/// value, or "missed at" each frame above it.
fn goal_item(
    goal: &str,
    results: &Results,
    value: impl Fn(&CaseResult) -> f64,
    limit: f64,
) -> String {
    let missed: Vec<String> = results
        .all_frames()
        .filter(|c| value(c) > limit)
        .map(|c| format!("{} ({:.2})", label(c), value(c)))
        .collect();
    if !missed.is_empty() {
        return format!("**Goal {goal}: missed** at {}.", missed.join(", "));
    }
    match results
        .all_frames()
        .max_by(|a, b| value(a).total_cmp(&value(b)))
    {
        Some(highest) => format!(
            "**Goal {goal}: met** (highest {:.2}, {}).",
            value(highest),
            label(highest)
        ),
        None => format!("**Goal {goal}:** nothing measured."),
    }
}

/// auto against LRT on the frames where `auto` traces no object, so that both run the same
/// code: the difference is the noise of the machine's timing.
fn noise_item(results: &Results) -> String {
    let same_code: Vec<(&CaseResult, f64)> = results
        .all_frames()
        .filter(|c| c.traced_objects == 0)
        .map(|c| (c, c.measurement.auto_ms / c.measurement.lrt_ms - 1.0))
        .collect();
    let Some((largest, difference)) = same_code
        .iter()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
    else {
        return "**Noise**: every frame traces an object, so auto and LRT never run the same code."
            .to_owned();
    };
    let typical = median(same_code.iter().map(|(_, d)| d.abs()).collect());
    format!(
        "**Noise** (where `auto` traces no object it runs the same code as LRT, so their difference is the machine's noise): up to {:.0} % ({}: auto {:.2} ms, LRT {:.2} ms), median {:.0} % over {} frames.",
        100.0 * difference.abs(),
        label(largest),
        largest.measurement.auto_ms,
        largest.measurement.lrt_ms,
        100.0 * typical,
        same_code.len()
    )
}

#[cfg(test)]
mod tests {
    use super::{short, summary};
    use crate::bench::results::tests::results;

    #[test]
    fn times_are_short() {
        assert_eq!(short(-20.0), "-20");
        assert_eq!(short(6.0), "6");
        assert_eq!(short(-16.363_636), "-16.36");
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(-0.001), "0");
    }

    #[test]
    fn summary_states_ranges_sweeps_goals_and_noise() {
        let text = summary(&results());
        assert!(text.contains(
            "at 1280×720**: auto / polygon 1.00–1.50 over 2 scenes; worst spider (1.50)"
        ));
        assert!(text.contains("**Sweep fly** (2 frames, 1280×720): worst frame at ct = 6 (auto / polygon 2.50), median 2.50"));
        assert!(text.contains(
            "every sweep frame: missed** at spider 1280×720 (1.50), fly@ct=0 1280×720 (1.20), \
             fly@ct=6 1280×720 (2.50)."
        ));
        assert!(text.contains("per covered pixel ≤ 1.2: met** (highest 1.00"));
        assert!(text.contains("up to 25 % (fly@ct=6 1280×720: auto 25.00 ms, LRT 20.00 ms)"));
    }

    #[test]
    fn summary_says_met_when_every_ratio_is_below_the_goal() {
        let mut results = results();
        results.sweeps.clear();
        results.cases[1].measurement.auto_ms = 9.0;
        let text = summary(&results);
        assert!(text.contains("every sweep frame: met** (highest 1.00, cube 1280×720)."));
    }
}
