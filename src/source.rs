//! Turning the SCENE argument into a scene through srt-scene's resolver
//! ([`srt_scene::resolve`]): a built-in scene name, a `.toml` scene file, or a bare 3D model file
//! (placed in front of the observer, moving with `--beta` or, by default, approaching at
//! [`DEFAULT_MODEL_SPEED`](srt_scene::resolve::DEFAULT_MODEL_SPEED)).

use glam::DVec3;
use srt_scene::{Scene, SceneSource, builtin_scenes};

/// Loads the scene named by `argument`; `beta` is the `--beta` option (used to place a bare
/// model). Returns the scene and non-fatal warnings.
///
/// # Errors
/// Unknown names, unsupported, unreadable or invalid files, bad values.
pub fn load_scene(argument: &str, beta: Option<DVec3>) -> anyhow::Result<(Scene, Vec<String>)> {
    let loaded = SceneSource::resolve(argument)?.load(beta)?;
    Ok((loaded.scene, loaded.warnings))
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
