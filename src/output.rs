//! Writing images and videos without ever leaving a half-written file: encode into a temporary
//! file in the destination folder ([`AtomicFile`]), then rename it over the destination. Images
//! carry a [`Provenance`] record (a video carries its frames', written by `srt render` and
//! `srt encode` through [`srt_video::VideoWriter::set_comment`]).

use std::fs::File;
use std::io::{BufWriter, ErrorKind, Write as _};
use std::ops::Range;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use glam::DVec3;
use rayon::prelude::*;
use srt::engine::{AOV_CHANNELS, channel_f32, display_as_linear};
use srt::tiles::BAND_ROW_MULTIPLE;
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

/// Display colours (sRGB-encoded, [0, 1]) as 8-bit RGB bytes, in order (quantised on all threads).
pub fn display_bytes(pixels: &[DVec3]) -> Vec<u8> {
    /// Pixels quantised by one task.
    const CHUNK: usize = 1 << 14;
    let mut bytes = vec![0_u8; 3 * pixels.len()];
    (bytes.par_chunks_mut(3 * CHUNK))
        .zip(pixels.par_chunks(CHUNK))
        .for_each(|(bytes, pixels)| {
            for (rgb, pixel) in bytes.chunks_exact_mut(3).zip(pixels) {
                rgb.copy_from_slice(&pixel.to_array().map(quantize_8bit));
            }
        });
    bytes
}

/// The channels of the displayed image in srt's EXR (linear light), beside R, G, B (radiance).
pub const EXR_DISPLAY_CHANNELS: [&str; 3] = ["display.R", "display.G", "display.B"];

/// What the R, G, B channels of srt's EXR hold, as its record says.
pub const EXR_RADIANCE_NOTE: &str = "R, G, B: radiance before the tone map and exposure (linear BT.709, unclamped; \
     luminance 1 = a white surface at rest facing the observer's lamp; each channel within f32's \
     range), drawn by the record's engine; display.R, display.G, display.B: the image the PNG \
     shows, as linear light";

/// What an image file holds for a band of its rows, row-major from the top: the display
/// colours and, for an EXR, the radiance and, with `--aov`, what each pixel sees of time.
pub struct Band {
    /// Display colours (sRGB-encoded, [0, 1]).
    pub display: Vec<DVec3>,
    /// Radiance, R, G, B (`None` where the file does not hold it).
    pub radiance: Option<Vec<DVec3>>,
    /// Each pixel's [`AOV_CHANNELS`] values ([`srt::engine::aov_values`]; `None`: not asked for).
    pub seen: Option<Vec<[f32; 5]>>,
}

/// Which layers an image file holds beside its display colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layers {
    /// The radiance (an EXR's R, G, B).
    pub radiance: bool,
    /// What each pixel sees of time (an EXR's [`AOV_CHANNELS`], with `--aov`).
    pub seen: bool,
}

impl Layers {
    /// The layers of an image written to `path`: an EXR holds the radiance, and the time
    /// channels when `aov` asks for them; a PNG only the display colours.
    #[must_use]
    pub fn for_path(path: &Path, aov: bool) -> Self {
        let exr = OutputFormat::for_path(path).ok() == Some(OutputFormat::Exr);
        Self {
            radiance: exr,
            seen: exr && aov,
        }
    }
}

/// The rows of an image of `height` rows, in bands of `band_rows` (the last may be shorter).
pub fn bands(height: u32, band_rows: u32) -> impl Iterator<Item = Range<u32>> {
    let band_rows = band_rows.max(1);
    (0..height)
        .step_by(band_rows as usize)
        .map(move |first| first..(first + band_rows).min(height))
}

/// What the [`AOV_CHANNELS`] of srt's EXR hold, appended to [`EXR_RADIANCE_NOTE`] in its record.
pub const EXR_AOV_NOTE: &str = "; emission_ct, proper_time, distance, doppler, object: what each \
     pixel's centre sees of time (the emission event's world time ct, the object's proper time \
     ct' there, the apparent distance, the Doppler factor of its light, the object's index or \
     -1; docs/scene-format.md), drawn by the record's engine (on the CPU where the GPU renders half \
     floats)";

/// Writes a `width` × `height` image to `path` (format by extension) atomically, with `record`
/// stored in it, a band of rows at a time: `band` gives the [`Band`] of each range of rows in
/// turn (from the top, `band_rows` each, a multiple of the EXR's 16-line blocks), so that the
/// picture is never held whole. A PNG holds the display colours (sRGB-encoded, [0, 1]); an EXR
/// the radiance as R, G, B, the display colours as linear light (the
/// [`EXR_DISPLAY_CHANNELS`]) and the [`AOV_CHANNELS`] when the bands hold them.
///
/// # Errors
/// If `path` is not an image format, `band` fails (its error is returned), an EXR's band lacks
/// its radiance, or encoding or writing fails; the destination is then untouched.
pub fn write_image(
    (width, height): (u32, u32),
    band_rows: u32,
    layers: Layers,
    record: &Provenance,
    path: &Path,
    band: &mut dyn FnMut(Range<u32>) -> anyhow::Result<Band>,
) -> anyhow::Result<()> {
    let format = OutputFormat::for_path(path)?;
    let file = AtomicFile::create(path)?;
    let mut writer = file.writer()?;
    // A failure of the render itself is the caller's, not the encoder's: it is returned as it
    // is, whatever the encoder made of the missing rows.
    let mut render_error = None;
    let exr = format == OutputFormat::Exr;
    let mut next_band = |rows: Range<u32>| -> Option<Band> {
        let pixels = rows.len() * width as usize;
        let checked = band(rows).and_then(|band| {
            let fits = |length: Option<usize>, wanted: bool| match length {
                Some(length) => length == pixels,
                None => !wanted,
            };
            anyhow::ensure!(
                band.display.len() == pixels
                    && fits(band.radiance.as_ref().map(Vec::len), exr && layers.radiance)
                    && fits(band.seen.as_ref().map(Vec::len), exr && layers.seen),
                "cannot write {}: a band of rows lacks a layer the file holds",
                path.display()
            );
            Ok(band)
        });
        match checked {
            Ok(band) => Some(band),
            Err(error) => {
                render_error.get_or_insert(error);
                None
            }
        }
    };
    let encoded = match format {
        OutputFormat::Png => write_png(
            (width, height),
            band_rows,
            record,
            &mut writer,
            &mut next_band,
        ),
        OutputFormat::Exr => {
            let mut note = EXR_RADIANCE_NOTE.to_owned();
            if layers.seen {
                note.push_str(EXR_AOV_NOTE);
            }
            let record = record.with(&[("exr channels", note)]);
            write_exr(
                (width, height),
                band_rows,
                layers,
                &record,
                &mut writer,
                &mut next_band,
            )
        }
        OutputFormat::Mp4 | OutputFormat::Gif => {
            bail!("cannot write {}: a video needs --frames", path.display())
        }
    };
    if let Some(error) = render_error {
        return Err(error);
    }
    encoded.with_context(|| format!("cannot encode {}", path.display()))?;
    file.flush(writer)?;
    file.commit()?;
    Ok(())
}

/// Encodes an 8-bit sRGB PNG with `record` in an iTXt chunk before the pixels, streaming the
/// rows of each band `band` gives (`None`: the render failed; the encoding stops).
fn write_png(
    (width, height): (u32, u32),
    band_rows: u32,
    record: &Provenance,
    writer: &mut BufWriter<File>,
    band: &mut dyn FnMut(Range<u32>) -> Option<Band>,
) -> anyhow::Result<()> {
    let mut encoder = png::Encoder::new(writer, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    // fdeflate's PNG-tuned compressor: a 1920 × 1080 picture in a few milliseconds, where the
    // default zlib-style level spent up to 60 ms on one thread after the picture was drawn.
    encoder.set_compression(png::Compression::Fast);
    encoder.add_itxt_chunk(provenance::KEY.to_owned(), record.to_text())?;
    let mut png = encoder.write_header()?;
    let mut rows = png.stream_writer()?;
    for range in bands(height, band_rows) {
        let Some(band) = band(range) else {
            bail!("the render stopped");
        };
        let bytes = display_bytes(&band.display);
        rows.write_all(&bytes)?;
    }
    rows.finish()?;
    Ok(())
}

/// Encodes a 32-bit float EXR (ZIP-compressed blocks of 16 scan lines, written in increasing
/// order so the bytes do not depend on thread scheduling) from the bands `band` gives: the
/// radiance as R, G, B, the display colours (decoded to linear light) as the
/// [`EXR_DISPLAY_CHANNELS`] and, with `layers.seen`, each pixel's [`AOV_CHANNELS`], with
/// `record` as a text attribute.
fn write_exr(
    (width, height): (u32, u32),
    band_rows: u32,
    layers: Layers,
    record: &Provenance,
    writer: &mut BufWriter<File>,
    band: &mut dyn FnMut(Range<u32>) -> Option<Band>,
) -> anyhow::Result<()> {
    use exr::block::UncompressedBlock;
    use exr::block::writer::ChunksWriter as _;
    use exr::meta::BlockDescription;
    use exr::meta::attribute::ChannelList;
    use exr::meta::header::Header;
    use exr::prelude::{
        AttributeValue, ChannelDescription, Compression, LayerAttributes, LineOrder, SampleType,
        SmallVec, Text,
    };
    /// Why a band's layers are there: [`write_image`] checked them.
    const CHECKED: &str = "write_image checked each band's layers";
    /// Where a channel's values come from in a band.
    #[derive(Clone, Copy)]
    enum Source {
        /// Component `i` of the radiance.
        Radiance(usize),
        /// Component `i` of the display colours, as linear light.
        Display(usize),
        /// AOV value `i`.
        Seen(usize),
    }
    // ZIP16's blocks of 16 scan lines, each within one band.
    anyhow::ensure!(
        band_rows.is_multiple_of(BAND_ROW_MULTIPLE),
        "an EXR is written in bands of whole {BAND_ROW_MULTIPLE}-line blocks, not {band_rows} rows"
    );
    let mut sources: Vec<(&str, Source)> = (["R", "G", "B"].into_iter().enumerate())
        .map(|(index, name)| (name, Source::Radiance(index)))
        .chain((EXR_DISPLAY_CHANNELS.into_iter().enumerate()).map(|(i, n)| (n, Source::Display(i))))
        .collect();
    if layers.seen {
        sources.extend((AOV_CHANNELS.into_iter().enumerate()).map(|(i, n)| (n, Source::Seen(i))));
    }
    // An EXR's channels are stored in the order of their names.
    sources.sort_by(|a, b| a.0.cmp(b.0));
    let channels = ChannelList::new(
        (sources.iter())
            .map(|(name, _)| ChannelDescription::named(*name, SampleType::F32))
            .collect::<SmallVec<_>>(),
    );
    let mut attributes = LayerAttributes::default();
    attributes.other.insert(
        Text::from(provenance::KEY),
        AttributeValue::Text(Text::from_slice_unchecked(record.to_text().as_bytes())),
    );
    let header = Header::new(
        Text::default(),
        (width as usize, height as usize),
        channels.list.clone(),
    )
    .with_encoding(
        Compression::ZIP16,
        BlockDescription::ScanLines,
        LineOrder::Increasing,
    )
    .with_attributes(attributes);
    let mut current: Option<(Range<u32>, Band)> = None;
    let mut bands = bands(height, band_rows);
    let blocks_of = |meta: &exr::meta::MetaData| {
        meta.enumerate_ordered_header_block_indices()
            .collect::<Vec<_>>()
    };
    exr::block::write(
        writer,
        SmallVec::from_vec(vec![header]),
        true,
        |meta, chunks| {
            // Stops at a band the render could not give; the error is the caller's to report.
            let blocks = blocks_of(&meta).into_iter().map_while(|(index, block)| {
                let top = block.pixel_position.y() as u32;
                while !current
                    .as_ref()
                    .is_some_and(|(rows, _)| rows.contains(&top))
                {
                    let rows = bands.next()?;
                    current = Some((rows.clone(), band(rows)?));
                }
                let (rows, band) = current.as_ref()?;
                let data =
                    UncompressedBlock::collect_block_data_from_lines(&channels, block, |line| {
                        let start =
                            (line.location.position.y() - rows.start as usize) * width as usize;
                        let pixels = start..start + width as usize;
                        let values: Vec<f32> = match sources[line.location.channel].1 {
                            Source::Radiance(i) => (band.radiance.as_ref().expect(CHECKED)[pixels]
                                .iter())
                            .map(|p| channel_f32(p[i]))
                            .collect(),
                            Source::Display(i) => (band.display[pixels].iter())
                                .map(|p| display_as_linear(p[i]))
                                .collect(),
                            Source::Seen(i) => (band.seen.as_ref().expect(CHECKED)[pixels].iter())
                                .map(|v| v[i])
                                .collect(),
                        };
                        line.write_samples_from_slice(&values)
                            .expect("a line of the block's width");
                    });
                Some((index, UncompressedBlock { index: block, data }))
            });
            // A writer by value, as the crate's own image writer takes it.
            (chunks.on_progress(|_| {})).compress_all_blocks_parallel(&meta, blocks)
        },
    )?;
    Ok(())
}
