//! `srt.Scene`: a scene that Python reads and edits — srt-scene's [`Editor`], the scene state the
//! viewer, the web page and `srt render` share — with the scene file's validation and messages;
//! an edit builds only what it changed (a velocity or a time builds nothing new), and
//! `srt.render` draws the edited scene with its arguments in place of the scene's values, as
//! `srt render` does. `Observer` and `SceneObject` are views of a scene's observer and objects:
//! setting one of their fields edits the scene.

use pyo3::prelude::*;
use srt_scene::description::LightsDescription;
use srt_scene::resolve::LocatedDescription;
use srt_scene::{Editor, Effects, Overrides, SceneDescription, SceneSource, SurfaceColour};

use crate::errors;

/// How messages name scene text given to `Scene.from_toml`.
const TEXT_ORIGIN: &str = "scene text";

/// The built-in scenes' names, in `srt scenes` order.
#[pyfunction]
pub fn scenes() -> Vec<&'static str> {
    srt_scene::builtin_scenes().iter().map(|s| s.name).collect()
}

/// What the file at `path` is, by its extension (a path is never a built-in scene's name);
/// a file that does not exist is refused here, naming it, as a name given as `str` is.
pub fn file_source(path: &std::path::Path) -> PyResult<SceneSource> {
    SceneSource::from_path(path)
        .and_then(SceneSource::existing)
        .map_err(|e| errors::resolve(&e))
}

/// A scene: what a scene file holds, built, and where it came from.
#[pyclass(module = "srt")]
pub struct Scene {
    /// The scene state: its description and the scene built from it.
    editor: Editor,
    /// The built-in scene, scene file or model it came from; `None` for scene text.
    source: Option<SceneSource>,
}

impl Scene {
    /// The description as edited so far.
    fn description(&self) -> &SceneDescription {
        self.editor.description()
    }

    /// Applies `change` to the description if the result passes the scene file's validation
    /// (and its new objects load); otherwise leaves the scene as it was and raises its message.
    fn edit(&mut self, change: impl FnOnce(&mut SceneDescription)) -> PyResult<()> {
        let mut edited = self.description().clone();
        change(&mut edited);
        (self.editor.set_description(edited))
            .map(|_no_new_objects| ())
            .map_err(|e| errors::edit(&e))
    }

    /// An editor of the scene built with `overrides` in place of its values (the scene itself
    /// unchanged), named in messages as its source names it.
    pub fn overridden(&self, overrides: &Overrides) -> PyResult<Editor> {
        let mut description = self.description().clone();
        let origin = match &self.source {
            Some(source) => source.origin(&description),
            None => description.origin(),
        };
        (overrides.apply(&mut description, &origin))
            .map_err(|kind| errors::scene(&srt_scene::SceneError::new(origin, kind)))?;
        let mut editor = self.editor.clone();
        (editor.set_description(description)).map_err(|e| errors::edit(&e))?;
        Ok(editor)
    }

    /// A scene from `source`, its description read (a bare model moving with `beta`) and built
    /// at once, so that a missing or broken file is reported now.
    fn from_source(source: SceneSource, beta: Option<[f64; 3]>) -> PyResult<Self> {
        let beta = beta.map(glam::DVec3::from_array);
        let located = source.description(beta).map_err(|e| errors::scene(&e))?;
        let loaded =
            (source.load_edited(located, &Overrides::default())).map_err(|e| errors::scene(&e))?;
        Ok(Self {
            editor: Editor::new(loaded).0,
            source: Some(source),
        })
    }
}

#[pymethods]
impl Scene {
    /// The built-in scene `name` (see `srt.scenes()`).
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        let builtin = srt_scene::builtin::find_builtin(name).ok_or_else(|| {
            errors::value(format!(
                "{name:?} is not a built-in scene; built-in scenes: {}",
                scenes().join(", ")
            ))
        })?;
        Self::from_source(SceneSource::Builtin(builtin), None)
    }

    /// The scene file (.toml) or model (.gltf, .glb, .obj, .ply, .stl) at `path`; a bare model
    /// is placed in front of the observer, moving with `beta` or approaching at 0.9c.
    #[staticmethod]
    #[pyo3(signature = (path, *, beta=None))]
    fn load(path: std::path::PathBuf, beta: Option<[f64; 3]>) -> PyResult<Self> {
        Self::from_source(file_source(&path)?, beta)
    }

    /// A scene from scene-file text (docs/scene-format.md); relative paths start from the
    /// current folder.
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        let description =
            SceneDescription::from_toml_str(text, TEXT_ORIGIN).map_err(|e| errors::scene(&e))?;
        let located = LocatedDescription {
            description,
            base_dir: ".".into(),
        };
        let loaded = (located.load_with(&Overrides::default())).map_err(|e| errors::scene(&e))?;
        Ok(Self {
            editor: Editor::new(loaded).0,
            source: None,
        })
    }

    /// The description as scene-file text that `Scene.from_toml` reads back.
    fn to_toml(&self) -> String {
        self.description().to_toml_string()
    }

    /// The scene's name (`None` if its description gives none).
    #[getter]
    fn name(&self) -> Option<String> {
        match (&self.description().name, &self.source) {
            (Some(name), _) => Some(name.clone()),
            (None, Some(SceneSource::Builtin(builtin))) => Some(builtin.name.to_owned()),
            (None, _) => None,
        }
    }

    /// The effect mode: "geometry", "doppler" or "searchlight" (setting it also gives the
    /// scene the mode's own tone map, as `srt render --effects` does).
    #[getter]
    fn effects(&self) -> &'static str {
        self.description().render.effects.name()
    }

    #[setter]
    fn set_effects(&mut self, name: &str) -> PyResult<()> {
        let effects: Effects = errors::chosen(name)?;
        self.edit(|d| {
            d.render.effects = effects;
            d.render.tone_map = None;
        })
    }

    /// How lit surfaces are coloured: "paper" (the paper's Eq. 18) or "spectral".
    #[getter]
    fn colour(&self) -> &'static str {
        self.description().render.colour.name()
    }

    #[setter]
    fn set_colour(&mut self, name: &str) -> PyResult<()> {
        let colour: SurfaceColour = errors::chosen(name)?;
        self.edit(|d| d.render.colour = colour)
    }

    /// The multiplier on the light before the tone map (spectral colour only).
    #[getter]
    fn exposure(&self) -> f64 {
        self.description().render.exposure
    }

    #[setter]
    fn set_exposure(&mut self, exposure: f64) -> PyResult<()> {
        self.edit(|d| d.render.exposure = exposure)
    }

    /// The observation time: the observer's own clock when it looks (`observer.time`, or
    /// `observer.ct` when the scene gives none); what `srt.render(time=)` and `srt render
    /// --time` set.
    #[getter]
    fn time(&self) -> f64 {
        self.editor.time()
    }

    #[setter]
    fn set_time(&mut self, time: f64) -> PyResult<()> {
        self.edit(|d| d.observer.time = Some(time))
    }

    /// The lamp's position and black-body temperature in kelvin, `None` without a lamp.
    #[getter]
    fn light(&self) -> Option<([f64; 3], f64)> {
        (self.description().light.as_ref())
            .and_then(LightsDescription::lamp)
            .map(|lamp| (lamp.position, lamp.temperature_k))
    }

    /// The observer (a view: setting its fields edits this scene).
    #[getter]
    fn observer(slf: Py<Self>) -> Observer {
        Observer { scene: slf }
    }

    /// The objects, in scene-file order (views: setting their fields edits this scene).
    #[getter]
    fn objects(slf: Py<Self>, py: Python<'_>) -> Vec<SceneObject> {
        let count = slf.borrow(py).description().objects.len();
        (0..count)
            .map(|index| SceneObject {
                scene: slf.clone_ref(py),
                index,
            })
            .collect()
    }

    fn __repr__(&self) -> String {
        format!(
            "<srt.Scene {} ({} objects, {})>",
            self.name().unwrap_or_else(|| "untitled".into()),
            self.description().objects.len(),
            self.effects()
        )
    }
}

/// The observer of a scene (a view of `Scene.observer`).
#[pyclass(module = "srt")]
pub struct Observer {
    /// The scene it belongs to.
    scene: Py<Scene>,
}

impl Observer {
    /// A value of the observer's description.
    fn get<T>(
        &self,
        py: Python<'_>,
        field: impl FnOnce(&srt_scene::ObserverDescription) -> T,
    ) -> T {
        field(&self.scene.borrow(py).description().observer)
    }

    /// Edits the observer's description (validated as the scene file is).
    fn set(
        &self,
        py: Python<'_>,
        change: impl FnOnce(&mut srt_scene::ObserverDescription),
    ) -> PyResult<()> {
        self.scene.borrow_mut(py).edit(|d| change(&mut d.observer))
    }
}

#[pymethods]
impl Observer {
    /// Position in the scene's world frame.
    #[getter]
    fn position(&self, py: Python<'_>) -> [f64; 3] {
        self.get(py, |o| o.position)
    }

    #[setter]
    fn set_position(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| o.position = value)
    }

    /// Velocity through the world frame in units of c (|beta| < 1).
    #[getter]
    fn beta(&self, py: Python<'_>) -> [f64; 3] {
        self.get(py, |o| o.beta)
    }

    #[setter]
    fn set_beta(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| o.beta = value)
    }

    /// The point looked at (`None` when a direction is given instead); setting it clears the
    /// direction.
    #[getter]
    fn look_at(&self, py: Python<'_>) -> Option<[f64; 3]> {
        self.get(py, |o| o.look_at)
    }

    #[setter]
    fn set_look_at(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| {
            o.look_at = Some(value);
            o.direction = None;
        })
    }

    /// The viewing direction (`None` when a point looked at is given instead); setting it
    /// clears the point.
    #[getter]
    fn direction(&self, py: Python<'_>) -> Option<[f64; 3]> {
        self.get(py, |o| o.direction)
    }

    #[setter]
    fn set_direction(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| {
            o.direction = Some(value);
            o.look_at = None;
        })
    }

    /// The camera's up direction.
    #[getter]
    fn up(&self, py: Python<'_>) -> [f64; 3] {
        self.get(py, |o| o.up)
    }

    #[setter]
    fn set_up(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| o.up = value)
    }

    /// Vertical field of view in degrees, in (0, 180).
    #[getter]
    fn fov_y_deg(&self, py: Python<'_>) -> f64 {
        self.get(py, |o| o.fov_y_deg)
    }

    #[setter]
    fn set_fov_y_deg(&self, py: Python<'_>, value: f64) -> PyResult<()> {
        self.set(py, |o| o.fov_y_deg = value)
    }

    /// W's time at which the observer is at `position` (its clock reads `ct` there; `Scene.time`
    /// is when it looks).
    #[getter]
    fn ct(&self, py: Python<'_>) -> f64 {
        self.get(py, |o| o.ct)
    }

    #[setter]
    fn set_ct(&self, py: Python<'_>, value: f64) -> PyResult<()> {
        self.set(py, |o| o.ct = value)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        self.get(py, |o| {
            format!(
                "<srt.Observer at {:?}, beta {:?}, ct {:?}>",
                o.position, o.beta, o.ct
            )
        })
    }
}

/// One object of a scene (a view of an item of `Scene.objects`).
#[pyclass(module = "srt")]
pub struct SceneObject {
    /// The scene it belongs to.
    scene: Py<Scene>,
    /// Its place in the scene's objects.
    index: usize,
}

impl SceneObject {
    /// A value of the object's description.
    fn get<T>(&self, py: Python<'_>, field: impl FnOnce(&srt_scene::ObjectDescription) -> T) -> T {
        field(&self.scene.borrow(py).description().objects[self.index])
    }

    /// Edits the object's description (validated as the scene file is).
    fn set(
        &self,
        py: Python<'_>,
        change: impl FnOnce(&mut srt_scene::ObjectDescription),
    ) -> PyResult<()> {
        let index = self.index;
        self.scene
            .borrow_mut(py)
            .edit(|d| change(&mut d.objects[index]))
    }
}

#[pymethods]
impl SceneObject {
    /// The object's name as messages give it (`object "NAME"` or `object N`).
    #[getter]
    fn name(&self, py: Python<'_>) -> String {
        let index = self.index;
        self.get(py, |o| o.name.clone().unwrap_or_else(|| o.label(index)))
    }

    /// Velocity of its rest frame S′ in units of c (|beta| < 1), relative to the world frame.
    #[getter]
    fn beta(&self, py: Python<'_>) -> [f64; 3] {
        self.get(py, |o| o.beta)
    }

    #[setter]
    fn set_beta(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| o.beta = value)
    }

    /// Where the origin of S′ is at t = t′ = 0 (the paper's a, Fig. 2).
    #[getter]
    fn offset(&self, py: Python<'_>) -> [f64; 3] {
        self.get(py, |o| o.offset)
    }

    #[setter]
    fn set_offset(&self, py: Python<'_>, value: [f64; 3]) -> PyResult<()> {
        self.set(py, |o| o.offset = value)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let name = self.name(py);
        self.get(py, |o| {
            format!(
                "<srt.SceneObject {name}, beta {:?}, offset {:?}>",
                o.beta, o.offset
            )
        })
    }
}
