//! The lights section: the lamp the observer carries (temperature, position, strength) and the
//! moving lights, listed like objects and edited like them (speed, direction, position at
//! t = 0, temperature, strength), with their late shadows on or off.

use eframe::egui::{self, RichText};
use glam::DVec3;
use srt_scene::LightDescription;

use super::{ViewerApp, panel::vector_row};
use crate::edit::MAX_SLIDER_SPEED;

impl ViewerApp {
    /// The lamp's controls, the moving lights' list, Add and Remove, the selected light's
    /// controls and the shadows switch.
    pub(super) fn lights_section(&mut self, ui: &mut egui::Ui) {
        self.lamp_controls(ui);
        ui.separator();
        let lights = self.editor.moving_lights();
        if self.selected_light.is_some_and(|i| i >= lights.len()) {
            self.selected_light = lights.len().checked_sub(1);
        }
        ui.label(RichText::new("Moving lights").strong());
        for (index, light) in lights.iter().enumerate() {
            let text = format!(
                "light {} — {:.3}c, {:.0} K, strength {:.3}",
                index + 1,
                DVec3::from_array(light.beta).length(),
                light.temperature_k,
                light.strength
            );
            ui.selectable_value(&mut self.selected_light, Some(index), text);
        }
        if lights.is_empty() {
            ui.label("None: add one to see its light arrive late and its shadows.");
        }
        ui.horizontal(|ui| {
            if ui.button("Add light").clicked() {
                match self.editor.add_moving_light() {
                    Ok(index) => {
                        self.selected_light = Some(index);
                        self.needs_render = true;
                    }
                    Err(error) => self.error(error.to_string()),
                }
            }
            if let Some(index) = self.selected_light
                && ui.button("Remove light").clicked()
            {
                let result = self.editor.remove_moving_light(index);
                self.edited(result);
            }
        });
        let mut shadows = self.editor.shadows();
        if ui
            .checkbox(&mut shadows, "Shadows (arriving late)")
            .on_hover_text("objects block the moving lights' light where it passed them")
            .changed()
        {
            let result = self.editor.set_shadows(shadows);
            self.edited(result);
        }
        if let Some(index) = self.selected_light.filter(|&i| i < lights.len()) {
            ui.separator();
            self.moving_light_controls(ui, index, lights[index].clone());
        }
    }

    /// The lamp's temperature, position and strength.
    fn lamp_controls(&mut self, ui: &mut egui::Ui) {
        ui.label(RichText::new("Lamp (carried by the observer)").strong());
        let (mut temperature, mut position) = self.editor.light();
        let mut changed = temperature_slider(ui, &mut temperature);
        changed |= vector_row(ui, "Lamp position", &mut position, 0.1, None);
        if ui.button("Put the lamp at the camera").clicked() {
            position = self.editor.scene().observer.position;
            changed = true;
        }
        if changed {
            let result = self.editor.set_light(temperature, position);
            self.edited(result);
        }
        let mut strength = self.editor.lamp_strength();
        if ui
            .add(egui::Slider::new(&mut strength, 0.0..=2.0).text("lamp strength"))
            .on_hover_text("0 turns the lamp off, its ambient light included")
            .changed()
        {
            let result = self.editor.set_lamp_strength(strength);
            self.edited(result);
        }
    }

    /// The controls of moving light `index`, now `light`.
    fn moving_light_controls(&mut self, ui: &mut egui::Ui, index: usize, light: LightDescription) {
        ui.label(RichText::new(format!("light {}", index + 1)).strong());
        let beta = DVec3::from_array(light.beta);
        let mut speed = beta.length();
        let mut direction = beta.try_normalize().unwrap_or(DVec3::X);
        let mut position = DVec3::from_array(light.position);
        let (mut temperature, mut strength) = (light.temperature_k, light.strength);
        let mut changed = ui
            .add(
                egui::Slider::new(&mut speed, 0.0..=MAX_SLIDER_SPEED)
                    .text("speed (c)")
                    .clamping(egui::SliderClamping::Always)
                    .max_decimals(4),
            )
            .changed();
        changed |= vector_row(ui, "Direction", &mut direction, 0.01, Some(-1.0..=1.0));
        changed |= vector_row(ui, "Position at t = 0", &mut position, 0.1, None);
        changed |= temperature_slider(ui, &mut temperature);
        changed |= ui
            .add(
                egui::Slider::new(&mut strength, 0.0..=400.0)
                    .logarithmic(true)
                    .text("strength"),
            )
            .on_hover_text("a surface facing it at distance r (in its frame) gets strength/r² of the lamp's diffuse light")
            .changed();
        if changed {
            let Some(unit) = direction.try_normalize() else {
                self.error("the direction of motion must be a non-zero vector".to_owned());
                return;
            };
            let edited = LightDescription {
                position: position.to_array(),
                temperature_k: temperature,
                strength,
                beta: (speed * unit).to_array(),
                carried: false,
            };
            let result = self.editor.set_moving_light(index, edited);
            self.edited(result);
        }
    }
}

/// A temperature slider from 1000 K to 40 000 K; whether it changed.
fn temperature_slider(ui: &mut egui::Ui, temperature: &mut f64) -> bool {
    ui.add(
        egui::Slider::new(temperature, 1000.0..=40000.0)
            .logarithmic(true)
            .text("temperature (K)")
            .max_decimals(0),
    )
    .changed()
}
