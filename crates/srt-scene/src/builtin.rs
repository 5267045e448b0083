//! Built-in scenes: the paper's test scenes (Fig. 4, 7, 10), a teaser in the spirit of Fig. 1, a
//! world the observer flies through, and clocks and blinking beacons that show time as it is seen,
//! embedded in the program as the TOML files in `crates/srt-scene/assets/scenes/` (which double
//! as examples of the scene format).

use std::path::Path;

use crate::description::{SceneDescription, SceneError};
use crate::scene::Scene;

/// A scene that ships with the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuiltinScene {
    /// The name to ask for it by (`srt render fig7`).
    pub name: &'static str,
    /// One line saying what it shows.
    pub summary: &'static str,
    toml: &'static str,
}

impl BuiltinScene {
    /// The scene file's text.
    #[must_use]
    pub const fn toml(&self) -> &'static str {
        self.toml
    }

    /// How messages name the scene: `built-in scene "NAME"`.
    #[must_use]
    pub fn origin(&self) -> String {
        format!("built-in scene \"{}\"", self.name)
    }

    /// The parsed scene description.
    ///
    /// # Panics
    /// If the embedded file does not parse, which the crate's tests rule out.
    #[must_use]
    pub fn description(&self) -> SceneDescription {
        SceneDescription::from_toml_str(self.toml, &self.origin())
            .unwrap_or_else(|e| panic!("built-in scene {} does not parse: {e}", self.name))
    }

    /// The runtime scene and the warnings met building it.
    ///
    /// # Errors
    /// [`SceneError`] if the scene does not build, which the crate's tests rule out.
    pub fn build(&self) -> Result<(Scene, Vec<String>), SceneError> {
        self.build_description(&self.description())
    }

    /// Builds `description` (this scene's, perhaps changed) as this scene is built, with errors
    /// naming this scene.
    ///
    /// # Errors
    /// [`SceneError`] if the description does not build.
    pub fn build_description(
        &self,
        description: &SceneDescription,
    ) -> Result<(Scene, Vec<String>), SceneError> {
        description
            .build(Path::new("."))
            .map_err(|e| e.with_origin(self.origin()))
    }
}

macro_rules! builtin_scene {
    ($name:literal, $summary:literal) => {
        BuiltinScene {
            name: $name,
            summary: $summary,
            toml: include_str!(concat!("../assets/scenes/", $name, ".toml")),
        }
    };
}

static BUILTIN_SCENES: [BuiltinScene; 14] = [
    builtin_scene!(
        "fig4",
        "Fig. 4: a unit cube at 0.95c seen at ct = 5.12, apparently rotated and distorted"
    ),
    builtin_scene!(
        "fig7",
        "Fig. 7: a checkered unit cube approaching at 0.95c, lit from the side (try searchlight)"
    ),
    builtin_scene!(
        "fig10-cube50",
        "Fig. 10 top: a checkered cube of size 5 with 50 triangles per face approaching at 0.95c"
    ),
    builtin_scene!(
        "fig10-cube50-wireframe",
        "Fig. 10 bottom: the same cube drawn as a wireframe of its 50 triangles per face"
    ),
    builtin_scene!(
        "fig10-cube200",
        "Fig. 10: the same cube with 200 triangles per face"
    ),
    builtin_scene!(
        "teaser",
        "Fig. 1's idea: a spider, a cube and a sphere flying in different directions at 0.95c, 0.8c and 0.5c"
    ),
    builtin_scene!(
        "spider",
        "The embedded spider model alone, approaching at 0.9c (a default-placed bare model)"
    ),
    builtin_scene!(
        "flythrough",
        "The observer flies at 0.9c over a ground between columns at rest, past a sphere and a cube"
    ),
    builtin_scene!(
        "beacon",
        "Blinking beacons approaching at 0.6c, at rest and receding: each is seen to blink D times its proper rate"
    ),
    builtin_scene!(
        "clocks",
        "Clocks at rest beside a train of clocks passing at 0.9c: each face shows the proper time of the event seen"
    ),
    builtin_scene!(
        "rolling-wheel",
        "A spoked wheel rolling at 0.9c: spokes bent into curves, the bottom sharp, the top smeared"
    ),
    builtin_scene!(
        "rocket",
        "A rocket accelerating away from rest with a clock on its side: it reddens, freezes and fades"
    ),
    builtin_scene!(
        "bell",
        "Bell's spaceships: two ships with equal thrust, a thread tied between them falls behind"
    ),
    builtin_scene!(
        "shadows",
        "A lamp flying at 0.9c behind a row of columns: the shadows point away from where it was"
    ),
];

/// All built-in scenes, in the order `srt scenes` lists them.
#[must_use]
pub fn builtin_scenes() -> &'static [BuiltinScene] {
    &BUILTIN_SCENES
}

/// The built-in scene called `name`, if there is one.
#[must_use]
pub fn builtin(name: &str) -> Option<SceneDescription> {
    find_builtin(name).map(BuiltinScene::description)
}

/// The built-in scene entry called `name`, if there is one.
#[must_use]
pub fn find_builtin(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|scene| scene.name == name)
}
