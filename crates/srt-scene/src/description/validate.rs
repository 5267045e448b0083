//! Checks of a description that need no file: ranges, finiteness and consistency of every value.
//! Lengths, positions and times are also bounded by [`MAX_COORDINATE`], and shape resolutions by
//! what fits in [`MAX_SCENE_TRIANGLES`], so that absurd but finite values are refused here, with
//! the key named, rather than in a renderer or a library.
//!
//! Every rule lives here once. The values a front end may override
//! ([`Overrides`](super::Overrides)) are named in messages by a [`ValueName`]: the scene file's
//! key, or the option that gave the value; the rules that front ends also need on their own
//! ([`observation_time`], [`velocity`]) are public.

use std::borrow::Cow;

use glam::DVec3;
use srt_physics::{Frame, FrameError, validate_beta};

use super::error::{SceneError, SceneErrorKind, value_error};
use super::model::{
    LightDescription, LightsDescription, ObjectDescription, ObserverDescription, RenderDescription,
    SceneDescription, ShapeDescription, TextureDescription,
};
use crate::limits::{MAX_COORDINATE, MAX_SCENE_TRIANGLES};
use crate::scene::{MAX_CUBE_MAP_SIZE, MAX_MOVING_LIGHTS, SurfaceColour};
use crate::shapes::{MAX_CUBE_SUBDIVISIONS, MAX_SPHERE_SEGMENTS, MIN_SPHERE_SEGMENTS};
use crate::textures::{MAX_CHECKER_SQUARES, MAX_FRAMES};

impl SceneDescription {
    /// How errors from [`SceneDescription::build`] name this scene when it is not read from a
    /// file.
    #[must_use]
    pub fn origin(&self) -> String {
        match &self.name {
            Some(name) => format!("scene \"{name}\""),
            None => "scene".to_owned(),
        }
    }

    /// Checks every value that does not need a file: the observer (exactly one of `look_at` and
    /// `direction`, a non-zero direction, `up` not parallel to it, fov in (0, 180), |β| < 1), the light
    /// (temperature > 0), the render settings and each object (|β| < 1, sizes and scales > 0,
    /// colours in [0, 1]…). All numbers must be finite, and positions, offsets, lengths, scale
    /// factors and ct at most [`MAX_COORDINATE`] in absolute value.
    ///
    /// # Errors
    /// The first problem found, naming the value (and the object) concerned.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.check()
            .map_err(|kind| SceneError::new(self.origin(), kind))
    }

    /// [`SceneDescription::validate`]'s checks, naming every value by its scene file key.
    pub(super) fn check(&self) -> Result<(), SceneErrorKind> {
        self.check_named(&Names::SCENE_FILE)
    }

    /// [`SceneDescription::validate`]'s checks, naming the overridable values as `names` says.
    pub(super) fn check_named(&self, names: &Names<'_>) -> Result<(), SceneErrorKind> {
        self.observer.check(names)?;
        if let Some(lights) = &self.light {
            check_lights(lights)?;
        }
        // A ride's thrust, its direction and the lamp it carries.
        self.looking_observer()?;
        self.render.check(names)?;
        if let Some(sky) = &self.sky {
            if sky.star_field > crate::sky::MAX_STARS {
                return Err(value_error(
                    "sky.star_field",
                    format!(
                        "must be at most {} stars, got {}",
                        crate::sky::MAX_STARS,
                        sky.star_field
                    ),
                ));
            }
            positive(
                ValueName::Key("sky.image_brightness"),
                sky.image_brightness,
                "",
            )?;
            if !(sky.saturation_magnitude.is_finite() && sky.saturation_magnitude.abs() <= 100.0) {
                return Err(value_error(
                    "sky.saturation_magnitude",
                    format!(
                        "must be a magnitude between -100 and 100, got {:?}",
                        sky.saturation_magnitude
                    ),
                ));
            }
        }
        for (index, object) in self.objects.iter().enumerate() {
            object.check(&object.label(index), names)?;
        }
        Ok(())
    }
}

/// What a message calls a value: the scene file's key, or the option that gave the value in
/// place of the scene's own.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueName<'a> {
    /// A key of the scene file, e.g. `render.exposure`.
    Key(&'a str),
    /// An option (or control) of a front end, e.g. `--exposure`.
    Option(&'a str),
}

impl<'a> ValueName<'a> {
    /// The key or the option.
    #[must_use]
    pub const fn name(self) -> &'a str {
        match self {
            Self::Key(name) | Self::Option(name) => name,
        }
    }

    /// The value shown with its name: `render.exposure = 2.0`, `--exposure 2.0`.
    fn with_value(self, value: &str) -> String {
        match self {
            Self::Key(key) => format!("{key} = {value}"),
            Self::Option(option) => format!("{option} {value}"),
        }
    }

    /// The error `reason` about the value, called `subject` in the message: a scene file's
    /// [`SceneErrorKind::Value`], an option's [`SceneErrorKind::Override`].
    fn error(self, subject: impl Into<String>, reason: impl Into<String>) -> SceneErrorKind {
        match self {
            Self::Key(_) => value_error(subject, reason),
            Self::Option(_) => SceneErrorKind::Override {
                option: subject.into(),
                reason: reason.into(),
            },
        }
    }
}

/// What messages call the values a front end may override.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Names<'a> {
    /// `render.exposure`.
    pub exposure: ValueName<'a>,
    /// `observer.beta`.
    pub observer_beta: ValueName<'a>,
    /// `observer.time`.
    pub time: ValueName<'a>,
    /// `observer.projection`.
    pub projection: ValueName<'a>,
    /// Every object's `beta`, when one option gives them all; `None`: each object's own.
    pub object_beta: Option<ValueName<'a>>,
    /// How to ask for spectral colour: `colour = "spectral"`, `--colour spectral`.
    pub spectral: Cow<'a, str>,
}

impl Names<'_> {
    /// Every value as the scene file gives it.
    pub const SCENE_FILE: Self = Self {
        exposure: ValueName::Key("render.exposure"),
        observer_beta: ValueName::Key("observer.beta"),
        time: ValueName::Key("observer.time"),
        projection: ValueName::Key("observer.projection"),
        object_beta: None,
        spectral: Cow::Borrowed("colour = \"spectral\""),
    };
}

/// `ct` if it is a usable time: finite and within ±[`MAX_COORDINATE`], the rule of `observer.ct`
/// and `observer.time` (and of the times front ends give, e.g. an animation's first and last).
///
/// # Errors
/// [`SceneErrorKind::Value`] or [`SceneErrorKind::Override`] naming `name`.
pub fn observation_time(name: ValueName<'_>, ct: f64) -> Result<f64, SceneErrorKind> {
    if ct.is_finite() && ct.abs() <= MAX_COORDINATE {
        Ok(ct)
    } else {
        Err(name.error(
            name.name(),
            format!("must be a finite number within ±{MAX_COORDINATE:e}, got {ct:?}"),
        ))
    }
}

/// `beta` if it is a velocity (finite, |β| < 1), the rule of `observer.beta` and of velocities
/// front ends give.
///
/// # Errors
/// [`SceneErrorKind::Value`] or [`SceneErrorKind::Override`] naming `name` (an option with the
/// value given, e.g. `--beta 0.0,1.2,0.0 is not a valid velocity: …`).
pub fn velocity(name: ValueName<'_>, beta: DVec3) -> Result<DVec3, SceneErrorKind> {
    validate_beta(beta).map_err(|error| invalid_velocity(name, beta, &error))
}

/// The error saying that `beta`, called `name`, is not a velocity because of `error`.
pub(super) fn invalid_velocity(
    name: ValueName<'_>,
    beta: DVec3,
    error: &FrameError,
) -> SceneErrorKind {
    let subject = match name {
        ValueName::Key(key) => key.to_owned(),
        ValueName::Option(_) => name.with_value(&format!("{:?},{:?},{:?}", beta.x, beta.y, beta.z)),
    };
    name.error(subject, format!("is not a valid velocity: {error}"))
}

/// The `light` key's checks: each table's position, temperature, strength and velocity; a
/// `[light]` table (the lamp) has no velocity; a `[[light]]` list has at most one carried entry
/// and at most [`MAX_MOVING_LIGHTS`] moving ones.
fn check_lights(lights: &LightsDescription) -> Result<(), SceneErrorKind> {
    let (list, in_list): (&[LightDescription], bool) = match lights {
        LightsDescription::Lamp(lamp) => (std::slice::from_ref(lamp), false),
        LightsDescription::List(list) => (list, true),
    };
    for (index, light) in list.iter().enumerate() {
        let key = |field: &str| {
            if in_list {
                format!("light[{index}].{field}")
            } else {
                format!("light.{field}")
            }
        };
        coordinates3(&key("position"), light.position)?;
        positive(
            ValueName::Key(&key("temperature_k")),
            light.temperature_k,
            " of kelvin",
        )?;
        non_negative(&key("strength"), light.strength)?;
        let beta = DVec3::from_array(light.beta);
        if light.is_lamp(in_list) && beta != DVec3::ZERO {
            return Err(value_error(
                key("beta"),
                "the lamp rests relative to the observer; give a light that moves as a \
                 [[light]] table without carried = true",
            ));
        }
        velocity(ValueName::Key(&key("beta")), beta)?;
    }
    if list.iter().filter(|l| in_list && l.carried).count() > 1 {
        return Err(value_error(
            "light",
            "at most one [[light]] table may be carried by the observer",
        ));
    }
    let moving = lights.moving().count();
    if moving > MAX_MOVING_LIGHTS {
        return Err(value_error(
            "light",
            format!("at most {MAX_MOVING_LIGHTS} moving lights, got {moving}"),
        ));
    }
    Ok(())
}

fn finite3(field: &str, value: [f64; 3]) -> Result<DVec3, SceneErrorKind> {
    let v = DVec3::from_array(value);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(value_error(
            field,
            format!("must have finite components, got {value:?}"),
        ))
    }
}

/// A position or direction: finite components within ±[`MAX_COORDINATE`].
fn coordinates3(field: &str, value: [f64; 3]) -> Result<DVec3, SceneErrorKind> {
    let v = DVec3::from_array(value);
    if v.is_finite() && v.abs().max_element() <= MAX_COORDINATE {
        Ok(v)
    } else {
        Err(value_error(
            field,
            format!("must have finite components within ±{MAX_COORDINATE:e}, got {value:?}"),
        ))
    }
}

fn unit_color(field: &str, value: [f64; 3]) -> Result<(), SceneErrorKind> {
    if value.iter().all(|c| (0.0..=1.0).contains(c)) {
        Ok(())
    } else {
        Err(value_error(
            field,
            format!("must have components in [0, 1], got {value:?}"),
        ))
    }
}

/// A finite number > 0; `unit` follows "number" in the message (e.g. " of kelvin").
fn positive(name: ValueName<'_>, value: f64, unit: &str) -> Result<(), SceneErrorKind> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(name.error(
            name.name(),
            format!("must be a positive number{unit}, got {value:?}"),
        ))
    }
}

/// A length: positive and at most [`MAX_COORDINATE`].
fn length(field: &str, value: f64) -> Result<(), SceneErrorKind> {
    if value > 0.0 && value <= MAX_COORDINATE {
        Ok(())
    } else {
        Err(value_error(
            field,
            format!("must be a positive number of at most {MAX_COORDINATE:e}, got {value:?}"),
        ))
    }
}

/// A shape resolution in `lo..=hi`; the message says how many triangles `value` would make.
fn resolution(
    field: &str,
    value: u32,
    (lo, hi): (u32, u32),
    triangles: u64,
) -> Result<(), SceneErrorKind> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(value_error(
            field,
            format!(
                "must be in {lo}..={hi}, got {value} (which would make {triangles} triangles; \
                 a scene may have at most {MAX_SCENE_TRIANGLES})"
            ),
        ))
    }
}

/// A factor: finite and at least 0.
fn non_negative(field: &str, value: f64) -> Result<(), SceneErrorKind> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(value_error(
            field,
            format!("must be a number ≥ 0, got {value:?}"),
        ))
    }
}

impl ObserverDescription {
    fn check(&self, names: &Names<'_>) -> Result<(), SceneErrorKind> {
        coordinates3("observer.position", self.position)?;
        let direction = match (self.look_at, self.direction) {
            (Some(target), None) => {
                coordinates3("observer.look_at", target)?;
                DVec3::from_array(target) - DVec3::from_array(self.position)
            }
            (None, Some(direction)) => coordinates3("observer.direction", direction)?,
            (Some(_), Some(_)) => {
                return Err(value_error(
                    "observer",
                    "gives both look_at and direction; give exactly one of them",
                ));
            }
            (None, None) => {
                return Err(value_error(
                    "observer",
                    "gives neither look_at nor direction; give exactly one of them",
                ));
            }
        };
        let direction = direction.try_normalize().ok_or_else(|| {
            value_error(
                "observer",
                "has a zero viewing direction (look_at equals position, or direction is zero)",
            )
        })?;
        let up = coordinates3("observer.up", self.up)?
            .try_normalize()
            .ok_or_else(|| value_error("observer.up", "must not be zero"))?;
        if direction.cross(up).length() < 1e-9 {
            return Err(value_error(
                "observer.up",
                format!(
                    "must not be parallel to the viewing direction, got {:?}",
                    self.up
                ),
            ));
        }
        if !(self.fov_y_deg > 0.0 && self.fov_y_deg < 180.0) {
            return Err(value_error(
                "observer.fov_y_deg",
                format!("must be in (0, 180) degrees, got {:?}", self.fov_y_deg),
            ));
        }
        velocity(names.observer_beta, DVec3::from_array(self.beta))?;
        observation_time(ValueName::Key("observer.ct"), self.ct)?;
        if let Some(time) = self.time {
            observation_time(names.time, time)?;
        }
        if let Some(projection) = self.projection {
            projection
                .check()
                .map_err(|reason| names.projection.error(names.projection.name(), reason))?;
        }
        if let Some(stereo) = self.stereo {
            stereo
                .check(self.projection.unwrap_or_default())
                .map_err(|reason| value_error("observer.stereo", reason))?;
        }
        Ok(())
    }
}

impl RenderDescription {
    fn check(&self, names: &Names<'_>) -> Result<(), SceneErrorKind> {
        unit_color("render.background", self.background)?;
        non_negative("render.ambient", self.ambient)?;
        non_negative("render.diffuse", self.diffuse)?;
        non_negative("render.specular", self.specular)?;
        non_negative("render.shininess", self.shininess)?;
        if !(1..=MAX_CUBE_MAP_SIZE).contains(&self.cube_map_size) {
            return Err(value_error(
                "render.cube_map_size",
                format!(
                    "must be a whole number of texels from 1 to {MAX_CUBE_MAP_SIZE}, got {}",
                    self.cube_map_size
                ),
            ));
        }
        let exposure = names.exposure;
        positive(exposure, self.exposure, "")?;
        if self.exposure != 1.0 && self.colour == SurfaceColour::Paper {
            return Err(exposure.error(
                exposure.with_value(&format!("{:?}", self.exposure)),
                format!(
                    "needs spectral colour ({}): the paper's colour tables have no exposure",
                    names.spectral
                ),
            ));
        }
        Ok(())
    }
}

impl ObjectDescription {
    /// Checks the object called `label`: its motion (`beta` named as `names` says), optics,
    /// shape, texture and placement.
    fn check(&self, label: &str, names: &Names<'_>) -> Result<(), SceneErrorKind> {
        let field = |name: &str| format!("{name} of {label}");
        if let Some(name) = names.object_beta {
            velocity(name, DVec3::from_array(self.beta))?;
        }
        Frame::new(DVec3::from_array(self.beta), DVec3::from_array(self.offset)).map_err(
            |error| SceneErrorKind::Frame {
                object: label.to_owned(),
                error,
            },
        )?;
        coordinates3(&field("offset"), self.offset)?;
        for (name, value) in [
            ("ultraviolet", self.ultraviolet),
            ("infrared", self.infrared),
        ] {
            if let Some(value) = value
                && !(0.0..=1.0).contains(&value)
            {
                return Err(value_error(
                    field(name),
                    format!("must be a reflectance in [0, 1], got {value:?}"),
                ));
            }
        }
        if let Some(emission) = &self.emission {
            positive(
                ValueName::Key(&field("emission.temperature_k")),
                emission.temperature_k,
                " of kelvin",
            )?;
            non_negative(&field("emission.brightness"), emission.brightness)?;
            if let Some(blink) = emission.blink {
                positive(
                    ValueName::Key(&field("emission.blink.period")),
                    blink.period,
                    " of proper time (ct')",
                )?;
                if !(0.0..=1.0).contains(&blink.duty) {
                    return Err(value_error(
                        field("emission.blink.duty"),
                        format!("must be a fraction in [0, 1], got {:?}", blink.duty),
                    ));
                }
            }
        }
        self.motion()
            .map_err(|(key, error)| value_error(field(key), error))?;
        self.shape.check(&field)?;
        if let Some(texture) = &self.texture {
            texture.check(&field)?;
        }
        if let Some(color) = self.color {
            unit_color(&field("color"), color)?;
        }
        if let Some(width) = self.wireframe {
            length(&field("wireframe"), width)?;
        }
        coordinates3(&field("translate"), self.translate)?;
        finite3(&field("rotate_deg"), self.rotate_deg)?;
        let factors = self.scale.factors();
        if !(factors.is_finite()
            && factors.min_element() > 0.0
            && factors.max_element() <= MAX_COORDINATE)
        {
            return Err(value_error(
                field("scale"),
                format!(
                    "must be positive and at most {MAX_COORDINATE:e} (one number or three), got {:?}",
                    factors.to_array()
                ),
            ));
        }
        Ok(())
    }
}

impl ShapeDescription {
    /// Checks sizes and resolutions; `field` names a key of the object (`shape.size of …`).
    fn check(&self, field: &dyn Fn(&str) -> String) -> Result<(), SceneErrorKind> {
        match self {
            Self::Cube { size, subdivisions } => {
                length(&field("shape.size"), *size)?;
                let n = u64::from(*subdivisions);
                resolution(
                    &field("shape.subdivisions"),
                    *subdivisions,
                    (1, MAX_CUBE_SUBDIVISIONS),
                    n.saturating_mul(n).saturating_mul(12),
                )
            }
            Self::Sphere { radius, segments } => {
                length(&field("shape.radius"), *radius)?;
                let n = u64::from(*segments);
                resolution(
                    &field("shape.segments"),
                    *segments,
                    (MIN_SPHERE_SEGMENTS, MAX_SPHERE_SEGMENTS),
                    n.saturating_mul((n / 2).max(2) - 1).saturating_mul(2),
                )
            }
            Self::Model { path } if path.is_empty() => {
                Err(value_error(field("shape.path"), "must not be empty"))
            }
            Self::Model { .. } => Ok(()),
        }
    }
}

impl TextureDescription {
    /// Checks the checker's squares and colours or the image's path; `field` names a key of the
    /// object (`texture.squares of …`).
    fn check(&self, field: &dyn Fn(&str) -> String) -> Result<(), SceneErrorKind> {
        match self {
            Self::Checker { squares, colors } => {
                if !(1..=MAX_CHECKER_SQUARES).contains(squares) {
                    return Err(value_error(
                        field("texture.squares"),
                        format!("must be in 1..={MAX_CHECKER_SQUARES}, got {squares}"),
                    ));
                }
                colors
                    .iter()
                    .try_for_each(|color| unit_color(&field("texture.colors"), *color))
            }
            Self::Image { path } if path.is_empty() => {
                Err(value_error(field("texture.path"), "must not be empty"))
            }
            Self::Image { .. } => Ok(()),
            Self::Frames { files, fps } => {
                if files.is_empty() || files.len() > MAX_FRAMES {
                    return Err(value_error(
                        field("texture.files"),
                        format!("must list 1 to {MAX_FRAMES} images, got {}", files.len()),
                    ));
                }
                if files.iter().any(String::is_empty) {
                    return Err(value_error(
                        field("texture.files"),
                        "must not hold an empty path",
                    ));
                }
                positive(
                    ValueName::Key(&field("texture.fps")),
                    *fps,
                    " of frames per unit of proper time",
                )
            }
            Self::Clock {
                rate,
                offset,
                dial,
                colors,
            } => {
                for (name, value) in [("texture.rate", rate), ("texture.offset", offset)] {
                    if !value.is_finite() {
                        return Err(value_error(
                            field(name),
                            format!("must be a finite number, got {value:?}"),
                        ));
                    }
                }
                positive(
                    ValueName::Key(&field("texture.dial")),
                    *dial,
                    " (the reading per turn of the slow hand)",
                )?;
                colors
                    .iter()
                    .try_for_each(|color| unit_color(&field("texture.colors"), *color))
            }
        }
    }
}
