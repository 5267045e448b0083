//! The library behind the `srt` command: the renderer that turns a built scene into an image's
//! display colours and radiance ([`engine`]), and what an empty picture is told with
//! ([`empty`]), shared by the command and by the Python module (`python/`), so that both give
//! the same pixels and words for the same arguments.
//!
//! The command itself (options, files, videos, provenance records) is the `srt` binary
//! (`src/main.rs`); the library crates (`srt-physics`, `srt-color`, `srt-scene`, `srt-trace`,
//! `srt-gpu`, …) are the building blocks.

pub mod empty;
pub mod engine;
pub mod software;
pub mod tiles;
