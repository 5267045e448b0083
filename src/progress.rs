//! Progress bars on standard error that stay hidden for the first second, so short jobs print
//! nothing but their result. Where standard error is not a terminal (a log file, a cluster job's
//! output) a bar would be hidden or garble the file: there the progress is a plain line every
//! [`LINE_SECONDS`] instead.

use std::io::{IsTerminal as _, Write as _};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a job runs before its bar appears.
const HIDDEN_SECONDS: f64 = 1.0;

/// Seconds between two progress lines where standard error is not a terminal: a modest rate
/// for a log (a day's render writes under 9 000 lines).
const LINE_SECONDS: f64 = 10.0;

/// Whether a progress line is due at `now` seconds into the job, the last one printed at
/// `last` (`None`: none yet): after the first [`HIDDEN_SECONDS`], then every [`LINE_SECONDS`].
fn line_due(last: Option<f64>, now: f64) -> bool {
    now > HIDDEN_SECONDS && last.is_none_or(|last| now - last >= LINE_SECONDS)
}

/// A progress line: "rendering fig7: 120/720 rows (16 %), 12 s".
fn progress_line(message: &str, done: u64, len: u64, unit: &str, seconds: f64) -> String {
    let percent = (done * 100).checked_div(len).unwrap_or(100);
    format!("{message}: {done}/{len} {unit} ({percent} %), {seconds:.0} s")
}

/// A progress bar counting `unit`s of one job, drawn once the job has run a second; or, where
/// standard error is not a terminal, a line every [`LINE_SECONDS`].
pub struct DelayedBar {
    bar: ProgressBar,
    start: Instant,
    shown: AtomicBool,
    /// The unit counted, for the lines.
    unit: String,
    /// Where standard error is not a terminal: when the last line was printed (seconds into
    /// the job; `None` before the first). `None` for a terminal, which gets the bar.
    lines: Option<Mutex<Option<f64>>>,
}

impl DelayedBar {
    /// A bar for `len` `unit`s (e.g. "rows", "frames") of the job `message` names.
    ///
    /// # Panics
    /// Never: the template is fixed and valid.
    #[must_use]
    pub fn new(len: u64, unit: &str, message: String) -> Self {
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
        bar.set_style(
            ProgressStyle::with_template(&format!(
                "{{spinner}} {{msg}} [{{bar:40}}] {{pos}}/{{len}} {unit}, {{eta}} left"
            ))
            .expect("valid progress template")
            .progress_chars("=> "),
        );
        bar.set_message(message);
        Self {
            bar,
            start: Instant::now(),
            shown: AtomicBool::new(false),
            unit: unit.to_owned(),
            lines: (!std::io::stderr().is_terminal()).then(|| Mutex::new(None)),
        }
    }

    /// Sets how many units are done (callable from any thread).
    pub fn set_position(&self, done: u64) {
        self.bar.set_position(done);
        let seconds = self.start.elapsed().as_secs_f64();
        let Some(lines) = &self.lines else {
            if seconds > HIDDEN_SECONDS && !self.shown.swap(true, Ordering::Relaxed) {
                self.bar.set_draw_target(ProgressDrawTarget::stderr());
            }
            return;
        };
        let Ok(mut last) = lines.try_lock() else {
            // Another thread is printing this moment's line.
            return;
        };
        if line_due(*last, seconds) {
            *last = Some(seconds);
            let len = self.bar.length().unwrap_or(done);
            let line = progress_line(&self.bar.message(), done, len, &self.unit, seconds);
            let _ = writeln!(std::io::stderr().lock(), "{line}");
        }
    }

    /// Counts one more unit done.
    pub fn inc(&self) {
        self.set_position(self.bar.position() + 1);
    }

    /// Prints `line` to standard output without garbling the bar. A closed standard output
    /// (`srt render … | head -1`) is not an error: the frames are still written.
    pub fn println(&self, line: &str) {
        self.bar.suspend(|| {
            let _ = writeln!(std::io::stdout().lock(), "{line}");
        });
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No line in the first second (a short job prints nothing but its result), the first after
    /// it, then one every ten seconds, whatever the updates in between.
    #[test]
    fn lines_come_after_the_first_second_then_every_ten() {
        assert!(!line_due(None, 0.5));
        assert!(!line_due(None, HIDDEN_SECONDS));
        assert!(line_due(None, 1.2));
        assert!(!line_due(Some(1.2), 5.0));
        assert!(!line_due(Some(1.2), 11.1));
        assert!(line_due(Some(1.2), 11.2));
        let printed: Vec<f64> = (0..=600)
            .map(|tenth| f64::from(tenth) * 0.1)
            .scan(None, |last: &mut Option<f64>, now| {
                let due = line_due(*last, now);
                if due {
                    *last = Some(now);
                }
                Some(due.then_some(now))
            })
            .flatten()
            .collect();
        assert_eq!(printed.len(), 6, "{printed:?}");
    }

    /// A line says the job, how far it is and how long it has run.
    #[test]
    fn a_line_says_the_job_its_share_done_and_its_time() {
        assert_eq!(
            progress_line("rendering fig7", 180, 720, "rows", 12.4),
            "rendering fig7: 180/720 rows (25 %), 12 s"
        );
        assert_eq!(
            progress_line("encoding", 0, 0, "frames", 1.0),
            "encoding: 0/0 frames (100 %), 1 s"
        );
    }
}
