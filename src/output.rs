//! Writing images and videos without ever leaving a half-written file: encode into a temporary
//! file in the destination folder ([`AtomicFile`]), then rename it over the destination. Images
//! carry a [`Provenance`] record.

use std::fs::File;
use std::io::{BufWriter, ErrorKind};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use glam::DVec3;
use image::RgbImage;
use srt::engine::{AOV_CHANNELS, channel_f32, display_as_linear};
use srt_color::quantize_8bit;
use srt_scene::message::io_reason;

use srt_video::{
    AtomicFile, VideoFormat, lowercase_extension, parent_folder, temporary_file_beside,
};

use crate::provenance::{self, Provenance};

/// File formats `srt` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB PNG.
    Png,
    /// 32-bit float OpenEXR: the radiance (R, G, B) and the displayed image (`display.R`…).
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
        match lowercase_extension(path).as_deref() {
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

    /// The video format, for the formats that hold many frames in one file.
    pub const fn video(self) -> Option<VideoFormat> {
        match self {
            Self::Mp4 => Some(VideoFormat::Mp4),
            Self::Gif => Some(VideoFormat::Gif),
            Self::Png | Self::Exr => None,
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

/// The channels of the displayed image in srt's EXR (linear light), beside R, G, B (radiance).
pub const EXR_DISPLAY_CHANNELS: [&str; 3] = ["display.R", "display.G", "display.B"];

/// What the R, G, B channels of srt's EXR hold, as its record says.
pub const EXR_RADIANCE_NOTE: &str = "R, G, B: radiance before the tone map and exposure (linear BT.709, unclamped; \
     luminance 1 = a white surface at rest facing the observer's lamp; each channel within f32's \
     range), drawn by the record's engine; display.R, display.G, display.B: the image the PNG \
     shows, as linear light";

/// What an EXR holds beside the display colours: the radiance and, with `--aov`, what each
/// pixel sees of time.
pub struct ExrLayers {
    /// Radiance, R, G, B, row-major from the top.
    pub radiance: Vec<DVec3>,
    /// Each pixel's [`AOV_CHANNELS`] values ([`srt::engine::aov_values`]; `None`: not asked for).
    pub seen: Option<Vec<[f32; 5]>>,
}

/// What the [`AOV_CHANNELS`] of srt's EXR hold, appended to [`EXR_RADIANCE_NOTE`] in its record.
pub const EXR_AOV_NOTE: &str = "; emission_ct, proper_time, distance, doppler, object: what each \
     pixel's centre sees of time (the emission event's world time ct, the object's proper time \
     ct' there, the apparent distance, the Doppler factor of its light, the object's index or \
     -1; docs/scene-format.md), drawn by the record's engine (on the CPU where the GPU renders half \
     floats)";

/// Writes a `width` × `height` image to `path` (format by extension) atomically, with `record`
/// stored in it: a PNG of `display` (display colours, sRGB-encoded, [0, 1], row-major from the
/// top), or an EXR of `exr`'s layers (radiance as R, G, B, the display colours as linear light,
/// the [`EXR_DISPLAY_CHANNELS`], and the [`AOV_CHANNELS`] when given).
///
/// # Errors
/// If `path` is not an image format, an EXR is asked for without its layers, or encoding or
/// writing fails; the destination is then untouched.
pub fn write_image(
    width: u32,
    height: u32,
    display: &[DVec3],
    exr: Option<&ExrLayers>,
    record: &Provenance,
    path: &Path,
) -> anyhow::Result<()> {
    let format = OutputFormat::for_path(path)?;
    let file = AtomicFile::create(path)?;
    let mut writer = file.writer()?;
    match (format, exr) {
        (OutputFormat::Png, _) => {
            write_png(&display_rgb8(width, height, display), record, &mut writer)
        }
        (OutputFormat::Exr, Some(layers)) => {
            let mut note = EXR_RADIANCE_NOTE.to_owned();
            if layers.seen.is_some() {
                note.push_str(EXR_AOV_NOTE);
            }
            let record = record.with(&[("exr channels", note)]);
            write_exr(width, height, display, layers, &record, &mut writer)
        }
        (OutputFormat::Exr, None) => bail!("cannot write {}: no radiance", path.display()),
        (OutputFormat::Mp4 | OutputFormat::Gif, _) => {
            bail!("cannot write {}: a video needs --frames", path.display())
        }
    }
    .with_context(|| format!("cannot encode {}", path.display()))?;
    file.flush(writer)?;
    file.commit()?;
    Ok(())
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

/// Encodes a 32-bit float EXR (ZIP-compressed scan lines, written in increasing order so the
/// bytes do not depend on thread scheduling): `radiance` as R, G, B, `display` (display
/// colours, decoded to linear light) as the [`EXR_DISPLAY_CHANNELS`] and, when given, each
/// pixel's [`AOV_CHANNELS`], with `record` as a text attribute.
fn write_exr(
    width: u32,
    height: u32,
    display: &[DVec3],
    layers: &ExrLayers,
    record: &Provenance,
    writer: &mut BufWriter<File>,
) -> anyhow::Result<()> {
    use exr::prelude::{
        AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, Layer,
        LayerAttributes, SmallVec, Text, Vec2, WritableImage as _,
    };
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let component = |pixels: &[DVec3], index: usize, convert: fn(f64) -> f32| -> Vec<f32> {
        pixels.iter().map(|p| convert(p[index])).collect()
    };
    let mut channels = Vec::new();
    for (index, name) in ["R", "G", "B"].into_iter().enumerate() {
        channels.push(channel(
            name,
            component(&layers.radiance, index, channel_f32),
        ));
    }
    for (index, name) in EXR_DISPLAY_CHANNELS.into_iter().enumerate() {
        channels.push(channel(name, component(display, index, display_as_linear)));
    }
    if let Some(values) = &layers.seen {
        for (index, name) in AOV_CHANNELS.into_iter().enumerate() {
            channels.push(channel(name, values.iter().map(|v| v[index]).collect()));
        }
    }
    let mut attributes = LayerAttributes::default();
    attributes.other.insert(
        Text::from(provenance::KEY),
        AttributeValue::Text(Text::from_slice_unchecked(record.to_text().as_bytes())),
    );
    Image::from_layer(Layer::new(
        Vec2(width as usize, height as usize),
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(channels)),
    ))
    .write()
    .to_buffered(writer)?;
    Ok(())
}
