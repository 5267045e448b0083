//! `srt render`: resolve the scene, apply command-line overrides, render one image or an
//! animation, and write it.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, bail};
use indicatif::{ProgressBar, ProgressStyle};
use srt_physics::Frame;
use srt_scene::{Effects, Scene};
use srt_trace::{RenderSettings, Tracer};

use crate::cli::{Backend, EffectsArg, RenderArgs};
use crate::output::{check_writable, numbered, write_image};
use crate::source::load_scene;

/// Runs `srt render`.
///
/// # Errors
/// Any user-facing failure: unknown scene, bad file, bad override, unwritable output.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let (mut scene, warnings) = load_scene(&args.scene, args.beta)?;
    for warning in &warnings {
        eprintln!("warning: {warning}");
    }
    apply_overrides(&mut scene, args)?;
    if args.backend == Backend::Gpu {
        bail!("the GPU backend is not part of this build yet; use --backend cpu (or auto)");
    }
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{}.png", file_safe(&scene.name))));
    check_writable(&output)?;
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        samples: args.samples,
    };
    match args.frames {
        None => render_one(&scene, settings, &output),
        Some(frames) => {
            let t0 = args.t0.unwrap_or(scene.observer.ct);
            let t1 = args.t1.unwrap_or(t0 + 10.0);
            let digits = frames.to_string().len().max(4);
            for frame in 0..frames {
                let fraction = if frames > 1 {
                    f64::from(frame) / f64::from(frames - 1)
                } else {
                    0.0
                };
                scene.observer.ct = t0 + fraction * (t1 - t0);
                render_one(&scene, settings, &numbered(&output, frame, digits))?;
            }
            Ok(())
        }
    }
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
        if !ct.is_finite() {
            bail!("--time must be a finite number");
        }
        scene.observer.ct = ct;
    }
    if let Some(beta) = args.beta {
        for object in &mut scene.objects {
            object.frame = Frame::new(beta, object.frame.offset()).with_context(|| {
                format!(
                    "--beta {},{},{} is not a valid velocity",
                    beta.x, beta.y, beta.z
                )
            })?;
        }
    }
    Ok(())
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

fn render_one(
    scene: &Scene,
    settings: RenderSettings,
    output: &std::path::Path,
) -> anyhow::Result<()> {
    let start = Instant::now();
    let tracer = Tracer::new(scene);
    let bar = ProgressBar::new(u64::from(settings.height));
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} rendering {msg} [{bar:40}] {pos}/{len} rows, {eta} left",
        )
        .expect("valid progress template")
        .progress_chars("=> "),
    );
    bar.set_message(scene.name.clone());
    // Only show the bar for renders that take more than a moment.
    bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    let shown = std::sync::atomic::AtomicBool::new(false);
    let image = tracer.render(settings, &|rows| {
        if start.elapsed().as_secs_f64() > 1.0
            && !shown.swap(true, std::sync::atomic::Ordering::Relaxed)
        {
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
        }
        bar.set_position(u64::from(rows));
    });
    bar.finish_and_clear();
    write_image(&image, output)?;
    println!(
        "wrote {} ({}x{}, {} sample{} per pixel, cpu, {:.2} s)",
        output.display(),
        settings.width,
        settings.height,
        settings.samples,
        if settings.samples == 1 { "" } else { "s" },
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
