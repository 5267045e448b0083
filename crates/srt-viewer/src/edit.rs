//! The scene being viewed and every edit the side panel can make to it, without any UI or GPU.
//!
//! An [`Editor`] keeps two views of the scene in step: the [`SceneDescription`] (what `srt render`
//! reads and what "Save scene" writes) and the runtime [`Scene`] the GPU renders. Every edit
//! changes a copy of the description; [`SceneDescription::validate`] checks the copy with the
//! scene file's own rules and messages, and only then is the runtime scene brought in step, so a
//! refused edit leaves both as they were.
//!
//! Bringing the runtime scene in step never reads a file again: each runtime object remembers the
//! geometry it was built from (its description without motion, name and wireframe), and an
//! object whose geometry is unchanged keeps its parts. Only new objects (or objects whose
//! geometry changed) are built, by [`SceneDescription::build`]. An edit of the observer alone
//! (time, camera, a flight's step: what runs every frame) builds nothing: the runtime scene
//! follows it ([`Scene::follow`]) unless the observer's new velocity turns an object's geometry
//! (the Wigner rotation). So dragging a slider or playing time costs no more than a validation. [`Editor::structure_version`] tells the renderer when the set of
//! meshes changed and must be uploaded again.
//!
//! Arguments and files are resolved by [`srt_scene::resolve`], as `srt render` resolves them.

use std::path::{Path, PathBuf};

use glam::{DMat3, DVec3};
use srt_color::ToneMap;
use srt_physics::motion::Motion;
use srt_physics::{Event, Frame, RelativeFrame};
use srt_scene::assets::BUILTIN_PREFIX;
use srt_scene::description::{
    DEFAULT_LIGHT_TEMPERATURE_K, FIT_RADIUS, SpinDescription, ThrustDescription,
};
use srt_scene::limits::Budget;
use srt_scene::resolve::{LocatedDescription, PathKind, path_kind};
use srt_scene::{
    Effects, LightDescription, LightsDescription, LoadedScene, Object, ObjectDescription, Observer,
    ObserverDescription, Part, ResolveError, Scene, SceneDescription, SceneError, SceneErrorKind,
    SceneSource, ShapeDescription, SurfaceColour, TextureDescription,
};

/// The scene opened when `srt view` is given no argument.
pub const DEFAULT_SCENE: &str = "teaser";

/// The fastest speed the speed slider offers, as a fraction of c.
pub const MAX_SLIDER_SPEED: f64 = 0.999;

/// How far in front of the camera an added model is placed, in radii of its bounding sphere
/// (times the cotangent of half the field of view: it then fills most of the image height).
const ADDED_MODEL_DISTANCE: f64 = 1.6;

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

/// Parses a speed typed by the user: a number ≥ 0 (a fraction of c), optionally followed by
/// `c`. Whether it is below the speed of light is the scene's rule, checked when it is set.
///
/// # Errors
/// [`EditError::Speed`] with a message for the status line when the text is not a finite
/// number or is negative.
pub fn parse_speed(text: &str) -> Result<f64, EditError> {
    let trimmed = text.trim();
    let number = trimmed.strip_suffix('c').unwrap_or(trimmed).trim();
    let speed = number
        .parse::<f64>()
        .ok()
        .filter(|speed| speed.is_finite())
        .ok_or_else(|| {
            EditError::Speed(format!(
                "\"{trimmed}\" is not a speed: type a fraction of the speed of light, e.g. 0.9"
            ))
        })?;
    if speed < 0.0 {
        return Err(EditError::Speed(format!(
            "a speed of {speed}c is negative: type a speed ≥ 0 and reverse the direction instead"
        )));
    }
    Ok(speed)
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
    /// The geometry ([`geometry_of`]) each runtime object's parts were built from, in order.
    built_from: Vec<Geometry>,
    /// Remembered unit direction of motion of each object (kept when the speed is 0).
    directions: Vec<DVec3>,
    home: Observer,
    structure_version: u64,
    /// Scenes built by edits so far (an edit of the observer alone builds none).
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
    /// An editor for a scene loaded by the resolver, and the warnings met loading it. Unnamed
    /// objects (and the scene) are given the names the runtime scene has, so that names stay
    /// put when objects are removed.
    fn from_loaded(loaded: LoadedScene) -> (Self, Vec<String>) {
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

    /// Opens one scene argument (a built-in scene, a `.toml` file or a model), as `srt render`
    /// does.
    ///
    /// # Errors
    /// As [`Editor::from_arguments`].
    pub fn open(argument: &str) -> Result<(Self, Vec<String>), EditError> {
        Ok(Self::from_loaded(
            SceneSource::resolve(argument)?.load(None)?,
        ))
    }

    /// Adds what a further argument names: a model in front of the camera, or the objects of a
    /// scene.
    fn add_argument(&mut self, argument: &str) -> Result<Vec<String>, EditError> {
        match SceneSource::resolve(argument)? {
            SceneSource::Model(path) => self.add_model(&path),
            source => self.merge(source.description(None)?),
        }
    }

    /// Adds the objects of `other` (whose paths are relative to its `base_dir`) to this scene.
    fn merge(&mut self, other: LocatedDescription) -> Result<Vec<String>, EditError> {
        let mut objects = other.description.objects;
        for object in &mut objects {
            absolutize_object(object, &other.base_dir);
        }
        self.add_objects(objects)
    }

    /// Appends `objects` (paths already absolute or `builtin:`), each under a name no other
    /// object has; nothing changes if any of them fails.
    fn add_objects(
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
                let (editor, warnings) = Self::from_loaded(source.load(None)?);
                let version = self.structure_version;
                *self = editor;
                self.structure_version = version + 1;
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

    /// Applies `change` to a copy of the description; if the scene file's rules accept the
    /// result, makes it the description and brings the runtime scene in step (building only
    /// objects whose geometry is new); otherwise nothing changes. Returns the warnings met
    /// building new objects.
    fn apply(
        &mut self,
        change: impl FnOnce(&mut SceneDescription) -> Result<(), EditError>,
    ) -> Result<Vec<String>, EditError> {
        let mut description = self.description.clone();
        change(&mut description)?;
        self.rebuild(description)
    }

    /// Makes `description` the description if the scene file's rules accept it, building the
    /// runtime scene's settings and the objects whose geometry is new; otherwise nothing
    /// changes. Returns the warnings met building new objects.
    fn rebuild(&mut self, description: SceneDescription) -> Result<Vec<String>, EditError> {
        description.validate()?;
        let frames = description.relative_frames()?;
        let geometry = geometries(&description, &frames);
        let plan = self.plan(&geometry);
        let (built, warnings) = self.build_new_objects(&description, &plan)?;
        self.builds += 1;
        self.commit(description, &plan, built, &frames, geometry);
        Ok(warnings)
    }

    /// Applies `change` to the observer (camera, time, velocity): the edit made every frame
    /// while time runs or the observer flies. Judged by the scene file's rules as every edit;
    /// then, when every object's geometry keeps its Wigner rotation (always for an observer at
    /// rest in W, and while the observer's velocity stays), the runtime scene follows the
    /// edit ([`Scene::follow`]) and nothing is built; otherwise as [`Editor::apply`].
    fn move_observer(
        &mut self,
        change: impl FnOnce(&mut ObserverDescription),
    ) -> Result<(), EditError> {
        let mut description = self.description.clone();
        change(&mut description.observer);
        description.validate()?;
        let kinematics = description.kinematics()?;
        let same_geometry = kinematics.frames.len() == self.built_from.len()
            && (kinematics.frames.iter())
                .zip(&self.built_from)
                .all(|(frame, built)| frame.rotation == built.rotation);
        if !same_geometry {
            return self.rebuild(description).map(|_no_new_objects| ());
        }
        self.scene.follow(&kinematics);
        self.description = description;
        Ok(())
    }

    /// [`Editor::apply`] for edits that add no object (and so meet no warning).
    fn edit(
        &mut self,
        change: impl FnOnce(&mut SceneDescription) -> Result<(), EditError>,
    ) -> Result<(), EditError> {
        self.apply(change).map(|_no_warnings| ())
    }

    /// Which runtime object's parts each object of an edited description, of `geometry`,
    /// keeps: the first one not yet taken with the same geometry.
    fn plan(&self, geometry: &[Geometry]) -> PartsPlan {
        let mut taken = vec![false; self.built_from.len()];
        geometry
            .iter()
            .map(|geometry| {
                let found =
                    (0..taken.len()).find(|&j| !taken[j] && self.built_from[j] == *geometry);
                if let Some(j) = found {
                    taken[j] = true;
                }
                found
            })
            .collect()
    }

    /// Builds the scene of `description` with only the objects `plan` does not find parts for:
    /// its observer, light and render settings, and those objects' parts, charged to one scene
    /// budget together with the parts the plan keeps. Warnings are those of the new objects.
    fn build_new_objects(
        &self,
        description: &SceneDescription,
        plan: &PartsPlan,
    ) -> Result<(Scene, Vec<String>), SceneError> {
        let new_objects: Vec<ObjectDescription> = description
            .objects
            .iter()
            .zip(plan)
            .filter(|(_, reused)| reused.is_none())
            .map(|(object, _)| object.clone())
            .collect();
        let nothing_new = new_objects.is_empty();
        let probe = SceneDescription {
            objects: new_objects,
            ..description.clone()
        };
        let mut budget = Budget::new();
        let kept_parts = plan
            .iter()
            .flatten()
            .flat_map(|&index| &self.scene.objects[index].parts);
        budget.charge_held_parts(kept_parts).map_err(|error| {
            let kind = SceneErrorKind::Value {
                field: "the objects this edit keeps".to_owned(),
                reason: format!("make the scene too large: {error}"),
            };
            SceneError::new(description.origin(), kind)
        })?;
        let (built, warnings) = probe.build_within(&self.base_dir, budget)?;
        // Without objects the only warning is that the probe has none, which is not news.
        Ok((built, if nothing_new { Vec::new() } else { warnings }))
    }

    /// Makes `description` the scene: the settings come from `built`, each object's parts from
    /// the runtime object `plan` names or, in order, from `built`'s objects.
    fn commit(
        &mut self,
        description: SceneDescription,
        plan: &PartsPlan,
        built: Scene,
        frames: &[RelativeFrame],
        geometry: Vec<Geometry>,
    ) {
        let old_count = self.scene.objects.len();
        // An object's parts and motion (both follow from its geometry, spin and thrust included).
        let mut kept: Vec<Option<(Vec<Part>, Motion)>> = std::mem::take(&mut self.scene.objects)
            .into_iter()
            .map(|object| Some((object.parts, object.motion)))
            .collect();
        let mut new_parts = built
            .objects
            .into_iter()
            .map(|object| (object.parts, object.motion));
        let objects = description
            .objects
            .iter()
            .zip(plan)
            .zip(frames)
            .enumerate()
            .map(|(index, ((object, reused), frame))| {
                let (parts, motion) = match reused {
                    Some(j) => kept[*j].take(),
                    None => new_parts.next(),
                }
                .expect("the plan takes each runtime object once and builds the rest");
                Object {
                    name: runtime_name(object, index),
                    parts,
                    frame: frame.frame,
                    rest_time_shift: frame.rest_time_shift,
                    wireframe: object.wireframe,
                    optics: object.optics(),
                    clock: object.clock(),
                    motion,
                }
            })
            .collect();
        let unchanged = plan.len() == old_count
            && plan
                .iter()
                .enumerate()
                .all(|(i, reused)| *reused == Some(i));
        if !unchanged {
            self.structure_version += 1;
        }
        self.built_from = geometry;
        self.scene = Scene { objects, ..built };
        self.description = description;
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

    /// The objects of the scene.
    #[must_use]
    pub fn objects(&self) -> &[Object] {
        &self.scene.objects
    }

    /// Speed |β| of object `index` relative to the scene's world frame, as a fraction of c (0
    /// for an index out of range).
    #[must_use]
    pub fn speed(&self, index: usize) -> f64 {
        self.description
            .objects
            .get(index)
            .map_or(0.0, |o| DVec3::from_array(o.beta).length())
    }

    /// Unit direction of motion of object `index` (remembered while its speed is 0).
    #[must_use]
    pub fn direction(&self, index: usize) -> DVec3 {
        self.directions.get(index).copied().unwrap_or(DVec3::X)
    }

    /// Offset **a** of object `index`: where its S′ origin is in the world frame at t = 0.
    #[must_use]
    pub fn offset(&self, index: usize) -> DVec3 {
        self.description
            .objects
            .get(index)
            .map_or(DVec3::ZERO, |o| DVec3::from_array(o.offset))
    }

    /// The observer's velocity through the scene's world frame, in units of c.
    #[must_use]
    pub fn observer_beta(&self) -> DVec3 {
        DVec3::from_array(self.description.observer.beta)
    }

    /// The light's temperature (kelvin) and its position in the world frame at the observation
    /// time (what [`Editor::set_light`] sets; the runtime scene has it in the observer's frame).
    #[must_use]
    pub fn light(&self) -> (f64, DVec3) {
        (self.description.light.as_ref())
            .and_then(LightsDescription::lamp)
            .map_or(
                (self.scene.light.temperature_k, self.scene.light.position),
                |light| (light.temperature_k, DVec3::from_array(light.position)),
            )
    }

    /// The wireframe line width of object `index` (`None`: textured).
    #[must_use]
    pub fn wireframe(&self, index: usize) -> Option<f64> {
        self.scene.objects.get(index).and_then(|o| o.wireframe)
    }

    /// Sets the velocity of object `index` (relative to the scene's world frame) to
    /// `speed · direction`. With `keep_apparent`, the offset changes too, so that the object's
    /// origin stays where the observer sees it now (only its shape and colour change);
    /// otherwise the offset stays.
    ///
    /// # Errors
    /// [`EditError::Direction`] for a zero or non-finite direction, [`EditError::Scene`] for a
    /// velocity or offset the scene file's rules refuse (a speed of 1 or more…); the scene is
    /// then unchanged.
    pub fn set_velocity(
        &mut self,
        index: usize,
        speed: f64,
        direction: DVec3,
        keep_apparent: bool,
    ) -> Result<(), EditError> {
        let object = self
            .description
            .objects
            .get(index)
            .ok_or(EditError::NoSuchObject(index))?;
        // Everything in the world frame: the description's velocity, offset and observation
        // event (the emission event seen now is the same event in every frame).
        let old = Frame::new(
            DVec3::from_array(object.beta),
            DVec3::from_array(object.offset),
        )
        .map_err(|error| {
            let kind = SceneErrorKind::Frame {
                object: object.label(index),
                error,
            };
            SceneError::new(self.description.origin(), kind)
        })?;
        let unit = direction
            .try_normalize()
            .ok_or(EditError::Direction(direction))?;
        let beta = speed * unit;
        let offset = if keep_apparent {
            let observer = &self.description.observer;
            let observer = Event::new(observer.ct, DVec3::from_array(observer.position));
            let apparent = old.apparent_position(DVec3::ZERO, observer);
            let distance = (apparent - observer.position).length();
            offset_keeping_apparent_position(apparent, distance, observer.ct, beta)
        } else {
            old.offset()
        };
        self.edit_object(index, |object| {
            object.beta = beta.to_array();
            object.offset = offset.to_array();
        })?;
        self.directions[index] = beta.try_normalize().unwrap_or(unit);
        Ok(())
    }

    /// Sets the offset **a** of object `index`.
    ///
    /// # Errors
    /// [`EditError::Scene`] for an offset the scene file's rules refuse (not finite, too far).
    pub fn set_offset(&mut self, index: usize, offset: DVec3) -> Result<(), EditError> {
        self.edit_object(index, |object| object.offset = offset.to_array())
    }

    /// Draws object `index` as a wireframe of lines `width` wide (in its own units), or textured.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a width the scene file's rules refuse (not positive…).
    pub fn set_wireframe(&mut self, index: usize, width: Option<f64>) -> Result<(), EditError> {
        self.edit_object(index, |object| object.wireframe = width)
    }

    /// The spin of object `index` as its description gives it (`None`: it does not spin).
    #[must_use]
    pub fn spin(&self, index: usize) -> Option<SpinDescription> {
        self.description.objects.get(index).and_then(|o| o.spin)
    }

    /// The thrust of object `index` as its description gives it (`None`: it does not thrust).
    #[must_use]
    pub fn thrust(&self, index: usize) -> Option<ThrustDescription> {
        self.description.objects.get(index).and_then(|o| o.thrust)
    }

    /// Sets (or, with `None`, removes) the spin of object `index`.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a spin the scene file's rules refuse (a zero axis, a point
    /// reaching the speed of light, a thrust as well…); the scene is then unchanged.
    pub fn set_spin(
        &mut self,
        index: usize,
        spin: Option<SpinDescription>,
    ) -> Result<(), EditError> {
        self.edit_object(index, |object| object.spin = spin)
    }

    /// Sets (or, with `None`, removes) the thrust of object `index`.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a thrust the scene file's rules refuse (a zero acceleration, a
    /// point beyond the Rindler horizon, a spin as well…); the scene is then unchanged.
    pub fn set_thrust(
        &mut self,
        index: usize,
        thrust: Option<ThrustDescription>,
    ) -> Result<(), EditError> {
        self.edit_object(index, |object| object.thrust = thrust)
    }

    /// Applies `change` to the description of object `index`, as [`Editor::apply`] does.
    fn edit_object(
        &mut self,
        index: usize,
        change: impl FnOnce(&mut ObjectDescription),
    ) -> Result<(), EditError> {
        self.edit(|description| {
            change(object_mut(description, index)?);
            Ok(())
        })
    }

    /// Sets the effect mode (and the tone map that goes with it, unless one was chosen).
    ///
    /// # Errors
    /// None in practice: every effect mode is valid (the edit goes through the same checks as
    /// any other).
    pub fn set_effects(&mut self, effects: Effects) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.effects = effects;
            Ok(())
        })
    }

    /// Chooses how lit surfaces are coloured; going back to the paper's colour resets the
    /// exposure to 1 (its colour tables have none).
    ///
    /// # Errors
    /// None in practice, as [`Editor::set_effects`].
    pub fn set_colour(&mut self, colour: SurfaceColour) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.colour = colour;
            if colour == SurfaceColour::Paper {
                description.render.exposure = 1.0;
            }
            Ok(())
        })
    }

    /// Sets the exposure of spectral colour.
    ///
    /// # Errors
    /// [`EditError::Scene`] for an exposure the scene file's rules refuse (not positive, or
    /// with the paper's colour).
    pub fn set_exposure(&mut self, exposure: f64) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.exposure = exposure;
            Ok(())
        })
    }

    /// The tone map chosen explicitly (`None`: the effect mode's).
    #[must_use]
    pub fn tone_map_choice(&self) -> Option<ToneMap> {
        self.description.render.tone_map
    }

    /// Chooses the tone map (`None`: the effect mode's own).
    ///
    /// # Errors
    /// None in practice, as [`Editor::set_effects`].
    pub fn set_tone_map(&mut self, tone_map: Option<ToneMap>) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.tone_map = tone_map;
            Ok(())
        })
    }

    /// Sets the light's temperature (kelvin) and position.
    ///
    /// # Errors
    /// [`EditError::Scene`] for values the scene file's rules refuse (a temperature that is not
    /// positive, a position that is not finite…).
    pub fn set_light(&mut self, temperature_k: f64, position: DVec3) -> Result<(), EditError> {
        self.edit(|description| {
            let lamp = LightDescription::lamp(position.to_array(), temperature_k);
            match description
                .light
                .as_mut()
                .and_then(LightsDescription::lamp_mut)
            {
                Some(light) => {
                    light.position = lamp.position;
                    light.temperature_k = temperature_k;
                }
                None => description.light = Some(LightsDescription::Lamp(lamp)),
            }
            Ok(())
        })
    }

    /// The lamp's strength (a multiplier on all its light; 0: no lamp).
    #[must_use]
    pub fn lamp_strength(&self) -> f64 {
        self.scene.light.strength
    }

    /// Sets the lamp's strength (0 turns it off, ambient light included).
    ///
    /// # Errors
    /// [`EditError::Scene`] for a strength the scene file's rules refuse (negative, not finite).
    pub fn set_lamp_strength(&mut self, strength: f64) -> Result<(), EditError> {
        let observer = self.description.observer.position;
        self.edit(|description| {
            let lights = light_list(description, observer);
            if let Some(lamp) = lights.iter_mut().find(|l| l.carried) {
                lamp.strength = strength;
            }
            Ok(())
        })
    }

    /// The moving lights as the scene file gives them (position in W at t = 0, velocity,
    /// temperature, strength), in order.
    #[must_use]
    pub fn moving_lights(&self) -> Vec<LightDescription> {
        (self.description.light.iter())
            .flat_map(LightsDescription::moving)
            .cloned()
            .collect()
    }

    /// Adds a moving light: 6000 K, at rest in W, 2 above the point 6 ahead of the camera, of
    /// strength 36 (the lamp's diffuse light at 6 units); returns its index.
    ///
    /// # Errors
    /// [`EditError::Scene`] when the scene has as many moving lights as it may.
    pub fn add_moving_light(&mut self) -> Result<usize, EditError> {
        let observer = self.description.observer.position;
        let (forward, _, up) = self.scene.observer.basis();
        let place = DVec3::from_array(observer) + 6.0 * forward + 2.0 * up;
        let light = LightDescription {
            carried: false,
            strength: 36.0,
            ..LightDescription::lamp(place.to_array(), DEFAULT_LIGHT_TEMPERATURE_K)
        };
        self.edit(|description| {
            light_list(description, observer).push(light);
            Ok(())
        })?;
        Ok(self.scene.lights.len() - 1)
    }

    /// Replaces moving light `index` with `light` (its `carried` flag is ignored).
    ///
    /// # Errors
    /// [`EditError::NoSuchLight`] when there is none; [`EditError::Scene`] for values the scene
    /// file's rules refuse (a speed of 1 or more, a temperature that is not positive…).
    pub fn set_moving_light(
        &mut self,
        index: usize,
        light: LightDescription,
    ) -> Result<(), EditError> {
        let observer = self.description.observer.position;
        self.edit(|description| {
            let entry = moving_light_mut(light_list(description, observer), index)?;
            *entry = LightDescription {
                carried: false,
                ..light
            };
            Ok(())
        })
    }

    /// Removes moving light `index`.
    ///
    /// # Errors
    /// [`EditError::NoSuchLight`] when there is none.
    pub fn remove_moving_light(&mut self, index: usize) -> Result<(), EditError> {
        let observer = self.description.observer.position;
        self.edit(|description| {
            let lights = light_list(description, observer);
            let position = (lights.iter().enumerate())
                .filter(|(_, l)| !l.carried)
                .nth(index)
                .map(|(position, _)| position)
                .ok_or(EditError::NoSuchLight(index))?;
            lights.remove(position);
            Ok(())
        })
    }

    /// Whether objects cast the moving lights' shadows.
    #[must_use]
    pub fn shadows(&self) -> bool {
        self.scene.shadows
    }

    /// Turns the moving lights' shadows on or off.
    ///
    /// # Errors
    /// None in practice (the scene is rebuilt as for any edit).
    pub fn set_shadows(&mut self, shadows: bool) -> Result<(), EditError> {
        self.edit(|description| {
            description.render.shadows = shadows;
            Ok(())
        })
    }

    /// Sets the observer (camera and observation time).
    ///
    /// # Errors
    /// [`EditError::Scene`] for values the scene file's rules refuse (a zero direction, an up
    /// vector parallel to it, a field of view outside (0°, 180°), a position or time that is not
    /// finite…); the observer is then unchanged.
    pub fn set_observer(&mut self, observer: Observer) -> Result<(), EditError> {
        self.move_observer(|description| {
            *description = ObserverDescription {
                position: observer.position.to_array(),
                look_at: None,
                direction: Some(observer.direction.to_array()),
                beta: description.beta,
                up: observer.up.to_array(),
                fov_y_deg: observer.fov_y_deg,
                ct: observer.ct,
            };
        })
    }

    /// Sets the observation time ct (in the world frame). A moving observer moves along its
    /// worldline: its position changes by β_o (ct − ct_before).
    ///
    /// # Errors
    /// [`EditError::Scene`] for a time the scene file's rules refuse (not finite, too large).
    pub fn set_time(&mut self, ct: f64) -> Result<(), EditError> {
        self.move_observer(|observer| {
            // A time the rules refuse is refused by its own name, not by a position made from it.
            if observer.beta != [0.0; 3] && ct.is_finite() {
                let moved = DVec3::from_array(observer.beta) * (ct - observer.ct);
                observer.position = (DVec3::from_array(observer.position) + moved).to_array();
            }
            observer.ct = ct;
        })
    }

    /// Sets the observer's velocity through the scene's world frame (units of c); the objects
    /// keep their velocities relative to the world frame.
    ///
    /// # Errors
    /// [`EditError::Scene`] for a velocity the scene file's rules refuse (|β| ≥ 1, not finite).
    pub fn set_observer_beta(&mut self, beta: DVec3) -> Result<(), EditError> {
        self.move_observer(|observer| observer.beta = beta.to_array())
    }

    /// The observation event in the world frame W (the description's observer position and ct).
    #[must_use]
    pub fn observer_event(&self) -> Event {
        let observer = &self.description.observer;
        Event::new(observer.ct, DVec3::from_array(observer.position))
    }

    /// Moves the observer to the event `event` (in W) with velocity `beta` through W, in one
    /// edit: one step of a flight (the camera's direction, up and field of view stay).
    ///
    /// # Errors
    /// [`EditError::Scene`] for values the scene file's rules refuse (|β| ≥ 1, a position or
    /// time that is not finite or too large); the observer is then unchanged.
    pub fn set_observer_motion(&mut self, event: Event, beta: DVec3) -> Result<(), EditError> {
        let direction = self.scene.observer.direction;
        self.move_observer(|observer| {
            // A point looked at would turn the camera as it moves: keep today's direction.
            observer.look_at = None;
            observer.direction = Some(direction.to_array());
            observer.position = event.position.to_array();
            observer.ct = event.ct;
            observer.beta = beta.to_array();
        })
    }

    /// The observer the scene started with (for "reset view").
    #[must_use]
    pub const fn home(&self) -> Observer {
        self.home
    }

    /// Puts the camera back where the scene started (the observation time stays).
    ///
    /// # Errors
    /// As [`Editor::set_observer`] (the home observer was accepted when the scene was built).
    pub fn reset_view(&mut self) -> Result<(), EditError> {
        self.set_observer(Observer {
            ct: self.scene.observer.ct,
            ..self.home
        })
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

/// The [`Geometry`] of `object`, whose frame relative to the observer is `frame`.
fn geometry_of(object: &ObjectDescription, frame: &RelativeFrame) -> Geometry {
    Geometry {
        object: ObjectDescription {
            name: None,
            wireframe: None,
            beta: [0.0; 3],
            offset: [0.0; 3],
            ..object.clone()
        },
        rotation: frame.rotation,
    }
}

/// The [`Geometry`] of every object of `description`, whose relative frames are `frames`.
fn geometries(description: &SceneDescription, frames: &[RelativeFrame]) -> Vec<Geometry> {
    description
        .objects
        .iter()
        .zip(frames)
        .map(|(object, frame)| geometry_of(object, frame))
        .collect()
}

/// The name the runtime object of `object`, number `index` (from 0), has: its own, or
/// `object N` as [`SceneDescription::build`] names it.
fn runtime_name(object: &ObjectDescription, index: usize) -> String {
    object.name.clone().unwrap_or_else(|| object.label(index))
}

/// The description of object `index`.
fn object_mut(
    description: &mut SceneDescription,
    index: usize,
) -> Result<&mut ObjectDescription, EditError> {
    description
        .objects
        .get_mut(index)
        .ok_or(EditError::NoSuchObject(index))
}

/// `base`, or `base 2`, `base 3`… whichever is not in `taken`.
fn unique_name(base: &str, taken: &[String]) -> String {
    let free = |name: &String| !taken.contains(name);
    std::iter::once(base.to_owned())
        .chain((2..).map(|n| format!("{base} {n}")))
        .find(free)
        .unwrap_or_default()
}

/// Direction of motion to remember for an object moving with `beta`: its own, or (at rest)
/// towards the observer.
fn default_direction(beta: DVec3, observer: &Observer) -> DVec3 {
    beta.try_normalize().unwrap_or_else(|| -observer.basis().0)
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

/// The model and texture paths of `object` made absolute against `base_dir`.
fn absolutize_object(object: &mut ObjectDescription, base_dir: &Path) {
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

/// The description's lights as a `[[light]]` list, made one if needed: a `[light]` table
/// becomes the list's carried entry, no light key the default lamp at `observer` (where it sits
/// without one), so that the scene lights as before.
fn light_list(
    description: &mut SceneDescription,
    observer: [f64; 3],
) -> &mut Vec<LightDescription> {
    let list = match description.light.take() {
        Some(LightsDescription::List(list)) => list,
        Some(LightsDescription::Lamp(lamp)) => vec![LightDescription {
            carried: true,
            ..lamp
        }],
        None => vec![LightDescription {
            carried: true,
            ..LightDescription::lamp(observer, DEFAULT_LIGHT_TEMPERATURE_K)
        }],
    };
    match description.light.insert(LightsDescription::List(list)) {
        LightsDescription::List(list) => list,
        LightsDescription::Lamp(_) => unreachable!("a list was just inserted"),
    }
}

/// The moving light `index` of a `[[light]]` list (its entries that are not carried).
fn moving_light_mut(
    lights: &mut [LightDescription],
    index: usize,
) -> Result<&mut LightDescription, EditError> {
    (lights.iter_mut())
        .filter(|l| !l.carried)
        .nth(index)
        .ok_or(EditError::NoSuchLight(index))
}

#[cfg(test)]
mod tests {
    use crate::camera;
    use srt_scene::load_scene_file;
    use srt_scene::resolve::DEFAULT_MODEL_SPEED;

    use super::*;

    fn teaser() -> Editor {
        Editor::from_arguments(&[]).expect("the teaser builds").0
    }

    /// A folder holding the tetrahedron fixture as `tetra.stl`, and that file's path.
    fn tetrahedron_file() -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let model = dir.path().join("tetra.stl");
        std::fs::write(&model, tetrahedron_stl()).unwrap();
        (dir, model)
    }

    #[test]
    fn spin_and_thrust_are_edits_checked_like_the_scene_file() {
        let (mut editor, _) = Editor::open("fig7").unwrap();
        let spin = SpinDescription {
            axis: [0.0, 0.0, 1.0],
            rate: 0.5,
            centre: [0.0; 3],
        };
        editor.set_spin(0, Some(spin)).unwrap();
        assert_eq!(editor.spin(0), Some(spin));
        assert!(matches!(
            editor.scene().objects[0].motion,
            srt_physics::motion::Motion::Spin(_)
        ));
        // A rim at the speed of light, or a thrust as well, is refused; nothing changes.
        let too_fast = SpinDescription { rate: 5.0, ..spin };
        assert!(editor.set_spin(0, Some(too_fast)).is_err());
        assert_eq!(editor.spin(0), Some(spin));
        let thrust = ThrustDescription {
            proper_acceleration: [0.0, 0.1, 0.0],
            start: 0.0,
            duration: f64::INFINITY,
        };
        assert!(editor.set_thrust(0, Some(thrust)).is_err());
        editor.set_spin(0, None).unwrap();
        editor.set_thrust(0, Some(thrust)).unwrap();
        assert!(matches!(
            editor.scene().objects[0].motion,
            srt_physics::motion::Motion::Thrust(_)
        ));
        editor.set_thrust(0, None).unwrap();
        assert!(editor.scene().objects[0].motion.is_rest());
    }

    #[test]
    fn moving_lights_are_added_edited_and_removed_like_objects() {
        let (mut editor, _) = Editor::open("fig7").unwrap();
        let lamp = editor.scene().light;
        assert!(editor.moving_lights().is_empty());
        let index = editor.add_moving_light().unwrap();
        assert_eq!(index, 0);
        // The `[light]` table became the list's carried lamp: it lights as before.
        assert_eq!(editor.scene().light, lamp);
        assert_eq!(editor.scene().lights.len(), 1);
        let mut light = editor.moving_lights()[0].clone();
        light.beta = [0.0, 0.8, 0.0];
        light.temperature_k = 4000.0;
        editor.set_moving_light(0, light.clone()).unwrap();
        assert_eq!(
            editor.scene().lights[0].frame.beta(),
            DVec3::new(0.0, 0.8, 0.0)
        );
        assert_eq!(editor.scene().lights[0].temperature_k, 4000.0);
        // Refused like a scene file's value; nothing changes.
        light.beta = [0.0, 1.0, 0.0];
        assert!(editor.set_moving_light(0, light).is_err());
        assert_eq!(
            editor.scene().lights[0].frame.beta(),
            DVec3::new(0.0, 0.8, 0.0)
        );
        assert!(matches!(
            editor.set_moving_light(3, LightDescription::lamp([0.0; 3], 5000.0)),
            Err(EditError::NoSuchLight(3))
        ));
        editor.set_lamp_strength(0.0).unwrap();
        assert_eq!(editor.scene().light.strength, 0.0);
        assert!(editor.set_lamp_strength(-1.0).is_err());
        assert!(editor.shadows());
        editor.set_shadows(false).unwrap();
        assert!(!editor.scene().shadows);
        // Saved and read back, the lights are the same.
        let text = editor.description_for_saving().to_toml_string();
        let saved = SceneDescription::from_toml_str(&text, "saved").unwrap();
        assert_eq!(saved.light, editor.description().light);
        editor.remove_moving_light(0).unwrap();
        assert!(editor.scene().lights.is_empty());
        assert_eq!(editor.scene().light.strength, 0.0);
        assert!(matches!(
            editor.remove_moving_light(0),
            Err(EditError::NoSuchLight(0))
        ));
    }

    #[test]
    fn spectral_colour_and_exposure_are_edits_checked_like_the_scene_file() {
        let (mut editor, _) = Editor::open("teaser").unwrap();
        assert_eq!(editor.scene().colour, SurfaceColour::Paper);
        // The paper's colour tables have no exposure.
        assert!(editor.set_exposure(2.0).is_err());
        assert_eq!(editor.scene().exposure, 1.0);
        editor.set_colour(SurfaceColour::Spectral).unwrap();
        editor.set_exposure(2.0).unwrap();
        assert_eq!(editor.scene().exposure, 2.0);
        assert!(editor.set_exposure(-1.0).is_err());
        assert!(editor.set_exposure(f64::NAN).is_err());
        assert_eq!(editor.scene().exposure, 2.0);
        // Back to the paper's colour: the exposure goes back to 1.
        editor.set_colour(SurfaceColour::Paper).unwrap();
        assert_eq!(editor.scene().exposure, 1.0);
    }

    #[test]
    fn typed_speeds_are_numbers_of_at_least_zero() {
        assert_eq!(parse_speed("0.9").unwrap(), 0.9);
        assert_eq!(parse_speed(" 0.5c ").unwrap(), 0.5);
        assert_eq!(parse_speed("0").unwrap(), 0.0);
        assert_eq!(parse_speed("0.9999").unwrap(), 0.9999);
        // Whether it is below c is the scene's rule, checked when the speed is set.
        assert_eq!(parse_speed("1.5c").unwrap(), 1.5);
        let message = |text| parse_speed(text).unwrap_err().to_string();
        assert!(message("fast").contains("not a speed"));
        assert!(message("NaN").contains("not a speed"));
        assert!(message("inf").contains("not a speed"));
        assert!(message("-0.5").contains("negative"));
    }

    /// Refused edits say what the scene file says about the same values, and change nothing.
    #[test]
    fn refused_edits_give_the_scene_files_message_and_change_nothing() {
        type Edit = fn(&mut Editor) -> Result<(), EditError>;
        type Same = fn(&mut SceneDescription);
        let cases: [(&str, Edit, Same); 6] = [
            (
                "speed",
                |e| e.set_velocity(1, 1.5, DVec3::X, false),
                |d| d.objects[1].beta = [1.5, 0.0, 0.0],
            ),
            (
                "offset",
                |e| e.set_offset(2, DVec3::new(0.0, f64::NAN, 0.0)),
                |d| d.objects[2].offset[1] = f64::NAN,
            ),
            (
                "wireframe",
                |e| e.set_wireframe(0, Some(-1.0)),
                |d| d.objects[0].wireframe = Some(-1.0),
            ),
            (
                "light",
                |e| e.set_light(0.0, DVec3::ONE),
                |d| {
                    d.light = Some(LightsDescription::Lamp(LightDescription::lamp(
                        [1.0; 3], 0.0,
                    )));
                },
            ),
            (
                "time",
                |e| e.set_time(f64::INFINITY),
                |d| {
                    d.observer.ct = f64::INFINITY;
                },
            ),
            (
                "field of view",
                |e| {
                    let observer = e.scene().observer;
                    e.set_observer(Observer {
                        fov_y_deg: 180.0,
                        ..observer
                    })
                },
                |d| d.observer.fov_y_deg = 180.0,
            ),
        ];
        for (what, edit, same) in cases {
            let mut editor = teaser();
            let (description, scene) = (editor.description().clone(), editor.scene().clone());
            let version = editor.structure_version();
            let error = edit(&mut editor).unwrap_err();
            assert!(matches!(error, EditError::Scene(_)), "{what}: {error}");
            let mut expected = description.clone();
            same(&mut expected);
            assert_eq!(
                error.to_string(),
                expected.validate().unwrap_err().to_string(),
                "{what}"
            );
            assert_eq!(editor.description(), &description, "{what}");
            assert_eq!(editor.scene(), &scene, "{what}");
            assert_eq!(editor.structure_version(), version, "{what}");
        }
    }

    #[test]
    fn a_speed_of_c_or_more_is_refused_naming_the_speed_of_light() {
        let mut editor = teaser();
        for text in ["1", "1.0", "1c", "300000"] {
            let speed = parse_speed(text).unwrap();
            let error = editor.set_velocity(1, speed, DVec3::X, true).unwrap_err();
            assert!(
                error.to_string().contains("speed of light"),
                "{text}: {error}"
            );
        }
        assert!(matches!(
            editor.set_velocity(1, 0.5, DVec3::ZERO, true),
            Err(EditError::Direction(_))
        ));
        assert!(matches!(
            editor.set_velocity(7, 0.5, DVec3::X, true),
            Err(EditError::NoSuchObject(7))
        ));
        assert_eq!(editor.description(), teaser().description());
    }

    #[test]
    fn no_argument_opens_the_teaser() {
        let editor = teaser();
        assert_eq!(editor.scene().name, "teaser");
        assert_eq!(editor.object_count(), 3);
        assert!((editor.speed(0) - 0.95).abs() < 1e-3);
    }

    #[test]
    fn further_arguments_add_objects_under_names_of_their_own() {
        let arguments = ["fig7", "teaser", "teaser"].map(str::to_owned);
        let (editor, _) = Editor::from_arguments(&arguments).unwrap();
        assert_eq!(editor.object_count(), 7);
        let names: Vec<_> = editor.objects().iter().map(|o| o.name.as_str()).collect();
        assert!(
            names
                .iter()
                .all(|n| names.iter().filter(|m| *m == n).count() == 1),
            "{names:?}"
        );
        let described: Vec<_> = editor
            .description()
            .objects
            .iter()
            .map(|o| o.name.as_deref().unwrap_or_default())
            .collect();
        assert_eq!(described, names);
    }

    #[test]
    fn a_bare_model_approaches_the_observer() {
        let (_dir, model) = tetrahedron_file();
        let (editor, _) = Editor::from_arguments(&[model.display().to_string()]).unwrap();
        let object = &editor.scene().objects[0];
        let observer = editor.scene().observer.event();
        let seen = object.frame.apparent_position(DVec3::ZERO, observer);
        let towards_observer = (observer.position - seen).normalize();
        assert!((editor.speed(0) - DEFAULT_MODEL_SPEED).abs() < 1e-12);
        assert!(object.frame.beta().normalize().dot(towards_observer) > 0.999);
    }

    #[test]
    fn unknown_arguments_and_unsupported_files_are_refused_by_the_resolver() {
        assert!(matches!(
            Editor::from_arguments(&["no-such-scene".to_owned()]),
            Err(EditError::Source(ResolveError::NotFound(_)))
        ));
        let dir = tempfile::tempdir().unwrap();
        let notes = dir.path().join("notes.txt");
        std::fs::write(&notes, "hello").unwrap();
        let mut editor = teaser();
        for result in [
            editor.open_file(&notes),
            editor.add_model(&notes),
            editor.add_model(Path::new("teaser")),
        ] {
            assert!(
                matches!(result, Err(EditError::Source(ResolveError::Unsupported(_)))),
                "{result:?}"
            );
        }
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
        assert_eq!(editor.object_count(), 3);
        assert_eq!(editor.description().objects.len(), 3);
        assert_eq!(editor.structure_version(), version);
    }

    #[test]
    fn models_are_added_in_view_and_removed() {
        let (_dir, model) = tetrahedron_file();
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
        assert_eq!(editor.description().objects.len(), 4);
        assert_eq!(editor.objects()[2].name, "tetra");
        assert!(editor.structure_version() > version);
        assert!(editor.remove_object(9).is_err());
    }

    /// Edits of motion, time, light and style reuse the loaded parts: they succeed with the
    /// model file gone, and the meshes need no new upload.
    #[test]
    fn cheap_edits_never_read_a_model_file_again() {
        let (dir, model) = tetrahedron_file();
        let mut editor = teaser();
        editor.add_model(&model).unwrap();
        drop(dir);
        assert!(!model.exists());
        let version = editor.structure_version();
        editor.set_velocity(3, 0.8, DVec3::Y, true).unwrap();
        editor.set_offset(3, DVec3::new(1.0, 2.0, 3.0)).unwrap();
        editor.set_wireframe(3, Some(0.05)).unwrap();
        editor.set_time(1.5).unwrap();
        editor.set_light(5000.0, DVec3::ONE).unwrap();
        editor.set_effects(Effects::Geometry).unwrap();
        assert_eq!(editor.structure_version(), version);
        editor.remove_object(0).unwrap();
        let tetra = &editor.objects()[2];
        assert_eq!((tetra.name.as_str(), tetra.triangle_count()), ("tetra", 4));
        assert_eq!(tetra.frame.offset(), DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(tetra.wireframe, Some(0.05));
    }

    /// The parts an edit keeps count against the scene's budget with the ones it builds: two
    /// cubes of 1.08 million triangles each do not fit in one scene (2 million), even when
    /// they are made one edit at a time.
    #[test]
    fn kept_parts_count_against_the_scene_budget() {
        let mut editor = teaser();
        let big_cube = |object: &mut ObjectDescription| {
            object.shape = ShapeDescription::Cube {
                size: 1.0,
                subdivisions: 300,
            };
        };
        editor.edit_object(0, big_cube).unwrap();
        let refused = editor.edit_object(1, big_cube).unwrap_err().to_string();
        assert!(
            refused.contains("too large") && refused.contains("already loaded"),
            "{refused}"
        );
        assert_ne!(editor.objects()[1].triangle_count(), 12 * 300 * 300);
    }

    /// An edit of an object's geometry rebuilds that object (and only needs its own files).
    #[test]
    fn an_edit_of_the_geometry_rebuilds_the_object() {
        let mut editor = teaser();
        let version = editor.structure_version();
        let triangles = editor.objects()[0].triangle_count();
        editor
            .edit_object(1, |object| {
                object.shape = ShapeDescription::Cube {
                    size: 2.0,
                    subdivisions: 3,
                };
            })
            .unwrap();
        assert_eq!(editor.objects()[1].triangle_count(), 12 * 3 * 3);
        assert_eq!(editor.objects()[0].triangle_count(), triangles);
        assert!(editor.structure_version() > version);
    }

    #[test]
    fn saved_scenes_load_back_with_the_edits() {
        let (dir, model) = tetrahedron_file();
        let mut editor = teaser();
        editor.add_model(&model).unwrap();
        editor
            .set_velocity(3, 0.9, DVec3::new(0.0, -1.0, 0.0), true)
            .unwrap();
        editor.set_effects(Effects::Searchlight).unwrap();
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
        for refused in [
            Observer {
                direction: DVec3::ZERO,
                ..moved
            },
            Observer {
                direction: moved.up,
                ..moved
            },
        ] {
            assert!(matches!(
                editor.set_observer(refused),
                Err(EditError::Scene(_))
            ));
        }
        assert_eq!(editor.scene().observer.fov_y_deg, 60.0);
        editor.set_time(4.0).unwrap();
        editor.reset_view().unwrap();
        assert_eq!(editor.scene().observer.position, home.position);
        assert_eq!(editor.scene().observer.ct, 4.0);
    }

    #[test]
    fn effects_and_tone_maps() {
        let mut editor = teaser();
        editor.set_effects(Effects::Searchlight).unwrap();
        assert_eq!(editor.scene().tone_map, ToneMap::Searchlight);
        editor.set_tone_map(Some(ToneMap::Luminance)).unwrap();
        assert_eq!(editor.scene().tone_map, ToneMap::Luminance);
        editor.set_effects(Effects::Geometry).unwrap();
        assert_eq!(editor.scene().tone_map, ToneMap::Luminance);
        editor.set_tone_map(None).unwrap();
        editor.set_effects(Effects::Searchlight).unwrap();
        assert_eq!(editor.scene().tone_map, ToneMap::Searchlight);
    }

    /// The editor's runtime scene is what building its description from scratch gives.
    fn assert_matches_a_fresh_build(editor: &Editor) {
        let (fresh, _) = editor.description().build(&editor.base_dir).unwrap();
        assert_eq!(editor.scene(), &fresh);
    }

    /// What runs every frame while time plays or the observer flies (time, camera, a flight's
    /// step) moves the runtime scene without building it, and gives what a fresh build of the
    /// edited description gives; a change of the observer's velocity that turns moving
    /// objects' geometry (the Wigner rotation) builds, as it must.
    #[test]
    fn time_and_flight_move_the_scene_without_building_it() {
        for name in ["teaser", "flythrough"] {
            let (mut editor, _) = Editor::open(name).unwrap();
            let builds = editor.builds;
            for step in 1..=3 {
                editor.set_time(0.5 * f64::from(step)).unwrap();
                assert_matches_a_fresh_build(&editor);
            }
            let observer = camera::turn(&editor.scene().observer, 0.1, -0.05);
            editor.set_observer(observer).unwrap();
            assert_matches_a_fresh_build(&editor);
            // A coasting flight: the observer moves on along its worldline, velocity unchanged.
            let beta = editor.observer_beta();
            let event = editor.observer_event();
            let next = Event::new(event.ct + 0.25, event.position + beta * 0.25);
            editor.set_observer_motion(next, beta).unwrap();
            assert_matches_a_fresh_build(&editor);
            assert_eq!(
                editor.builds, builds,
                "{name}: an observer edit built the scene"
            );
        }
        // Thrust changes the observer's velocity: the teaser's moving objects turn, so it builds.
        let (mut editor, _) = Editor::open("teaser").unwrap();
        let builds = editor.builds;
        editor
            .set_observer_motion(editor.observer_event(), DVec3::new(0.0, 0.1, 0.0))
            .unwrap();
        assert_eq!(editor.builds, builds + 1);
        assert_matches_a_fresh_build(&editor);
        // A time the rules refuse is refused on the fast path too, changing nothing.
        let before = editor.scene().clone();
        assert!(matches!(
            editor.set_time(f64::NAN),
            Err(EditError::Scene(_))
        ));
        assert_eq!(editor.scene(), &before);
    }

    /// With a moving observer, edits are made in the world frame, and parts turned by the
    /// Wigner rotation are rebuilt when a velocity changes the rotation.
    #[test]
    fn a_moving_observer_is_edited_in_the_world_frame() {
        let (mut editor, _) = Editor::open("flythrough").unwrap();
        let beta_o = DVec3::new(0.0, 0.9, 0.0);
        assert_eq!(editor.observer_beta(), beta_o);
        assert_matches_a_fresh_build(&editor);
        // The sphere moves at 0.6c in W (the panel's speed), faster relative to the observer.
        assert!((editor.speed(0) - 0.6).abs() < 1e-15);
        assert!(editor.objects()[0].frame.beta().length() > 0.9);
        editor
            .set_velocity(0, 0.3, DVec3::new(-1.0, 0.0, 0.2), true)
            .unwrap();
        assert!((editor.speed(0) - 0.3).abs() < 1e-15);
        assert_matches_a_fresh_build(&editor);
        // Keeping where it is seen: the emission event seen now, in W, is unchanged.
        editor.set_observer_beta(DVec3::new(0.2, 0.7, 0.0)).unwrap();
        assert_matches_a_fresh_build(&editor);
        // Time moves the observer along its worldline through W.
        let before = editor.description().observer.position;
        editor.set_time(2.0).unwrap();
        let after = editor.description().observer.position;
        let moved = DVec3::from_array(after) - DVec3::from_array(before);
        assert!(
            (moved - DVec3::new(0.4, 1.4, 0.0)).length() < 1e-12,
            "{moved}"
        );
        assert_matches_a_fresh_build(&editor);
        assert!(matches!(
            editor.set_observer_beta(DVec3::new(0.0, 1.0, 0.0)),
            Err(EditError::Scene(_))
        ));
        // The light is read and written in the world frame.
        let (temperature, position) = editor.light();
        editor.set_light(temperature, position).unwrap();
        assert_eq!(editor.light(), (temperature, position));
    }

    /// Changing the velocity keeps the object's origin where it is seen, in the world frame
    /// when the observer moves.
    #[test]
    fn keeping_the_apparent_position_works_for_a_moving_observer() {
        let (mut editor, _) = Editor::open("flythrough").unwrap();
        let seen = |editor: &Editor| {
            let object = &editor.objects()[1];
            object
                .frame
                .apparent_position(DVec3::ZERO, editor.scene().observer.event())
        };
        let before = seen(&editor);
        editor
            .set_velocity(1, 0.8, DVec3::new(0.0, 1.0, 0.0), true)
            .unwrap();
        let after = seen(&editor);
        assert!((after - before).length() < 1e-9, "{before} → {after}");
    }

    /// A binary STL file with one tetrahedron (4 triangles), the fixture the UI tests use too.
    fn tetrahedron_stl() -> Vec<u8> {
        include_bytes!("../tests/fixtures/tetrahedron.stl").to_vec()
    }
}
