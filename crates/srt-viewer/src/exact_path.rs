//! Who draws the viewer's exact panes: the GPU's passes, srt's CPU tracer, or the faster of the
//! two on a software adapter, by srt-gpu's rule ([`srt_gpu::exact_path`], shared with the web
//! page). A hardware GPU always draws under [`ExactPath::Auto`].

pub use srt_gpu::exact_path::{DrawnBy, PaneTimes};

/// Who draws the exact panes, as the panel offers it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ExactPath {
    /// The faster of the two on a software adapter, the GPU on a hardware one.
    #[default]
    Auto,
    /// Always the GPU.
    Gpu,
    /// Always the CPU tracer.
    Cpu,
}

impl ExactPath {
    /// All choices, in the order the panel lists them.
    pub const ALL: [Self; 3] = [Self::Auto, Self::Gpu, Self::Cpu];

    /// The label in the panel.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::Auto => "the faster (GPU or CPU)",
            Self::Gpu => "the GPU",
            Self::Cpu => "the CPU tracer",
        }
    }
}
