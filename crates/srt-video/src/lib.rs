//! Output files for srt's programs: videos (H.264 in MP4, animated GIF) from rendered frames,
//! with a text record of how they were made that reads back ([`read_comments`]), and files that
//! appear complete or not at all. Shared by `srt render`, `srt encode` and the
//! viewer's recorder, so a video written from any of them is the same.
//!
//! Errors are [`WriteError`]s: every one's `Display` is a finished one-line message for a person
//! (it names the file and the reason), and its variant says what went wrong for a program that
//! wants to react.
//!
//! ```
//! use image::{Rgb, RgbImage};
//! use srt_video::{VideoWriter, WriteError};
//!
//! let folder = tempfile::tempdir().unwrap();
//! let path = folder.path().join("odd.mp4");
//! // H.264 stores colour at half resolution: an odd size is refused before anything is written.
//! let error = VideoWriter::create(&path, 65, 36, 24).err().unwrap();
//! assert!(matches!(error, WriteError::OddSize { width: 65, .. }));
//! assert!(error.to_string().ends_with("the picture is 65x36"));
//! assert!(!path.exists());
//! ```

mod atomic;
mod error;
mod mp4box;
mod record;
pub mod spherical;
mod video;

pub use atomic::{AtomicFile, parent_folder, remove_partial_files, temporary_file_beside};
pub use error::{EncoderError, WriteError};
pub use record::{read_comments, read_gif_comments, read_mp4_comments, video_format_of};
pub use spherical::StereoMode;
pub use video::{VideoFormat, VideoWriter, check_size, lowercase_extension};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
