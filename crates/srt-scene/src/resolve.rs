//! What a scene argument names, for every front end (`srt render SCENE`, `srt view SCENE…`, a
//! file dropped on the viewer): a built-in scene, a `.toml` scene file or a bare model file, with
//! one set of messages for what is none of these.
//!
//! The rule, in order: a built-in scene's name wins; otherwise the argument is a path, judged by
//! its extension (case-insensitive): `.toml` is a scene file, one of [`SUPPORTED_EXTENSIONS`] a
//! model. Any other file that exists is refused as unsupported, anything else as not found. A
//! scene or model file that turns out to be missing or invalid is reported when it is read, by a
//! [`SceneError`] that names it.
//!
//! A bare model becomes the scene of [`SceneDescription::for_model`]: fitted, in front of the
//! observer, moving with the β the caller gives or, by default, approaching at
//! [`DEFAULT_MODEL_SPEED`].
//!
//! Values a front end gives in place of the scene's own ([`Overrides`], e.g. `srt render
//! --exposure`) take one route, [`SceneSource::load_with`]: they edit the description, which is
//! then validated and built like any other.

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::builtin::{BuiltinScene, find_builtin};
pub use crate::description::scene_file_folder;
use crate::description::{
    Overrides, SceneDescription, SceneError, build_scene_file, read_scene_file,
};
use crate::import::SUPPORTED_EXTENSIONS;
use crate::placement::approach_velocity;
use crate::scene::Scene;

/// Speed of a bare model (as a fraction of c, towards the observer) when no β is given.
pub const DEFAULT_MODEL_SPEED: f64 = 0.9;

/// The extension of scene files, without the dot.
pub const SCENE_FILE_EXTENSION: &str = "toml";

/// What a path names, judged by its extension alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathKind {
    /// A scene file (`.toml`).
    SceneFile,
    /// A 3D model: one of [`SUPPORTED_EXTENSIONS`].
    Model,
    /// Anything else.
    Unsupported,
}

/// Classifies `path` by its extension (case-insensitive), without looking at the file.
#[must_use]
pub fn path_kind(path: &Path) -> PathKind {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some(SCENE_FILE_EXTENSION) => PathKind::SceneFile,
        Some(ext) if SUPPORTED_EXTENSIONS.contains(&ext) => PathKind::Model,
        _ => PathKind::Unsupported,
    }
}

/// The model extensions for messages and help texts: `.gltf, .glb, .obj, .ply, .stl`.
#[must_use]
pub fn model_extension_list() -> String {
    SUPPORTED_EXTENSIONS
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Why a scene argument names no scene.
#[derive(Debug, thiserror::Error)]
pub enum ResolveError {
    /// Neither a built-in scene's name nor an existing file.
    #[error("{0:?} is neither a built-in scene (see `srt scenes`) nor an existing file")]
    NotFound(String),
    /// A scene file or model (judged by its extension) that does not exist.
    #[error("cannot open {0}: no such file or directory")]
    NoSuchFile(String),
    /// A file that is neither a scene file nor a model, judged by its extension.
    #[error(
        "cannot open {0:?}: a scene file must end in .{SCENE_FILE_EXTENSION} and a model in one of {list}",
        list = model_extension_list()
    )]
    Unsupported(String),
    /// The scene or model was found but does not load (the message names the file).
    #[error(transparent)]
    Scene(#[from] SceneError),
}

/// What a scene argument names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SceneSource {
    /// A built-in scene.
    Builtin(&'static BuiltinScene),
    /// A scene file (it may still turn out to be missing when read).
    SceneFile(PathBuf),
    /// A model file (it may still turn out to be missing when read).
    Model(PathBuf),
}

/// A scene description and the folder its relative paths start from.
#[derive(Debug, Clone, PartialEq)]
pub struct LocatedDescription {
    /// The description.
    pub description: SceneDescription,
    /// Where its relative model and texture paths start.
    pub base_dir: PathBuf,
}

impl LocatedDescription {
    /// Loads a description that no file or built-in scene holds (scene text a script gave) with
    /// `overrides` in place of its values: validated, built from [`LocatedDescription::base_dir`]
    /// and named in messages as a bare model's scene is ([`SceneDescription::origin`]).
    ///
    /// # Errors
    /// As [`SceneSource::load_with`].
    pub fn load_with(self, overrides: &Overrides) -> Result<LoadedScene, SceneError> {
        load_overridden(self, overrides, SceneDescription::origin, build_located)
    }
}

/// Applies `overrides` to `source`'s description (judged by its validation, named by
/// `origin`) and builds it with `build`: the one route of [`Overrides`] into a scene.
fn load_overridden(
    source: LocatedDescription,
    overrides: &Overrides,
    origin: impl FnOnce(&SceneDescription) -> String,
    build: impl FnOnce(LocatedDescription) -> Result<LoadedScene, SceneError>,
) -> Result<LoadedScene, SceneError> {
    build(overridden(source, overrides, origin)?)
}

/// `source` with `overrides` applied to its description ([`Overrides::apply`]), refused by
/// the scene file's rules with the scene named by `origin`.
fn overridden(
    mut source: LocatedDescription,
    overrides: &Overrides,
    origin: impl FnOnce(&SceneDescription) -> String,
) -> Result<LocatedDescription, SceneError> {
    let origin = origin(&source.description);
    overrides
        .apply(&mut source.description, &origin)
        .map_err(|kind| SceneError::new(origin, kind))?;
    Ok(source)
}

/// Builds a description from its base folder, errors naming it by [`SceneDescription::origin`].
fn build_located(source: LocatedDescription) -> Result<LoadedScene, SceneError> {
    let (scene, warnings) = source.description.build(&source.base_dir)?;
    Ok(LoadedScene {
        scene,
        source,
        warnings,
    })
}

/// A scene loaded from a [`SceneSource`]: the runtime scene with its description.
#[derive(Debug, Clone)]
pub struct LoadedScene {
    /// The runtime scene.
    pub scene: Scene,
    /// What it was built from, and where its relative paths start.
    pub source: LocatedDescription,
    /// Problems worked around while building it.
    pub warnings: Vec<String>,
}

impl SceneSource {
    /// What `argument` names: a built-in scene's name, else a path judged by its extension.
    ///
    /// # Errors
    /// [`ResolveError::Unsupported`] for an existing file of another kind,
    /// [`ResolveError::NotFound`] for anything else.
    pub fn resolve(argument: &str) -> Result<Self, ResolveError> {
        if let Some(builtin) = find_builtin(argument) {
            return Ok(Self::Builtin(builtin));
        }
        let path = Path::new(argument);
        Self::from_path(path)
            .map_err(|error| match error {
                ResolveError::Unsupported(_) if !path.exists() => {
                    ResolveError::NotFound(argument.to_owned())
                }
                other => other,
            })
            .and_then(|source| source.existing())
    }

    /// The source itself if its file exists (or it has none);
    /// [`ResolveError::NoSuchFile`] naming the file otherwise, the one message for a missing
    /// scene file or model whichever front end names it.
    ///
    /// # Errors
    /// [`ResolveError::NoSuchFile`].
    pub fn existing(self) -> Result<Self, ResolveError> {
        match &self {
            Self::SceneFile(path) | Self::Model(path) if !path.exists() => {
                Err(ResolveError::NoSuchFile(path.display().to_string()))
            }
            _ => Ok(self),
        }
    }

    /// What the file at `path` is, by its extension alone (a file picked or dropped: never a
    /// built-in scene).
    ///
    /// # Errors
    /// [`ResolveError::Unsupported`] when it is neither a scene file nor a model.
    pub fn from_path(path: &Path) -> Result<Self, ResolveError> {
        match path_kind(path) {
            PathKind::SceneFile => Ok(Self::SceneFile(path.to_path_buf())),
            PathKind::Model => Ok(Self::Model(path.to_path_buf())),
            PathKind::Unsupported => Err(ResolveError::Unsupported(path.display().to_string())),
        }
    }

    /// The description of the scene, without building it (no model or texture is read). A bare
    /// model moves with `model_beta`, or approaches at [`DEFAULT_MODEL_SPEED`].
    ///
    /// # Errors
    /// [`SceneError`] naming the scene file when it cannot be read or parsed.
    pub fn description(&self, model_beta: Option<DVec3>) -> Result<LocatedDescription, SceneError> {
        let here = || PathBuf::from(".");
        Ok(match self {
            Self::Builtin(builtin) => LocatedDescription {
                description: builtin.description(),
                base_dir: here(),
            },
            Self::SceneFile(path) => LocatedDescription {
                description: read_scene_file(path)?,
                base_dir: scene_file_folder(path),
            },
            Self::Model(path) => LocatedDescription {
                description: model_scene(path, model_beta),
                base_dir: here(),
            },
        })
    }

    /// Loads and builds the scene (see [`SceneSource::description`] for `model_beta`).
    ///
    /// # Errors
    /// [`SceneError`] naming the file (or the built-in scene) when it cannot be read, parsed or
    /// built.
    pub fn load(&self, model_beta: Option<DVec3>) -> Result<LoadedScene, SceneError> {
        self.build(self.description(model_beta)?)
    }

    /// Loads the scene with `overrides` in place of its own values: the description is edited
    /// and validated ([`Overrides::apply`]; a bare model is placed for [`Overrides::beta`]),
    /// then built.
    ///
    /// # Errors
    /// As [`SceneSource::load`]; a value of an option the scene file's rules refuse is reported
    /// by the option's name ([`SceneErrorKind::Override`](crate::SceneErrorKind::Override)),
    /// before any model or texture is read.
    pub fn load_with(&self, overrides: &Overrides) -> Result<LoadedScene, SceneError> {
        self.load_edited(self.description(overrides.beta)?, overrides)
    }

    /// The description [`SceneSource::load_with`] builds: this source's own with `overrides` in
    /// place of its values, judged by the scene file's rules (what an [`crate::Editor`] is
    /// given when a front end's values change).
    ///
    /// # Errors
    /// As [`SceneSource::load_with`], before anything is built.
    pub fn description_with(
        &self,
        overrides: &Overrides,
    ) -> Result<LocatedDescription, SceneError> {
        overridden(self.description(overrides.beta)?, overrides, |d| {
            self.origin(d)
        })
    }

    /// Loads `source`, this source's description as a front end holds it (perhaps edited since
    /// [`SceneSource::description`] gave it, as a Python script edits a scene), with
    /// `overrides` in place of its values, exactly as [`SceneSource::load_with`] loads the
    /// source's own description.
    ///
    /// # Errors
    /// As [`SceneSource::load_with`].
    pub fn load_edited(
        &self,
        source: LocatedDescription,
        overrides: &Overrides,
    ) -> Result<LoadedScene, SceneError> {
        load_overridden(
            source,
            overrides,
            |d| self.origin(d),
            |source| self.build(source),
        )
    }

    /// Builds `source`, this scene's description (perhaps edited), as the scene is built: a scene
    /// file's errors name the file, a built-in scene's the scene.
    fn build(&self, mut source: LocatedDescription) -> Result<LoadedScene, SceneError> {
        let (scene, warnings) = match self {
            Self::SceneFile(path) => {
                let (scene, description, warnings) = build_scene_file(source.description, path)?;
                source.description = description;
                (scene, warnings)
            }
            Self::Builtin(builtin) => builtin.build_description(&source.description)?,
            Self::Model(_) => return build_located(source),
        };
        Ok(LoadedScene {
            scene,
            source,
            warnings,
        })
    }

    /// How messages name the scene of `description`, read from this source.
    #[must_use]
    pub fn origin(&self, description: &SceneDescription) -> String {
        match self {
            Self::Builtin(builtin) => builtin.origin(),
            Self::SceneFile(path) => path.display().to_string(),
            Self::Model(_) => description.origin(),
        }
    }
}

/// The scene of a bare model at `path`, moving with `beta` or approaching at
/// [`DEFAULT_MODEL_SPEED`].
fn model_scene(path: &Path, beta: Option<DVec3>) -> SceneDescription {
    let beta = beta.unwrap_or_else(|| approach_velocity(DEFAULT_MODEL_SPEED));
    SceneDescription::for_model(path, beta)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_classified_by_extension_whatever_its_case() {
        assert_eq!(path_kind(Path::new("a/b/ship.GLB")), PathKind::Model);
        for name in ["x.gltf", "x.obj", "x.ply", "x.stl"] {
            assert_eq!(path_kind(Path::new(name)), PathKind::Model, "{name}");
        }
        assert_eq!(path_kind(Path::new("scene.TOML")), PathKind::SceneFile);
        assert_eq!(path_kind(Path::new("notes.txt")), PathKind::Unsupported);
        assert_eq!(path_kind(Path::new("Makefile")), PathKind::Unsupported);
        assert_eq!(path_kind(Path::new("toml")), PathKind::Unsupported);
    }

    #[test]
    fn the_extension_list_names_every_model_format_once() {
        assert_eq!(model_extension_list(), ".gltf, .glb, .obj, .ply, .stl");
    }

    #[test]
    fn scene_files_resolve_paths_from_their_folder() {
        assert_eq!(scene_file_folder(Path::new("a/b/s.toml")), Path::new("a/b"));
        assert_eq!(scene_file_folder(Path::new("s.toml")), Path::new("."));
    }
}
