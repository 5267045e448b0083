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
//! The boxes and every box around them grow by the inserted size; the file is copied by
//! `mp4box.rs`'s pass, which moves the chunk offsets.

use std::io::{self, Read, Write};

use crate::mp4box::{boxed, children, full_box, insert_at, invalid, rewrite_movie};

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
    rewrite_movie(from, to, |moov| {
        insert_into_sample_entry(moov, &spherical_boxes(stereo))
    })
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
/// growing every box around it.
pub(crate) fn insert_into_sample_entry(moov: &mut Vec<u8>, inserted: &[u8]) -> io::Result<()> {
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
    insert_at(moov, &ancestors, start + size, inserted);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mp4box::read_u32;

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
