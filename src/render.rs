//! `srt render`: resolve the scene, apply command-line overrides, choose the backend, render one
//! image or an animation, and write it.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context as _, bail};
use glam::DVec3;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use srt_gpu::{FootprintShape, GpuContext, GpuError, GpuRenderer, Method};
use srt_physics::Frame;
use srt_scene::limits::MAX_COORDINATE;
use srt_scene::{Effects, Scene};
use srt_trace::{RenderSettings, Tracer};

use crate::cli::{Backend, EffectsArg, MethodArg, RenderArgs};
use crate::output::{check_writable, numbered, write_image};
use crate::source::load_scene;

/// A renderer ready to produce frames of one scene.
enum Engine {
    /// The exact CPU reference.
    Cpu,
    /// The GPU local ray tracer (or polygon method), rendering at `scale`× the output size.
    Gpu {
        context: Box<GpuContext>,
        renderer: Box<GpuRenderer>,
        scale: u32,
        method: Method,
    },
}

impl Engine {
    fn name(&self) -> String {
        match self {
            Self::Cpu => "cpu".into(),
            Self::Gpu {
                context, method, ..
            } => format!("gpu {} on {}", method.name(), context.adapter_info.name),
        }
    }
}

/// Runs `srt render`.
///
/// # Errors
/// Any user-facing failure: unknown scene, bad file, bad override, no GPU for `--backend gpu`,
/// unwritable output.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    // A named output is checked before the scene is even loaded: a typo in -o must not cost a
    // model import and a render.
    if let Some(output) = &args.output {
        check_writable(output)?;
    }
    let (mut scene, warnings) = load_scene(&args.scene, args.beta)?;
    for warning in &warnings {
        eprintln!("warning: {warning}");
    }
    apply_overrides(&mut scene, args)?;
    let output = match &args.output {
        Some(output) => output.clone(),
        None => {
            let output = PathBuf::from(format!("{}.png", file_safe(&scene.name)));
            check_writable(&output)?;
            output
        }
    };
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        samples: args.samples,
    };
    let mut engine = choose_engine(args, &scene)?;
    match args.frames {
        None => render_one(&mut engine, &scene, settings, &output),
        Some(frames) => {
            let t0 = observation_time("--t0", args.t0.unwrap_or(scene.observer.ct))?;
            let t1 = observation_time("--t1", args.t1.unwrap_or(t0 + 10.0))?;
            let digits = frames.to_string().len().max(4);
            for frame in 0..frames {
                let fraction = if frames > 1 {
                    f64::from(frame) / f64::from(frames - 1)
                } else {
                    0.0
                };
                scene.observer.ct = t0 + fraction * (t1 - t0);
                render_one(
                    &mut engine,
                    &scene,
                    settings,
                    &numbered(&output, frame, digits),
                )?;
            }
            Ok(())
        }
    }
}

/// Picks the renderer: `cpu`, `gpu` (an error without an adapter) or `auto` (the GPU when
/// there is one, otherwise the CPU with a one-line notice).
fn choose_engine(args: &RenderArgs, scene: &Scene) -> anyhow::Result<Engine> {
    let method = match args.method {
        MethodArg::Lrt => Method::Lrt,
        MethodArg::Polygon => Method::Polygon,
    };
    let context = match args.backend {
        Backend::Cpu if method == Method::Polygon => {
            bail!("the polygon method runs on the GPU only; use --backend gpu or auto")
        }
        Backend::Cpu => return Ok(Engine::Cpu),
        Backend::Gpu => GpuContext::new().context("--backend gpu")?,
        Backend::Auto => match GpuContext::new() {
            Ok(context) => context,
            Err(error) if method == Method::Lrt => {
                eprintln!("note: {error}; rendering on the CPU instead");
                return Ok(Engine::Cpu);
            }
            Err(error) => bail!("the polygon method needs a GPU: {error}"),
        },
    };
    // Supersampling on the GPU: render at ⌈√N⌉× the size and average.
    let scale = f64::from(args.samples).sqrt().ceil() as u32;
    let (width, height) = (args.width * scale, args.height * scale);
    let renderer = match GpuRenderer::new(&context, scene, width, height) {
        Ok(renderer) => renderer,
        Err(error @ GpuError::ExceedsLimit { .. })
            if args.backend == Backend::Auto && method == Method::Lrt =>
        {
            eprintln!(
                "note: the GPU cannot render {}x{} at {} samples (a {width}x{height} target): \
                 {error}; rendering on the CPU instead",
                args.width, args.height, args.samples
            );
            return Ok(Engine::Cpu);
        }
        Err(error) => {
            return Err(error).with_context(|| {
                format!(
                    "cannot prepare scene {} for the GPU ({}x{} at {} samples needs a \
                     {width}x{height} target; use fewer pixels or samples, or --backend cpu)",
                    scene.name, args.width, args.height, args.samples
                )
            });
        }
    };
    Ok(Engine::Gpu {
        context: Box::new(context),
        renderer: Box::new(renderer),
        scale,
        method,
    })
}

/// Applies --effects, --time and --beta.
fn apply_overrides(scene: &mut Scene, args: &RenderArgs) -> anyhow::Result<()> {
    if let Some(effects) = args.effects {
        scene.set_effects(match effects {
            EffectsArg::Geometry => Effects::Geometry,
            EffectsArg::Doppler => Effects::Doppler,
            EffectsArg::Searchlight => Effects::Searchlight,
        });
    }
    if let Some(ct) = args.time {
        scene.observer.ct = observation_time("--time", ct)?;
    }
    if let Some(beta) = args.beta {
        for object in &mut scene.objects {
            object.frame = Frame::new(beta, object.frame.offset()).with_context(|| {
                format!(
                    "--beta {:?},{:?},{:?} is not a valid velocity",
                    beta.x, beta.y, beta.z
                )
            })?;
        }
    }
    Ok(())
}

/// `ct` if it is a finite observation time within ±`MAX_COORDINATE`, the scene file's bound.
fn observation_time(option: &str, ct: f64) -> anyhow::Result<f64> {
    if ct.is_finite() && ct.abs() <= MAX_COORDINATE {
        Ok(ct)
    } else {
        bail!("{option} must be a finite number within ±{MAX_COORDINATE:e}, got {ct:?}")
    }
}

/// A name usable as a file name.
fn file_safe(name: &str) -> String {
    let cleaned: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if cleaned.is_empty() {
        "render".into()
    } else {
        cleaned
    }
}

/// Renders one frame with `engine` and writes it to `output`.
fn render_one(
    engine: &mut Engine,
    scene: &Scene,
    settings: RenderSettings,
    output: &Path,
) -> anyhow::Result<()> {
    let start = Instant::now();
    let pixels = match engine {
        Engine::Cpu => render_cpu(scene, settings),
        Engine::Gpu {
            context,
            renderer,
            scale,
            method,
        } => {
            let (image, _) = renderer
                .render(context, scene, *method, FootprintShape::Hull)
                .with_context(|| format!("GPU rendering of {} failed", scene.name))?;
            downsample(&image.pixels, settings.width, settings.height, *scale)
        }
    };
    write_image(settings.width, settings.height, &pixels, output)?;
    println!(
        "wrote {} ({}x{}, {} sample{} per pixel, {}, {:.2} s)",
        output.display(),
        settings.width,
        settings.height,
        settings.samples,
        if settings.samples == 1 { "" } else { "s" },
        engine.name(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The exact CPU render, with a progress bar once it takes more than a second.
fn render_cpu(scene: &Scene, settings: RenderSettings) -> Vec<DVec3> {
    let start = Instant::now();
    let tracer = Tracer::new(scene);
    let bar = ProgressBar::with_draw_target(
        Some(u64::from(settings.height)),
        ProgressDrawTarget::hidden(),
    );
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} rendering {msg} [{bar:40}] {pos}/{len} rows, {eta} left",
        )
        .expect("valid progress template")
        .progress_chars("=> "),
    );
    bar.set_message(scene.name.clone());
    let shown = AtomicBool::new(false);
    let image = tracer.render(settings, &|rows| {
        if start.elapsed().as_secs_f64() > 1.0 && !shown.swap(true, Ordering::Relaxed) {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_position(u64::from(rows));
    });
    bar.finish_and_clear();
    image.pixels
}

/// Box-filters an image rendered at `scale`× the size down to `width` × `height`.
fn downsample(pixels: &[[f32; 4]], width: u32, height: u32, scale: u32) -> Vec<DVec3> {
    let big_width = (width * scale) as usize;
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height as usize {
        for x in 0..width as usize {
            let mut sum = DVec3::ZERO;
            for dy in 0..scale as usize {
                for dx in 0..scale as usize {
                    let p = pixels[(y * scale as usize + dy) * big_width + x * scale as usize + dx];
                    sum += DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
                }
            }
            out.push(sum / f64::from(scale * scale));
        }
    }
    out
}
