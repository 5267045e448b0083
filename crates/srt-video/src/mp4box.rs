//! The MP4 box walk shared by the metadata srt adds to the muxer's file ([`crate::spherical`],
//! [`crate::record`]): box headers (32-bit size, or 1 and a 64-bit `largesize`, or 0 for a box
//! that runs to the end of the file), a box's children, and one copy pass that edits the movie
//! box (`moov`) in memory while the media data is copied as it is, in blocks. Where the movie
//! box comes before the media data (as the muxer writes it), every chunk offset (`stco`, `co64`)
//! moves by what the movie box grew.

use std::io::{self, Read, Write};

/// A box of `kind` holding `payload`.
pub(crate) fn boxed(kind: &[u8; 4], payload: &[u8]) -> Vec<u8> {
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
pub(crate) fn full_box(kind: &[u8; 4], payload: &[u8]) -> Vec<u8> {
    boxed(kind, &[&[0_u8; 4][..], payload].concat())
}

/// The big-endian `u32` at `at` of `data`.
pub(crate) fn read_u32(data: &[u8], at: usize) -> u32 {
    u32::from_be_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]])
}

/// The big-endian `u64` at `at` of `data`.
pub(crate) fn read_u64(data: &[u8], at: usize) -> u64 {
    (u64::from(read_u32(data, at)) << 32) | u64::from(read_u32(data, at + 4))
}

/// An [`io::ErrorKind::InvalidData`] error.
pub(crate) fn invalid(message: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message.to_owned())
}

/// The next top-level box's header bytes and its whole size (0: it runs to the end of the
/// file), or `None` at the end.
pub(crate) fn read_box_header(from: &mut impl Read) -> io::Result<Option<(Vec<u8>, u64)>> {
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
        from.read_exact(&mut large).map_err(|error| {
            if error.kind() == io::ErrorKind::UnexpectedEof {
                invalid("the MP4 ends inside a box header")
            } else {
                error
            }
        })?;
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
///
/// # Errors
/// A child's size is smaller than a header or runs past the box.
pub(crate) fn children(
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

/// Inserts `inserted` into `moov` (a whole movie box) at `at`, growing the 32-bit size of each
/// box that starts at one of `ancestors` (the boxes around `at`, the movie box's 0 included).
pub(crate) fn insert_at(moov: &mut Vec<u8>, ancestors: &[usize], at: usize, inserted: &[u8]) {
    #[expect(clippy::cast_possible_truncation, reason = "metadata boxes are small")]
    let grow = inserted.len() as u32;
    for &box_start in ancestors {
        let old = read_u32(moov, box_start);
        moov[box_start..box_start + 4].copy_from_slice(&(old + grow).to_be_bytes());
    }
    moov.splice(at..at, inserted.iter().copied());
}

/// Copies the MP4 `from` to `to` with its movie box changed by `edit` (which gets the whole box,
/// its 8-byte header included, and keeps every box size in it right); when the movie box comes
/// before the media data, every chunk offset moves by what it grew.
///
/// # Errors
/// Reading or writing fails, `edit` fails, or the file is not an MP4 with one movie box of a
/// 32-bit size (an [`io::ErrorKind::InvalidData`] error saying what is wrong).
pub(crate) fn rewrite_movie(
    from: &mut impl Read,
    to: &mut impl Write,
    edit: impl FnOnce(&mut Vec<u8>) -> io::Result<()>,
) -> io::Result<()> {
    let mut edit = Some(edit);
    let mut media_seen = false;
    while let Some((header, size)) = read_box_header(from)? {
        let kind = [header[4], header[5], header[6], header[7]];
        let body_size = size.saturating_sub(header.len() as u64);
        if size == 0 {
            // A last box that runs to the end of the file.
            to.write_all(&header)?;
            io::copy(from, to)?;
            media_seen |= &kind == b"mdat";
            continue;
        }
        if &kind == b"moov" {
            let Some(edit) = edit.take() else {
                return Err(invalid("the MP4 has two movie boxes (moov)"));
            };
            if header.len() != 8 {
                return Err(invalid("the MP4's movie box has a 64-bit size"));
            }
            let mut moov = header;
            from.take(body_size).read_to_end(&mut moov)?;
            if moov.len() as u64 != size {
                return Err(invalid("the MP4 ends inside a box"));
            }
            edit(&mut moov)?;
            let grown = moov.len() as u64 - size;
            if !media_seen && grown > 0 {
                let whole = moov.len();
                shift_chunk_offsets(&mut moov, 0, whole, grown)?;
            }
            to.write_all(&moov)?;
        } else {
            media_seen |= &kind == b"mdat";
            to.write_all(&header)?;
            let copied = io::copy(&mut from.take(body_size), to)?;
            if copied != body_size {
                return Err(invalid("the MP4 ends inside a box"));
            }
        }
    }
    if edit.is_none() {
        Ok(())
    } else {
        Err(invalid("the MP4 has no movie box (moov)"))
    }
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
