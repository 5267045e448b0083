//! The renderer behind `srt render` (and `srt.render` in Python): which backend draws a scene's
//! display colours and the radiance an EXR holds, and how a GPU image is supersampled down to
//! the output size. One piece of code, so that the command and every other front end produce the same
//! pixels for the same arguments.

use std::cell::{OnceCell, RefCell};
use std::ops::Range;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use anyhow::{Context as _, bail};
use glam::DVec3;
use srt_color::srgb_decode;
use srt_gpu::limits::DeviceLimits;
use srt_gpu::renderer::check_per_pixel_resources;
use srt_gpu::{FootprintShape, GpuContext, GpuError, GpuRenderer, Method, SoftwareApi};

use crate::software::{
    CpuCost, Job, MEASURED_WHILE_OPENING, SceneSize, SoftwareCosts, gpu_possible, weigh,
};
use crate::tiles::{BAND_ROW_MULTIPLE, Tiling, assemble};
use srt_scene::{Scene, UploadKey};
use srt_trace::{FrameMeasure, Output, PROBE_ROWS, RenderSettings, SeenEvent, Tracer};

/// The largest image width or height `srt render` accepts, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The most samples per pixel `srt render` accepts.
pub const MAX_SAMPLES: u32 = 1024;

/// The most pixels the CPU renders at a time for a file written a band of rows at a time
/// ([`Engine::band_rows`]): about a hundred bytes each while the band is held (display colours,
/// radiance, time channels), so about 100 MiB whatever the picture's size.
pub const BAND_PIXELS: u64 = 1 << 20;

/// The most memory `srt render` means to hold for one picture beyond its scene (2 GiB): the
/// CPU renders a band of rows at a time, far below it at any size srt accepts; the GPU draws in
/// tiles that hold at most [`crate::tiles::GPU_TILE_BYTES`] (docs/performance.md, "Memory").
pub const MEMORY_BOUND: u64 = 2 << 30;

/// The GPU's supersampling for `samples` per pixel: it renders at this many times the size.
fn supersampling_scale(samples: u32) -> u32 {
    f64::from(samples).sqrt().ceil() as u32
}

/// Which renderer draws the display colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// The exact CPU ray tracer (srt-trace).
    Cpu,
    /// The GPU; an error without an adapter.
    Gpu,
    /// A GPU that can hold the target; a software adapter (lavapipe, llvmpipe) only where it is
    /// expected to finish before the CPU ([`crate::software`]); otherwise the CPU.
    #[default]
    Auto,
}

srt_scene::choice!(Backend, "backend", {
    Auto => "auto", "a GPU; a software adapter (lavapipe, llvmpipe) only where it is expected to finish first, otherwise the CPU (a note says which and why)";
    Cpu => "cpu", "the exact CPU ray tracer (srt-trace)";
    Gpu => "gpu", "the GPU; an error without an adapter";
});

/// One frame's scene, with the exact CPU tracer (its BVHs, textures and tables) built at most
/// once for every layer of the frame that needs it: the CPU engine's display colours, the
/// radiance and the time channels; and `auto`'s measure of the CPU's cost, whose rows the
/// CPU's picture takes instead of tracing them again.
pub struct Frame<'a> {
    /// The scene at the frame's time, in the frame's view.
    scene: &'a Scene,
    /// The tracer, built on first use.
    tracer: OnceCell<Tracer<'a>>,
    /// The CPU's cost measured on a few rows of the picture ([`Frame::measure_cpu`]), with the
    /// seconds its tracer took to build.
    measure: RefCell<Option<(f64, FrameMeasure)>>,
}

impl<'a> Frame<'a> {
    /// The frame of `scene`; nothing is built yet.
    #[must_use]
    pub const fn new(scene: &'a Scene) -> Self {
        Self {
            scene,
            tracer: OnceCell::new(),
            measure: RefCell::new(None),
        }
    }

    /// The scene.
    #[must_use]
    pub const fn scene(&self) -> &'a Scene {
        self.scene
    }

    /// The CPU tracer of the scene, built on first use.
    pub fn tracer(&self) -> &Tracer<'a> {
        self.tracer.get_or_init(|| Tracer::new(self.scene))
    }

    /// The CPU's cost of a display picture of this frame at `settings`, measured once on
    /// [`PROBE_ROWS`] of its rows ([`Tracer::measure_frame`]), its tracer built (and kept)
    /// first; the rows are kept for the picture.
    pub fn measure_cpu(&self, settings: RenderSettings) -> CpuCost {
        let start = Instant::now();
        let tracer = self.tracer();
        let build_seconds = start.elapsed().as_secs_f64();
        let measure = tracer.measure_frame(settings, Output::Display, PROBE_ROWS);
        let cost = CpuCost::of(build_seconds, &measure);
        *self.measure.borrow_mut() = Some((build_seconds, measure));
        cost
    }

    /// The CPU's cost measured once more ([`Tracer::measure_again`]) on the rows of the last
    /// [`Frame::measure_cpu`], which must have been called; a measure of two passes already is
    /// not repeated.
    ///
    /// # Panics
    /// If the CPU was not measured.
    pub fn measure_cpu_again(&self) -> CpuCost {
        let mut kept = self.measure.borrow_mut();
        let (build_seconds, measure) = kept
            .as_mut()
            .expect("the CPU is measured again only after a first measure");
        if measure.passes() < 2 {
            self.tracer().measure_again(measure);
        }
        CpuCost::of(*build_seconds, measure)
    }
}

/// A renderer ready to produce frames of one scene.
pub enum Engine {
    /// The exact CPU reference.
    Cpu,
    /// The GPU local ray tracer (or polygon method), rendering at `tiling.scale`× the output
    /// size, in tiles where the picture is larger than the adapter or the memory bound allows.
    Gpu {
        /// The adapter and device.
        context: Box<GpuContext>,
        /// The scene's geometry on the GPU, with targets of one tile at `tiling.scale`× the
        /// output size.
        renderer: Box<GpuRenderer>,
        /// The tiles, and the supersampling: each output pixel averages `scale`² rendered
        /// pixels.
        tiling: Tiling,
        /// The method the GPU draws with.
        method: Method,
    },
}

/// An [`Engine`] and why it is not the one asked for, if it is not (`auto` fell back to the
/// CPU): a one-line note for the user.
pub struct Chosen {
    /// The engine.
    pub engine: Engine,
    /// "the GPU …; rendering on the CPU instead", when `auto` fell back.
    pub note: Option<String>,
    /// The GPU devices opened and scenes uploaded in choosing it.
    pub made: Made,
}

/// What choosing an engine made, counted where it is made: a GPU device opened
/// ([`GpuContext::new`], by [`Engine::choose`]) and a scene uploaded ([`GpuRenderer::new`]), so
/// that a kept engine's reuse can be checked ([`KeptEngine::made`], Python's
/// `Renderer.devices_opened` and `Renderer.scene_uploads`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Made {
    /// GPU devices opened, whether kept or not (`auto` may open one and draw on the CPU).
    pub devices: u32,
    /// Scenes uploaded to the GPU (each a [`GpuRenderer`] made: the scene's geometry, textures
    /// and pipelines).
    pub uploads: u32,
}

impl std::ops::AddAssign for Made {
    fn add_assign(&mut self, other: Self) {
        self.devices += other.devices;
        self.uploads += other.uploads;
    }
}

impl Engine {
    /// Picks the renderer for `job`, whose first frame is `frame`: `cpu`, `gpu` (an error
    /// without an adapter) or `auto`: a GPU that can hold the supersampled target; a software
    /// adapter only where it is expected to finish the job before the CPU tracer
    /// ([`crate::software`]: the CPU's cost is measured on a few rows of `frame`, whose tracer is
    /// kept); otherwise the CPU. A note says why, when `auto` did not take the GPU or took a
    /// software adapter. The GPU supersamples by rendering at ⌈√samples⌉× the size.
    ///
    /// # Errors
    /// An approximate method (polygon, image-based) on the CPU or without a GPU, `gpu` without
    /// an adapter, or a scene the GPU cannot prepare (a target beyond its limits when `gpu` was
    /// asked for).
    pub fn choose(
        backend: Backend,
        method: Method,
        job: &Job,
        frame: &Frame<'_>,
    ) -> anyhow::Result<Chosen> {
        let (settings, scene) = (job.settings, frame.scene());
        let cpu = |note: Option<String>| {
            Ok(Chosen {
                engine: Self::Cpu,
                note,
                made: Made::default(),
            })
        };
        // The GPU draws spinning and thrusting bodies with its exact methods (traced through
        // their BVH, docs/physics.md "Spinning and accelerating bodies") and, approximately,
        // with the polygon method (vertex by vertex), but not the moving lights' late shadows
        // they cast.
        if let Some(why) = method.cannot_draw(scene) {
            if backend == Backend::Auto && method.is_exact() {
                return cpu(Some(format!("{why}; rendering on the CPU instead")));
            }
            if backend != Backend::Cpu || !method.is_exact() {
                bail!("{why}");
            }
        }
        let weighs = backend == Backend::Auto && method.is_exact();
        let mut measured = None;
        if weighs && !gpu_possible() {
            // Only a software rasteriser can open: the CPU need not wait for one to know.
            let (cost, at_best) = weigh(
                job,
                SceneSize::of(scene),
                frame.measure_cpu(settings),
                &SoftwareCosts::CHEAPEST,
                || frame.measure_cpu_again(),
            );
            if !at_best.worth_opening() {
                let against = if at_best.cpu_is_faster() {
                    "against at least"
                } else {
                    "too close to opening's cost to open one for, against at least"
                };
                return cpu(Some(format!(
                    "auto renders on the CPU: about {:.2} s ({}), {against} {:.2} s on a \
                     software rasteriser, the only kind of adapter without a GPU device (none \
                     under /dev; docs/performance.md, \"auto without a hardware GPU\")",
                    at_best.cpu_seconds,
                    cost.describe(),
                    at_best.gpu_seconds
                )));
            }
            measured = Some(cost);
        }
        let context = match backend {
            Backend::Cpu if !method.is_exact() => {
                bail!(
                    "the {} method runs on the GPU only; use --backend gpu or auto",
                    method.name()
                )
            }
            Backend::Cpu => return cpu(None),
            Backend::Gpu => GpuContext::new().context("--backend gpu")?,
            Backend::Auto => {
                let measure = weighs && measured.is_none();
                match open_measuring(measure, frame, settings) {
                    (Ok(context), cost) => {
                        measured = measured.or(cost);
                        context
                    }
                    (Err(error), _) if method.is_exact() => {
                        return cpu(Some(format!("{error}; rendering on the CPU instead")));
                    }
                    (Err(error), _) => {
                        bail!("the {} method needs a GPU: {error}", method.name())
                    }
                }
            }
        };
        let chosen = match context.software_api().filter(|_| weighs) {
            None => Self::on_gpu(Box::new(context), backend, method, settings, scene),
            Some(api) => {
                let cost = measured.unwrap_or_else(|| frame.measure_cpu(settings));
                Self::weighed(context, api, &cost, job, frame, method)
            }
        };
        // A device was opened above, whichever engine draws.
        chosen.map(|mut chosen| {
            chosen.made.devices += 1;
            chosen
        })
    }

    /// `auto`'s choice between the CPU and the software adapter of `context`, reached through
    /// `api`, for `job` of `frame`, whose CPU cost is `cost` ([`crate::software`]), with the note
    /// that says which it took and why.
    ///
    /// # Errors
    /// As [`Engine::on_gpu`].
    fn weighed(
        context: GpuContext,
        api: SoftwareApi,
        cost: &CpuCost,
        job: &Job,
        frame: &Frame<'_>,
        method: Method,
    ) -> anyhow::Result<Chosen> {
        let (settings, scene) = (job.settings, frame.scene());
        let (cost, estimates) = weigh(
            job,
            SceneSize::of(scene),
            *cost,
            &SoftwareCosts::of(api),
            || frame.measure_cpu_again(),
        );
        let adapter = format!("{} ({api:?})", context.adapter_info.name);
        if estimates.cpu_is_faster() {
            return Ok(Chosen {
                engine: Self::Cpu,
                note: Some(format!(
                    "auto renders on the CPU: about {:.2} s ({}), against {:.2} s on {adapter}, \
                     a software rasteriser (docs/performance.md, \"auto without a hardware \
                     GPU\")",
                    estimates.cpu_seconds,
                    cost.describe(),
                    estimates.gpu_seconds
                )),
                made: Made::default(),
            });
        }
        let mut chosen = Self::on_gpu(Box::new(context), Backend::Auto, method, settings, scene)?;
        if matches!(chosen.engine, Self::Gpu { .. }) {
            let why = format!(
                "auto renders on {adapter}, a software rasteriser: about {:.2} s, against \
                 {:.2} s on the CPU ({})",
                estimates.gpu_seconds,
                estimates.cpu_seconds,
                cost.describe()
            );
            chosen.note = Some(match chosen.note {
                Some(note) => format!("{why}; {note}"),
                None => why,
            });
        }
        Ok(chosen)
    }

    /// The GPU engine on `context` for `scene` at `settings` ([`Engine::choose`]'s rules): the
    /// scene uploaded for a target ⌈√samples⌉× the size, or with `auto` the CPU when the target
    /// exceeds the adapter's limits.
    fn on_gpu(
        context: Box<GpuContext>,
        backend: Backend,
        method: Method,
        settings: RenderSettings,
        scene: &Scene,
    ) -> anyhow::Result<Chosen> {
        let RenderSettings {
            width,
            height,
            samples,
        } = settings;
        let scale = supersampling_scale(samples);
        let limits = DeviceLimits::of(&context);
        let texel_bytes = srt_gpu::readback::texel_bytes(context.color_format)?;
        let tiling = Tiling::new(width, height, scale, |tile_width, tile_height| {
            check_per_pixel_resources(&limits, tile_width, tile_height, texel_bytes).is_ok()
        });
        let (big_width, big_height) = (tiling.tile_width * scale, tiling.tile_height * scale);
        let mut renderer = match GpuRenderer::new(&context, scene, big_width, big_height) {
            Ok(renderer) => renderer,
            Err(error @ GpuError::ExceedsLimit { .. })
                if backend == Backend::Auto && method.is_exact() =>
            {
                return Ok(Chosen {
                    engine: Self::Cpu,
                    note: Some(format!(
                        "the GPU cannot render {width}x{height} at {samples} samples (in \
                         {big_width}x{big_height} tiles): {error}; rendering on the CPU instead"
                    )),
                    made: Made::default(),
                });
            }
            Err(error) => {
                return Err(error).with_context(|| {
                    format!(
                        "cannot prepare scene {} for the GPU ({width}x{height} at {samples} \
                         samples, in {big_width}x{big_height} tiles; use fewer pixels or \
                         samples, or --backend cpu)",
                        scene.name
                    )
                });
            }
        };
        // Each output pixel averages scale² rendered pixels; a star lights all of them.
        renderer.set_supersampling(scale);
        let observer = &scene.observer;
        let projection = observer.projection;
        let what = observer.picture_decides().then(|| {
            match (projection.is_pinhole(), observer.stereo.is_some()) {
                (true, _) => "for the stereo pair".to_owned(),
                (false, false) => format!("in the {projection} projection"),
                (false, true) => format!("in the {projection} projection's stereo pair"),
            }
        });
        let note = what.filter(|_| method == Method::Auto).map(|what| {
            format!(
                "auto traces every object by the ray tracer (rt) {what}: the local ray tracer's \
                 footprints are drawn through one pinhole"
            )
        });
        Ok(Chosen {
            engine: Self::Gpu {
                context,
                renderer: Box::new(renderer),
                tiling,
                method,
            },
            note,
            made: Made {
                devices: 0,
                uploads: 1,
            },
        })
    }

    /// "cpu" or "gpu METHOD on ADAPTER".
    #[must_use]
    pub fn name(&self) -> String {
        match self {
            Self::Cpu => "cpu".into(),
            Self::Gpu {
                context, method, ..
            } => format!("gpu {} on {}", method.name(), context.adapter_info.name),
        }
    }

    /// The backend, method and adapter entries of an image's provenance record.
    #[must_use]
    pub fn record_entries(&self) -> [(&'static str, String); 3] {
        match self {
            Self::Cpu => [
                ("backend", "cpu".into()),
                ("method", "lrt (exact CPU ray tracer)".into()),
                ("adapter", "none".into()),
            ],
            Self::Gpu {
                context, method, ..
            } => [
                ("backend", "gpu".into()),
                ("method", method.name().into()),
                (
                    "adapter",
                    format!(
                        "{} ({:?})",
                        context.adapter_info.name, context.adapter_info.backend
                    ),
                ),
            ],
        }
    }

    /// Renders one frame's `output`, row-major from the top: display colours (the tone map's,
    /// sRGB-encoded, in [0, 1]) or radiance (what an EXR's R, G, B hold: linear BT.709,
    /// unclamped; srt-color's `radiance` module). The CPU reports finished rows to `progress`
    /// and gives up (`Ok(None)`) once `stop` is set; the GPU finishes the frame.
    ///
    /// # Errors
    /// A GPU failure (device lost, out of memory).
    pub fn render(
        &mut self,
        frame: &Frame<'_>,
        settings: RenderSettings,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> anyhow::Result<Option<Vec<DVec3>>> {
        self.render_band(frame, settings, 0..settings.height, output, progress, stop)
    }

    /// [`Engine::render`]'s picture with the pixels that show an object ([`Drawn`]).
    ///
    /// # Errors
    /// As [`Engine::render`].
    pub fn draw(
        &mut self,
        frame: &Frame<'_>,
        settings: RenderSettings,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> anyhow::Result<Option<Drawn>> {
        self.draw_band(frame, settings, 0..settings.height, output, progress, stop)
    }

    /// How many rows of a picture at `settings` to render at a time when it is written a band
    /// at a time, so that memory does not grow with the picture's height: about
    /// [`BAND_PIXELS`] pixels on the CPU, a row of tiles on the GPU (the whole frame where it is
    /// one tile); a multiple of [`BAND_ROW_MULTIPLE`] either way.
    #[must_use]
    pub fn band_rows(&self, settings: RenderSettings) -> u32 {
        let rows = match self {
            Self::Cpu => {
                let rows = BAND_PIXELS / u64::from(settings.width.max(1));
                u32::try_from(rows).unwrap_or(u32::MAX).min(settings.height)
            }
            Self::Gpu { tiling, .. } => tiling.tile_height,
        };
        rows.max(1).div_ceil(BAND_ROW_MULTIPLE) * BAND_ROW_MULTIPLE
    }

    /// The rows `rows` of [`Engine::render`]'s picture: the CPU renders only those rows, the
    /// same pixels bit for bit (`progress` hears the band's finished rows); the GPU draws the
    /// tiles over them, or the whole frame where it is one tile, and keeps them.
    ///
    /// # Errors
    /// A GPU failure (device lost, out of memory).
    ///
    /// # Panics
    /// If `rows` reaches past the picture's height.
    pub fn render_band(
        &mut self,
        frame: &Frame<'_>,
        settings: RenderSettings,
        rows: Range<u32>,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> anyhow::Result<Option<Vec<DVec3>>> {
        let drawn = self.draw_band(frame, settings, rows, output, progress, stop)?;
        Ok(drawn.map(|drawn| drawn.pixels))
    }

    /// The rows `rows` of [`Engine::draw`]'s picture: [`Engine::render_band`]'s pixels with
    /// those that show an object.
    ///
    /// # Errors
    /// As [`Engine::render_band`].
    ///
    /// # Panics
    /// As [`Engine::render_band`].
    pub fn draw_band(
        &mut self,
        frame: &Frame<'_>,
        settings: RenderSettings,
        rows: Range<u32>,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> anyhow::Result<Option<Drawn>> {
        let scene = frame.scene();
        Ok(match self {
            Self::Cpu => {
                let measure = frame.measure.borrow();
                let known = measure.as_ref().map(|(_, measure)| measure);
                frame
                    .tracer()
                    .render_band_reusing(settings, rows, output, progress, stop, known)
                    .map(|image| Drawn {
                        seen: image.coverage.iter().map(|&object| object != 0).collect(),
                        pixels: image.pixels,
                    })
            }
            Self::Gpu {
                context,
                renderer,
                tiling,
                method,
            } => {
                let failed = || format!("GPU rendering of {} failed", scene.name);
                let scale = tiling.scale;
                let mut draw = |window| {
                    renderer.set_window(window);
                    let (image, _) = renderer
                        .render_as(context, scene, *method, FootprintShape::Hull, output)
                        .with_context(failed)?;
                    let (width, height) = (image.width / scale, image.height / scale);
                    anyhow::Ok(downsample(&image.pixels, width, height, scale))
                };
                let band = if tiling.is_whole() {
                    keep_rows(draw(None)?, settings.width, rows)
                } else {
                    assemble(tiling, rows, |tile| draw(Some(tiling.window(tile, scale))))?
                };
                let (pixels, seen) = band.into_iter().unzip();
                Some(Drawn { pixels, seen })
            }
        })
    }
}

/// Opens the GPU for `auto` on another thread and meanwhile, on this one, measures the CPU's
/// cost of `frame` at `settings` ([`CpuCost::measure`], whose tracer `frame` keeps) when
/// `measure` is set and the scene has at most [`MEASURED_WHILE_OPENING`] triangles (a larger
/// one's tracer is built only once the adapter is known to be a software one). The measure then
/// costs little beyond the adapter's opening.
fn open_measuring(
    measure: bool,
    frame: &Frame<'_>,
    settings: RenderSettings,
) -> (Result<GpuContext, GpuError>, Option<CpuCost>) {
    std::thread::scope(|scope| {
        let opening = scope.spawn(GpuContext::new);
        let measured = (measure && frame.scene().triangle_count() <= MEASURED_WHILE_OPENING)
            .then(|| frame.measure_cpu(settings));
        let opened = opening
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (opened, measured)
    })
}

/// A picture (or a band of its rows) as [`Engine::draw`] draws it: its pixels and, per pixel,
/// whether it shows an object — on the CPU whether the ray through its centre hits one (the
/// `--aov` object channel's test), on the GPU whether any of its supersamples does — for
/// [`crate::empty`]'s test of an empty picture, which colours cannot decide under a starry sky.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    /// Display colours or radiance, row-major from the top.
    pub pixels: Vec<DVec3>,
    /// Per pixel, in the same order, whether an object is seen in it.
    pub seen: Vec<bool>,
}

/// An engine kept for a sequence of frames whose scenes may change (Python's `srt.Renderer`):
/// the GPU's device is made once, and a scene is uploaded again only when its [`UploadKey`]
/// asks for it (srt-scene's one rule, on the editor's structure version, as the viewer and the
/// web page keep theirs), when the settings change, or when the GPU cannot draw it (a
/// projection it does not trace); each frame is drawn by the engine [`Engine::choose`] would
/// choose for it.
pub struct KeptEngine {
    /// The backend asked for.
    backend: Backend,
    /// The method asked for.
    method: Method,
    /// The engine, with the key of the upload it holds and the settings it was made for.
    kept: Option<(Engine, UploadKey, RenderSettings)>,
    /// Whether the GPU was asked for by `auto` and could not serve (no adapter, a target
    /// beyond its limits, or a software adapter expected to be slower than the CPU): a CPU
    /// engine chosen only because the GPU could not draw a frame (a projection it does not
    /// trace) gives way to the GPU again when it can.
    gpu_unavailable: bool,
    /// The devices opened and scenes uploaded for every frame so far.
    made: Made,
}

impl KeptEngine {
    /// Nothing made yet: the first frame chooses the engine.
    #[must_use]
    pub const fn new(backend: Backend, method: Method) -> Self {
        Self {
            backend,
            method,
            kept: None,
            gpu_unavailable: false,
            made: Made {
                devices: 0,
                uploads: 0,
            },
        }
    }

    /// The GPU devices opened and scenes uploaded over every frame so far: one device, and an
    /// upload for each change of the scene's structure or of the settings, where the GPU draws.
    #[must_use]
    pub const fn made(&self) -> Made {
        self.made
    }

    /// The device the last frame was drawn on: `None` before the first frame, and where the CPU
    /// drew it.
    #[must_use]
    pub fn context(&self) -> Option<&GpuContext> {
        match &self.kept {
            Some((Engine::Gpu { context, .. }, ..)) => Some(context),
            _ => None,
        }
    }

    /// The engine ready to render `job` of `frame`, whose scene's upload is `key`, and
    /// [`Chosen::note`] when it was chosen for this frame.
    ///
    /// # Errors
    /// As [`Engine::choose`].
    pub fn engine_for(
        &mut self,
        frame: &Frame<'_>,
        job: &Job,
        key: &UploadKey,
    ) -> anyhow::Result<(&mut Engine, Option<String>)> {
        let (scene, settings) = (frame.scene(), job.settings);
        let gpu_can_draw = self.method.cannot_draw(scene).is_none();
        let fits = |(engine, uploaded, made_for): &(Engine, UploadKey, RenderSettings)| {
            *made_for == settings
                && !uploaded.needs_upload(key)
                && match engine {
                    Engine::Cpu => {
                        self.backend == Backend::Cpu || self.gpu_unavailable || !gpu_can_draw
                    }
                    Engine::Gpu { .. } => gpu_can_draw,
                }
        };
        let mut note = None;
        let kept = match self.kept.take() {
            Some(kept) if fits(&kept) => kept,
            previous => {
                let chosen = match previous {
                    Some((Engine::Gpu { context, .. }, ..)) if gpu_can_draw => {
                        Engine::on_gpu(context, self.backend, self.method, settings, scene)?
                    }
                    _ => Engine::choose(self.backend, self.method, job, frame)?,
                };
                self.gpu_unavailable = self.backend == Backend::Auto
                    && gpu_can_draw
                    && matches!(chosen.engine, Engine::Cpu);
                note = chosen.note;
                self.made += chosen.made;
                (chosen.engine, key.clone(), settings)
            }
        };
        let (engine, ..) = self.kept.insert(kept);
        Ok((engine, note))
    }
}

/// The per-pixel channels `--aov` adds to an EXR (and `srt.render(aov=True)` returns), in the
/// order of [`aov_values`]: what each pixel's centre sees of time ([`SeenEvent`];
/// docs/scene-format.md, "Per-pixel channels").
pub const AOV_CHANNELS: [&str; 5] = srt_gpu::SEEN_CHANNELS;

impl Engine {
    /// What each pixel's centre sees of time, row-major from the top, as [`AOV_CHANNELS`] orders
    /// it ([`aov_values`]): from the CPU tracer, or the GPU's seen-event passes
    /// ([`GpuRenderer::render_seen`], rendered at the output size whatever the supersampling,
    /// since a pixel's event is its centre's). A GPU whose colour target is half float (GL)
    /// cannot hold times to f32 precision, so the CPU tracer computes them there. `Ok(None)` if
    /// `stop` was set.
    ///
    /// # Errors
    /// A GPU failure.
    pub fn render_aov(
        &mut self,
        frame: &Frame<'_>,
        settings: RenderSettings,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> anyhow::Result<Option<Vec<[f32; 5]>>> {
        self.render_aov_band(frame, settings, 0..settings.height, progress, stop)
    }

    /// The rows `rows` of [`Engine::render_aov`]'s channels, as [`Engine::render_band`] gives
    /// a band of the colours.
    ///
    /// # Errors
    /// A GPU failure.
    ///
    /// # Panics
    /// If `rows` reaches past the picture's height.
    pub fn render_aov_band(
        &mut self,
        frame: &Frame<'_>,
        settings: RenderSettings,
        rows: Range<u32>,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> anyhow::Result<Option<Vec<[f32; 5]>>> {
        let scene = frame.scene();
        match self {
            Self::Gpu {
                context,
                renderer,
                tiling,
                method,
            } if context.color_format == srt_gpu::formats::COLOR_FORMAT => {
                let failed = || format!("GPU rendering of {}'s time channels failed", scene.name);
                // Drawn at the output size (scale 1), in tiles of the output's tile size.
                let unscaled = Tiling {
                    scale: 1,
                    ..*tiling
                };
                renderer
                    .resize(context, unscaled.tile_width, unscaled.tile_height)
                    .with_context(failed)?;
                let mut draw = |window| {
                    renderer.set_window(window);
                    renderer
                        .render_seen(context, scene, *method, FootprintShape::Hull)
                        .with_context(failed)
                };
                let seen = if unscaled.is_whole() {
                    draw(None).map(|seen| keep_rows(seen, settings.width, rows))
                } else {
                    assemble(&unscaled, rows, |tile| draw(Some(unscaled.window(tile, 1))))
                };
                let scale = tiling.scale;
                renderer
                    .resize(
                        context,
                        tiling.tile_width * scale,
                        tiling.tile_height * scale,
                    )
                    .with_context(failed)?;
                Ok(Some(seen?))
            }
            _ => Ok(frame
                .tracer()
                .render_seen_events_band(settings.width, settings.height, rows, progress, stop)
                .map(|events| events.iter().map(|e| aov_values(e.as_ref())).collect())),
        }
    }
}

/// A pixel's [`AOV_CHANNELS`] values as 32-bit floats: the object's index in scene order, or −1
/// with every other channel 0 where no object is seen.
#[must_use]
pub fn aov_values(seen: Option<&SeenEvent>) -> [f32; 5] {
    seen.map_or([0.0, 0.0, 0.0, 0.0, -1.0], |event| {
        #[expect(
            clippy::cast_precision_loss,
            reason = "object indices are far below 2^24"
        )]
        let object = event.object as f32;
        let float = channel_f32;
        [
            float(event.emission_ct),
            float(event.proper_time),
            float(event.distance),
            float(event.doppler),
            object,
        ]
    })
}

/// A display colour (sRGB-encoded) as the linear light an EXR's display channels hold.
#[must_use]
pub fn display_as_linear(colour: f64) -> f32 {
    #[expect(clippy::cast_possible_truncation, reason = "32-bit float channels")]
    let linear = srgb_decode(colour.clamp(0.0, 1.0)) as f32;
    linear
}

/// A value (radiance, a time, a factor) as an EXR's 32-bit float channel holds it: rounded to
/// f32, a magnitude beyond f32's range held at its largest finite value (radiance can exceed it
/// where the lamp is nearly invisible: docs/colour.md), so that every channel is finite.
#[must_use]
pub fn channel_f32(value: f64) -> f32 {
    let largest = f64::from(f32::MAX);
    #[expect(clippy::cast_possible_truncation, reason = "32-bit float channels")]
    let float = value.clamp(-largest, largest) as f32;
    float
}

/// The rows `rows` of `pixels`, a picture `width` pixels wide, row-major from the top.
fn keep_rows<T>(mut pixels: Vec<T>, width: u32, rows: Range<u32>) -> Vec<T> {
    let width = width as usize;
    pixels.truncate(rows.end as usize * width);
    pixels.drain(..rows.start as usize * width);
    pixels
}

/// Box-filters an image rendered at `scale`× the size down to `width` × `height`; with each
/// pixel, whether some sample of it shows an object (alpha 1 in the GPU's colour target, 0 where
/// the background or the sky is seen: `GpuImage::pixels`).
fn downsample(pixels: &[[f32; 4]], width: u32, height: u32, scale: u32) -> Vec<(DVec3, bool)> {
    let big_width = (width * scale) as usize;
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height as usize {
        for x in 0..width as usize {
            let mut sum = DVec3::ZERO;
            let mut seen = false;
            for dy in 0..scale as usize {
                for dx in 0..scale as usize {
                    let p = pixels[(y * scale as usize + dy) * big_width + x * scale as usize + dx];
                    sum += DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
                    seen |= p[3] > 0.5;
                }
            }
            out.push((sum / f64::from(scale * scale), seen));
        }
    }
    out
}
