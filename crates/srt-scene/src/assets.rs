//! Files embedded in the program (the built-in scenes' models) and how scene files refer to
//! files: a path relative to the scene file's folder, or `builtin:NAME` for an embedded asset.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, PoisonError};

use crate::import::{self, ImportError, ImportFailure, Model};
use crate::input_file::InputFileError;
use crate::limits::Budget;
use crate::mesh::Texture;
use crate::textures;

/// Prefix of paths in scene files that name an embedded asset, e.g. `builtin:models/spider.stl`.
pub const BUILTIN_PREFIX: &str = "builtin:";

/// The embedded assets by name (see `crates/srt-scene/assets/models/NOTICE.md` for sources and
/// licences).
const EMBEDDED: &[(&str, &[u8])] = &[(
    "models/spider.stl",
    include_bytes!("../assets/models/spider.stl"),
)];

/// Names of the embedded assets (use them as `builtin:NAME` in scene files).
pub fn embedded_names() -> impl Iterator<Item = &'static str> {
    EMBEDDED.iter().map(|(name, _)| *name)
}

/// The bytes of the embedded asset `name` (without the `builtin:` prefix), if there is one.
#[must_use]
pub fn embedded(name: &str) -> Option<&'static [u8]> {
    EMBEDDED
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, bytes)| *bytes)
}

/// Where a path in a scene file leads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Resolved {
    /// A file on disk.
    File(PathBuf),
    /// An embedded asset.
    Embedded {
        /// Its name, without the `builtin:` prefix.
        name: &'static str,
        /// Its content.
        bytes: &'static [u8],
    },
}

/// Resolves `path` from a scene file whose folder is `base_dir`: `builtin:NAME` is the embedded
/// asset NAME; other paths are joined to `base_dir` (absolute paths stay as they are).
///
/// # Errors
/// A message if `path` names an embedded asset that does not exist.
pub fn resolve(base_dir: &Path, path: &str) -> Result<Resolved, String> {
    match path.strip_prefix(BUILTIN_PREFIX) {
        Some(name) => EMBEDDED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(name, bytes)| Resolved::Embedded { name, bytes })
            .ok_or_else(|| {
                let known = embedded_names().collect::<Vec<_>>().join(", ");
                format!("there is no built-in asset \"{name}\" (there are: {known})")
            }),
        None => Ok(Resolved::File(base_dir.join(path))),
    }
}

/// Loads the model at `resolved` with [`import::load_model_within`], charging it to `budget`;
/// embedded models are loaded once per process and cached (and charged on every use).
///
/// # Errors
/// [`ImportError`] naming the file, as [`import::load_model_within`] gives it.
pub fn load_model(resolved: &Resolved, budget: &mut Budget) -> Result<Model, ImportError> {
    static CACHE: Mutex<Option<HashMap<&'static str, Model>>> = Mutex::new(None);
    match resolved {
        Resolved::File(path) => import::load_model_within(path, budget),
        Resolved::Embedded { name, bytes } => {
            let cached = CACHE
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .as_ref()
                .and_then(|cache| cache.get(name).cloned());
            let label = format!("{BUILTIN_PREFIX}{name}");
            if let Some(model) = cached {
                let charged = budget
                    .charge_parts(model.parts.len() as u64)
                    .and_then(|()| {
                        budget
                            .charge_mesh(model.triangle_count() as u64, model.vertex_count() as u64)
                    });
                return charged
                    .map(|()| model)
                    .map_err(|e| ImportError::new(label, e.into()));
            }
            let model = load_model_bytes(&label, bytes, budget)?;
            CACHE
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .get_or_insert_with(HashMap::new)
                .insert(name, model.clone());
            Ok(model)
        }
    }
}

/// Loads a model from the bytes of a single-file model (STL, PLY, GLB, or OBJ/glTF without
/// external files) called `name`, whose extension picks the format, with
/// [`import::load_model_within`] and `budget`: the bytes are written to a fresh temporary
/// folder, loaded and removed again. Warnings name `name` rather than the temporary file.
///
/// # Errors
/// [`ImportError`] if the temporary file cannot be written or the model cannot be loaded.
pub fn load_model_bytes(
    name: &str,
    bytes: &[u8],
    budget: &mut Budget,
) -> Result<Model, ImportError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let file_name = Path::new(name)
        .file_name()
        .map_or_else(|| "model".into(), ToOwned::to_owned);
    let dir = std::env::temp_dir().join(format!(
        "srt-scene-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let path = dir.join(file_name);
    let written = std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&path, bytes));
    let result = match written {
        Ok(()) => import::load_model_within(&path, budget),
        Err(error) => Err(ImportError::new(
            name,
            ImportFailure::Io(InputFileError::Io(error)),
        )),
    };
    // Best effort: a leftover temporary folder is harmless.
    let _ = std::fs::remove_dir_all(&dir);
    let mut model = result?;
    let temporary = path.display().to_string();
    for warning in &mut model.warnings {
        *warning = warning.replace(&temporary, name);
    }
    Ok(model)
}

/// Loads the texture image at `resolved`, charging its texels to `budget`.
///
/// # Errors
/// A message saying why the image cannot be read or decoded, or does not fit in the budget.
pub fn load_texture(resolved: &Resolved, budget: &mut Budget) -> Result<Texture, String> {
    match resolved {
        Resolved::File(path) => textures::load_image(path, budget),
        Resolved::Embedded { name, bytes } => {
            let extension = Path::new(name).extension().and_then(|e| e.to_str());
            let source = format!("{BUILTIN_PREFIX}{name}");
            textures::decode_image(bytes, extension, &source, budget)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolves_builtin_and_relative_paths() {
        assert_eq!(
            resolve(Path::new("scenes"), "ship.glb"),
            Ok(Resolved::File(PathBuf::from("scenes/ship.glb")))
        );
        assert!(matches!(
            resolve(Path::new("x"), "builtin:models/spider.stl"),
            Ok(Resolved::Embedded {
                name: "models/spider.stl",
                ..
            })
        ));
        let error = resolve(Path::new("x"), "builtin:models/nothing.stl").unwrap_err();
        assert!(
            error.contains("nothing.stl") && error.contains("models/spider.stl"),
            "{error}"
        );
    }

    #[test]
    fn the_embedded_spider_loads() {
        let resolved = resolve(Path::new("."), "builtin:models/spider.stl").unwrap();
        let mut budget = Budget::new();
        let model = load_model(&resolved, &mut budget).unwrap();
        assert_eq!(model.triangle_count(), 1368);
        // Cached: the second load gives the same model, and is charged again.
        assert_eq!(load_model(&resolved, &mut budget).unwrap(), model);
        assert_eq!(budget.triangles(), 2 * 1368);
    }
}
