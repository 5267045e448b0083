//! Relativistic flight in the viewer, without UI or GPU: the throttle accelerates the observer
//! with a chosen proper acceleration along its look direction, releasing it coasts, braking
//! brings it to rest relative to the world frame W. The worldline is integrated exactly by
//! [`srt_physics::flight::Worldline`] (rapidity linear in proper time along a fixed direction,
//! boosts composed as matrices otherwise); every frame is then drawn in the observer's
//! instantaneous rest frame by setting its event and velocity ([`Editor::set_observer_motion`]).
//!
//! The camera's look direction is kept in the rest frame S of
//! [`srt_physics::MovingObserver`] (axes parallel to W's as the observer sees them), not
//! carried along as a gyroscope would be: after a turn at relativistic speed the two differ by
//! the Thomas precession, which the viewer does not show.

use glam::DVec3;
use srt_physics::FrameError;
use srt_physics::flight::Worldline;

use srt_scene::{EditError, Editor};

/// The default proper acceleration α, in units of c per unit of ct (c²/length with c = 1):
/// from rest, 0.9c (rapidity 1.47) after 2.9 units of proper time.
pub const DEFAULT_ACCELERATION: f64 = 0.5;

/// The fastest the engine takes the observer, as a fraction of c (γ ≈ 70.7): beyond it the
/// engine cuts off, so that the GPU's f32 arithmetic still resolves 1 − |β|.
pub const MAX_FLIGHT_SPEED: f64 = 0.9999;

/// What the engine does during a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Engine {
    /// Thrust along the look direction, scaled by the throttle in [−1, 1] (−1: backwards).
    Thrust(f64),
    /// No thrust: constant velocity.
    Coast,
    /// Decelerate against the motion through W until at rest.
    Brake,
}

/// A flight in progress: the world time it started at and the proper time flown since.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// World time ct (in W) when the flight started.
    pub started_ct: f64,
    /// Proper time cτ on the observer's clock since the flight started.
    pub proper_time: f64,
    /// Whether the observer is braking to rest (until it is at rest, or thrust is given).
    pub braking: bool,
}

impl Flight {
    /// A flight starting now, at the editor's observation time.
    #[must_use]
    pub fn start(editor: &Editor) -> Self {
        Self {
            started_ct: editor.observer_event().ct,
            proper_time: 0.0,
            braking: false,
        }
    }

    /// World time ct elapsed since the flight started.
    #[must_use]
    pub fn world_time(&self, editor: &Editor) -> f64 {
        editor.observer_event().ct - self.started_ct
    }

    /// Flies `dtau` of proper time with `engine` at proper acceleration `alpha` (1/length),
    /// starting from the editor's observer (so camera moves and velocity edits in between are
    /// respected) and leaving it at the new event with the new velocity. Thrust cancels
    /// braking; braking lasts until rest.
    ///
    /// # Errors
    /// [`EditError::Scene`] when the scene's rules refuse the new observer (the flight left the
    /// scene's bounds); the observer is then unchanged.
    pub fn step(
        &mut self,
        editor: &mut Editor,
        engine: Engine,
        alpha: f64,
        dtau: f64,
    ) -> Result<(), EditError> {
        let start = worldline(editor).map_err(|error| edit_error(editor, error))?;
        let direction = editor
            .scene()
            .observer
            .direction
            .try_normalize()
            .unwrap_or(DVec3::Y);
        let engine = match engine {
            Engine::Thrust(throttle) if throttle != 0.0 => {
                self.braking = false;
                Engine::Thrust(throttle.clamp(-1.0, 1.0))
            }
            Engine::Brake => {
                self.braking = true;
                Engine::Brake
            }
            _ if self.braking => Engine::Brake,
            _ => Engine::Coast,
        };
        let end = match engine {
            Engine::Thrust(throttle) => start.advance(throttle * alpha * direction, dtau),
            Engine::Coast => start.advance(DVec3::ZERO, dtau),
            Engine::Brake => {
                let (end, at_rest) = start.brake(alpha, dtau);
                self.braking = !at_rest;
                end
            }
        };
        let end = end.with_rapidity_at_most(MAX_FLIGHT_SPEED.atanh());
        editor.set_observer_motion(end.event, end.beta())?;
        if dtau.is_finite() && dtau > 0.0 {
            self.proper_time += dtau;
        }
        Ok(())
    }
}

/// What the panel shows about the observer's motion through W.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionReadout {
    /// Speed |β| through W.
    pub speed: f64,
    /// Lorentz factor γ.
    pub gamma: f64,
    /// Doppler factor of light from sources at rest in W straight ahead, √((1+β)/(1−β)).
    pub doppler_ahead: f64,
    /// The same straight behind, √((1−β)/(1+β)).
    pub doppler_behind: f64,
}

impl MotionReadout {
    /// The readout of the editor's observer (at rest when its velocity cannot be read).
    #[must_use]
    pub fn of(editor: &Editor) -> Self {
        let line = worldline(editor).unwrap_or(Worldline {
            event: editor.observer_event(),
            four_velocity: glam::DVec4::X,
            proper_time: 0.0,
        });
        let (doppler_ahead, doppler_behind) = line.doppler_ahead_and_behind();
        Self {
            speed: line.beta().length(),
            gamma: line.gamma(),
            doppler_ahead,
            doppler_behind,
        }
    }
}

/// The editor's observer as a worldline state (its event and velocity in W).
fn worldline(editor: &Editor) -> Result<Worldline, FrameError> {
    Worldline::new(editor.observer_event(), editor.observer_beta())
}

/// A physics error about the observer as an edit error naming the scene.
fn edit_error(editor: &Editor, error: FrameError) -> EditError {
    let kind = srt_scene::SceneErrorKind::Value {
        field: "observer".to_owned(),
        reason: error.to_string(),
    };
    EditError::Scene(srt_scene::SceneError::new(
        editor.description().origin(),
        kind,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flythrough() -> Editor {
        Editor::open("flythrough").unwrap().0
    }

    /// Flies `seconds` of proper time in steps of 0.05 with `engine`.
    fn fly(editor: &mut Editor, flight: &mut Flight, engine: Engine, alpha: f64, time: f64) {
        let steps = (time / 0.05).round() as usize;
        for _ in 0..steps {
            flight.step(editor, engine, alpha, 0.05).unwrap();
        }
    }

    #[test]
    fn thrust_adds_rapidity_along_the_look_direction() {
        let mut editor = flythrough();
        let beta = editor.observer_beta();
        let direction = editor.scene().observer.direction.normalize();
        let mut flight = Flight::start(&editor);
        fly(&mut editor, &mut flight, Engine::Thrust(1.0), 0.5, 1.0);
        // Along (almost) the direction of motion the rapidity grows by ατ = 0.5; the look
        // direction is slightly off the motion (it looks 3° down), so a little less.
        let grown = editor.observer_beta().length().atanh() - beta.length().atanh();
        assert!(grown > 0.49 && grown <= 0.5 + 1e-9, "{grown}");
        assert!((flight.proper_time - 1.0).abs() < 1e-9);
        // The world clock runs faster than the proper time (γ > 1).
        assert!(flight.world_time(&editor) > 2.0 * flight.proper_time);
        assert!(editor.observer_beta().normalize().dot(direction) > 0.99);
    }

    #[test]
    fn coasting_keeps_the_velocity_and_braking_stops() {
        let mut editor = flythrough();
        let beta = editor.observer_beta();
        let start = editor.observer_event();
        let mut flight = Flight::start(&editor);
        fly(&mut editor, &mut flight, Engine::Coast, 1.0, 0.5);
        assert!((editor.observer_beta() - beta).length() < 1e-12);
        let moved = editor.observer_event().position - start.position;
        assert!((moved - beta * (editor.observer_event().ct - start.ct)).length() < 1e-9);
        // Braking at α = 1 from 0.9c (rapidity 1.47) takes 1.47 of proper time; once started
        // it goes on while coasting.
        flight.step(&mut editor, Engine::Brake, 1.0, 0.05).unwrap();
        fly(&mut editor, &mut flight, Engine::Coast, 1.0, 1.5);
        assert_eq!(editor.observer_beta(), DVec3::ZERO);
        assert!(!flight.braking);
    }

    #[test]
    fn flying_keeps_the_look_direction() {
        // fig7 looks at a point: the flight keeps the direction instead of turning to it.
        let mut editor = Editor::open("fig7").unwrap().0;
        let direction = editor.scene().observer.direction.normalize();
        let mut flight = Flight::start(&editor);
        fly(&mut editor, &mut flight, Engine::Thrust(-1.0), 1.0, 1.0);
        let after = editor.scene().observer.direction.normalize();
        assert!(
            (after - direction).length() < 1e-12,
            "{direction} → {after}"
        );
        // Reverse thrust moves backwards, away from where it looks.
        assert!(editor.observer_beta().dot(direction) < -0.7);
    }

    #[test]
    fn the_engine_cuts_off_below_light() {
        let mut editor = flythrough();
        let mut flight = Flight::start(&editor);
        fly(&mut editor, &mut flight, Engine::Thrust(1.0), 10.0, 2.0);
        let speed = editor.observer_beta().length();
        assert!(
            speed < 1.0 && (speed - MAX_FLIGHT_SPEED).abs() < 1e-9,
            "{speed}"
        );
    }

    #[test]
    fn the_readout_gives_the_doppler_factors_ahead_and_behind() {
        let mut editor = flythrough();
        editor.set_observer_beta(DVec3::new(0.0, 0.6, 0.0)).unwrap();
        let readout = MotionReadout::of(&editor);
        assert!((readout.gamma - 1.25).abs() < 1e-12);
        assert!((readout.doppler_ahead - 2.0).abs() < 1e-12);
        assert!((readout.doppler_behind - 0.5).abs() < 1e-12);
    }
}
