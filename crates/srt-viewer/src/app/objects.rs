//! The object list and the selected object's controls: speed (slider and typed), direction
//! of motion, offset, wireframe, and spin or thrust in the object's own frame.

use eframe::egui::{self, Key, RichText};
use glam::DVec3;
use srt_physics::{Frame, doppler_factor};
use srt_scene::description::{SpinDescription, ThrustDescription};
use srt_scene::resolve::model_extension_list;

use super::{DEFAULT_WIREFRAME_WIDTH, Purpose, ViewerApp, panel::vector_row};
use crate::edit::MAX_SLIDER_SPEED;
use srt_scene::edit::parse_speed;

impl ViewerApp {
    /// The object list, Add model and Remove, and the selected object's controls.
    pub(super) fn objects_section(&mut self, ui: &mut egui::Ui) {
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

    /// The controls of object `index`: speed, direction, offset and wireframe.
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
        self.motion_controls(ui, index);
    }

    /// Spin and thrust of object `index` in its own frame (the CPU renderer draws them).
    fn motion_controls(&mut self, ui: &mut egui::Ui, index: usize) {
        let spin = self.editor.spin(index);
        let mut spinning = spin.is_some();
        let mut spin = spin.unwrap_or(SpinDescription {
            axis: [0.0, 0.0, 1.0],
            rate: 0.2,
            centre: [0.0; 3],
        });
        let mut changed = ui
            .checkbox(&mut spinning, "Spin in its own frame")
            .on_hover_text("kinematic rotation about an axis; every point stays below c")
            .changed();
        if spinning {
            let mut axis = DVec3::from_array(spin.axis);
            let mut centre = DVec3::from_array(spin.centre);
            changed |= vector_row(ui, "Axis", &mut axis, 0.01, Some(-1.0..=1.0));
            changed |= vector_row(ui, "Centre", &mut centre, 0.05, None);
            changed |= ui
                .add(egui::Slider::new(&mut spin.rate, -2.0..=2.0).text("rate (rad per ct′)"))
                .changed();
            spin.axis = axis.to_array();
            spin.centre = centre.to_array();
        }
        if changed {
            let result = self.editor.set_spin(index, spinning.then_some(spin));
            self.edited(result);
        }
        let thrust = self.editor.thrust(index);
        let mut thrusting = thrust.is_some();
        let mut thrust = thrust.unwrap_or(ThrustDescription {
            proper_acceleration: [0.0, 0.1, 0.0],
            start: 0.0,
            duration: f64::INFINITY,
        });
        let mut changed = ui
            .checkbox(&mut thrusting, "Thrust in its own frame")
            .on_hover_text("Born-rigid acceleration from rest, then coasting")
            .changed();
        if thrusting {
            let mut acceleration = DVec3::from_array(thrust.proper_acceleration);
            changed |= vector_row(ui, "Proper acceleration", &mut acceleration, 0.005, None);
            thrust.proper_acceleration = acceleration.to_array();
            changed |= ui
                .add(egui::Slider::new(&mut thrust.start, -50.0..=50.0).text("start (ct′)"))
                .changed();
            let mut endless = thrust.duration.is_infinite();
            changed |= ui.checkbox(&mut endless, "for ever").changed();
            if endless {
                thrust.duration = f64::INFINITY;
            } else {
                if thrust.duration.is_infinite() {
                    thrust.duration = 10.0;
                }
                changed |= ui
                    .add(
                        egui::Slider::new(&mut thrust.duration, 0.0..=100.0)
                            .text("duration (proper)"),
                    )
                    .changed();
            }
        }
        if changed {
            let result = self.editor.set_thrust(index, thrusting.then_some(thrust));
            self.edited(result);
        }
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
