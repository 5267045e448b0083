//! `cargo xtask bench --throughput`: sustained frames per second of each method — N frames
//! rendered back to back, each at a later observation time (the scene moves on, as in an
//! animation or the viewer), with up to [`IN_FLIGHT`] frames queued on the GPU and no readback;
//! the clock runs from the first frame's encoding to the GPU's idle after the last. The first
//! frame of each case is saved as a PNG (`target/bench-throughput/`) to look at what was timed.

use std::collections::VecDeque;
use std::path::Path;
use std::time::Instant;

use anyhow::Context as _;
use serde::{Deserialize, Serialize};
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_scene::Scene;

use super::WARM_UP;
use super::document::replace_block;
use super::report::Markers;
use super::results::{METHODS, method_name};

/// Frames a method may have queued on the GPU while the next is encoded.
pub const IN_FLIGHT: usize = 2;
/// How far the observation time moves over a measurement's frames, in scene units of ct, however
/// many frames it has (more frames sample the same motion more finely, so that a fast GPU's
/// longer runs time the same scenes as a software adapter's 30 frames).
pub const CT_SPAN: f64 = 1.5;

/// One case's sustained frame rates.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Throughput {
    /// The case.
    pub name: String,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Triangles in the scene.
    pub triangles: usize,
    /// Frames rendered back to back per method.
    pub frames: u32,
    /// Frames per second of each of [`METHODS`], in that order.
    pub fps: [f64; 4],
    /// Mean CPU time per frame in ms spent encoding and submitting it, per method: where it
    /// comes near a frame's share of the time (1000 / fps), the CPU bounds the rate.
    pub encode_ms: [f64; 4],
}

impl Throughput {
    /// The report line.
    #[must_use]
    pub fn text(&self) -> String {
        let rates: Vec<String> = METHODS
            .iter()
            .zip(self.fps.iter().zip(self.encode_ms))
            .map(|(method, (fps, encode))| {
                let name = method_name(*method).to_lowercase();
                format!("{name}_fps={fps:.2} {name}_encode_ms={encode:.3}")
            })
            .collect();
        format!(
            "throughput scene={} size={}x{} tris={} frames={} in_flight={IN_FLIGHT} {}",
            self.name,
            self.width,
            self.height,
            self.triangles,
            self.frames,
            rates.join(" ")
        )
    }
}

/// Encodes and submits one frame of `scene` with `method` (no readback); returns its
/// submission.
pub(super) fn submit(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    method: Method,
) -> anyhow::Result<wgpu::SubmissionIndex> {
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("xtask bench throughput frame"),
        });
    renderer.encode(ctx, &mut encoder, scene, method, FootprintShape::Hull)?;
    Ok(ctx.queue.submit([encoder.finish()]))
}

/// Sustained frames per second of each of [`METHODS`] on `scene` with `renderer`, and the
/// mean CPU time per frame in ms spent encoding and submitting: `frames` frames each, from
/// the scene's own time on over [`CT_SPAN`] in equal steps, after [`WARM_UP`] frames.
///
/// # Errors
/// A GPU failure.
pub fn measure(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    frames: u32,
) -> anyhow::Result<([f64; 4], [f64; 4])> {
    let mut moving = scene.clone();
    let start_ct = scene.observer.time;
    let (mut fps, mut encode_ms) = ([0.0; 4], [0.0; 4]);
    let step = CT_SPAN / f64::from(frames.max(1));
    for ((rate, encode), method) in fps.iter_mut().zip(&mut encode_ms).zip(METHODS) {
        for _ in 0..WARM_UP {
            submit(ctx, renderer, scene, method)?;
        }
        ctx.wait()?;
        let start = Instant::now();
        let mut encoding = std::time::Duration::ZERO;
        let mut queued = VecDeque::new();
        for frame in 0..frames {
            moving.observer.time = start_ct + step * f64::from(frame);
            let encode_start = Instant::now();
            queued.push_back(submit(ctx, renderer, &moving, method)?);
            encoding += encode_start.elapsed();
            if queued.len() > IN_FLIGHT
                && let Some(oldest) = queued.pop_front()
            {
                ctx.device
                    .poll(wgpu::PollType::Wait {
                        submission_index: Some(oldest),
                        timeout: None,
                    })
                    .map_err(|e| anyhow::anyhow!("waiting for a frame: {e}"))?;
            }
        }
        ctx.wait()?;
        *rate = f64::from(frames) / start.elapsed().as_secs_f64();
        *encode = encoding.as_secs_f64() * 1e3 / f64::from(frames.max(1));
        ctx.take_errors()?;
    }
    Ok((fps, encode_ms))
}

/// Saves `renderer`'s picture of `scene` (exact, display colours) as `folder/NAME_WxH.png`.
///
/// # Errors
/// A GPU failure or an unwritable folder.
pub fn save_first_frame(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    name: &str,
    folder: &Path,
) -> anyhow::Result<()> {
    let (width, height) = renderer.size();
    let (image, _) = renderer.render(ctx, scene, Method::Auto, FootprintShape::Hull)?;
    let bytes: Vec<u8> = image.to_rgb8().into_iter().flatten().collect();
    std::fs::create_dir_all(folder)?;
    let file = folder.join(format!(
        "{}_{width}x{height}.png",
        name.replace([' ', '/'], "-")
    ));
    image::RgbImage::from_raw(width, height, bytes)
        .context("one colour per pixel")?
        .save(&file)
        .with_context(|| format!("cannot write {}", file.display()))?;
    Ok(())
}

/// The Markdown table of `measured` on `adapter`, between `markers`.
#[must_use]
pub fn table(
    measured: &[Throughput],
    adapter: &str,
    date: &str,
    commit: &str,
    markers: Markers,
) -> String {
    let mut table = format!(
        "{}\nAdapter: {adapter}. {date}, commit {commit}. Frames per second, \
         sustained: each method renders the case's frames back to back (the observation time \
         moving on by {CT_SPAN} over the frames, in equal steps), up to {IN_FLIGHT} frames queued, no readback; timed \
         from the first frame's encoding to the GPU's idle after the last.\n\n\
         | case | size | triangles | frames | auto fps | LRT fps | RT fps | polygon fps | auto / polygon time |\n\
         |---|---|---|---|---|---|---|---|---|\n",
        markers.start
    );
    for line in measured {
        let [auto, lrt, rt, polygon] = line.fps;
        table.push_str(&format!(
            "| {} | {}×{} | {} | {} | {auto:.2} | {lrt:.2} | {rt:.2} | {polygon:.2} | {:.2} |\n",
            line.name,
            line.width,
            line.height,
            line.triangles,
            line.frames,
            polygon / auto
        ));
    }
    table + markers.end
}

/// Rewrites the throughput block between `markers` of `document` (appended where it is
/// missing).
///
/// # Errors
/// An unreadable or unwritable document.
pub fn write(document: &Path, block: &str, markers: Markers) -> anyhow::Result<()> {
    let text = std::fs::read_to_string(document)
        .with_context(|| format!("cannot read {}", document.display()))?;
    let updated = replace_block(&text, markers, block);
    std::fs::write(document, updated)
        .with_context(|| format!("cannot write {}", document.display()))?;
    println!("updated {}", document.display());
    Ok(())
}
