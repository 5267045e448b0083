//! The generated blocks of `docs/performance.md` — the table and the summary sentences — made
//! from a run's [`Results`], and whether each line's frames were validated
//! (`cargo xtask validate --bench-frames`).

use std::path::Path;

use anyhow::Context as _;
use srt_gpu::Method;

use super::report::{Markers, Report};
use super::results::{CaseResult, FullSkyResult, METHODS, Results, SweepResult};
use super::summary::summary;

/// The document the bench updates, relative to the workspace.
pub const DOCUMENT: &str = "docs/performance.md";

/// Where `validate --bench-frames` records its verdicts (relative to the workspace), which the
/// document quotes: a header line `# commit=HASH date=YYYY-MM-DD`, then one line per frame,
/// `NAME<TAB>WxH<TAB>pass|FAIL`. Here, below validate, since validate times the bench's frames.
pub const BENCH_FRAMES_RECORD: &str = "target/validate/bench-frames.tsv";

/// What the last `cargo xtask validate --bench-frames` recorded
/// ([`BENCH_FRAMES_RECORD`]) and the commit the bench measures.
pub struct Validation {
    /// The commit and date the record was made at, if there is a record.
    made: Option<(String, String)>,
    /// Each recorded frame: name, `WxH`, whether it passed.
    frames: Vec<(String, String, bool)>,
    /// The commit being measured.
    commit: String,
}

impl Validation {
    /// Reads the record, if any.
    pub fn read(workspace: &Path) -> Self {
        let text = std::fs::read_to_string(workspace.join(BENCH_FRAMES_RECORD)).unwrap_or_default();
        Self::parse(&text, crate::provenance::commit(workspace))
    }

    /// The record `text` (a `# commit=… date=…` header, then `name\tWxH\tpass|fail` lines),
    /// judged for `commit`.
    fn parse(text: &str, commit: String) -> Self {
        let mut lines = text.lines();
        let made = lines.next().and_then(|header| {
            let header = header.strip_prefix("# commit=")?;
            let (commit, date) = header.split_once(" date=")?;
            Some((commit.to_owned(), date.to_owned()))
        });
        let frames = lines
            .filter_map(|line| {
                let mut fields = line.split('\t');
                Some((
                    fields.next()?.to_owned(),
                    fields.next()?.to_owned(),
                    fields.next()? == "pass",
                ))
            })
            .collect();
        Self {
            made,
            frames,
            commit,
        }
    }

    /// The table cell for a line timing `frames`: validated (and when) only if every frame
    /// passed in a record made at the commit being measured.
    fn cell<'a>(&self, frames: impl IntoIterator<Item = (&'a str, u32, u32)>) -> String {
        let Some((commit, date)) = &self.made else {
            return "no (run `cargo xtask validate --bench-frames`)".to_owned();
        };
        if *commit != self.commit || commit.ends_with("-dirty") {
            return format!("no (the record is of {commit})");
        }
        let (mut passed, mut total) = (0, 0);
        for (name, width, height) in frames {
            let size = format!("{width}x{height}");
            total += 1;
            passed += usize::from(
                self.frames
                    .iter()
                    .any(|(n, s, pass)| n == name && *s == size && *pass),
            );
        }
        if passed == total {
            format!("yes, {date} ({commit})")
        } else {
            format!("no: {passed} of {total} frames passed")
        }
    }
}

/// A static case's row, without its last cell (the validation's).
fn case_row(case: &CaseResult) -> String {
    let m = &case.measurement;
    format!(
        "| {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} | **{:.2}** | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
        case.name,
        case.size(),
        case.triangles,
        m.auto_ms,
        m.lrt_ms,
        m.rt_ms,
        m.polygon_ms,
        m.image_based_ms
            .map_or_else(|| "—".to_owned(), |ms| format!("{ms:.2}")),
        m.ratio(),
        m.ratio_of(Method::Lrt),
        m.ratio_of(Method::Rt),
        m.shaded_per_pixel,
        m.overdraw_auto,
        m.overdraw_hull,
        m.overdraw_rt
    )
}

/// A sweep's row (each method's slowest frame and worst ratio), without its last cell.
fn sweep_row(sweep: &SweepResult) -> Option<String> {
    let first = &sweep.frames.first()?.case;
    let slowest: Vec<String> = METHODS[..3]
        .iter()
        .map(|&method| format!("≤ {:.2}", sweep.slowest(method)))
        .collect();
    let worst: Vec<String> = METHODS[..3]
        .iter()
        .map(|&method| format!("worst {:.2}", sweep.worst_ratio_of(method)))
        .collect();
    Some(format!(
        "| {} (sweep, {} frames) | {} | {} | {} | | | {} | | | | |",
        sweep.name,
        sweep.frames.len(),
        first.size(),
        first.triangles,
        slowest.join(" | "),
        worst.join(" | "),
    ))
}

/// A full-sky line's row, without its last cell: LRT and the polygon method draw through the
/// pinhole only, so their cells and the ratios are empty; the CPU reference's time is named.
fn full_sky_row(line: &FullSkyResult) -> String {
    format!(
        "| {} (full sky; CPU {:.0} ms) | {}×{} | {} | {:.2} | — | {:.2} | — | — | — | — | — | {:.2} | {:.2} | — | {:.2} |",
        line.name,
        line.cpu_ms,
        line.width,
        line.height,
        line.triangles,
        line.auto_ms,
        line.rt_ms,
        line.shaded_per_pixel,
        line.overdraw_rt,
        line.overdraw_rt
    )
}

/// The table block between `markers`.
fn table(results: &Results, validation: &Validation, markers: Markers) -> String {
    let mut table = format!(
        "{}\nAdapter: {}; {}, timed by {}.\n\n\
         | scene | size | triangles | auto ms | LRT ms | RT ms | polygon ms | IB ms | **auto / polygon** | LRT / polygon | RT / polygon | shaded per covered pixel | auto fragments per covered pixel | LRT fragments | RT fragments | frames validated |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
        markers.start,
        results.adapter,
        results.sampling(),
        results.timing
    );
    for case in &results.cases {
        table += &format!("{} {} |\n", case_row(case), validation.cell([case.frame()]));
    }
    for sweep in &results.sweeps {
        if let Some(row) = sweep_row(sweep) {
            let frames = sweep.frames.iter().map(|f| f.case.frame());
            table += &format!("{row} {} |\n", validation.cell(frames));
        }
    }
    for line in &results.full_sky {
        let frame = [(line.name.as_str(), line.width, line.height)];
        table += &format!("{} {} |\n", full_sky_row(line), validation.cell(frame));
    }
    table + markers.end
}

/// `text` with the block between `markers` (included) replaced by `block`, or with
/// `block` appended where the markers are missing.
pub(super) fn replace_block(text: &str, markers: Markers, block: &str) -> String {
    match (text.find(markers.start), text.find(markers.end)) {
        (Some(a), Some(b)) if a < b => {
            format!("{}{block}{}", &text[..a], &text[b + markers.end.len()..])
        }
        _ => format!("{text}\n{block}\n"),
    }
}

/// The document `text` with `report`'s generated blocks (table and summary) rewritten from
/// `results`.
#[must_use]
pub fn update(text: &str, results: &Results, validation: &Validation, report: Report) -> String {
    let summary = format!(
        "{}\n{}{}",
        report.summary.start,
        summary(results),
        report.summary.end
    );
    let text = replace_block(text, report.summary, &summary);
    replace_block(
        &text,
        report.table,
        &table(results, validation, report.table),
    )
}

/// Rewrites `report`'s generated blocks of [`DOCUMENT`] and saves the results as its
/// results file.
///
/// # Errors
/// An unreadable or unwritable file.
pub fn write(workspace: &Path, results: &Results, report: Report) -> anyhow::Result<()> {
    let doc = workspace.join(DOCUMENT);
    let text =
        std::fs::read_to_string(&doc).with_context(|| format!("cannot read {}", doc.display()))?;
    let updated = update(&text, results, &Validation::read(workspace), report);
    std::fs::write(&doc, updated).with_context(|| format!("cannot write {}", doc.display()))?;
    println!("updated {}", doc.display());
    let json = workspace.join(report.results);
    results.save(&json)?;
    println!("wrote {}", json.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{Validation, update};
    use crate::bench::report::{HARDWARE, SOFTWARE};
    use crate::bench::results::tests::results;

    /// A document with both software blocks holding stale text between hand-written prose.
    fn document() -> String {
        let (summary, table) = (SOFTWARE.summary, SOFTWARE.table);
        format!(
            "# Performance\n\nProse.\n\n{}\nstale summary\n{}\n\nMore prose.\n\n{}\nstale table\n{}\n\nEnd.\n",
            summary.start, summary.end, table.start, table.end
        )
    }

    #[test]
    fn both_blocks_are_rewritten_and_the_prose_kept() {
        let validation = Validation::parse(
            "# commit=abc date=2026-01-01\ncube\t1280x720\tpass\nspider\t1280x720\tfail\nfly@ct=0\t1280x720\tpass\nfly@ct=6\t1280x720\tpass\n",
            "abc".to_owned(),
        );
        let text = update(&document(), &results(), &validation, SOFTWARE);
        assert!(!text.contains("stale"));
        for kept in [
            "Prose.",
            "More prose.",
            "End.",
            SOFTWARE.summary.end,
            SOFTWARE.table.end,
        ] {
            assert_eq!(text.matches(kept).count(), 1, "{kept}");
        }
        assert!(text.contains("every sweep frame: missed** at spider 1280×720 (1.50)"));
        assert!(text.contains(
            "| cube | 1280×720 | 300 | 10.00 | 11.00 | 22.00 | 10.00 | 5.00 | **1.00** |"
        ));
        assert!(text.contains("| 1.50 | 1.50 | 1.20 | yes, 2026-01-01 (abc) |"));
        assert!(text.contains("| 1.50 | 1.50 | 1.20 | no: 0 of 1 frames passed |"));
        assert!(text.contains(
            "| fly (sweep, 2 frames) | 1280×720 | 300 | ≤ 25.00 | ≤ 20.00 | ≤ 40.00 | | | worst 2.50 | worst 2.00 | worst 4.00 | | | | | yes, 2026-01-01 (abc) |"
        ));
        assert!(text.contains(
            "| sky (full sky; CPU 90 ms) | 2048×1024 | 300 | 40.00 | — | 40.00 | — | — | — | — | — | 1.00 | 1.50 | — | 1.50 | no: 0 of 1 frames passed |"
        ));
        assert_eq!(update(&text, &results(), &validation, SOFTWARE), text);
    }

    /// A hardware GPU's run adds its own blocks and leaves the software run's as they were.
    #[test]
    fn a_hardware_run_keeps_the_software_blocks() {
        let validation = Validation::parse("", "abc".to_owned());
        let text = update(&document(), &results(), &validation, HARDWARE);
        assert!(text.starts_with(&document()));
        assert!(text.contains(HARDWARE.summary.start) && text.contains(HARDWARE.table.end));
        let again = update(&text, &results(), &validation, HARDWARE);
        assert_eq!(again, text);
    }

    #[test]
    fn missing_blocks_are_appended() {
        let validation = Validation::parse("", "abc".to_owned());
        let text = update("# Performance\n", &results(), &validation, SOFTWARE);
        assert!(text.starts_with("# Performance\n"));
        assert!(text.contains(SOFTWARE.summary.start) && text.contains(SOFTWARE.table.start));
        assert!(text.contains("no (run `cargo xtask validate --bench-frames`)"));
    }
}
