//! The picture: rendering every pane on the GPU, painting it, turning and zooming the camera
//! with the mouse, and probing a clicked pixel with the CPU reference tracer.

use std::borrow::Cow;
use std::time::{Duration, Instant};

use eframe::egui::{self, Color32, Sense};
use srt_scene::{Observer, Scene, UploadKey, View};

use super::{Level, ProbeShown, SLOW_FRAME_MS, Status, TURN_PER_POINT, ViewerApp};
use crate::camera;
use crate::probe::{Probe, probe};
use crate::view::{Pane, PaneScene};

impl ViewerApp {
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

    /// The picture: renders it when needed, paints each pane and marks the probed pixel.
    pub(super) fn central(&mut self, ui: &mut egui::Ui) {
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
                if let Some(stats) = &mut self.stats {
                    stats.rendered(now.duration_since(start));
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
