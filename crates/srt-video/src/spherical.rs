//! 360° video: the Spherical Video V2 metadata (Google's RFC, as YouTube, VLC and headset
//! players read it) added to an MP4 written by the muxer, so that players show an
//! equirectangular video as a sphere around the viewer instead of a flat picture.
//!
//! Two boxes go into the video track's sample entry (`avc1`), after its `avcC`:
//! - `st3d` (a full box, version 0): one byte of stereo mode — 0 mono, 1 top-bottom (left eye
//!   on top), 2 left-right;
//! - `sv3d`: `svhd` (a full box: the metadata source, a NUL-terminated string) and `proj`,
//!   holding `prhd` (a full box: pose yaw, pitch and roll, 16.16 fixed point degrees, all 0) and
//!   `equi` (a full box: the projection bounds top, bottom, left, right, 0.32 fixed point, all 0
//!   for the full sphere).
//!
//! The boxes and every box around them grow by the inserted size; where the movie box comes
//! before the media data (as the muxer writes it), every chunk offset (`stco`, `co64`) moves
//! by that size too. The media data is copied as it is, in blocks.

use std::io::{self, Read, Write};

/// How the two eyes' pictures share one frame of a 360° video (`st3d`'s stereo mode).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StereoMode {
    /// One picture.
    Mono = 0,
    /// The left eye's picture above the right eye's.
    TopBottom = 1,
    /// The left eye's picture left of the right eye's.
    LeftRight = 2,
}

/// What `svhd` names as the metadata's source.
const METADATA_SOURCE: &str = "srt (Spherical Video V2)";

/// A box of `kind` holding `payload`.
fn boxed(kind: &[u8; 4], payload: &[u8]) -> Vec<u8> {
    // The boxes are a few dozen bytes.
    #[expect(clippy::cast_possible_truncation, reason = "metadata boxes are small")]
    let size = (8 + payload.len()) as u32;
    let mut out = Vec::with_capacity(8 + payload.len());
    out.extend_from_slice(&size.to_be_bytes());
    out.extend_from_slice(kind);
    out.extend_from_slice(payload);
    out
}

/// A full box (version 0, flags 0) of `kind` holding `payload`.
fn full_box(kind: &[u8; 4], payload: &[u8]) -> Vec<u8> {
    boxed(kind, &[&[0_u8; 4][..], payload].concat())
}

/// The `st3d` and `sv3d` boxes of an equirectangular video in `stereo` mode.
#[must_use]
pub fn spherical_boxes(stereo: StereoMode) -> Vec<u8> {
    let st3d = full_box(b"st3d", &[stereo as u8]);
    let svhd = full_box(b"svhd", &[METADATA_SOURCE.as_bytes(), &[0]].concat());
    let prhd = full_box(b"prhd", &[0_u8; 12]);
    let equi = full_box(b"equi", &[0_u8; 16]);
    let proj = boxed(b"proj", &[prhd, equi].concat());
    let sv3d = boxed(b"sv3d", &[svhd, proj].concat());
    [st3d, sv3d].concat()
}

/// Copies the MP4 `from` to `to` with [`spherical_boxes`] in its video sample entry.
///
/// # Errors
/// Reading or writing fails, or the file is not an MP4 with one `avc1` video sample entry in
/// its movie box (an [`io::ErrorKind::InvalidData`] error saying what is missing).
pub fn add_spherical_metadata(
    from: &mut impl Read,
    to: &mut impl Write,
    stereo: StereoMode,
) -> io::Result<()> {
    let inserted = spherical_boxes(stereo);
    let mut media_seen = false;
    let mut moov_done = false;
    while let Some((header, size)) = read_box_header(from)? {
        let kind = [header[4], header[5], header[6], header[7]];
        let body_size = size - header.len() as u64;
        if size == 0 {
            // A last box that runs to the end of the file.
            to.write_all(&header)?;
            io::copy(from, to)?;
            media_seen |= &kind == b"mdat";
            continue;
        }
        if &kind == b"moov" {
            let mut moov = header;
            from.take(body_size).read_to_end(&mut moov)?;
            let shift = if media_seen { 0 } else { inserted.len() as u64 };
            insert_into_sample_entry(&mut moov, &inserted, shift)?;
            to.write_all(&moov)?;
            moov_done = true;
        } else {
            media_seen |= &kind == b"mdat";
            to.write_all(&header)?;
            let copied = io::copy(&mut from.take(body_size), to)?;
            if copied != body_size {
                return Err(invalid("the MP4 ends inside a box"));
            }
        }
    }
    if moov_done {
        Ok(())
    } else {
        Err(invalid("the MP4 has no movie box (moov)"))
    }
}

/// The big-endian `u32` at `at` of `data`.
fn read_u32(data: &[u8], at: usize) -> u32 {
    u32::from_be_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]])
}

/// The big-endian `u64` at `at` of `data`.
fn read_u64(data: &[u8], at: usize) -> u64 {
    (u64::from(read_u32(data, at)) << 32) | u64::from(read_u32(data, at + 4))
}

/// An [`io::ErrorKind::InvalidData`] error.
fn invalid(message: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message.to_owned())
}

/// The next top-level box's header bytes and its whole size (0: it runs to the end of the
/// file), or `None` at the end.
fn read_box_header(from: &mut impl Read) -> io::Result<Option<(Vec<u8>, u64)>> {
    let mut header = vec![0_u8; 8];
    let mut filled = 0;
    while filled < 8 {
        let n = from.read(&mut header[filled..])?;
        if n == 0 {
            return if filled == 0 {
                Ok(None)
            } else {
                Err(invalid("the MP4 ends inside a box header"))
            };
        }
        filled += n;
    }
    let mut size = u64::from(read_u32(&header, 0));
    if size == 1 {
        let mut large = [0_u8; 8];
        from.read_exact(&mut large)?;
        header.extend_from_slice(&large);
        size = u64::from_be_bytes(large);
    }
    if size != 0 && size < header.len() as u64 {
        return Err(invalid("an MP4 box has a size smaller than its header"));
    }
    Ok(Some((header, size)))
}

/// The children of the box at `start` (of `size` bytes) of `data`: each (kind, start, size),
/// after `skip` bytes of the box's own fields following its 8-byte header.
fn children(
    data: &[u8],
    start: usize,
    size: usize,
    skip: usize,
) -> io::Result<Vec<([u8; 4], usize, usize)>> {
    let end = start + size;
    let mut at = start + 8 + skip;
    let mut found = Vec::new();
    while at + 8 <= end {
        let child_size = read_u32(data, at) as usize;
        if child_size < 8 || at + child_size > end {
            return Err(invalid(
                "a box in the movie box has a size that does not fit",
            ));
        }
        let kind = [data[at + 4], data[at + 5], data[at + 6], data[at + 7]];
        found.push((kind, at, child_size));
        at += child_size;
    }
    Ok(found)
}

/// The bytes of its own fields each box on the way to the sample entry has before its children.
fn fields_before_children(kind: &[u8; 4]) -> usize {
    match kind {
        b"stsd" => 8,  // version, flags and entry count
        b"avc1" => 78, // the visual sample entry's fields
        _ => 0,
    }
}

/// Inserts `inserted` at the end of the `avc1` sample entry in `moov` (a whole movie box),
/// growing every box around it, and adds `shift` to every chunk offset.
fn insert_into_sample_entry(moov: &mut Vec<u8>, inserted: &[u8], shift: u64) -> io::Result<()> {
    const PATH: [&[u8; 4]; 6] = [b"trak", b"mdia", b"minf", b"stbl", b"stsd", b"avc1"];
    let mut ancestors = vec![0_usize];
    let (mut start, mut size) = (0, moov.len());
    let mut kind = *b"moov";
    for wanted in &PATH {
        let (_, child_start, child_size) =
            children(moov, start, size, fields_before_children(&kind))?
                .into_iter()
                .find(|(child, ..)| child == *wanted)
                .ok_or_else(|| {
                    invalid(&format!(
                        "the MP4's movie box has no {} box on the way to the video sample entry",
                        String::from_utf8_lossy(*wanted)
                    ))
                })?;
        (start, size, kind) = (child_start, child_size, **wanted);
        ancestors.push(start);
    }
    #[expect(clippy::cast_possible_truncation, reason = "metadata boxes are small")]
    let grow = inserted.len() as u32;
    for &box_start in &ancestors {
        let old = read_u32(moov, box_start);
        moov[box_start..box_start + 4].copy_from_slice(&(old + grow).to_be_bytes());
    }
    let at = start + size;
    moov.splice(at..at, inserted.iter().copied());
    if shift > 0 {
        let whole = moov.len();
        shift_chunk_offsets(moov, 0, whole, shift)?;
    }
    Ok(())
}

/// Adds `shift` to every entry of the `stco` and `co64` boxes inside the box at `start`.
fn shift_chunk_offsets(moov: &mut [u8], start: usize, size: usize, shift: u64) -> io::Result<()> {
    for (kind, child, child_size) in children(moov, start, size, 0)? {
        match &kind {
            b"trak" | b"mdia" | b"minf" | b"stbl" => {
                shift_chunk_offsets(moov, child, child_size, shift)?;
            }
            b"stco" | b"co64" => {
                if child_size < 16 {
                    return Err(invalid("a chunk offset box is shorter than its header"));
                }
                let wide = &kind == b"co64";
                let count_at = child + 12;
                let count = read_u32(moov, count_at) as usize;
                let width = if wide { 8 } else { 4 };
                if count_at + 4 + count * width > child + child_size {
                    return Err(invalid("a chunk offset box is shorter than its entries"));
                }
                for entry in 0..count {
                    let at = count_at + 4 + entry * width;
                    if wide {
                        let old = read_u64(moov, at);
                        moov[at..at + 8].copy_from_slice(&(old + shift).to_be_bytes());
                    } else {
                        let old = read_u32(moov, at);
                        let new = u32::try_from(u64::from(old) + shift)
                            .map_err(|_| invalid("a chunk offset no longer fits 32 bits"))?;
                        moov[at..at + 4].copy_from_slice(&new.to_be_bytes());
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A movie box whose one track has an `avc1` sample entry (with an empty `avcC`) and a
    /// chunk offset table holding `offset`.
    fn movie(offset: u32) -> Vec<u8> {
        let avc1 = boxed(b"avc1", &[&[0_u8; 78][..], &boxed(b"avcC", &[])].concat());
        let stsd = boxed(b"stsd", &[&[0, 0, 0, 0, 0, 0, 0, 1][..], &avc1].concat());
        let stco = full_box(
            b"stco",
            &[1_u32.to_be_bytes(), offset.to_be_bytes()].concat(),
        );
        let stbl = boxed(b"stbl", &[stsd, stco].concat());
        let minf = boxed(b"minf", &stbl);
        let mdia = boxed(b"mdia", &minf);
        let trak = boxed(b"trak", &mdia);
        boxed(b"moov", &trak)
    }

    fn chunk_offset(file: &[u8]) -> u32 {
        let at = file
            .windows(4)
            .position(|w| w == b"stco")
            .expect("an stco box")
            + 12;
        read_u32(file, at)
    }

    #[test]
    fn chunk_offsets_move_only_when_the_movie_box_comes_first() {
        let media = boxed(b"mdat", b"frame data");
        let inserted = spherical_boxes(StereoMode::TopBottom).len();
        for movie_first in [true, false] {
            let ftyp = boxed(b"ftyp", b"isom");
            let file = if movie_first {
                let offset = (ftyp.len() + movie(0).len() + 8) as u32;
                [ftyp, movie(offset), media.clone()].concat()
            } else {
                [ftyp.clone(), media.clone(), movie((ftyp.len() + 8) as u32)].concat()
            };
            let mut out = Vec::new();
            add_spherical_metadata(&mut file.as_slice(), &mut out, StereoMode::TopBottom)
                .expect("added");
            assert_eq!(out.len(), file.len() + inserted);
            let data_at = chunk_offset(&out) as usize;
            assert_eq!(
                &out[data_at..data_at + 10],
                b"frame data",
                "movie first: {movie_first}"
            );
            let st3d = out.windows(4).position(|w| w == b"st3d").expect("st3d") - 4;
            assert_eq!(out[st3d + 12], 1, "top-bottom");
            let avc1 = out.windows(4).position(|w| w == b"avc1").expect("avc1") - 4;
            assert_eq!(
                read_u32(&out, avc1) as usize,
                8 + 78 + 8 + inserted,
                "avc1 grew"
            );
            let moov = out.windows(4).position(|w| w == b"moov").expect("moov") - 4;
            assert_eq!(
                read_u32(&out, moov) as usize,
                movie(0).len() + inserted,
                "moov grew"
            );
        }
    }

    #[test]
    fn a_file_without_a_video_sample_entry_is_refused() {
        let mut out = Vec::new();
        let no_movie = boxed(b"mdat", b"x");
        let error = add_spherical_metadata(&mut no_movie.as_slice(), &mut out, StereoMode::Mono)
            .expect_err("no moov");
        assert!(error.to_string().contains("moov"), "{error}");
        let empty_movie = boxed(b"moov", &boxed(b"trak", &[]));
        let error = add_spherical_metadata(&mut empty_movie.as_slice(), &mut out, StereoMode::Mono)
            .expect_err("no sample entry");
        assert!(error.to_string().contains("mdia"), "{error}");
    }
}
