//! Where a bench run is written: runs on a software adapter (the CI machine's lavapipe) fill
//! the main generated blocks of `docs/performance.md` and `docs/performance-results.json`; runs
//! on a hardware GPU (a lent machine) fill blocks and a results file of their own, so that a
//! real GPU's figures stand beside lavapipe's instead of replacing them.

use srt_gpu::GpuContext;

/// The first and last line of one generated block of `docs/performance.md`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Markers {
    /// The block's first line.
    pub start: &'static str,
    /// The block's last line.
    pub end: &'static str,
}

/// The blocks and the results file one kind of adapter writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Report {
    /// The bench table.
    pub table: Markers,
    /// The summary sentences under the table.
    pub summary: Markers,
    /// The sustained frame rates of `bench --throughput`.
    pub throughput: Markers,
    /// The saved results, relative to the workspace.
    pub results: &'static str,
}

/// What a software adapter's run writes (the machine CI runs on).
pub const SOFTWARE: Report = Report {
    table: Markers {
        start: "<!-- table1:start (written by cargo xtask bench) -->",
        end: "<!-- table1:end -->",
    },
    summary: Markers {
        start: "<!-- summary:start (written by cargo xtask bench) -->",
        end: "<!-- summary:end -->",
    },
    throughput: Markers {
        start: "<!-- throughput:start (written by cargo xtask bench --throughput) -->",
        end: "<!-- throughput:end -->",
    },
    results: "docs/performance-results.json",
};

/// What a hardware GPU's run writes.
pub const HARDWARE: Report = Report {
    table: Markers {
        start: "<!-- gpu-table:start (written by cargo xtask bench on a hardware GPU) -->",
        end: "<!-- gpu-table:end -->",
    },
    summary: Markers {
        start: "<!-- gpu-summary:start (written by cargo xtask bench on a hardware GPU) -->",
        end: "<!-- gpu-summary:end -->",
    },
    throughput: Markers {
        start: "<!-- gpu-throughput:start (written by cargo xtask bench --throughput on a hardware GPU) -->",
        end: "<!-- gpu-throughput:end -->",
    },
    results: "docs/performance-results-gpu.json",
};

impl Report {
    /// [`SOFTWARE`] for a CPU adapter (lavapipe, llvmpipe), [`HARDWARE`] for any other.
    #[must_use]
    pub fn for_adapter(ctx: &GpuContext) -> Self {
        if ctx.adapter_info.device_type == wgpu::DeviceType::Cpu {
            SOFTWARE
        } else {
            HARDWARE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{HARDWARE, SOFTWARE};

    /// No marker of one report is found inside another's, so neither run can overwrite the
    /// other's blocks.
    #[test]
    fn the_two_reports_never_share_a_marker() {
        let markers = |r: super::Report| {
            [r.table, r.summary, r.throughput]
                .into_iter()
                .flat_map(|m| [m.start, m.end])
                .collect::<Vec<_>>()
        };
        let (software, hardware) = (markers(SOFTWARE), markers(HARDWARE));
        for a in &software {
            for b in &hardware {
                assert!(!a.contains(b) && !b.contains(a), "{a} / {b}");
            }
        }
        assert_ne!(SOFTWARE.results, HARDWARE.results);
    }
}
