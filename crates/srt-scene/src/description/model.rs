//! The serde model of a scene file: the description types, their defaults, the custom forms of
//! `texture` and `scale`, and parsing and saving TOML text.

use std::fmt;

use glam::{DMat4, DQuat, DVec3};
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};

use crate::projection::{Projection, Stereo};
use crate::scene::DEFAULT_CUBE_MAP_SIZE;
use srt_color::ToneMap;
use srt_physics::motion::{Motion, Spin, Thrust};

#[cfg(doc)]
use super::FIT_RADIUS;
use super::error::{SceneError, SceneErrorKind, line_column};
use super::{
    DEFAULT_CUBE_SIZE, DEFAULT_CUBE_SUBDIVISIONS, DEFAULT_FOV_Y_DEG, DEFAULT_LIGHT_TEMPERATURE_K,
    DEFAULT_SPHERE_RADIUS, DEFAULT_SPHERE_SEGMENTS, DEFAULT_UP,
};
use crate::scene::{
    Blink, DEFAULT_CLOCK_COLORS, DEFAULT_CLOCK_DIAL, Effects, Shading, SurfaceColour,
};
#[cfg(doc)]
use crate::shapes;
use crate::textures::{DEFAULT_CHECKER_COLORS, DEFAULT_CHECKER_SQUARES};

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
    /// The observer (the camera), moving with `observer.beta` through the scene's world frame.
    pub observer: ObserverDescription,
    /// The lights: `[light]`, the lamp at rest relative to the observer, or `[[light]]`, any
    /// number of lights, each carried by the observer or on its own worldline. Without the key a
    /// lamp of [`DEFAULT_LIGHT_TEMPERATURE_K`] sits at the observer's position.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub light: Option<LightsDescription>,
    /// Effect mode, tone map, background and Phong factors.
    #[serde(default)]
    pub render: RenderDescription,
    /// The moving objects (`[[object]]` tables).
    #[serde(default, rename = "object", skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<ObjectDescription>,
    /// Stars at infinity, at rest in the world frame (`[sky]`); none without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky: Option<SkyDescription>,
}

/// An object's `emission`: a black body of `temperature_k`, `brightness` times the luminance
/// tone map's white.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EmissionDescription {
    /// Black-body temperature in kelvin (> 0).
    pub temperature_k: f64,
    /// Brightness (≥ 0; 1 = the white of the luminance tone map).
    #[serde(default = "default_brightness")]
    pub brightness: f64,
    /// Blinking in the object's proper time (`blink = { period, duty }`; none: always on).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blink: Option<Blink>,
}

/// The `[sky]` table: stars at infinity at rest in the world frame W — the built-in star field,
/// stars from a CSV file, or both — and an image of the sky behind them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkyDescription {
    /// Stars of the built-in synthetic star field (0: none).
    #[serde(default, skip_serializing_if = "is_zero_count")]
    pub star_field: usize,
    /// A CSV file of stars (path relative to the scene file; docs/scene-format.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stars: Option<String>,
    /// A star of this visual magnitude at rest fills one pixel with its full colour.
    #[serde(default = "default_saturation_magnitude")]
    pub saturation_magnitude: f64,
    /// An equirectangular image of the sky (EXR or Radiance HDR; path relative to the scene
    /// file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<String>,
    /// Factor on the image's radiance (> 0).
    #[serde(default = "default_brightness")]
    pub image_brightness: f64,
}

/// The `[observer]` table: a pinhole camera moving with `beta` through the world frame W, at
/// `position` at W's time `ct`, where its own clock reads `ct`; it looks when its clock reads
/// `time` (default `ct`). Its orientation is given in its own rest frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObserverDescription {
    /// Position in W at the observation event.
    pub position: [f64; 3],
    /// A point the camera looks at: `look_at − position` is the viewing direction in the
    /// observer's rest frame (give this or `direction`, not both).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub look_at: Option<[f64; 3]>,
    /// Viewing direction in the observer's rest frame (give this or `look_at`, not both).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f64; 3]>,
    /// The observer's velocity relative to W in units of c (|β| < 1; default at rest).
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub beta: [f64; 3],
    /// Approximate up direction of the image, in the observer's rest frame (default +z).
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Vertical field of view in degrees, in (0, 180).
    #[serde(default = "default_fov")]
    pub fov_y_deg: f64,
    /// W's time ct at which the observer is at `position` (c = 1, same unit as positions); its
    /// own clock reads `ct` there.
    #[serde(default)]
    pub ct: f64,
    /// The observation time: the observer's own clock when it looks (`None`: `ct`). Between
    /// `ct` and `time` the observer moves along its worldline; for an observer at rest in W
    /// both are W's time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
    /// How the image maps its points to viewing directions (`None`: the pinhole of
    /// `fov_y_deg`); docs/scene-format.md, "Projections".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projection: Option<Projection>,
    /// The ride: from its own clock's `start` on, the observer accelerates Born-rigidly (the
    /// hyperbolic worldline of an object's `thrust`, in the observer's rest frame at
    /// (`ct`, `position`), along `observer.beta` when it moves), then coasts; each picture is
    /// drawn from its event and velocity when its clock reads `time` (docs/scene-format.md,
    /// "The ride").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thrust: Option<ThrustDescription>,
    /// Two eyes in one picture: top-bottom for the equirectangular projection, side by side for
    /// the pinhole (docs/scene-format.md, "Projections").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stereo: Option<Stereo>,
}

/// One light table: a point light radiating a Planck spectrum. The lamp (`[light]`, or a
/// `[[light]]` entry with `carried = true`) rests relative to the observer and lights with the
/// paper's constant strength (ambient term included); every other `[[light]]` entry moves on
/// its own worldline and falls off with the inverse square of the distance in its rest frame
/// (docs/physics.md, "Moving lights").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDescription {
    /// The lamp's position in W at W's time `observer.ct`; a moving light's
    /// position in W at t = 0.
    pub position: [f64; 3],
    /// Black-body temperature in kelvin (> 0).
    #[serde(default = "default_temperature")]
    pub temperature_k: f64,
    /// Multiplier on the light (≥ 0; default 1). A moving light of strength s gives a surface
    /// facing it at distance r (in the light's rest frame) s / r² of the lamp's diffuse light.
    #[serde(default = "default_strength", skip_serializing_if = "is_one")]
    pub strength: f64,
    /// A moving light's velocity relative to W in units of c (|β| < 1; default at rest in W).
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub beta: [f64; 3],
    /// In a `[[light]]` list: this entry is the lamp the observer carries (at most one).
    #[serde(default, skip_serializing_if = "is_false")]
    pub carried: bool,
}

impl LightDescription {
    /// A `[light]` table: the lamp carried by the observer at `position` (W, at the
    /// observation time), of strength 1.
    #[must_use]
    pub fn lamp(position: [f64; 3], temperature_k: f64) -> Self {
        Self {
            position,
            temperature_k,
            strength: 1.0,
            beta: [0.0; 3],
            carried: false,
        }
    }

    /// Whether this table is the lamp: a `[light]` table (`in_list` false) or a carried entry.
    #[must_use]
    pub fn is_lamp(&self, in_list: bool) -> bool {
        !in_list || self.carried
    }
}

/// The `light` key: one `[light]` table (the lamp) or a `[[light]]` list.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum LightsDescription {
    /// `[light]`: the lamp the observer carries, the only light.
    Lamp(LightDescription),
    /// `[[light]]`: at most one carried lamp and any number of moving lights (at most
    /// [`MAX_MOVING_LIGHTS`](crate::scene::MAX_MOVING_LIGHTS)); without a carried entry there
    /// is no lamp (and no ambient light).
    List(Vec<LightDescription>),
}

impl LightsDescription {
    /// The lamp, if there is one.
    #[must_use]
    pub fn lamp(&self) -> Option<&LightDescription> {
        match self {
            Self::Lamp(lamp) => Some(lamp),
            Self::List(lights) => lights.iter().find(|l| l.carried),
        }
    }

    /// The lamp, mutably, if there is one.
    pub fn lamp_mut(&mut self) -> Option<&mut LightDescription> {
        match self {
            Self::Lamp(lamp) => Some(lamp),
            Self::List(lights) => lights.iter_mut().find(|l| l.carried),
        }
    }

    /// The moving lights (the entries of a list that are not carried), in order.
    pub fn moving(&self) -> impl Iterator<Item = &LightDescription> {
        let list = match self {
            Self::Lamp(_) => &[][..],
            Self::List(lights) => lights.as_slice(),
        };
        list.iter().filter(|l| !l.carried)
    }
}

impl<'de> Deserialize<'de> for LightsDescription {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct LightsVisitor;
        impl<'de> Visitor<'de> for LightsVisitor {
            type Value = LightsDescription;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a [light] table or [[light]] tables")
            }
            fn visit_map<M: MapAccess<'de>>(self, map: M) -> Result<Self::Value, M::Error> {
                LightDescription::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(LightsDescription::Lamp)
            }
            fn visit_seq<S: SeqAccess<'de>>(self, seq: S) -> Result<Self::Value, S::Error> {
                Vec::<LightDescription>::deserialize(de::value::SeqAccessDeserializer::new(seq))
                    .map(LightsDescription::List)
            }
        }
        deserializer.deserialize_any(LightsVisitor)
    }
}

/// The `[render]` table: effect mode, tone map, background and Phong factors (Eq. 18).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderDescription {
    /// Which relativistic effects the colours show.
    #[serde(default, with = "crate::choice::by_name")]
    pub effects: Effects,
    /// Colour table; `None` means the effect mode's ([`Effects::default_tone_map`]).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::choice::by_optional_name"
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
    /// How lit surfaces are coloured: the paper's shortcut or spectral reflectance.
    #[serde(default, with = "crate::choice::by_name")]
    pub colour: SurfaceColour,
    /// Multiplier on the light before the tone map (> 0; only with spectral colour).
    #[serde(default = "default_exposure")]
    pub exposure: f64,
    /// Whether objects cast the moving lights' shadows (default true).
    #[serde(default = "default_true", skip_serializing_if = "is_true")]
    pub shadows: bool,
    /// The side in texels of each face of the image-based method's cube map (≥ 1).
    #[serde(
        default = "default_cube_map_size",
        skip_serializing_if = "is_default_cube_map_size"
    )]
    pub cube_map_size: u32,
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
            colour: SurfaceColour::default(),
            exposure: 1.0,
            shadows: true,
            cube_map_size: DEFAULT_CUBE_MAP_SIZE,
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
    /// Velocity of S′ relative to W in units of c (|β| < 1).
    #[serde(default)]
    pub beta: [f64; 3],
    /// Position in W of the S′ origin at t = t′ = 0 (the paper's **a**).
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
    /// Reflectance below 380 nm, in [0, 1] (spectral colour; default: the model's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ultraviolet: Option<f64>,
    /// Reflectance above 780 nm, in [0, 1] (spectral colour; default: the model's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub infrared: Option<f64>,
    /// The object glows as a black body instead of reflecting the light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission: Option<EmissionDescription>,
    /// The object spins in its rest frame (not together with `thrust`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin: Option<SpinDescription>,
    /// The object accelerates Born-rigidly in its rest frame (not together with `spin`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thrust: Option<ThrustDescription>,
}

/// An object's `spin`: kinematic rotation in its rest frame S′ about the line through `centre`
/// along `axis`, `rate` radians per unit of ct′ (right-handed); docs/physics.md.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpinDescription {
    /// The axis direction (non-zero), in S′ (the object's placed coordinates).
    pub axis: [f64; 3],
    /// ω in radians per unit of ct′; every point's speed ω·(distance from the axis) must stay
    /// below 1.
    pub rate: f64,
    /// A point of the axis, in S′.
    #[serde(default)]
    pub centre: [f64; 3],
}

/// An object's `thrust`: from S′ time `start` on, Born-rigid acceleration with the proper
/// acceleration `proper_acceleration` at the S′ origin, for `duration` of the origin's proper
/// time (default: without end), then coasting; docs/physics.md.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThrustDescription {
    /// The origin's proper acceleration (non-zero), per unit of ct′, in S′.
    pub proper_acceleration: [f64; 3],
    /// S′ time ct′ at which the thrust starts.
    #[serde(default)]
    pub start: f64,
    /// The origin's proper time the thrust lasts (≥ 0; `inf` for ever).
    #[serde(default = "default_duration")]
    pub duration: f64,
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
    /// A flipbook: image files of one size shown one after another as the object's proper time
    /// advances, `fps` frames per unit of ct′, looping.
    Frames {
        /// The frames' files, in order (as `Image`'s path).
        files: Vec<String>,
        /// Frames per unit of proper time ct′ (> 0).
        fps: f64,
    },
    /// A clock face showing the object's proper time where each point is seen
    /// ([`crate::Clock`]).
    Clock {
        /// Reading per unit of proper time ct′ (finite).
        rate: f64,
        /// Reading at proper time 0 (finite).
        offset: f64,
        /// Reading per turn of the slow hand (> 0).
        dial: f64,
        /// Face and ink colours (sRGB, components in [0, 1]).
        colors: [[f64; 3]; 2],
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
    Frames {
        files: Vec<String>,
        #[serde(default = "default_fps")]
        fps: f64,
    },
    Clock {
        #[serde(default = "default_clock_rate")]
        rate: f64,
        #[serde(default)]
        offset: f64,
        #[serde(default = "default_clock_dial")]
        dial: f64,
        #[serde(default = "default_clock_colors")]
        colors: [[f64; 3]; 2],
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
            Self::Frames { files, fps } => TextureTable::Frames {
                files: files.clone(),
                fps: *fps,
            }
            .serialize(serializer),
            Self::Clock {
                rate,
                offset,
                dial,
                colors,
            } => TextureTable::Clock {
                rate: *rate,
                offset: *offset,
                dial: *dial,
                colors: *colors,
            }
            .serialize(serializer),
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
                    "\"checker\", an image path, or a table with type = \"checker\", \"image\", \
                     \"frames\" or \"clock\"",
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
                        TextureTable::Frames { files, fps } => {
                            TextureDescription::Frames { files, fps }
                        }
                        TextureTable::Clock {
                            rate,
                            offset,
                            dial,
                            colors,
                        } => TextureDescription::Clock {
                            rate,
                            offset,
                            dial,
                            colors,
                        },
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

fn default_up() -> [f64; 3] {
    DEFAULT_UP
}
fn default_fov() -> f64 {
    DEFAULT_FOV_Y_DEG
}
fn default_temperature() -> f64 {
    DEFAULT_LIGHT_TEMPERATURE_K
}
fn default_duration() -> f64 {
    f64::INFINITY
}
fn default_cube_map_size() -> u32 {
    DEFAULT_CUBE_MAP_SIZE
}
#[expect(
    clippy::trivially_copy_pass_by_ref,
    reason = "serde's skip_serializing_if passes a reference"
)]
fn is_default_cube_map_size(size: &u32) -> bool {
    *size == DEFAULT_CUBE_MAP_SIZE
}
fn default_true() -> bool {
    true
}
#[expect(
    clippy::trivially_copy_pass_by_ref,
    reason = "serde's skip_serializing_if passes a reference"
)]
fn is_true(value: &bool) -> bool {
    *value
}
fn default_strength() -> f64 {
    1.0
}
#[expect(
    clippy::trivially_copy_pass_by_ref,
    reason = "serde's skip_serializing_if passes a reference"
)]
fn is_one(value: &f64) -> bool {
    *value == 1.0
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
fn default_fps() -> f64 {
    1.0
}
fn default_clock_rate() -> f64 {
    1.0
}
fn default_clock_dial() -> f64 {
    DEFAULT_CLOCK_DIAL
}
fn default_clock_colors() -> [[f64; 3]; 2] {
    DEFAULT_CLOCK_COLORS
}
#[expect(
    clippy::trivially_copy_pass_by_ref,
    reason = "serde's skip_serializing_if passes a reference"
)]
fn is_false(value: &bool) -> bool {
    !*value
}
fn default_exposure() -> f64 {
    1.0
}
fn default_brightness() -> f64 {
    1.0
}
fn default_saturation_magnitude() -> f64 {
    crate::sky::DEFAULT_SATURATION_MAGNITUDE
}
#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_zero_count(value: &usize) -> bool {
    *value == 0
}
fn is_zero3(value: &[f64; 3]) -> bool {
    *value == [0.0; 3]
}

impl ObjectDescription {
    /// The motion `spin` or `thrust` asks for, in the object's placed rest coordinates (not yet
    /// checked against its points: [`ObjectDescription::placed_motion`]).
    ///
    /// # Errors
    /// The key at fault and why: a parameter that is not finite, a zero axis or acceleration, a
    /// negative duration, or both `spin` and `thrust`.
    pub fn motion(&self) -> Result<Motion, (&'static str, String)> {
        match (self.spin, self.thrust) {
            (None, None) => Ok(Motion::Rest),
            (Some(_), Some(_)) => Err((
                "thrust",
                "an object may spin or thrust, not both".to_owned(),
            )),
            (Some(spin), None) => Spin::new(
                DVec3::from_array(spin.axis),
                spin.rate,
                DVec3::from_array(spin.centre),
            )
            .map(Motion::Spin)
            .map_err(|e| ("spin", e.to_string())),
            (None, Some(thrust)) => Thrust::new(
                DVec3::from_array(thrust.proper_acceleration),
                thrust.start,
                thrust.duration,
            )
            .map(Motion::Thrust)
            .map_err(|e| ("thrust", e.to_string())),
        }
    }

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
            ultraviolet: None,
            infrared: None,
            emission: None,
            spin: None,
            thrust: None,
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
}
