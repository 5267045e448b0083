//! Recording what the viewer shows into a video (the formats of `srt render`: H.264 in MP4,
//! animated GIF; crate srt-video), at a fixed frame rate that does not depend on how fast the
//! machine draws: while recording, the viewer advances its clock (observation time, flight) by
//! exactly one frame period per drawn frame, and every drawn frame becomes one video frame. A
//! slow software adapter therefore records a smooth video; the window merely plays slower than
//! real time meanwhile. UI-free, so it is tested without a window.

use std::path::{Path, PathBuf};

use image::{RgbImage, RgbaImage};
use srt_video::{VideoFormat, VideoWriter};

/// Frame rates the recorder offers, the default first.
pub const FRAME_RATES: [u32; 4] = [24, 25, 30, 60];

/// A video being recorded; it appears at its path only when [`Recorder::finish`] succeeds.
pub struct Recorder {
    writer: VideoWriter,
    path: PathBuf,
    fps: u32,
    size: (u32, u32),
}

impl Recorder {
    /// Starts recording `width` × `height` frames at `fps` into `path` (.mp4 or .gif). H.264
    /// needs even sizes: an odd width or height is recorded one pixel smaller (the last column or
    /// row is left out).
    ///
    /// # Errors
    /// A message naming the file if its extension is not a video's, the size does not fit the
    /// format, or the file cannot be created.
    pub fn start(path: &Path, width: u32, height: u32, fps: u32) -> Result<Self, String> {
        let format = VideoFormat::for_path(path).ok_or_else(|| {
            format!(
                "cannot record {}: the file name must end in .mp4 or .gif",
                path.display()
            )
        })?;
        let size = match format {
            VideoFormat::Mp4 => (width & !1, height & !1),
            VideoFormat::Gif => (width, height),
        };
        let writer = VideoWriter::create(path, size.0.max(2), size.1.max(2), fps.max(1))
            .map_err(|e| format!("{e:#}"))?;
        Ok(Self {
            writer,
            path: path.to_owned(),
            fps: fps.max(1),
            size: (size.0.max(2), size.1.max(2)),
        })
    }

    /// Seconds of the viewer's clock per recorded frame: 1 / fps.
    #[must_use]
    pub fn frame_period(&self) -> f64 {
        1.0 / f64::from(self.fps)
    }

    /// The file being recorded.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends the viewer's image as the next frame (cropped to the video's size; a smaller image
    /// — the window shrank — is padded with black).
    ///
    /// # Errors
    /// A message naming the file if encoding or writing fails.
    pub fn push(&mut self, image: &RgbaImage) -> Result<(), String> {
        let (width, height) = self.size;
        let frame = RgbImage::from_fn(width, height, |x, y| {
            if x < image.width() && y < image.height() {
                let [r, g, b, _] = image.get_pixel(x, y).0;
                image::Rgb([r, g, b])
            } else {
                image::Rgb([0, 0, 0])
            }
        });
        self.writer.push(&frame).map_err(|e| format!("{e:#}"))
    }

    /// Finishes the video; returns its path and frame count.
    ///
    /// # Errors
    /// A message naming the file if it has no frames or cannot be completed; nothing is then
    /// left at the path.
    pub fn finish(self) -> Result<(PathBuf, u32), String> {
        let frames = self.writer.finish().map_err(|e| format!("{e:#}"))?;
        Ok((self.path, frames))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(width: u32, height: u32, shade: u8) -> RgbaImage {
        RgbaImage::from_pixel(width, height, image::Rgba([shade, 0, 255 - shade, 255]))
    }

    #[test]
    fn records_a_gif_and_an_mp4_frame_by_frame() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["flight.gif", "flight.mp4"] {
            let path = dir.path().join(name);
            // An odd size: the MP4 drops the last column and row.
            let mut recorder = Recorder::start(&path, 33, 21, 25).unwrap();
            assert!((recorder.frame_period() - 0.04).abs() < 1e-15);
            for k in 0..5 {
                recorder.push(&frame(33, 21, 50 * k)).unwrap();
            }
            assert!(!path.exists(), "{name} appears before it is finished");
            let (written, frames) = recorder.finish().unwrap();
            assert_eq!((written, frames), (path.clone(), 5));
            assert!(std::fs::metadata(&path).unwrap().len() > 100, "{name}");
        }
    }

    #[test]
    fn bad_paths_and_empty_recordings_leave_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let e = Recorder::start(&dir.path().join("x.png"), 32, 32, 24)
            .err()
            .unwrap();
        assert!(e.contains("x.png") && e.contains(".mp4 or .gif"), "{e}");
        let e = Recorder::start(&dir.path().join("missing/x.mp4"), 32, 32, 24)
            .err()
            .unwrap();
        assert!(e.contains("x.mp4"), "{e}");
        let path = dir.path().join("empty.gif");
        let e = Recorder::start(&path, 32, 32, 24)
            .unwrap()
            .finish()
            .unwrap_err();
        assert!(e.contains("at least one frame"), "{e}");
        assert!(!path.exists());
        // Dropped while recording (the viewer closed): no file either.
        let path = dir.path().join("dropped.mp4");
        let mut recorder = Recorder::start(&path, 32, 32, 24).unwrap();
        recorder.push(&frame(32, 32, 9)).unwrap();
        drop(recorder);
        assert!(!path.exists());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "leftovers"
        );
    }
}
