//! Edits of one object: its velocity (keeping where it is seen, if asked), offset, wireframe,
//! spin and thrust.

use glam::DVec3;
use srt_physics::{Event, Frame};

use super::{EditError, Editor};
use crate::description::{SpinDescription, ThrustDescription};
use crate::{ObjectDescription, SceneDescription, SceneError, SceneErrorKind};

/// Parses a speed typed by the user: a number ≥ 0 (a fraction of c), optionally followed by
/// `c`. Whether it is below the speed of light is the scene's rule, checked when it is set.
///
/// # Errors
/// [`EditError::Speed`] with a message for the status line when the text is not a finite
/// number or is negative.
pub fn parse_speed(text: &str) -> Result<f64, EditError> {
    let trimmed = text.trim();
    let number = trimmed.strip_suffix('c').unwrap_or(trimmed).trim();
    let speed = number
        .parse::<f64>()
        .ok()
        .filter(|speed| speed.is_finite())
        .ok_or_else(|| {
            EditError::Speed(format!(
                "\"{trimmed}\" is not a speed: type a fraction of the speed of light, e.g. 0.9"
            ))
        })?;
    if speed < 0.0 {
        return Err(EditError::Speed(format!(
            "a speed of {speed}c is negative: type a speed ≥ 0 and reverse the direction instead"
        )));
    }
    Ok(speed)
}

/// The velocity `speed · direction` (units of c) that keeps the point `apparent` — seen at
/// distance `distance` from an observer observing at time `ct` — where it is seen: the offset for
/// that velocity such that the worldline passes through `apparent` at time `ct − distance`.
#[must_use]
pub fn offset_keeping_apparent_position(
    apparent: DVec3,
    distance: f64,
    ct: f64,
    beta: DVec3,
) -> DVec3 {
    apparent - beta * (ct - distance)
}

impl Editor {
    /// Speed |β| of object `index` relative to the scene's world frame, as a fraction of c (0
    /// for an index out of range).
    #[must_use]
    pub fn speed(&self, index: usize) -> f64 {
        self.description
            .objects
            .get(index)
            .map_or(0.0, |o| DVec3::from_array(o.beta).length())
    }

    /// Unit direction of motion of object `index` (remembered while its speed is 0).
    #[must_use]
    pub fn direction(&self, index: usize) -> DVec3 {
        self.directions.get(index).copied().unwrap_or(DVec3::X)
    }

    /// Offset **a** of object `index`: where its S′ origin is in the world frame at t = 0.
    #[must_use]
    pub fn offset(&self, index: usize) -> DVec3 {
        self.description
            .objects
            .get(index)
            .map_or(DVec3::ZERO, |o| DVec3::from_array(o.offset))
    }

    /// The wireframe line width of object `index` (`None`: textured).
    #[must_use]
    pub fn wireframe(&self, index: usize) -> Option<f64> {
        self.scene.objects.get(index).and_then(|o| o.wireframe)
    }

    /// Sets the velocity of object `index` (relative to the scene's world frame) to
    /// `speed · direction`. With `keep_apparent`, the offset changes too, so that the object's
    /// origin stays where the observer sees it now (only its shape and colour change);
    /// otherwise the offset stays.
    ///
    /// # Errors
    /// [`EditError::Direction`] for a zero or non-finite direction, [`EditError::Scene`] for a
    /// velocity or offset the scene file's rules refuse (a speed of 1 or more…); the scene is
    /// then unchanged.
    pub fn set_velocity(
        &mut self,
        index: usize,
        speed: f64,
        direction: DVec3,
        keep_apparent: bool,
    ) -> Result<(), EditError> {
        let object = self
            .description
            .objects
            .get(index)
            .ok_or(EditError::NoSuchObject(index))?;
        // Everything in the world frame: the description's velocity, offset and observation
        // event (the emission event seen now is the same event in every frame).
        let old = Frame::new(
            DVec3::from_array(object.beta),
            DVec3::from_array(object.offset),
        )
        .map_err(|error| {
            let kind = SceneErrorKind::Frame {
                object: object.label(index),
                error,
            };
            SceneError::new(self.description.origin(), kind)
        })?;
        let unit = direction
            .try_normalize()
            .ok_or(EditError::Direction(direction))?;
        let beta = speed * unit;
        let offset = if keep_apparent {
            let observer = &self.description.observer;
            let observer = Event::new(observer.ct, DVec3::from_array(observer.position));
            let apparent = old.apparent_position(DVec3::ZERO, observer);
            let distance = (apparent - observer.position).length();
            offset_keeping_apparent_position(apparent, distance, observer.ct, beta)
        } else {
            old.offset()
        };
        self.edit_object(index, |object| {
            object.beta = beta.to_array();
            object.offset = offset.to_array();
        })?;
        self.directions[index] = beta.try_normalize().unwrap_or(unit);
        Ok(())
    }

    /// Sets the offset **a** of object `index`.
    ///
    /// # Errors
    /// [`EditError::Scene`] for an offset the scene file's rules refuse (not finite, too far).
    pub fn set_offset(&mut self, index: usize, offset: DVec3) -> Result<(), EditError> {
        self.edit_object(index, |object| object.offset = offset.to_array())
    }

    /// Draws object `index` as a wireframe of lines `width` wide (in its own units), or textured.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a width the scene file's rules refuse (not positive…).
    pub fn set_wireframe(&mut self, index: usize, width: Option<f64>) -> Result<(), EditError> {
        self.edit_object(index, |object| object.wireframe = width)
    }

    /// The spin of object `index` as its description gives it (`None`: it does not spin).
    #[must_use]
    pub fn spin(&self, index: usize) -> Option<SpinDescription> {
        self.description.objects.get(index).and_then(|o| o.spin)
    }

    /// The thrust of object `index` as its description gives it (`None`: it does not thrust).
    #[must_use]
    pub fn thrust(&self, index: usize) -> Option<ThrustDescription> {
        self.description.objects.get(index).and_then(|o| o.thrust)
    }

    /// Sets (or, with `None`, removes) the spin of object `index`.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a spin the scene file's rules refuse (a zero axis, a point
    /// reaching the speed of light, a thrust as well…); the scene is then unchanged.
    pub fn set_spin(
        &mut self,
        index: usize,
        spin: Option<SpinDescription>,
    ) -> Result<(), EditError> {
        self.edit_object(index, |object| object.spin = spin)
    }

    /// Sets (or, with `None`, removes) the thrust of object `index`.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a thrust the scene file's rules refuse (a zero acceleration, a
    /// point beyond the Rindler horizon, a spin as well…); the scene is then unchanged.
    pub fn set_thrust(
        &mut self,
        index: usize,
        thrust: Option<ThrustDescription>,
    ) -> Result<(), EditError> {
        self.edit_object(index, |object| object.thrust = thrust)
    }

    /// Applies `change` to the description of object `index`, as [`Editor::apply`] does.
    pub(super) fn edit_object(
        &mut self,
        index: usize,
        change: impl FnOnce(&mut ObjectDescription),
    ) -> Result<(), EditError> {
        self.edit(|description| {
            change(object_mut(description, index)?);
            Ok(())
        })
    }
}

/// The description of object `index`.
pub(super) fn object_mut(
    description: &mut SceneDescription,
    index: usize,
) -> Result<&mut ObjectDescription, EditError> {
    description
        .objects
        .get_mut(index)
        .ok_or(EditError::NoSuchObject(index))
}
