//! Turning the SCENE argument into a scene through srt-scene's resolver
//! ([`srt_scene::resolve`]): a built-in scene name, a `.toml` scene file, or a bare 3D model file
//! (placed in front of the observer, moving with `--beta` or, by default, approaching at
//! [`DEFAULT_MODEL_SPEED`](srt_scene::resolve::DEFAULT_MODEL_SPEED)), with the command-line
//! overrides applied to its description ([`srt_scene::Overrides`]).

use std::fmt::Write as _;
use std::io::{Read as _, Write as _};
use std::path::Path;

use anyhow::anyhow;
use glam::DVec3;
use sha2::{Digest as _, Sha256};
use srt_scene::builtin::find_builtin;
use srt_scene::message::io_reason;
use srt_scene::{Editor, Overrides, SceneSource, builtin_scenes};

/// A scene ready to render, and where it came from.
pub struct LoadedScene {
    /// The scene, in srt-scene's scene state (an animation moves its time).
    pub editor: Editor,
    /// Non-fatal problems worked around while loading it.
    pub warnings: Vec<String>,
    /// What it was loaded from, for the images' provenance record.
    pub origin: SceneOrigin,
    /// The observer's velocity through the scene's world frame (zero: at rest).
    pub observer_beta: DVec3,
}

/// Where a scene came from, in words that are the same on every machine (no folders).
pub struct SceneOrigin {
    /// "NAME (built-in)", "FILE (scene file)" or "FILE (model)": a file by its name alone.
    pub description: String,
    /// The SHA-256 of the scene or model file's content, in hex; `None` for a built-in scene.
    /// (A scene file's own models and textures are not included.)
    pub sha256: Option<String>,
}

impl SceneOrigin {
    /// Whether the scene is one of srt's own (built-in), not the user's file.
    pub const fn is_builtin(&self) -> bool {
        self.sha256.is_none()
    }
}

/// Loads the scene named by `argument` with the command-line `overrides` in place of its own
/// values (srt-scene's one route for them, [`SceneSource::load_with`]: they edit the description,
/// whose validation judges them by their options' names).
///
/// # Errors
/// Unknown names, unsupported, unreadable or invalid files, bad values, among them an override
/// the scene file's rules refuse (`--beta` with a moving observer included).
pub fn load_scene(argument: &str, overrides: &Overrides) -> anyhow::Result<LoadedScene> {
    let source = SceneSource::resolve(argument)?;
    let loaded = source.load_with(overrides)?;
    let origin = match &source {
        SceneSource::Builtin(scene) => SceneOrigin {
            description: format!("{} (built-in)", scene.name),
            sha256: None,
        },
        SceneSource::SceneFile(path) => file_origin(path, "scene file")?,
        SceneSource::Model(path) => file_origin(path, "model")?,
    };
    let observer_beta = DVec3::from_array(loaded.source.description.observer.beta);
    let (editor, warnings) = Editor::new(loaded);
    Ok(LoadedScene {
        editor,
        warnings,
        origin,
        observer_beta,
    })
}

/// The origin of a scene read from the file at `path`, with its content hash.
fn file_origin(path: &Path, kind: &str) -> anyhow::Result<SceneOrigin> {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    Ok(SceneOrigin {
        description: format!("{name} ({kind})"),
        sha256: Some(sha256_hex(path)?),
    })
}

/// The SHA-256 of a file's content in lowercase hex, read in blocks.
fn sha256_hex(path: &Path) -> anyhow::Result<String> {
    let cannot =
        |error: &std::io::Error| anyhow!("cannot read {} ({})", path.display(), io_reason(error));
    let mut file = std::fs::File::open(path).map_err(|e| cannot(&e))?;
    let mut hasher = Sha256::new();
    let mut block = vec![0_u8; 1 << 16];
    loop {
        match file.read(&mut block) {
            Ok(0) => break,
            Ok(n) => hasher.update(&block[..n]),
            Err(error) if error.kind() == std::io::ErrorKind::Interrupted => {}
            Err(error) => return Err(cannot(&error)),
        }
    }
    let mut hex = String::with_capacity(64);
    for byte in hasher.finalize() {
        let _ = write!(hex, "{byte:02x}");
    }
    Ok(hex)
}

/// Prints the built-in scenes, one per line, or with `show` the file of the scene of that name:
/// its explanation (the comments at its top and beside its values) and its values, as a scene
/// file to copy and edit (built-in models keep their `builtin:` paths, which work in any file).
///
/// # Errors
/// No built-in scene is called `show` (the message lists those there are), or writing to
/// standard output failed.
pub fn print_scenes(show: Option<&str>) -> anyhow::Result<()> {
    let Some(name) = show else {
        return Ok(crate::listing::print_rows(
            builtin_scenes().iter().map(|s| (s.name, s.summary)),
        )?);
    };
    let scene = find_builtin(name).ok_or_else(|| {
        let names: Vec<&str> = builtin_scenes().iter().map(|s| s.name).collect();
        anyhow!(
            "no built-in scene is called {name:?}; there are {}",
            names.join(", ")
        )
    })?;
    let mut out = std::io::stdout().lock();
    out.write_all(scene.toml().as_bytes())?;
    Ok(out.flush()?)
}

#[cfg(test)]
mod tests {
    /// The hash of a known input (FIPS 180-2's "abc" example), read from a file.
    #[test]
    fn sha256_of_a_file_matches_the_standard_example() {
        let dir = tempfile::tempdir().expect("temporary folder");
        let path = dir.path().join("abc.toml");
        std::fs::write(&path, "abc").expect("written");
        assert_eq!(
            super::sha256_hex(&path).expect("hashed"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
