//! The scene a page shows, as `srt render` loads it: a built-in scene or a dropped model, with
//! the page's [`Overrides`] in place of the scene's own values (srt-scene's one route for them),
//! held by srt-scene's [`Editor`], the scene state every front end shares: playing time costs no
//! build, a velocity keeps every object's parts. The CPU picture is the exact tracer's, quantised
//! as `srt render` writes its PNG.

use glam::DVec3;
use srt_color::quantize_8bit;
use srt_scene::resolve::ResolveError;
use srt_scene::{
    EditError, Editor, OverrideNames, Overrides, Scene, SceneError, SceneSource, builtin_scenes,
};
use srt_trace::{RenderSettings, Tracer, measure_picture};

/// Why the page cannot show what was asked.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// A scene name that is no built-in scene.
    #[error("there is no built-in scene \"{name}\" (there are: {known})")]
    UnknownScene {
        /// The name asked for.
        name: String,
        /// The built-in scenes' names.
        known: String,
    },
    /// A dropped file that is no model (judged by its extension).
    #[error(transparent)]
    Resolve(#[from] ResolveError),
    /// A scene or model that does not load, or a value its rules refuse (the message names the
    /// file or the key).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// An edit the scene's rules refuse (the message names the key).
    #[error(transparent)]
    Edit(#[from] EditError),
}

/// The scene a page shows (srt-scene's [`Editor`], the one scene state) and the values it
/// overrides.
pub struct Session {
    source: SceneSource,
    /// The page's values, judged when the scene is next asked for.
    overrides: Overrides,
    /// The values the editor's scene was made with.
    applied: Overrides,
    editor: Editor,
    /// Warnings of the last scene opened.
    warnings: Vec<String>,
}

/// What the page's controls start from: the scene's own values.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneInfo {
    /// The scene's name.
    pub name: String,
    /// The observation time (the observer's clock, `observer.time`).
    pub time: f64,
    /// The velocity of the first moving object (zero if none moves).
    pub beta: DVec3,
    /// Whether the observer moves (then objects' velocities cannot be overridden).
    pub observer_moves: bool,
    /// The effect mode's name.
    pub effects: &'static str,
    /// The surface colour's name.
    pub colour: &'static str,
    /// Warnings of the last build.
    pub warnings: Vec<String>,
}

impl Session {
    /// A session showing the built-in scene `name` with its own values (built now).
    ///
    /// # Errors
    /// [`SessionError::UnknownScene`] when there is no such built-in scene, or one that does
    /// not build.
    pub fn new(name: &str) -> Result<Self, SessionError> {
        let source = builtin_source(name)?;
        let overrides = Overrides {
            names: OverrideNames::KEYS,
            ..Overrides::default()
        };
        let (editor, warnings) = Editor::new(source.load_with(&overrides)?);
        Ok(Self {
            source,
            applied: overrides.clone(),
            overrides,
            editor,
            warnings,
        })
    }

    /// Shows the built-in scene `name`, built at once with the values set; when it does not
    /// exist or build, the session keeps showing what it showed.
    ///
    /// # Errors
    /// [`SessionError::UnknownScene`], or the scene's build error.
    pub fn set_builtin(&mut self, name: &str) -> Result<(), SessionError> {
        let source = builtin_source(name)?;
        if source != self.source {
            self.show(source)?;
        }
        Ok(())
    }

    /// Shows the model `file_name` (its extension picks the format) made of `bytes`, placed as
    /// `srt render MODEL` places it. The model is loaded at once, with the command's limits and
    /// messages; when it fails, the session keeps showing what it showed. Returns the warnings.
    ///
    /// # Errors
    /// [`SessionError`] naming the file and the reason.
    pub fn load_model(
        &mut self,
        file_name: &str,
        bytes: Vec<u8>,
    ) -> Result<Vec<String>, SessionError> {
        let base = file_name.rsplit(['/', '\\']).next().unwrap_or(file_name);
        let path = srt_scene::assets::add_memory_file(base, bytes);
        self.show(SceneSource::from_path(std::path::Path::new(&path))?)?;
        Ok(self.warnings.clone())
    }

    /// Opens `source` with the values set and shows it ([`Editor::replace_with`]), or leaves
    /// everything as it was.
    fn show(&mut self, source: SceneSource) -> Result<(), SessionError> {
        let (editor, warnings) = Editor::new(source.load_with(&self.overrides)?);
        self.editor.replace_with(editor);
        self.source = source;
        self.applied = self.overrides.clone();
        self.warnings = warnings;
        Ok(())
    }

    /// Sets the values in place of the scene's own (their names in messages stay the page's);
    /// they are judged when the scene is next asked for.
    pub fn set_overrides(&mut self, overrides: Overrides) {
        self.overrides = Overrides {
            names: OverrideNames::KEYS,
            ..overrides
        };
    }

    /// The scene as it is now to be shown: the scene's own description with the page's values,
    /// given to the editor ([`Editor::set_description`]: playing time, or any change of the
    /// observer alone, builds nothing; a velocity keeps every object's parts).
    ///
    /// # Errors
    /// [`SessionError::Scene`] when it does not build or a value is refused; the scene shown
    /// before stays.
    pub fn scene(&mut self) -> Result<&Scene, SessionError> {
        if self.overrides != self.applied {
            let located = self.source.description_with(&self.overrides)?;
            self.editor.set_description(located.description)?;
            self.applied = self.overrides.clone();
        }
        Ok(self.editor.scene())
    }

    /// A number that changes whenever the scene changed in a way a GPU renderer must upload
    /// again ([`Scene::same_structure`]: other meshes, materials or sky); velocities, times,
    /// effects and colours leave it.
    #[must_use]
    pub const fn upload_version(&self) -> u64 {
        self.editor.structure_version()
    }

    /// How many times the scene has been built (playing time builds nothing).
    #[must_use]
    pub const fn builds(&self) -> u64 {
        self.editor.builds()
    }

    /// The scene's own values (before the page's) for the page's controls, and the warnings
    /// of the last build.
    ///
    /// # Errors
    /// A scene file that cannot be read (never for built-in scenes and dropped models).
    pub fn info(&self) -> Result<SceneInfo, SessionError> {
        let own = self.source.description(None)?.description;
        let beta = own
            .objects
            .iter()
            .map(|object| DVec3::from_array(object.beta))
            .find(|beta| *beta != DVec3::ZERO)
            .unwrap_or(DVec3::ZERO);
        Ok(SceneInfo {
            name: self.editor.scene().name.clone(),
            time: own.observer.time.unwrap_or(own.observer.ct),
            beta,
            observer_moves: DVec3::from_array(own.observer.beta) != DVec3::ZERO,
            effects: own.render.effects.name(),
            colour: own.render.colour.name(),
            warnings: self.warnings.clone(),
        })
    }

    /// The exact CPU picture at `width`×`height`, RGBA with 8 bits per channel, rows from the
    /// top: the bytes `srt render --backend cpu` writes (plus an opaque alpha).
    ///
    /// # Errors
    /// As [`Session::scene`].
    pub fn render_cpu(&mut self, width: u32, height: u32) -> Result<Vec<u8>, SessionError> {
        let scene = self.scene()?;
        let settings = RenderSettings {
            width,
            height,
            samples: 1,
        };
        let image = Tracer::new(scene).render(settings, &|_| {});
        Ok(image
            .pixels
            .iter()
            .flat_map(|p| {
                let [r, g, b] = p.to_array().map(quantize_8bit);
                [r, g, b, u8::MAX]
            })
            .collect())
    }

    /// The seconds the exact CPU picture at `width`×`height` is estimated to take: its
    /// tracer's build and the frame measured on a few rows ([`measure_picture`]).
    ///
    /// # Errors
    /// As [`Session::scene`].
    pub fn measure_cpu(&mut self, width: u32, height: u32) -> Result<f64, SessionError> {
        let settings = RenderSettings {
            width,
            height,
            samples: 1,
        };
        Ok(measure_picture(self.scene()?, settings).seconds)
    }
}

/// The source of the built-in scene `name`.
fn builtin_source(name: &str) -> Result<SceneSource, SessionError> {
    srt_scene::builtin::find_builtin(name)
        .map(SceneSource::Builtin)
        .ok_or_else(|| SessionError::UnknownScene {
            name: name.to_owned(),
            known: scene_names().join(", "),
        })
}

/// The names of the built-in scenes, in `srt scenes` order.
#[must_use]
pub fn scene_names() -> Vec<&'static str> {
    builtin_scenes().iter().map(|scene| scene.name).collect()
}
