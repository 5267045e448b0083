//! Edits of the observer: camera, time on its own clock, velocity, a flight's step.

use glam::DVec3;
use srt_physics::Event;

use super::{EditError, Editor};
use crate::{Observer, ObserverDescription, Projection};

impl Editor {
    /// The observer's velocity through the scene's world frame, in units of c.
    #[must_use]
    pub fn observer_beta(&self) -> DVec3 {
        DVec3::from_array(self.description.observer.beta)
    }

    /// Sets the observer: the camera, and the observation time on its own clock (`observer.ct`
    /// of the runtime observer; [`Editor::time`]).
    ///
    /// # Errors
    /// [`EditError::Scene`] for values the scene file's rules refuse (a zero direction, an up
    /// vector parallel to it, a field of view outside (0°, 180°), a position or time that is not
    /// finite…); the observer is then unchanged.
    pub fn set_observer(&mut self, observer: Observer) -> Result<(), EditError> {
        let clock_moved = observer.time != self.time();
        self.move_observer(|description| {
            // A riding observer's runtime position is where the ride has taken it: its start
            // stays the description's.
            let position = if description.thrust.is_some() {
                description.position
            } else {
                observer.position.to_array()
            };
            *description = ObserverDescription {
                position,
                look_at: None,
                direction: Some(observer.direction.to_array()),
                beta: description.beta,
                up: observer.up.to_array(),
                fov_y_deg: observer.fov_y_deg,
                ct: description.ct,
                time: if clock_moved {
                    Some(observer.time)
                } else {
                    description.time
                },
                projection: (observer.projection != Projection::Perspective)
                    .then_some(observer.projection),
                thrust: description.thrust,
                stereo: observer.stereo,
            };
        })
    }

    /// The observation time: the observer's own clock when it looks (`observer.time`, or
    /// `observer.ct` when the scene gives none).
    #[must_use]
    pub const fn time(&self) -> f64 {
        self.scene.observer.time
    }

    /// Sets the observation time on the observer's own clock (`observer.time`): a moving
    /// observer moves along its worldline, as `srt render --time` moves it.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a time the scene file's rules refuse (not finite, too large).
    pub fn set_time(&mut self, time: f64) -> Result<(), EditError> {
        self.move_observer(|observer| observer.time = Some(time))
    }

    /// Sets the observer's velocity through the scene's world frame (units of c); the objects
    /// keep their velocities relative to the world frame.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a velocity the scene file's rules refuse (|β| ≥ 1, not finite).
    pub fn set_observer_beta(&mut self, beta: DVec3) -> Result<(), EditError> {
        self.move_observer(|observer| observer.beta = beta.to_array())
    }

    /// The observation event in the world frame W: where the observer is at
    /// [`Editor::time`] ([`crate::SceneDescription::observation_event`]).
    #[must_use]
    pub fn observer_event(&self) -> Event {
        let observer = &self.description.observer;
        self.description
            .observation_event()
            .unwrap_or_else(|_| Event::new(observer.ct, DVec3::from_array(observer.position)))
    }

    /// Moves the observer to the event `event` (in W) with velocity `beta` through W, in one
    /// edit: one step of a flight (the camera's direction, up and field of view stay). The
    /// observer's clock then reads W's time there (`observer.ct` = `event.ct`, no `time`).
    ///
    /// # Errors
    /// [`EditError::Scene`] for values the scene file's rules refuse (|β| ≥ 1, a position or
    /// time that is not finite or too large); the observer is then unchanged.
    pub fn set_observer_motion(&mut self, event: Event, beta: DVec3) -> Result<(), EditError> {
        let direction = self.scene.observer.direction;
        self.move_observer(|observer| {
            // A point looked at would turn the camera as it moves: keep today's direction.
            observer.look_at = None;
            observer.direction = Some(direction.to_array());
            observer.position = event.position.to_array();
            observer.ct = event.ct;
            observer.time = None;
            observer.beta = beta.to_array();
        })
    }

    /// The observer the scene started with (for "reset view").
    #[must_use]
    pub const fn home(&self) -> Observer {
        self.home
    }

    /// Puts the camera back where the scene started (the observation time stays).
    ///
    /// # Errors
    /// As [`Editor::set_observer`] (the home observer was accepted when the scene was built).
    pub fn reset_view(&mut self) -> Result<(), EditError> {
        self.set_observer(Observer {
            time: self.scene.observer.time,
            ..self.home
        })
    }
}
