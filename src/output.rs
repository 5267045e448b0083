//! Writing images and videos without ever leaving a half-written file: encode into a temporary
//! file in the destination folder ([`AtomicFile`]), then rename it over the destination. Images
//! carry a [`Provenance`] record.

use std::fs::File;
use std::io::{BufWriter, ErrorKind};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow, bail};
use glam::DVec3;
use image::RgbImage;
use srt_color::{quantize_8bit, srgb_decode};
use srt_scene::message::io_reason;
use tempfile::NamedTempFile;

use crate::provenance::{self, Provenance};

/// File formats `srt` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB PNG.
    Png,
    /// 32-bit float OpenEXR with linear-light values.
    Exr,
    /// H.264 video in an MP4 container.
    Mp4,
    /// Animated GIF.
    Gif,
}

impl OutputFormat {
    /// The format for `path`'s extension.
    ///
    /// # Errors
    /// If the extension is none of `.png`, `.exr`, `.mp4` and `.gif`.
    pub fn for_path(path: &Path) -> anyhow::Result<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(Self::Png),
            Some("exr") => Ok(Self::Exr),
            Some("mp4") => Ok(Self::Mp4),
            Some("gif") => Ok(Self::Gif),
            _ => bail!(
                "cannot write {}: the file name must end in .png or .exr (images), or .mp4 or \
                 .gif (videos)",
                path.display()
            ),
        }
    }

    /// Whether this is a video format (many frames in one file).
    pub const fn is_video(self) -> bool {
        matches!(self, Self::Mp4 | Self::Gif)
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

/// A file being written in its destination's folder: [`AtomicFile::commit`] renames it into
/// place; dropped before that (an error, a panic), it is removed and the destination is
/// untouched.
pub struct AtomicFile {
    temp: NamedTempFile,
    path: PathBuf,
}

impl AtomicFile {
    /// Starts writing `path`.
    ///
    /// # Errors
    /// If no file can be created in `path`'s folder.
    pub fn create(path: &Path) -> anyhow::Result<Self> {
        Ok(Self {
            temp: temporary_file_beside(path)?,
            path: path.to_owned(),
        })
    }

    /// A buffered writer to the temporary file; finish it with [`AtomicFile::flush`].
    ///
    /// # Errors
    /// If the file handle cannot be duplicated.
    pub fn writer(&self) -> anyhow::Result<BufWriter<File>> {
        let file = self
            .temp
            .as_file()
            .try_clone()
            .map_err(|error| self.io_error(&error))?;
        Ok(BufWriter::new(file))
    }

    /// Flushes what an encoder left in `writer`.
    ///
    /// # Errors
    /// If writing fails (a full disk, say).
    pub fn flush(&self, writer: BufWriter<File>) -> anyhow::Result<()> {
        writer
            .into_inner()
            .map(drop)
            .map_err(|error| self.io_error(error.error()))
    }

    /// Renames the finished file into place.
    ///
    /// # Errors
    /// If the rename fails; the temporary file is then removed.
    pub fn commit(self) -> anyhow::Result<()> {
        let path = self.path;
        self.temp.persist(&path).map_err(|error| {
            anyhow!(
                "cannot write {} ({})",
                path.display(),
                io_reason(&error.error)
            )
        })?;
        Ok(())
    }

    /// "cannot write PATH (reason)".
    fn io_error(&self, error: &std::io::Error) -> anyhow::Error {
        anyhow!(
            "cannot write {} ({})",
            self.path.display(),
            io_reason(error)
        )
    }
}

/// Display colours (sRGB-encoded, [0, 1], row-major from the top) as an 8-bit image.
///
/// # Panics
/// If `pixels` does not hold `width` × `height` colours (a bug in the caller).
#[must_use]
pub fn display_rgb8(width: u32, height: u32, pixels: &[DVec3]) -> RgbImage {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|p| p.to_array().map(quantize_8bit))
        .collect();
    RgbImage::from_raw(width, height, bytes).expect("one colour per pixel")
}

/// Writes a `width` × `height` image of display colours (sRGB-encoded, [0, 1], row-major from
/// the top) to `path` (format by extension) atomically, with `record` stored in it.
///
/// # Errors
/// If `path` is not an image format, or encoding or writing fails; the destination is then
/// untouched.
pub fn write_image(
    width: u32,
    height: u32,
    pixels: &[DVec3],
    record: &Provenance,
    path: &Path,
) -> anyhow::Result<()> {
    let format = OutputFormat::for_path(path)?;
    let file = AtomicFile::create(path)?;
    let mut writer = file.writer()?;
    match format {
        OutputFormat::Png => write_png(&display_rgb8(width, height, pixels), record, &mut writer),
        OutputFormat::Exr => write_exr(width, height, pixels, record, &mut writer),
        OutputFormat::Mp4 | OutputFormat::Gif => {
            bail!("cannot write {}: a video needs --frames", path.display())
        }
    }
    .with_context(|| format!("cannot encode {}", path.display()))?;
    file.flush(writer)?;
    file.commit()
}

/// Encodes an 8-bit sRGB PNG with `record` in an iTXt chunk before the pixels.
fn write_png(
    image: &RgbImage,
    record: &Provenance,
    writer: &mut BufWriter<File>,
) -> anyhow::Result<()> {
    let mut encoder = png::Encoder::new(writer, image.width(), image.height());
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.add_itxt_chunk(provenance::KEY.to_owned(), record.to_text())?;
    let mut png = encoder.write_header()?;
    png.write_image_data(image.as_raw())?;
    png.finish()?;
    Ok(())
}

/// Encodes a linear-light 32-bit float EXR (ZIP-compressed scan lines, written in increasing
/// order so the bytes do not depend on thread scheduling) with `record` as a text attribute.
fn write_exr(
    width: u32,
    height: u32,
    pixels: &[DVec3],
    record: &Provenance,
    writer: &mut BufWriter<File>,
) -> anyhow::Result<()> {
    use exr::prelude::{
        AttributeValue, Encoding, Image, Layer, LayerAttributes, SpecificChannels, Text, Vec2,
        WritableImage as _,
    };
    let size = Vec2(width as usize, height as usize);
    let linear = |c: f64| srgb_decode(c.clamp(0.0, 1.0)) as f32;
    let channels = SpecificChannels::rgb(|position: Vec2<usize>| {
        let p = pixels[position.flat_index_for_size(size)];
        (linear(p.x), linear(p.y), linear(p.z))
    });
    let mut attributes = LayerAttributes::default();
    attributes.other.insert(
        Text::from(provenance::KEY),
        AttributeValue::Text(Text::from_slice_unchecked(record.to_text().as_bytes())),
    );
    Image::from_layer(Layer::new(
        size,
        attributes,
        Encoding::SMALL_LOSSLESS,
        channels,
    ))
    .write()
    .to_buffered(writer)?;
    Ok(())
}
