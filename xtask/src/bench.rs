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
//!   columns passing beside it, 12 frames each; one line per sweep with the worst
//!   frame's ratio (`worst_ratio`), each method's worst ratio and slowest frame;
//! - a large scene: three engines side by side (364 488 triangles);
//! - what the newer features cost: the teaser with spectral colour (`teaser-spectral`) and the
//!   `flythrough` (a moving observer under 6 000 stars).
//!
//! Prints one line per case and rewrites the tables in `docs/performance.md`.

use std::path::Path;
use std::time::Instant;

use anyhow::Context as _;
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_scene::{Scene, SurfaceColour};
use srt_trace::{RenderSettings, Tracer};

use crate::cases::{
    Case, ENGINE, ENGINE_BESIDE, at_time, builtin_cases, engine_sweep_times,
    flythrough_sweep_times, model_case, shifted, teaser_sweep_times,
};

/// Image sizes of the static cases; the first is also that of the sweeps.
const SIZES: [(u32, u32); 2] = [(1280, 720), (1920, 1080)];
const WARM_UP: u32 = 2;
const TABLE_START: &str = "<!-- table1:start (written by cargo xtask bench) -->";
const TABLE_END: &str = "<!-- table1:end -->";

/// One measured frame: a scene at one size.
struct Measurement {
    lrt_ms: f64,
    proxy_ms: f64,
    rt_ms: f64,
    /// `auto`: each object by LRT or the ray tracer, as `Method::Auto` chooses.
    auto_ms: f64,
    polygon_ms: f64,
    /// LRT visibility fragments per covered pixel.
    overdraw_hull: f64,
    /// Ray-tracer visibility fragments per covered pixel.
    overdraw_rt: f64,
    /// Visibility fragments of `auto` per covered pixel.
    overdraw_auto: f64,
    /// Pixels shaded per covered pixel (the most of the exact methods; they share the
    /// shading pass).
    shaded_per_pixel: f64,
}

impl Measurement {
    /// Frame time of `method`.
    fn ms(&self, method: Method) -> f64 {
        match method {
            Method::Auto => self.auto_ms,
            Method::Lrt => self.lrt_ms,
            Method::Rt => self.rt_ms,
            Method::Polygon => self.polygon_ms,
        }
    }

    /// The exact method the program uses (`auto`) against the polygon method.
    fn ratio(&self) -> f64 {
        self.auto_ms / self.polygon_ms
    }

    /// The report's `key=value` fields of the measurement.
    fn fields(&self) -> String {
        format!(
            "method=auto ratio={:.2} auto_ms={:.2} lrt_ms={:.2} proxy_ms={:.2} rt_ms={:.2} polygon_ms={:.2} lrt_ratio={:.2} rt_ratio={:.2} shaded_per_pixel={:.2} overdraw_auto={:.2} overdraw_hull={:.2} overdraw_rt={:.2}",
            self.ratio(),
            self.auto_ms,
            self.lrt_ms,
            self.proxy_ms,
            self.rt_ms,
            self.polygon_ms,
            self.lrt_ms / self.polygon_ms,
            self.rt_ms / self.polygon_ms,
            self.shaded_per_pixel,
            self.overdraw_auto,
            self.overdraw_hull,
            self.overdraw_rt
        )
    }
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Median frame time in ms of each of `methods` (GPU timestamps where supported, else wall
/// clock of render + readback) and median time of its proxy pass (0 where unknown). The
/// methods take turns frame by frame, so that a slow spell of the machine (software adapters
/// share its cores) falls on all of them alike.
fn frame_times<const N: usize>(
    ctx: &GpuContext,
    renderer: &GpuRenderer,
    scene: &Scene,
    methods: [Method; N],
    frames: u32,
) -> anyhow::Result<[(f64, f64); N]> {
    for _ in 0..WARM_UP {
        for method in methods {
            renderer.render(ctx, scene, method, FootprintShape::Hull)?;
        }
    }
    let mut times = [(); N].map(|()| (Vec::new(), Vec::new()));
    for _ in 0..frames {
        for (method, (time, proxy)) in methods.iter().zip(&mut times) {
            let start = Instant::now();
            let (_, stats) = renderer.render(ctx, scene, *method, FootprintShape::Hull)?;
            let wall = start.elapsed().as_secs_f64() * 1e3;
            time.push(stats.gpu_time_ms.unwrap_or(wall));
            proxy.push(stats.proxy_time_ms.unwrap_or(0.0));
        }
    }
    Ok(times.map(|(time, proxy)| (median(time), median(proxy))))
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
    Ok(Measurement {
        lrt_ms,
        proxy_ms,
        rt_ms,
        auto_ms,
        polygon_ms,
        overdraw_hull: lrt.run as f64 / covered,
        overdraw_rt: rt.run as f64 / covered,
        overdraw_auto: auto.run as f64 / covered,
        shaded_per_pixel: lrt.shaded.max(rt.shaded).max(auto.shaded) as f64 / covered,
    })
}

/// A line of the report and a row of the table.
struct Line {
    text: String,
    /// The table row without its last cell, the validation's (see [`Validation::cell`]).
    row: String,
    /// The frames the line times, by name and size, as `validate --bench-frames` records them.
    frames: Vec<(String, (u32, u32))>,
}

fn static_line(case: &Case, (width, height): (u32, u32), m: &Measurement) -> Line {
    let tris = case.scene.triangle_count();
    Line {
        frames: vec![(case.name.clone(), (width, height))],
        text: format!(
            "scene={} size={width}x{height} tris={tris} {}",
            case.name,
            m.fields()
        ),
        row: format!(
            "| {} | {width}×{height} | {tris} | {:.2} | {:.2} | {:.2} | {:.2} | **{:.2}** | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            case.name,
            m.auto_ms,
            m.lrt_ms,
            m.rt_ms,
            m.polygon_ms,
            m.ratio(),
            m.lrt_ms / m.polygon_ms,
            m.rt_ms / m.polygon_ms,
            m.shaded_per_pixel,
            m.overdraw_auto,
            m.overdraw_hull,
            m.overdraw_rt
        ),
    }
}

/// Measures `scene` at each of `times` (one renderer for the whole sweep, as a viewer would
/// use) and summarises the sweep in one line: the worst ratio and slowest LRT frame.
fn sweep(
    ctx: &GpuContext,
    name: &str,
    scene: &Scene,
    times: &[f64],
    frames: u32,
) -> anyhow::Result<Line> {
    let (width, height) = SIZES[0];
    let mut renderer = GpuRenderer::new(ctx, scene, width, height)?;
    let mut measured = Vec::new();
    for &ct in times {
        let case = at_time(name, scene, ct);
        let m = measure(ctx, &mut renderer, &case.scene, frames)?;
        println!("  {} {}", case.name, m.fields());
        measured.push((ct, m));
    }
    let worst = measured
        .iter()
        .max_by(|a, b| a.1.ratio().total_cmp(&b.1.ratio()))
        .context("a sweep has frames")?;
    let slowest = |method| {
        measured
            .iter()
            .map(|(_, m)| m.ms(method))
            .fold(0.0, f64::max)
    };
    let worst_of = |method| {
        measured
            .iter()
            .map(|(_, m)| m.ms(method) / m.polygon_ms)
            .fold(0.0, f64::max)
    };
    let median_ratio = median(measured.iter().map(|(_, m)| m.ratio()).collect());
    let tris = scene.triangle_count();
    let frames_swept = times.len();
    Ok(Line {
        frames: times
            .iter()
            .map(|&ct| (at_time(name, scene, ct).name, (width, height)))
            .collect(),
        text: format!(
            "sweep={name} size={width}x{height} tris={tris} frames={frames_swept} method=auto worst_ratio={:.2} worst_ct={:.2} median_ratio={median_ratio:.2} worst_lrt_ratio={:.2} worst_rt_ratio={:.2} slowest_auto_ms={:.2} slowest_lrt_ms={:.2} slowest_rt_ms={:.2} worst_shaded_per_pixel={:.2}",
            worst.1.ratio(),
            worst.0,
            worst_of(Method::Lrt),
            worst_of(Method::Rt),
            slowest(Method::Auto),
            slowest(Method::Lrt),
            slowest(Method::Rt),
            measured
                .iter()
                .map(|(_, m)| m.shaded_per_pixel)
                .fold(0.0, f64::max)
        ),
        row: format!(
            "| {name} (sweep, {frames_swept} frames) | {width}×{height} | {tris} | ≤ {:.2} | ≤ {:.2} | ≤ {:.2} | | worst {:.2} | worst {:.2} | worst {:.2} | | | | |",
            slowest(Method::Auto),
            slowest(Method::Lrt),
            slowest(Method::Rt),
            worst_of(Method::Auto),
            worst_of(Method::Lrt),
            worst_of(Method::Rt),
        ),
    })
}

/// What the last `cargo xtask validate --bench-frames` recorded
/// ([`crate::validate::BENCH_FRAMES_RECORD`]) and the commit the bench measures.
struct Validation {
    /// The commit and date the record was made at, if there is a record.
    made: Option<(String, String)>,
    /// Each recorded frame: name, `WxH`, whether it passed.
    frames: Vec<(String, String, bool)>,
    /// The commit being measured.
    commit: String,
}

impl Validation {
    /// Reads the record, if any.
    fn read(workspace: &Path) -> Self {
        let text = std::fs::read_to_string(workspace.join(crate::validate::BENCH_FRAMES_RECORD))
            .unwrap_or_default();
        let mut lines = text.lines();
        let made = lines.next().and_then(|header| {
            let header = header.strip_prefix("# commit=")?;
            let (commit, date) = header.split_once(" date=")?;
            Some((commit.to_owned(), date.to_owned()))
        });
        let frames = lines
            .filter_map(|line| {
                let mut fields = line.split('\t');
                Some((
                    fields.next()?.to_owned(),
                    fields.next()?.to_owned(),
                    fields.next()? == "pass",
                ))
            })
            .collect();
        Self {
            made,
            frames,
            commit: crate::provenance::commit(workspace),
        }
    }

    /// The table cell for a line timing `frames`: validated (and when) only if every frame
    /// passed in a record made at the commit being measured.
    fn cell(&self, frames: &[(String, (u32, u32))]) -> String {
        let Some((commit, date)) = &self.made else {
            return "no (run `cargo xtask validate --bench-frames`)".to_owned();
        };
        if *commit != self.commit || commit.ends_with("-dirty") {
            return format!("no (the record is of {commit})");
        }
        let passed = frames
            .iter()
            .filter(|(name, (width, height))| {
                let size = format!("{width}x{height}");
                self.frames
                    .iter()
                    .any(|(n, s, pass)| n == name && *s == size && *pass)
            })
            .count();
        if passed == frames.len() {
            format!("yes, {date} ({commit})")
        } else {
            format!("no: {passed} of {} frames passed", frames.len())
        }
    }
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

/// The static cases, each timed at every size of [`SIZES`].
fn static_cases() -> anyhow::Result<Vec<Case>> {
    Ok(vec![
        builtin("fig10-cube50")?,
        builtin("fig10-cube200")?,
        model_case("OBJ/spider.obj", 0.9)?,
        model_case(ENGINE, 0.9)?,
        builtin("teaser")?,
        three_engines()?,
        with_spectral_colour(builtin("teaser")?),
        builtin("flythrough")?,
    ])
}

/// The fly-by sweeps: name, scene and the observation times of their frames, timed at the first
/// size of [`SIZES`].
fn sweeps() -> anyhow::Result<Vec<(&'static str, Scene, Vec<f64>)>> {
    Ok(vec![
        ("teaser", builtin("teaser")?.scene, teaser_sweep_times()),
        (
            "engine-beside",
            shifted(&model_case(ENGINE, 0.9)?.scene, ENGINE_BESIDE),
            engine_sweep_times(),
        ),
        (
            "flythrough",
            builtin("flythrough")?.scene,
            flythrough_sweep_times(),
        ),
    ])
}

/// Every frame the bench times, named as the bench prints it (`NAME@ct=T` for a sweep's
/// frames), with its size: what `cargo xtask validate --bench-frames` checks.
///
/// # Errors
/// Missing models.
pub fn timed_frames() -> anyhow::Result<Vec<(Case, (u32, u32))>> {
    let static_cases = static_cases()?;
    let mut frames = Vec::new();
    for size in SIZES {
        frames.extend(static_cases.iter().map(|case| {
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
                .map(|&ct| (at_time(name, &scene, ct), SIZES[0])),
        );
    }
    Ok(frames)
}

/// Runs the benchmark with `frames` timed frames per measurement and updates
/// `docs/performance.md`; with `only`, runs the cases whose name contains it and leaves the
/// document alone.
///
/// # Errors
/// No GPU, missing models, or an unwritable document.
pub fn run(workspace: &Path, frames: u32, only: Option<&str>) -> anyhow::Result<()> {
    let selected = |name: &str| only.is_none_or(|o| name.contains(o));
    let ctx =
        GpuContext::new().context("cargo xtask bench needs a GPU adapter (software ones count)")?;
    let adapter = ctx.adapter_summary();
    println!("adapter: {adapter}");
    let static_cases = static_cases()?;
    let mut lines = Vec::new();
    for size in SIZES {
        for case in static_cases.iter().filter(|c| selected(&c.name)) {
            let mut renderer = GpuRenderer::new(&ctx, &case.scene, size.0, size.1)?;
            let m = measure(&ctx, &mut renderer, &case.scene, frames)?;
            let layers: Vec<String> = renderer
                .object_layers()
                .iter()
                .map(|l| l.map_or_else(|| "-".to_owned(), |l| format!("{l:.2}")))
                .collect();
            println!("  layers per object: {}", layers.join(" "));
            let line = static_line(case, size, &m);
            println!("{}", line.text);
            lines.push(line);
        }
    }
    for (name, scene, times) in sweeps()? {
        if !selected(name) {
            continue;
        }
        let line = sweep(&ctx, name, &scene, &times, frames)?;
        println!("{}", line.text);
        lines.push(line);
    }
    if only.is_some() {
        return Ok(());
    }
    let timing = if ctx.timestamps {
        "GPU timestamp queries"
    } else {
        "wall clock of render + readback"
    };
    let mut table = format!(
        "{TABLE_START}\nAdapter: {adapter}. Median of {frames} frames after {WARM_UP} warm-up frames per measurement, timed by {timing}.\n\n\
         | scene | size | triangles | auto ms | LRT ms | RT ms | polygon ms | **auto / polygon** | LRT / polygon | RT / polygon | shaded per covered pixel | auto fragments per covered pixel | LRT fragments | RT fragments | frames validated |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n"
    );
    let validation = Validation::read(workspace);
    for line in &lines {
        table += &format!("{} {} |\n", line.row, validation.cell(&line.frames));
    }
    table += TABLE_END;
    let doc = workspace.join("docs/performance.md");
    let text =
        std::fs::read_to_string(&doc).with_context(|| format!("cannot read {}", doc.display()))?;
    let updated = match (text.find(TABLE_START), text.find(TABLE_END)) {
        (Some(a), Some(b)) if a < b => {
            format!("{}{table}{}", &text[..a], &text[b + TABLE_END.len()..])
        }
        _ => format!("{text}\n{table}\n"),
    };
    std::fs::write(&doc, updated).with_context(|| format!("cannot write {}", doc.display()))?;
    println!("updated {}", doc.display());
    Ok(())
}
