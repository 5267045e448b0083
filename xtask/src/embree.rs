//! `cargo xtask embree`: the CPU tracer against Intel's Embree on identical rays (issue 69's
//! anchor).
//!
//! For each case the exact CPU picture's marginal cost — what the whole `srt render --backend
//! cpu` process takes at the picture's size over the same render at 8 × 8, medians of runs in
//! turn, so that start-up and the tracer's build cancel — is set against Embree's intersection
//! time on the same rays, per thread: every pixel's backward ray taken into each object's rest
//! frame (a straight line there for an object at rest or in uniform motion, Eq. 3 and 5),
//! queried against one Embree scene per object, one thread (`embreex`, Embree's Python binding,
//! run by `xtask/embree/anchor.py`; a development tool, never a dependency of srt), its time
//! divided by srt's thread count. The rays, meshes and the CPU's hit mask are written under
//! `target/embree/`; the hit masks must agree on ≥ 99.9 % of the pixels (f32 silhouettes
//! against f64). Only scenes whose objects move uniformly: a spinning or thrusting body's rays
//! are curves in its rest frame, which Embree does not trace.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use anyhow::{Context as _, bail};
use glam::DVec2;
use srt_scene::{Scene, SceneDescription};
use srt_trace::Tracer;

use crate::bench::results::median;

/// The least fraction of pixels on which Embree's and the CPU tracer's hit masks agree.
pub const LEAST_AGREEMENT: f64 = 0.999;

/// Whole-process runs of each size per case, in turn (medians are compared).
const RUNS: usize = 5;

/// The size whose render is subtracted as the process's fixed cost.
const SMALL: (u32, u32) = (8, 8);

/// A case: its name, what `srt render` is given, and the scene it builds.
struct EmbreeCase {
    name: String,
    argument: String,
    scene: Scene,
}

/// A scene file's observer at `position`, looking at the origin, z up, with a 45° field.
fn observer_toml(name: &str, position: [f64; 3]) -> String {
    let [x, y, z] = position;
    format!(
        "name = \"{name}\"\n[observer]\nposition = [{x:?}, {y:?}, {z:?}]\n\
         look_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, 1.0]\nfov_y_deg = 45.0\n"
    )
}

/// A scene file's object: the model at `model`, `fit`, at rest with its rest frame's origin at
/// `offset`.
fn engine_toml_object(name: &str, model: &Path, offset: [f64; 3]) -> String {
    let [x, y, z] = offset;
    format!(
        "[[object]]\nname = \"{name}\"\nfit = true\noffset = [{x:?}, {y:?}, {z:?}]\n\
         [object.shape]\ntype = \"model\"\npath = \"{}\"\n",
        model.display()
    )
}

/// The 2CylinderEngine of the assimp corpus, `fit`, at rest, seen from (0, −2.6, 0) along +y
/// with a 45° field: the setting.
fn engine_toml(model: &Path) -> String {
    observer_toml("engine-at-rest", [0.0, -2.6, 0.0])
        + &engine_toml_object("engine", model, [0.0; 3])
}

/// Nine engines at rest, `fit`, on a 3 × 3 grid facing the observer at (0, −9, 0) (1.09 M
/// triangles, one BVH shared by all nine): the large scene.
fn nine_engines_toml(model: &Path) -> String {
    let mut text = observer_toml("nine-engines", [0.0, -9.0, 0.0]);
    for (row, z) in [2.2, 0.0, -2.2].into_iter().enumerate() {
        for (column, x) in [-3.0, 0.0, 3.0].into_iter().enumerate() {
            text += &engine_toml_object(&format!("engine {row}{column}"), model, [x, 0.0, z]);
        }
    }
    text
}

/// The cases: the built-in spider, Fig. 10's cubes and the teaser, and the engine at rest and
/// nine of them (written as scene files under `folder`, where the assimp corpus is installed).
fn cases(folder: &Path) -> anyhow::Result<Vec<EmbreeCase>> {
    let mut cases = Vec::new();
    for name in ["spider", "fig10-cube200", "fig10-cube50", "teaser"] {
        let builtin = srt_scene::builtin::find_builtin(name)
            .with_context(|| format!("{name} is a built-in scene"))?;
        let (scene, _) = builtin.build()?;
        cases.push(EmbreeCase {
            name: name.to_owned(),
            argument: name.to_owned(),
            scene,
        });
    }
    let model = srt_scene::corpus::folder().join(crate::cases::ENGINE);
    if model.is_file() {
        for (name, text) in [
            ("engine-at-rest", engine_toml(&model)),
            ("nine-engines", nine_engines_toml(&model)),
        ] {
            let path = folder.join(format!("{name}.toml"));
            std::fs::create_dir_all(folder)?;
            std::fs::write(&path, &text).with_context(|| format!("writing {}", path.display()))?;
            let (scene, _) = SceneDescription::from_toml_str(&text, name)?.build(folder)?;
            cases.push(EmbreeCase {
                name: name.to_owned(),
                argument: path.display().to_string(),
                scene,
            });
        }
    } else {
        println!(
            "SKIPPED engine-at-rest and nine-engines: {} is missing ({})",
            model.display(),
            srt_scene::corpus::HOW_TO_GET_IT
        );
    }
    Ok(cases)
}

/// Writes what `anchor.py` reads for `scene` at `width` × `height` into `folder`: per object
/// its rest-frame vertices (f32 triples), triangles (u32 triples) and every pixel's backward
/// ray in its rest frame (origin and direction, f32), row by row; `hits.u8`, 1 where the CPU
/// tracer sees an object; `meta.json`. Returns the scene's triangle count.
fn export(scene: &Scene, (width, height): (u32, u32), folder: &Path) -> anyhow::Result<usize> {
    if scene.objects.iter().any(|o| !o.motion.is_rest()) {
        bail!("a spinning or thrusting body's rays are curves: Embree cannot trace them");
    }
    std::fs::create_dir_all(folder).with_context(|| format!("creating {}", folder.display()))?;
    let rays = scene
        .observer
        .view_rays(f64::from(width) / f64::from(height));
    let centre = srt_trace::sample_offsets(1)[0];
    let observer = scene.observer.event();
    let mut triangles = 0;
    for (k, object) in scene.objects.iter().enumerate() {
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        for part in &object.parts {
            let base = u32::try_from(vertices.len() / 12)?;
            for p in part.mesh.positions() {
                for c in p.to_array() {
                    vertices.extend_from_slice(&(c as f32).to_le_bytes());
                }
            }
            for t in part.mesh.triangles() {
                for i in t {
                    indices.extend_from_slice(&(base + i).to_le_bytes());
                }
            }
            triangles += part.mesh.triangles().len();
        }
        let mut bytes = Vec::with_capacity(width as usize * height as usize * 24);
        for y in 0..height {
            for x in 0..width {
                let point = DVec2::new(f64::from(x), f64::from(y)) + centre;
                let ndc = srt_trace::pixel_ndc((f64::from(width), f64::from(height)), point);
                let (_, direction) = rays.ray(ndc).context("a perspective picture's ray")?;
                let ray = object.frame.backward_ray(observer, direction);
                for c in ray
                    .origin
                    .to_array()
                    .into_iter()
                    .chain(ray.direction.to_array())
                {
                    bytes.extend_from_slice(&(c as f32).to_le_bytes());
                }
            }
        }
        let write = |name: String, data: &[u8]| {
            let path = folder.join(name);
            std::fs::write(&path, data).with_context(|| format!("writing {}", path.display()))
        };
        write(format!("object_{k}_vertices.f32"), &vertices)?;
        write(format!("object_{k}_triangles.u32"), &indices)?;
        write(format!("object_{k}_rays.f32"), &bytes)?;
    }
    let tracer = Tracer::new(scene);
    let events = tracer
        .render_seen_events(width, height, &|_| {}, &AtomicBool::new(false))
        .context("a render without a stop flag finishes")?;
    let hits: Vec<u8> = events.iter().map(|e| u8::from(e.is_some())).collect();
    std::fs::write(folder.join("hits.u8"), hits)?;
    let meta = format!(
        "{{\"objects\": {}, \"width\": {width}, \"height\": {height}}}",
        scene.objects.len()
    );
    std::fs::write(folder.join("meta.json"), meta)?;
    Ok(triangles)
}

/// What `anchor.py` measured: Embree's best one-thread time over every object's rays, and the
/// fraction of pixels whose hit agrees with the CPU tracer's.
struct Anchor {
    seconds: f64,
    /// The same rays against one far triangle per object, which every ray misses at the root:
    /// the part of `seconds` paid per ray whatever the mesh (the binding's and Embree's setup).
    floor: f64,
    agreement: f64,
    /// The fraction of pixels some object's ray hits in Embree.
    hits: f64,
}

/// Runs `anchor.py` on an exported `folder`.
fn anchor(root: &Path, folder: &Path) -> anyhow::Result<Anchor> {
    let script = root.join("xtask/embree/anchor.py");
    let output = Command::new("python3")
        .arg(&script)
        .arg(folder)
        .output()
        .with_context(|| format!("running python3 {}", script.display()))?;
    if !output.status.success() {
        bail!(
            "{} failed ({}): {}\nEmbree's Python binding installs with `pip install embreex`",
            script.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    let text = String::from_utf8(output.stdout)?;
    let field = |name: &str| -> anyhow::Result<f64> {
        let line = text
            .lines()
            .find_map(|l| l.strip_prefix(&format!("{name}=")))
            .with_context(|| format!("anchor.py printed no {name}: {text}"))?;
        Ok(line.trim().parse()?)
    };
    Ok(Anchor {
        seconds: field("seconds")?,
        floor: field("floor_seconds")?,
        agreement: field("agreement")?,
        hits: field("embree_hits")?,
    })
}

/// The marginal seconds of `srt render ARGUMENT --backend cpu` at `size` over [`SMALL`]: medians
/// of [`RUNS`] whole processes of each, in turn.
fn marginal(
    srt: &Path,
    argument: &str,
    (width, height): (u32, u32),
    out: &Path,
) -> anyhow::Result<f64> {
    let run = |(w, h): (u32, u32)| -> anyhow::Result<f64> {
        let start = Instant::now();
        let status = Command::new(srt)
            .args(["render", argument, "--backend", "cpu", "--width"])
            .arg(w.to_string())
            .arg("--height")
            .arg(h.to_string())
            .arg("-o")
            .arg(out)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status()
            .with_context(|| format!("running {}", srt.display()))?;
        if !status.success() {
            bail!("srt render {argument} at {w}x{h} failed ({status})");
        }
        Ok(start.elapsed().as_secs_f64())
    };
    let (mut full, mut small) = (Vec::new(), Vec::new());
    for _ in 0..RUNS {
        full.push(run((width, height))?);
        small.push(run(SMALL)?);
    }
    Ok(median(full) - median(small))
}

/// The tracer's own costs of a picture, measured inside this process (medians of [`RUNS`],
/// wall time): what the whole process's marginal time splits into.
struct InProcess {
    /// Building the tracer (its BVHs): [`Tracer::new`], the first of a process (no BVH kept
    /// from an earlier tracer).
    build: f64,
    /// The same for a later frame of the same scene (its BVHs kept from the last tracer).
    build_next: f64,
    /// Tracing every pixel, nothing shaded ([`Tracer::coverage`]), on all threads.
    tracing: f64,
    /// The same on one thread.
    tracing_one_thread: f64,
    /// The display picture ([`Tracer::render`]): tracing and shading, on all threads.
    picture: f64,
}

/// [`InProcess`] of `scene` at `width` × `height`, one sample per pixel.
fn in_process(scene: &Scene, (width, height): (u32, u32)) -> anyhow::Result<InProcess> {
    let settings = srt_trace::RenderSettings {
        width,
        height,
        samples: 1,
    };
    let timed = |f: &dyn Fn()| {
        let times: Vec<f64> = (0..RUNS)
            .map(|_| {
                let start = Instant::now();
                f();
                start.elapsed().as_secs_f64()
            })
            .collect();
        median(times)
    };
    let build = timed(&|| {
        srt_trace::forget_kept_bvhs();
        drop(Tracer::new(scene));
    });
    let tracer = Tracer::new(scene);
    let build_next = timed(&|| drop(Tracer::new(scene)));
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    Ok(InProcess {
        build,
        build_next,
        tracing: timed(&|| drop(tracer.coverage(settings))),
        tracing_one_thread: timed(&|| one_thread.install(|| drop(tracer.coverage(settings)))),
        picture: timed(&|| drop(tracer.render(settings, &|_| {}))),
    })
}

/// `cargo xtask embree`: every case (or those whose name contains `only`) at each of `sizes`,
/// one line each; fails where a hit mask agrees on fewer than [`LEAST_AGREEMENT`] of the pixels.
///
/// # Errors
/// If a case does not build, srt or `anchor.py` fails, or the masks disagree.
pub fn run(root: &Path, sizes: &[(u32, u32)], only: Option<&str>) -> anyhow::Result<()> {
    let status = Command::new("cargo")
        .current_dir(root)
        .args(["build", "--release", "--locked", "-p", "srt"])
        .status()
        .context("running cargo build")?;
    if !status.success() {
        bail!("cargo build --release -p srt failed");
    }
    let srt = root.join("target/release/srt");
    let folder: PathBuf = root.join("target/embree");
    // The CPU tracer's threads: rayon's default, one per core.
    let threads = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let mut failures = Vec::new();
    for case in cases(&folder)? {
        if only.is_some_and(|o| !case.name.contains(o)) {
            continue;
        }
        for &(width, height) in sizes {
            let here = folder.join(format!("{}_{width}x{height}", case.name));
            let triangles = export(&case.scene, (width, height), &here)?;
            let anchor = anchor(root, &here)?;
            let srt_seconds =
                marginal(&srt, &case.argument, (width, height), &here.join("srt.png"))?;
            let own = in_process(&case.scene, (width, height))?;
            let per_thread = anchor.seconds / threads as f64;
            let above_floor = (anchor.seconds - anchor.floor) / threads as f64;
            println!(
                "case={} size={width}x{height} triangles={triangles} embree_one_thread_ms={:.2} \
                 embree_floor_ms={:.2} threads={threads} srt_marginal_ms={:.2} ratio={:.2} \
                 ratio_above_floor={:.2} tracing_ms={:.2} ratio_tracing={:.2} shading_ms={:.2} \
                 rest_ms={:.2} thread_speedup={:.2} build_ms={:.2} build_per_picture={:.2} \
                 next_build_ms={:.2} \
                 hit={:.4} agreement={:.5}",
                case.name,
                1e3 * anchor.seconds,
                1e3 * anchor.floor,
                1e3 * srt_seconds,
                srt_seconds / per_thread,
                srt_seconds / above_floor,
                1e3 * own.tracing,
                own.tracing / per_thread,
                1e3 * (own.picture - own.tracing),
                1e3 * (srt_seconds - own.picture),
                own.tracing_one_thread / own.tracing,
                1e3 * own.build,
                own.build / own.picture,
                1e3 * own.build_next,
                anchor.hits,
                anchor.agreement
            );
            std::io::stdout().flush()?;
            if anchor.agreement < LEAST_AGREEMENT {
                failures.push(format!(
                    "{} at {width}x{height}: the hit masks agree on {:.5} of the pixels, under {LEAST_AGREEMENT}",
                    case.name, anchor.agreement
                ));
            }
        }
    }
    if !failures.is_empty() {
        bail!("{}", failures.join("\n"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use srt_trace::intersect_triangle;

    /// The little-endian 4-byte words of a file `export` wrote.
    fn words(path: &Path) -> Vec<[u8; 4]> {
        let bytes = std::fs::read(path).unwrap();
        bytes
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect()
    }

    /// The exported rays, met with the exported meshes by the f64 triangle test, hit where the
    /// CPU tracer sees an object (the spider approaching at 0.9c, 128 × 72): Embree is given the
    /// rays the tracer traces. Seen to fail with the rays taken in the observer's frame (the
    /// spider's rest direction replaced by the viewing direction).
    #[test]
    fn the_exported_rays_meet_the_meshes_where_the_cpu_tracer_sees_them() {
        let (scene, _) = srt_scene::builtin::find_builtin("spider")
            .unwrap()
            .build()
            .unwrap();
        let folder = std::env::temp_dir().join(format!("srt-embree-test-{}", std::process::id()));
        let (width, height) = (128, 72);
        export(&scene, (width, height), &folder).unwrap();
        let floats = |name: &str| -> Vec<f64> {
            words(&folder.join(name))
                .into_iter()
                .map(|w| f64::from(f32::from_le_bytes(w)))
                .collect()
        };
        let vertices: Vec<DVec3> = floats("object_0_vertices.f32")
            .chunks_exact(3)
            .map(DVec3::from_slice)
            .collect();
        let triangles: Vec<u32> = words(&folder.join("object_0_triangles.u32"))
            .into_iter()
            .map(u32::from_le_bytes)
            .collect();
        let rays = floats("object_0_rays.f32");
        let hits = std::fs::read(folder.join("hits.u8")).unwrap();
        assert_eq!(hits.len(), (width * height) as usize);
        let mut agree = 0;
        for (pixel, ray) in rays.chunks_exact(6).enumerate() {
            let (origin, direction) = (DVec3::from_slice(&ray[..3]), DVec3::from_slice(&ray[3..]));
            let met = triangles.chunks_exact(3).any(|t| {
                let corners = [0, 1, 2].map(|i| vertices[t[i] as usize]);
                intersect_triangle(origin, direction, corners).is_some()
            });
            agree += usize::from(met == (hits[pixel] == 1));
        }
        let seen = hits.iter().filter(|&&h| h == 1).count();
        assert!(seen > 200, "the spider covers {seen} pixels");
        assert!(
            agree >= hits.len() - 2,
            "{agree} of {} pixels agree",
            hits.len()
        );
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
