//! The window's contents: the side panel, the status line and the rendered view, with the
//! keyboard and mouse controls. [`ViewerApp::show`] draws everything into any [`egui::Ui`], so
//! the same code runs in the real window (through [`eframe::App`]) and in headless tests.

use std::borrow::Cow;
use std::collections::VecDeque;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::time::{Duration, Instant};

use eframe::egui::{self, Color32, Key, RichText, Sense};
use eframe::egui_wgpu;
use glam::DVec3;
use srt_color::ToneMap;
use srt_gpu::GpuContext;
use srt_physics::{Frame, doppler_factor};
use srt_scene::import::SUPPORTED_EXTENSIONS;
use srt_scene::resolve::{PathKind, SCENE_FILE_EXTENSION, model_extension_list, path_kind};
use srt_scene::{Effects, Observer, ResolveError, Scene, SurfaceColour, View};

use crate::camera::{self, Movement};
use crate::edit::{EditError, Editor, MAX_SLIDER_SPEED, parse_speed};
use crate::pilot::{DEFAULT_ACCELERATION, Engine, Flight, MotionReadout};
use crate::probe::{Probe, probe};
use crate::record::{FRAME_RATES, Recorder};
use crate::view::{Pane, PaneScene, SceneView, UploadKey, ViewMethod, view_label};

/// The egui renderer the display textures are registered with.
pub type EguiRenderer = Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>;

/// Default line width of a wireframe, in the object's own units (its radius is about 1).
const DEFAULT_WIREFRAME_WIDTH: f64 = 0.02;

/// A frame slower than this (milliseconds) pauses playback with a message.
const SLOW_FRAME_MS: f64 = 1500.0;

/// Turning speed of a mouse drag, radians per point.
const TURN_PER_POINT: f64 = 0.004;

/// How serious a status message is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Something happened as asked.
    Info,
    /// It happened, but with a caveat (a model's missing texture…).
    Warning,
    /// It was refused; the scene is unchanged.
    Error,
}

/// The message in the status line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Status {
    /// How serious.
    pub level: Level,
    /// The text.
    pub text: String,
}

/// The last probe: which pixel of which pane was clicked, and what is there.
#[derive(Debug, Clone, PartialEq)]
struct ProbeShown {
    /// The pane clicked, and the point clicked in it as fractions of its width and height.
    pane: Pane,
    at: egui::Vec2,
    /// The pixel in the pane's picture, and the picture's size.
    pixel: (u32, u32),
    size: (u32, u32),
    /// The observer of the picture probed (time and camera).
    observer: Observer,
    /// What is there (`None`: the background).
    found: Option<Probe>,
}

/// What a file dialog was opened for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Purpose {
    AddModel,
    OpenScene,
    SaveScene,
    SaveImage,
    Record,
}

/// The GPU side: the device (shared with egui in the window), the uploaded scene and the
/// display textures.
struct Gpu {
    ctx: GpuContext,
    egui: Option<EguiRenderer>,
    view: SceneView,
}

/// The interactive viewer: the scene editor, the GPU view and the panel's state.
pub struct ViewerApp {
    editor: Editor,
    gpu: Option<Gpu>,
    status: Status,
    selected: Option<usize>,
    speed_text: String,
    speed_text_for: Option<usize>,
    keep_apparent: bool,
    method: ViewMethod,
    playing: bool,
    playback_speed: f64,
    time_range: (f64, f64),
    fly_speed: f64,
    path_text: String,
    dialog: Option<(Purpose, Receiver<Option<PathBuf>>)>,
    needs_render: bool,
    last_size: (u32, u32),
    rendered: VecDeque<Instant>,
    last_fps: f64,
    /// Smoothed time to render one frame (GPU included), milliseconds.
    frame_ms: f64,
    /// Fraction of the window's pixels rendered (1, ½ or ¼ per axis).
    resolution: f32,
    /// Print frame statistics to stderr once a second (`SRT_VIEW_STATS=1`).
    stats: Option<Instant>,
    gpu_failed: bool,
    /// The view on the left (or alone), and the one on its right, if the screen is split.
    left_view: View,
    right_view: Option<View>,
    /// The panes last rendered, left to right.
    panes: Vec<Pane>,
    /// The flight in progress (throttle or brake pressed since the last "End flight").
    flight: Option<Flight>,
    /// The engine's proper acceleration α, in c per unit of ct.
    acceleration: f64,
    /// The engine command from the panel's buttons this frame (keys add to it).
    engine_button: Option<Engine>,
    probe: Option<ProbeShown>,
    /// The video being recorded: while it runs, every drawn frame is one video frame and the
    /// clock advances by one frame period per frame.
    recorder: Option<Recorder>,
    /// The frame rate of the next recording (one of [`FRAME_RATES`]).
    record_fps: u32,
}

impl ViewerApp {
    /// A viewer of `editor`'s scene. `gpu` is the device to render with and, in the window,
    /// the egui renderer to show the image with; without a GPU the panel still works but shows
    /// no image. `warnings` (from loading the scene) go to the status line.
    #[must_use]
    pub fn new(
        editor: Editor,
        gpu: Option<(GpuContext, Option<EguiRenderer>)>,
        warnings: &[String],
    ) -> Self {
        let observer = editor.scene().observer;
        let fly_speed =
            camera::default_fly_speed(&observer, editor.objects().iter().map(|o| o.frame.offset()));
        let gpu = gpu.map(|(ctx, egui)| Gpu {
            view: SceneView::new(&ctx),
            ctx,
            egui,
        });
        let status = if warnings.is_empty() {
            Status {
                level: Level::Info,
                text: intro(&editor),
            }
        } else {
            Status {
                level: Level::Warning,
                text: warnings.join("; "),
            }
        };
        let ct = observer.ct;
        Self {
            selected: (editor.object_count() > 0).then_some(0),
            editor,
            gpu,
            status,
            speed_text: String::new(),
            speed_text_for: None,
            keep_apparent: true,
            method: ViewMethod::Exact,
            playing: false,
            playback_speed: 1.0,
            time_range: (ct.min(0.0) - 20.0, ct.max(0.0) + 20.0),
            fly_speed,
            path_text: String::new(),
            dialog: None,
            needs_render: true,
            last_size: (0, 0),
            rendered: VecDeque::new(),
            last_fps: 0.0,
            frame_ms: 0.0,
            resolution: 1.0,
            stats: std::env::var_os("SRT_VIEW_STATS").map(|_| Instant::now()),
            gpu_failed: false,
            left_view: View::Seen,
            right_view: None,
            panes: Vec::new(),
            flight: None,
            acceleration: DEFAULT_ACCELERATION,
            engine_button: None,
            probe: None,
            recorder: None,
            record_fps: FRAME_RATES[0],
        }
    }

    /// The views shown, left to right (one, or two side by side).
    #[must_use]
    pub fn views(&self) -> Vec<View> {
        std::iter::once(self.left_view)
            .chain(self.right_view.filter(|&right| right != self.left_view))
            .collect()
    }

    /// Shows `left` alone (`right` = `None`) or `left` and `right` side by side.
    pub fn set_views(&mut self, left: View, right: Option<View>) {
        self.left_view = left;
        self.right_view = right;
        self.needs_render = true;
    }

    /// The flight in progress, if any.
    #[must_use]
    pub const fn flight(&self) -> Option<&Flight> {
        self.flight.as_ref()
    }

    /// The probe's finding at the last pixel clicked: `None` before any click, `Some(None)` for
    /// the background.
    #[must_use]
    pub fn probed(&self) -> Option<Option<&Probe>> {
        self.probe.as_ref().map(|p| p.found.as_ref())
    }

    /// Probes the point `at` (fractions of the width and height, from the top-left) of pane
    /// `pane` (left to right, as last rendered) whose picture is `size` pixels: what is seen
    /// there, computed by the CPU reference tracer for that pixel's viewing ray.
    pub fn probe_at(&mut self, pane: usize, at: egui::Vec2, size: (u32, u32)) {
        let Some(&shown) = self.panes.get(pane) else {
            return;
        };
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "a pixel inside the picture"
        )]
        let pixel = (
            ((at.x.clamp(0.0, 1.0) * size.0 as f32) as u32).min(size.0.saturating_sub(1)),
            ((at.y.clamp(0.0, 1.0) * size.1 as f32) as u32).min(size.1.saturating_sub(1)),
        );
        let scene = self.editor.scene();
        let found = match view_scene(shown.view, scene) {
            Ok(viewed) => probe(viewed.as_ref(), size.0, size.1, pixel.0, pixel.1),
            Err(error) => {
                self.error(error);
                return;
            }
        };
        self.probe = Some(ProbeShown {
            pane: shown,
            at,
            pixel,
            size,
            observer: scene.observer,
            found,
        });
    }

    /// The scene editor (the scene as it is now).
    #[must_use]
    pub const fn editor(&self) -> &Editor {
        &self.editor
    }

    /// The message in the status line.
    #[must_use]
    pub const fn status(&self) -> &Status {
        &self.status
    }

    /// The GPU adapter's description, or a note that there is none.
    #[must_use]
    pub fn adapter(&self) -> String {
        self.gpu
            .as_ref()
            .map_or_else(|| "no GPU".to_owned(), |g| g.ctx.adapter_summary())
    }

    /// Reads back the image shown (both halves in split screen), if a GPU renders it.
    ///
    /// # Errors
    /// A message when there is no GPU, nothing was rendered yet, or the readback fails.
    pub fn read_image(&self) -> Result<image::RgbaImage, String> {
        let gpu = self.gpu.as_ref().ok_or("no GPU")?;
        gpu.view.read_image(&gpu.ctx).map_err(|e| e.to_string())
    }

    /// Frames rendered per second over the last second (0 when idle).
    #[must_use]
    pub fn frames_per_second(&self) -> f64 {
        let (Some(first), Some(last)) = (self.rendered.front(), self.rendered.back()) else {
            return 0.0;
        };
        if last.elapsed() > Duration::from_secs(1) || self.rendered.len() < 2 {
            return 0.0;
        }
        let span = last.duration_since(*first).as_secs_f64();
        if span > 0.0 {
            (self.rendered.len() - 1) as f64 / span
        } else {
            0.0
        }
    }

    /// Opens dropped or chosen files one by one (models are added; a `.toml` replaces the
    /// scene); every refusal is reported in the status line and leaves the scene as it was.
    pub fn open_files(&mut self, paths: &[PathBuf]) {
        for path in paths {
            self.open_file(path);
        }
    }

    fn open_file(&mut self, path: &Path) {
        let before = self.editor.clone();
        let result = self.editor.open_file(path);
        self.finish_structure_change(before, result, &format!("opened {}", path.display()));
        if self.status.level == Level::Error {
            return;
        }
        match path_kind(path) {
            PathKind::Model => {
                self.selected = self.editor.object_count().checked_sub(1);
                self.status.text.push_str(
                    " — it rests in front of you; give it a speed (e.g. type 0.9) to see it distort and change colour",
                );
            }
            PathKind::SceneFile => {
                self.selected = (self.editor.object_count() > 0).then_some(0);
                self.reset_time_range();
            }
            PathKind::Unsupported => {}
        }
    }

    /// After an edit that changed the set of objects: upload the new scene, or restore `before`
    /// when the edit or the upload failed.
    fn finish_structure_change(
        &mut self,
        before: Editor,
        result: Result<Vec<String>, EditError>,
        done: &str,
    ) {
        match result {
            Err(error) => self.error(error.to_string()),
            Ok(warnings) => match self.upload() {
                Err(error) => {
                    self.editor = before;
                    let _ = self.upload();
                    self.error(format!(
                        "the GPU cannot show this: {error}; the scene is unchanged"
                    ));
                }
                Ok(()) if warnings.is_empty() => self.info(done.to_owned()),
                Ok(()) => self.warn(format!("{done}, with warnings: {}", warnings.join("; "))),
            },
        }
        self.needs_render = true;
    }

    fn upload(&mut self) -> Result<(), String> {
        match &mut self.gpu {
            Some(gpu) => gpu
                .view
                .upload(
                    &gpu.ctx,
                    self.editor.scene(),
                    self.editor.structure_version(),
                )
                .map_err(|e| e.to_string()),
            None => Ok(()),
        }
    }

    fn info(&mut self, text: String) {
        self.status = Status {
            level: Level::Info,
            text,
        };
    }

    fn warn(&mut self, text: String) {
        self.status = Status {
            level: Level::Warning,
            text,
        };
    }

    fn error(&mut self, text: String) {
        self.status = Status {
            level: Level::Error,
            text,
        };
    }

    /// Reports the outcome of an edit: an error goes to the status line; success marks the
    /// view for rendering.
    fn edited(&mut self, result: Result<(), EditError>) {
        match result {
            Ok(()) => self.needs_render = true,
            Err(error) => self.error(error.to_string()),
        }
    }

    fn reset_time_range(&mut self) {
        let ct = self.editor.scene().observer.ct;
        self.time_range = (ct.min(0.0) - 20.0, ct.max(0.0) + 20.0);
    }

    /// Draws the whole viewer into `ui` and handles its input.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        // While recording, the clock advances by exactly one video frame per drawn frame, however
        // long the frame took to draw.
        let dt = match &self.recorder {
            Some(recorder) => recorder.frame_period(),
            None => f64::from(ui.input(|i| i.unstable_dt)).clamp(0.0, 0.5),
        };
        self.poll_dialog(ui.ctx());
        self.handle_drops(ui.ctx());
        self.handle_keys(ui.ctx(), dt);
        let engine = self.engine_button.take();
        self.fly(engine, dt);
        if self.playing && self.flight.is_none() {
            let ct = self.editor.scene().observer.ct + self.playback_speed * dt;
            let result = self.editor.set_time(ct);
            self.edited(result);
            self.extend_time_range(ct);
        }
        egui::Panel::bottom("srt-status").show(ui, |ui| self.status_line(ui));
        egui::Panel::left("srt-panel")
            .default_size(360.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.side_panel(ui));
            });
        egui::CentralPanel::no_frame().show(ui, |ui| self.central(ui));
        self.record_frame();
        if self.playing || self.recorder.is_some() {
            ui.ctx().request_repaint();
        }
    }

    /// Whether a video is being recorded.
    #[must_use]
    pub fn is_recording(&self) -> bool {
        self.recorder.is_some()
    }

    /// Starts recording what the viewer shows into `path` (.mp4 or .gif) at the chosen frame
    /// rate (see [`crate::record`]).
    ///
    /// # Errors
    /// A message naming the file when it cannot be recorded (extension, folder, size), or a
    /// recording is already running.
    pub fn start_recording(&mut self, path: &Path) -> Result<(), String> {
        if self.recorder.is_some() {
            return Err("a recording is already running: stop it first".to_owned());
        }
        let image = self.read_image()?;
        let recorder = Recorder::start(path, image.width(), image.height(), self.record_fps)?;
        self.recorder = Some(recorder);
        self.needs_render = true;
        Ok(())
    }

    /// Stops recording and finishes the video; returns its path and frame count.
    ///
    /// # Errors
    /// A message naming the file when it cannot be completed (nothing is left at its path), or
    /// when nothing is being recorded.
    pub fn stop_recording(&mut self) -> Result<(PathBuf, u32), String> {
        self.recorder
            .take()
            .ok_or_else(|| "nothing is being recorded".to_owned())?
            .finish()
    }

    /// Adds the image shown to the recording, if one runs; a failure stops it with a message.
    fn record_frame(&mut self) {
        if self.recorder.is_none() {
            return;
        }
        let pushed = self
            .read_image()
            .and_then(|image| match &mut self.recorder {
                Some(recorder) => recorder.push(&image),
                None => Ok(()),
            });
        if let Err(error) = pushed {
            // Dropping the recorder removes the unfinished file.
            self.recorder = None;
            self.error(format!("recording stopped: {error}"));
        }
    }

    /// Widens the time slider's range to include `ct`.
    fn extend_time_range(&mut self, ct: f64) {
        self.time_range.0 = self.time_range.0.min(ct);
        self.time_range.1 = self.time_range.1.max(ct);
    }

    /// One frame of flight: `engine` (from keys or buttons) starts a flight if none is in
    /// progress (and starts the clock); while the clock runs, the observer flies `dt` seconds
    /// times the playback speed of proper time.
    fn fly(&mut self, engine: Option<Engine>, dt: f64) {
        if engine.is_some() {
            if self.flight.is_none() {
                self.flight = Some(Flight::start(&self.editor));
            }
            self.playing = true;
        }
        let (Some(mut flight), true) = (self.flight, self.playing) else {
            return;
        };
        let dtau = self.playback_speed * dt;
        let engine = engine.unwrap_or(Engine::Coast);
        match flight.step(&mut self.editor, engine, self.acceleration, dtau) {
            Ok(()) => {
                self.flight = Some(flight);
                self.needs_render = true;
                self.extend_time_range(self.editor.observer_event().ct);
            }
            Err(error) => {
                self.playing = false;
                self.error(format!("the flight stopped: {error}"));
            }
        }
    }

    fn poll_dialog(&mut self, ctx: &egui::Context) {
        let Some((purpose, receiver)) = &self.dialog else {
            return;
        };
        let purpose = *purpose;
        match receiver.try_recv() {
            Err(TryRecvError::Empty) => ctx.request_repaint_after(Duration::from_millis(200)),
            Err(TryRecvError::Disconnected) | Ok(None) => {
                self.dialog = None;
                self.warn(
                    "no file chosen (if no dialog appeared, this desktop has no file-chooser portal or \
                     zenity: type the path into the field under \"Files\", or drop the file on the window)"
                        .to_owned(),
                );
            }
            Ok(Some(path)) => {
                self.dialog = None;
                self.path_text = path.display().to_string();
                self.file_action(purpose, &path);
            }
        }
    }

    fn file_action(&mut self, purpose: Purpose, path: &Path) {
        match purpose {
            Purpose::AddModel => {
                if path_kind(path) == PathKind::Model {
                    self.open_file(path);
                } else {
                    self.error(ResolveError::Unsupported(path.display().to_string()).to_string());
                }
            }
            Purpose::OpenScene => {
                if path_kind(path) == PathKind::SceneFile {
                    self.open_file(path);
                } else {
                    self.error(format!(
                        "{}: a scene file must end in .{SCENE_FILE_EXTENSION}",
                        path.display()
                    ));
                }
            }
            Purpose::SaveScene => match self.editor.save_toml(path) {
                Ok(()) => self.info(format!(
                    "saved the scene to {} (open it with `srt view` or `srt render`)",
                    path.display()
                )),
                Err(error) => self.error(error.to_string()),
            },
            Purpose::SaveImage => match self.save_png(path) {
                Ok(()) => self.info(format!("saved the image to {}", path.display())),
                Err(error) => self.error(error),
            },
            Purpose::Record => match self.start_recording(path) {
                Ok(()) => self.info(format!(
                    "recording {} at {} frames per second: press Stop recording to finish",
                    path.display(),
                    self.record_fps
                )),
                Err(error) => self.error(error),
            },
        }
    }

    /// Saves the image shown as a PNG file.
    ///
    /// # Errors
    /// A message when there is no image or the file cannot be written.
    pub fn save_png(&self, path: &Path) -> Result<(), String> {
        let image = self.read_image()?;
        let rgb = image::DynamicImage::ImageRgba8(image).into_rgb8();
        rgb.save_with_format(path, image::ImageFormat::Png)
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    fn start_dialog(&mut self, purpose: Purpose) {
        let (sender, receiver) = std::sync::mpsc::channel();
        let start = std::env::current_dir().ok();
        let name = self.editor.scene().name.clone();
        std::thread::spawn(move || {
            let mut dialog = rfd::FileDialog::new();
            if let Some(start) = start {
                dialog = dialog.set_directory(start);
            }
            let result = match purpose {
                Purpose::AddModel => dialog
                    .set_title("Add a 3D model")
                    .add_filter("3D models", &SUPPORTED_EXTENSIONS)
                    .pick_file(),
                Purpose::OpenScene => dialog
                    .set_title("Open a scene")
                    .add_filter("srt scenes", &[SCENE_FILE_EXTENSION])
                    .pick_file(),
                Purpose::SaveScene => dialog
                    .set_title("Save the scene")
                    .add_filter("srt scenes", &[SCENE_FILE_EXTENSION])
                    .set_file_name(format!("{name}.{SCENE_FILE_EXTENSION}"))
                    .save_file(),
                Purpose::SaveImage => dialog
                    .set_title("Save the image")
                    .add_filter("PNG images", &["png"])
                    .set_file_name(format!("{name}.png"))
                    .save_file(),
                Purpose::Record => dialog
                    .set_title("Record a video")
                    .add_filter("H.264 video or animated GIF", &["mp4", "gif"])
                    .set_file_name(format!("{name}.mp4"))
                    .save_file(),
            };
            let _ = sender.send(result);
        });
        self.dialog = Some((purpose, receiver));
    }

    fn handle_drops(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        if !dropped.is_empty() {
            self.open_files(&dropped);
        }
    }

    fn handle_keys(&mut self, ctx: &egui::Context, dt: f64) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let (movement, reset, toggle, fast, thrust, brake) = ctx.input(|i| {
            let down = |keys: [Key; 2]| f64::from(u8::from(keys.iter().any(|&k| i.key_down(k))));
            let axis = |plus: Key, minus: Key| down([plus, plus]) - down([minus, minus]);
            (
                Movement {
                    right: axis(Key::D, Key::A),
                    up: axis(Key::E, Key::Q),
                    forward: axis(Key::W, Key::S),
                },
                i.key_pressed(Key::R),
                i.key_pressed(Key::Space),
                i.modifiers.shift,
                down([Key::PageUp, Key::T]) - down([Key::PageDown, Key::G]),
                i.key_pressed(Key::B) || i.key_down(Key::B),
            )
        });
        if thrust != 0.0 {
            self.engine_button = Some(Engine::Thrust(thrust));
        } else if brake {
            self.engine_button = Some(Engine::Brake);
        }
        if self.flight.is_some() && (thrust != 0.0 || brake) {
            ctx.request_repaint();
        }
        if toggle {
            self.playing = !self.playing;
        }
        if reset {
            let result = self.editor.reset_view();
            self.edited(result);
        }
        if !movement.is_zero() {
            let speed = self.fly_speed * if fast { 4.0 } else { 1.0 };
            let observer = camera::fly(&self.editor.scene().observer, movement, speed, dt);
            let result = self.editor.set_observer(observer);
            self.edited(result);
            ctx.request_repaint();
        }
    }

    /// The status line: the message's first line (all of it on hover).
    fn status_line(&mut self, ui: &mut egui::Ui) {
        let colour = match self.status.level {
            Level::Info => ui.visuals().text_color(),
            Level::Warning => Color32::from_rgb(230, 180, 60),
            Level::Error => Color32::from_rgb(240, 90, 80),
        };
        let text = self.status.text.trim();
        let first = text.lines().next().unwrap_or_default();
        let shown = if first.len() < text.len() {
            format!("{first} (more: hover)")
        } else {
            first.to_owned()
        };
        let response = ui.add(egui::Label::new(RichText::new(shown).color(colour)).truncate());
        if first.len() < text.len() || response.hovered() {
            response.on_hover_text(text);
        }
    }

    fn side_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("srt view");
        self.readout(ui);
        egui::CollapsingHeader::new("Probe")
            .default_open(true)
            .show(ui, |ui| self.probe_section(ui));
        egui::CollapsingHeader::new("Objects")
            .default_open(true)
            .show(ui, |ui| self.objects_section(ui));
        egui::CollapsingHeader::new("Effects")
            .default_open(true)
            .show(ui, |ui| self.effects_section(ui));
        egui::CollapsingHeader::new("Time")
            .default_open(true)
            .show(ui, |ui| self.time_section(ui));
        egui::CollapsingHeader::new("Observer")
            .default_open(true)
            .show(ui, |ui| self.observer_section(ui));
        egui::CollapsingHeader::new("Flight")
            .default_open(true)
            .show(ui, |ui| self.flight_section(ui));
        egui::CollapsingHeader::new("Light")
            .default_open(false)
            .show(ui, |ui| self.light_section(ui));
        egui::CollapsingHeader::new("Views")
            .default_open(true)
            .show(ui, |ui| self.views_section(ui));
        egui::CollapsingHeader::new("Method")
            .default_open(true)
            .show(ui, |ui| self.method_section(ui));
        egui::CollapsingHeader::new("Files")
            .default_open(true)
            .show(ui, |ui| self.files_section(ui));
    }

    fn readout(&mut self, ui: &mut egui::Ui) {
        let fps = self.frames_per_second();
        if fps > 0.0 {
            self.last_fps = fps;
        }
        let (w, h) = self.last_size;
        ui.label(format!(
            "{} · {} triangles · {w}×{h} px",
            if fps > 0.0 {
                format!("{fps:.1} frames/s")
            } else if self.last_fps > 0.0 {
                format!("idle (was {:.1} frames/s)", self.last_fps)
            } else {
                "idle".to_owned()
            },
            self.editor.scene().triangle_count(),
        ));
        if self.frame_ms > 0.0 {
            ui.label(format!("last frame rendered in {:.0} ms", self.frame_ms));
        }
        ui.label(RichText::new(format!("GPU: {}", self.adapter())).small());
    }

    fn objects_section(&mut self, ui: &mut egui::Ui) {
        let count = self.editor.object_count();
        if self.selected.is_some_and(|i| i >= count) {
            self.selected = count.checked_sub(1);
        }
        for (index, object) in self.editor.objects().iter().enumerate() {
            let text = format!(
                "{} — {:.3}c, {} triangles",
                object.name,
                object.frame.beta().length(),
                object.triangle_count()
            );
            ui.selectable_value(&mut self.selected, Some(index), text);
        }
        if count == 0 {
            ui.label("No objects: add a model below, or drop one on the window.");
        }
        ui.horizontal(|ui| {
            if ui
                .button("Add model…")
                .on_hover_text(format!("a file dialog for {}", model_extension_list()))
                .clicked()
            {
                self.start_dialog(Purpose::AddModel);
            }
            if let Some(index) = self.selected
                && ui.button("Remove").clicked()
            {
                let before = self.editor.clone();
                let name = self.editor.objects()[index].name.clone();
                let result = self.editor.remove_object(index).map(|()| Vec::new());
                self.finish_structure_change(before, result, &format!("removed {name}"));
                self.selected = self
                    .editor
                    .object_count()
                    .checked_sub(1)
                    .map(|last| index.min(last));
            }
        });
        let Some(index) = self.selected.filter(|&i| i < self.editor.object_count()) else {
            return;
        };
        ui.separator();
        self.object_controls(ui, index);
    }

    fn object_controls(&mut self, ui: &mut egui::Ui, index: usize) {
        let object = &self.editor.objects()[index];
        let (name, readout) = (object.name.clone(), motion_readout(&object.frame));
        ui.label(RichText::new(&name).strong());
        self.speed_controls(ui, index, &name);
        ui.label(RichText::new(readout).small());
        self.direction_controls(ui, index);
        ui.checkbox(
            &mut self.keep_apparent,
            "Keep it where it is seen when the velocity changes",
        )
        .on_hover_text(
            "adjusts the offset so that the object's centre stays at the same place in the image",
        );
        let mut offset = self.editor.offset(index);
        if vector_row(ui, "Offset", &mut offset, 0.05, None) {
            let result = self.editor.set_offset(index, offset);
            self.edited(result);
        }
        self.wireframe_controls(ui, index);
    }

    /// Sets the velocity of object `index` (keeping where it is seen, if so chosen); whether the
    /// edit was accepted (a refusal goes to the status line).
    fn set_velocity(&mut self, index: usize, speed: f64, direction: DVec3) -> bool {
        let result = self
            .editor
            .set_velocity(index, speed, direction, self.keep_apparent);
        let done = result.is_ok();
        self.edited(result);
        done
    }

    /// The speed slider and the typed-speed field of object `index`.
    fn speed_controls(&mut self, ui: &mut egui::Ui, index: usize, name: &str) {
        let speed = self.editor.speed(index);
        let direction = self.editor.direction(index);
        let mut slider_speed = speed;
        let slider = egui::Slider::new(&mut slider_speed, 0.0..=MAX_SLIDER_SPEED)
            .text("speed (c)")
            .clamping(egui::SliderClamping::Always)
            .max_decimals(4);
        if ui.add(slider).changed() {
            self.set_velocity(index, slider_speed, direction);
            self.speed_text_for = None;
        }
        ui.horizontal(|ui| {
            let label = ui.label("Type a speed:");
            if self.speed_text_for != Some(index) {
                self.speed_text = format_speed(speed);
                self.speed_text_for = Some(index);
            }
            let response = ui
                .add(egui::TextEdit::singleline(&mut self.speed_text).desired_width(80.0))
                .labelled_by(label.id);
            let entered = response.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
            if entered || ui.button("Set").clicked() {
                match parse_speed(&self.speed_text) {
                    Ok(typed) => {
                        if self.set_velocity(index, typed, direction) {
                            self.info(format!("{name} now moves at {typed}c"));
                        }
                    }
                    Err(error) => self.error(error.to_string()),
                }
            }
        });
    }

    /// The direction of motion of object `index`, typed or from the presets.
    fn direction_controls(&mut self, ui: &mut egui::Ui, index: usize) {
        let speed = self.editor.speed(index);
        let mut direction = self.editor.direction(index);
        if vector_row(ui, "Direction", &mut direction, 0.01, Some(-1.0..=1.0)) {
            self.set_velocity(index, speed, direction);
        }
        ui.horizontal(|ui| {
            let (forward, right, _) = self.editor.scene().observer.basis();
            let presets = [
                ("towards me", -forward),
                ("away", forward),
                ("left to right", right),
                ("right to left", -right),
            ];
            for (label, preset) in presets {
                if ui.small_button(label).clicked() {
                    self.set_velocity(index, speed, preset);
                }
            }
        });
    }

    /// The wireframe switch and line width of object `index`.
    fn wireframe_controls(&mut self, ui: &mut egui::Ui, index: usize) {
        ui.horizontal(|ui| {
            let wireframe = self.editor.wireframe(index);
            let mut on = wireframe.is_some();
            let mut width = wireframe.unwrap_or(DEFAULT_WIREFRAME_WIDTH);
            let toggled = ui
                .checkbox(&mut on, "Wireframe")
                .on_hover_text("draw the triangle edges (Fig. 10 bottom)")
                .changed();
            let resized = on && {
                let label = ui.label("width");
                ui.add(
                    egui::DragValue::new(&mut width)
                        .speed(0.001)
                        .range(0.001..=1.0),
                )
                .labelled_by(label.id)
                .changed()
            };
            if toggled || resized {
                let result = self.editor.set_wireframe(index, on.then_some(width));
                self.edited(result);
            }
        });
    }

    fn effects_section(&mut self, ui: &mut egui::Ui) {
        let mut effects = self.editor.scene().effects;
        let labels = [
            (
                Effects::Geometry,
                "Geometry only",
                "aberration and light travel time; no colour change",
            ),
            (
                Effects::Doppler,
                "Doppler",
                "colours shift with the Doppler factor; brightness is normalised",
            ),
            (
                Effects::Searchlight,
                "Doppler + searchlight",
                "approaching objects also get brighter, receding ones darker",
            ),
        ];
        for (value, label, hover) in labels {
            ui.radio_value(&mut effects, value, label)
                .on_hover_text(hover);
        }
        if effects != self.editor.scene().effects {
            let result = self.editor.set_effects(effects);
            self.edited(result);
        }
        let mut tone = self.editor.tone_map_choice();
        let name = |t: Option<ToneMap>| match t {
            None => "automatic (the effect's own)",
            Some(ToneMap::Luminance) => "luminance (Fig. 6 left)",
            Some(ToneMap::Searchlight) => "searchlight (Fig. 6 right)",
        };
        egui::ComboBox::from_label("tone map")
            .selected_text(name(tone))
            .show_ui(ui, |ui| {
                for t in [None, Some(ToneMap::Luminance), Some(ToneMap::Searchlight)] {
                    ui.selectable_value(&mut tone, t, name(t));
                }
            });
        if tone != self.editor.tone_map_choice() {
            let result = self.editor.set_tone_map(tone);
            self.edited(result);
        }
        let mut colour = self.editor.scene().colour;
        ui.radio_value(&mut colour, SurfaceColour::Paper, "Paper's colour")
            .on_hover_text(
                "the paper's shortcut: the light's colour at D·T, scaled by the surface's \
                 grey value; red and blue surfaces shift alike",
            );
        ui.radio_value(&mut colour, SurfaceColour::Spectral, "Spectral colour")
            .on_hover_text(
                "every colour is a reflectance spectrum that really shifts: a red surface \
                 approaching turns orange, then yellow; what was infrared comes into view",
            );
        if colour != self.editor.scene().colour {
            let result = self.editor.set_colour(colour);
            self.edited(result);
        }
        let mut exposure = self.editor.scene().exposure;
        let slider = ui.add_enabled(
            colour == SurfaceColour::Spectral,
            egui::Slider::new(&mut exposure, 1e-3..=1e3)
                .logarithmic(true)
                .text("exposure"),
        );
        if slider.changed() {
            let result = self.editor.set_exposure(exposure);
            self.edited(result);
        }
    }

    fn time_section(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let label = if self.playing { "Pause" } else { "Play" };
            if ui.button(label).on_hover_text("Space").clicked() {
                self.playing = !self.playing;
            }
            if ui.button("ct = 0").clicked() {
                let result = self.editor.set_time(0.0);
                self.edited(result);
            }
        });
        let mut ct = self.editor.scene().observer.ct;
        let (lo, hi) = self.time_range;
        if ui
            .add(
                egui::Slider::new(&mut ct, lo..=hi)
                    .text("observation time ct")
                    // Shown to 2 decimals; `max_decimals` would also round the value itself
                    // every frame, so that playback advanced ct in steps of 0.01.
                    .custom_formatter(|value, _| format!("{value:.2}")),
            )
            .changed()
        {
            let result = self.editor.set_time(ct);
            self.edited(result);
        }
        ui.add(
            egui::Slider::new(&mut self.playback_speed, 0.05..=20.0)
                .logarithmic(true)
                .text("playback (ct per second)"),
        );
    }

    fn observer_section(&mut self, ui: &mut egui::Ui) {
        let observer = self.editor.scene().observer;
        let mut changed = observer;
        vector_row(ui, "Position", &mut changed.position, 0.05, None);
        ui.add(
            egui::Slider::new(&mut changed.fov_y_deg, 5.0..=120.0)
                .text("field of view (°)")
                .max_decimals(1),
        );
        if changed != observer {
            let result = self.editor.set_observer(changed);
            self.edited(result);
        }
        let mut beta = self.editor.observer_beta();
        if vector_row(ui, "Velocity (c)", &mut beta, 0.01, Some(-0.999..=0.999)) {
            let result = self.editor.set_observer_beta(beta);
            self.edited(result);
        }
        ui.label(
            RichText::new(format!(
                "|β| = {:.4}: the observer's velocity through the world; objects keep theirs",
                beta.length()
            ))
            .small(),
        );
        ui.add(
            egui::Slider::new(&mut self.fly_speed, 0.1..=100.0)
                .logarithmic(true)
                .text("flying speed (units/s)"),
        );
        ui.horizontal(|ui| {
            if ui.button("Reset view").on_hover_text("R").clicked() {
                let result = self.editor.reset_view();
                self.edited(result);
            }
            ui.label(
                RichText::new(
                    "W A S D fly, Q E down/up, drag to look, wheel zooms, Shift is faster",
                )
                .small(),
            );
        });
    }

    /// The probe's last finding (click the picture to probe a pixel).
    fn probe_section(&mut self, ui: &mut egui::Ui) {
        let Some(shown) = &self.probe else {
            ui.label(
                RichText::new(
                    "Click the picture: the probe tells what is there, computed exactly on the CPU.",
                )
                .small(),
            );
            return;
        };
        ui.label(
            RichText::new(format!(
                "pixel ({}, {}) of {}×{}, {}, at ct = {:.3}",
                shown.pixel.0,
                shown.pixel.1,
                shown.size.0,
                shown.size.1,
                view_label(shown.pane.view),
                shown.observer.ct
            ))
            .small(),
        );
        if shown.observer != self.editor.scene().observer {
            ui.label(
                RichText::new("(the picture has changed since: click it again to update)").small(),
            );
        }
        match &shown.found {
            None => {
                ui.label("the background: no object is seen here");
            }
            Some(found) => {
                for line in found.lines() {
                    ui.label(line);
                }
            }
        }
    }

    /// The engine: throttle, brake, proper acceleration, and the motion readouts.
    fn flight_section(&mut self, ui: &mut egui::Ui) {
        ui.add(
            egui::Slider::new(&mut self.acceleration, 0.01..=10.0)
                .logarithmic(true)
                .text("proper acceleration α (c per unit ct)"),
        );
        ui.horizontal_wrapped(|ui| {
            // Thrust lasts while the button is held, as with the keys.
            for (label, keys, throttle) in [
                ("Thrust", "hold PageUp or T", 1.0),
                ("Reverse", "hold PageDown or G", -1.0),
            ] {
                if ui
                    .button(label)
                    .on_hover_text(keys)
                    .is_pointer_button_down_on()
                {
                    self.engine_button = Some(Engine::Thrust(throttle));
                    ui.ctx().request_repaint();
                }
            }
            if ui.button("Brake to rest").on_hover_text("B").clicked() {
                self.engine_button = Some(Engine::Brake);
            }
            if self.flight.is_some() && ui.button("End flight").clicked() {
                self.flight = None;
                self.playing = false;
            }
        });
        let readout = MotionReadout::of(&self.editor);
        ui.label(format!(
            "|β| = {:.6}, γ = {:.4}",
            readout.speed, readout.gamma
        ));
        ui.label(format!(
            "Doppler factor ahead {:.4}, behind {:.4} (along your motion, for light from things \
             at rest in the world)",
            readout.doppler_ahead, readout.doppler_behind
        ));
        match &self.flight {
            Some(flight) => {
                let state = if flight.braking {
                    "braking"
                } else if self.playing {
                    "flying (coasting when no thrust is given)"
                } else {
                    "paused (Space)"
                };
                ui.label(format!(
                    "{state}: your clock τ = {:.3}, world clock ct = {:.3} since the start",
                    flight.proper_time,
                    flight.world_time(&self.editor)
                ));
            }
            None => {
                ui.label(
                    RichText::new(
                        "Hold PageUp / T to accelerate along your look direction, PageDown / G \
                         backwards, B to brake; the clock (playback speed) runs your proper time.",
                    )
                    .small(),
                );
            }
        }
    }

    /// The view on the left and, for a split screen, the one on the right.
    fn views_section(&mut self, ui: &mut egui::Ui) {
        let (mut left, mut right) = (self.left_view, self.right_view);
        egui::ComboBox::from_label("left (or only) view")
            .selected_text(view_label(left))
            .show_ui(ui, |ui| {
                for view in View::ALL {
                    ui.selectable_value(&mut left, view, view_label(view));
                }
            });
        egui::ComboBox::from_label("right view")
            .selected_text(right.map_or("none (one view)", view_label))
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut right, None, "none (one view)");
                for view in View::ALL {
                    ui.selectable_value(&mut right, Some(view), view_label(view));
                }
            });
        if (left, right) != (self.left_view, self.right_view) {
            self.set_views(left, right);
        }
        ui.label(
            RichText::new(
                "measured and Newtonian show everything at rest where it is now, as \
                 `srt render --view` does",
            )
            .small(),
        );
    }

    fn light_section(&mut self, ui: &mut egui::Ui) {
        let (mut temperature, mut position) = self.editor.light();
        let mut changed = ui
            .add(
                egui::Slider::new(&mut temperature, 1000.0..=40000.0)
                    .logarithmic(true)
                    .text("temperature (K)")
                    .max_decimals(0),
            )
            .changed();
        changed |= vector_row(ui, "Light position", &mut position, 0.1, None);
        if ui.button("Put the light at the camera").clicked() {
            position = self.editor.scene().observer.position;
            changed = true;
        }
        if changed {
            let result = self.editor.set_light(temperature, position);
            self.edited(result);
        }
    }

    fn method_section(&mut self, ui: &mut egui::Ui) {
        for method in ViewMethod::ALL {
            if ui
                .radio_value(&mut self.method, method, method.label())
                .changed()
            {
                self.needs_render = true;
            }
        }
        let name = |r: f32| match r {
            0.5 => "half",
            0.25 => "quarter",
            _ => "full",
        };
        let before = self.resolution;
        egui::ComboBox::from_label("resolution")
            .selected_text(name(self.resolution))
            .show_ui(ui, |ui| {
                for r in [1.0, 0.5, 0.25] {
                    ui.selectable_value(&mut self.resolution, r, name(r));
                }
            })
            .response
            .on_hover_text("render fewer pixels for speed on slow (software) adapters");
        #[expect(clippy::float_cmp, reason = "one of three exact values")]
        if self.resolution != before {
            self.needs_render = true;
        }
    }

    fn files_section(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            if ui.button("Open scene…").clicked() {
                self.start_dialog(Purpose::OpenScene);
            }
            if ui.button("Save scene as TOML…").clicked() {
                self.start_dialog(Purpose::SaveScene);
            }
            if ui.button("Save image as PNG…").clicked() {
                self.start_dialog(Purpose::SaveImage);
            }
        });
        self.recording_controls(ui);
        ui.horizontal(|ui| {
            let label = ui.label("Path:");
            ui.add(
                egui::TextEdit::singleline(&mut self.path_text)
                    .hint_text("a model, .toml, .png, .mp4 or .gif path")
                    .desired_width(220.0),
            )
            .labelled_by(label.id);
        });
        ui.horizontal_wrapped(|ui| {
            let path = PathBuf::from(self.path_text.trim());
            let empty = self.path_text.trim().is_empty();
            for (label, purpose) in [
                ("Add model", Purpose::AddModel),
                ("Open scene", Purpose::OpenScene),
                ("Save scene", Purpose::SaveScene),
                ("Save PNG", Purpose::SaveImage),
                ("Record", Purpose::Record),
            ] {
                if ui.add_enabled(!empty, egui::Button::new(label)).clicked() {
                    self.file_action(purpose, &path);
                }
            }
        });
        ui.label(
            RichText::new(format!(
                "or drop {} or .{SCENE_FILE_EXTENSION} files on the window",
                model_extension_list()
            ))
            .small(),
        );
    }

    /// Record / Stop and the frame rate.
    fn recording_controls(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            if let Some(recorder) = &self.recorder {
                let text = format!("Stop recording ({})", recorder.path().display());
                if ui
                    .button(RichText::new(text).color(Color32::from_rgb(240, 90, 80)))
                    .clicked()
                {
                    match self.stop_recording() {
                        Ok((path, frames)) => {
                            self.info(format!("recorded {frames} frames into {}", path.display()));
                        }
                        Err(error) => self.error(error),
                    }
                }
            } else {
                if ui.button("Record video…").clicked() {
                    self.start_dialog(Purpose::Record);
                }
                egui::ComboBox::from_label("frame rate")
                    .selected_text(format!("{} fps", self.record_fps))
                    .show_ui(ui, |ui| {
                        for fps in FRAME_RATES {
                            ui.selectable_value(&mut self.record_fps, fps, format!("{fps} fps"));
                        }
                    });
            }
        })
        .response
        .on_hover_text(
            "Every frame drawn while recording is one video frame, and time (playback, flight) \
             advances by exactly one frame period per frame: the video is smooth even where the \
             window draws slowly.",
        );
    }

    fn central(&mut self, ui: &mut egui::Ui) {
        let available = ui.available_size();
        let ppp = ui.ctx().pixels_per_point();
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "a window size in pixels"
        )]
        let size = (
            (available.x * ppp * self.resolution).round().max(1.0) as u32,
            (available.y * ppp * self.resolution).round().max(1.0) as u32,
        );
        let (rect, response) = ui.allocate_exact_size(available, Sense::click_and_drag());
        self.navigate(ui, &response);
        if self.needs_render || size != self.last_size {
            self.render(size);
        }
        let Some(gpu) = &self.gpu else {
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "no GPU adapter: nothing to show",
                egui::FontId::proportional(18.0),
                Color32::GRAY,
            );
            return;
        };
        // Each pane gets an equal share of the width (the textures may be smaller than the
        // rectangle when rendering at a reduced resolution: they are stretched).
        let textures: Vec<_> = gpu.view.textures().collect();
        #[expect(clippy::cast_precision_loss, reason = "a few panes")]
        let width = rect.width() / textures.len().max(1) as f32;
        let part = |index: usize| {
            #[expect(clippy::cast_precision_loss, reason = "a few panes")]
            let left = rect.left() + index as f32 * width;
            egui::Rect::from_min_size(
                egui::pos2(left, rect.top()),
                egui::vec2(width, rect.height()),
            )
        };
        for (index, (id, _)) in textures.iter().enumerate() {
            let part = part(index);
            egui::Image::new(egui::load::SizedTexture::new(*id, part.size())).paint_at(ui, part);
            if let Some(label) = Pane::label(&self.panes, index) {
                ui.painter().text(
                    part.left_top() + egui::vec2(8.0, 6.0),
                    egui::Align2::LEFT_TOP,
                    label,
                    egui::FontId::proportional(14.0),
                    Color32::WHITE,
                );
            }
        }
        // A click (not a drag) probes the pixel under the pointer.
        let clicked = response
            .clicked()
            .then(|| response.interact_pointer_pos())
            .flatten();
        if let Some(position) = clicked
            && let Some(index) = (0..textures.len()).find(|&i| part(i).contains(position))
        {
            let part = part(index);
            let at = (position - part.left_top()) / part.size();
            let [w, h] = textures[index].1;
            self.probe_at(index, at, (w, h));
        }
        if let Some(shown) = &self.probe
            && shown.observer == self.editor.scene().observer
            && let Some(index) = self.panes.iter().position(|p| *p == shown.pane)
            && index < textures.len()
        {
            let part = part(index);
            let centre = part.left_top() + shown.at * part.size();
            let stroke = egui::Stroke::new(1.5, Color32::from_rgb(255, 220, 0));
            ui.painter().circle_stroke(centre, 6.0, stroke);
        }
    }

    /// Mouse: drag turns the camera, the wheel zooms (field of view).
    fn navigate(&mut self, ui: &egui::Ui, response: &egui::Response) {
        let drag = response.drag_delta();
        if response.dragged() && drag != egui::Vec2::ZERO {
            let observer = camera::turn(
                &self.editor.scene().observer,
                -f64::from(drag.x) * TURN_PER_POINT,
                -f64::from(drag.y) * TURN_PER_POINT,
            );
            let result = self.editor.set_observer(observer);
            self.edited(result);
        }
        if response.hovered() {
            let scroll = f64::from(ui.input(|i| i.smooth_scroll_delta.y));
            if scroll != 0.0 {
                let observer = self.editor.scene().observer;
                let fov = (observer.fov_y_deg * (-scroll * 0.002).exp()).clamp(5.0, 120.0);
                let result = self.editor.set_observer(Observer {
                    fov_y_deg: fov,
                    ..observer
                });
                self.edited(result);
            }
        }
    }

    /// Renders the scene at `size` pixels (all views together).
    fn render(&mut self, size: (u32, u32)) {
        self.last_size = size;
        self.needs_render = false;
        self.panes = Pane::row(&self.views(), self.method);
        let Some(gpu) = &mut self.gpu else { return };
        let scene = self.editor.scene();
        let version = self.editor.structure_version();
        // Each view's scene once (the seen one is the editor's own), with the key of its meshes.
        let mut viewed: Vec<(View, Cow<'_, Scene>, UploadKey)> = Vec::new();
        for pane in &self.panes {
            if viewed.iter().all(|(view, _, _)| *view != pane.view) {
                match view_scene(pane.view, scene) {
                    Ok(picture) => {
                        let key = UploadKey::new(pane.view, scene, version);
                        viewed.push((pane.view, picture, key));
                    }
                    Err(error) => {
                        self.status = Status {
                            level: Level::Error,
                            text: error,
                        };
                        return;
                    }
                }
            }
        }
        let panes: Vec<PaneScene<'_>> = self
            .panes
            .iter()
            .filter_map(|pane| {
                let (_, picture, key) = viewed.iter().find(|(view, _, _)| *view == pane.view)?;
                Some(PaneScene {
                    scene: picture.as_ref(),
                    key,
                    method: pane.method,
                })
            })
            .collect();
        let start = Instant::now();
        let mut egui = gpu.egui.as_ref().map(|r| r.write());
        let result = gpu
            .view
            .render(&gpu.ctx, egui.as_deref_mut(), &panes, size)
            // Waiting for the frame keeps slow (software) adapters from queueing frames behind
            // the user's input, and measures what a frame costs.
            .and_then(|()| gpu.ctx.wait());
        drop(egui);
        drop(panes);
        drop(viewed);
        match result {
            Ok(()) => {
                let now = Instant::now();
                let ms = now.duration_since(start).as_secs_f64() * 1e3;
                self.frame_ms = if self.frame_ms > 0.0 {
                    0.8 * self.frame_ms + 0.2 * ms
                } else {
                    ms
                };
                if self.playing && ms > SLOW_FRAME_MS {
                    self.playing = false;
                    self.warn(format!(
                        "paused: that frame took {:.1} s to render. Local ray tracing gets slow when an \
                         object passes close to or behind the camera (its triangles then cover the \
                         whole screen); try the polygon method or a lower resolution",
                        ms / 1e3
                    ));
                }
                self.rendered.push_back(now);
                while self
                    .rendered
                    .front()
                    .is_some_and(|t| now.duration_since(*t) > Duration::from_secs(1))
                {
                    self.rendered.pop_front();
                }
                self.gpu_failed = false;
                if let Some(last) = self.stats
                    && now.duration_since(last) >= Duration::from_secs(1)
                {
                    self.stats = Some(now);
                    eprintln!(
                        "srt view: {:.1} frames/s, {ms:.0} ms to render the last frame ({}x{} px, {})",
                        self.frames_per_second(),
                        size.0,
                        size.1,
                        self.method.label()
                    );
                }
            }
            Err(error) => {
                if !self.gpu_failed {
                    eprintln!("srt view: rendering failed: {error}");
                    self.error(format!("rendering failed: {error}"));
                }
                self.gpu_failed = true;
            }
        }
    }
}

/// `scene` as `view` shows it (borrowed for the seen view), or the message why it cannot be.
fn view_scene(view: View, scene: &Scene) -> Result<Cow<'_, Scene>, String> {
    match view {
        View::Seen => Ok(Cow::Borrowed(scene)),
        _ => view
            .apply(scene)
            .map(Cow::Owned)
            .map_err(|error| format!("the {} view cannot be drawn: {error}", view.name())),
    }
}

/// A row `label x [..] y [..] z [..]` editing `value`; whether it changed.
fn vector_row(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut DVec3,
    speed: f64,
    range: Option<RangeInclusive<f64>>,
) -> bool {
    ui.horizontal(|ui| {
        let row = ui.label(label);
        let mut changed = false;
        for (axis, c) in [
            ("x", &mut value.x),
            ("y", &mut value.y),
            ("z", &mut value.z),
        ] {
            let axis = ui.label(axis);
            let mut drag = egui::DragValue::new(c).speed(speed).max_decimals(3);
            if let Some(range) = range.clone() {
                drag = drag.range(range);
            }
            changed |= ui
                .add(drag)
                .labelled_by(row.id)
                .labelled_by(axis.id)
                .changed();
        }
        changed
    })
    .inner
}

/// γ and the range of Doppler factors of an object moving in `frame`: from light it sends
/// straight backwards (seen receding) to light it sends straight ahead (seen approaching).
fn motion_readout(frame: &Frame) -> String {
    let beta = frame.beta();
    let ahead = beta.try_normalize().unwrap_or(DVec3::X);
    format!(
        "γ = {:.3}; Doppler factor from {:.3} (receding) to {:.3} (approaching)",
        frame.gamma(),
        doppler_factor(beta, -ahead),
        doppler_factor(beta, ahead)
    )
}

/// A speed for the typed-speed field: at most six decimals, without trailing zeros.
fn format_speed(speed: f64) -> String {
    let text = format!("{speed:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

fn intro(editor: &Editor) -> String {
    let count = editor.object_count();
    format!(
        "{}: {count} object{}. Pick one on the left and change its speed; W A S D Q E and mouse \
         drag fly, PageUp accelerates you, B brakes; click the picture to probe it; drop a 3D \
         model on the window to add it.",
        editor.scene().name,
        if count == 1 { "" } else { "s" },
    )
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speeds_are_shown_with_at_most_six_decimals() {
        assert_eq!(format_speed(0.950_013_99), "0.950014");
        assert_eq!(format_speed(0.9), "0.9");
        assert_eq!(format_speed(0.0), "0");
    }

    #[test]
    fn the_readout_gives_gamma_and_the_doppler_range_of_the_motion() {
        let frame = |beta| Frame::new(beta, DVec3::ONE).unwrap();
        assert_eq!(
            motion_readout(&frame(DVec3::new(0.0, -0.6, 0.0))),
            "γ = 1.250; Doppler factor from 0.500 (receding) to 2.000 (approaching)"
        );
        assert_eq!(
            motion_readout(&frame(DVec3::ZERO)),
            "γ = 1.000; Doppler factor from 1.000 (receding) to 1.000 (approaching)"
        );
    }
}
