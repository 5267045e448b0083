//! `cargo xtask bench`: the paper's Table 1 on the current adapter, and scenes in motion.
//!
//! For each case: the median frame time of each exact method — `auto` (what `srt` uses: each
//! object by LRT or the BVH ray tracer), local ray tracing alone (LRT, hull footprints) and the
//! ray tracer alone (RT) — and of the polygon method, taking turns frame by frame; `ratio` is
//! auto's against the polygon method's. Per pixel the scene actually covers (coverage from the
//! exact CPU renderer): visibility fragments run by each exact method (`overdraw_auto`,
//! `overdraw_hull` for LRT, `overdraw_rt`) and `shaded_per_pixel`, pixels shaded. Cases:
//!
//! - the paper's static frames (the five scenes of the issue) at 1280×720 and 1920×1080;
//! - fly-by sweeps at 1280×720: the teaser while the spider passes the camera, the engine
//!   passing beside, above and behind it, and the `flythrough`'s observer flying on between
//!   columns passing beside it, 12 frames each, and the `rolling-wheel` rolling past (6
//!   frames); one line per sweep with the worst frame's ratio (`worst_ratio`), each method's
//!   worst ratio and slowest frame;
//! - large scenes: three engines side by side (364 488 triangles), and nine in a 3 × 3 grid
//!   (1 093 464 triangles);
//! - what the newer features cost: the teaser with spectral colour (`teaser-spectral`) and the
//!   `flythrough` (a moving observer under 6 000 stars), and two moving lights with their late
//!   shadows against the same scene without shadows (`two moving lights`), and bodies that
//!   move in their rest frame: the spinning `rolling-wheel` and the thrusting `rocket` (traced
//!   along each ray's body-space curve; the polygon method moves each vertex).
//!
//! - the full sky: the `flythrough` as the full sphere at 2048×1024 ([`FULL_SKY_SIZE`]), drawn
//!   by the ray tracer and `auto` (LRT and the polygon method draw through the pinhole only),
//!   beside the CPU reference's time for the same frame.
//!
//! `--size WxH` (repeatable) measures the static cases at other sizes instead, the sweeps at
//! the first. `--throughput` measures instead how many frames per second each method sustains
//! on the static cases, at 1280×720 or at each `--size` ([`throughput`]).
//!
//! Prints one line per case. A full run rewrites the generated blocks of `docs/performance.md`
//! (the table and the summary sentences, [`document`]) and saves every measurement as
//! `docs/performance-results.json` ([`results`]), or, on a hardware GPU, blocks and a results
//! file of its own ([`report`]); `--results PATH` saves them elsewhere too, on
//! any run, and `--compare OLD NEW` puts two saved runs side by side ([`compare`]).

mod compare;
mod document;
mod replay;
mod report;
pub mod results;
mod summary;
mod throughput;

pub use document::BENCH_FRAMES_RECORD;

use std::path::Path;
use std::time::Instant;

use anyhow::Context as _;
use glam::DVec3;
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_physics::Frame;
use srt_scene::{MovingLight, Projection, Scene, SurfaceColour};
use srt_trace::{RenderSettings, Tracer};

use crate::cases::{
    Case, ENGINE, ENGINE_BESIDE, at_time, builtin_cases, engine_sweep_times,
    flythrough_sweep_times, model_case, shifted, teaser_sweep_times,
};
use crate::renderers::KeptRenderer;
use results::{
    CaseResult, FullSkyResult, Machine, Measurement, Results, SweepFrame, SweepResult, median,
};

/// Image sizes of the static cases unless `--size` names others; the first is also that of the
/// sweeps (and `--throughput` measures at the first alone).
pub const DEFAULT_SIZES: [(u32, u32); 2] = [(1280, 720), (1920, 1080)];

/// Parses an image size written `WIDTHxHEIGHT` (e.g. `3840x2160`), each from 1 to 16 384.
///
/// # Errors
/// A message naming the text and what is wrong with it.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (width, height) = text
        .split_once(['x', '×'])
        .ok_or_else(|| format!("{text:?} is not a size: write WIDTHxHEIGHT, e.g. 1920x1080"))?;
    let side = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=16_384).contains(n))
            .ok_or_else(|| format!("{text:?}: {s:?} is not a side from 1 to 16384 pixels"))
    };
    Ok((side(width)?, side(height)?))
}
/// Frames rendered by every method before timing starts.
const WARM_UP: u32 = 2;

/// Least time each method's timed frames of one measurement add up to: a case whose frames
/// are short takes more than the requested frames, so that one slow spell of the machine (a
/// millisecond on a 3 ms frame) does not decide its median.
const MIN_MEASURED_MS: u32 = 250;

/// Most frames timed per method in one measurement, however short its frames.
const MAX_FRAMES: u32 = 60;
/// How long a hardware GPU renders the case's frames back to back before they are timed
/// ([`Timing::Timestamps`]), so that its clock is up.
const CLOCK_WARM_UP: std::time::Duration = std::time::Duration::from_millis(300);

/// How the bench times a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Timing {
    /// GPU timestamp queries from the frame's first pass to the end of its last.
    Timestamps,
    /// The wall clock from encoding the frame to the GPU's idle (no readback).
    Wall,
}

impl Timing {
    /// GPU timestamps where the adapter has them and they time the work, the wall clock
    /// elsewhere. A CPU adapter (Mesa's lavapipe, llvmpipe) writes a render pass's end
    /// timestamp once its draws are binned, before the deferred rasterisation runs, so the
    /// fragment work that dominates LRT and RT escapes its timestamps (the flythrough's LRT
    /// frame at 1280×720: 127 ms by timestamps, 494 ms from submit to idle; the polygon
    /// method's, mostly vertex work: 118 ms and 164 ms with readback; performance-log.md).
    fn for_adapter(ctx: &GpuContext) -> Self {
        if ctx.timestamps && ctx.adapter_info.device_type != wgpu::DeviceType::Cpu {
            Self::Timestamps
        } else {
            Self::Wall
        }
    }

    /// How the results and docs/performance.md name it.
    const fn describe(self) -> &'static str {
        match self {
            Self::Timestamps => "GPU timestamp queries",
            Self::Wall => {
                "the wall clock from encoding a frame to the GPU's idle, no readback (a CPU \
                 adapter's timestamps miss its deferred rasterisation)"
            }
        }
    }
}

/// Median frame time in ms of each of `methods` (timed as `timing` says) and median time of its
/// proxy pass (0 where unknown: the wall clock cannot single it out). The methods take turns
/// frame by frame, so that a slow spell of the machine (software adapters share its cores)
/// falls on all of them alike, for at least `frames` turns and on until every method's frames
/// add up to [`MIN_MEASURED_MS`], at most [`MAX_FRAMES`] turns.
fn frame_times<const N: usize>(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    methods: [Method; N],
    frames: u32,
) -> anyhow::Result<[(f64, f64); N]> {
    let timing = Timing::for_adapter(ctx);
    for _ in 0..WARM_UP {
        for method in methods {
            renderer.render(ctx, scene, method, FootprintShape::Hull)?;
        }
    }
    if timing == Timing::Timestamps {
        // A hardware GPU idles while the case is prepared on the CPU and lowers its clock
        // (an H200 to a sixth, within a second): frames back to back bring it up again.
        let start = Instant::now();
        while start.elapsed() < CLOCK_WARM_UP {
            for method in methods {
                throughput::submit(ctx, renderer, scene, method)?;
            }
            ctx.wait()?;
        }
    }
    let mut times = [(); N].map(|()| (Vec::new(), Vec::new()));
    let enough = |times: &[(Vec<f64>, Vec<f64>); N]| {
        let least_ms = times
            .iter()
            .map(|(time, _)| time.iter().sum::<f64>())
            .fold(f64::INFINITY, f64::min);
        timed_enough(times[0].0.len(), least_ms, frames)
    };
    while !enough(&times) {
        for (method, (time, proxy)) in methods.iter().zip(&mut times) {
            let (frame_ms, proxy_ms) = match timing {
                Timing::Timestamps => timestamped_ms(ctx, renderer, scene, *method)?,
                Timing::Wall => (submit_to_idle_ms(ctx, renderer, scene, *method)?, 0.0),
            };
            time.push(frame_ms);
            proxy.push(proxy_ms);
        }
    }
    Ok(times.map(|(time, proxy)| (median(time), median(proxy))))
}

/// Whether `turns` turns of the methods are enough, the method whose timed frames add up to
/// least having `least_ms`: at least `frames` turns, then on until [`MIN_MEASURED_MS`] or
/// [`MAX_FRAMES`] turns.
fn timed_enough(turns: usize, least_ms: f64, frames: u32) -> bool {
    turns >= frames as usize
        && (least_ms >= f64::from(MIN_MEASURED_MS) || turns >= MAX_FRAMES as usize)
}

/// Milliseconds from encoding one frame of `scene` with `method` to the GPU's idle, as the
/// viewer draws a frame (encode, submit, wait; no readback).
fn submit_to_idle_ms(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    method: Method,
) -> anyhow::Result<f64> {
    let start = Instant::now();
    throughput::submit(ctx, renderer, scene, method)?;
    ctx.wait()?;
    let elapsed = start.elapsed().as_secs_f64() * 1e3;
    ctx.take_errors()?;
    Ok(elapsed)
}

/// GPU time in ms of one frame of `scene` with `method` and of its proxy pass, by timestamp
/// queries, the frame queued behind an untimed one and nothing read back but its timestamps:
/// the GPU stays busy between measurements. Waiting for each frame and reading its image back
/// kept an H200's SM clock at its idle 345 MHz, so that only the methods' ratios meant
/// anything (performance-log.md, 2026-11-26 sixth entry).
fn timestamped_ms(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    method: Method,
) -> anyhow::Result<(f64, f64)> {
    throughput::submit(ctx, renderer, scene, method)?;
    throughput::submit(ctx, renderer, scene, method)?;
    ctx.wait()?;
    ctx.take_errors()?;
    let (frame_ms, proxy_ms) = renderer.frame_times(ctx, method)?;
    Ok((
        frame_ms.context("the adapter has timestamp queries")?,
        proxy_ms.unwrap_or(0.0),
    ))
}

/// Times the methods on `scene` with `renderer` (made for this scene's structure), then counts
/// each exact method's fragments against the pixels the exact renderer finds covered.
fn measure(
    ctx: &GpuContext,
    renderer: &mut GpuRenderer,
    scene: &Scene,
    frames: u32,
) -> anyhow::Result<Measurement> {
    renderer.set_fragment_counting(false);
    let [
        (lrt_ms, proxy_ms),
        (rt_ms, _),
        (auto_ms, _),
        (polygon_ms, _),
    ] = frame_times(
        ctx,
        renderer,
        scene,
        [Method::Lrt, Method::Rt, Method::Auto, Method::Polygon],
        frames,
    )?;
    let image_based_ms = if Method::ImageBased.cannot_draw(scene).is_none() {
        let [(ms, _)] = frame_times(ctx, renderer, scene, [Method::ImageBased], frames)?;
        Some(ms)
    } else {
        None
    };
    let (width, height) = renderer.size();
    let covered = Tracer::new(scene)
        .render(
            RenderSettings {
                width,
                height,
                samples: 1,
            },
            &|_| {},
        )
        .coverage
        .iter()
        .filter(|&&c| c != 0)
        .count()
        .max(1) as f64;
    renderer.set_fragment_counting(true);
    let count = |method| -> anyhow::Result<_> {
        renderer
            .render(ctx, scene, method, FootprintShape::Hull)?
            .1
            .fragments
            .context("the renderer counts fragments")
    };
    let (lrt, rt, auto) = (
        count(Method::Lrt)?,
        count(Method::Rt)?,
        count(Method::Auto)?,
    );
    renderer.set_fragment_counting(false);
    // The depth the visibility passes declare (at least the footprint's) must hold, or a GPU
    // that tests depth early may drop visible fragments: the timed images would be wrong.
    let nearer = lrt.nearer_than_footprint + rt.nearer_than_footprint + auto.nearer_than_footprint;
    anyhow::ensure!(
        nearer == 0,
        "{nearer} visibility fragments found hits nearer than their footprints' depth bound \
         (LRT {}, RT {}, auto {})",
        lrt.nearer_than_footprint,
        rt.nearer_than_footprint,
        auto.nearer_than_footprint
    );
    Ok(Measurement {
        lrt_ms,
        proxy_ms,
        rt_ms,
        auto_ms,
        polygon_ms,
        image_based_ms,
        overdraw_hull: lrt.run as f64 / covered,
        overdraw_rt: rt.run as f64 / covered,
        overdraw_auto: auto.run as f64 / covered,
        shaded_per_pixel: lrt.shaded.max(rt.shaded).max(auto.shaded) as f64 / covered,
    })
}

/// Measures `case` with `renderer` (made for its scene's structure) as a result.
fn measure_case(
    ctx: &GpuContext,
    renderer: &mut GpuRenderer,
    case: &Case,
    frames: u32,
) -> anyhow::Result<CaseResult> {
    let measurement = measure(ctx, renderer, &case.scene, frames)?;
    let (width, height) = renderer.size();
    Ok(CaseResult {
        name: case.name.clone(),
        width,
        height,
        triangles: case.scene.triangle_count(),
        traced_objects: renderer.auto_traced_objects(&case.scene),
        objects: object_load_records(renderer, &case.scene),
        measurement,
        cpu_ms: None,
    })
}

/// The exact CPU reference's frame of `scene` at `width` × `height`, one sample per pixel:
/// median of three renders by one tracer, made before (a sequence of frames keeps its BVHs), ms.
fn cpu_frame_ms(scene: &Scene, (width, height): (u32, u32)) -> f64 {
    let tracer = Tracer::new(scene);
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    let times = (0..3)
        .map(|_| {
            let start = Instant::now();
            drop(tracer.render(settings, &|_| {}));
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    median(times)
}

/// What `auto` weighs of each of `scene`'s objects with `renderer`, as the results keep it.
fn object_load_records(renderer: &GpuRenderer, scene: &Scene) -> Vec<results::ObjectLoadRecord> {
    renderer
        .object_loads(scene)
        .into_iter()
        .flatten()
        .map(Into::into)
        .collect()
}

/// Copies the results file `input` to `output` with [`CaseResult::objects`] filled in for
/// every static case and sweep frame, each frame's scene rebuilt by its name and size
/// ([`timed_frames`]) and uploaded to this machine's adapter.
///
/// # Errors
/// No GPU, a frame this bench no longer times, missing models, unreadable or unwritable files.
pub fn run_object_loads(input: &Path, output: &Path) -> anyhow::Result<()> {
    let mut results = Results::load(input)?;
    let ctx = GpuContext::new().context("filling in object loads needs a GPU adapter")?;
    // Every frame the bench times at each size met, built once per size.
    let mut frames_by_size = std::collections::HashMap::new();
    let mut kept = KeptRenderer::default();
    let frames = results.cases.iter_mut().chain(
        results
            .sweeps
            .iter_mut()
            .flat_map(|s| s.frames.iter_mut().map(|f| &mut f.case)),
    );
    for line in frames {
        let size = (line.width, line.height);
        if let std::collections::hash_map::Entry::Vacant(entry) = frames_by_size.entry(size) {
            entry.insert(timed_frames(&[size])?);
        }
        let (case, _) = frames_by_size[&size]
            .iter()
            .find(|(case, _)| case.name == line.name)
            .with_context(|| {
                format!(
                    "{}: the bench times no frame {:?}",
                    input.display(),
                    line.name
                )
            })?;
        let renderer = kept.for_scene(&ctx, &case.scene, size)?;
        line.objects = object_load_records(renderer, &case.scene);
        println!(
            "{} {}: {} objects",
            line.name,
            line.size(),
            line.objects.len()
        );
    }
    results.save(output)?;
    println!("wrote {}", output.display());
    Ok(())
}

/// A static case's report line.
fn case_text(case: &CaseResult) -> String {
    let cpu = case.cpu_ms.map_or_else(String::new, |cpu_ms| {
        format!(
            " cpu_ms={cpu_ms:.2} cpu_over_polygon={:.2}",
            cpu_ms / case.measurement.polygon_ms
        )
    });
    format!(
        "scene={} size={}x{} tris={} {}{cpu}",
        case.name,
        case.width,
        case.height,
        case.triangles,
        case.measurement.fields()
    )
}

/// A sweep's report line: the worst frame, each method's worst ratio and slowest frame.
fn sweep_text(sweep: &SweepResult) -> String {
    let Some(worst) = sweep.worst_frame() else {
        return format!("sweep={} frames=0", sweep.name);
    };
    format!(
        "sweep={} size={}x{} tris={} frames={} method=auto worst_ratio={:.2} worst_ct={:.2} median_ratio={:.2} worst_lrt_ratio={:.2} worst_rt_ratio={:.2} slowest_auto_ms={:.2} slowest_lrt_ms={:.2} slowest_rt_ms={:.2} worst_shaded_per_pixel={:.2}",
        sweep.name,
        worst.case.width,
        worst.case.height,
        worst.case.triangles,
        sweep.frames.len(),
        worst.case.measurement.ratio(),
        worst.ct,
        sweep.median_ratio(),
        sweep.worst_ratio_of(Method::Lrt),
        sweep.worst_ratio_of(Method::Rt),
        sweep.slowest(Method::Auto),
        sweep.slowest(Method::Lrt),
        sweep.slowest(Method::Rt),
        sweep.worst_shaded(),
    )
}

/// Measures `scene` at each of `times` with one renderer for the whole sweep, as a viewer
/// would use, printing each frame.
fn sweep(
    ctx: &GpuContext,
    name: &str,
    scene: &Scene,
    times: &[f64],
    (width, height): (u32, u32),
    frames: u32,
) -> anyhow::Result<SweepResult> {
    let mut renderer = GpuRenderer::new(ctx, scene, width, height)?;
    let mut measured = Vec::new();
    for &ct in times {
        let case = measure_case(ctx, &mut renderer, &at_time(name, scene, ct), frames)?;
        println!("  {} {}", case.name, case.measurement.fields());
        measured.push(SweepFrame { ct, case });
    }
    Ok(SweepResult {
        name: name.to_owned(),
        frames: measured,
    })
}

/// Three engines side by side, each approaching at 0.9c.
fn three_engines() -> anyhow::Result<Case> {
    let engine = model_case(ENGINE, 0.9)?;
    let mut scene = engine.scene.clone();
    for shift in [-1.0, 1.0] {
        let copy = shifted(
            &engine.scene,
            glam::DVec3::new(3.0 * shift, 0.0, 0.8 * shift),
        );
        scene.objects.extend(copy.objects);
    }
    Ok(Case {
        name: "three engines".to_owned(),
        scene,
    })
}

/// Nine engines in a 3 × 3 grid across the line of sight, 6 units farther than the bare model
/// is placed, each approaching at 0.9c: over a million triangles, all in view.
fn nine_engines() -> anyhow::Result<Case> {
    let engine = model_case(ENGINE, 0.9)?;
    let mut scene = engine.scene.clone();
    scene.objects.clear();
    let farther = -0.6 * DVec3::from_array(srt_scene::placement::VIEW_FROM).normalize();
    for row in [-1.0, 0.0, 1.0] {
        for column in [-1.0, 0.0, 1.0] {
            let across = DVec3::new(1.9 * column, 0.0, 1.1 * row);
            scene
                .objects
                .extend(shifted(&engine.scene, farther + across).objects);
        }
    }
    Ok(Case {
        name: "nine engines".to_owned(),
        scene,
    })
}

/// The `shadows` scene with a second moving light (3500 K, flying the other way at 0.7c in
/// front of the columns), with the late shadows (`shadows` true) or without them: what shadows
/// cost.
fn two_moving_lights(shadows: bool) -> anyhow::Result<Case> {
    let mut scene = builtin("shadows")?.scene;
    let second = Frame::new(DVec3::new(-0.7, 0.0, 0.0), DVec3::new(4.0, -3.0, 2.0))?;
    scene.lights.push(MovingLight {
        frame: second,
        temperature_k: 3500.0,
        strength: 20.0,
    });
    scene.shadows = shadows;
    let name = if shadows {
        "two moving lights"
    } else {
        "two moving lights, no shadows"
    };
    Ok(Case {
        name: name.to_owned(),
        scene,
    })
}

/// Fig. 10's cube with 400 × 400 squares a face: one mesh of 1 920 000 triangles, whose
/// footprints (96 bytes a triangle) are more than a 128 MiB storage binding holds, so the
/// renderer uploads it in slices (WebGPU's default binding size and the software adapters').
fn fine_cube() -> anyhow::Result<Case> {
    let overrides = srt_scene::Overrides {
        settings: vec![
            "object.cube.shape.subdivisions=400"
                .parse()
                .map_err(anyhow::Error::msg)?,
        ],
        ..srt_scene::Overrides::default()
    };
    let loaded = srt_scene::SceneSource::resolve("fig10-cube200")?.load_with(&overrides)?;
    Ok(Case {
        name: "cube-1.9M".to_owned(),
        scene: loaded.scene,
    })
}

/// `case` with spectral surface colour, named `NAME-spectral`.
fn with_spectral_colour(case: Case) -> Case {
    let mut scene = case.scene;
    scene.colour = SurfaceColour::Spectral;
    Case {
        name: format!("{}-spectral", case.name),
        scene,
    }
}

/// The built-in scene `name` as a case.
fn builtin(name: &str) -> anyhow::Result<Case> {
    builtin_cases()?
        .into_iter()
        .find(|c| c.name == name)
        .with_context(|| format!("{name} is a built-in scene"))
}

/// The static cases, each timed at every size the run measures.
fn static_cases() -> anyhow::Result<Vec<Case>> {
    Ok(vec![
        builtin("fig10-cube50")?,
        builtin("fig10-cube200")?,
        fine_cube()?,
        model_case("OBJ/spider.obj", 0.9)?,
        model_case(ENGINE, 0.9)?,
        builtin("teaser")?,
        three_engines()?,
        nine_engines()?,
        with_spectral_colour(builtin("teaser")?),
        builtin("flythrough")?,
        two_moving_lights(true)?,
        two_moving_lights(false)?,
        builtin("rolling-wheel")?,
        builtin("rocket")?,
    ])
}

/// The `rolling-wheel` rolling past the camera at 0.9c: its axle is seen straight ahead at
/// ct = 0 and at the image's edges near ct = −3.5 and 5.4; 6 frames from entering to leaving.
fn wheel_sweep_times() -> Vec<f64> {
    // Exact quotients, so that the frames print as −3, −1.4, 0.2, 1.8, 3.4 and 5.
    (0..6).map(|k| f64::from(8 * k - 15) / 5.0).collect()
}

/// The fly-by sweeps: name, scene and the observation times of their frames, timed at the first
/// size the run measures.
fn sweeps() -> anyhow::Result<Vec<(&'static str, Scene, Vec<f64>)>> {
    // Loaded once for both engine sweeps.
    let engine = model_case(ENGINE, 0.9)?.scene;
    Ok(vec![
        ("teaser", builtin("teaser")?.scene, teaser_sweep_times()),
        (
            "engine-beside",
            shifted(&engine, ENGINE_BESIDE),
            engine_sweep_times(),
        ),
        ("engine-through", engine, engine_sweep_times()),
        (
            "flythrough",
            builtin("flythrough")?.scene,
            flythrough_sweep_times(),
        ),
        (
            "rolling-wheel",
            builtin("rolling-wheel")?.scene,
            wheel_sweep_times(),
        ),
    ])
}

/// Every frame the bench times at `sizes` (the static cases at each, the sweeps at the first),
/// named as the bench prints it (`NAME@ct=T` for a sweep's frames), with its size: what
/// `cargo xtask validate --bench-frames` checks.
///
/// # Errors
/// Missing models.
pub fn timed_frames(sizes: &[(u32, u32)]) -> anyhow::Result<Vec<(Case, (u32, u32))>> {
    let mut frames = Vec::new();
    for case in static_cases()? {
        frames.extend(sizes.iter().map(|&size| {
            let case = Case {
                name: case.name.clone(),
                scene: case.scene.clone(),
            };
            (case, size)
        }));
    }
    for (name, scene, times) in sweeps()? {
        frames.extend(
            times
                .iter()
                .map(|&ct| (at_time(name, &scene, ct), sizes[0])),
        );
    }
    frames.push((full_sky_case()?, FULL_SKY_SIZE));
    Ok(frames)
}

/// The full-sky line's picture size, whatever `--size` says: the usual 2 : 1 of a 360° frame.
pub const FULL_SKY_SIZE: (u32, u32) = (2048, 1024);

/// The full-sky line: the `flythrough`'s observer at 0.9c as the full sphere, the sky folded
/// into the forward cone, columns passing on both sides and behind.
fn full_sky_case() -> anyhow::Result<Case> {
    let mut case = builtin("flythrough")?;
    case.scene.observer.projection = Projection::Equirectangular;
    case.name = format!("flythrough-{}", Projection::Equirectangular);
    Ok(case)
}

/// Times the full-sky line at [`FULL_SKY_SIZE`]: the ray tracer and `auto` (which traces every
/// object there) taking turns, their fragments against the covered pixels, and the CPU
/// reference's frame ([`cpu_frame_ms`]).
fn full_sky(ctx: &GpuContext, frames: u32) -> anyhow::Result<FullSkyResult> {
    let case = full_sky_case()?;
    let scene = &case.scene;
    let (width, height) = FULL_SKY_SIZE;
    let mut renderer = GpuRenderer::new(ctx, scene, width, height)?;
    let [(rt_ms, _), (auto_ms, _)] =
        frame_times(ctx, &renderer, scene, [Method::Rt, Method::Auto], frames)?;
    let cpu_ms = cpu_frame_ms(scene, (width, height));
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    let coverage = Tracer::new(scene).coverage(settings);
    let covered = coverage.iter().filter(|&&c| c != 0).count().max(1);
    renderer.set_fragment_counting(true);
    let counts = renderer
        .render(ctx, scene, Method::Rt, FootprintShape::Hull)?
        .1
        .fragments
        .context("the renderer counts fragments")?;
    renderer.set_fragment_counting(false);
    Ok(FullSkyResult {
        name: case.name,
        width,
        height,
        triangles: scene.triangle_count(),
        auto_ms,
        rt_ms,
        cpu_ms,
        overdraw_rt: counts.run as f64 / covered as f64,
        shaded_per_pixel: counts.shaded as f64 / covered as f64,
    })
}

/// Measures the static cases whose name `selected` accepts, each at each of `sizes` in turn,
/// printing each and handing it to `measured` as soon as it is measured.
fn static_results(
    ctx: &GpuContext,
    frames: u32,
    sizes: &[(u32, u32)],
    selected: impl Fn(&str) -> bool,
    mut measured: impl FnMut(CaseResult) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let static_cases = static_cases()?;
    // One renderer per case, resized for each size: its BVHs are built once.
    let mut kept = KeptRenderer::default();
    for case in static_cases.iter().filter(|c| selected(&c.name)) {
        for &size in sizes {
            let renderer = kept.for_scene(ctx, &case.scene, size)?;
            let mut result = measure_case(ctx, renderer, case, frames)?;
            result.cpu_ms = Some(cpu_frame_ms(&case.scene, size));
            let loads: Vec<String> = result
                .objects
                .iter()
                .map(|o| format!("{}/{:.2}/{:.0}", o.triangles, o.layers, o.seen_pixels))
                .collect();
            println!(
                "  triangles/layers/seen pixels per object: {}",
                loads.join(" ")
            );
            println!("{}", case_text(&result));
            measured(result)?;
        }
    }
    Ok(())
}

/// Runs the benchmark at `sizes` with `frames` timed frames per measurement, rewrites the
/// adapter's generated blocks of `docs/performance.md` and saves its results file
/// ([`report::Report`]); with `only`, runs the cases whose name contains it and leaves both
/// alone. With `results`, also saves the results there (on any run), rewritten after every
/// case, so that a run cut short keeps what it measured.
///
/// # Errors
/// No GPU, missing models, or an unwritable file.
pub fn run(
    workspace: &Path,
    frames: u32,
    sizes: &[(u32, u32)],
    only: Option<&str>,
    results: Option<&Path>,
) -> anyhow::Result<()> {
    let selected = |name: &str| only.is_none_or(|o| name.contains(o));
    let ctx =
        GpuContext::new().context("cargo xtask bench needs a GPU adapter (software ones count)")?;
    let adapter = ctx.adapter_summary();
    println!("adapter: {adapter}");
    let mut measured = Results {
        machine: Machine::this(),
        adapter,
        timing: Timing::for_adapter(&ctx).describe().to_owned(),
        commit: crate::provenance::commit(workspace),
        date: crate::provenance::today(),
        frames,
        warm_up: WARM_UP,
        min_measured_ms: MIN_MEASURED_MS,
        max_frames: MAX_FRAMES,
        cases: Vec::new(),
        sweeps: Vec::new(),
        full_sky: Vec::new(),
    };
    let save = |measured: &Results| results.map_or(Ok(()), |path| measured.save(path));
    static_results(&ctx, frames, sizes, selected, |case| {
        measured.cases.push(case);
        save(&measured)
    })?;
    for (name, scene, times) in sweeps()? {
        if selected(name) {
            let result = sweep(&ctx, name, &scene, &times, sizes[0], frames)?;
            println!("{}", sweep_text(&result));
            measured.sweeps.push(result);
            save(&measured)?;
        }
    }
    if selected(&full_sky_case()?.name) {
        let line = full_sky(&ctx, frames)?;
        println!("{}", line.text());
        measured.full_sky.push(line);
        save(&measured)?;
    }
    if let Some(path) = results {
        measured.save(path)?;
        println!("wrote {}", path.display());
    }
    println!("{}", replay::summary(&measured));
    if only.is_none() {
        document::write(workspace, &measured, report::Report::for_adapter(&ctx))?;
    }
    Ok(())
}

/// Measures the sustained frame rate of every method on the static cases whose name contains
/// `only` (all without it) at each of `sizes`, `frames` frames each, printing each; a full run
/// rewrites the adapter's throughput block of docs/performance.md ([`report::Report`]).
///
/// # Errors
/// No GPU, missing models, or an unwritable file.
pub fn run_throughput(
    workspace: &Path,
    frames: u32,
    sizes: &[(u32, u32)],
    only: Option<&str>,
) -> anyhow::Result<()> {
    let ctx =
        GpuContext::new().context("cargo xtask bench needs a GPU adapter (software ones count)")?;
    let adapter = ctx.adapter_summary();
    println!("adapter: {adapter}");
    let pictures = workspace.join("target/bench-throughput");
    let mut measured = Vec::new();
    let cases = static_cases()?;
    let selected = cases
        .iter()
        .filter(|c| only.is_none_or(|o| c.name.contains(o)));
    for (&(width, height), case) in sizes
        .iter()
        .flat_map(|size| selected.clone().map(move |case| (size, case)))
    {
        let renderer = GpuRenderer::new(&ctx, &case.scene, width, height)?;
        throughput::save_first_frame(&ctx, &renderer, &case.scene, &case.name, &pictures)?;
        let (fps, encode_ms) = throughput::measure(&ctx, &renderer, &case.scene, frames)?;
        let line = throughput::Throughput {
            name: case.name.clone(),
            width,
            height,
            triangles: case.scene.triangle_count(),
            frames,
            fps,
            encode_ms,
        };
        println!("{}", line.text());
        measured.push(line);
    }
    println!("first frames: {}", pictures.display());
    if only.is_none() {
        let markers = report::Report::for_adapter(&ctx).throughput;
        let block = throughput::table(
            &measured,
            &format!("{adapter}, on {}", Machine::this().describe()),
            &crate::provenance::today(),
            &crate::provenance::commit(workspace),
            markers,
        );
        throughput::write(&workspace.join(document::DOCUMENT), &block, markers)?;
    }
    Ok(())
}

/// Prints the Markdown comparison of the results saved in `old` and `new`.
///
/// # Errors
/// A missing or malformed results file.
pub fn run_compare(old: &Path, new: &Path) -> anyhow::Result<()> {
    print!(
        "{}",
        compare::compare(&Results::load(old)?, &Results::load(new)?)
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{MAX_FRAMES, MIN_MEASURED_MS, parse_size, timed_enough};

    #[test]
    fn short_frames_are_timed_until_they_add_up_and_long_ones_the_frames_asked() {
        // Long frames: the frames asked for, no more.
        assert!(!timed_enough(4, 400.0, 5));
        assert!(timed_enough(5, 400.0, 5));
        // Short frames: on until the least-timed method has MIN_MEASURED_MS…
        assert!(!timed_enough(5, 15.0, 5));
        assert!(!timed_enough(40, f64::from(MIN_MEASURED_MS) - 1.0, 5));
        assert!(timed_enough(40, f64::from(MIN_MEASURED_MS), 5));
        // …or MAX_FRAMES turns, unless more frames were asked for.
        assert!(timed_enough(MAX_FRAMES as usize, 1.0, 5));
        assert!(!timed_enough(MAX_FRAMES as usize, 1.0, 100));
        assert!(timed_enough(100, 1.0, 100));
    }

    #[test]
    fn sizes_parse_and_bad_ones_are_named() {
        assert_eq!(parse_size("3840x2160"), Ok((3840, 2160)));
        assert_eq!(parse_size("1920×1080"), Ok((1920, 1080)));
        for bad in ["1920", "0x10", "x10", "1920x", "20000x10", "axb", "-5x5"] {
            let message = parse_size(bad).expect_err(bad);
            assert!(message.contains(bad), "{message}");
        }
    }
}
