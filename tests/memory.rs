//! A picture of any size `srt render` accepts is rendered and written a band of rows at a time
//! (issue 54, "Memory"): the file holds the whole picture, bit for bit, and the process holds
//! a band, not the picture.

use std::path::Path;
use std::process::Command;
use std::sync::atomic::AtomicBool;

use crate::common::{builtin_scene, exr_channel, folder, srt, stderr};
use srt::engine::{aov_values, channel_f32, display_as_linear};
use srt_trace::{RenderSettings, Tracer};

/// 4096 × 600 pixels are three bands on the CPU (256, 256 and 88 rows): the PNG and every
/// channel of the EXR are the whole picture the tracer renders at once.
#[test]
fn a_picture_written_in_bands_is_the_whole_picture() {
    let dir = folder();
    let size = ["--width", "4096", "--height", "600", "--backend", "cpu"];
    for file in [&["-o", "t.png"][..], &["--aov", "-o", "t.exr"]] {
        let output = srt(&[&["render", "fig4"][..], &size, file].concat(), dir.path());
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let scene = builtin_scene("fig4");
    let tracer = Tracer::new(&scene);
    let settings = RenderSettings {
        width: 4096,
        height: 600,
        samples: 1,
    };
    let display = tracer.render(settings, &|_| {});
    let png = image::open(dir.path().join("t.png")).unwrap().into_rgb8();
    assert_eq!(png.dimensions(), (4096, 600));
    assert_eq!(display.pixels.len(), 4096 * 600);
    assert!(
        display.to_rgb8().iter().flatten().eq(png.as_raw().iter()),
        "the PNG is the whole picture"
    );
    let exr = dir.path().join("t.exr");
    let radiance = tracer.render_radiance(settings, &|_| {});
    let events = tracer
        .render_seen_events(4096, 600, &|_| {}, &AtomicBool::new(false))
        .unwrap();
    for (k, (light, shown)) in [("R", "display.R"), ("G", "display.G"), ("B", "display.B")]
        .into_iter()
        .enumerate()
    {
        let wanted: Vec<f32> = radiance.pixels.iter().map(|p| channel_f32(p[k])).collect();
        assert!(exr_channel(&exr, light) == wanted, "channel {light}");
        let wanted: Vec<f32> = (display.pixels.iter())
            .map(|p| display_as_linear(p[k]))
            .collect();
        assert!(exr_channel(&exr, shown) == wanted, "channel {shown}");
    }
    for (k, name) in srt::engine::AOV_CHANNELS.into_iter().enumerate() {
        let wanted: Vec<f32> = (events.iter())
            .map(|event| aov_values(event.as_ref())[k])
            .collect();
        assert!(
            exr_channel(&exr, name)
                .iter()
                .map(|v| v.to_bits())
                .eq(wanted.iter().map(|v| v.to_bits())),
            "channel {name}"
        );
    }
    assert!(events.iter().any(Option::is_some), "the cube is seen");
}

/// The peak resident size of `srt ARGS` run in `dir`, in bytes, with its standard error; the run
/// must succeed. The size is the kernel's own count for the process (`ru_maxrss`, which `wait4`
/// gives with its exit status): exact, whatever the machine's speed or load, where reading the
/// high-water mark while it runs could miss a peak between two reads.
#[cfg(target_os = "linux")]
fn peak_resident_bytes(args: &[&str], dir: &Path) -> (u64, String) {
    use std::io::Read as _;
    use std::os::unix::process::ExitStatusExt as _;
    let mut child = Command::new(env!("CARGO_BIN_EXE_srt"))
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("srt runs");
    let mut err = String::new();
    (child.stderr.take().expect("piped"))
        .read_to_string(&mut err)
        .expect("srt's standard error reads");
    let (status, peak) = wait_with_usage(child);
    let status = std::process::ExitStatus::from_raw(status);
    assert!(status.success(), "{status}: {err}");
    assert!(peak > 0, "no resident size for srt {args:?}");
    (peak, err)
}

/// Waits for `child` (which std then never waits for): its raw wait status and its peak resident
/// size in bytes (`wait4(2)`'s `ru_maxrss`, in KiB on Linux).
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn wait_with_usage(child: std::process::Child) -> (i32, u64) {
    let pid = libc::pid_t::try_from(child.id()).expect("a process id fits pid_t");
    let mut status = 0;
    // SAFETY: `rusage` is plain integers, for which all zeros is a valid value.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    loop {
        // SAFETY: both pointers are to live locals of the types wait4 writes.
        let waited = unsafe { libc::wait4(pid, &raw mut status, 0, &raw mut usage) };
        if waited == pid {
            break;
        }
        let error = std::io::Error::last_os_error();
        assert_eq!(
            error.kind(),
            std::io::ErrorKind::Interrupted,
            "wait4: {error}"
        );
    }
    let kib = u64::try_from(usage.ru_maxrss).expect("a size is not negative");
    (status, kib * 1024)
}

/// The widest picture srt accepts (16384 pixels, so the widest band) held in bands on the CPU:
/// a 16384 × 2048 PNG, where holding the picture took 76 bytes a pixel (2.5 GB), and a 16384 ×
/// 512 EXR with every channel (about 100 bytes a pixel: 0.8 GB), stay far below that; with
/// `auto` (the GPU's tiles where there is an adapter), the PNG stays within srt's bound.
#[cfg(target_os = "linux")]
#[test]
fn a_huge_picture_is_written_within_the_memory_bound() {
    const MIB: u64 = 1 << 20;
    let (png_limit, exr_limit) = (256 * MIB, 512 * MIB);
    assert!(exr_limit.max(png_limit) <= srt::engine::MEMORY_BOUND);
    let dir = folder();
    let wide = ["render", "fig4", "--width", "16384"];
    let (png_peak, _) = peak_resident_bytes(
        &[
            &wide[..],
            &["--height", "2048", "--backend", "cpu", "-o", "t.png"],
        ]
        .concat(),
        dir.path(),
    );
    assert!(png_peak < png_limit, "PNG: peak {} MiB", png_peak / MIB);
    let (exr_peak, _) = peak_resident_bytes(
        &[
            &wide[..],
            &[
                "--height",
                "512",
                "--backend",
                "cpu",
                "--aov",
                "-o",
                "t.exr",
            ],
        ]
        .concat(),
        dir.path(),
    );
    assert!(exr_peak < exr_limit, "EXR: peak {} MiB", exr_peak / MIB);
    let (auto_peak, _) = peak_resident_bytes(
        &[&wide[..], &["--height", "2048", "-o", "auto.png"]].concat(),
        dir.path(),
    );
    assert!(
        auto_peak < srt::engine::MEMORY_BOUND,
        "auto: peak {} MiB",
        auto_peak / MIB
    );
    for name in ["t.png", "auto.png"] {
        let size = image::ImageReader::open(dir.path().join(name))
            .unwrap()
            .into_dimensions()
            .unwrap();
        assert_eq!(size, (16384, 2048));
    }
}

/// The GPU engine with tiles forced small (40 × 32 output pixels of a 160 × 90 picture at 4
/// samples: the widest that fits 128 target pixels, in whole 16-row blocks) gives what it gives drawing the frame whole: the display colours and the radiance
/// of every tile and the time channels drawn tile by tile at the output size, as `srt render`
/// asks the engine for them band by band.
#[test]
fn gpu_tiles_give_the_whole_frame() {
    use srt::engine::{Backend, Engine, Frame};
    use srt::software::Job;
    use srt::tiles::Tiling;
    use srt_gpu::Method;
    use srt_trace::Output;
    if srt_gpu::context_or_skip("gpu_tiles_give_the_whole_frame").is_none() {
        return;
    }
    let scene = builtin_scene("teaser");
    let settings = RenderSettings {
        width: 160,
        height: 90,
        samples: 4,
    };
    let engine = || {
        Engine::choose(
            Backend::Gpu,
            Method::Auto,
            &Job::still(settings),
            &Frame::new(&scene),
        )
        .unwrap()
        .engine
    };
    let (mut whole, mut tiled) = (engine(), engine());
    let Engine::Gpu {
        context,
        renderer,
        tiling,
        ..
    } = &mut tiled
    else {
        panic!("--backend gpu gives a GPU engine");
    };
    let scale = tiling.scale;
    let (side_width, side_height) = (64 * scale, 48 * scale);
    *tiling = Tiling::new(160, 90, scale, |w, h| w <= side_width && h <= side_height);
    assert_eq!((tiling.tile_width, tiling.tile_height), (40, 32));
    renderer.resize(context, 40 * scale, 32 * scale).unwrap();
    let frame = Frame::new(&scene);
    let never = AtomicBool::new(false);
    let bands = [0..32, 32..64, 64..90];
    for output in [Output::Display, Output::Radiance] {
        let expected = whole
            .render(&frame, settings, output, &|_| {}, &never)
            .unwrap()
            .unwrap();
        let mut banded = Vec::new();
        for rows in bands.clone() {
            let band = tiled
                .render_band(&frame, settings, rows, output, &|_| {}, &never)
                .unwrap()
                .unwrap();
            banded.extend(band);
        }
        // The whole frame and the bands' rows, pixel for pixel: a short band fails here.
        assert_eq!(expected.len(), 160 * 90, "{output:?}: the whole frame");
        assert_eq!(
            banded.len(),
            expected.len(),
            "{output:?}: the bands' pixels"
        );
        let worst = (expected.iter().zip(&banded))
            .map(|(e, t)| ((*e - *t).abs() / e.abs().max(glam::DVec3::splat(1e-3))).max_element())
            .fold(0.0, f64::max);
        assert!(worst < 1e-3, "{output:?}: relative difference {worst}");
    }
    let expected = whole
        .render_aov(&frame, settings, &|_| {}, &never)
        .unwrap()
        .unwrap();
    let mut banded = Vec::new();
    for rows in bands {
        let band = tiled
            .render_aov_band(&frame, settings, rows, &|_| {}, &never)
            .unwrap()
            .unwrap();
        banded.extend(band);
    }
    assert_eq!(expected.len(), 160 * 90, "the whole frame's time channels");
    assert_eq!(banded.len(), expected.len(), "the bands' time channels");
    for (e, t) in expected.iter().zip(&banded) {
        assert_eq!(e[4], t[4], "the same object seen");
        for k in 0..4 {
            assert!(
                (e[k] - t[k]).abs() <= 1e-4 * e[k].abs().max(1.0),
                "{e:?} {t:?}"
            );
        }
    }
    assert!(
        expected.iter().any(|v| v[4] >= 0.0),
        "some pixel sees an object"
    );
}
