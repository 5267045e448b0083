//! Files: opening models and scenes (dialog, path field, dropped files), saving the scene and
//! the image, and recording video.

use std::path::{Path, PathBuf};
use std::sync::mpsc::TryRecvError;
use std::time::Duration;

use eframe::egui::{self, Color32, RichText};
use srt_scene::ResolveError;
use srt_scene::import::SUPPORTED_EXTENSIONS;
use srt_scene::resolve::{PathKind, SCENE_FILE_EXTENSION, model_extension_list, path_kind};

use super::{Level, Purpose, ViewerApp};
use crate::record::{FRAME_RATES, Recorder};
use srt_scene::{EditError, Editor};

impl ViewerApp {
    /// Opens dropped or chosen files one by one (models are added; a `.toml` replaces the
    /// scene); every refusal is reported in the status line and leaves the scene as it was.
    pub fn open_files(&mut self, paths: &[PathBuf]) {
        for path in paths {
            self.open_file(path);
        }
    }

    /// Opens one file: a model is added in front of the camera, a scene file replaces the scene.
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
    pub(super) fn finish_structure_change(
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

    /// Uploads the editor's scene to the GPU (nothing without a GPU).
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

    /// Takes the path chosen in the file dialog, if it has closed, and acts on it.
    pub(super) fn poll_dialog(&mut self, ctx: &egui::Context) {
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

    /// Does what `purpose` asks with `path`; the outcome goes to the status line.
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

    /// Opens a file dialog for `purpose` on its own thread ([`Self::poll_dialog`] takes its
    /// answer).
    pub(super) fn start_dialog(&mut self, purpose: Purpose) {
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

    /// Opens the files dropped on the window.
    pub(super) fn handle_drops(&mut self, ctx: &egui::Context) {
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
    pub(super) fn record_frame(&mut self) {
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

    /// The panel's file buttons, recording controls and path field.
    pub(super) fn files_section(&mut self, ui: &mut egui::Ui) {
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
}
