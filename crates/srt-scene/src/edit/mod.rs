//! The editable scene: one scene state under every front end (the viewer's panel, the web page,
//! Python's `srt.Scene` and `srt render`'s animations).
//!
//! An [`Editor`] keeps two views of the scene in step: the [`SceneDescription`] (what `srt render`
//! reads and what "Save scene" writes) and the runtime [`Scene`] a renderer draws. Every edit
//! changes a copy of the description; [`SceneDescription::validate`] checks the copy with the
//! scene file's own rules and messages, and only then is the runtime scene brought in step, so a
//! refused edit leaves both as they were.
//!
//! Bringing the runtime scene in step never reads a file again (follow.rs, the one rule): each
//! runtime object remembers the geometry it was built from (its description without motion, name
//! and wireframe), and an object whose geometry is unchanged keeps its parts. Only new objects (or
//! objects whose geometry changed) are built, by [`SceneDescription::build`]. An edit of the
//! observer alone (time, camera, a flight's step: what runs every frame) builds nothing: the
//! runtime scene follows it ([`Scene::follow`]) unless the observer's new velocity turns an
//! object's geometry (the Wigner rotation). So dragging a slider or playing time costs no more
//! than a validation. [`Editor::structure_version`] tells a renderer when what it uploaded
//! ([`Scene::same_structure`]) changed.
//!
//! Time has two words (docs/scene-format.md, "Time"): `ct` is W's time at which the observer is
//! at its position, and **time** ([`Editor::time`], `observer.time`, `--time`) the observer's own
//! clock when it looks.
//!
//! Arguments and files are resolved by [`crate::resolve`], as `srt render` resolves them.

mod follow;
mod objects;
mod observer;
mod open;
mod settings;
#[cfg(test)]
mod tests;

use std::path::PathBuf;

use glam::{DMat3, DVec3};

use crate::{
    Object, ObjectDescription, Observer, ResolveError, Scene, SceneDescription, SceneError,
};

pub use objects::{offset_keeping_apparent_position, parse_speed};

/// Why an edit or a file operation was refused. The message is meant for the status line.
#[derive(Debug, thiserror::Error)]
pub enum EditError {
    /// Typed text that is not a speed (not a number, or negative).
    #[error("{0}")]
    Speed(String),
    /// A direction of motion that is zero or not finite.
    #[error("the direction of motion must be a non-zero vector, got {0}")]
    Direction(DVec3),
    /// An argument or file that names no scene or model (not found, or of another kind).
    #[error(transparent)]
    Source(#[from] ResolveError),
    /// An edit the scene file's rules refuse, or a scene or model that does not load (the
    /// message names the value or the file).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Writing a file failed.
    #[error("{path}: {error}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        error: std::io::Error,
    },
    /// An object index that does not exist.
    #[error("there is no object number {0}")]
    NoSuchObject(usize),
    /// A moving light's index that does not exist.
    #[error("there is no moving light number {0}")]
    NoSuchLight(usize),
}

/// The scene being viewed: its description (for saving) and its runtime scene (for rendering),
/// edited together.
#[derive(Debug, Clone)]
pub struct Editor {
    description: SceneDescription,
    base_dir: PathBuf,
    scene: Scene,
    /// The geometry ([`geometry_of`]) each runtime object's parts were built from, in order.
    built_from: Vec<Geometry>,
    /// Remembered unit direction of motion of each object (kept when the speed is 0).
    directions: Vec<DVec3>,
    home: Observer,
    structure_version: u64,
    /// Scenes built by edits and opened so far (an edit of the observer alone builds none).
    builds: u64,
}

/// Where each object of an edited description gets its parts: `Some(index)` of the runtime
/// object whose parts it keeps, or `None` when it must be built.
type PartsPlan = Vec<Option<usize>>;

/// What an object's parts are built from: its description without what edits change cheaply
/// (velocity, offset, name, wireframe), and the Wigner rotation its rest-frame geometry was
/// turned by (the identity unless the observer moves).
#[derive(Debug, Clone, PartialEq)]
struct Geometry {
    /// The description, cheap fields cleared.
    object: ObjectDescription,
    /// The rotation of the rest-frame geometry ([`RelativeFrame::rotation`]).
    rotation: DMat3,
}

impl Editor {
    /// The runtime scene to render.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene description (what "Save scene" writes, with paths made absolute).
    #[must_use]
    pub fn description(&self) -> &SceneDescription {
        &self.description
    }

    /// Changes whenever objects are added or removed (the meshes must then be uploaded again).
    #[must_use]
    pub const fn structure_version(&self) -> u64 {
        self.structure_version
    }

    /// Number of objects.
    #[must_use]
    pub fn object_count(&self) -> usize {
        self.scene.objects.len()
    }

    /// The objects of the scene.
    #[must_use]
    pub fn objects(&self) -> &[Object] {
        &self.scene.objects
    }

    /// How many times an edit built objects or settings, or another scene was opened in place
    /// ([`Editor::replace_with`]); following the observer builds nothing.
    #[must_use]
    pub const fn builds(&self) -> u64 {
        self.builds
    }
}
