//! Values a front end gives in place of a scene's own — `srt render`'s `--effects`, `--colour`,
//! `--exposure`, `--beta`, `--observer-beta` and `--time` — applied as edits of the
//! [`SceneDescription`] before it is built, so that the scene file's validation judges them: one
//! set of rules, with each overridden value named in messages by the option that gave it.
//! `--time` is `observer.time`, the observer's own clock (docs/scene-format.md, "Time"). Any other
//! key is given by a [`Setting`] (`--set KEY=VALUE`), applied first.

use std::borrow::Cow;

use glam::DVec3;

use super::error::SceneErrorKind;
use super::model::SceneDescription;
use super::setting::Setting;
use super::validate::{Names, ValueName};
use crate::projection::Projection;
use crate::scene::{Effects, SurfaceColour};

/// Values that replace a scene's own (`None`: the scene's), each named in messages by the
/// option that gave it ([`Overrides::names`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// The effect mode (`render.effects`); the tone map becomes the mode's own.
    pub effects: Option<Effects>,
    /// How lit surfaces are coloured (`render.colour`).
    pub colour: Option<SurfaceColour>,
    /// The exposure of spectral colour (`render.exposure`).
    pub exposure: Option<f64>,
    /// The observation time on the observer's own clock (`observer.time`).
    pub time: Option<f64>,
    /// Every object's velocity, relative to an observer at rest (refused with a moving one); a
    /// bare model is also placed for it.
    pub beta: Option<DVec3>,
    /// The observer's velocity through the scene's world frame (`observer.beta`).
    pub observer_beta: Option<DVec3>,
    /// How the image maps its points to viewing directions (`observer.projection`).
    pub projection: Option<Projection>,
    /// Any scene file keys with their values, in order, applied before the values above (which
    /// therefore win where both give one).
    pub settings: Vec<Setting>,
    /// What messages call each of them.
    pub names: OverrideNames,
}

/// What messages call each override: the option (or control) of the front end that gives it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OverrideNames {
    /// Names [`Overrides::colour`].
    pub colour: &'static str,
    /// Names [`Overrides::exposure`].
    pub exposure: &'static str,
    /// Names [`Overrides::time`].
    pub time: &'static str,
    /// Names [`Overrides::beta`].
    pub beta: &'static str,
    /// Names [`Overrides::observer_beta`].
    pub observer_beta: &'static str,
    /// Names [`Overrides::projection`].
    pub projection: &'static str,
    /// Names [`Overrides::settings`].
    pub settings: &'static str,
}

impl OverrideNames {
    /// The options of `srt render`.
    pub const COMMAND_LINE: Self = Self {
        colour: "--colour",
        exposure: "--exposure",
        time: "--time",
        beta: "--beta",
        observer_beta: "--observer-beta",
        projection: "--projection",
        settings: "--set",
    };

    /// The keys of the web page's address (`?time=5&set=…`) and the keyword arguments of
    /// Python's `srt.render`: each override called by its own name, `set` for the settings.
    pub const KEYS: Self = Self {
        colour: "colour",
        exposure: "exposure",
        time: "time",
        beta: "beta",
        observer_beta: "observer_beta",
        projection: "projection",
        settings: "set",
    };
}

impl Default for OverrideNames {
    fn default() -> Self {
        Self::COMMAND_LINE
    }
}

/// Reads "X,Y,Z" (spaces allowed around each number) as a vector of three finite numbers: a
/// velocity as the command line's `--beta` and the page's `beta=` take it.
///
/// # Errors
/// What is wrong with `text`: not three parts, or a part that is not a finite number.
pub fn parse_vector(text: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!(
            "expected three comma-separated numbers X,Y,Z, got {text:?}"
        ));
    };
    let number = |s: &str| -> Result<f64, String> {
        let v: f64 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(format!("{s:?} is not a finite number"))
        }
    };
    Ok(DVec3::new(number(x)?, number(y)?, number(z)?))
}

impl Overrides {
    /// Edits `description` with these values and validates the result
    /// ([`SceneDescription::validate`]'s rules), naming every overridden value by its option.
    /// `origin` names the scene in the message refusing [`Overrides::beta`] with a moving
    /// observer.
    ///
    /// # Errors
    /// [`SceneErrorKind::Override`] for a value of an option the rules refuse (a time or an
    /// exposure out of range, a velocity |β| ≥ 1, an exposure with the paper's colour, `beta`
    /// with a moving observer), and any other problem of the description as validation reports
    /// it.
    pub fn apply(
        &self,
        description: &mut SceneDescription,
        origin: &str,
    ) -> Result<(), SceneErrorKind> {
        for setting in &self.settings {
            setting.apply(description, self.names.settings)?;
        }
        if let Some(time) = self.time {
            description.observer.time = Some(time);
        }
        if let Some(projection) = self.projection {
            description.observer.projection = Some(projection);
        }
        let render = &mut description.render;
        if let Some(effects) = self.effects {
            render.effects = effects;
            render.tone_map = None;
        }
        if let Some(colour) = self.colour {
            render.colour = colour;
        }
        if let Some(exposure) = self.exposure {
            render.exposure = exposure;
        }
        if let Some(beta) = self.observer_beta {
            description.observer.beta = beta.to_array();
        }
        if let Some(beta) = self.beta {
            for object in &mut description.objects {
                object.beta = beta.to_array();
            }
        }
        description.check_named(&self.value_names())?;
        if self.beta.is_some() && description.observer.beta != [0.0; 3] {
            return Err(SceneErrorKind::Override {
                option: self.names.beta.to_owned(),
                reason: format!(
                    "sets every object's velocity relative to a resting observer and cannot be \
                     combined with a moving observer ({} or observer.beta of {origin}); give the \
                     objects' velocities in the scene file instead",
                    self.names.observer_beta
                ),
            });
        }
        Ok(())
    }

    /// What validation calls the values: the options for those given, the keys for the rest.
    fn value_names(&self) -> Names<'static> {
        let named = |given: bool, option, scene| {
            if given {
                ValueName::Option(option)
            } else {
                scene
            }
        };
        let scene = Names::SCENE_FILE;
        Names {
            exposure: named(self.exposure.is_some(), self.names.exposure, scene.exposure),
            observer_beta: named(
                self.observer_beta.is_some(),
                self.names.observer_beta,
                scene.observer_beta,
            ),
            time: named(self.time.is_some(), self.names.time, scene.time),
            projection: named(
                self.projection.is_some(),
                self.names.projection,
                scene.projection,
            ),
            object_beta: self.beta.map(|_| ValueName::Option(self.names.beta)),
            spectral: Cow::Owned(format!("{} spectral", self.names.colour)),
        }
    }
}
