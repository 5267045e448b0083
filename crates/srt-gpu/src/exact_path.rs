//! Which path draws an exact picture: the GPU's passes or srt's CPU tracer (srt-trace). On a
//! software adapter (Mesa's lavapipe and llvmpipe, SwiftShader, a browser's fallback adapter)
//! the two share the cores, and a CPU frame may come sooner than the adapter's — a scene of
//! millions of triangles does (docs/performance.md, "auto without a hardware GPU"). A picture
//! drawn by "the faster" keeps both paths' recent frame times ([`PaneTimes`]) and draws by the
//! faster: the GPU first, then the CPU's cost measured on a few rows
//! (`srt_trace::Tracer::measure_frame`), then every frame's own time. The path not in use is
//! timed again every [`REFRESH`], as a change of view changes both. The viewer's exact panes and
//! the web page's canvas share this rule. Times are read on [`web_time::Instant`], the standard
//! library's clock natively and the page's `performance.now()` in a browser.

use std::time::Duration;

use web_time::Instant;

/// How old the time of the path not in use may grow before it is timed again: an object passing
/// close to the camera, or a change of speed, changes both paths' costs.
pub const REFRESH: Duration = Duration::from_secs(5);

/// How much faster the other path must be for a picture to change paths: a path's frame times
/// move by about a tenth from frame to frame on a software adapter, and a picture should not
/// flip between the two on that.
pub const MARGIN: f64 = 1.15;

/// The weight of a new frame's time in its path's running time.
const SMOOTHING: f64 = 0.3;

/// The most of a picture's time that timing the path not in use may take: that path is timed
/// again no sooner than what timing it last cost over this share (and no sooner than
/// [`REFRESH`]). The CPU's measure of a 1.92 M-triangle cube builds its tracer, 1.3–2 s in a
/// browser's worker, and a software GPU's frame of it takes 3 s: every 5 s, either would stall
/// the path in use for a large part of the time.
pub const TIMING_SHARE: f64 = 0.1;

/// Which path draws one frame of a picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawnBy {
    /// The GPU's passes.
    Gpu,
    /// srt-trace's CPU tracer, its picture shown in the GPU's place.
    Cpu,
}

/// A path's running time, when it was last timed, and what that timing cost.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Timed {
    seconds: f64,
    at: Instant,
    /// Seconds the last timing took (a frame, or the CPU's measure).
    cost: f64,
}

/// Whether `timed` is unknown or older than [`REFRESH`] at `now`: a time that old is replaced
/// by the next, not averaged with it.
fn stale(timed: Option<Timed>, now: Instant) -> bool {
    timed.is_none_or(|t| now.saturating_duration_since(t.at) > REFRESH)
}

/// Whether the path of `timed`, not in use, is to be timed again at `now`: its time is unknown,
/// or older than [`REFRESH`] and than its timing's cost over [`TIMING_SHARE`].
fn due(timed: Option<Timed>, now: Instant) -> bool {
    timed.is_none_or(|t| {
        let age = now.saturating_duration_since(t.at).as_secs_f64();
        age > REFRESH.as_secs_f64() && age * TIMING_SHARE > t.cost
    })
}

/// One exact picture's frame times on both paths (a viewer pane's, the page's canvas), and the
/// path of its last frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PaneTimes {
    gpu: Option<Timed>,
    cpu: Option<Timed>,
    last: Option<DrawnBy>,
}

impl PaneTimes {
    /// Whether the CPU's cost is to be measured before the frame at `now`: the picture draws on
    /// the GPU, whose time is known, and the CPU's time is unknown or due again (older than
    /// [`REFRESH`] and than its measure's cost over [`TIMING_SHARE`]).
    #[must_use]
    pub fn wants_cpu_measure(&self, now: Instant) -> bool {
        self.last != Some(DrawnBy::Cpu) && self.gpu.is_some() && due(self.cpu, now)
    }

    /// Who draws the frame at `now`: the GPU until both times are known; then the
    /// path in use unless the other is faster by [`MARGIN`]; the GPU for one frame when the
    /// picture draws on the CPU and the GPU's time is due again (older than [`REFRESH`] and
    /// than its frame over [`TIMING_SHARE`]).
    #[must_use]
    pub fn next(&self, now: Instant) -> DrawnBy {
        let (Some(gpu), Some(cpu)) = (self.gpu, self.cpu) else {
            return DrawnBy::Gpu;
        };
        let cpu_faster = if self.last == Some(DrawnBy::Cpu) {
            !due(Some(gpu), now) && cpu.seconds <= gpu.seconds * MARGIN
        } else {
            cpu.seconds * MARGIN < gpu.seconds
        };
        if cpu_faster {
            DrawnBy::Cpu
        } else {
            DrawnBy::Gpu
        }
    }

    /// A frame drawn `by` one path took `seconds`, ending at `now`.
    pub fn drawn(&mut self, by: DrawnBy, seconds: f64, now: Instant) {
        let slot = match by {
            DrawnBy::Gpu => &mut self.gpu,
            DrawnBy::Cpu => &mut self.cpu,
        };
        let cost = seconds;
        let seconds = match *slot {
            Some(kept) if !stale(Some(kept), now) => {
                kept.seconds + SMOOTHING * (seconds - kept.seconds)
            }
            _ => seconds,
        };
        *slot = Some(Timed {
            seconds,
            at: now,
            cost,
        });
        self.last = Some(by);
    }

    /// The CPU's cost of a frame measured at `now`: its tracer's build and a picture estimated
    /// from a few of its rows (`seconds`), by a measure that took `took` seconds.
    pub fn measured_cpu(&mut self, seconds: f64, took: f64, now: Instant) {
        self.cpu = Some(Timed {
            seconds,
            at: now,
            cost: took,
        });
    }

    /// The last frame's path, and both paths' running times in seconds where known.
    #[must_use]
    pub fn report(&self) -> (Option<DrawnBy>, Option<f64>, Option<f64>) {
        (
            self.last,
            self.gpu.map(|t| t.seconds),
            self.cpu.map(|t| t.seconds),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The GPU draws first; the CPU is measured once the GPU is timed; the faster by the
    /// margin takes over, and a small difference does not move a pane.
    #[test]
    fn a_pane_moves_to_the_cpu_only_when_it_is_faster_by_the_margin() {
        let start = Instant::now();
        let mut times = PaneTimes::default();
        assert_eq!(times.next(start), DrawnBy::Gpu);
        assert!(!times.wants_cpu_measure(start));
        times.drawn(DrawnBy::Gpu, 1.0, start);
        assert!(times.wants_cpu_measure(start));
        // Within the margin: the GPU stays.
        times.measured_cpu(0.9, 0.01, start);
        assert!(!times.wants_cpu_measure(start));
        assert_eq!(times.next(start), DrawnBy::Gpu);
        // Faster by more than the margin: the CPU.
        times.measured_cpu(0.8, 0.01, start);
        assert_eq!(times.next(start), DrawnBy::Cpu);
        times.drawn(DrawnBy::Cpu, 0.8, start);
        assert!(!times.wants_cpu_measure(start));
        // A CPU frame a little slower than the GPU's time keeps the CPU (no flipping)…
        times.drawn(DrawnBy::Cpu, 1.3, start);
        let running = times.report().2.unwrap();
        assert!(
            (running - (0.8 + SMOOTHING * 0.5)).abs() < 1e-12,
            "{running}"
        );
        assert_eq!(times.next(start), DrawnBy::Cpu);
        // …while CPU frames slower by more than the margin send the pane back.
        for _ in 0..10 {
            times.drawn(DrawnBy::Cpu, 2.0, start);
        }
        assert_eq!(times.next(start), DrawnBy::Gpu);
    }

    /// The path not in use is timed again after [`REFRESH`]: the CPU by a measure while the
    /// GPU draws, the GPU by one frame while the CPU draws; a stale time is replaced, not
    /// averaged.
    #[test]
    fn the_other_path_is_timed_again_after_the_refresh() {
        let start = Instant::now();
        let later = start + REFRESH + Duration::from_millis(1);
        let mut times = PaneTimes::default();
        times.drawn(DrawnBy::Gpu, 1.0, start);
        times.measured_cpu(2.0, 0.01, start);
        assert_eq!(times.next(start), DrawnBy::Gpu);
        times.drawn(DrawnBy::Gpu, 1.0, later);
        assert!(times.wants_cpu_measure(later));
        let mut on_cpu = PaneTimes::default();
        on_cpu.drawn(DrawnBy::Gpu, 0.4, start);
        on_cpu.measured_cpu(0.2, 0.01, start);
        on_cpu.drawn(DrawnBy::Cpu, 0.2, later);
        assert_eq!(on_cpu.next(later), DrawnBy::Gpu, "the GPU's time is stale");
        on_cpu.drawn(DrawnBy::Gpu, 1.2, later);
        assert_eq!(on_cpu.report().1, Some(1.2), "replaced, not averaged");
        assert_eq!(on_cpu.next(later), DrawnBy::Cpu);
    }

    /// A path whose timing costs much is timed again less often: a CPU measure of 2 s waits
    /// 20 s, not [`REFRESH`], and so does a GPU frame of 3 s while the CPU draws (30 s), so
    /// that timing the path not in use takes at most [`TIMING_SHARE`] of the time.
    #[test]
    fn a_costly_timing_is_repeated_at_most_a_tenth_of_the_time() {
        let start = Instant::now();
        let at = |seconds: u64| start + Duration::from_secs(seconds);
        let mut on_gpu = PaneTimes::default();
        on_gpu.drawn(DrawnBy::Gpu, 0.6, start);
        on_gpu.measured_cpu(2.0, 2.0, start);
        on_gpu.drawn(DrawnBy::Gpu, 0.6, at(6));
        assert!(!on_gpu.wants_cpu_measure(at(6)), "2 s of measure, 6 s ago");
        assert!(!on_gpu.wants_cpu_measure(at(19)));
        assert!(on_gpu.wants_cpu_measure(at(21)));
        let mut on_cpu = PaneTimes::default();
        on_cpu.drawn(DrawnBy::Gpu, 3.0, start);
        on_cpu.measured_cpu(1.7, 0.1, start);
        on_cpu.drawn(DrawnBy::Cpu, 1.7, at(6));
        assert_eq!(on_cpu.next(at(6)), DrawnBy::Cpu, "a 3 s GPU frame, 6 s ago");
        assert_eq!(on_cpu.next(at(29)), DrawnBy::Cpu);
        assert_eq!(on_cpu.next(at(31)), DrawnBy::Gpu);
    }
}
