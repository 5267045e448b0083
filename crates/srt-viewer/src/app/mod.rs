//! The window's contents: the side panel, the status line and the rendered view, with the
//! keyboard and mouse controls. [`ViewerApp::show`] draws everything into any [`egui::Ui`], so
//! the same code runs in the real window (through [`eframe::App`]) and in headless tests.
//!
//! The viewer's state and its public operations live here; its parts, each an `impl ViewerApp`
//! block of its own: `picture` (rendering the panes, mouse navigation, the probe), `observer`
//! (time, the camera and the flight: keys and their panel sections), `objects` (the object list
//! and each object's controls), `panel` (the side panel's layout, readouts and the sections on
//! how the scene is drawn), `files` (opening, saving, file dialogs, recording) and `stats` (where
//! a frame's time goes, `SRT_VIEW_STATS=1`).

use std::collections::VecDeque;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::Receiver;
use std::time::{Duration, Instant};

use eframe::egui::{self};
use eframe::egui_wgpu;
use srt_gpu::GpuContext;
use srt_scene::{Observer, View};

use crate::camera::{self};
use crate::exact_path::{DrawnBy, ExactPath};
use crate::pilot::{DEFAULT_ACCELERATION, Engine, Flight};
use crate::probe::Probe;
use crate::record::{FRAME_RATES, Recorder};
use crate::view::{Pane, SceneView, ViewMethod};
use srt_scene::{EditError, Editor};

mod files;
mod lights;
mod objects;
mod observer;
mod panel;
mod picture;
mod stats;

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
    /// The moving light whose controls are shown.
    selected_light: Option<usize>,
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
    /// Where the frames' time goes, printed to stderr once a second (`SRT_VIEW_STATS=1`).
    stats: Option<stats::FrameStats>,
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
        let ct = observer.time;
        Self {
            selected: (editor.object_count() > 0).then_some(0),
            selected_light: None,
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
            stats: std::env::var_os("SRT_VIEW_STATS").map(|_| stats::FrameStats::default()),
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

    /// Who draws the exact panes ([`ExactPath`]) from the next frame on; nothing without a GPU
    /// (there is no pane to draw into).
    pub fn set_exact_path(&mut self, path: ExactPath) {
        if let Some(gpu) = &mut self.gpu {
            gpu.view.set_exact_path(path);
            self.needs_render = true;
        }
    }

    /// Who draws the exact panes.
    #[must_use]
    pub fn exact_path(&self) -> ExactPath {
        self.gpu
            .as_ref()
            .map_or(ExactPath::default(), |gpu| gpu.view.exact_path())
    }

    /// Where the viewer weighs the CPU tracer against a software adapter: the path that drew
    /// the first exact pane's last frame and both paths' frame times in seconds where known
    /// ([`SceneView::exact_report`](crate::view::SceneView::exact_report)).
    #[must_use]
    pub fn exact_report(&self) -> Option<(DrawnBy, Option<f64>, Option<f64>)> {
        self.gpu.as_ref()?.view.exact_report()
    }

    /// The flight in progress, if any.
    #[must_use]
    pub const fn flight(&self) -> Option<&Flight> {
        self.flight.as_ref()
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

    /// Takes the GPU errors (wgpu validation, out of memory…) reported since the last call.
    ///
    /// # Errors
    /// A message listing them, if there were any.
    pub fn take_gpu_errors(&self) -> Result<(), String> {
        self.gpu.as_ref().map_or(Ok(()), |gpu| {
            gpu.ctx.take_errors().map_err(|e| e.to_string())
        })
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

    /// Shows `text` in the status line as news.
    fn info(&mut self, text: String) {
        self.status = Status {
            level: Level::Info,
            text,
        };
    }

    /// Shows `text` in the status line as a warning.
    fn warn(&mut self, text: String) {
        self.status = Status {
            level: Level::Warning,
            text,
        };
    }

    /// Shows `text` in the status line as a refusal.
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

    /// Draws the whole viewer into `ui` and handles its input.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        if let Some(stats) = &mut self.stats {
            stats.start(Instant::now());
        }
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
            let ct = self.editor.time() + self.playback_speed * dt;
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
        if let Some(split) = self.stats.as_mut().and_then(|s| s.end(Instant::now())) {
            eprintln!("{}", split.line(self.last_size, self.method.label()));
        }
    }
}

/// The status line's first message: the scene, its objects and how to start.
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
