//! Checks of a description that need no file: ranges, finiteness and consistency of every value.
//! Lengths, positions and times are also bounded by [`MAX_COORDINATE`], and shape resolutions by
//! what fits in [`MAX_SCENE_TRIANGLES`], so that absurd but finite values are refused here, with
//! the key named, rather than in a renderer or a library.

use glam::DVec3;
use srt_physics::{Frame, validate_beta};

use super::error::{SceneError, SceneErrorKind, value_error};
use super::model::{
    ObjectDescription, ObserverDescription, RenderDescription, SceneDescription, ShapeDescription,
    TextureDescription,
};
use crate::limits::{MAX_COORDINATE, MAX_SCENE_TRIANGLES};
use crate::scene::SurfaceColour;
use crate::shapes::{MAX_CUBE_SUBDIVISIONS, MAX_SPHERE_SEGMENTS, MIN_SPHERE_SEGMENTS};
use crate::textures::MAX_CHECKER_SQUARES;

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

    pub(super) fn check(&self) -> Result<(), SceneErrorKind> {
        self.observer.check()?;
        if let Some(light) = &self.light {
            coordinates3("light.position", light.position)?;
            if !(light.temperature_k.is_finite() && light.temperature_k > 0.0) {
                return Err(value_error(
                    "light.temperature_k",
                    format!(
                        "must be a positive number of kelvin, got {:?}",
                        light.temperature_k
                    ),
                ));
            }
        }
        self.render.check()?;
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
            if !(sky.image_brightness.is_finite() && sky.image_brightness > 0.0) {
                return Err(value_error(
                    "sky.image_brightness",
                    format!("must be a positive number, got {:?}", sky.image_brightness),
                ));
            }
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
            object.check(&object.label(index))?;
        }
        Ok(())
    }
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
    fn check(&self) -> Result<(), SceneErrorKind> {
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
        validate_beta(DVec3::from_array(self.beta)).map_err(|error| {
            value_error("observer.beta", format!("is not a valid velocity: {error}"))
        })?;
        if !self.ct.is_finite() || self.ct.abs() > MAX_COORDINATE {
            return Err(value_error(
                "observer.ct",
                format!(
                    "must be finite and within ±{MAX_COORDINATE:e}, got {:?}",
                    self.ct
                ),
            ));
        }
        Ok(())
    }
}

impl RenderDescription {
    fn check(&self) -> Result<(), SceneErrorKind> {
        unit_color("render.background", self.background)?;
        non_negative("render.ambient", self.ambient)?;
        non_negative("render.diffuse", self.diffuse)?;
        non_negative("render.specular", self.specular)?;
        non_negative("render.shininess", self.shininess)?;
        if !(self.exposure.is_finite() && self.exposure > 0.0) {
            return Err(value_error(
                "render.exposure",
                format!("must be a positive number, got {:?}", self.exposure),
            ));
        }
        if self.exposure != 1.0 && self.colour == SurfaceColour::Paper {
            return Err(value_error(
                "render.exposure",
                "needs colour = \"spectral\" (the paper's colour tables have no exposure)",
            ));
        }
        Ok(())
    }
}

impl ObjectDescription {
    fn check(&self, label: &str) -> Result<(), SceneErrorKind> {
        let field = |name: &str| format!("{name} of {label}");
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
            if !(emission.temperature_k.is_finite() && emission.temperature_k > 0.0) {
                return Err(value_error(
                    field("emission.temperature_k"),
                    format!(
                        "must be a positive number of kelvin, got {:?}",
                        emission.temperature_k
                    ),
                ));
            }
            non_negative(&field("emission.brightness"), emission.brightness)?;
        }
        match &self.shape {
            ShapeDescription::Cube { size, subdivisions } => {
                length(&field("shape.size"), *size)?;
                let n = u64::from(*subdivisions);
                resolution(
                    &field("shape.subdivisions"),
                    *subdivisions,
                    (1, MAX_CUBE_SUBDIVISIONS),
                    n.saturating_mul(n).saturating_mul(12),
                )?;
            }
            ShapeDescription::Sphere { radius, segments } => {
                length(&field("shape.radius"), *radius)?;
                let n = u64::from(*segments);
                resolution(
                    &field("shape.segments"),
                    *segments,
                    (MIN_SPHERE_SEGMENTS, MAX_SPHERE_SEGMENTS),
                    n.saturating_mul((n / 2).max(2) - 1).saturating_mul(2),
                )?;
            }
            ShapeDescription::Model { path } => {
                if path.is_empty() {
                    return Err(value_error(field("shape.path"), "must not be empty"));
                }
            }
        }
        match &self.texture {
            Some(TextureDescription::Checker { squares, colors }) => {
                if !(1..=MAX_CHECKER_SQUARES).contains(squares) {
                    return Err(value_error(
                        field("texture.squares"),
                        format!("must be in 1..={MAX_CHECKER_SQUARES}, got {squares}"),
                    ));
                }
                for color in colors {
                    unit_color(&field("texture.colors"), *color)?;
                }
            }
            Some(TextureDescription::Image { path }) if path.is_empty() => {
                return Err(value_error(field("texture.path"), "must not be empty"));
            }
            _ => {}
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
