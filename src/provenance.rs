//! How an image or video was made: the scene (name, or file name and SHA-256 of its content),
//! observation time, velocities, effects, view, renderer and srt version, stored in every PNG (an
//! iTXt chunk), EXR (a text attribute), MP4 (the user-data comment `moov/udta/©cmt`) and GIF (a
//! comment extension) that `srt render` and `srt encode` write ([`srt_video::read_comments`] says
//! how a video holds it), and printed by `srt info` (with, for an EXR, the range of its pixels:
//! [`crate::exr_range`]). A video's record is its frames' ([`Provenance::for_video`]).
//!
//! The record is one text block of `key: value` lines under the name [`KEY`], so its bytes do not
//! depend on the order a container keeps its entries in. It holds nothing that differs between
//! machines or runs (no clock, host or folder), so a frame is byte-identical whichever machine of
//! a cluster renders it.

use std::fs::File;
use std::io::{BufReader, Read as _, Seek as _};
use std::path::Path;

use anyhow::{anyhow, bail};
use srt_scene::message::io_reason;

use crate::exr_range::PixelRange;

/// The PNG keyword and EXR attribute name the record is stored under (a video's comment holds
/// the text alone, recognised by its first entry, [`VERSION_KEY`]).
pub const KEY: &str = "srt";

/// The first entry of every record: the version of srt that wrote it.
const VERSION_KEY: &str = "srt version";

/// The entries of one frame's record that a video's record states for all its frames instead.
const FRAME_KEYS: [&str; 3] = ["time", "frame", "exr channels"];

/// The first bytes of a PNG file.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
/// The first bytes of an OpenEXR file.
const EXR_MAGIC: &[u8] = &[0x76, 0x2f, 0x31, 0x01];

/// An ordered list of `key: value` entries describing how an image was made.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Provenance {
    entries: Vec<(String, String)>,
}

impl Provenance {
    /// A record that starts with the srt version.
    #[must_use]
    pub fn new() -> Self {
        let mut record = Self::default();
        record.push(VERSION_KEY, env!("CARGO_PKG_VERSION"));
        record
    }

    /// The value of the first entry named `key`.
    #[must_use]
    pub fn get(&self, key: &str) -> Option<&str> {
        self.entries().find(|(k, _)| *k == key).map(|(_, v)| v)
    }

    /// The record of a video of `count` frames at `fps` frames per second whose first and last
    /// frames were made as `first` and `last` say: `first`'s entries but its frame's own (time,
    /// frame number, EXR channels), then the time and frame range from `first` to `last` (where
    /// both state them) and the video's frames. `joined` says how the frames became a video.
    #[must_use]
    pub fn for_video(first: &Self, last: &Self, count: usize, fps: u32, joined: &str) -> Self {
        let mut record = Self {
            entries: (first.entries.iter())
                .filter(|(key, _)| !FRAME_KEYS.contains(&key.as_str()))
                .cloned()
                .collect(),
        };
        if let (Some(t0), Some(t1)) = (first.get("time"), last.get("time")) {
            record.push("time", format!("{t0} to {t1}"));
        }
        // A numbered frame's record says "N of 0 to LAST".
        if let (Some(a), Some(b)) = (first.get("frame"), last.get("frame")) {
            let (a, all) = a.split_once(" of ").unwrap_or((a, ""));
            let b = b.split_once(" of ").map_or(b, |(b, _)| b);
            let of = if all.is_empty() {
                String::new()
            } else {
                format!(" of {all}")
            };
            record.push("frames", format!("{a} to {b}{of}"));
        }
        record.push("video", format!("{count} frames at {fps} fps, {joined}"));
        record
    }
    /// Appends an entry; line breaks and other control characters in `value` become spaces so
    /// that every entry stays one line.
    pub fn push(&mut self, key: &str, value: impl Into<String>) {
        let value: String = value
            .into()
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        self.entries.push((key.to_owned(), value));
    }

    /// This record followed by `more`'s entries.
    #[must_use]
    pub fn with(&self, more: &[(&str, String)]) -> Self {
        let mut record = self.clone();
        for (key, value) in more {
            record.push(key, value.clone());
        }
        record
    }

    /// The entries in order.
    pub fn entries(&self) -> impl Iterator<Item = (&str, &str)> {
        self.entries.iter().map(|(k, v)| (k.as_str(), v.as_str()))
    }

    /// The record as stored: one `key: value` line per entry.
    #[must_use]
    pub fn to_text(&self) -> String {
        self.entries
            .iter()
            .map(|(key, value)| format!("{key}: {value}\n"))
            .collect()
    }

    /// Parses a stored record; lines without `": "` are ignored.
    #[must_use]
    pub fn from_text(text: &str) -> Self {
        let entries = text
            .lines()
            .filter_map(|line| line.split_once(": "))
            .map(|(key, value)| (key.to_owned(), value.to_owned()))
            .collect();
        Self { entries }
    }

    /// Reads the record from a PNG, EXR, MP4 or GIF file (recognised by its first bytes, not its
    /// name).
    ///
    /// # Errors
    /// If the file cannot be read, is none of those (or a video cut short or malformed), or holds
    /// no srt record; the message names the file and the reason.
    pub fn read(path: &Path) -> anyhow::Result<Self> {
        let cannot_read = |error: &std::io::Error| {
            anyhow!("cannot read {} ({})", path.display(), io_reason(error))
        };
        let mut start = [0_u8; 12];
        let mut file = File::open(path).map_err(|e| cannot_read(&e))?;
        let length = read_up_to(&mut file, &mut start).map_err(|e| cannot_read(&e))?;
        let start = &start[..length];
        file.rewind().map_err(|e| cannot_read(&e))?;
        let text = if start.starts_with(PNG_SIGNATURE) {
            png_record(file)
        } else if start.starts_with(EXR_MAGIC) {
            exr_record(file)
        } else if let Some(format) = srt_video::video_format_of(start) {
            video_record(file, format)
        } else {
            bail!(
                "{} is not a PNG or EXR image, nor an MP4 or GIF video",
                path.display()
            );
        }
        .map_err(|reason| anyhow!("cannot read {} ({reason})", path.display()))?;
        match text {
            Some(text) if !text.trim().is_empty() => Ok(Self::from_text(&text)),
            _ => bail!(
                "{} has no srt record of how it was made (srt render and srt encode write one)",
                path.display()
            ),
        }
    }
}

/// Fills as much of `buffer` as the file has; returns how many bytes were read.
fn read_up_to(file: &mut File, buffer: &mut [u8]) -> std::io::Result<usize> {
    let mut filled = 0;
    while filled < buffer.len() {
        match file.read(&mut buffer[filled..])? {
            0 => break,
            n => filled += n,
        }
    }
    Ok(filled)
}

/// The text of the PNG's iTXt chunk [`KEY`] (only the chunks before the image data are read).
fn png_record(file: File) -> Result<Option<String>, String> {
    let reader = png::Decoder::new(BufReader::new(file))
        .read_info()
        .map_err(|error| error.to_string())?;
    reader
        .info()
        .utf8_text
        .iter()
        .find(|chunk| chunk.keyword == KEY)
        .map(|chunk| chunk.get_text().map_err(|error| error.to_string()))
        .transpose()
}

/// The srt record among the comments of a video (the first that starts with [`VERSION_KEY`]).
fn video_record(mut file: File, format: srt_video::VideoFormat) -> Result<Option<String>, String> {
    let comments = srt_video::read_comments(&mut file, format).map_err(|error| {
        if error.kind() == std::io::ErrorKind::InvalidData {
            error.to_string()
        } else {
            io_reason(&error)
        }
    })?;
    let srt_comment = |text: &String| text.starts_with(&format!("{VERSION_KEY}: "));
    Ok(comments.into_iter().find(srt_comment))
}

/// The text attribute [`KEY`] of the EXR's first header (the pixels are not read).
fn exr_record(file: File) -> Result<Option<String>, String> {
    let meta = exr::meta::MetaData::read_from_buffered(BufReader::new(file), false)
        .map_err(|error| error.to_string())?;
    let key = exr::prelude::Text::from(KEY);
    Ok(meta.headers.first().and_then(|header| {
        [
            &header.own_attributes.other,
            &header.shared_attributes.other,
        ]
        .into_iter()
        .find_map(|attributes| match attributes.get(&key) {
            Some(exr::meta::attribute::AttributeValue::Text(text)) => {
                Some(String::from_utf8_lossy(text.bytes()).into_owned())
            }
            _ => None,
        })
    }))
}

/// Runs `srt info FILE` (an image or a video): prints the record, one aligned `key  value` line per entry.
///
/// # Errors
/// As [`Provenance::read`].
pub fn print_info(path: &Path) -> anyhow::Result<()> {
    let record = Provenance::read(path)?;
    let mut lines: Vec<(String, String)> = record
        .entries()
        .map(|(key, value)| (key.to_owned(), value.to_owned()))
        .collect();
    if is_exr(path)? {
        let range = PixelRange::read(path)?;
        lines.extend((range.lines().into_iter()).map(|(key, value)| (key.to_owned(), value)));
        lines.extend(crate::exr_range::aov_lines(path)?);
    }
    crate::listing::print_rows(lines.iter().map(|(k, v)| (k.as_str(), v.as_str())))?;
    Ok(())
}

/// Whether the file at `path` starts as an OpenEXR image does.
fn is_exr(path: &Path) -> anyhow::Result<bool> {
    let mut start = [0_u8; 4];
    let read = File::open(path)
        .and_then(|mut file| read_up_to(&mut file, &mut start))
        .map_err(|error| anyhow!("cannot read {} ({})", path.display(), io_reason(&error)))?;
    Ok(start[..read].starts_with(EXR_MAGIC))
}

#[cfg(test)]
mod tests {
    use super::Provenance;

    /// The stored text parses back to the same entries, values with ": " included.
    #[test]
    fn text_round_trips() {
        let mut record = Provenance::new();
        record.push("scene", "a: b.toml");
        record.push("velocities", "cube (0, 0.9, 0)\nsneaky line");
        let parsed = Provenance::from_text(&record.to_text());
        assert_eq!(parsed, record);
        assert_eq!(
            parsed.entries().nth(2),
            Some(("velocities", "cube (0, 0.9, 0) sneaky line"))
        );
    }
}
