//! Drives the viewer's UI headless with egui_kittest: the widgets are found by their labels
//! through AccessKit, clicked and typed into as a user would, and the image the viewer shows is
//! read back from the GPU (the same display texture the window draws).
//!
//! GPU tests start with `srt_gpu::context_or_skip` (a visible skip without an adapter; a failure
//! with `SRT_REQUIRE_GPU=1`). The bad-input tests need no GPU.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use eframe::egui::{self, Key, Modifiers};
use eframe::egui_wgpu;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use srt_gpu::GpuContext;
use srt_scene::{Effects, View};
use srt_viewer::exact_path::ExactPath;
use srt_viewer::view::DISPLAY_FORMAT;
use srt_viewer::{Level, ViewerApp};

const SIZE: [f32; 2] = [1000.0, 620.0];

fn app(scene: &str, ctx: Option<GpuContext>) -> ViewerApp {
    let (editor, warnings) =
        srt_viewer::open_arguments(&[scene.to_owned()]).expect("the scene opens");
    let gpu = ctx.map(|ctx| {
        let renderer = egui_wgpu::Renderer::new(
            &ctx.device,
            DISPLAY_FORMAT,
            egui_wgpu::RendererOptions::default(),
        );
        (ctx, Some(Arc::new(egui::mutex::RwLock::new(renderer))))
    });
    let mut app = ViewerApp::new(editor, gpu, &warnings);
    // The GPU draws every pane, so that pictures compared across frames come from one path
    // whatever the machine's timing (the choice between paths has a test of its own).
    app.set_exact_path(ExactPath::Gpu);
    app
}

fn harness(app: ViewerApp) -> Harness<'static, ViewerApp> {
    let mut harness = Harness::builder()
        .with_size(SIZE)
        .build_ui_state(|ui, app: &mut ViewerApp| app.show(ui), app);
    harness.run_steps(3);
    harness
}

/// Replaces the text of the field labelled `label` by `text` and presses Enter.
fn type_into(harness: &mut Harness<'static, ViewerApp>, label: &str, text: &str) {
    click(harness, label);
    harness.run_steps(1);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::A);
    harness.run_steps(1);
    harness.get_by_label(label).type_text(text);
    harness.run_steps(1);
    harness.key_press(Key::Enter);
    harness.run_steps(3);
}

/// Scrolls the widget labelled `label` into view and clicks it.
fn click(harness: &mut Harness<'static, ViewerApp>, label: &str) {
    harness.get_by_label(label).scroll_to_me();
    harness.run_steps(2);
    harness.get_by_label(label).hover();
    harness.run_steps(1);
    harness.get_by_label(label).click();
    harness.run_steps(2);
}

fn image(harness: &Harness<'static, ViewerApp>) -> image::RgbaImage {
    harness
        .state()
        .read_image()
        .expect("the viewer shows an image")
}

/// Number of pixels that differ by more than 8 levels in some channel.
fn changed_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 8))
        .count()
}

/// Mean colour of the pixels that are not background (black), as fractions summing to 1.
fn mean_chromaticity(image: &image::RgbaImage) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for p in image.pixels().filter(|p| p.0[..3].iter().any(|&c| c > 10)) {
        for (s, c) in sum.iter_mut().zip(p.0) {
            *s += f64::from(c);
        }
    }
    let total: f64 = sum.iter().sum();
    assert!(total > 0.0, "the image is black");
    sum.map(|s| s / total)
}

#[test]
fn changing_the_speed_changes_the_image_and_switching_effects_changes_its_colours() {
    let Some(ctx) = srt_gpu::context_or_skip("viewer_speed_and_effects") else {
        return;
    };
    // The teaser: a spider approaching at 0.95c (selected first), a receding cube, a sphere.
    let mut harness = harness(app("teaser", Some(ctx)));
    assert_eq!(
        harness.state().status().level,
        Level::Info,
        "{:?}",
        harness.state().status()
    );
    let at_095 = image(&harness);
    assert!(
        at_095.width() > 300 && at_095.height() > 300,
        "{:?}",
        at_095.dimensions()
    );

    // Speed: type 0.3 into the speed field of the selected object (the spider).
    type_into(&mut harness, "Type a speed:", "0.3");
    assert!(
        (harness.state().editor().speed(0) - 0.3).abs() < 1e-12,
        "{:?}",
        harness.state().status()
    );
    let at_03 = image(&harness);
    let changed = changed_pixels(&at_095, &at_03);
    assert!(
        changed > 2000,
        "changing the speed changed only {changed} pixels"
    );

    // Effects: Doppler → geometry only changes the colours, not (much) the shape.
    assert_eq!(harness.state().editor().scene().effects, Effects::Doppler);
    let doppler = mean_chromaticity(&at_03);
    click(&mut harness, "Geometry only");
    assert_eq!(harness.state().editor().scene().effects, Effects::Geometry);
    let geometry_image = image(&harness);
    let geometry = mean_chromaticity(&geometry_image);
    let shift: f64 = doppler
        .iter()
        .zip(geometry)
        .map(|(a, b)| (a - b).abs())
        .sum();
    assert!(
        shift > 0.03,
        "switching effects did not change the colours: {doppler:?} vs {geometry:?}"
    );

    // Doppler + searchlight: brightness now changes too.
    click(&mut harness, "Doppler + searchlight");
    assert_eq!(
        harness.state().editor().scene().effects,
        Effects::Searchlight
    );
    assert!(changed_pixels(&geometry_image, &image(&harness)) > 1000);

    // A speed of 1 is refused with a message and changes nothing.
    let before = image(&harness);
    type_into(&mut harness, "Type a speed:", "1");
    let status = harness.state().status().clone();
    assert_eq!(status.level, Level::Error);
    assert!(status.text.contains("speed of light"), "{}", status.text);
    assert!((harness.state().editor().speed(0) - 0.3).abs() < 1e-12);
    assert_eq!(changed_pixels(&before, &image(&harness)), 0);

    // Split screen: both methods side by side, as wide as one view before.
    click(&mut harness, "Split screen (both)");
    let split = image(&harness);
    assert!(
        split.width().abs_diff(before.width()) <= 1,
        "{} vs {}",
        split.width(),
        before.width()
    );
    let half = split.width() / 2;
    let left = image::imageops::crop_imm(&split, 0, 0, half, split.height()).to_image();
    let right = image::imageops::crop_imm(&split, half, 0, half, split.height()).to_image();
    mean_chromaticity(&left);
    mean_chromaticity(&right);
    assert!(
        !harness.state().status().text.contains("rendering failed"),
        "{:?}",
        harness.state().status()
    );

    // "Save PNG" writes what is shown.
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("view.png");
    type_into(&mut harness, "Path:", &png.display().to_string());
    click(&mut harness, "Save PNG");
    assert_eq!(
        harness.state().status().level,
        Level::Info,
        "{}",
        harness.state().status().text
    );
    let saved = image::open(&png).expect("the PNG was written").into_rgba8();
    assert_eq!(saved.dimensions(), split.dimensions());
    assert_eq!(changed_pixels(&saved, &split), 0);

    // Back to one view and to split screen again (the second view's texture is reused).
    click(&mut harness, "Local ray tracing");
    assert_eq!(image(&harness).dimensions(), before.dimensions());
    click(&mut harness, "Split screen (both)");
    assert_eq!(changed_pixels(&image(&harness), &split), 0);
    harness.state().take_gpu_errors().expect("no GPU errors");
}

#[test]
fn adding_and_removing_a_model_reuploads_the_scene() {
    let Some(ctx) = srt_gpu::context_or_skip("viewer_add_remove") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("tetra.stl");
    std::fs::write(&model, tetrahedron_stl()).unwrap();
    let mut harness = harness(app("teaser", Some(ctx)));
    let before = image(&harness);
    drop_files(&mut harness, &[model]);
    assert_eq!(
        harness.state().editor().object_count(),
        4,
        "{:?}",
        harness.state().status()
    );
    assert_ne!(harness.state().status().level, Level::Error);
    let with_model = image(&harness);
    if changed_pixels(&before, &with_model) < 100 {
        with_model
            .save(std::env::temp_dir().join("viewer_added_model.png"))
            .unwrap();
        panic!(
            "the added model is not seen (image in the temporary folder: viewer_added_model.png)"
        );
    }
    click(&mut harness, "Remove");
    assert_eq!(harness.state().editor().object_count(), 3);
    // The same scene as before (a few pixels may differ where triangles meet).
    let after = image(&harness);
    let changed = changed_pixels(&before, &after);
    assert!(
        changed < 50,
        "{changed} pixels differ from the scene before the model was added"
    );
    harness.state().take_gpu_errors().expect("no GPU errors");
}

/// A file as the window system hands it to egui when it is dropped.
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

fn drop_files(harness: &mut Harness<'static, ViewerApp>, paths: &[PathBuf]) {
    for path in paths {
        harness
            .input_mut()
            .dropped_files
            .push(Arc::new(Dropped(path.clone())));
    }
    harness.run_steps(3);
}

#[test]
fn bad_input_gives_a_message_and_leaves_the_scene_unchanged() {
    // No GPU needed: the panel works without one.
    let mut harness = harness(app("teaser", None));
    let description = harness.state().editor().description().clone();

    for (text, expected) in [
        ("1", "speed of light"),
        ("1.5c", "speed of light"),
        ("fast", "not a speed"),
        ("-0.2", "negative"),
    ] {
        type_into(&mut harness, "Type a speed:", text);
        let status = harness.state().status();
        assert_eq!(status.level, Level::Error, "{text}");
        assert!(status.text.contains(expected), "{text}: {}", status.text);
        assert_eq!(
            harness.state().editor().description(),
            &description,
            "{text}"
        );
    }

    let dir = tempfile::tempdir().unwrap();
    let notes = dir.path().join("notes.txt");
    std::fs::write(&notes, "not a model").unwrap();
    drop_files(&mut harness, &[notes]);
    assert_eq!(harness.state().status().level, Level::Error);
    assert!(
        harness.state().status().text.contains("notes.txt"),
        "{}",
        harness.state().status().text
    );

    let broken = dir.path().join("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nf 1 2 3\nthis is no OBJ file\n").unwrap();
    drop_files(&mut harness, &[broken]);
    assert_eq!(harness.state().status().level, Level::Error);
    assert!(
        harness.state().status().text.contains("broken.obj"),
        "{}",
        harness.state().status().text
    );

    let missing = dir.path().join("missing.glb");
    type_into(&mut harness, "Path:", &missing.display().to_string());
    click(&mut harness, "Add model");
    assert_eq!(harness.state().status().level, Level::Error);
    assert!(
        harness.state().status().text.contains("missing.glb"),
        "{}",
        harness.state().status().text
    );

    assert_eq!(harness.state().editor().description(), &description);
    assert_eq!(harness.state().editor().object_count(), 3);
}

#[test]
fn the_scene_is_saved_as_toml_from_the_panel() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("my scene.toml");
    let mut harness = harness(app("teaser", None));
    type_into(&mut harness, "Type a speed:", "0.5");
    click(&mut harness, "Doppler + searchlight");
    type_into(&mut harness, "Path:", &path.display().to_string());
    click(&mut harness, "Save scene");
    assert_eq!(
        harness.state().status().level,
        Level::Info,
        "{}",
        harness.state().status().text
    );
    let (scene, _, _) = srt_scene::load_scene_file(&path).expect("the saved scene loads");
    assert_eq!(scene.objects.len(), 3);
    assert!((scene.objects[0].frame.beta().length() - 0.5).abs() < 1e-12);
    assert_eq!(scene.effects, Effects::Searchlight);
}

#[test]
fn keyboard_flies_and_resets_the_camera() {
    let mut harness = harness(app("teaser", None));
    let home = harness.state().editor().scene().observer;
    harness.key_down(Key::W);
    harness.run_steps(5);
    harness.key_up(Key::W);
    harness.run_steps(1);
    let moved = harness.state().editor().scene().observer;
    assert!(
        (moved.position - home.position).dot(home.direction) > 0.0,
        "W moves forward"
    );
    harness.key_press(Key::R);
    harness.run_steps(1);
    assert_eq!(
        harness.state().editor().scene().observer.position,
        home.position
    );
    harness.key_press(Key::Space);
    harness.run_steps(5);
    assert!(
        harness.state().editor().scene().observer.time > home.time,
        "Space plays the time"
    );
}

#[test]
fn the_throttle_accelerates_releasing_it_coasts_and_b_brakes_to_rest() {
    // No GPU needed: the flight changes the observer, which the panel shows.
    let mut harness = harness(app("flythrough", None));
    let start = harness.state().editor().observer_beta().length();
    assert!(harness.state().flight().is_none());
    harness.key_down(Key::PageUp);
    harness.run_steps(20);
    harness.key_up(Key::PageUp);
    harness.run_steps(1);
    let flying = harness.state().editor().observer_beta().length();
    assert!(flying > start, "PageUp accelerates: {start} → {flying}");
    let flight = *harness.state().flight().expect("a flight started");
    assert!(flight.proper_time > 0.0);
    assert!(flight.world_time(harness.state().editor()) > flight.proper_time);
    // Released: the velocity stays, the clocks run.
    harness.run_steps(10);
    let coasting = harness.state().editor().observer_beta().length();
    assert!((coasting - flying).abs() < 1e-12, "{flying} → {coasting}");
    assert!(harness.state().flight().unwrap().proper_time > flight.proper_time);
    // B brakes to rest (at α = 0.5 from above 0.9c: some hundreds of frames).
    harness.key_press(Key::B);
    for _ in 0..2000 {
        harness.run_steps(10);
        if harness.state().editor().observer_beta() == glam::DVec3::ZERO {
            break;
        }
    }
    assert_eq!(harness.state().editor().observer_beta(), glam::DVec3::ZERO);
    assert_ne!(harness.state().status().level, Level::Error);
}

#[test]
fn two_views_side_by_side_and_the_probe_tells_what_a_pixel_shows() {
    let Some(ctx) = srt_gpu::context_or_skip("viewer_views_and_probe") else {
        return;
    };
    let mut harness = harness(app("fig7", Some(ctx)));
    let one = image(&harness);
    harness
        .state_mut()
        .set_views(View::Seen, Some(View::Newtonian));
    harness.run_steps(2);
    let two = image(&harness);
    assert!(two.width().abs_diff(one.width()) <= 1);
    let half = two.width() / 2;
    let left = image::imageops::crop_imm(&two, 0, 0, half, two.height()).to_image();
    let right = image::imageops::crop_imm(&two, half, 0, half, two.height()).to_image();
    // The seen cube (approaching at 0.95c) and the Newtonian cube (at rest where it is now,
    // rest colours) look different.
    assert!(changed_pixels(&left, &right) > 100);
    assert!(!harness.state().status().text.contains("failed"));

    // The probe: the centre of the left (seen) pane is on the cube, a corner is background.
    harness
        .state_mut()
        .probe_at(0, egui::vec2(0.5, 0.5), left.dimensions());
    let found = harness
        .state()
        .probed()
        .flatten()
        .expect("the cube is at the centre")
        .clone();
    assert_eq!(found.object, "cube");
    assert!(found.doppler > 5.0, "{}", found.doppler);
    // At ct = 0 the Newtonian cube is at the origin, straight ahead, at rest: D = 1.
    click(&mut harness, "time = 0");
    harness
        .state_mut()
        .probe_at(1, egui::vec2(0.5, 0.5), right.dimensions());
    let rest = harness
        .state()
        .probed()
        .flatten()
        .expect("the cube")
        .clone();
    assert!(
        (rest.doppler - 1.0).abs() < 1e-12,
        "at rest: {}",
        rest.doppler
    );
    harness
        .state_mut()
        .probe_at(0, egui::vec2(0.01, 0.01), left.dimensions());
    assert_eq!(harness.state().probed(), Some(None));

    // A click on the picture probes too (the picture fills the window right of the panel).
    harness.input_mut().events.extend([
        egui::Event::PointerMoved(egui::pos2(SIZE[0] - 5.0, 60.0)),
        egui::Event::PointerButton {
            pos: egui::pos2(SIZE[0] - 5.0, 60.0),
            button: egui::PointerButton::Primary,
            pressed: true,
            modifiers: Modifiers::NONE,
        },
    ]);
    harness.run_steps(1);
    harness.input_mut().events.push(egui::Event::PointerButton {
        pos: egui::pos2(SIZE[0] - 5.0, 60.0),
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    harness.run_steps(2);
    assert_eq!(
        harness.state().probed(),
        Some(None),
        "a click at the edge: background"
    );
    harness.state().take_gpu_errors().expect("no GPU errors");
}

/// A binary STL file with one tetrahedron (4 triangles), shared with the unit tests.
fn tetrahedron_stl() -> Vec<u8> {
    include_bytes!("../../srt-scene/tests/fixtures/tetrahedron.stl").to_vec()
}

#[test]
fn recording_writes_one_video_frame_per_drawn_frame_on_a_fixed_clock() {
    let Some(ctx) = srt_gpu::context_or_skip("recording_writes_one_video_frame_per_drawn_frame")
    else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("teaser flight.gif");
    let mut harness = harness(app("teaser", Some(ctx)));
    type_into(&mut harness, "Path:", &path.display().to_string());
    click(&mut harness, "Record");
    assert!(
        harness.state().is_recording(),
        "{}",
        harness.state().status().text
    );
    click(&mut harness, "Play");
    let ct_start = harness.state().editor().scene().observer.time;
    harness.run_steps(12);
    let ct_end = harness.state().editor().scene().observer.time;
    // 12 frames at 24 fps of playback at 1 unit of time per second: exactly 0.5, whatever the frames took.
    assert!(
        (ct_end - ct_start - 0.5).abs() < 1e-9,
        "ct advanced by {} in 12 recorded frames",
        ct_end - ct_start
    );
    assert!(!path.exists(), "the video appears before it is finished");
    let (written, frames) = harness.state_mut().stop_recording().unwrap();
    assert_eq!(written, path);
    // Frames drawn since Record was clicked: the clicks' steps and the twelve.
    assert!(frames >= 12, "{frames} frames");
    let mut decoder = gif::DecodeOptions::new()
        .read_info(std::fs::File::open(&path).unwrap())
        .unwrap();
    let mut decoded = 0;
    let mut first: Option<Vec<u8>> = None;
    let mut changed = false;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        decoded += 1;
        match &first {
            None => first = Some(frame.buffer.to_vec()),
            Some(f) => changed |= *f != frame.buffer.to_vec(),
        }
    }
    assert_eq!(decoded, frames);
    assert!(changed, "the objects move while the video plays");
    assert!(!harness.state().is_recording());
    harness.state().take_gpu_errors().expect("no GPU errors");
}

/// The exact picture drawn by the CPU tracer is the CPU reference's, byte for byte, and agrees
/// with the GPU's but at silhouettes; with "the faster", a software adapter's viewer times both
/// paths and shows the same picture by either (a hardware GPU always draws).
#[test]
fn the_exact_picture_is_the_same_by_the_cpu_tracer_and_the_gpu_and_auto_times_both() {
    let Some(ctx) = srt_gpu::context_or_skip("viewer_exact_path") else {
        return;
    };
    let software = ctx.software_api().is_some();
    let mut harness = harness(app("fig7", Some(ctx)));
    harness.state_mut().set_exact_path(ExactPath::Gpu);
    harness.run_steps(2);
    let gpu = image(&harness);
    assert_eq!(harness.state().exact_report(), None);
    harness.state_mut().set_exact_path(ExactPath::Cpu);
    harness.run_steps(2);
    let cpu = image(&harness);
    let (width, height) = cpu.dimensions();
    let scene = harness.state().editor().scene();
    let settings = srt_trace::RenderSettings {
        width,
        height,
        samples: 1,
    };
    let reference = srt_trace::Tracer::new(scene).render(settings, &|_| {});
    let reference: Vec<u8> = (reference.to_rgb8().into_iter())
        .flat_map(|[r, g, b]| [r, g, b, u8::MAX])
        .collect();
    assert!(
        cpu.as_raw() == &reference,
        "the CPU pane is the CPU reference"
    );
    let apart = changed_pixels(&gpu, &cpu);
    assert!(
        apart < (width * height / 100) as usize,
        "{apart} of {width}×{height} pixels apart"
    );
    assert!(changed_pixels(&gpu, &image::RgbaImage::new(width, height)) > 1000);

    // "The faster": the GPU's frames are timed, then the CPU is measured, and the faster by
    // the margin draws.
    for _ in 0..2 {
        harness.state_mut().set_exact_path(ExactPath::Auto);
        harness.run_steps(2);
    }
    if !software {
        assert_eq!(harness.state().exact_report(), None);
        return;
    }
    // Both paths were timed (which of them then draws is the rule's, tested in exact_path:
    // the times reported are those after the last frame, not those it was chosen by).
    let (_, gpu_seconds, cpu_seconds) = harness.state().exact_report().expect("weighed");
    assert!(gpu_seconds.is_some_and(|s| s > 0.0), "the GPU timed");
    assert!(cpu_seconds.is_some_and(|s| s > 0.0), "the CPU measured");
    let shown = image(&harness);
    assert!(changed_pixels(&shown, &cpu) < (width * height / 100) as usize);
    harness.state().take_gpu_errors().expect("no GPU errors");
}
