//! srt in a web page: the exact relativistic renderer behind a teacher's controls, in a
//! browser. The page (`web/` beside this crate, built by `cargo xtask web`) draws with WebGPU —
//! srt-gpu's passes, exactly as on the desktop — or, where WebGPU is missing, with the exact CPU
//! tracer in a Web Worker.
//!
//! - [`query`] — the page's address as settings: the keys of `srt render`'s options, so that
//!   an embedded page and the command draw the same picture;
//! - [`session`] — the scene shown (a built-in scene or a dropped model) with the page's values
//!   in place of its own, built as `srt render` builds it; the CPU picture;
//! - `web` (wasm32 only) — what the page's JavaScript calls: `GpuPage` (a canvas drawn with
//!   WebGPU) and `CpuPage` (the CPU picture as bytes).

pub mod query;
pub mod session;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use query::{BackendChoice, PageQuery, QueryError, parse_query};
pub use session::{SceneInfo, Session, SessionError, scene_names};
