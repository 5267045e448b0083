//! Writing images without ever leaving a half-written file: encode into a temporary file in the
//! destination folder, then rename it over the destination.

use std::io::{BufWriter, ErrorKind, Write as _};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow, bail};
use glam::DVec3;
use image::{ImageFormat, Rgb32FImage, RgbImage};
use srt_color::{quantize_8bit, srgb_decode};
use srt_scene::message::io_reason;
use tempfile::NamedTempFile;

/// Image file formats `srt` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB PNG.
    Png,
    /// 32-bit float OpenEXR with linear-light values.
    Exr,
}

impl OutputFormat {
    /// The format for `path`'s extension.
    ///
    /// # Errors
    /// If the extension is neither `.png` nor `.exr`.
    pub fn for_path(path: &Path) -> anyhow::Result<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(Self::Png),
            Some("exr") => Ok(Self::Exr),
            _ => bail!(
                "cannot write {}: the file name must end in .png or .exr",
                path.display()
            ),
        }
    }
}

/// `path` with `_NNNN` (frame number, zero-padded to `digits`) inserted before the extension.
pub fn numbered(path: &Path, frame: u32, digits: usize) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!("{stem}_{frame:0digits$}.{extension}"))
}

/// Checks up front that `path` can be written (a known image extension, not a folder or a device,
/// in an existing folder where a file can be created), so a long render does not end in an
/// error and nothing the user had is replaced by surprise.
///
/// # Errors
/// If any of those does not hold; the message names the path and the reason.
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    OutputFormat::for_path(path)?;
    if let Ok(metadata) = std::fs::metadata(path) {
        if metadata.is_dir() {
            bail!("cannot write {}: it is a folder", path.display());
        }
        if !metadata.is_file() {
            bail!(
                "cannot write {}: it exists and is not a regular file (a device, pipe or socket)",
                path.display()
            );
        }
    }
    let folder = parent_folder(path);
    match std::fs::metadata(folder) {
        Ok(metadata) if metadata.is_dir() => {}
        Ok(_) => bail!(
            "cannot write {}: {} is not a folder",
            path.display(),
            folder.display()
        ),
        Err(error) if error.kind() == ErrorKind::NotFound => bail!(
            "cannot write {}: folder {} does not exist",
            path.display(),
            folder.display()
        ),
        Err(error) => bail!(
            "cannot write {}: folder {} cannot be used ({})",
            path.display(),
            folder.display(),
            io_reason(&error)
        ),
    }
    temporary_file_beside(path)?;
    Ok(())
}

/// A new, empty temporary file in `path`'s folder (removed when dropped), created with the
/// permissions any new file gets there: 0o666 less the umask on Unix, not `tempfile`'s private
/// 0o600, which would otherwise survive the rename into place.
fn temporary_file_beside(path: &Path) -> anyhow::Result<NamedTempFile> {
    let folder = parent_folder(path);
    let mut builder = tempfile::Builder::new();
    builder.prefix(".srt-").suffix(".partial");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(folder).map_err(|error| {
        anyhow!(
            "cannot write {}: cannot create a file in folder {} ({})",
            path.display(),
            folder.display(),
            io_reason(&error)
        )
    })
}

fn parent_folder(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Writes a `width` × `height` image of display colours (sRGB-encoded, [0, 1], row-major from
/// the top) to `path` (format by extension) atomically.
///
/// # Errors
/// If encoding or writing fails; the destination is then untouched.
pub fn write_image(width: u32, height: u32, pixels: &[DVec3], path: &Path) -> anyhow::Result<()> {
    let format = OutputFormat::for_path(path)?;
    let mut temp = temporary_file_beside(path)?;
    {
        let mut writer = BufWriter::new(temp.as_file_mut());
        match format {
            OutputFormat::Png => {
                let bytes: Vec<u8> = pixels
                    .iter()
                    .flat_map(|p| p.to_array().map(quantize_8bit))
                    .collect();
                let buffer =
                    RgbImage::from_raw(width, height, bytes).context("image size mismatch")?;
                buffer.write_to(&mut writer, ImageFormat::Png)
            }
            OutputFormat::Exr => {
                let linear: Vec<f32> = pixels
                    .iter()
                    .flat_map(|p| p.to_array().map(|c| srgb_decode(c.clamp(0.0, 1.0)) as f32))
                    .collect();
                let buffer =
                    Rgb32FImage::from_raw(width, height, linear).context("image size mismatch")?;
                buffer.write_to(&mut writer, ImageFormat::OpenExr)
            }
        }
        .with_context(|| format!("cannot encode {}", path.display()))?;
        writer
            .flush()
            .map_err(|error| anyhow!("cannot write {} ({})", path.display(), io_reason(&error)))?;
    }
    temp.persist(path).map_err(|error| {
        anyhow!(
            "cannot write {} ({})",
            path.display(),
            io_reason(&error.error)
        )
    })?;
    Ok(())
}
