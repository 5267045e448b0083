//! Where a frame of the viewer goes (`SRT_VIEW_STATS=1`): once a second, the frames drawn and,
//! per frame on average, the time between frames split into rendering the picture (encoding
//! and the GPU's work, waited for), the rest of [`super::ViewerApp::show`] (input, the scene's
//! time step, the panel's layout) and what is outside it (egui's tessellation and painting of
//! the window, presenting it, and any wait for the next event).

use std::time::{Duration, Instant};

/// Sums over the frames of the current second.
#[derive(Debug, Default)]
pub(super) struct FrameStats {
    /// When the current second's first frame started.
    since: Option<Instant>,
    /// When the last frame's `show` started.
    last_start: Option<Instant>,
    /// Frames whose interval is counted (each from its start to the next frame's).
    frames: u32,
    /// Sum of those frames' intervals.
    interval: Duration,
    /// Sum of their `show` time.
    show: Duration,
    /// Sum of their rendering time (within `show`).
    render: Duration,
    /// Frames that rendered the picture.
    rendered: u32,
    /// `show` of the frame in progress: its start and its rendering time so far.
    current: Option<(Instant, Duration)>,
}

/// One second's averages, milliseconds per frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct FrameSplit {
    /// Frames counted.
    pub(super) frames: u32,
    /// Frames that rendered the picture.
    pub(super) rendered: u32,
    /// From one frame's start to the next's.
    pub(super) interval_ms: f64,
    /// Rendering the picture.
    pub(super) render_ms: f64,
    /// The rest of `show`: input, the scene's step, the panel.
    pub(super) ui_ms: f64,
    /// Outside `show`: egui's painting, presenting, waiting.
    pub(super) outside_ms: f64,
}

impl FrameStats {
    /// A frame's `show` starts at `now`.
    pub(super) fn start(&mut self, now: Instant) {
        if let Some(last) = self.last_start {
            self.interval += now.duration_since(last);
            self.frames += 1;
        }
        self.since.get_or_insert(now);
        self.last_start = Some(now);
        self.current = Some((now, Duration::ZERO));
    }

    /// The frame in progress rendered its picture in `took`.
    pub(super) fn rendered(&mut self, took: Duration) {
        if let Some((_, render)) = &mut self.current {
            *render += took;
            self.rendered += 1;
        }
    }

    /// The frame's `show` ends at `now`; returns the averages once a second has passed since
    /// the last report (and starts the next second).
    pub(super) fn end(&mut self, now: Instant) -> Option<FrameSplit> {
        if let Some((start, render)) = self.current.take() {
            self.show += now.duration_since(start);
            self.render += render;
        }
        let since = self.since?;
        if now.duration_since(since) < Duration::from_secs(1) || self.frames == 0 {
            return None;
        }
        // The sums of `show` and rendering include the frame just ended, whose interval is not
        // counted yet: average them over the frames shown, the interval over those counted.
        let shown = f64::from(self.frames + 1);
        let per = |sum: Duration, count: f64| sum.as_secs_f64() * 1e3 / count;
        let interval_ms = per(self.interval, f64::from(self.frames));
        let show_ms = per(self.show, shown);
        let render_ms = per(self.render, shown);
        let split = FrameSplit {
            frames: self.frames,
            rendered: self.rendered,
            interval_ms,
            render_ms,
            ui_ms: show_ms - render_ms,
            outside_ms: (interval_ms - show_ms).max(0.0),
        };
        *self = Self {
            last_start: self.last_start,
            ..Self::default()
        };
        Some(split)
    }
}

impl FrameSplit {
    /// The line printed to stderr.
    pub(super) fn line(&self, size: (u32, u32), method: &str) -> String {
        format!(
            "srt view: {:.1} frames/s, per frame {:.0} ms: render {:.0} ms ({} of {} frames \
             rendered, {}x{} px, {method}), rest of the update {:.1} ms, painting and presenting \
             the window {:.0} ms",
            1e3 / self.interval_ms,
            self.interval_ms,
            self.render_ms,
            self.rendered,
            self.frames + 1,
            size.0,
            size.1,
            self.ui_ms,
            self.outside_ms,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three frames 100 ms apart, each 60 ms of `show` of which 40 ms rendering: the split is
    /// 100 = 40 + 20 + 40.
    #[test]
    fn a_second_of_frames_splits_into_render_ui_and_outside() {
        let mut stats = FrameStats::default();
        let t0 = Instant::now();
        let ms = |n: u64| t0 + Duration::from_millis(n);
        for k in 0..11 {
            stats.start(ms(100 * k));
            stats.rendered(Duration::from_millis(40));
            let split = stats.end(ms(100 * k + 60));
            if k < 10 {
                assert_eq!(split, None, "frame {k}");
            } else {
                let split = split.expect("a second has passed");
                assert_eq!(split.frames, 10);
                assert_eq!(split.rendered, 11);
                assert!((split.interval_ms - 100.0).abs() < 1e-6);
                assert!((split.render_ms - 40.0).abs() < 1e-6);
                assert!((split.ui_ms - 20.0).abs() < 1e-6);
                assert!((split.outside_ms - 40.0).abs() < 1e-6);
            }
        }
        // The next second starts from the last frame.
        stats.start(ms(1100));
        assert_eq!(stats.frames, 1);
    }
}
