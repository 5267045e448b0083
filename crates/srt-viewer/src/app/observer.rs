//! Time and the observer's motion: playback, the camera flown with the keys, the relativistic
//! flight under thrust, and their panel sections.

use eframe::egui::{self, Key, RichText};

use srt_scene::Projection;

use super::{ViewerApp, panel::vector_row};
use crate::camera::{self, Movement};
use crate::pilot::{Engine, Flight, MotionReadout};

impl ViewerApp {
    /// Centres the time slider's range on the observation time of a newly opened scene.
    pub(super) fn reset_time_range(&mut self) {
        let ct = self.editor.time();
        self.time_range = (ct.min(0.0) - 20.0, ct.max(0.0) + 20.0);
    }

    /// Widens the time slider's range to include `ct`.
    pub(super) fn extend_time_range(&mut self, ct: f64) {
        self.time_range.0 = self.time_range.0.min(ct);
        self.time_range.1 = self.time_range.1.max(ct);
    }

    /// One frame of flight: `engine` (from keys or buttons) starts a flight if none is in
    /// progress (and starts the clock); while the clock runs, the observer flies `dt` seconds
    /// times the playback speed of proper time.
    pub(super) fn fly(&mut self, engine: Option<Engine>, dt: f64) {
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

    /// Keyboard: W A S D Q E fly the camera, R resets it, Space plays or pauses, PageUp/T and
    /// PageDown/G thrust, B brakes.
    pub(super) fn handle_keys(&mut self, ctx: &egui::Context, dt: f64) {
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

    /// Play and pause, the time slider (the observer's clock, [`srt_scene::Editor::time`]) and the
    /// playback speed.
    pub(super) fn time_section(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let label = if self.playing { "Pause" } else { "Play" };
            if ui.button(label).on_hover_text("Space").clicked() {
                self.playing = !self.playing;
            }
            if ui.button("time = 0").clicked() {
                let result = self.editor.set_time(0.0);
                self.edited(result);
            }
        });
        let mut ct = self.editor.time();
        let (lo, hi) = self.time_range;
        if ui
            .add(
                egui::Slider::new(&mut ct, lo..=hi)
                    .text("time (the observer's clock)")
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
                .text("playback (time per second)"),
        );
    }

    /// The camera's position and field of view, the observer's velocity and the flying speed.
    pub(super) fn observer_section(&mut self, ui: &mut egui::Ui) {
        let observer = self.editor.scene().observer;
        let mut changed = observer;
        vector_row(ui, "Position", &mut changed.position, 0.05, None);
        ui.add(
            egui::Slider::new(&mut changed.fov_y_deg, 5.0..=120.0)
                .text("field of view (°)")
                .max_decimals(1),
        );
        // The picture's projection: the pinhole, the whole sky (drag to look around in it) or
        // a planetarium's dome; the GPU's ray tracer draws the wide ones (auto does).
        let shown = if Projection::ALL.contains(&changed.projection) {
            changed.projection.label().to_owned()
        } else {
            changed.projection.to_string()
        };
        egui::ComboBox::from_label("projection")
            .selected_text(shown)
            .show_ui(ui, |ui| {
                for projection in Projection::ALL {
                    ui.selectable_value(&mut changed.projection, projection, projection.label());
                }
            });
        if changed.projection != observer.projection {
            // A stereo pair does not fit a dome, nor a new layout: one picture.
            changed.stereo = None;
        }
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

    /// The engine: throttle, brake, proper acceleration, and the motion readouts.
    pub(super) fn flight_section(&mut self, ui: &mut egui::Ui) {
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
}
