//! Output files for srt's programs: videos (H.264 in MP4, animated GIF) from rendered frames,
//! and files that appear complete or not at all. Shared by `srt render`, `srt encode` and the
//! viewer's recorder, so a video written from any of them is the same.
//!
//! Errors are [`anyhow::Error`]s: every one is a finished message for a person (it names the
//! file and the reason), which is all its callers do with it.

mod atomic;
mod video;

pub use atomic::{AtomicFile, parent_folder, temporary_file_beside};
pub use video::{VideoFormat, VideoWriter, check_size, lowercase_extension};
