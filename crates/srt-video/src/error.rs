//! [`WriteError`], why a video or an atomic file could not be written.

use std::path::PathBuf;

use srt_scene::message::io_reason;

/// An error of an encoder or container library (OpenH264, muxide, gif), kept as it came.
pub type EncoderError = Box<dyn std::error::Error + Send + Sync + 'static>;

/// Why a video or an atomic file could not be written.
///
/// Its `Display` is the whole message for a person, one line that names the file and the
/// reason ("cannot write flight.mp4: H.264 video needs an even width and height, and the
/// picture is 65x36"); [`std::error::Error::source`] is `None`, so an `anyhow` chain printed with
/// `{:#}` says it once. Match the variants to react to a cause; the underlying I/O or encoder
/// error is in the variant's `error` field.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WriteError {
    /// The file name does not end in `.mp4` or `.gif` ([`crate::VideoFormat::for_path`]).
    #[error("cannot write {}: a video must end in .mp4 or .gif", .path.display())]
    NotAVideo {
        /// The file asked for.
        path: PathBuf,
    },
    /// H.264 (4:2:0) needs an even width and height.
    #[error(
        "cannot write {}: H.264 video needs an even width and height, and {origin} is \
         {width}x{height}",
        .path.display()
    )]
    OddSize {
        /// The video.
        path: PathBuf,
        /// Where the size came from ("the picture", "--width x --height", a frame's file).
        origin: String,
        /// The width asked for, in pixels.
        width: u32,
        /// The height asked for, in pixels.
        height: u32,
    },
    /// The picture is larger than OpenH264 encodes (3840×2160 either way round).
    #[error(
        "cannot write {}: the H.264 encoder takes at most {}x{} (or {}x{}), and {origin} is \
         {width}x{height}",
        .path.display(),
        .max.0,
        .max.1,
        .max.1,
        .max.0
    )]
    TooLargeForH264 {
        /// The video.
        path: PathBuf,
        /// Where the size came from.
        origin: String,
        /// The width asked for, in pixels.
        width: u32,
        /// The height asked for, in pixels.
        height: u32,
        /// The largest picture, longer side by shorter side.
        max: (u32, u32),
    },
    /// A GIF's sides are 16-bit numbers.
    #[error(
        "cannot write {}: a GIF is at most 65535 pixels a side and 8192x8192 pixels in all (its \
         colour quantiser holds about 9 bytes a pixel), and {origin} is {width}x{height}; write \
         numbered PNGs instead",
        .path.display()
    )]
    TooLargeForGif {
        /// The video.
        path: PathBuf,
        /// Where the size came from.
        origin: String,
        /// The width asked for, in pixels.
        width: u32,
        /// The height asked for, in pixels.
        height: u32,
    },
    /// A frame whose size is not the video's.
    #[error(
        "cannot add a {}x{} frame to {}, a {}x{} video",
        .frame.0,
        .frame.1,
        .path.display(),
        .video.0,
        .video.1
    )]
    FrameSize {
        /// The video.
        path: PathBuf,
        /// The frame's width and height.
        frame: (u32, u32),
        /// The video's width and height.
        video: (u32, u32),
    },
    /// [`crate::VideoWriter::finish`] before any frame was pushed.
    #[error("cannot write {}: a video needs at least one frame", .path.display())]
    NoFrames {
        /// The video.
        path: PathBuf,
    },
    /// No temporary file could be created in the destination's folder.
    #[error(
        "cannot write {}: cannot create a file in folder {} ({})",
        .path.display(),
        .folder.display(),
        io_reason(.error)
    )]
    CreateFile {
        /// The file asked for.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// Writing, flushing or renaming the file into place failed (a full disk, say).
    #[error("cannot write {} ({})", .path.display(), io_reason(.error))]
    Io {
        /// The file asked for.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// The H.264 encoder could not be started.
    #[error(
        "cannot write {}: the H.264 encoder failed to start: {error}",
        .path.display()
    )]
    EncoderStart {
        /// The video.
        path: PathBuf,
        /// OpenH264's error.
        error: EncoderError,
    },
    /// The encoder or the container failed: on frame `frame` (counted from 0), or, when it is
    /// `None`, while setting up or completing the file.
    #[error("{}: {error}", cannot_write(.path, *.frame))]
    Encode {
        /// The video.
        path: PathBuf,
        /// The frame being added, if any.
        frame: Option<u32>,
        /// The encoder's or container's error.
        error: EncoderError,
    },
}

/// "cannot write PATH" or "cannot write frame N of PATH".
fn cannot_write(path: &std::path::Path, frame: Option<u32>) -> String {
    match frame {
        Some(frame) => format!("cannot write frame {frame} of {}", path.display()),
        None => format!("cannot write {}", path.display()),
    }
}

impl WriteError {
    /// The file the error is about.
    #[must_use]
    pub fn path(&self) -> &std::path::Path {
        match self {
            Self::NotAVideo { path }
            | Self::OddSize { path, .. }
            | Self::TooLargeForH264 { path, .. }
            | Self::TooLargeForGif { path, .. }
            | Self::FrameSize { path, .. }
            | Self::NoFrames { path }
            | Self::CreateFile { path, .. }
            | Self::Io { path, .. }
            | Self::EncoderStart { path, .. }
            | Self::Encode { path, .. } => path,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use image::RgbImage;

    use crate::{AtomicFile, VideoFormat, VideoWriter, WriteError, check_size};

    #[test]
    fn size_messages_name_the_file_the_size_and_its_origin() {
        let path = Path::new("out/f.mp4");
        let message = |format, width, height| {
            check_size(path, format, width, height, "--width x --height")
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            message(VideoFormat::Mp4, 65, 36),
            "cannot write out/f.mp4: H.264 video needs an even width and height, and \
             --width x --height is 65x36"
        );
        assert_eq!(
            message(VideoFormat::Mp4, 4000, 720),
            "cannot write out/f.mp4: the H.264 encoder takes at most 3840x2160 (or 2160x3840), \
             and --width x --height is 4000x720"
        );
        assert_eq!(
            message(VideoFormat::Gif, 70_000, 2),
            "cannot write out/f.mp4: a GIF is at most 65535 pixels a side and 8192x8192 pixels \
             in all (its colour quantiser holds about 9 bytes a pixel), and --width x --height \
             is 70000x2; write numbered PNGs instead"
        );
        // The largest picture srt renders is too many pixels for one GIF frame; 8192² is not.
        assert!(message(VideoFormat::Gif, 16384, 8192).contains("8192x8192 pixels in all"));
        assert!(check_size(path, VideoFormat::Gif, 8192, 8192, "").is_ok());
        assert!(check_size(path, VideoFormat::Mp4, 2160, 3840, "").is_ok());
    }

    #[test]
    fn writer_errors_are_typed_and_leave_nothing() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("v.gif");
        let error = VideoWriter::create(&folder.path().join("v.avi"), 4, 4, 10).unwrap_err();
        assert!(matches!(error, WriteError::NotAVideo { .. }), "{error:?}");
        assert!(
            error
                .to_string()
                .ends_with("a video must end in .mp4 or .gif")
        );

        let mut video = VideoWriter::create(&path, 4, 4, 10).unwrap();
        let error = video.push(&RgbImage::new(4, 6)).unwrap_err();
        assert_eq!(
            error.to_string(),
            format!("cannot add a 4x6 frame to {}, a 4x4 video", path.display())
        );
        assert_eq!(error.path(), path);
        let error = video.finish().unwrap_err();
        assert!(matches!(error, WriteError::NoFrames { .. }), "{error:?}");
        assert!(
            error
                .to_string()
                .ends_with("a video needs at least one frame")
        );
        assert_eq!(std::fs::read_dir(folder.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_missing_folder_is_named_with_the_reason() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("missing").join("f.png");
        let Err(error) = AtomicFile::create(&path) else {
            panic!("a file in a missing folder was created");
        };
        assert!(matches!(error, WriteError::CreateFile { .. }), "{error:?}");
        assert_eq!(
            error.to_string(),
            format!(
                "cannot write {}: cannot create a file in folder {} (no such file or directory)",
                path.display(),
                path.parent().unwrap().display()
            )
        );
        assert!(std::error::Error::source(&error).is_none());
    }
}
