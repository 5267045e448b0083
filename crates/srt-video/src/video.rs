//! Videos from rendered frames, written atomically through [`AtomicFile`]: H.264 (Cisco's
//! OpenH264, constrained baseline profile) in an MP4 with its index before the data (muxide), so
//! browsers and presentation software play it while it loads; or an animated GIF that loops
//! (the gif crate, one palette per frame). Either may carry a text record ([`crate::record`]).

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use image::RgbImage;
use muxide::api::{Muxer, MuxerBuilder, VideoCodec};
use openh264::OpenH264API;
use openh264::encoder::{
    BitRate, Encoder, EncoderConfig, FrameRate, FrameType, IntraFramePeriod, RateControlMode,
    VuiConfig,
};
use openh264::formats::{RgbSliceU8, YUVBuffer};

use crate::atomic::AtomicFile;
use crate::error::{EncoderError, WriteError};
use crate::mp4box::rewrite_movie;
use crate::record::{add_mp4_comment, write_gif_comment};
use crate::spherical::{StereoMode, insert_into_sample_entry, spherical_boxes};

/// Bits per pixel and frame the H.264 encoder's buffer model is set up for (about 5.5 Mbit/s at
/// 1280×720 and 24 fps).
const BITS_PER_PIXEL: f64 = 0.25;
/// Seconds between key frames, so players can seek.
const KEY_FRAME_SECONDS: u32 = 2;
/// The GIF colour quantiser's speed (1 best and slowest, 30 fastest).
const GIF_QUANTISER_SPEED: i32 = 10;

/// The video formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VideoFormat {
    /// H.264 video in an MP4 container.
    Mp4,
    /// Animated GIF.
    Gif,
}

impl VideoFormat {
    /// The format for `path`'s extension (`.mp4` or `.gif`, any case), if it is a video's.
    #[must_use]
    pub fn for_path(path: &Path) -> Option<Self> {
        match lowercase_extension(path).as_deref() {
            Some("mp4") => Some(Self::Mp4),
            Some("gif") => Some(Self::Gif),
            _ => None,
        }
    }
}

/// `path`'s extension in lower case, if it has one that is UTF-8.
#[must_use]
pub fn lowercase_extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// OpenH264's largest picture, longer side by shorter side (its encoder refuses more).
const MAX_H264_SIZE: (u32, u32) = (3840, 2160);

/// The most pixels of a GIF frame srt writes, 8192 × 8192: the frame and the colour
/// quantiser's copies hold about 9 bytes a pixel (601 MB measured for one 8192 × 8192 frame),
/// so that a GIF stays within srt's memory bound of 2 GiB (docs/performance.md, "Memory").
const MAX_GIF_PIXELS: u64 = 8192 * 8192;

/// Checks that a `width` × `height` picture can be stored as `format`: H.264 (4:2:0) needs even
/// sizes and OpenH264 at most 3840×2160 (either way round), a GIF at most 65535 pixels a side
/// and 8192 × 8192 pixels in all (`MAX_GIF_PIXELS`).
/// `origin` says where the size came from (options or a file) for the message.
///
/// # Errors
/// [`WriteError::OddSize`], [`WriteError::TooLargeForH264`] or [`WriteError::TooLargeForGif`] if
/// it cannot; the message names `path`, the size and `origin`.
pub fn check_size(
    path: &Path,
    format: VideoFormat,
    width: u32,
    height: u32,
    origin: &str,
) -> Result<(), WriteError> {
    let path = path.to_owned();
    let origin = origin.to_owned();
    match format {
        VideoFormat::Mp4 if width % 2 == 1 || height % 2 == 1 => Err(WriteError::OddSize {
            path,
            origin,
            width,
            height,
        }),
        VideoFormat::Mp4
            if width.max(height) > MAX_H264_SIZE.0 || width.min(height) > MAX_H264_SIZE.1 =>
        {
            Err(WriteError::TooLargeForH264 {
                path,
                origin,
                width,
                height,
                max: MAX_H264_SIZE,
            })
        }
        VideoFormat::Gif
            if width > u32::from(u16::MAX)
                || height > u32::from(u16::MAX)
                || u64::from(width) * u64::from(height) > MAX_GIF_PIXELS =>
        {
            Err(WriteError::TooLargeForGif {
                path,
                origin,
                width,
                height,
            })
        }
        _ => Ok(()),
    }
}

/// A video being written frame by frame; it appears at its path only when
/// [`VideoWriter::finish`] succeeds.
pub struct VideoWriter {
    file: AtomicFile,
    path: PathBuf,
    width: u32,
    height: u32,
    frames: u32,
    encoder: VideoEncoder,
    /// The 360° metadata to add to an MP4 ([`VideoWriter::set_spherical`]).
    spherical: Option<StereoMode>,
    /// The text record to store in the file ([`VideoWriter::set_comment`]).
    comment: Option<String>,
}

impl std::fmt::Debug for VideoWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let format = match self.encoder {
            VideoEncoder::Mp4 { .. } => VideoFormat::Mp4,
            VideoEncoder::Gif { .. } => VideoFormat::Gif,
        };
        f.debug_struct("VideoWriter")
            .field("path", &self.path)
            .field("format", &format)
            .field("width", &self.width)
            .field("height", &self.height)
            .field("frames", &self.frames)
            .finish_non_exhaustive()
    }
}

/// The encoder of one format.
enum VideoEncoder {
    /// OpenH264 feeding the MP4 muxer.
    Mp4 {
        encoder: Box<Encoder>,
        muxer: Box<Muxer<BufWriter<File>>>,
        fps: u32,
    },
    /// The GIF encoder and each frame's delay in hundredths of a second.
    Gif {
        encoder: Box<gif::Encoder<BufWriter<File>>>,
        delay: u16,
    },
}

impl VideoWriter {
    /// Starts a `width` × `height` video at `fps` frames per second; the format is `path`'s
    /// extension (.mp4 or .gif).
    ///
    /// # Errors
    /// [`WriteError::NotAVideo`] if `path` is not a video format, the errors of [`check_size`]
    /// if the size does not fit it, and others if the file or encoder cannot be set up.
    pub fn create(path: &Path, width: u32, height: u32, fps: u32) -> Result<Self, WriteError> {
        let Some(format) = VideoFormat::for_path(path) else {
            return Err(WriteError::NotAVideo {
                path: path.to_owned(),
            });
        };
        check_size(path, format, width, height, "the picture")?;
        let file = AtomicFile::create(path)?;
        let writer = file.writer()?;
        let cannot = |error| encode_error(path, None, error);
        let encoder = match format {
            VideoFormat::Mp4 => {
                let rate = f64::from(width) * f64::from(height) * f64::from(fps) * BITS_PER_PIXEL;
                let config = EncoderConfig::new()
                    .bitrate(BitRate::from_bps(rate as u32))
                    .max_frame_rate(FrameRate::from_hz(fps as f32))
                    // Every rendered frame is kept: the rate control may not drop any.
                    .skip_frames(false)
                    // Quality given the buffer, not a bit rate (that mode would need frame
                    // skipping); on the teaser it gave the best picture (45.8 dB PSNR at 320x180).
                    .rate_control_mode(RateControlMode::Bufferbased)
                    .intra_frame_period(IntraFramePeriod::from_num_frames(fps * KEY_FRAME_SECONDS))
                    // OpenH264's RGB to YUV conversion is BT.601, limited range.
                    .vui(VuiConfig::bt601());
                let encoder = Encoder::with_api_config(OpenH264API::from_source(), config)
                    .map_err(|error| WriteError::EncoderStart {
                        path: path.to_owned(),
                        error: error.into(),
                    })?;
                let muxer = MuxerBuilder::new(writer)
                    .video(VideoCodec::H264, width, height, f64::from(fps))
                    .build()
                    .map_err(|error| cannot(error.into()))?;
                VideoEncoder::Mp4 {
                    encoder: Box::new(encoder),
                    muxer: Box::new(muxer),
                    fps,
                }
            }
            VideoFormat::Gif => {
                // `check_size` has bounded the size to 16 bits.
                let mut encoder = gif::Encoder::new(writer, width as u16, height as u16, &[])
                    .map_err(|error| cannot(error.into()))?;
                encoder
                    .set_repeat(gif::Repeat::Infinite)
                    .map_err(|error| cannot(error.into()))?;
                VideoEncoder::Gif {
                    encoder: Box::new(encoder),
                    delay: (100.0 / f64::from(fps)).round().max(2.0) as u16,
                }
            }
        };
        Ok(Self {
            file,
            path: path.to_owned(),
            width,
            height,
            frames: 0,
            encoder,
            spherical: None,
            comment: None,
        })
    }

    /// Marks the video as 360° equirectangular, its eyes' pictures laid out as `stereo` says:
    /// an MP4 gets the Spherical Video V2 boxes ([`crate::spherical`]) so that 360° players show
    /// it around the viewer. A GIF has no such metadata and is written as it is.
    pub const fn set_spherical(&mut self, stereo: StereoMode) {
        self.spherical = Some(stereo);
    }

    /// Stores `text` in the video when it is finished: an MP4's user-data comment
    /// (`moov/udta/©cmt`), a GIF's comment extension (`record.rs`); it reads back with
    /// [`crate::read_comments`]. srt stores its record of how the video was made there.
    pub fn set_comment(&mut self, text: &str) {
        self.comment = Some(text.to_owned());
    }

    /// Appends a frame.
    ///
    /// # Errors
    /// [`WriteError::FrameSize`] if its size differs from the video's, [`WriteError::Encode`]
    /// if encoding or writing fails.
    pub fn push(&mut self, frame: &RgbImage) -> Result<(), WriteError> {
        if frame.dimensions() != (self.width, self.height) {
            return Err(WriteError::FrameSize {
                path: self.path.clone(),
                frame: frame.dimensions(),
                video: (self.width, self.height),
            });
        }
        let (path, index) = (&self.path, self.frames);
        let cannot = |error| encode_error(path, Some(index), error);
        match &mut self.encoder {
            VideoEncoder::Mp4 {
                encoder,
                muxer,
                fps,
            } => {
                let size = (self.width as usize, self.height as usize);
                let yuv = YUVBuffer::from_rgb8_source(RgbSliceU8::new(frame.as_raw(), size));
                let bitstream = encoder.encode(&yuv).map_err(|error| cannot(error.into()))?;
                let keyframe = bitstream.frame_type() == FrameType::IDR;
                let data = bitstream.to_vec();
                let seconds = f64::from(self.frames) / f64::from(*fps);
                muxer
                    .write_video(seconds, &data, keyframe)
                    .map_err(|error| cannot(error.into()))?;
            }
            VideoEncoder::Gif { encoder, delay } => {
                let mut gif_frame = gif::Frame::from_rgb_speed(
                    self.width as u16,
                    self.height as u16,
                    frame.as_raw(),
                    GIF_QUANTISER_SPEED,
                );
                gif_frame.delay = *delay;
                encoder
                    .write_frame(&gif_frame)
                    .map_err(|error| cannot(error.into()))?;
            }
        }
        self.frames += 1;
        Ok(())
    }

    /// Completes the container and renames the file into place; returns the number of frames.
    ///
    /// # Errors
    /// [`WriteError::NoFrames`] if the video has no frames, [`WriteError::Encode`] or
    /// [`WriteError::Io`] if finishing or writing fails; nothing is then left at the path.
    pub fn finish(self) -> Result<u32, WriteError> {
        if self.frames == 0 {
            return Err(WriteError::NoFrames { path: self.path });
        }
        let path = &self.path;
        let cannot = |error| encode_error(path, None, error);
        let (writer, rewrite) = match self.encoder {
            VideoEncoder::Mp4 { mut muxer, .. } => {
                muxer
                    .finish_in_place()
                    .map_err(|error| cannot(error.into()))?;
                let rewrite = self.spherical.is_some() || self.comment.is_some();
                ((*muxer).into_writer(), rewrite)
            }
            VideoEncoder::Gif { mut encoder, .. } => {
                if let Some(text) = &self.comment {
                    write_gif_comment(&mut encoder, text).map_err(|error| cannot(error.into()))?;
                }
                let writer = (*encoder)
                    .into_inner()
                    .map_err(|error| cannot(error.into()))?;
                (writer, false)
            }
        };
        self.file.flush(writer)?;
        if !rewrite {
            self.file.commit()?;
            return Ok(self.frames);
        }
        // The muxer's file, copied with the 360° boxes and the comment into a second temporary
        // file that replaces it; the first is removed when it drops.
        let with_metadata = AtomicFile::create(path)?;
        let mut out = with_metadata.writer()?;
        let (spherical, comment) = (self.spherical, self.comment.as_deref());
        rewrite_movie(&mut self.file.reader()?, &mut out, |moov| {
            if let Some(stereo) = spherical {
                insert_into_sample_entry(moov, &spherical_boxes(stereo))?;
            }
            if let Some(text) = comment {
                add_mp4_comment(moov, text)?;
            }
            Ok(())
        })
        .map_err(|error| cannot(error.into()))?;
        with_metadata.flush(out)?;
        with_metadata.commit()?;
        Ok(self.frames)
    }
}

/// [`WriteError::Encode`] about frame `frame` (or the file, when `None`) of `path`.
fn encode_error(path: &Path, frame: Option<u32>, error: EncoderError) -> WriteError {
    WriteError::Encode {
        path: path.to_owned(),
        frame,
        error,
    }
}
