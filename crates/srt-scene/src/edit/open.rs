//! Opening scenes and models, adding and removing objects, and saving the scene file.

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::follow::{geometries, runtime_name};
use super::objects::object_mut;
use super::{EditError, Editor};
use crate::assets::BUILTIN_PREFIX;
use crate::description::FIT_RADIUS;
use crate::resolve::{LocatedDescription, PathKind, path_kind};
use crate::{
    LoadedScene, ObjectDescription, Observer, ResolveError, SceneDescription, SceneSource,
    ShapeDescription, TextureDescription,
};

/// How far in front of the camera an added model is placed, in radii of its bounding sphere
/// (times the cotangent of half the field of view: it then fills most of the image height).
const ADDED_MODEL_DISTANCE: f64 = 1.6;

impl Editor {
    /// An editor for a scene loaded by the resolver ([`SceneSource::load_with`]), and the
    /// warnings met loading it. Unnamed objects (and the scene) are given the names the runtime
    /// scene has, so that names stay put when objects are removed.
    #[must_use]
    pub fn new(loaded: LoadedScene) -> (Self, Vec<String>) {
        let LoadedScene {
            scene,
            source,
            warnings,
        } = loaded;
        let LocatedDescription {
            mut description,
            base_dir,
        } = source;
        description.name.get_or_insert_with(|| scene.name.clone());
        for (object, built) in description.objects.iter_mut().zip(&scene.objects) {
            object.name.get_or_insert_with(|| built.name.clone());
        }
        let directions = description
            .objects
            .iter()
            .map(|o| default_direction(DVec3::from_array(o.beta), &scene.observer))
            .collect();
        // The scene was built from this description, so its frames are usable; without them
        // the first edit rebuilds every object.
        let built_from = description
            .relative_frames()
            .map(|frames| geometries(&description, &frames))
            .unwrap_or_default();
        let editor = Self {
            home: scene.observer,
            built_from,
            description,
            base_dir,
            scene,
            directions,
            structure_version: 0,
            builds: 0,
        };
        (editor, warnings)
    }

    /// Opens one scene argument (a built-in scene, a `.toml` file or a model), as `srt render`
    /// does.
    ///
    /// # Errors
    /// An unknown name, a missing or unsupported file, or a scene or model that does not load.
    pub fn open(argument: &str) -> Result<(Self, Vec<String>), EditError> {
        Ok(Self::new(SceneSource::resolve(argument)?.load(None)?))
    }

    /// Adds what a further argument names: a model in front of the camera, or the objects of a
    /// scene (each under a name no other object has).
    ///
    /// # Errors
    /// As [`Editor::open`]; the scene is then unchanged.
    pub fn add_argument(&mut self, argument: &str) -> Result<Vec<String>, EditError> {
        match SceneSource::resolve(argument)? {
            SceneSource::Model(path) => self.add_model(&path),
            source => self.merge(source.description(None)?),
        }
    }

    /// Adds the objects of `other` (whose paths are relative to its `base_dir`) to this scene.
    pub(super) fn merge(&mut self, other: LocatedDescription) -> Result<Vec<String>, EditError> {
        let mut objects = other.description.objects;
        for object in &mut objects {
            absolutize_object(object, &other.base_dir);
        }
        self.add_objects(objects)
    }

    /// Appends `objects` (paths already absolute or `builtin:`), each under a name no other
    /// object has; nothing changes if any of them fails.
    pub(super) fn add_objects(
        &mut self,
        mut objects: Vec<ObjectDescription>,
    ) -> Result<Vec<String>, EditError> {
        let first_new = self.description.objects.len();
        let mut taken: Vec<String> = self.scene.objects.iter().map(|o| o.name.clone()).collect();
        for (i, object) in objects.iter_mut().enumerate() {
            let base = runtime_name(object, first_new + i);
            let name = unique_name(&base, &taken);
            taken.push(name.clone());
            object.name = Some(name);
        }
        let warnings = self.apply(|description| {
            description.objects.extend(objects);
            Ok(())
        })?;
        let observer = self.scene.observer;
        let added = self.description.objects[first_new..].iter();
        self.directions
            .extend(added.map(|o| default_direction(DVec3::from_array(o.beta), &observer)));
        Ok(warnings)
    }

    /// Adds the model file at `path`, scaled to radius [`FIT_RADIUS`], at rest in front of the
    /// camera (so it can be seen at once); its direction of motion is set towards the observer,
    /// so that giving it a speed shows it approaching.
    ///
    /// # Errors
    /// [`EditError::Source`] for a file that is not a model, [`EditError::Scene`] when the
    /// model does not load (the message names the file). The scene is then unchanged.
    pub fn add_model(&mut self, path: &Path) -> Result<Vec<String>, EditError> {
        if path_kind(path) != PathKind::Model {
            return Err(ResolveError::Unsupported(path.display().to_string()).into());
        }
        let path = absolute(path);
        let mut object = ObjectDescription::new(ShapeDescription::Model {
            path: path.to_string_lossy().into_owned(),
        });
        object.name = Some(
            path.file_stem()
                .map_or_else(|| "model".to_owned(), |s| s.to_string_lossy().into_owned()),
        );
        object.fit = true;
        let observer = &self.scene.observer;
        let (forward, _, _) = observer.basis();
        let half_fov = 0.5 * observer.fov_y_deg.to_radians();
        let distance = ADDED_MODEL_DISTANCE * FIT_RADIUS / half_fov.tan();
        object.offset = (observer.position + forward * distance).to_array();
        let warnings = self.add_objects(vec![object])?;
        if let Some(direction) = self.directions.last_mut() {
            *direction = -forward;
        }
        Ok(warnings)
    }

    /// Opens a dropped or chosen file: a model is added, a scene file replaces the scene.
    ///
    /// # Errors
    /// [`EditError::Source`] for other files, and whatever loading the file gives; the scene
    /// is then unchanged.
    pub fn open_file(&mut self, path: &Path) -> Result<Vec<String>, EditError> {
        match SceneSource::from_path(path)? {
            SceneSource::Model(path) => self.add_model(&path),
            source => {
                let (editor, warnings) = Self::new(source.load(None)?);
                self.replace_with(editor);
                Ok(warnings)
            }
        }
    }

    /// Removes object `index`.
    ///
    /// # Errors
    /// [`EditError::NoSuchObject`] when there is none.
    pub fn remove_object(&mut self, index: usize) -> Result<(), EditError> {
        self.edit(|description| {
            object_mut(description, index)?;
            description.objects.remove(index);
            Ok(())
        })?;
        self.directions.remove(index);
        Ok(())
    }

    /// The description as it should be saved: model and texture paths made absolute, so the
    /// file works from any folder.
    #[must_use]
    pub fn description_for_saving(&self) -> SceneDescription {
        let mut description = self.description.clone();
        for object in &mut description.objects {
            absolutize_object(object, &self.base_dir);
        }
        description
    }

    /// Saves the scene as a TOML scene file that `srt render` and `srt view` read.
    ///
    /// # Errors
    /// [`EditError::Io`] when the file cannot be written.
    pub fn save_toml(&self, path: &Path) -> Result<(), EditError> {
        let mut text = String::from("# Saved by `srt view`.\n");
        text.push_str(&self.description_for_saving().to_toml_string());
        std::fs::write(path, text).map_err(|error| EditError::Io {
            path: path.display().to_string(),
            error,
        })
    }
}

/// `base`, or `base 2`, `base 3`… whichever is not in `taken`.
pub(super) fn unique_name(base: &str, taken: &[String]) -> String {
    let free = |name: &String| !taken.contains(name);
    std::iter::once(base.to_owned())
        .chain((2..).map(|n| format!("{base} {n}")))
        .find(free)
        .unwrap_or_default()
}

/// Direction of motion to remember for an object moving with `beta`: its own, or (at rest)
/// towards the observer.
pub(super) fn default_direction(beta: DVec3, observer: &Observer) -> DVec3 {
    beta.try_normalize().unwrap_or_else(|| -observer.basis().0)
}

/// `path` made absolute (against the current folder), without resolving links.
pub(super) fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// A path from a scene file made absolute against `base_dir` (`builtin:` paths stay).
pub(super) fn absolutize(path: &str, base_dir: &Path) -> String {
    if path.starts_with(BUILTIN_PREFIX) || Path::new(path).is_absolute() {
        path.to_owned()
    } else {
        absolute(&base_dir.join(path))
            .to_string_lossy()
            .into_owned()
    }
}

/// The model and texture paths of `object` made absolute against `base_dir`.
pub(super) fn absolutize_object(object: &mut ObjectDescription, base_dir: &Path) {
    if let ShapeDescription::Model { path } = &mut object.shape {
        *path = absolutize(path, base_dir);
    }
    match &mut object.texture {
        Some(TextureDescription::Image { path }) => *path = absolutize(path, base_dir),
        Some(TextureDescription::Frames { files, .. }) => {
            for path in files {
                *path = absolutize(path, base_dir);
            }
        }
        _ => {}
    }
}
