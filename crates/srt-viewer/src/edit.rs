//! The scene being viewed and every edit the side panel can make to it, without any UI or GPU.
//!
//! An [`Editor`] keeps two views of the scene in step: the [`SceneDescription`] (what `srt render`
//! reads and what "Save scene" writes) and the runtime [`Scene`] the GPU renders. Edits of
//! velocities, offsets, the observer, the light and the effect mode change both in place; models
//! are loaded only when an object is added, so dragging a slider never re-reads a file. Objects
//! are added and removed as a whole, and [`Editor::structure_version`] tells the renderer when the
//! set of meshes changed and must be uploaded again.
//!
//! Every edit validates its input first and leaves the scene as it was when it returns an error.

use std::path::{Path, PathBuf};

use glam::DVec3;
use srt_color::ToneMap;
use srt_physics::Frame;
use srt_scene::assets::BUILTIN_PREFIX;
use srt_scene::builtin::find_builtin;
use srt_scene::description::FIT_RADIUS;
use srt_scene::import::SUPPORTED_EXTENSIONS;
use srt_scene::placement::approach_velocity;
use srt_scene::{
    Effects, LightDescription, Object, ObjectDescription, Observer, Scene, SceneDescription,
    SceneError, ShapeDescription, TextureDescription, load_scene_file,
};

/// The scene opened when `srt view` is given no argument.
pub const DEFAULT_SCENE: &str = "teaser";

/// The fastest speed the speed slider offers, as a fraction of c.
pub const MAX_SLIDER_SPEED: f64 = 0.999;

/// Speed of a bare model given on the command line as the first argument (as `srt render`).
pub const DEFAULT_MODEL_SPEED: f64 = 0.9;

/// Why an edit or a file operation was refused. The message is meant for the status line.
#[derive(Debug, thiserror::Error)]
pub enum EditError {
    /// A typed speed that is not a number in [0, 1).
    #[error("{0}")]
    Speed(String),
    /// A value out of its range (a direction of length zero, a field of view of 200°…).
    #[error("{0}")]
    Value(String),
    /// A file whose kind the viewer cannot open.
    #[error(
        "cannot open {path}: the viewer opens 3D models ({}) and scene files (.toml)",
        supported_list()
    )]
    Unsupported {
        /// The file.
        path: String,
    },
    /// A scene or model that failed to load or build (the message names the file).
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// An argument that is neither a built-in scene nor an existing file.
    #[error("{0:?} is neither a built-in scene (see `srt scenes`) nor an existing file")]
    NotFound(String),
    /// Reading or writing a file failed.
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
}

fn supported_list() -> String {
    SUPPORTED_EXTENSIONS
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What kind of file a path names, by its extension (case-insensitive).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A 3D model: glTF/GLB, OBJ, PLY or STL.
    Model,
    /// A scene file (`.toml`).
    Scene,
    /// Anything else.
    Unsupported,
}

/// Classifies `path` by its extension: what dropping it on the window does.
#[must_use]
pub fn file_kind(path: &Path) -> FileKind {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("toml") => FileKind::Scene,
        Some(ext) if SUPPORTED_EXTENSIONS.contains(&ext) => FileKind::Model,
        _ => FileKind::Unsupported,
    }
}

/// Parses a speed typed by the user: a number (optionally followed by `c`) in [0, 1).
///
/// # Errors
/// [`EditError::Speed`] with a message for the status line when the text is not a number, is
/// negative, or is 1 or more (nothing with mass reaches the speed of light).
pub fn parse_speed(text: &str) -> Result<f64, EditError> {
    let trimmed = text.trim();
    let number = trimmed.strip_suffix('c').unwrap_or(trimmed).trim();
    let speed: f64 = number.parse().map_err(|_| {
        EditError::Speed(format!(
            "\"{trimmed}\" is not a speed: type a fraction of the speed of light, e.g. 0.9"
        ))
    })?;
    check_speed(speed)
}

/// Checks that `speed` (a fraction of c) is finite and in [0, 1).
///
/// # Errors
/// [`EditError::Speed`] otherwise.
pub fn check_speed(speed: f64) -> Result<f64, EditError> {
    if !speed.is_finite() {
        Err(EditError::Speed(format!("{speed} is not a usable speed")))
    } else if speed >= 1.0 {
        Err(EditError::Speed(format!(
            "a speed of {speed}c is impossible: nothing with mass reaches the speed of light; \
             type a value below 1 (e.g. 0.999) — the scene is unchanged"
        )))
    } else if speed < 0.0 {
        Err(EditError::Speed(format!(
            "a speed of {speed}c is negative: type a speed ≥ 0 and reverse the direction instead"
        )))
    } else {
        Ok(speed)
    }
}

/// The velocity `speed · direction` (units of c) that keeps the point `apparent` — seen at
/// distance `distance` from an observer observing at time `ct` — where it is seen: the offset for
/// that velocity such that the worldline passes through `apparent` at time `ct − distance`.
#[must_use]
pub fn offset_keeping_apparent_position(
    apparent: DVec3,
    distance: f64,
    ct: f64,
    beta: DVec3,
) -> DVec3 {
    apparent - beta * (ct - distance)
}

/// The scene being viewed: its description (for saving) and its runtime scene (for rendering),
/// edited together.
#[derive(Debug, Clone)]
pub struct Editor {
    description: SceneDescription,
    base_dir: PathBuf,
    scene: Scene,
    /// Remembered unit direction of motion of each object (kept when the speed is 0).
    directions: Vec<DVec3>,
    home: Observer,
    structure_version: u64,
}

impl Editor {
    /// An editor for `description`, whose relative paths are relative to `base_dir`.
    ///
    /// # Errors
    /// [`EditError::Scene`] when the description does not build (a missing model…).
    pub fn new(
        description: SceneDescription,
        base_dir: &Path,
    ) -> Result<(Self, Vec<String>), EditError> {
        let (scene, warnings) = description.build(base_dir)?;
        Ok((
            Self::from_parts(description, base_dir.to_path_buf(), scene),
            warnings,
        ))
    }

    fn from_parts(mut description: SceneDescription, base_dir: PathBuf, scene: Scene) -> Self {
        if description.name.is_none() {
            description.name = Some(scene.name.clone());
        }
        let directions = description
            .objects
            .iter()
            .map(|o| default_direction(DVec3::from_array(o.beta), &scene.observer))
            .collect();
        Self {
            home: scene.observer,
            description,
            base_dir,
            scene,
            directions,
            structure_version: 0,
        }
    }

    /// Opens what `srt view` was given: none opens [`DEFAULT_SCENE`]; the first argument is a
    /// built-in scene name, a scene file (`.toml`) or a model (placed as `srt render` places
    /// it); every further argument adds its objects (a model, or the objects of a scene) to the
    /// first scene.
    ///
    /// # Errors
    /// An unknown name, a missing or unsupported file, or a scene or model that does not load.
    pub fn from_arguments(arguments: &[String]) -> Result<(Self, Vec<String>), EditError> {
        let (first, rest) = match arguments.split_first() {
            Some((first, rest)) => (first.as_str(), rest),
            None => (DEFAULT_SCENE, &[][..]),
        };
        let (mut editor, mut warnings) = Self::open(first)?;
        for argument in rest {
            warnings.extend(editor.add_argument(argument)?);
        }
        Ok((editor, warnings))
    }

    /// Opens one scene argument (a built-in scene, a `.toml` file or a model).
    ///
    /// # Errors
    /// As [`Editor::from_arguments`].
    pub fn open(argument: &str) -> Result<(Self, Vec<String>), EditError> {
        if let Some(builtin) = find_builtin(argument) {
            return Self::new(builtin.description(), Path::new("."));
        }
        let path = Path::new(argument);
        match file_kind(path) {
            FileKind::Scene => {
                let (scene, description, warnings) = load_scene_file(path)?;
                Ok((
                    Self::from_parts(description, folder_of(path), scene),
                    warnings,
                ))
            }
            FileKind::Model => {
                let beta = approach_velocity(DEFAULT_MODEL_SPEED);
                let description = SceneDescription::for_model(&absolute(path), beta);
                Self::new(description, Path::new("."))
            }
            FileKind::Unsupported if path.exists() => Err(EditError::Unsupported {
                path: argument.to_owned(),
            }),
            FileKind::Unsupported => Err(EditError::NotFound(argument.to_owned())),
        }
    }

    fn add_argument(&mut self, argument: &str) -> Result<Vec<String>, EditError> {
        if let Some(builtin) = find_builtin(argument) {
            return self.merge(builtin.description(), Path::new("."));
        }
        let path = Path::new(argument);
        match file_kind(path) {
            FileKind::Model => self.add_model(path),
            FileKind::Scene => {
                let text = std::fs::read_to_string(path).map_err(|error| EditError::Io {
                    path: argument.to_owned(),
                    error,
                })?;
                let description = SceneDescription::from_toml_str(&text, argument)?;
                self.merge(description, &folder_of(path))
            }
            FileKind::Unsupported if path.exists() => Err(EditError::Unsupported {
                path: argument.to_owned(),
            }),
            FileKind::Unsupported => Err(EditError::NotFound(argument.to_owned())),
        }
    }

    /// Adds the objects of `other` (whose paths are relative to `base_dir`) to this scene.
    fn merge(
        &mut self,
        other: SceneDescription,
        base_dir: &Path,
    ) -> Result<Vec<String>, EditError> {
        let mut objects = other.objects;
        for object in &mut objects {
            absolutize_object(object, base_dir);
        }
        self.add_objects(objects)
    }

    /// Builds `objects` (paths already absolute or `builtin:`) and appends them; nothing changes
    /// if any of them fails.
    fn add_objects(
        &mut self,
        mut objects: Vec<ObjectDescription>,
    ) -> Result<Vec<String>, EditError> {
        for (i, object) in objects.iter_mut().enumerate() {
            let base = object
                .name
                .clone()
                .unwrap_or_else(|| format!("object {}", self.description.objects.len() + i + 1));
            object.name = Some(self.unique_name(&base));
        }
        let probe = SceneDescription {
            objects: objects.clone(),
            ..self.description.clone()
        };
        let (built, warnings) = probe.build(&self.base_dir)?;
        for (object, built) in objects.into_iter().zip(built.objects) {
            self.directions.push(default_direction(
                DVec3::from_array(object.beta),
                &self.scene.observer,
            ));
            self.description.objects.push(object);
            self.scene.objects.push(built);
        }
        self.structure_version += 1;
        Ok(warnings)
    }

    /// A name not yet used by an object: `base`, or `base 2`, `base 3`…
    fn unique_name(&self, base: &str) -> String {
        let taken = |name: &str| self.scene.objects.iter().any(|o| o.name == name);
        if !taken(base) {
            return base.to_owned();
        }
        (2..)
            .map(|n| format!("{base} {n}"))
            .find(|name| !taken(name))
            .unwrap_or_default()
    }

    /// Adds the model file at `path`, scaled to radius [`FIT_RADIUS`], at rest in front of the
    /// camera (so it can be seen at once); its direction of motion is set towards the observer,
    /// so that giving it a speed shows it approaching.
    ///
    /// # Errors
    /// [`EditError::Unsupported`] for a file that is not a model, [`EditError::Scene`] when the
    /// model does not load (the message names the file). The scene is then unchanged.
    pub fn add_model(&mut self, path: &Path) -> Result<Vec<String>, EditError> {
        if file_kind(path) != FileKind::Model {
            return Err(EditError::Unsupported {
                path: path.display().to_string(),
            });
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
        let distance = 1.6 * FIT_RADIUS / (0.5 * observer.fov_y_deg.to_radians()).tan();
        object.offset = (observer.position + forward * distance).to_array();
        let count = self.description.objects.len();
        self.add_objects(vec![object])?;
        self.directions[count] = -forward;
        Ok(Vec::new())
    }

    /// Opens a dropped or chosen file: a model is added, a scene file replaces the scene.
    ///
    /// # Errors
    /// [`EditError::Unsupported`] for other files, and whatever loading the file gives; the
    /// scene is then unchanged.
    pub fn open_file(&mut self, path: &Path) -> Result<Vec<String>, EditError> {
        match file_kind(path) {
            FileKind::Model => self.add_model(path),
            FileKind::Scene => {
                let (scene, description, warnings) = load_scene_file(path)?;
                let version = self.structure_version;
                *self = Self::from_parts(description, folder_of(path), scene);
                self.structure_version = version + 1;
                Ok(warnings)
            }
            FileKind::Unsupported => Err(EditError::Unsupported {
                path: path.display().to_string(),
            }),
        }
    }

    /// Removes object `index`.
    ///
    /// # Errors
    /// [`EditError::NoSuchObject`] when there is none.
    pub fn remove_object(&mut self, index: usize) -> Result<(), EditError> {
        self.check_index(index)?;
        self.description.objects.remove(index);
        self.scene.objects.remove(index);
        self.directions.remove(index);
        self.structure_version += 1;
        Ok(())
    }

    fn check_index(&self, index: usize) -> Result<(), EditError> {
        if index < self.scene.objects.len() {
            Ok(())
        } else {
            Err(EditError::NoSuchObject(index))
        }
    }

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

    /// Speed |β| of object `index` as a fraction of c (0 for an index out of range).
    #[must_use]
    pub fn speed(&self, index: usize) -> f64 {
        self.scene
            .objects
            .get(index)
            .map_or(0.0, |o| o.frame.beta().length())
    }

    /// Unit direction of motion of object `index` (remembered while its speed is 0).
    #[must_use]
    pub fn direction(&self, index: usize) -> DVec3 {
        self.directions.get(index).copied().unwrap_or(DVec3::X)
    }

    /// Offset **a** of object `index`: where its S′ origin is in S at t = 0.
    #[must_use]
    pub fn offset(&self, index: usize) -> DVec3 {
        self.scene
            .objects
            .get(index)
            .map_or(DVec3::ZERO, |o| o.frame.offset())
    }

    /// Sets the velocity of object `index` to `speed · direction`. With `keep_apparent`, the
    /// offset changes too, so that the object's origin stays where the observer sees it now
    /// (only its shape and colour change); otherwise the offset stays.
    ///
    /// # Errors
    /// [`EditError::Speed`] for a speed outside [0, 1), [`EditError::Value`] for a zero or
    /// non-finite direction; the scene is then unchanged.
    pub fn set_velocity(
        &mut self,
        index: usize,
        speed: f64,
        direction: DVec3,
        keep_apparent: bool,
    ) -> Result<(), EditError> {
        self.check_index(index)?;
        let speed = check_speed(speed)?;
        let direction = direction.try_normalize().ok_or_else(|| {
            EditError::Value("the direction of motion must not be zero".to_owned())
        })?;
        let beta = speed * direction;
        let old = self.scene.objects[index].frame;
        let offset = if keep_apparent {
            let observer = self.scene.observer.event();
            let apparent = old.apparent_position(DVec3::ZERO, observer);
            let distance = (apparent - observer.position).length();
            offset_keeping_apparent_position(apparent, distance, observer.ct, beta)
        } else {
            old.offset()
        };
        self.set_frame(index, beta, offset)?;
        self.directions[index] = direction;
        Ok(())
    }

    /// Sets the offset **a** of object `index`.
    ///
    /// # Errors
    /// [`EditError::Value`] for a non-finite offset.
    pub fn set_offset(&mut self, index: usize, offset: DVec3) -> Result<(), EditError> {
        self.check_index(index)?;
        let beta = self.scene.objects[index].frame.beta();
        self.set_frame(index, beta, offset)
    }

    fn set_frame(&mut self, index: usize, beta: DVec3, offset: DVec3) -> Result<(), EditError> {
        let frame = Frame::new(beta, offset)
            .map_err(|e| EditError::Value(format!("{}: {e}", self.scene.objects[index].name)))?;
        self.scene.objects[index].frame = frame;
        let description = &mut self.description.objects[index];
        description.beta = beta.to_array();
        description.offset = offset.to_array();
        Ok(())
    }

    /// The wireframe line width of object `index` (`None`: textured).
    #[must_use]
    pub fn wireframe(&self, index: usize) -> Option<f64> {
        self.scene.objects.get(index).and_then(|o| o.wireframe)
    }

    /// Draws object `index` as a wireframe of lines `width` wide (in its own units), or textured.
    ///
    /// # Errors
    /// [`EditError::Value`] for a width that is not positive.
    pub fn set_wireframe(&mut self, index: usize, width: Option<f64>) -> Result<(), EditError> {
        self.check_index(index)?;
        if let Some(w) = width
            && !(w.is_finite() && w > 0.0)
        {
            return Err(EditError::Value(format!(
                "a wireframe width must be positive, got {w}"
            )));
        }
        self.scene.objects[index].wireframe = width;
        self.description.objects[index].wireframe = width;
        Ok(())
    }

    /// The objects of the scene.
    #[must_use]
    pub fn objects(&self) -> &[Object] {
        &self.scene.objects
    }

    /// Sets the effect mode (and the tone map that goes with it, unless one was chosen).
    pub fn set_effects(&mut self, effects: Effects) {
        self.description.render.effects = effects;
        self.scene.effects = effects;
        self.scene.tone_map = self
            .description
            .render
            .tone_map
            .unwrap_or_else(|| effects.default_tone_map());
    }

    /// The tone map chosen explicitly (`None`: the effect mode's).
    #[must_use]
    pub fn tone_map_choice(&self) -> Option<ToneMap> {
        self.description.render.tone_map
    }

    /// Chooses the tone map (`None`: the effect mode's own).
    pub fn set_tone_map(&mut self, tone_map: Option<ToneMap>) {
        self.description.render.tone_map = tone_map;
        self.scene.tone_map = tone_map.unwrap_or_else(|| self.scene.effects.default_tone_map());
    }

    /// Sets the light's temperature (kelvin) and position.
    ///
    /// # Errors
    /// [`EditError::Value`] for a temperature that is not positive or a non-finite position.
    pub fn set_light(&mut self, temperature_k: f64, position: DVec3) -> Result<(), EditError> {
        if !(temperature_k.is_finite() && temperature_k > 0.0) {
            return Err(EditError::Value(format!(
                "the light's temperature must be positive, got {temperature_k} K"
            )));
        }
        if !position.is_finite() {
            return Err(EditError::Value(
                "the light's position must be finite".to_owned(),
            ));
        }
        self.scene.light.temperature_k = temperature_k;
        self.scene.light.position = position;
        self.description.light = Some(LightDescription {
            position: position.to_array(),
            temperature_k,
        });
        Ok(())
    }

    /// Sets the observer (camera and observation time).
    ///
    /// # Errors
    /// [`EditError::Value`] for a non-finite position or time, a zero direction, an up vector
    /// parallel to it, or a field of view outside (0°, 180°); the observer is then unchanged.
    pub fn set_observer(&mut self, observer: Observer) -> Result<(), EditError> {
        let direction = observer.direction.try_normalize().filter(|d| d.is_finite());
        let Some(direction) = direction else {
            return Err(EditError::Value(
                "the viewing direction must not be zero".to_owned(),
            ));
        };
        if !(observer.position.is_finite() && observer.ct.is_finite()) {
            return Err(EditError::Value(
                "the observer's position and time must be finite".to_owned(),
            ));
        }
        if direction.cross(observer.up).length() < 1e-9 {
            return Err(EditError::Value(
                "the camera cannot look straight along its up direction".to_owned(),
            ));
        }
        if !(observer.fov_y_deg > 0.0 && observer.fov_y_deg < 180.0) {
            return Err(EditError::Value(format!(
                "the field of view must be in (0°, 180°), got {}°",
                observer.fov_y_deg
            )));
        }
        let observer = Observer {
            direction,
            ..observer
        };
        self.scene.observer = observer;
        let d = &mut self.description.observer;
        d.position = observer.position.to_array();
        d.look_at = None;
        d.direction = Some(direction.to_array());
        d.up = observer.up.to_array();
        d.fov_y_deg = observer.fov_y_deg;
        d.ct = observer.ct;
        Ok(())
    }

    /// Sets the observation time ct.
    ///
    /// # Errors
    /// [`EditError::Value`] for a non-finite time.
    pub fn set_time(&mut self, ct: f64) -> Result<(), EditError> {
        self.set_observer(Observer {
            ct,
            ..self.scene.observer
        })
    }

    /// The observer the scene started with (for "reset view").
    #[must_use]
    pub const fn home(&self) -> Observer {
        self.home
    }

    /// Puts the camera back where the scene started (the observation time stays).
    pub fn reset_view(&mut self) {
        let home = Observer {
            ct: self.scene.observer.ct,
            ..self.home
        };
        // The home observer was valid when the scene was built.
        let _ = self.set_observer(home);
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

/// Direction of motion to remember for an object moving with `beta`: its own, or (at rest)
/// towards the observer.
fn default_direction(beta: DVec3, observer: &Observer) -> DVec3 {
    beta.try_normalize().unwrap_or_else(|| -observer.basis().0)
}

/// The folder of a scene file, `.` for a bare file name.
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// `path` made absolute (against the current folder), without resolving links.
fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// A path from a scene file made absolute against `base_dir` (`builtin:` paths stay).
fn absolutize(path: &str, base_dir: &Path) -> String {
    if path.starts_with(BUILTIN_PREFIX) || Path::new(path).is_absolute() {
        path.to_owned()
    } else {
        absolute(&base_dir.join(path))
            .to_string_lossy()
            .into_owned()
    }
}

fn absolutize_object(object: &mut ObjectDescription, base_dir: &Path) {
    if let ShapeDescription::Model { path } = &mut object.shape {
        *path = absolutize(path, base_dir);
    }
    if let Some(TextureDescription::Image { path }) = &mut object.texture {
        *path = absolutize(path, base_dir);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn teaser() -> Editor {
        Editor::from_arguments(&[]).expect("the teaser builds").0
    }

    #[test]
    fn typed_speeds_below_one_are_accepted() {
        assert_eq!(parse_speed("0.9").unwrap(), 0.9);
        assert_eq!(parse_speed(" 0.5c ").unwrap(), 0.5);
        assert_eq!(parse_speed("0").unwrap(), 0.0);
        assert_eq!(parse_speed("0.9999").unwrap(), 0.9999);
    }

    #[test]
    fn typed_speeds_of_one_or_more_are_refused_with_a_message() {
        for text in ["1", "1.0", "1c", "1.5", "300000"] {
            let message = parse_speed(text).unwrap_err().to_string();
            assert!(message.contains("speed of light"), "{text}: {message}");
        }
        assert!(
            parse_speed("fast")
                .unwrap_err()
                .to_string()
                .contains("not a speed")
        );
        assert!(
            parse_speed("-0.5")
                .unwrap_err()
                .to_string()
                .contains("negative")
        );
        assert!(parse_speed("NaN").is_err());
        assert!(parse_speed("inf").is_err());
    }

    #[test]
    fn files_are_classified_by_extension() {
        assert_eq!(file_kind(Path::new("a/b/ship.GLB")), FileKind::Model);
        assert_eq!(file_kind(Path::new("bunny.ply")), FileKind::Model);
        assert_eq!(file_kind(Path::new("x.stl")), FileKind::Model);
        assert_eq!(file_kind(Path::new("x.obj")), FileKind::Model);
        assert_eq!(file_kind(Path::new("x.gltf")), FileKind::Model);
        assert_eq!(file_kind(Path::new("scene.toml")), FileKind::Scene);
        assert_eq!(file_kind(Path::new("notes.txt")), FileKind::Unsupported);
        assert_eq!(file_kind(Path::new("Makefile")), FileKind::Unsupported);
    }

    #[test]
    fn no_argument_opens_the_teaser() {
        let editor = teaser();
        assert_eq!(editor.scene().name, "teaser");
        assert_eq!(editor.object_count(), 3);
        assert!((editor.speed(0) - 0.95).abs() < 1e-3);
    }

    #[test]
    fn further_arguments_add_objects() {
        let (editor, _) =
            Editor::from_arguments(&["fig7".to_owned(), "teaser".to_owned()]).unwrap();
        assert_eq!(editor.object_count(), 4);
        let names: Vec<_> = editor.objects().iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names.len(), 4);
        assert!(
            names
                .iter()
                .all(|n| names.iter().filter(|m| *m == n).count() == 1),
            "{names:?}"
        );
    }

    #[test]
    fn a_bare_model_approaches_the_observer() {
        let dir = tempfile::tempdir().unwrap();
        let model = dir.path().join("tetra.stl");
        std::fs::write(&model, tetrahedron_stl()).unwrap();
        let (editor, _) = Editor::from_arguments(&[model.display().to_string()]).unwrap();
        let object = &editor.scene().objects[0];
        let observer = editor.scene().observer.event();
        let seen = object.frame.apparent_position(DVec3::ZERO, observer);
        let towards_observer = (observer.position - seen).normalize();
        assert!((editor.speed(0) - DEFAULT_MODEL_SPEED).abs() < 1e-12);
        assert!(object.frame.beta().normalize().dot(towards_observer) > 0.999);
    }

    #[test]
    fn unknown_arguments_are_errors() {
        assert!(matches!(
            Editor::from_arguments(&["no-such-scene".to_owned()]),
            Err(EditError::NotFound(_))
        ));
    }

    #[test]
    fn a_refused_speed_leaves_the_scene_unchanged() {
        let mut editor = teaser();
        let before = editor.description().clone();
        let frame = editor.scene().objects[1].frame;
        assert!(matches!(
            editor.set_velocity(1, 1.0, DVec3::X, true),
            Err(EditError::Speed(_))
        ));
        assert!(editor.set_velocity(1, 0.5, DVec3::ZERO, true).is_err());
        assert!(editor.set_velocity(7, 0.5, DVec3::X, true).is_err());
        assert_eq!(editor.description(), &before);
        assert_eq!(editor.scene().objects[1].frame, frame);
    }

    #[test]
    fn changing_the_speed_keeps_the_apparent_position() {
        let mut editor = teaser();
        let observer = editor.scene().observer.event();
        let before = editor.scene().objects[0]
            .frame
            .apparent_position(DVec3::ZERO, observer);
        for speed in [0.0, 0.3, 0.99] {
            let direction = editor.direction(0);
            editor.set_velocity(0, speed, direction, true).unwrap();
            let frame = editor.scene().objects[0].frame;
            assert!((frame.beta().length() - speed).abs() < 1e-12);
            let after = frame.apparent_position(DVec3::ZERO, observer);
            assert!(
                (after - before).length() < 1e-9,
                "{speed}: {before} → {after}"
            );
            assert_eq!(
                editor.description().objects[0].beta,
                frame.beta().to_array()
            );
            assert_eq!(
                editor.description().objects[0].offset,
                frame.offset().to_array()
            );
        }
        // The remembered direction survives a speed of zero.
        assert!(
            editor
                .direction(0)
                .dot(DVec3::new(0.4883, -0.8139, 0.0407).normalize())
                > 0.999
        );
    }

    #[test]
    fn a_model_that_fails_to_load_leaves_the_scene_unchanged() {
        let dir = tempfile::tempdir().unwrap();
        let broken = dir.path().join("broken.stl");
        std::fs::write(&broken, b"solid nothing\nthis is not an STL file\n").unwrap();
        let mut editor = teaser();
        let version = editor.structure_version();
        let error = editor.add_model(&broken).unwrap_err().to_string();
        assert!(error.contains("broken.stl"), "{error}");
        let missing = editor
            .add_model(&dir.path().join("missing.obj"))
            .unwrap_err()
            .to_string();
        assert!(missing.contains("missing.obj"), "{missing}");
        let text = dir.path().join("notes.txt");
        std::fs::write(&text, "hello").unwrap();
        assert!(matches!(
            editor.open_file(&text),
            Err(EditError::Unsupported { .. })
        ));
        assert_eq!(editor.object_count(), 3);
        assert_eq!(editor.structure_version(), version);
    }

    #[test]
    fn models_are_added_in_view_and_removed() {
        let dir = tempfile::tempdir().unwrap();
        let model = dir.path().join("tetra.stl");
        std::fs::write(&model, tetrahedron_stl()).unwrap();
        let mut editor = teaser();
        editor.add_model(&model).unwrap();
        editor.add_model(&model).unwrap();
        assert_eq!(editor.object_count(), 5);
        assert_eq!(editor.objects()[3].name, "tetra");
        assert_eq!(editor.objects()[4].name, "tetra 2");
        assert_eq!(editor.speed(3), 0.0);
        // In front of the camera.
        let observer = editor.scene().observer;
        let to_object = editor.offset(3) - observer.position;
        assert!(to_object.normalize().dot(observer.basis().0) > 0.999);
        editor
            .set_velocity(3, 0.9, editor.direction(3), true)
            .unwrap();
        assert!(
            editor.direction(3).dot(observer.basis().0) < -0.999,
            "approaches the observer"
        );
        let version = editor.structure_version();
        editor.remove_object(0).unwrap();
        assert_eq!(editor.object_count(), 4);
        assert!(editor.structure_version() > version);
        assert!(editor.remove_object(9).is_err());
    }

    #[test]
    fn saved_scenes_load_back_with_the_edits() {
        let dir = tempfile::tempdir().unwrap();
        let model = dir.path().join("tetra.stl");
        std::fs::write(&model, tetrahedron_stl()).unwrap();
        let mut editor = teaser();
        editor.add_model(&model).unwrap();
        editor
            .set_velocity(3, 0.9, DVec3::new(0.0, -1.0, 0.0), true)
            .unwrap();
        editor.set_effects(Effects::Searchlight);
        editor.set_wireframe(1, Some(0.02)).unwrap();
        editor.set_light(8000.0, DVec3::new(1.0, 2.0, 3.0)).unwrap();
        editor.set_time(2.5).unwrap();
        let saved = dir.path().join("sub").join("saved.toml");
        std::fs::create_dir_all(saved.parent().unwrap()).unwrap();
        editor.save_toml(&saved).unwrap();
        let (scene, description, _) = load_scene_file(&saved).unwrap();
        assert_eq!(scene.objects.len(), 4);
        assert_eq!(description.objects[3].beta, [0.0, -0.9, 0.0]);
        assert_eq!(scene.effects, Effects::Searchlight);
        assert_eq!(scene.objects[1].wireframe, Some(0.02));
        assert_eq!(scene.light.temperature_k, 8000.0);
        assert_eq!(scene.observer.ct, 2.5);
        assert_eq!(scene.objects[3].triangle_count(), 4);
    }

    #[test]
    fn the_observer_is_validated_and_reset() {
        let mut editor = teaser();
        let home = editor.home();
        let mut moved = home;
        moved.position += DVec3::new(1.0, 2.0, 0.5);
        moved.fov_y_deg = 60.0;
        editor.set_observer(moved).unwrap();
        assert!(
            editor
                .set_observer(Observer {
                    fov_y_deg: 180.0,
                    ..moved
                })
                .is_err()
        );
        assert!(
            editor
                .set_observer(Observer {
                    direction: DVec3::ZERO,
                    ..moved
                })
                .is_err()
        );
        assert!(
            editor
                .set_observer(Observer {
                    direction: moved.up,
                    ..moved
                })
                .is_err()
        );
        assert_eq!(editor.scene().observer.fov_y_deg, 60.0);
        editor.set_time(4.0).unwrap();
        editor.reset_view();
        assert_eq!(editor.scene().observer.position, home.position);
        assert_eq!(editor.scene().observer.ct, 4.0);
    }

    #[test]
    fn effects_and_tone_maps() {
        let mut editor = teaser();
        editor.set_effects(Effects::Searchlight);
        assert_eq!(editor.scene().tone_map, ToneMap::Searchlight);
        editor.set_tone_map(Some(ToneMap::Luminance));
        assert_eq!(editor.scene().tone_map, ToneMap::Luminance);
        editor.set_effects(Effects::Geometry);
        assert_eq!(editor.scene().tone_map, ToneMap::Luminance);
        editor.set_tone_map(None);
        editor.set_effects(Effects::Searchlight);
        assert_eq!(editor.scene().tone_map, ToneMap::Searchlight);
        assert!(editor.set_light(0.0, DVec3::ZERO).is_err());
        assert!(editor.set_wireframe(0, Some(-1.0)).is_err());
    }

    /// A binary STL file with one tetrahedron (4 triangles), shared with the UI tests.
    pub(crate) fn tetrahedron_stl() -> Vec<u8> {
        include_bytes!("../tests/fixtures/tetrahedron.stl").to_vec()
    }
}
