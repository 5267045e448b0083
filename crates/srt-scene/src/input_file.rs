//! Reading the files a scene names — scene files, models with their buffers and material
//! libraries, texture images — through one door: [`read`].
//!
//! It refuses what is not a regular file after following symbolic links (a folder, a device
//! such as `/dev/zero`, a FIFO, a socket) without opening it, refuses files larger than the cap
//! of their [`FileKind`], and reads through a bounded reader, so a file that grows between the
//! size check and the read still cannot make srt read more than the cap.

use std::fs::{File, Metadata};
use std::io::Read as _;
use std::path::Path;

/// One mebibyte, for the caps below.
const MIB: u64 = 1 << 20;

/// The largest scene file.
pub const MAX_SCENE_FILE_BYTES: u64 = MIB;

/// The largest model file, glTF buffer or material library (a 2-million-triangle binary STL
/// has 100 MB; an ASCII STL about 250 bytes per triangle).
pub const MAX_MODEL_FILE_BYTES: u64 = 256 * MIB;

/// The largest texture image file.
pub const MAX_IMAGE_FILE_BYTES: u64 = 64 * MIB;

/// The most bytes a star file may have (room for a million stars of 60 characters).
pub const MAX_STAR_FILE_BYTES: u64 = 64 * MIB;

/// What a file is read as; decides its size cap and what messages call it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A TOML scene file ([`MAX_SCENE_FILE_BYTES`]).
    Scene,
    /// A model file, a glTF buffer or an MTL material library ([`MAX_MODEL_FILE_BYTES`]).
    Model,
    /// A texture image ([`MAX_IMAGE_FILE_BYTES`]).
    Image,
    /// A CSV file of stars ([`MAX_STAR_FILE_BYTES`]).
    Stars,
}

impl FileKind {
    /// The most bytes a file of this kind may have.
    #[must_use]
    pub const fn max_bytes(self) -> u64 {
        match self {
            Self::Scene => MAX_SCENE_FILE_BYTES,
            Self::Model => MAX_MODEL_FILE_BYTES,
            Self::Image => MAX_IMAGE_FILE_BYTES,
            Self::Stars => MAX_STAR_FILE_BYTES,
        }
    }

    /// What messages call a file of this kind.
    #[must_use]
    pub const fn noun(self) -> &'static str {
        match self {
            Self::Scene => "scene file",
            Self::Model => "model file",
            Self::Image => "texture image",
            Self::Stars => "star file",
        }
    }
}

/// Why a file was not read. The message says why in words; the caller names the file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum InputFileError {
    /// The operating system could not open or read it (missing, no permission…).
    #[error("{}", crate::message::io_reason(.0))]
    Io(#[from] std::io::Error),
    /// It is a folder.
    #[error("it is a folder, not a file")]
    Folder,
    /// It is a device, FIFO, socket or other special file.
    #[error("it is {0}, not a regular file")]
    NotRegular(&'static str),
    /// It is larger than its kind allows.
    #[error("it has {size} bytes, more than the {max} bytes a {noun} may have")]
    TooLarge {
        /// Its size in bytes (at least `max + 1` if it grew while being read).
        size: u64,
        /// The cap.
        max: u64,
        /// What it was read as.
        noun: &'static str,
    },
    /// A text file is not UTF-8.
    #[error("it is not UTF-8 text")]
    NotText,
}

/// Reads the whole file at `path` (following symbolic links) as a file of `kind`.
///
/// # Errors
/// [`InputFileError`] if it cannot be opened or read, is not a regular file, or has more bytes
/// than `kind` allows.
pub fn read(path: &Path, kind: FileKind) -> Result<Vec<u8>, InputFileError> {
    // Checked before opening: opening a FIFO blocks until someone writes to it.
    check_metadata(&std::fs::metadata(path)?, kind)?;
    let file = File::open(path)?;
    // Checked again on what was opened, in case the path changed in between.
    let metadata = file.metadata()?;
    check_metadata(&metadata, kind)?;
    let max = kind.max_bytes();
    let expected = usize::try_from(metadata.len().min(max)).unwrap_or(0);
    let mut bytes = Vec::with_capacity(expected);
    file.take(max + 1).read_to_end(&mut bytes)?;
    let size = u64::try_from(bytes.len()).unwrap_or(u64::MAX);
    if size > max {
        return Err(too_large(size, kind));
    }
    Ok(bytes)
}

/// Reads the file at `path` as UTF-8 text (a leading byte-order mark is dropped), like [`read`].
///
/// # Errors
/// As [`read`], and [`InputFileError::NotText`] if it is not UTF-8.
pub fn read_text(path: &Path, kind: FileKind) -> Result<String, InputFileError> {
    let mut bytes = read(path, kind)?;
    if bytes.starts_with(b"\xef\xbb\xbf") {
        bytes.drain(..3);
    }
    String::from_utf8(bytes).map_err(|_| InputFileError::NotText)
}

/// The error of a file of `size` bytes, more than `kind` allows.
pub(crate) fn too_large(size: u64, kind: FileKind) -> InputFileError {
    InputFileError::TooLarge {
        size,
        max: kind.max_bytes(),
        noun: kind.noun(),
    }
}

/// Refuses what is not a regular file, or is too large for `kind`.
fn check_metadata(metadata: &Metadata, kind: FileKind) -> Result<(), InputFileError> {
    let file_type = metadata.file_type();
    if file_type.is_dir() {
        return Err(InputFileError::Folder);
    }
    if !file_type.is_file() {
        return Err(InputFileError::NotRegular(special_kind(&file_type)));
    }
    if metadata.len() > kind.max_bytes() {
        return Err(too_large(metadata.len(), kind));
    }
    Ok(())
}

/// What kind of special file `file_type` is, in words.
#[cfg(unix)]
fn special_kind(file_type: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt as _;
    if file_type.is_char_device() {
        "a character device"
    } else if file_type.is_block_device() {
        "a block device"
    } else if file_type.is_fifo() {
        "a FIFO (named pipe)"
    } else if file_type.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

/// What kind of special file `file_type` is, in words.
#[cfg(not(unix))]
fn special_kind(_file_type: &std::fs::FileType) -> &'static str {
    "a special file"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_files_are_read_and_folders_refused() {
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
        let bytes = read(&manifest.join("Cargo.toml"), FileKind::Scene).unwrap();
        assert!(bytes.starts_with(b"[package]"));
        let error = read(manifest, FileKind::Model).unwrap_err();
        assert_eq!(error.to_string(), "it is a folder, not a file");
        let error = read(&manifest.join("no such file"), FileKind::Model).unwrap_err();
        assert!(matches!(error, InputFileError::Io(_)), "{error}");
    }

    #[test]
    fn too_large_files_are_refused_by_size() {
        let error = too_large(5 << 20, FileKind::Scene);
        assert_eq!(
            error.to_string(),
            "it has 5242880 bytes, more than the 1048576 bytes a scene file may have"
        );
    }

    #[cfg(unix)]
    #[test]
    fn devices_are_refused_without_reading() {
        let error = read(Path::new("/dev/zero"), FileKind::Image).unwrap_err();
        assert_eq!(
            error.to_string(),
            "it is a character device, not a regular file"
        );
    }
}
