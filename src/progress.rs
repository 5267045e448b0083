//! Progress bars on standard error that stay hidden for the first second, so short jobs print
//! nothing but their result.

use std::io::Write as _;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a job runs before its bar appears.
const HIDDEN_SECONDS: f64 = 1.0;

/// A progress bar counting `unit`s of one job, drawn once the job has run a second.
pub struct DelayedBar {
    bar: ProgressBar,
    start: Instant,
    shown: AtomicBool,
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
        }
    }

    /// Sets how many units are done (callable from any thread).
    pub fn set_position(&self, done: u64) {
        if self.start.elapsed().as_secs_f64() > HIDDEN_SECONDS
            && !self.shown.swap(true, Ordering::Relaxed)
        {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        self.bar.set_position(done);
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
