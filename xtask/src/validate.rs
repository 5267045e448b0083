//! `cargo xtask validate`: every GPU pass against its CPU mirror on the current adapter.
//!
//! 1. physics kernels, colour-table sampling and spectral colour (`srt-gpu` probe pass vs
//!    `srt-physics` / `srt-color`, f32 vs f64): worst error per kernel against its tolerance;
//! 2. the proxy pass against `srt-proxy`: the footprints the GPU draws for a triangle (its own
//!    and those of the pieces it was split into) must together contain the on-screen part of
//!    its apparent triangle, computed in f64 (edges and interior sampled densely), and culled
//!    back faces must be back faces of closed solids seen from outside;
//! 3. images: every built-in scene and three assimp models at 0.5c, 0.9c and 0.99c, and scenes
//!    in motion (the teaser while the spider passes the camera, the engine passing through and
//!    beside the camera, the flythrough's observer further on, the camera inside a sphere and
//!    a long box, spectral colour with exposures and emitters), the GPU's exact methods (local ray tracing, the BVH ray tracer, and `auto`,
//!    which picks one of them per object), the polygon method and the image-based method
//!    against the exact CPU reference. The metric is the fraction
//!    of pixels differing by more than 2/255 in any channel, not counting pixels within 1 px of a
//!    silhouette edge of the CPU image. PNGs go to `target/validate/`. The exact methods'
//!    radiance (an EXR's R, G, B) is compared too, relative to each pixel's brightness (2 %,
//!    absolute below 1 % of the unit), and so are their `--aov` channels, what each pixel sees
//!    of time (the same object; each value within 1e-3 of its magnitude, at least 1). Pinholes
//!    are counted apart ([`pinholes`]): a pixel whose object or distance differs from the CPU's
//!    while its 8 neighbours agree with the CPU, showing what none of them shows (a ray slipping
//!    between two triangles that share an edge, or a footprint leaving a pixel out), which the
//!    0.1 % budget would let through. The sphere of 900 segments ([`crate::cases::pinhole_case`],
//!    at its own 160×120) is among the cases: a closed mesh with many shared edges under a pixel.
//!
//! Exits non-zero if any exact method's mismatch exceeds 0.001 or it has a pinhole, the
//! image-based method's mismatch exceeds 0.25 (its documented error), any kernel its tolerance,
//! or any footprint is not conservative.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use anyhow::Context as _;
use glam::{DMat4, DVec2, DVec3};
use image::RgbImage;
use srt_gpu::culling::BackFaceCulling;
use srt_gpu::probe::{
    SPECTRAL_TOLERANCE, compare_physics, compare_spectral, lut_tolerance, run_lut_probe,
    run_physics_probe, run_spectral_probe, seeded_cases, spectral_seeded_cases,
};
use srt_gpu::projection::view_projection;
use srt_gpu::types::GpuFootprint;
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_physics::{Event, Frame};
use srt_proxy::{Viewport, footprint};
use srt_scene::Scene;
use srt_trace::compare::{Mismatch, compare, compare_radiance, compare_seen};
use srt_trace::{Output, RenderSettings, SeenEvent, Tracer};

use crate::cases::{
    Case, ENGINE, PINHOLE_SIZE, builtin_cases, fly_by_cases, model_case, pinhole_case, with_speed,
};
use crate::renderers::KeptRenderer;

/// Image size of the image comparisons.
const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;
/// Channel tolerance (steps of 1/255) and silhouette margin (pixels) of the image metric.
pub const TOLERANCE: u8 = 2;
pub const EDGE_MARGIN: u32 = 1;
/// Largest mismatch of an exact method accepted.
pub const MAX_MISMATCH: f64 = 0.001;
/// Largest mismatch of the image-based method accepted, with the scenes' cube maps (2048 texels
/// a side): approximate by design, it tells apart the pixels whose texel stands for several of
/// them and, on densely textured scenes, the pixels its faces filter for their own finer texels
/// (docs/performance.md, "The image-based method's error"; at most 18 % measured, the striped
/// flythrough in the measured view, 8.5 % on every other case). A wrong face, Doppler factor or
/// composition tells apart every pixel an object covers.
pub const MAX_IMAGE_BASED_MISMATCH: f64 = 0.25;
/// Radiance: a pixel differs when a channel is off by more than this fraction of the reference
/// pixel's largest channel, or of [`RADIANCE_FLOOR`] where that is smaller.
const RADIANCE_TOLERANCE: f64 = 0.02;
/// Radiance below which differences count absolutely: 1 % of a white surface facing the lamp.
const RADIANCE_FLOOR: f64 = 0.01;
/// What pixels see of time: a pixel differs when its object differs or a channel is off by
/// more than this fraction of its magnitude (at least 1, in scene units of ct).
const SEEN_TOLERANCE: f64 = 1e-3;
/// How far from a pixel's centre (in pixels) the CPU looks for what a GPU method drew there before
/// a difference counts as a pinhole ([`grazed_within_rounding`]). The GPU's f32 moves what a ray
/// meets by its rounding of the rays and rest coordinates: at 0.99c the rolling wheel's rest
/// coordinates reach 57 units, where f32's step is 4·10⁻⁶ of a unit and a pixel is about 0.08, so
/// 5·10⁻⁵ of a pixel; a ray that grazes a silhouette closer than that is decided by rounding
/// (column 323, row 94 of that case passes the rim's edge 1.5·10⁻⁷ outside: the GPU sees the rim,
/// the CPU the background). A hole in a closed mesh is no such tie: the CPU sees the surface on
/// every side of a shared edge or vertex, however little the ray moves.
const GRAZING_REACH_PX: f64 = 1e-3;
/// Speeds of the image cases.
const SPEEDS: [f64; 3] = [0.5, 0.9, 0.99];
/// The assimp models of the image cases.
const MODELS: [&str; 3] = [
    ENGINE,
    "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
    "OBJ/WusonOBJ.obj",
];
/// Samples per edge of the conservativeness check.
const EDGE_SAMPLES: u32 = 32;
/// How far (pixels) a point of the apparent triangle may lie outside the GPU hull before it counts as a
/// failure: the GPU dilates by 0.25 px, so this only absorbs rounding.
const HULL_TOLERANCE: f64 = 1e-2;

/// Runs the validation (image cases filtered by `only`); returns an error (non-zero exit) when
/// any check fails.
///
/// # Errors
/// When no GPU is available, a model is missing, or a check fails.
pub fn run(workspace: &Path, only: Option<&str>) -> anyhow::Result<()> {
    let ctx = GpuContext::new()
        .context("cargo xtask validate needs a GPU adapter (software ones count)")?;
    println!("adapter: {}", ctx.adapter_summary());
    let mut failures = Vec::new();
    failures.extend(validate_kernels(&ctx)?);
    let out = workspace.join("target/validate");
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut cases = Vec::new();
    for case in builtin_cases()? {
        for speed in SPEEDS {
            cases.push((
                Case {
                    name: case.name.clone(),
                    scene: with_speed(&case.scene, speed)?,
                },
                speed,
                (WIDTH, HEIGHT),
            ));
        }
    }
    for model in MODELS {
        for speed in SPEEDS {
            cases.push((model_case(model, speed)?, speed, (WIDTH, HEIGHT)));
        }
    }
    for case in fly_by_cases()? {
        let speed = fastest(&case.scene);
        cases.push((case, speed, (WIDTH, HEIGHT)));
    }
    let pinhole = pinhole_case()?;
    let speed = fastest(&pinhole.scene);
    cases.push((pinhole, speed, PINHOLE_SIZE));
    cases.retain(|(case, _, _)| only.is_none_or(|o| case.name.contains(o)));
    let mut renderers = KeptRenderer::default();
    for (case, speed, size) in &cases {
        let renderer = renderers.for_scene(&ctx, &case.scene, *size)?;
        failures.extend(validate_footprints(&ctx, renderer, case)?);
        failures.extend(validate_image(
            &ctx,
            renderer,
            case,
            *speed,
            &out,
            Compared::Everything,
        )?);
    }
    ctx.take_errors()?;
    if failures.is_empty() {
        println!(
            "validate: all {} image cases, footprints and kernels agree",
            cases.len()
        );
        Ok(())
    } else {
        anyhow::bail!("validate failed:\n  {}", failures.join("\n  "))
    }
}

/// The largest speed of `scene`'s objects, for the report.
fn fastest(scene: &Scene) -> f64 {
    scene
        .objects
        .iter()
        .map(|o| o.frame.beta().length())
        .fold(0.0, f64::max)
}

/// `cargo xtask validate --bench-frames`: every frame `cargo xtask bench` times, at its size,
/// rendered by every exact method and compared with the CPU reference under the rules of the
/// image cases. Records each frame's verdict, with the commit and the date, in
/// [`crate::bench::BENCH_FRAMES_RECORD`] (rewritten after every frame, so that a run cut short keeps its
/// verdicts), from which the bench's table says which lines were validated.
///
/// # Errors
/// When no GPU is available, a model is missing, or a frame disagrees.
pub fn run_bench_frames(
    workspace: &Path,
    sizes: &[(u32, u32)],
    only: Option<&str>,
) -> anyhow::Result<()> {
    let ctx = GpuContext::new()
        .context("cargo xtask validate needs a GPU adapter (software ones count)")?;
    println!("adapter: {}", ctx.adapter_summary());
    let out = workspace.join("target/validate/bench-frames");
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut failures = Vec::new();
    let mut record = format!(
        "# commit={} date={}\n",
        crate::provenance::commit(workspace),
        crate::provenance::today()
    );
    let frames = crate::bench::timed_frames(sizes)?;
    let frames: Vec<_> = frames
        .into_iter()
        .filter(|(case, _)| only.is_none_or(|o| case.name.contains(o)))
        .collect();
    let path = workspace.join(crate::bench::BENCH_FRAMES_RECORD);
    let mut renderers = KeptRenderer::default();
    for (case, size) in &frames {
        let failed = validate_image(
            &ctx,
            renderers.for_scene(&ctx, &case.scene, *size)?,
            case,
            fastest(&case.scene),
            &out,
            Compared::Display,
        )?;
        let verdict = if failed.is_empty() { "pass" } else { "FAIL" };
        record += &format!("{}\t{}x{}\t{verdict}\n", case.name, size.0, size.1);
        failures.extend(failed);
        // After every frame, so that a run cut short keeps the verdicts it reached.
        std::fs::write(&path, &record)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    ctx.take_errors()?;
    if failures.is_empty() {
        println!(
            "validate --bench-frames: all {} frames the bench times agree (recorded in {})",
            frames.len(),
            path.display()
        );
        Ok(())
    } else {
        anyhow::bail!(
            "validate --bench-frames failed:\n  {}",
            failures.join("\n  ")
        )
    }
}

/// Physics kernels, colour-table sampling and spectral colour.
fn validate_kernels(ctx: &GpuContext) -> anyhow::Result<Vec<String>> {
    let mut failures = Vec::new();
    let cases = seeded_cases(0x5eed, 16_384);
    let results = run_physics_probe(ctx, &cases)?;
    for error in compare_physics(&cases, &results) {
        let verdict = if error.passes() { "ok" } else { "FAIL" };
        println!(
            "kernel={} worst_relative={:.3e} tolerance={:.1e} {verdict}",
            error.kernel, error.worst_relative, error.tolerance
        );
        if !error.passes() {
            failures.push(format!(
                "kernel {} error {:.3e} > {:.1e}",
                error.kernel, error.worst_relative, error.tolerance
            ));
        }
    }
    for tone_map in srt_color::ToneMap::ALL {
        let lut = srt_color::TemperatureLut::with_defaults(tone_map);
        // Seeded temperatures across and beyond the table: a geometric sweep with an irrational
        // step, plus every 97th texel temperature exactly.
        let mut temperatures: Vec<f32> = (0..20_000)
            .map(|i| (30.0 * (1.000_753_1f64).powi(i)) as f32)
            .collect();
        temperatures.extend(
            (0..lut.size())
                .step_by(97)
                .map(|i| lut.texel_temperature(i) as f32),
        );
        let gpu = run_lut_probe(ctx, &lut, &temperatures)?;
        let worst = temperatures
            .iter()
            .zip(&gpu)
            .map(|(&t, g)| {
                let c = lut.sample(f64::from(t));
                (0..4).map(|k| (c[k] - g[k]).abs()).fold(0.0f32, f32::max)
            })
            .fold(0.0f32, f32::max);
        let tolerance = lut_tolerance(&lut);
        let ok = worst <= tolerance;
        println!(
            "kernel=lut_{} worst_absolute={worst:.3e} tolerance={tolerance:.1e} {}",
            tone_map.name(),
            if ok { "ok" } else { "FAIL" }
        );
        if !ok {
            failures.push(format!(
                "colour table {} error {worst:.3e} > {tolerance:.1e}",
                tone_map.name()
            ));
        }
    }
    let cases = spectral_seeded_cases(0x5eed, 4096);
    let results = run_spectral_probe(ctx, &cases)?;
    let [reflected, emitted] = compare_spectral(&cases, &results);
    for (kernel, (worst, case)) in [
        ("spectral_reflected_display", reflected),
        ("spectral_emitted_display", emitted),
    ] {
        let ok = worst <= SPECTRAL_TOLERANCE;
        println!(
            "kernel={kernel} worst_absolute={worst:.3e} tolerance={SPECTRAL_TOLERANCE:.1e} {}",
            if ok { "ok" } else { "FAIL" }
        );
        if !ok {
            failures.push(format!(
                "kernel {kernel} error {worst:.3e} > {SPECTRAL_TOLERANCE:.1e} (case {case}: {:?})",
                cases[case]
            ));
        }
    }
    Ok(failures)
}

/// The GPU proxy pass (`renderer`'s, made for `case`'s scene) against srt-proxy: each GPU
/// footprint must contain the f64 one.
fn validate_footprints(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    case: &Case,
) -> anyhow::Result<Vec<String>> {
    let scene = &case.scene;
    if let Some(why) = Method::Lrt.cannot_draw(scene) {
        // A wide projection or a stereo pair: every object is traced, through a box footprint.
        println!("scene={}: no footprints to check: {why}", case.name);
        return Ok(Vec::new());
    }
    let (width, height) = renderer.size();
    let viewport = Viewport {
        width: f64::from(width),
        height: f64::from(height),
    };
    let view_projection = view_projection(&scene.observer, width, height);
    let observer = scene.observer.event();
    let (mut triangles, mut not_conservative, mut extra_whole, mut worst_excess) =
        (0, 0, 0, 0.0f64);
    let (mut culled, mut empty, mut split, mut pieces, mut whole) = (0, 0, 0, 0, 0);
    let all = renderer.read_footprints(ctx, scene)?;
    // Spinning and thrusting bodies have no footprints: every exact method traces them.
    let drawn = scene
        .objects
        .iter()
        .zip(&all)
        .filter(|(o, _)| o.motion.is_rest());
    for (object, object_footprints) in drawn {
        for (part, gpu) in object.parts.iter().zip(object_footprints) {
            let observer_rest = object.frame.to_rest(observer).position;
            let cullable =
                BackFaceCulling::for_mesh(&part.mesh).applies(&part.mesh, &object.frame, observer);
            for (t, drawn) in gpu.iter().enumerate() {
                let g = &drawn.own;
                triangles += 1;
                let corners = part.mesh.triangle_positions(t);
                let cpu = footprint(&object.frame, corners, observer, view_projection, viewport);
                if g.hull_len() == 0 && !g.whole_screen() && drawn.pieces.is_empty() {
                    // Empty: a culled back face (up to f32 rounding of edge-on ones), or a
                    // triangle nothing of which is on screen (the samples below check it).
                    let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
                    let to_observer = observer_rest - corners[0];
                    let facing = normal.dot(to_observer) / (normal.length() * to_observer.length());
                    if cullable && facing <= 1e-4 {
                        culled += 1;
                        continue;
                    }
                    empty += 1;
                }
                if g.whole_screen() {
                    whole += 1;
                    extra_whole += usize::from(!cpu.whole_screen);
                    continue;
                }
                split += usize::from(cpu.split);
                pieces += drawn.pieces.len();
                let outside = escapes_footprints(
                    &object.frame,
                    corners,
                    observer,
                    (view_projection, viewport),
                    std::iter::once(g).chain(&drawn.pieces),
                );
                not_conservative += usize::from(outside);
                if outside && std::env::var_os("SRT_VALIDATE_DEBUG").is_some() {
                    eprintln!("triangle {t}: outside\n  gpu {drawn:?}\n  cpu {cpu:?}");
                }
                let Some(bounds) = g.bounds() else {
                    continue;
                };
                if cpu.split || cpu.whole_screen || !drawn.pieces.is_empty() {
                    // Clamped to the screen, split, or empty: no margin to measure.
                    continue;
                }
                worst_excess = worst_excess.max(bounds_excess(&cpu.rect, bounds, viewport));
            }
        }
    }
    println!(
        "proxy scene={} triangles={triangles} culled={culled} empty={empty} split={split} pieces={pieces} whole_screen={whole} not_conservative={not_conservative} extra_whole_screen={extra_whole} worst_bounds_margin_px={worst_excess:.3}",
        case.name
    );
    Ok(if not_conservative > 0 {
        vec![format!(
            "{}: {not_conservative} GPU footprints do not contain their apparent triangle",
            case.name
        )]
    } else {
        Vec::new()
    })
}

/// Whether the curved apparent triangle of `corners` (in `frame`'s rest coordinates), sampled
/// densely in f64 along its edges and over its interior, has a point on the screen outside every
/// one of `footprints` (the GPU's footprint of the triangle and its pieces'): a footprint that is
/// not conservative. Off-screen points and points behind the camera cannot produce fragments.
fn escapes_footprints<'a>(
    frame: &Frame,
    corners: [DVec3; 3],
    observer: Event,
    (view_projection, viewport): (DMat4, Viewport),
    footprints: impl Iterator<Item = &'a GpuFootprint>,
) -> bool {
    // What the visibility passes draw of each footprint: its hull (a rectangle as four points).
    let shapes: Vec<Vec<DVec2>> = footprints
        .map(|f| {
            (f.hull_points().iter())
                .map(|h| DVec2::new(f64::from(h[0]), f64::from(h[1])))
                .collect()
        })
        .collect();
    let boundary = (0..3).flat_map(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        (0..EDGE_SAMPLES).map(move |s| a + (b - a) * (f64::from(s) / f64::from(EDGE_SAMPLES)))
    });
    let interior = (0..=EDGE_SAMPLES).flat_map(|i| {
        (0..=EDGE_SAMPLES - i).map(move |j| {
            let (u, v) = (
                f64::from(i) / f64::from(EDGE_SAMPLES),
                f64::from(j) / f64::from(EDGE_SAMPLES),
            );
            corners[0] + u * (corners[1] - corners[0]) + v * (corners[2] - corners[0])
        })
    });
    let on_screen =
        |q: DVec2| q.x >= 0.0 && q.y >= 0.0 && q.x <= viewport.width && q.y <= viewport.height;
    let inside = |q: DVec2, hull: &[DVec2]| srt_proxy::hull_contains(hull, q, HULL_TOLERANCE);
    boundary.chain(interior).any(|rest| {
        let seen = frame.apparent_position(rest, observer);
        srt_proxy::project(view_projection, viewport, seen)
            .is_some_and(|q| on_screen(q) && !shapes.iter().any(|shape| inside(q, shape)))
    })
}

/// How much larger the rectangle `gpu` of what the GPU draws of a footprint is than the f64
/// footprint's rectangle, `cpu`, on the screen: the largest of its four margins, in pixels.
fn bounds_excess(cpu: &srt_proxy::Rect, gpu: [f32; 4], viewport: Viewport) -> f64 {
    let cpu_rect = cpu.clamped(viewport);
    let gpu_rect = srt_proxy::Rect {
        min: DVec2::new(f64::from(gpu[0]), f64::from(gpu[1])),
        max: DVec2::new(f64::from(gpu[2]), f64::from(gpu[3])),
    }
    .clamped(viewport);
    [
        cpu_rect.min.x - gpu_rect.min.x,
        cpu_rect.min.y - gpu_rect.min.y,
        gpu_rect.max.x - cpu_rect.max.x,
        gpu_rect.max.y - cpu_rect.max.y,
    ]
    .into_iter()
    .fold(f64::NEG_INFINITY, f64::max)
}

/// What [`validate_image`] compares with the CPU reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Compared {
    /// Display colours.
    Display,
    /// Display colours, and the exact methods' radiance and what their pixels see of time.
    Everything,
}

/// Each method's 8-bit picture of a case's scene: `None` where the GPU refuses the method for
/// it (`Method::cannot_draw`: late shadows cast by spinning or thrusting bodies; a wide
/// projection by LRT and the polygon method; spectral colour, moving lights or a stereo pair by
/// the image-based method). The ray tracer and `auto` draw every case.
struct Drawn {
    lrt: Option<Vec<[u8; 3]>>,
    rt: Vec<[u8; 3]>,
    auto: Vec<[u8; 3]>,
    polygon: Option<Vec<[u8; 3]>>,
    image_based: Option<Vec<[u8; 3]>>,
}

/// Draws `case` with every method ([`Drawn`]) and counts the visibility fragments that found
/// hits nearer than their footprint's depth bound: the depth the visibility passes declare
/// must hold, or a GPU that tests depth early would drop visible fragments, which only a
/// hardware GPU's image could show.
fn draw_methods(
    ctx: &GpuContext,
    renderer: &mut GpuRenderer,
    case: &Case,
) -> anyhow::Result<(Drawn, u64)> {
    renderer.set_fragment_counting(true);
    let mut nearer_than_footprint = 0;
    let [lrt, rt, auto, polygon, image_based] = [
        Method::Lrt,
        Method::Rt,
        Method::Auto,
        Method::Polygon,
        Method::ImageBased,
    ]
    .map(|method| renderer.render(ctx, &case.scene, method, FootprintShape::Hull))
    .map(|result| {
        result.map(|(image, stats)| {
            nearer_than_footprint += stats.fragments.map_or(0, |f| f.nearer_than_footprint);
            image.to_rgb8()
        })
    });
    renderer.set_fragment_counting(false);
    let drawn = |method: &str, rgb: Result<Vec<[u8; 3]>, srt_gpu::GpuError>| match rgb {
        Err(srt_gpu::GpuError::Unsupported(why)) => {
            println!("scene={}: no {method} image: {why}", case.name);
            Ok(None)
        }
        other => other.map(Some),
    };
    let drawn = Drawn {
        lrt: drawn("lrt", lrt)?,
        rt: rt?,
        auto: auto?,
        polygon: drawn("polygon", polygon)?,
        image_based: drawn("image-based", image_based)?,
    };
    Ok((drawn, nearer_than_footprint))
}

/// `renderer`'s images (made for `case`'s scene, at its size) of the exact methods (LRT, the ray
/// tracer and `auto`, which picks one of them per object) and of the polygon and image-based
/// methods against the CPU reference (the image-based method held to
/// [`MAX_IMAGE_BASED_MISMATCH`]); with [`Compared::Everything`], the exact methods' radiance (relative,
/// [`compare_radiance`]) and their `--aov` channels ([`compare_seen`]) too.
fn validate_image(
    ctx: &GpuContext,
    renderer: &mut GpuRenderer,
    case: &Case,
    speed: f64,
    out: &Path,
    compared: Compared,
) -> anyhow::Result<Vec<String>> {
    let scene: &Scene = &case.scene;
    let (width, height) = renderer.size();
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    let tracer = Tracer::new(scene);
    let reference = tracer.render(settings, &|_| {});
    let (
        Drawn {
            lrt: lrt_rgb,
            rt: rt_rgb,
            auto: auto_rgb,
            polygon: polygon_rgb,
            image_based: image_based_rgb,
        },
        nearer_than_footprint,
    ) = draw_methods(ctx, renderer, case)?;
    let mismatch_of = |rgb: Option<&Vec<[u8; 3]>>| {
        rgb.map_or(f64::NAN, |rgb| {
            compare(&reference, rgb, TOLERANCE, EDGE_MARGIN).fraction()
        })
    };
    let mismatch = mismatch_of(lrt_rgb.as_ref());
    let rt_mismatch = mismatch_of(Some(&rt_rgb));
    let auto_mismatch = mismatch_of(Some(&auto_rgb));
    let polygon_mismatch = mismatch_of(polygon_rgb.as_ref());
    let image_based_mismatch = mismatch_of(image_based_rgb.as_ref());
    let (further_mismatches, pinhole_counts) = if compared == Compared::Everything {
        further_mismatches(ctx, renderer, scene, &tracer, settings)?
    } else {
        (Vec::new(), Vec::new())
    };
    let traced = renderer.auto_traced_objects(scene);
    let further_report: String = further_mismatches
        .iter()
        .map(|(what, m)| format!(" {what}_mismatch={:.6}", m.fraction()))
        .chain(
            pinhole_counts
                .iter()
                .map(|(method, found)| format!(" {method}_pinholes={}", found.len())),
        )
        .collect();
    println!(
        "scene={} size={width}x{height} beta={speed} mismatch={mismatch:.6} rt_mismatch={rt_mismatch:.6} auto_mismatch={auto_mismatch:.6} auto_traced_objects={traced} nearer_than_footprint={nearer_than_footprint} polygon_mismatch={polygon_mismatch:.6} image_based_mismatch={image_based_mismatch:.6}{further_report}",
        case.name,
    );
    let stem = format!(
        "{}_{width}x{height}_b{speed:.2}",
        case.name.replace(['.', ' ', '@', '='], "_")
    );
    save_images(
        &out.join(stem),
        (width, height),
        &reference.to_rgb8(),
        [
            lrt_rgb.as_ref(),
            Some(&rt_rgb),
            polygon_rgb.as_ref(),
            image_based_rgb.as_ref(),
        ],
    )?;
    let display = [
        ("LRT", mismatch),
        ("RT", rt_mismatch),
        ("auto", auto_mismatch),
    ]
    .map(|(method, fraction)| (method.to_owned(), fraction));
    let further = further_mismatches
        .iter()
        .map(|(what, m)| (what.replace('_', " "), m.fraction()));
    let nearer = (nearer_than_footprint > 0).then(|| {
        format!(
            "{} at {width}x{height}, {speed}c: {nearer_than_footprint} visibility fragments found \
             hits nearer than their footprint's depth bound",
            case.name
        )
    });
    let pinholes = pinhole_failures(&pinhole_counts, &case.name, speed, (width, height));
    let image_based = (image_based_mismatch > MAX_IMAGE_BASED_MISMATCH).then(|| {
        format!(
            "{} at {width}x{height}, {speed}c: image-based mismatch {image_based_mismatch:.6} > \
             {MAX_IMAGE_BASED_MISMATCH}",
            case.name
        )
    });
    Ok(display
        .into_iter()
        .chain(further)
        .filter(|(_, fraction)| *fraction > MAX_MISMATCH)
        .map(|(what, fraction)| {
            format!(
                "{} at {width}x{height}, {speed}c: {what} mismatch {fraction:.6} > {MAX_MISMATCH}",
                case.name,
            )
        })
        .chain(image_based)
        .chain(nearer)
        .chain(pinholes)
        .collect())
}

/// What [`further_mismatches`] finds: mismatches named as validate reports them
/// (`lrt_radiance`, `rt_seen`, …), and each exact method's number of [`pinholes`].
type Further = (
    Vec<(String, Mismatch<f64>)>,
    Vec<(&'static str, Vec<(u32, u32)>)>,
);

/// The exact methods' radiance against the CPU's ([`compare_radiance`], relative, the reference
/// clamped as the GPU's colour target holds it) and what their pixels see of time
/// ([`compare_seen`]), each named as validate reports it (`lrt_radiance`, `rt_seen`, …); and the
/// [`pinholes`] of what each exact method's pixels see.
fn further_mismatches(
    ctx: &GpuContext,
    renderer: &mut GpuRenderer,
    scene: &Scene,
    tracer: &Tracer<'_>,
    settings: RenderSettings,
) -> anyhow::Result<Further> {
    let (width, height) = (settings.width, settings.height);
    let mut further_mismatches = Vec::new();
    let mut reference = tracer.render_radiance(settings, &|_| {});
    // As the GPU's colour target holds it: each channel's magnitude at most its largest
    // value (f32's, as an EXR holds it, or a half float's).
    let largest = f64::from(srt_gpu::formats::largest_value(ctx.color_format));
    for pixel in &mut reference.pixels {
        *pixel = pixel.clamp(DVec3::splat(-largest), DVec3::splat(largest));
    }
    // The exact methods that draw the scene (LRT not in a wide projection).
    let exact: Vec<Method> = [Method::Lrt, Method::Rt, Method::Auto]
        .into_iter()
        .filter(|method| method.cannot_draw(scene).is_none())
        .collect();
    for &method in &exact {
        let (image, _) =
            renderer.render_as(ctx, scene, method, FootprintShape::Hull, Output::Radiance)?;
        let pixels: Vec<DVec3> = image
            .pixels
            .iter()
            .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
            .collect();
        let mismatch = compare_radiance(
            &reference,
            &pixels,
            RADIANCE_TOLERANCE,
            RADIANCE_FLOOR,
            EDGE_MARGIN,
        );
        further_mismatches.push((format!("{}_radiance", method.name()), mismatch));
    }
    let events = tracer.render_seen_events(width, height, &|_| {}, &AtomicBool::new(false));
    let events = events.context("a render without a stop flag finishes")?;
    let mut pinhole_counts = Vec::new();
    for &method in &exact {
        let seen = renderer.render_seen(ctx, scene, method, FootprintShape::Hull)?;
        let mismatch = compare_seen(&reference, &events, &seen, SEEN_TOLERANCE, EDGE_MARGIN);
        further_mismatches.push((format!("{}_seen", method.name()), mismatch));
        let found = pinholes(&events, &seen, width)
            .into_iter()
            .filter(|&(x, y)| {
                let i = (y * width + x) as usize;
                !grazed_within_rounding(tracer, (width, height), (x, y), seen[i])
                    && !coincident_surfaces(scene, (width, height), (x, y), seen[i], &events[i])
            });
        pinhole_counts.push((method.name(), found.collect()));
    }
    Ok((further_mismatches, pinhole_counts))
}

/// One failure line per method with `found` pinholes (per method name), for case `name` at
/// `speed`.
fn pinhole_failures(
    found: &[(&str, Vec<(u32, u32)>)],
    name: &str,
    speed: f64,
    (width, height): (u32, u32),
) -> Vec<String> {
    (found.iter())
        .filter_map(|(method, pixels)| {
            let (x, y) = pixels.first()?;
            Some(format!(
                "{name} at {width}x{height}, {speed}c: {} pinholes under {method} (the first at \
                 column {x}, row {y})",
                pixels.len()
            ))
        })
        .collect()
}

/// Whether the CPU's `event` shows what a GPU method's pixel `candidate` (a row of
/// [`GpuRenderer::render_seen`]) shows: the background for both, or the same object at the same
/// distance ([`SEEN_TOLERANCE`]).
fn shows_alike(event: Option<&SeenEvent>, candidate: [f32; 5]) -> bool {
    let [.., distance, _, object] = candidate.map(f64::from);
    event.map_or(object < 0.0, |event| {
        object == event.object as f64 && near_distance(distance, event.distance)
    })
}

/// Whether `value` is `expected`'s distance within [`SEEN_TOLERANCE`] (of its magnitude, at
/// least 1).
fn near_distance(value: f64, expected: f64) -> bool {
    (value - expected).abs() <= SEEN_TOLERANCE * expected.abs().max(1.0)
}

/// Whether the CPU, tracing rays [`GRAZING_REACH_PX`] from pixel `(x, y)`'s centre in eight
/// directions, sees what the GPU's `candidate` shows there ([`shows_alike`]): a silhouette grazed
/// within the GPU's rounding, not a pinhole.
fn grazed_within_rounding(
    tracer: &Tracer<'_>,
    (width, height): (u32, u32),
    (x, y): (u32, u32),
    candidate: [f32; 5],
) -> bool {
    let centre = DVec2::new(f64::from(x), f64::from(y)) + srt_trace::sample_offsets(1)[0];
    (0..8).any(|k| {
        let angle = std::f64::consts::FRAC_PI_4 * f64::from(k);
        let point = centre + GRAZING_REACH_PX * DVec2::from_angle(angle);
        let hit = tracer.hit_at(width, height, point);
        shows_alike(hit.map(|hit| tracer.seen_event(&hit)).as_ref(), candidate)
    })
}

/// Whether a GPU method's pixel `candidate` shows another object than the CPU's `event`, at the
/// same distance ([`SEEN_TOLERANCE`]), and the CPU, tracing that object alone, meets it along the
/// pixel's ray at that distance too: two surfaces that coincide there (the rolling wheel's rim
/// segments overlap at their joints, their side faces in one plane), between which rounding
/// and each renderer's order decide, not a pinhole. Through a hole the object behind is met
/// farther than the CPU's surface.
fn coincident_surfaces(
    scene: &Scene,
    (width, height): (u32, u32),
    (x, y): (u32, u32),
    candidate: [f32; 5],
    event: &Option<SeenEvent>,
) -> bool {
    let [.., distance, _, object] = candidate.map(f64::from);
    let Some(event) = event else {
        return false;
    };
    if object < 0.0 || object as usize == event.object || !near_distance(distance, event.distance) {
        return false;
    }
    let Some(shown) = scene.objects.get(object as usize) else {
        return false;
    };
    let mut alone = scene.clone();
    alone.objects = vec![shown.clone()];
    let tracer = Tracer::new(&alone);
    (tracer.hit_at_pixel(width, height, x, y))
        .is_some_and(|hit| near_distance(tracer.seen_event(&hit).distance, event.distance))
}

/// The pinholes of `candidate` (what a method's pixels see, [`GpuRenderer::render_seen`]'s
/// rows of `width` pixels) against the CPU's `events`, as (column, row): pixels whose object or
/// distance differs from the CPU's ([`SEEN_TOLERANCE`]) while each of their 8 neighbours agrees
/// with the CPU, and which show what none of their neighbours shows in the CPU's image (the
/// background where every neighbour sees an object; an object none of them sees, or at a
/// distance outside theirs) — an edge of the reference moved by a pixel through rounding is not
/// a pinhole. Pixels on the image's border are not judged.
fn pinholes(events: &[Option<SeenEvent>], candidate: &[[f32; 5]], width: u32) -> Vec<(u32, u32)> {
    let width = width as usize;
    let height = events.len() / width;
    let agrees = |i: usize| shows_alike(events[i].as_ref(), candidate[i]);
    let mut found = Vec::new();
    for y in 1..height.saturating_sub(1) {
        for x in 1..width - 1 {
            let i = y * width + x;
            let neighbours = [
                i - width - 1,
                i - width,
                i - width + 1,
                i - 1,
                i + 1,
                i + width - 1,
                i + width,
                i + width + 1,
            ];
            if agrees(i) || !neighbours.iter().all(|&n| agrees(n)) {
                continue;
            }
            let [.., distance, _, object] = candidate[i].map(f64::from);
            let shown = neighbours.iter().filter_map(|&n| match events[n] {
                None => (object < 0.0).then_some(None),
                Some(event) => (object == event.object as f64).then_some(Some(event.distance)),
            });
            let explained = shown.fold(
                (false, f64::INFINITY, f64::NEG_INFINITY),
                |acc, s| match s {
                    None => (true, acc.1, acc.2),
                    Some(d) => (acc.0, acc.1.min(d), acc.2.max(d)),
                },
            );
            let between = object >= 0.0
                && explained.1 <= explained.2
                && (near_distance(distance, explained.1)
                    || near_distance(distance, explained.2)
                    || (explained.1..=explained.2).contains(&distance));
            if !(explained.0 || between) {
                found.push((x as u32, y as u32));
            }
        }
    }
    found
}

/// Saves a case's images beside `stem` (a path without extension): the CPU reference, LRT's
/// image (`_actual`), the polygon method's and the image-based method's where there are, the
/// ray tracer's, and LRT's
/// difference from the reference (the ray tracer's where LRT drew none), 16× amplified.
fn save_images(
    stem: &Path,
    (width, height): (u32, u32),
    reference: &[[u8; 3]],
    [lrt, rt, polygon, image_based]: [Option<&Vec<[u8; 3]>>; 4],
) -> anyhow::Result<()> {
    let named = |suffix: &str| {
        let mut name = stem.as_os_str().to_owned();
        name.push(format!("_{suffix}.png"));
        PathBuf::from(name)
    };
    save(named("reference"), width, height, reference)?;
    for (suffix, image) in [
        ("actual", lrt),
        ("rt", rt),
        ("polygon", polygon),
        ("image_based", image_based),
    ] {
        if let Some(image) = image {
            save(named(suffix), width, height, image)?;
        }
    }
    if let Some(lrt) = lrt.or(rt) {
        let difference: Vec<[u8; 3]> = reference
            .iter()
            .zip(lrt)
            .map(|(a, b)| [0, 1, 2].map(|c| a[c].abs_diff(b[c]).saturating_mul(16)))
            .collect();
        save(named("difference"), width, height, &difference)?;
    }
    Ok(())
}

fn save(path: PathBuf, width: u32, height: u32, pixels: &[[u8; 3]]) -> anyhow::Result<()> {
    let bytes = pixels.iter().flatten().copied().collect();
    RgbImage::from_raw(width, height, bytes)
        .context("image size")?
        .save(&path)
        .with_context(|| format!("cannot write {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cases::moving_body_cases;

    /// A 5 × 4 picture of one object at distance 10 whose CPU events are `events`.
    fn flat(distance: f64) -> (Vec<Option<SeenEvent>>, Vec<[f32; 5]>) {
        let event = SeenEvent {
            object: 0,
            emission_ct: 0.0,
            proper_time: 0.0,
            distance,
            doppler: 1.0,
        };
        let seen = [0.0, 0.0, distance as f32, 1.0, 0.0];
        (vec![Some(event); 20], vec![seen; 20])
    }

    #[test]
    fn a_hole_or_a_far_hit_inside_an_object_is_a_pinhole() {
        let (events, mut seen) = flat(10.0);
        assert!(pinholes(&events, &seen, 5).is_empty());
        seen[7] = [0.0, 0.0, 0.0, 0.0, -1.0];
        assert_eq!(pinholes(&events, &seen, 5), vec![(2, 1)]);
        seen[7] = [0.0, 0.0, 10.4, 1.0, 0.0];
        assert_eq!(pinholes(&events, &seen, 5), vec![(2, 1)]);
        // Two wrong pixels side by side: each has a neighbour that disagrees.
        seen[8] = seen[7];
        assert!(pinholes(&events, &seen, 5).is_empty());
        // On the border: not judged.
        let (events, mut seen) = flat(10.0);
        seen[0] = [0.0, 0.0, 0.0, 0.0, -1.0];
        assert!(pinholes(&events, &seen, 5).is_empty());
    }

    #[test]
    fn an_edge_moved_by_a_pixel_is_not_a_pinhole() {
        // The object's silhouette: the CPU sees it at distance 10 in the right three columns;
        // the GPU sees the background at one pixel of its edge, as a neighbour does.
        let (mut events, mut seen) = flat(10.0);
        for row in 0..4 {
            for column in 0..2 {
                events[row * 5 + column] = None;
                seen[row * 5 + column] = [0.0, 0.0, 0.0, 0.0, -1.0];
            }
        }
        seen[7] = [0.0, 0.0, 0.0, 0.0, -1.0];
        assert!(pinholes(&events, &seen, 5).is_empty());
        // A fold of the object behind itself: the CPU sees 12 at the left, the GPU the far
        // layer at one pixel of the fold, between what its neighbours see.
        let (mut events, mut seen) = flat(10.0);
        for row in 0..4 {
            for column in 0..2 {
                events[row * 5 + column].as_mut().unwrap().distance = 12.0;
                seen[row * 5 + column][2] = 12.0;
            }
        }
        seen[7][2] = 11.99;
        assert!(pinholes(&events, &seen, 5).is_empty());
    }

    /// The rolling wheel at 0.99c, 640 × 360: column 323 of row 94 passes the edge of rim 3
    /// (object 3) 1.5·10⁻⁷ outside in its rest coordinates, where the GPU's f32 meets the rim
    /// at distance 7.963 and the CPU sees the background.
    #[test]
    fn a_silhouette_grazed_within_rounding_is_no_pinhole_and_a_hole_is() {
        let wheel = builtin_cases()
            .unwrap()
            .into_iter()
            .find(|case| case.name == "rolling-wheel")
            .unwrap();
        let scene = with_speed(&wheel.scene, 0.99).unwrap();
        let tracer = Tracer::new(&scene);
        let size = (640, 360);
        assert!(tracer.hit_at_pixel(640, 360, 323, 94).is_none());
        let rim = |distance: f32| [0.0, 0.0, distance, 1.0, 3.0];
        assert!(grazed_within_rounding(
            &tracer,
            size,
            (323, 94),
            rim(7.963_163)
        ));
        // The rim, but not where the CPU sees it near this pixel.
        assert!(!grazed_within_rounding(&tracer, size, (323, 94), rim(8.1)));
        // The background one pixel over, inside the rim (the CPU: rim 3 at 7.9507).
        let inside = tracer.hit_at_pixel(640, 360, 324, 94).unwrap();
        assert_eq!(inside.object, 3);
        let background = [0.0, 0.0, 0.0, 0.0, -1.0];
        assert!(!grazed_within_rounding(
            &tracer,
            size,
            (324, 94),
            background
        ));
        assert!(grazed_within_rounding(
            &tracer,
            size,
            (324, 94),
            rim(7.950_644)
        ));
    }

    /// The rolling wheel passing 3 units away at ct = −5 (`wheel-passing@ct=-5`), 640 × 360:
    /// at column 426, row 265 the side faces of rims 8 and 9 (objects 8 and 9) coincide at
    /// distance 2.908303; the CPU shows rim 8, llvmpipe's GL driver rim 9 (at 2.9082, the seen
    /// texture's half floats).
    #[test]
    fn coincident_surfaces_are_no_pinhole_and_a_surface_behind_is() {
        let passing = moving_body_cases()
            .unwrap()
            .into_iter()
            .find(|case| case.name == "wheel-passing@ct=-5")
            .unwrap();
        let scene = passing.scene;
        let tracer = Tracer::new(&scene);
        let (size, pixel) = ((640, 360), (426, 265));
        let event = tracer
            .hit_at_pixel(640, 360, 426, 265)
            .map(|hit| tracer.seen_event(&hit));
        let seen = event.unwrap();
        assert_eq!(seen.object, 8);
        assert!((seen.distance - 2.908_303).abs() < 1e-6, "{seen:?}");
        let rim = |object: f32, distance: f32| [0.0, 0.0, distance, 1.0, object];
        assert!(coincident_surfaces(
            &scene,
            size,
            pixel,
            rim(9.0, 2.908_203),
            &event
        ));
        // Rim 10 is not on this ray; rim 9 not at another distance; rim 8 (the CPU's own)
        // farther is its far side, not a tie; and nothing ties with the background.
        assert!(!coincident_surfaces(
            &scene,
            size,
            pixel,
            rim(10.0, 2.908_303),
            &event
        ));
        assert!(!coincident_surfaces(
            &scene,
            size,
            pixel,
            rim(9.0, 2.95),
            &event
        ));
        assert!(!coincident_surfaces(
            &scene,
            size,
            pixel,
            rim(8.0, 2.95),
            &event
        ));
        assert!(!coincident_surfaces(
            &scene,
            size,
            pixel,
            rim(9.0, 2.908_203),
            &None
        ));
    }
}
