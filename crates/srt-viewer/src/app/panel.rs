//! The side panel's layout, the readouts and status line, and the sections on how the scene
//! is drawn (effects and colour, views, method, the probe's finding); app::lights has the lights.

use std::ops::RangeInclusive;

use eframe::egui::{self, Color32, RichText};
use glam::DVec3;
use srt_color::ToneMap;
use srt_scene::{Effects, SurfaceColour, View};

use super::{Level, ViewerApp};
use crate::exact_path::{DrawnBy, ExactPath};
use crate::view::{ViewMethod, view_label};

impl ViewerApp {
    /// The status line: the message's first line (all of it on hover).
    pub(super) fn status_line(&mut self, ui: &mut egui::Ui) {
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

    /// The side panel: readouts, then one collapsible section per subject.
    pub(super) fn side_panel(&mut self, ui: &mut egui::Ui) {
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
        egui::CollapsingHeader::new("Lights")
            .default_open(false)
            .show(ui, |ui| self.lights_section(ui));
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

    /// Frames per second, triangles, picture size, frame time and the adapter.
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
        if let Some((path, gpu, cpu)) = self.exact_report() {
            let ms = |seconds: Option<f64>| {
                seconds.map_or_else(
                    || "not yet timed".to_owned(),
                    |s| format!("{:.0} ms", s * 1e3),
                )
            };
            let by = match path {
                DrawnBy::Gpu => "the GPU",
                DrawnBy::Cpu => "the CPU tracer",
            };
            ui.label(format!(
                "exact picture drawn by {by} (a frame: GPU {}, CPU {})",
                ms(gpu),
                ms(cpu)
            ));
        }
        ui.label(RichText::new(format!("GPU: {}", self.adapter())).small());
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
                "pixel ({}, {}) of {}×{}, {}, at time {:.3}",
                shown.pixel.0,
                shown.pixel.1,
                shown.size.0,
                shown.size.1,
                view_label(shown.pane.view),
                shown.observer.time
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

    /// The effect mode, the tone map, paper's or spectral colour and the exposure.
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

    /// The rendering method and the resolution.
    fn method_section(&mut self, ui: &mut egui::Ui) {
        for method in ViewMethod::ALL {
            if ui
                .radio_value(&mut self.method, method, method.label())
                .changed()
            {
                self.needs_render = true;
            }
        }
        if self.gpu.is_some() {
            let before = self.exact_path();
            let mut chosen = before;
            egui::ComboBox::from_label("exact picture drawn by")
                .selected_text(chosen.label())
                .show_ui(ui, |ui| {
                    for path in ExactPath::ALL {
                        ui.selectable_value(&mut chosen, path, path.label());
                    }
                })
                .response
                .on_hover_text(
                    "on a software adapter (lavapipe, llvmpipe) srt's CPU tracer can draw a frame \
                     sooner than the adapter: \"the faster\" times both and draws by the faster",
                );
            if chosen != before {
                self.set_exact_path(chosen);
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
}

/// A row `label x [..] y [..] z [..]` editing `value`; whether it changed.
pub(super) fn vector_row(
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
