//! A text record in the videos srt writes, and read back: srt keeps its record of how a video
//! was made there (the `key: value` lines of the srt command's provenance record, the same text
//! a PNG holds in its `srt` iTXt chunk), so `srt info` prints it for a video as for an image.
//!
//! - MP4: a QuickTime user-data text box, the comment `©cmt` (0xA9 `cmt`), in the movie's user
//!   data box: `moov/udta/©cmt`, holding a 16-bit text length, a 16-bit language code (`und`,
//!   packed ISO 639-2/T) and the UTF-8 text. Players skip it; ffprobe shows it as the file's
//!   `comment` tag.
//! - GIF: a comment extension (0x21 0xFE), the text in sub-blocks of at most 255 bytes, written
//!   after the last frame, before the trailer (GIF89a lets a comment stand between any blocks).
//!
//! Reading walks the whole file's structure (an MP4's top-level boxes by their sizes, a GIF's
//! blocks with the gif crate's streaming decoder, its pixels not decoded), so a file cut short
//! anywhere is an error, not a missing record.

use std::io::{self, BufRead as _, BufReader, Read, Seek, SeekFrom};

use crate::VideoFormat;
use crate::mp4box::{boxed, children, insert_at, invalid, read_box_header};

/// The QuickTime comment box's type, `©cmt`.
const COMMENT: [u8; 4] = [0xA9, b'c', b'm', b't'];
/// The language of the comment: `und` (undetermined), ISO 639-2/T packed in 5-bit letters.
const UNDETERMINED: u16 = 0x55C4;
/// The GIF comment extension's label.
const GIF_COMMENT: u8 = 0xFE;

/// The video format a file's first bytes (at least 12) show: an MP4 has an `ftyp` box first,
/// a GIF starts with `GIF87a` or `GIF89a`.
#[must_use]
pub fn video_format_of(start: &[u8]) -> Option<VideoFormat> {
    if start.get(4..8) == Some(b"ftyp") {
        Some(VideoFormat::Mp4)
    } else if start.starts_with(b"GIF87a") || start.starts_with(b"GIF89a") {
        Some(VideoFormat::Gif)
    } else {
        None
    }
}

/// Adds a `©cmt` box holding `text` to the user data box of `moov` (a whole movie box, as
/// [`crate::mp4box::rewrite_movie`] hands it), making the user data box if there is none.
pub(crate) fn add_mp4_comment(moov: &mut Vec<u8>, text: &str) -> io::Result<()> {
    let length = u16::try_from(text.len())
        .map_err(|_| invalid("the record is longer than an MP4 comment holds (65535 bytes)"))?;
    let comment = boxed(
        &COMMENT,
        &[
            &length.to_be_bytes()[..],
            &UNDETERMINED.to_be_bytes(),
            text.as_bytes(),
        ]
        .concat(),
    );
    let whole = moov.len();
    match children(moov, 0, whole, 0)?
        .into_iter()
        .find(|(kind, ..)| kind == b"udta")
    {
        Some((_, udta, size)) => insert_at(moov, &[0, udta], udta + size, &comment),
        None => insert_at(moov, &[0], whole, &boxed(b"udta", &comment)),
    }
    Ok(())
}

/// Writes `text` as a comment extension of the GIF being encoded.
pub(crate) fn write_gif_comment<W: io::Write>(
    encoder: &mut gif::Encoder<W>,
    text: &str,
) -> Result<(), gif::EncodingError> {
    encoder.write_raw_extension(gif::AnyExtension(GIF_COMMENT), &[text.as_bytes()])
}

/// The comments (`©cmt` boxes directly in the movie's user data box) of the MP4 `file`, in
/// order; empty when it has none.
///
/// # Errors
/// Reading fails, or the file is not a whole MP4: a box runs past the end of the file (it was
/// cut short), there is no movie box, or a box in it does not fit (an
/// [`io::ErrorKind::InvalidData`] error saying which).
pub fn read_mp4_comments(file: &mut (impl Read + Seek)) -> io::Result<Vec<String>> {
    let length = file.seek(SeekFrom::End(0))?;
    file.seek(SeekFrom::Start(0))?;
    let mut at = 0_u64;
    let mut moov = None;
    while at < length {
        let Some((header, size)) = read_box_header(file)? else {
            break;
        };
        let kind = [header[4], header[5], header[6], header[7]];
        let size = if size == 0 { length - at } else { size };
        if at + size > length {
            return Err(invalid(&format!(
                "the MP4 is cut short: its {} box needs {size} bytes and {} are left",
                kind.escape_ascii(),
                length - at
            )));
        }
        if &kind == b"moov" && moov.is_none() {
            let mut whole = header.clone();
            file.take(size - header.len() as u64)
                .read_to_end(&mut whole)?;
            moov = Some((whole, header.len() - 8));
        } else {
            file.seek(SeekFrom::Start(at + size))?;
        }
        at += size;
    }
    let Some((moov, wide_header)) = moov else {
        return Err(invalid("the MP4 has no movie box (moov)"));
    };
    let mut comments = Vec::new();
    for (_, udta, udta_size) in children(&moov, 0, moov.len(), wide_header)?
        .into_iter()
        .filter(|(kind, ..)| kind == b"udta")
    {
        for (_, comment, size) in children(&moov, udta, udta_size, 0)?
            .into_iter()
            .filter(|(kind, ..)| kind == &COMMENT)
        {
            let body = &moov[comment + 8..comment + size];
            let text = body
                .get(..2)
                .map(|n| usize::from(u16::from_be_bytes([n[0], n[1]])))
                .and_then(|n| body.get(4..4 + n))
                .ok_or_else(|| invalid("the MP4's comment box is shorter than its text"))?;
            comments.push(String::from_utf8_lossy(text).into_owned());
        }
    }
    Ok(comments)
}

/// The comment extensions of the GIF `reader`, in order; empty when it has none.
///
/// # Errors
/// Reading fails, or the file is not a whole GIF: it ends before its trailer (it was cut
/// short) or the gif crate's decoder finds it malformed (an [`io::ErrorKind::InvalidData`]
/// error saying why).
pub fn read_gif_comments(reader: impl Read) -> io::Result<Vec<String>> {
    use gif::streaming_decoder::{Block, Decoded, OutputBuffer, StreamingDecoder};
    let mut reader = BufReader::new(reader);
    let mut decoder = StreamingDecoder::new();
    let mut comments = Vec::new();
    let mut current = Vec::new();
    loop {
        let buffer = reader.fill_buf()?;
        if buffer.is_empty() {
            return Err(invalid("the GIF is cut short: it ends before its trailer"));
        }
        let (used, decoded) = decoder
            .update(buffer, &mut OutputBuffer::None)
            .map_err(|error| invalid(&format!("the GIF is malformed: {error}")))?;
        match decoded {
            Decoded::SubBlock { ext, is_last } if ext.0 == GIF_COMMENT => {
                current.extend_from_slice(decoder.last_ext_sub_block());
                if is_last {
                    comments.push(String::from_utf8_lossy(&current).into_owned());
                    current.clear();
                }
            }
            Decoded::BlockStart(Block::Trailer) => return Ok(comments),
            _ => {}
        }
        reader.consume(used);
    }
}

/// The comments of the video `file` in `format` ([`read_mp4_comments`], [`read_gif_comments`]).
///
/// # Errors
/// As those.
pub fn read_comments(
    file: &mut (impl Read + Seek),
    format: VideoFormat,
) -> io::Result<Vec<String>> {
    match format {
        VideoFormat::Mp4 => read_mp4_comments(file),
        VideoFormat::Gif => read_gif_comments(file),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mp4box::read_u32;

    /// A record long enough to need several GIF sub-blocks, with a line break and a non-ASCII
    /// character.
    fn text() -> String {
        format!("srt version: 0.1.0\nscene: ß {}\n", "x".repeat(600))
    }

    #[test]
    fn an_mp4_comment_reads_back_and_grows_the_boxes_around_it() {
        for existing in [None, Some(boxed(b"udta", &boxed(b"name", b"n")))] {
            let mut moov = boxed(b"moov", &existing.clone().unwrap_or_default());
            add_mp4_comment(&mut moov, &text()).expect("added");
            assert_eq!(read_u32(&moov, 0) as usize, moov.len(), "moov grew");
            let file = [boxed(b"ftyp", b"isom"), moov.clone(), boxed(b"mdat", b"d")].concat();
            let comments = read_mp4_comments(&mut io::Cursor::new(&file)).expect("read");
            assert_eq!(comments, [text()], "existing udta: {}", existing.is_some());
            let udtas = children(&moov, 0, moov.len(), 0).unwrap();
            assert_eq!(udtas.len(), 1, "one user data box");
        }
    }

    #[test]
    fn a_cut_or_foreign_mp4_is_an_error_naming_the_reason() {
        let file = [
            boxed(b"ftyp", b"isom"),
            boxed(b"moov", &[]),
            boxed(b"mdat", &[7; 100]),
        ]
        .concat();
        assert_eq!(
            read_mp4_comments(&mut io::Cursor::new(&file)).expect("whole"),
            Vec::<String>::new()
        );
        let cut = &file[..file.len() - 10];
        let error = read_mp4_comments(&mut io::Cursor::new(cut)).expect_err("cut");
        assert_eq!(
            error.to_string(),
            "the MP4 is cut short: its mdat box needs 108 bytes and 98 are left"
        );
        let no_movie = [boxed(b"ftyp", b"isom"), boxed(b"mdat", &[])].concat();
        let error = read_mp4_comments(&mut io::Cursor::new(&no_movie)).expect_err("no moov");
        assert!(error.to_string().contains("no movie box"), "{error}");
    }

    #[test]
    fn a_gif_comment_reads_back_and_a_cut_gif_is_an_error() {
        let mut bytes = Vec::new();
        {
            let mut encoder = gif::Encoder::new(&mut bytes, 2, 2, &[]).unwrap();
            let frame = gif::Frame::from_rgb(2, 2, &[9; 12]);
            encoder.write_frame(&frame).unwrap();
            write_gif_comment(&mut encoder, &text()).unwrap();
            encoder.into_inner().unwrap();
        }
        assert_eq!(video_format_of(&bytes), Some(VideoFormat::Gif));
        assert_eq!(read_gif_comments(bytes.as_slice()).expect("read"), [text()]);
        let error = read_gif_comments(&bytes[..bytes.len() - 1]).expect_err("cut");
        assert!(error.to_string().contains("cut short"), "{error}");
    }
}
