//! Scene files: the TOML model of a scene ([`SceneDescription`]), its validation, and building the
//! runtime [`Scene`](crate::scene::Scene) the renderers consume.
//!
//! A description is what a user writes, what the built-in scenes are, and what the interactive
//! viewer edits and saves: [`SceneDescription::from_toml_str`] and
//! [`SceneDescription::to_toml_string`] round-trip. [`SceneDescription::build`] checks every
//! value, creates the procedural shapes, loads models and textures (relative to the scene file's
//! folder, or from the binary for `builtin:` paths) and places everything. The format is
//! documented with examples in `docs/scene-format.md`.
//!
//! Conventions: c = 1, so times are given as ct in the same length unit as positions; β is the
//! velocity in units of c; positions, velocities and the observation event are given in the
//! scene's world frame W, through which the observer moves with `observer.beta` (default at
//! rest); each object rests in its own frame S′ whose origin is at `offset` in W at t = t′ = 0.
//! Building the scene expresses everything in the observer's rest frame S
//! ([`srt_physics::MovingObserver`]), where the light rests. The default up direction is +z.
//!
//! The module is split by concern: `error` (what can go wrong), `model` (the serde
//! model of the file), `validate` (checks that need no file, every rule once), `overrides`
//! (values front ends give in place of the scene's own, applied as edits and judged by the same
//! checks), `setting` (any key given as `KEY=VALUE`) and `build` (shapes, models, textures and placement into the runtime scene).

mod build;
mod error;
mod model;
mod overrides;
mod setting;
mod validate;

pub use build::{
    build_scene_file, fit_transform, load_scene_file, read_scene_file, scene_file_folder,
};
pub use error::{SceneError, SceneErrorKind, line_column};
pub use model::{
    EmissionDescription, LightDescription, LightsDescription, ObjectDescription,
    ObserverDescription, RenderDescription, Scale, SceneDescription, ShapeDescription,
    SkyDescription, SpinDescription, TextureDescription, ThrustDescription,
};
pub use overrides::{OverrideNames, Overrides, parse_vector};
pub use setting::Setting;
pub use validate::{ValueName, observation_time, velocity};

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
