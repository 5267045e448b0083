//! The library behind the `srt` command: the renderer that turns a built scene into an image's
//! display colours and radiance ([`engine`]), shared by the command and by the Python module
//! (`python/`), so that both give the same pixels for the same arguments.
//!
//! The command itself (options, files, videos, provenance records) is the `srt` binary
//! (`src/main.rs`); the library crates (`srt-physics`, `srt-color`, `srt-scene`, `srt-trace`,
//! `srt-gpu`, …) are the building blocks.

pub mod engine;
