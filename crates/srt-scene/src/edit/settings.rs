//! Edits of how the scene is drawn and lit: effects, colour, exposure, tone map, the lamp, the
//! moving lights and their shadows.

use glam::DVec3;
use srt_color::ToneMap;

use super::{EditError, Editor};
use crate::description::DEFAULT_LIGHT_TEMPERATURE_K;
use crate::{Effects, LightDescription, LightsDescription, SceneDescription, SurfaceColour};

impl Editor {
    /// Sets the effect mode (and the tone map that goes with it, unless one was chosen).
    ///
    /// # Errors
    /// None in practice: every effect mode is valid (the edit goes through the same checks as
    /// any other).
    pub fn set_effects(&mut self, effects: Effects) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.effects = effects;
            Ok(())
        })
    }

    /// Chooses how lit surfaces are coloured; going back to the paper's colour resets the
    /// exposure to 1 (its colour tables have none).
    ///
    /// # Errors
    /// None in practice, as [`Editor::set_effects`].
    pub fn set_colour(&mut self, colour: SurfaceColour) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.colour = colour;
            if colour == SurfaceColour::Paper {
                description.render.exposure = 1.0;
            }
            Ok(())
        })
    }

    /// Sets the exposure of spectral colour.
    ///
    /// # Errors
    /// [`EditError::Scene`] for an exposure the scene file's rules refuse (not positive, or
    /// with the paper's colour).
    pub fn set_exposure(&mut self, exposure: f64) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.exposure = exposure;
            Ok(())
        })
    }

    /// The tone map chosen explicitly (`None`: the effect mode's).
    #[must_use]
    pub fn tone_map_choice(&self) -> Option<ToneMap> {
        self.description.render.tone_map
    }

    /// Chooses the tone map (`None`: the effect mode's own).
    ///
    /// # Errors
    /// None in practice, as [`Editor::set_effects`].
    pub fn set_tone_map(&mut self, tone_map: Option<ToneMap>) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.tone_map = tone_map;
            Ok(())
        })
    }

    /// The light's temperature (kelvin) and its position in the world frame at the observation
    /// time (what [`Editor::set_light`] sets; the runtime scene has it in the observer's frame).
    #[must_use]
    pub fn light(&self) -> (f64, DVec3) {
        (self.description.light.as_ref())
            .and_then(LightsDescription::lamp)
            .map_or(
                (self.scene.light.temperature_k, self.scene.light.position),
                |light| (light.temperature_k, DVec3::from_array(light.position)),
            )
    }

    /// Sets the light's temperature (kelvin) and position.
    ///
    /// # Errors
    /// [`EditError::Scene`] for values the scene file's rules refuse (a temperature that is not
    /// positive, a position that is not finite…).
    pub fn set_light(&mut self, temperature_k: f64, position: DVec3) -> Result<(), EditError> {
        self.edit(|description| {
            let lamp = LightDescription::lamp(position.to_array(), temperature_k);
            match description
                .light
                .as_mut()
                .and_then(LightsDescription::lamp_mut)
            {
                Some(light) => {
                    light.position = lamp.position;
                    light.temperature_k = temperature_k;
                }
                None => description.light = Some(LightsDescription::Lamp(lamp)),
            }
            Ok(())
        })
    }

    /// The lamp's strength (a multiplier on all its light; 0: no lamp).
    #[must_use]
    pub fn lamp_strength(&self) -> f64 {
        self.scene.light.strength
    }

    /// Sets the lamp's strength (0 turns it off, ambient light included).
    ///
    /// # Errors
    /// [`EditError::Scene`] for a strength the scene file's rules refuse (negative, not finite).
    pub fn set_lamp_strength(&mut self, strength: f64) -> Result<(), EditError> {
        let observer = self.description.observer.position;
        self.edit(|description| {
            let lights = light_list(description, observer);
            if let Some(lamp) = lights.iter_mut().find(|l| l.carried) {
                lamp.strength = strength;
            }
            Ok(())
        })
    }

    /// The moving lights as the scene file gives them (position in W at t = 0, velocity,
    /// temperature, strength), in order.
    #[must_use]
    pub fn moving_lights(&self) -> Vec<LightDescription> {
        (self.description.light.iter())
            .flat_map(LightsDescription::moving)
            .cloned()
            .collect()
    }

    /// Adds a moving light: 6000 K, at rest in W, 2 above the point 6 ahead of the camera, of
    /// strength 36 (the lamp's diffuse light at 6 units); returns its index.
    ///
    /// # Errors
    /// [`EditError::Scene`] when the scene has as many moving lights as it may.
    pub fn add_moving_light(&mut self) -> Result<usize, EditError> {
        let observer = self.description.observer.position;
        let (forward, _, up) = self.scene.observer.basis();
        let place = DVec3::from_array(observer) + 6.0 * forward + 2.0 * up;
        let light = LightDescription {
            carried: false,
            strength: 36.0,
            ..LightDescription::lamp(place.to_array(), DEFAULT_LIGHT_TEMPERATURE_K)
        };
        self.edit(|description| {
            light_list(description, observer).push(light);
            Ok(())
        })?;
        Ok(self.scene.lights.len() - 1)
    }

    /// Replaces moving light `index` with `light` (its `carried` flag is ignored).
    ///
    /// # Errors
    /// [`EditError::NoSuchLight`] when there is none; [`EditError::Scene`] for values the scene
    /// file's rules refuse (a speed of 1 or more, a temperature that is not positive…).
    pub fn set_moving_light(
        &mut self,
        index: usize,
        light: LightDescription,
    ) -> Result<(), EditError> {
        let observer = self.description.observer.position;
        self.edit(|description| {
            let entry = moving_light_mut(light_list(description, observer), index)?;
            *entry = LightDescription {
                carried: false,
                ..light
            };
            Ok(())
        })
    }

    /// Removes moving light `index`.
    ///
    /// # Errors
    /// [`EditError::NoSuchLight`] when there is none.
    pub fn remove_moving_light(&mut self, index: usize) -> Result<(), EditError> {
        let observer = self.description.observer.position;
        self.edit(|description| {
            let lights = light_list(description, observer);
            let position = (lights.iter().enumerate())
                .filter(|(_, l)| !l.carried)
                .nth(index)
                .map(|(position, _)| position)
                .ok_or(EditError::NoSuchLight(index))?;
            lights.remove(position);
            Ok(())
        })
    }

    /// Whether objects cast the moving lights' shadows.
    #[must_use]
    pub fn shadows(&self) -> bool {
        self.scene.shadows
    }

    /// Turns the moving lights' shadows on or off.
    ///
    /// # Errors
    /// None in practice (the scene is rebuilt as for any edit).
    pub fn set_shadows(&mut self, shadows: bool) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.shadows = shadows;
            Ok(())
        })
    }
}

/// The description's lights as a `[[light]]` list, made one if needed: a `[light]` table
/// becomes the list's carried entry, no light key the default lamp at `observer` (where it sits
/// without one), so that the scene lights as before.
pub(super) fn light_list(
    description: &mut SceneDescription,
    observer: [f64; 3],
) -> &mut Vec<LightDescription> {
    let list = match description.light.take() {
        Some(LightsDescription::List(list)) => list,
        Some(LightsDescription::Lamp(lamp)) => vec![LightDescription {
            carried: true,
            ..lamp
        }],
        None => vec![LightDescription {
            carried: true,
            ..LightDescription::lamp(observer, DEFAULT_LIGHT_TEMPERATURE_K)
        }],
    };
    match description.light.insert(LightsDescription::List(list)) {
        LightsDescription::List(list) => list,
        LightsDescription::Lamp(_) => unreachable!("a list was just inserted"),
    }
}

/// The moving light `index` of a `[[light]]` list (its entries that are not carried).
pub(super) fn moving_light_mut(
    lights: &mut [LightDescription],
    index: usize,
) -> Result<&mut LightDescription, EditError> {
    (lights.iter_mut())
        .filter(|l| !l.carried)
        .nth(index)
        .ok_or(EditError::NoSuchLight(index))
}
