//! `cargo xtask bench --compare OLD NEW`: a Markdown before/after table of two saved runs
//! ([`Results`]), matched by case name and size; needs no GPU.

use std::fmt::Write as _;

use super::results::{CaseResult, METHODS, Results, method_name};

/// The frames of `results` that `other` has too (by name and size) and those it lacks.
fn split<'a>(
    results: &'a Results,
    other: &Results,
) -> (Vec<(&'a CaseResult, CaseResult)>, Vec<&'a CaseResult>) {
    let mut matched = Vec::new();
    let mut alone = Vec::new();
    for case in results.all_frames() {
        let twin = other
            .all_frames()
            .find(|o| o.name == case.name && (o.width, o.height) == (case.width, case.height));
        match twin {
            Some(twin) => matched.push((case, twin.clone())),
            None => alone.push(case),
        }
    }
    (matched, alone)
}

/// One line on where a run was made.
fn provenance(label: &str, results: &Results) -> String {
    format!(
        "- {label}: commit {}, {}, {}, {} frames per measurement, timed by {}.\n",
        results.commit, results.date, results.adapter, results.frames, results.timing
    )
}

/// A list of the frames only one run has, or nothing.
fn only_in(label: &str, frames: &[&CaseResult]) -> String {
    if frames.is_empty() {
        return String::new();
    }
    let names: Vec<String> = frames
        .iter()
        .map(|c| format!("{} {}", c.name, c.size()))
        .collect();
    format!("\nOnly in {label}: {}.\n", names.join(", "))
}

/// The comparison in Markdown: where each run was made, then per frame both have (in the old
/// run's order) each method's old and new median ms and new / old, then the frames only one of
/// them has.
#[must_use]
pub fn compare(old: &Results, new: &Results) -> String {
    let mut text = provenance("old", old) + &provenance("new", new);
    if old.adapter != new.adapter {
        text += "\nThe adapters differ: the times are not comparable.\n";
    }
    let (matched, old_only) = split(old, new);
    let (_, new_only) = split(new, old);
    if matched.is_empty() {
        text += "\nNo case is in both files.\n";
    } else {
        text += &table(&matched);
    }
    text + &only_in("old", &old_only) + &only_in("new", &new_only)
}

/// The before/after table of the `matched` frames (old, new).
fn table(matched: &[(&CaseResult, CaseResult)]) -> String {
    let mut text = "\n| scene | size |".to_owned();
    let mut rule = "|---|---|".to_owned();
    for name in METHODS.map(method_name).into_iter().chain(["cpu"]) {
        let _ = write!(text, " {name} old ms | {name} new ms | {name} new / old |");
        rule += "---:|---:|---:|";
    }
    text += &format!("\n{rule}\n");
    for (before, after) in matched {
        let _ = write!(text, "| {} | {} |", before.name, before.size());
        for method in METHODS {
            let (a, b) = (before.measurement.ms(method), after.measurement.ms(method));
            let _ = write!(text, " {a:.2} | {b:.2} | {:.2} |", b / a);
        }
        // The CPU reference's frame, where both runs timed it.
        match (before.cpu_ms, after.cpu_ms) {
            (Some(a), Some(b)) => {
                let _ = write!(text, " {a:.2} | {b:.2} | {:.2} |", b / a);
            }
            _ => text += " — | — | — |",
        }
        text.push('\n');
    }
    text
}

#[cfg(test)]
mod tests {
    use super::{compare, split};
    use crate::bench::results::tests::{case, measurement, results};

    /// The test results changed: the cube 20 % slower, the spider at 1920×1080 instead, the
    /// sweep the same.
    fn newer() -> crate::bench::results::Results {
        let mut new = results();
        new.commit = "def".to_owned();
        new.cases = vec![
            case("cube", measurement(12.0, 11.0, 10.0, 1.0)),
            crate::bench::results::CaseResult {
                width: 1920,
                height: 1080,
                ..case("spider", measurement(15.0, 15.0, 10.0, 1.0))
            },
        ];
        new
    }

    #[test]
    fn frames_match_by_name_and_size() {
        let (old, new) = (results(), newer());
        let (matched, old_only) = split(&old, &new);
        let names: Vec<&str> = matched.iter().map(|(c, _)| c.name.as_str()).collect();
        assert_eq!(names, ["cube", "fly@ct=0", "fly@ct=6"]);
        assert_eq!(old_only.len(), 1);
        assert_eq!(
            (old_only[0].name.as_str(), old_only[0].width),
            ("spider", 1280)
        );
    }

    #[test]
    fn the_table_shows_old_new_and_their_ratio() {
        let text = compare(&results(), &newer());
        assert!(text.contains("- old: commit abc, 2026-01-01, test adapter, 3 frames"));
        assert!(text.contains("- new: commit def,"));
        assert!(text.contains(
            "| scene | size | auto old ms | auto new ms | auto new / old | LRT old ms |"
        ));
        assert!(text.contains(
            "| cube | 1280×720 | 10.00 | 12.00 | 1.20 | 11.00 | 11.00 | 1.00 | 22.00 | 22.00 | 1.00 | 10.00 | 10.00 | 1.00 |"
        ));
        assert!(text.contains("| fly@ct=6 | 1280×720 | 25.00 | 25.00 | 1.00 |"));
        assert!(text.contains("Only in old: spider 1280×720."));
        assert!(text.contains("Only in new: spider 1920×1080."));
        assert!(!text.contains("adapters differ"));
    }

    #[test]
    fn runs_without_common_cases_say_so() {
        let mut other = newer();
        other.adapter = "another adapter".to_owned();
        other.cases.clear();
        other.sweeps.clear();
        let text = compare(&results(), &other);
        assert!(text.contains("The adapters differ"));
        assert!(text.contains("No case is in both files."));
        assert!(!text.contains("| scene |"));
    }
}
