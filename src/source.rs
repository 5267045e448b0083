//! Turning the SCENE argument into a scene: a built-in scene name, a `.toml` scene file, or a
//! bare 3D model file (placed in front of the observer, moving with `--beta` or, by default,
//! approaching at 0.9c).

use std::path::Path;

use anyhow::bail;
use glam::DVec3;
use srt_scene::builtin::find_builtin;
use srt_scene::import::SUPPORTED_EXTENSIONS;
use srt_scene::placement::approach_velocity;
use srt_scene::{Scene, SceneDescription, builtin_scenes, load_scene_file};

/// Speed of a bare model when `--beta` is not given (towards the observer).
pub const DEFAULT_MODEL_SPEED: f64 = 0.9;

/// Loads the scene named by `argument`; `beta` is the `--beta` option (used to place a bare
/// model). Returns the scene and non-fatal warnings.
///
/// # Errors
/// Unknown names, unreadable or invalid files, bad values.
pub fn load_scene(argument: &str, beta: Option<DVec3>) -> anyhow::Result<(Scene, Vec<String>)> {
    if let Some(builtin) = find_builtin(argument) {
        return Ok(builtin.build()?);
    }
    let path = Path::new(argument);
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("toml") => {
            let (scene, _, warnings) = load_scene_file(path)?;
            Ok((scene, warnings))
        }
        Some(ext) if SUPPORTED_EXTENSIONS.contains(&ext) => {
            let beta = beta.unwrap_or_else(|| approach_velocity(DEFAULT_MODEL_SPEED));
            Ok(SceneDescription::for_model(path, beta).build(Path::new("."))?)
        }
        _ if path.exists() => bail!(
            "cannot render {argument:?}: a scene file must end in .toml and a model in one of {}",
            SUPPORTED_EXTENSIONS
                .iter()
                .map(|e| format!(".{e}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        _ => bail!(
            "{argument:?} is neither a built-in scene (see `srt scenes`) nor an existing file"
        ),
    }
}

/// Prints the built-in scenes, one per line.
pub fn print_scenes() {
    let width = builtin_scenes()
        .iter()
        .map(|s| s.name.len())
        .max()
        .unwrap_or(0);
    for scene in builtin_scenes() {
        println!("{:width$}  {}", scene.name, scene.summary);
    }
}
