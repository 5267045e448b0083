//! Writing images without ever leaving a half-written file: encode into a temporary file in the
//! destination folder, then rename it over the destination.

use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use glam::DVec3;
use image::{ImageFormat, Rgb32FImage, RgbImage};
use srt_color::srgb_decode;

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

/// Checks up front that `path` can be written (its folder exists and is writable), so a long
/// render does not end in an error.
///
/// # Errors
/// If the folder does not exist or a file cannot be created in it.
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    OutputFormat::for_path(path)?;
    let folder = parent_folder(path);
    tempfile::NamedTempFile::new_in(folder).with_context(|| {
        format!(
            "cannot write {}: folder {} is not writable",
            path.display(),
            folder.display()
        )
    })?;
    Ok(())
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
    let folder = parent_folder(path);
    let mut temp = tempfile::NamedTempFile::new_in(folder).with_context(|| {
        format!(
            "cannot write {}: folder {} is not writable",
            path.display(),
            folder.display()
        )
    })?;
    {
        let mut writer = BufWriter::new(temp.as_file_mut());
        match format {
            OutputFormat::Png => {
                let bytes: Vec<u8> = pixels
                    .iter()
                    .flat_map(|p| {
                        p.to_array()
                            .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
                    })
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
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    temp.persist(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}
