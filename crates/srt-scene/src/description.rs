//! Scene files: the TOML model of a scene ([`SceneDescription`]), its validation, and building the
//! runtime [`Scene`] the renderers consume.
//!
//! A description is what a user writes, what the built-in scenes are, and what the interactive
//! viewer edits and saves: [`SceneDescription::from_toml_str`] and
//! [`SceneDescription::to_toml_string`] round-trip. [`SceneDescription::build`] checks every
//! value, creates the procedural shapes, loads models and textures (relative to the scene file's
//! folder, or from the binary for `builtin:` paths) and places everything. The format is
//! documented with examples in `docs/scene-format.md`.
//!
//! Conventions: c = 1, so times are given as ct in the same length unit as positions; β is the
//! velocity in units of c; the observer and the light rest in S; each object rests in its own
//! frame S′ whose origin is at `offset` in S at t = t′ = 0. The default up direction is +z.

use std::fmt;
use std::path::Path;
use std::sync::Arc;

use glam::{DMat4, DQuat, DVec3};
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};
use srt_color::ToneMap;
use srt_physics::{Frame, FrameError};

use crate::assets;
use crate::import::ImportError;
use crate::mesh::{Material, MeshError, Part, Texture};
use crate::scene::{Effects, Light, Object, Observer, Scene, Shading};
use crate::shapes::{self, MAX_CUBE_SUBDIVISIONS, MAX_SPHERE_SEGMENTS, MIN_SPHERE_SEGMENTS};
use crate::textures::{self, DEFAULT_CHECKER_COLORS, DEFAULT_CHECKER_SQUARES, MAX_CHECKER_SQUARES};

/// Up direction of the observer's camera when a scene file gives none: +z.
pub const DEFAULT_UP: [f64; 3] = [0.0, 0.0, 1.0];

/// Vertical field of view in degrees when a scene file gives none.
pub const DEFAULT_FOV_Y_DEG: f64 = 45.0;

/// Temperature of the light in kelvin when a scene file gives none.
pub const DEFAULT_LIGHT_TEMPERATURE_K: f64 = 6000.0;

/// Edge length of a cube when a scene file gives none.
pub const DEFAULT_CUBE_SIZE: f64 = 1.0;

/// Subdivisions per cube edge when a scene file gives none (2 triangles per face).
pub const DEFAULT_CUBE_SUBDIVISIONS: u32 = 1;

/// Radius of a sphere when a scene file gives none.
pub const DEFAULT_SPHERE_RADIUS: f64 = 1.0;

/// Slices around a sphere when a scene file gives none.
pub const DEFAULT_SPHERE_SEGMENTS: u32 = 32;

/// Bounding-sphere radius (in S′ units) of an object placed with `fit = true`.
pub const FIT_RADIUS: f64 = 1.0;

// ------------------------------------------------------------------------------------------------
// Errors
// ------------------------------------------------------------------------------------------------

/// Why a scene could not be loaded or built: where (the file, or the scene's name) and why.
///
/// Its message names both, e.g. `scenes/cube.toml: line 4, column 1: unknown field `colour`, …`
/// or `scene "demo": object "probe" has an invalid velocity or offset: speed |β| = 1.2 is not
/// below the speed of light (it must be < 1)`.
#[derive(Debug, thiserror::Error)]
#[error("{origin}: {kind}")]
pub struct SceneError {
    origin: String,
    kind: Box<SceneErrorKind>,
}

impl SceneError {
    /// An error about `origin` (a file path or a scene name, as it should appear in messages).
    #[must_use]
    pub fn new(origin: impl Into<String>, kind: SceneErrorKind) -> Self {
        Self {
            origin: origin.into(),
            kind: Box::new(kind),
        }
    }

    /// Where the error is: the scene file, or `scene "name"` for a description not read from a
    /// file.
    #[must_use]
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// What is wrong.
    #[must_use]
    pub fn kind(&self) -> &SceneErrorKind {
        &self.kind
    }

    /// The same error, said to be about `origin` instead.
    #[must_use]
    pub fn with_origin(self, origin: impl Into<String>) -> Self {
        Self {
            origin: origin.into(),
            kind: self.kind,
        }
    }
}

/// The reason part of a [`SceneError`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneErrorKind {
    /// The scene file could not be read.
    #[error("cannot read the scene file: {0}")]
    Io(std::io::Error),
    /// The text is not valid TOML, or does not fit the format (unknown key, wrong type, missing
    /// key…). Line and column count from 1; columns count characters.
    #[error("line {line}, column {column}: {message}")]
    Syntax {
        /// Line of the offending text.
        line: usize,
        /// Column (in characters) of the offending text.
        column: usize,
        /// What the parser found wrong.
        message: String,
    },
    /// A value is out of its range or inconsistent with another one.
    #[error("{field} {reason}")]
    Value {
        /// The value concerned, e.g. `observer.fov_y_deg` or `shape.size of object "cube"`.
        field: String,
        /// What is wrong with it, e.g. `must be in (0, 180) degrees, got 200`.
        reason: String,
    },
    /// An object's velocity or offset is not usable (|β| ≥ 1, NaN…).
    #[error("{object} has an invalid velocity or offset: {error}")]
    Frame {
        /// The object, e.g. `object "probe"` or `object 3`.
        object: String,
        /// What [`Frame::new`] rejected.
        error: FrameError,
    },
    /// An object's model file could not be loaded (the message names the file).
    #[error("{object}: {error}")]
    Model {
        /// The object, e.g. `object "ship"`.
        object: String,
        /// The import error, naming the model file.
        error: ImportError,
    },
    /// Placing an object's geometry produced an invalid mesh (a transform with huge values).
    #[error("{object}: {error}")]
    Mesh {
        /// The object.
        object: String,
        /// What is wrong with the mesh.
        error: MeshError,
    },
}

/// Line and column (both from 1, the column in characters) of byte offset `offset` in `text`.
#[must_use]
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

fn value_error(field: impl Into<String>, reason: impl Into<String>) -> SceneErrorKind {
    SceneErrorKind::Value {
        field: field.into(),
        reason: reason.into(),
    }
}

// ------------------------------------------------------------------------------------------------
// The description
// ------------------------------------------------------------------------------------------------

/// A scene as written in a TOML scene file (see `docs/scene-format.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDescription {
    /// Name of the scene (defaults to the file stem).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text describing the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The observer (the camera) at rest in S.
    pub observer: ObserverDescription,
    /// The light at rest in S; without one, a light of [`DEFAULT_LIGHT_TEMPERATURE_K`] sits at
    /// the observer's position.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub light: Option<LightDescription>,
    /// Effect mode, tone map, background and Phong factors.
    #[serde(default)]
    pub render: RenderDescription,
    /// The moving objects (`[[object]]` tables).
    #[serde(default, rename = "object", skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<ObjectDescription>,
}

/// The `[observer]` table: a pinhole camera at rest in S, observing at time `ct`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObserverDescription {
    /// Position in S.
    pub position: [f64; 3],
    /// A point in S the camera looks at (give this or `direction`, not both).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub look_at: Option<[f64; 3]>,
    /// Viewing direction in S (give this or `look_at`, not both).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f64; 3]>,
    /// Approximate up direction of the image (default +z).
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Vertical field of view in degrees, in (0, 180).
    #[serde(default = "default_fov")]
    pub fov_y_deg: f64,
    /// Observation time ct (c = 1, same unit as positions).
    #[serde(default)]
    pub ct: f64,
}

/// The `[light]` table: a point light at rest in S radiating a Planck spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDescription {
    /// Position in S.
    pub position: [f64; 3],
    /// Black-body temperature in kelvin (> 0).
    #[serde(default = "default_temperature")]
    pub temperature_k: f64,
}

/// The `[render]` table: effect mode, tone map, background and Phong factors (Eq. 18).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderDescription {
    /// Which relativistic effects the colours show.
    #[serde(default, with = "effects_name")]
    pub effects: Effects,
    /// Colour table; `None` means the effect mode's ([`Effects::default_tone_map`]).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "tone_map_name"
    )]
    pub tone_map: Option<ToneMap>,
    /// Display colour (sRGB, components in [0, 1]) where no object is seen.
    #[serde(default)]
    pub background: [f64; 3],
    /// Ambient term (`f_amb` of Eq. 18).
    #[serde(default = "default_ambient")]
    pub ambient: f64,
    /// Diffuse weight.
    #[serde(default = "default_diffuse")]
    pub diffuse: f64,
    /// Specular weight.
    #[serde(default = "default_specular")]
    pub specular: f64,
    /// Phong exponent.
    #[serde(default = "default_shininess")]
    pub shininess: f64,
}

impl Default for RenderDescription {
    fn default() -> Self {
        let shading = Shading::default();
        Self {
            effects: Effects::default(),
            tone_map: None,
            background: [0.0; 3],
            ambient: shading.ambient,
            diffuse: shading.diffuse,
            specular: shading.specular,
            shininess: shading.shininess,
        }
    }
}

/// One `[[object]]` table: a rigid object at rest in its own frame S′.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDescription {
    /// Name for messages and listings (default `object N`, counting from 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// What the object is: a cube, a sphere or a model file.
    pub shape: ShapeDescription,
    /// Centre the shape at the S′ origin and scale it to a bounding-sphere radius of
    /// [`FIT_RADIUS`] before `scale`, `rotate_deg` and `translate` apply.
    #[serde(default, skip_serializing_if = "is_false")]
    pub fit: bool,
    /// Texture replacing the shape's own (a checkerboard or an image file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureDescription>,
    /// Base colour (sRGB, components in [0, 1]) multiplied with the texture; default white.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f64; 3]>,
    /// Draw triangle edges of this width (in S′ units) instead of the texture.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wireframe: Option<f64>,
    /// Velocity of S′ relative to S in units of c (|β| < 1).
    #[serde(default)]
    pub beta: [f64; 3],
    /// Position in S of the S′ origin at t = t′ = 0 (the paper's **a**).
    #[serde(default)]
    pub offset: [f64; 3],
    /// Rest-frame translation, applied last.
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub translate: [f64; 3],
    /// Rest-frame rotation in degrees about the x, then the y, then the z axis (fixed axes),
    /// applied after `scale`.
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub rotate_deg: [f64; 3],
    /// Rest-frame scale (a number or one factor per axis, all > 0), applied first.
    #[serde(default, skip_serializing_if = "Scale::is_one")]
    pub scale: Scale,
}

/// The `shape` of an object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum ShapeDescription {
    /// An axis-aligned cube centred at the S′ origin ([`shapes::cube`]).
    Cube {
        /// Edge length.
        #[serde(default = "default_cube_size")]
        size: f64,
        /// Squares per edge of each face (2·n² triangles per face).
        #[serde(default = "default_cube_subdivisions")]
        subdivisions: u32,
    },
    /// A latitude–longitude sphere centred at the S′ origin ([`shapes::uv_sphere`]).
    Sphere {
        /// Radius.
        #[serde(default = "default_sphere_radius")]
        radius: f64,
        /// Slices around the z axis (rings: half as many).
        #[serde(default = "default_sphere_segments")]
        segments: u32,
    },
    /// A model file (glTF, GLB, OBJ, PLY, STL), relative to the scene file's folder, or
    /// `builtin:NAME` for a model embedded in the program.
    Model {
        /// The file.
        path: String,
    },
}

/// An object's `texture`: `"checker"`, `{ type = "checker", squares = 8, colors = [...] }`,
/// `{ type = "image", path = "wood.png" }` or just the image path as a string.
#[derive(Debug, Clone, PartialEq)]
pub enum TextureDescription {
    /// A checkerboard with `squares` × `squares` squares on each texture (each cube face).
    Checker {
        /// Squares along each edge.
        squares: u32,
        /// The two colours (sRGB, components in [0, 1]); the top-left square has the first.
        colors: [[f64; 3]; 2],
    },
    /// An image file (PNG, JPEG, BMP, TGA), relative to the scene file's folder, or
    /// `builtin:NAME`.
    Image {
        /// The file.
        path: String,
    },
}

impl TextureDescription {
    /// The default checkerboard ([`DEFAULT_CHECKER_SQUARES`] squares, black and white).
    #[must_use]
    pub const fn checker() -> Self {
        Self::Checker {
            squares: DEFAULT_CHECKER_SQUARES,
            colors: DEFAULT_CHECKER_COLORS,
        }
    }
}

/// Serde mirror of [`TextureDescription`] in its table form.
#[derive(Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
enum TextureTable {
    Checker {
        #[serde(default = "default_checker_squares")]
        squares: u32,
        #[serde(default = "default_checker_colors")]
        colors: [[f64; 3]; 2],
    },
    Image {
        path: String,
    },
}

impl Serialize for TextureDescription {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            _ if *self == Self::checker() => serializer.serialize_str("checker"),
            Self::Checker { squares, colors } => TextureTable::Checker {
                squares: *squares,
                colors: *colors,
            }
            .serialize(serializer),
            Self::Image { path } => {
                TextureTable::Image { path: path.clone() }.serialize(serializer)
            }
        }
    }
}

impl<'de> Deserialize<'de> for TextureDescription {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TextureVisitor;
        impl<'de> Visitor<'de> for TextureVisitor {
            type Value = TextureDescription;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(
                    "\"checker\", an image path, or a table with type = \"checker\" or \"image\"",
                )
            }
            fn visit_str<E: de::Error>(self, value: &str) -> Result<Self::Value, E> {
                if value.is_empty() {
                    Err(E::custom("the texture path is empty"))
                } else if value == "checker" {
                    Ok(TextureDescription::checker())
                } else {
                    Ok(TextureDescription::Image {
                        path: value.to_owned(),
                    })
                }
            }
            fn visit_map<M: MapAccess<'de>>(self, map: M) -> Result<Self::Value, M::Error> {
                Ok(
                    match TextureTable::deserialize(de::value::MapAccessDeserializer::new(map))? {
                        TextureTable::Checker { squares, colors } => {
                            TextureDescription::Checker { squares, colors }
                        }
                        TextureTable::Image { path } => TextureDescription::Image { path },
                    },
                )
            }
        }
        deserializer.deserialize_any(TextureVisitor)
    }
}

/// An object's rest-frame `scale`: one factor, or one per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    /// The same factor on every axis.
    Uniform(f64),
    /// Factors for x, y and z.
    PerAxis([f64; 3]),
}

impl Default for Scale {
    fn default() -> Self {
        Self::Uniform(1.0)
    }
}

impl Scale {
    /// The factors for x, y and z.
    #[must_use]
    pub const fn factors(self) -> DVec3 {
        match self {
            Self::Uniform(s) => DVec3::splat(s),
            Self::PerAxis([x, y, z]) => DVec3::new(x, y, z),
        }
    }

    /// Whether this is the identity (written as nothing when saving).
    fn is_one(&self) -> bool {
        *self == Self::Uniform(1.0)
    }
}

impl Serialize for Scale {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match *self {
            Self::Uniform(s) => serializer.serialize_f64(s),
            Self::PerAxis(v) => {
                let mut seq = serializer.serialize_seq(Some(3))?;
                for c in v {
                    seq.serialize_element(&c)?;
                }
                seq.end()
            }
        }
    }
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ScaleVisitor;
        impl<'de> Visitor<'de> for ScaleVisitor {
            type Value = Scale;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number or an array of three numbers")
            }
            fn visit_f64<E: de::Error>(self, value: f64) -> Result<Self::Value, E> {
                Ok(Scale::Uniform(value))
            }
            #[expect(
                clippy::cast_precision_loss,
                reason = "scale factors are small numbers"
            )]
            fn visit_i64<E: de::Error>(self, value: i64) -> Result<Self::Value, E> {
                Ok(Scale::Uniform(value as f64))
            }
            #[expect(
                clippy::cast_precision_loss,
                reason = "scale factors are small numbers"
            )]
            fn visit_u64<E: de::Error>(self, value: u64) -> Result<Self::Value, E> {
                Ok(Scale::Uniform(value as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut v = [0.0; 3];
                for (i, c) in v.iter_mut().enumerate() {
                    *c = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &self))?;
                }
                if seq.next_element::<f64>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &self));
                }
                Ok(Scale::PerAxis(v))
            }
        }
        deserializer.deserialize_any(ScaleVisitor)
    }
}

mod effects_name {
    //! Serde for [`Effects`] by its scene-file name.
    use serde::{Deserialize, Deserializer, Serializer, de};

    use crate::scene::Effects;

    pub(super) fn serialize<S: Serializer>(effects: &Effects, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(effects.name())
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Effects, D::Error> {
        let name = String::deserialize(d)?;
        Effects::from_name(&name).ok_or_else(|| {
            de::Error::custom(format!(
                "unknown effect mode \"{name}\"; expected \"geometry\", \"doppler\" or \"searchlight\""
            ))
        })
    }
}

mod tone_map_name {
    //! Serde for an optional [`ToneMap`] by its name.
    use serde::{Deserialize, Deserializer, Serializer, de};
    use srt_color::ToneMap;

    #[expect(
        clippy::ref_option,
        reason = "serde's serialize_with passes a reference"
    )]
    pub(super) fn serialize<S: Serializer>(
        tone_map: &Option<ToneMap>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        match tone_map {
            Some(t) => s.serialize_str(t.name()),
            None => s.serialize_none(),
        }
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<ToneMap>, D::Error> {
        let name = String::deserialize(d)?;
        ToneMap::ALL
            .into_iter()
            .find(|t| t.name() == name)
            .map(Some)
            .ok_or_else(|| {
                de::Error::custom(format!(
                    "unknown tone map \"{name}\"; expected \"luminance\" or \"searchlight\""
                ))
            })
    }
}

fn default_up() -> [f64; 3] {
    DEFAULT_UP
}
fn default_fov() -> f64 {
    DEFAULT_FOV_Y_DEG
}
fn default_temperature() -> f64 {
    DEFAULT_LIGHT_TEMPERATURE_K
}
fn default_ambient() -> f64 {
    Shading::default().ambient
}
fn default_diffuse() -> f64 {
    Shading::default().diffuse
}
fn default_specular() -> f64 {
    Shading::default().specular
}
fn default_shininess() -> f64 {
    Shading::default().shininess
}
fn default_cube_size() -> f64 {
    DEFAULT_CUBE_SIZE
}
fn default_cube_subdivisions() -> u32 {
    DEFAULT_CUBE_SUBDIVISIONS
}
fn default_sphere_radius() -> f64 {
    DEFAULT_SPHERE_RADIUS
}
fn default_sphere_segments() -> u32 {
    DEFAULT_SPHERE_SEGMENTS
}
fn default_checker_squares() -> u32 {
    DEFAULT_CHECKER_SQUARES
}
fn default_checker_colors() -> [[f64; 3]; 2] {
    DEFAULT_CHECKER_COLORS
}
#[expect(
    clippy::trivially_copy_pass_by_ref,
    reason = "serde's skip_serializing_if passes a reference"
)]
fn is_false(value: &bool) -> bool {
    !*value
}
fn is_zero3(value: &[f64; 3]) -> bool {
    *value == [0.0; 3]
}

impl ObjectDescription {
    /// An object of `shape` at rest at the S′ origin, with every other field at its default.
    #[must_use]
    pub fn new(shape: ShapeDescription) -> Self {
        Self {
            name: None,
            shape,
            fit: false,
            texture: None,
            color: None,
            wireframe: None,
            beta: [0.0; 3],
            offset: [0.0; 3],
            translate: [0.0; 3],
            rotate_deg: [0.0; 3],
            scale: Scale::default(),
        }
    }

    /// How messages name the object with index `index` (from 0) in its scene: `object "name"`,
    /// or `object N` (counting from 1) when it has no name.
    #[must_use]
    pub fn label(&self, index: usize) -> String {
        match &self.name {
            Some(name) => format!("object \"{name}\""),
            None => format!("object {}", index + 1),
        }
    }

    /// The rest-frame placement (scale, then rotation about x, y, z, then translation), not
    /// including `fit`.
    #[must_use]
    pub fn placement(&self) -> DMat4 {
        let [x, y, z] = self.rotate_deg.map(f64::to_radians);
        let rotation =
            DQuat::from_rotation_z(z) * DQuat::from_rotation_y(y) * DQuat::from_rotation_x(x);
        DMat4::from_scale_rotation_translation(
            self.scale.factors(),
            rotation,
            DVec3::from_array(self.translate),
        )
    }
}

// ------------------------------------------------------------------------------------------------
// Parsing, saving, validation
// ------------------------------------------------------------------------------------------------

impl SceneDescription {
    /// Parses a scene file's text; `source_name` (usually the file's path) names it in errors.
    ///
    /// # Errors
    /// [`SceneErrorKind::Syntax`] with the line and column of the problem for invalid TOML, an
    /// unknown key, a value of the wrong type or a missing required key. Values are not checked
    /// here: [`SceneDescription::validate`] and [`SceneDescription::build`] do that.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, SceneError> {
        toml::from_str(text).map_err(|error: toml::de::Error| {
            let (line, column) = line_column(text, error.span().map_or(0, |span| span.start));
            let message = error.message().trim_end().to_owned();
            SceneError::new(
                source_name,
                SceneErrorKind::Syntax {
                    line,
                    column,
                    message,
                },
            )
        })
    }

    /// The description as TOML text that [`SceneDescription::from_toml_str`] reads back into an
    /// equal description. Defaults are written out, except for empty optional fields.
    ///
    /// # Panics
    /// Never: every value of a description has a TOML representation.
    #[must_use]
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).expect("a scene description is always representable in TOML")
    }

    /// How errors from [`SceneDescription::build`] name this scene when it is not read from a
    /// file.
    fn origin(&self) -> String {
        match &self.name {
            Some(name) => format!("scene \"{name}\""),
            None => "scene".to_owned(),
        }
    }

    /// Checks every value that does not need a file: the observer (exactly one of `look_at` and
    /// `direction`, a non-zero direction, `up` not parallel to it, fov in (0, 180)), the light
    /// (temperature > 0), the render settings and each object (|β| < 1, sizes and scales > 0,
    /// colours in [0, 1]…). All numbers must be finite.
    ///
    /// # Errors
    /// The first problem found, naming the value (and the object) concerned.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.check()
            .map_err(|kind| SceneError::new(self.origin(), kind))
    }

    fn check(&self) -> Result<(), SceneErrorKind> {
        self.observer.check()?;
        if let Some(light) = &self.light {
            finite3("light.position", light.position)?;
            if !(light.temperature_k.is_finite() && light.temperature_k > 0.0) {
                return Err(value_error(
                    "light.temperature_k",
                    format!(
                        "must be a positive number of kelvin, got {}",
                        light.temperature_k
                    ),
                ));
            }
        }
        self.render.check()?;
        for (index, object) in self.objects.iter().enumerate() {
            object.check(&object.label(index))?;
        }
        Ok(())
    }

    /// Validates the description and builds the runtime scene: shapes are generated, models and
    /// textures loaded (paths relative to `base_dir`, or embedded for `builtin:` paths), objects
    /// placed in their rest frames. Returns the scene and the warnings met on the way (a missing
    /// texture image, problems the model importer could work around, a scene without objects…).
    ///
    /// The scene's name is `name`, or `"untitled"`.
    ///
    /// # Errors
    /// [`SceneError`] for every problem [`SceneDescription::validate`] finds, a model file that
    /// is missing or cannot be loaded (the message names it), or a placement that produces
    /// non-finite geometry.
    pub fn build(&self, base_dir: &Path) -> Result<(Scene, Vec<String>), SceneError> {
        let fail = |kind| SceneError::new(self.origin(), kind);
        self.check().map_err(fail)?;
        let mut warnings = Vec::new();
        let observer = self.observer.to_observer();
        let light = self.light.as_ref().map_or(
            Light {
                position: observer.position,
                temperature_k: DEFAULT_LIGHT_TEMPERATURE_K,
            },
            |l| Light {
                position: DVec3::from_array(l.position),
                temperature_k: l.temperature_k,
            },
        );
        let objects = self
            .objects
            .iter()
            .enumerate()
            .map(|(index, object)| object.build(index, base_dir, &mut warnings))
            .collect::<Result<Vec<_>, _>>()
            .map_err(fail)?;
        if objects.is_empty() {
            warnings.push("the scene has no objects".to_owned());
        }
        let render = &self.render;
        let scene = Scene {
            name: self.name.clone().unwrap_or_else(|| "untitled".to_owned()),
            objects,
            observer,
            light,
            shading: Shading {
                ambient: render.ambient,
                diffuse: render.diffuse,
                specular: render.specular,
                shininess: render.shininess,
            },
            effects: render.effects,
            tone_map: render
                .tone_map
                .unwrap_or_else(|| render.effects.default_tone_map()),
            background: DVec3::from_array(render.background),
        };
        Ok((scene, warnings))
    }
}

/// Reads, parses and builds the scene file at `path`; model and texture paths in it are relative
/// to its folder. Returns the scene (named after the file stem unless the file gives a name), the
/// description (for editing and saving) and the warnings.
///
/// # Errors
/// [`SceneError`] naming the file: it cannot be read, it is not a valid scene file (with line and
/// column), or [`SceneDescription::build`] fails.
pub fn load_scene_file(path: &Path) -> Result<(Scene, SceneDescription, Vec<String>), SceneError> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError::new(origin.clone(), SceneErrorKind::Io(e)))?;
    let description = SceneDescription::from_toml_str(&text, &origin)?;
    let base_dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let (mut scene, warnings) = description
        .build(base_dir)
        .map_err(|e| e.with_origin(origin.clone()))?;
    if description.name.is_none()
        && let Some(stem) = path.file_stem()
    {
        scene.name = stem.to_string_lossy().into_owned();
    }
    Ok((scene, description, warnings))
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

fn positive(field: &str, value: f64) -> Result<(), SceneErrorKind> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(value_error(
            field,
            format!("must be a positive number, got {value}"),
        ))
    }
}

fn non_negative(field: &str, value: f64) -> Result<(), SceneErrorKind> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(value_error(
            field,
            format!("must be a number ≥ 0, got {value}"),
        ))
    }
}

impl ObserverDescription {
    /// The viewing direction (from `direction`, or from `position` to `look_at`), unnormalised.
    /// `None` if neither or both are given.
    #[must_use]
    pub fn view_direction(&self) -> Option<DVec3> {
        match (self.look_at, self.direction) {
            (Some(target), None) => {
                Some(DVec3::from_array(target) - DVec3::from_array(self.position))
            }
            (None, Some(direction)) => Some(DVec3::from_array(direction)),
            _ => None,
        }
    }

    fn check(&self) -> Result<(), SceneErrorKind> {
        finite3("observer.position", self.position)?;
        let direction = match (self.look_at, self.direction) {
            (Some(target), None) => {
                finite3("observer.look_at", target)?;
                DVec3::from_array(target) - DVec3::from_array(self.position)
            }
            (None, Some(direction)) => finite3("observer.direction", direction)?,
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
        let up = finite3("observer.up", self.up)?
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
                format!("must be in (0, 180) degrees, got {}", self.fov_y_deg),
            ));
        }
        if !self.ct.is_finite() {
            return Err(value_error(
                "observer.ct",
                format!("must be finite, got {}", self.ct),
            ));
        }
        Ok(())
    }

    /// The runtime observer, with unit `direction` and `up`; only valid after `check`.
    fn to_observer(&self) -> Observer {
        let direction = self
            .view_direction()
            .unwrap_or(DVec3::NEG_Y)
            .normalize_or(DVec3::NEG_Y);
        Observer {
            position: DVec3::from_array(self.position),
            direction,
            up: DVec3::from_array(self.up).normalize_or(DVec3::Z),
            fov_y_deg: self.fov_y_deg,
            ct: self.ct,
        }
    }
}

impl RenderDescription {
    fn check(&self) -> Result<(), SceneErrorKind> {
        unit_color("render.background", self.background)?;
        non_negative("render.ambient", self.ambient)?;
        non_negative("render.diffuse", self.diffuse)?;
        non_negative("render.specular", self.specular)?;
        non_negative("render.shininess", self.shininess)
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
        match &self.shape {
            ShapeDescription::Cube { size, subdivisions } => {
                positive(&field("shape.size"), *size)?;
                if !(1..=MAX_CUBE_SUBDIVISIONS).contains(subdivisions) {
                    return Err(value_error(
                        field("shape.subdivisions"),
                        format!("must be in 1..={MAX_CUBE_SUBDIVISIONS}, got {subdivisions}"),
                    ));
                }
            }
            ShapeDescription::Sphere { radius, segments } => {
                positive(&field("shape.radius"), *radius)?;
                if !(MIN_SPHERE_SEGMENTS..=MAX_SPHERE_SEGMENTS).contains(segments) {
                    return Err(value_error(
                        field("shape.segments"),
                        format!(
                            "must be in {MIN_SPHERE_SEGMENTS}..={MAX_SPHERE_SEGMENTS}, got {segments}"
                        ),
                    ));
                }
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
            positive(&field("wireframe"), width)?;
        }
        finite3(&field("translate"), self.translate)?;
        finite3(&field("rotate_deg"), self.rotate_deg)?;
        let factors = self.scale.factors();
        if !(factors.is_finite() && factors.min_element() > 0.0) {
            return Err(value_error(
                field("scale"),
                format!(
                    "must be positive (one number or three), got {:?}",
                    factors.to_array()
                ),
            ));
        }
        Ok(())
    }

    /// Builds the runtime object; only valid after `check`.
    fn build(
        &self,
        index: usize,
        base_dir: &Path,
        warnings: &mut Vec<String>,
    ) -> Result<Object, SceneErrorKind> {
        let label = self.label(index);
        let frame = Frame::new(DVec3::from_array(self.beta), DVec3::from_array(self.offset))
            .map_err(|error| SceneErrorKind::Frame {
                object: label.clone(),
                error,
            })?;
        let mut parts = match &self.shape {
            ShapeDescription::Cube { size, subdivisions } => vec![Part {
                mesh: shapes::cube(*size, *subdivisions),
                material: Material {
                    name: "cube".to_owned(),
                    ..Material::default()
                },
            }],
            ShapeDescription::Sphere { radius, segments } => vec![Part {
                mesh: shapes::uv_sphere(*radius, *segments),
                material: Material {
                    name: "sphere".to_owned(),
                    ..Material::default()
                },
            }],
            ShapeDescription::Model { path } => {
                let resolved = assets::resolve(base_dir, path)
                    .map_err(|reason| value_error(format!("shape.path of {label}"), reason))?;
                let model =
                    assets::load_model(&resolved).map_err(|error| SceneErrorKind::Model {
                        object: label.clone(),
                        error,
                    })?;
                warnings.extend(model.warnings.into_iter().map(|w| format!("{label}: {w}")));
                model.parts
            }
        };
        if let Some(texture) = self.texture(base_dir, &label, warnings) {
            for part in &mut parts {
                part.material.texture = Some(Arc::clone(&texture));
            }
        }
        if let Some(color) = self.color {
            for part in &mut parts {
                for (channel, factor) in part.material.base_color.iter_mut().zip(color) {
                    #[expect(clippy::cast_possible_truncation, reason = "a colour in [0, 1]")]
                    let factor = factor as f32;
                    *channel *= factor;
                }
            }
        }
        let mut transform = self.placement();
        if self.fit {
            match fit_transform(&parts) {
                Some(fit) => transform *= fit,
                None => warnings.push(format!(
                    "{label}: fit = true ignored, the shape has no extent to scale"
                )),
            }
        }
        if transform != DMat4::IDENTITY {
            parts = parts
                .into_iter()
                .map(|Part { mesh, material }| {
                    let mesh = mesh.transformed(transform)?;
                    Ok(Part { mesh, material })
                })
                .collect::<Result<_, MeshError>>()
                .map_err(|error| SceneErrorKind::Mesh {
                    object: label.clone(),
                    error,
                })?;
        }
        Ok(Object {
            name: self.name.clone().unwrap_or(label),
            parts,
            frame,
            wireframe: self.wireframe,
        })
    }

    /// The texture this object asks for; `None` (with a warning) if its image cannot be loaded.
    fn texture(
        &self,
        base_dir: &Path,
        label: &str,
        warnings: &mut Vec<String>,
    ) -> Option<Arc<Texture>> {
        match self.texture.as_ref()? {
            TextureDescription::Checker { squares, colors } => Some(Arc::new(textures::checker(
                textures::checker_resolution(*squares),
                *squares,
                colors[0],
                colors[1],
            ))),
            TextureDescription::Image { path } => {
                let loaded = assets::resolve(base_dir, path).and_then(|r| assets::load_texture(&r));
                match loaded {
                    Ok(texture) => Some(Arc::new(texture)),
                    Err(error) => {
                        let fallback = if matches!(self.shape, ShapeDescription::Model { .. }) {
                            "the model's own materials are used"
                        } else {
                            "the base colour is used"
                        };
                        warnings.push(format!(
                            "{label}: texture \"{path}\" cannot be loaded ({error}); {fallback}"
                        ));
                        None
                    }
                }
            }
        }
    }
}

/// The transform that centres `parts` (their bounding box) at the origin and scales them to a
/// bounding-sphere radius of [`FIT_RADIUS`]; `None` if they have no extent.
#[must_use]
pub fn fit_transform(parts: &[Part]) -> Option<DMat4> {
    let (lo, hi) = parts
        .iter()
        .map(|p| p.mesh.bounds())
        .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))?;
    let centre = 0.5 * (lo + hi);
    let radius = parts
        .iter()
        .flat_map(|p| p.mesh.positions())
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max);
    (radius.is_finite() && radius > 0.0).then(|| {
        DMat4::from_scale(DVec3::splat(FIT_RADIUS / radius)) * DMat4::from_translation(-centre)
    })
}
