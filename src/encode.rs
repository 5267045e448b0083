//! `srt encode`: join rendered frames (PNG, or linear EXR converted to sRGB) into one video,
//! typically the numbered frames that the shares of a cluster render wrote (docs/cluster.md).
//! The video holds the frames' record ([`Provenance::for_video`]): the first frame's, with the
//! time and frame range from the first frame to the last.

use std::path::Path;
use std::time::Instant;

use anyhow::{anyhow, bail};
use image::{DynamicImage, RgbImage};
use srt_color::{quantize_8bit, srgb_encode};

use crate::cli::EncodeArgs;
use crate::output::{EXR_DISPLAY_CHANNELS, OutputFormat, check_writable};
use crate::progress::DelayedBar;
use crate::provenance::Provenance;
use srt_video::{VideoWriter, check_size};

/// Runs `srt encode FRAME... -o VIDEO`.
///
/// # Errors
/// If the output is not a writable .mp4 or .gif, a frame cannot be read, or the frames differ
/// in size; nothing is then written.
pub fn run(args: &EncodeArgs) -> anyhow::Result<()> {
    let start = Instant::now();
    let output = &args.output;
    check_writable(output)?;
    let Some(format) = OutputFormat::for_path(output)?.video() else {
        bail!(
            "cannot write {}: srt encode writes a video; the file name must end in .mp4 or .gif",
            output.display()
        );
    };
    let Some(first_path) = args.frames.first() else {
        bail!("srt encode needs at least one frame");
    };
    let first = read_frame(first_path)?;
    let (width, height) = first.dimensions();
    check_size(
        output,
        format,
        width,
        height,
        &first_path.display().to_string(),
    )?;
    let mut video = VideoWriter::create(output, width, height, args.video.fps())?;
    video.set_comment(&joined_record(&args.frames, args.video.fps()).to_text());
    let bar = DelayedBar::new(
        args.frames.len() as u64,
        "frames",
        format!("encoding {}", output.display()),
    );
    video.push(&first)?;
    bar.inc();
    for path in &args.frames[1..] {
        let frame = read_frame(path)?;
        if frame.dimensions() != (width, height) {
            bail!(
                "{} is {}x{}, but {} is {width}x{height}: all frames of a video must have one size",
                path.display(),
                frame.width(),
                frame.height(),
                first_path.display()
            );
        }
        video.push(&frame)?;
        bar.inc();
    }
    bar.finish();
    let frames = video.finish()?;
    println!(
        "wrote {} ({frames} frames, {width}x{height}, {} fps, {:.2} s)",
        output.display(),
        args.video.fps(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The record of a video joined from `frames`: theirs ([`Provenance::for_video`]) where the
/// first and last frames hold srt records, else one that says only that srt joined them.
fn joined_record(frames: &[std::path::PathBuf], fps: u32) -> Provenance {
    let joined = "joined by srt encode";
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return Provenance::new();
    };
    match (Provenance::read(first), Provenance::read(last)) {
        (Ok(first), Ok(last)) => Provenance::for_video(&first, &last, frames.len(), fps, joined),
        _ => Provenance::for_video(
            &Provenance::new(),
            &Provenance::new(),
            frames.len(),
            fps,
            &format!("{joined} from frames without an srt record"),
        ),
    }
}

/// Reads a frame as 8-bit display colours: a PNG as it is; srt's EXR by its displayed image
/// (the [`EXR_DISPLAY_CHANNELS`], linear light) through the sRGB encoding; another
/// floating-point image by its R, G, B the same way.
fn read_frame(path: &Path) -> anyhow::Result<RgbImage> {
    if let Some(display) = read_exr_display(path) {
        return Ok(display);
    }
    let image = image::open(path)
        .map_err(|error| anyhow!("cannot read frame {} ({error})", path.display()))?;
    Ok(match image {
        DynamicImage::ImageRgb32F(_) | DynamicImage::ImageRgba32F(_) => {
            let linear = image.into_rgb32f();
            let (width, height) = linear.dimensions();
            let bytes = linear
                .into_raw()
                .into_iter()
                .map(|c| quantize_8bit(srgb_encode(f64::from(c).clamp(0.0, 1.0))))
                .collect();
            RgbImage::from_raw(width, height, bytes).expect("three channels per pixel")
        }
        other => other.into_rgb8(),
    })
}

/// The displayed image of an EXR written by `srt render` (its [`EXR_DISPLAY_CHANNELS`]) as 8-bit
/// sRGB, or `None` when `path` is not an EXR with those channels.
fn read_exr_display(path: &Path) -> Option<RgbImage> {
    use exr::prelude::{ReadChannels as _, ReadLayers as _, ReadSpecificChannel as _, read};
    let [r, g, b] = EXR_DISPLAY_CHANNELS;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required(r)
        .required(g)
        .required(b)
        .collect_pixels(
            |size, _| (size.width(), vec![[0.0_f32; 3]; size.area()]),
            |(width, pixels): &mut (usize, Vec<[f32; 3]>), position, (r, g, b): (f32, f32, f32)| {
                pixels[position.y() * *width + position.x()] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .ok()?;
    let size = image.layer_data.size;
    let (_, pixels) = image.layer_data.channel_data.pixels;
    let bytes = pixels
        .iter()
        .flatten()
        .map(|&c| quantize_8bit(srgb_encode(f64::from(c).clamp(0.0, 1.0))))
        .collect();
    RgbImage::from_raw(
        u32::try_from(size.width()).ok()?,
        u32::try_from(size.height()).ok()?,
        bytes,
    )
}
