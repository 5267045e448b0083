//! Files that appear complete or not at all: written to a temporary file in the destination's
//! folder (with the permissions any new file gets there) and renamed into place when finished;
//! dropped before that, the temporary file is removed and the destination is untouched. A
//! process ended by a signal drops nothing: its handler calls [`remove_partial_files`], which
//! removes every temporary file an [`AtomicFile`] still holds.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use tempfile::NamedTempFile;

use crate::WriteError;

/// A new, empty temporary file in `path`'s folder (removed when dropped), created with the
/// permissions any new file gets there: 0o666 less the umask on Unix, not `tempfile`'s private
/// 0o600, which would otherwise survive the rename into place.
///
/// # Errors
/// [`WriteError::CreateFile`] if no file can be created there; the message names `path`, the
/// folder and the reason.
pub fn temporary_file_beside(path: &Path) -> Result<NamedTempFile, WriteError> {
    let folder = parent_folder(path);
    let mut builder = tempfile::Builder::new();
    builder.prefix(".srt-").suffix(".partial");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder
        .tempfile_in(folder)
        .map_err(|error| WriteError::CreateFile {
            path: path.to_owned(),
            folder: folder.to_owned(),
            error,
        })
}

/// The folder `path` is in (`.` for a bare file name).
#[must_use]
pub fn parent_folder(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A file being written in its destination's folder: [`AtomicFile::commit`] renames it into
/// place; dropped before that (an error, a panic), it is removed and the destination is
/// untouched.
#[derive(Debug)]
pub struct AtomicFile {
    temp: NamedTempFile,
    path: PathBuf,
    /// Keeps the temporary file in [`PARTIAL_FILES`] while it exists.
    _listed: Listed,
}

/// The temporary files of every [`AtomicFile`] not yet committed or dropped.
static PARTIAL_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes every temporary file an [`AtomicFile`] of this process still holds (best effort: a
/// file already gone is no error): what a signal handler calls before the process exits, so
/// that an interrupted render leaves the folder as it was. Returns how many were removed.
pub fn remove_partial_files() -> usize {
    let listed = PARTIAL_FILES.lock().map_or_else(
        |poisoned| poisoned.into_inner().clone(),
        |files| files.clone(),
    );
    listed
        .iter()
        .filter(|path| std::fs::remove_file(path).is_ok())
        .count()
}

/// A temporary file's entry in [`PARTIAL_FILES`], removed when dropped.
#[derive(Debug)]
struct Listed(PathBuf);

impl Listed {
    /// Lists `path`.
    fn new(path: &Path) -> Self {
        if let Ok(mut files) = PARTIAL_FILES.lock() {
            files.push(path.to_owned());
        }
        Self(path.to_owned())
    }
}

impl Drop for Listed {
    fn drop(&mut self) {
        if let Ok(mut files) = PARTIAL_FILES.lock() {
            files.retain(|path| *path != self.0);
        }
    }
}

impl AtomicFile {
    /// Starts writing `path`.
    ///
    /// # Errors
    /// [`WriteError::CreateFile`] if no file can be created in `path`'s folder.
    pub fn create(path: &Path) -> Result<Self, WriteError> {
        let temp = temporary_file_beside(path)?;
        Ok(Self {
            _listed: Listed::new(temp.path()),
            temp,
            path: path.to_owned(),
        })
    }

    /// A buffered writer to the temporary file; finish it with [`AtomicFile::flush`].
    ///
    /// # Errors
    /// [`WriteError::Io`] if the file handle cannot be duplicated.
    pub fn writer(&self) -> Result<BufWriter<File>, WriteError> {
        let file = self
            .temp
            .as_file()
            .try_clone()
            .map_err(|error| self.io_error(error))?;
        Ok(BufWriter::new(file))
    }

    /// The temporary file read from its start (what has been flushed to it).
    ///
    /// # Errors
    /// [`WriteError::Io`] if the file cannot be opened again.
    pub fn reader(&self) -> Result<std::io::BufReader<File>, WriteError> {
        let file = self.temp.reopen().map_err(|error| self.io_error(error))?;
        Ok(std::io::BufReader::new(file))
    }

    /// Flushes what an encoder left in `writer`.
    ///
    /// # Errors
    /// [`WriteError::Io`] if writing fails (a full disk, say).
    pub fn flush(&self, writer: BufWriter<File>) -> Result<(), WriteError> {
        writer
            .into_inner()
            .map(drop)
            .map_err(|error| self.io_error(error.into_error()))
    }

    /// Renames the finished file into place.
    ///
    /// # Errors
    /// [`WriteError::Io`] if the rename fails; the temporary file is then removed.
    pub fn commit(self) -> Result<(), WriteError> {
        let Self {
            temp,
            path,
            _listed,
        } = self;
        match temp.persist(&path) {
            Ok(_) => Ok(()),
            Err(error) => Err(WriteError::Io {
                path,
                error: error.error,
            }),
        }
    }

    /// "cannot write PATH (reason)".
    fn io_error(&self, error: std::io::Error) -> WriteError {
        WriteError::Io {
            path: self.path.clone(),
            error,
        }
    }
}
