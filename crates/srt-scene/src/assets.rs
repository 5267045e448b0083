//! Files embedded in the program (the built-in scenes' models), files a front end holds in
//! memory (a model dropped on the web page), and how scene files refer to files: a path
//! relative to the scene file's folder, `builtin:NAME` for an embedded asset, or `memory:NAME`
//! for a file given to [`add_memory_file`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use crate::import::{self, ImportError, Model};
use crate::limits::Budget;
use crate::mesh::Texture;
use crate::textures;

/// Prefix of paths in scene files that name an embedded asset, e.g. `builtin:models/spider.stl`.
pub const BUILTIN_PREFIX: &str = "builtin:";

/// Prefix of paths that name a file held in memory ([`add_memory_file`]), e.g. `memory:ship.glb`.
pub const MEMORY_PREFIX: &str = "memory:";

/// The files given to [`add_memory_file`], by name.
static MEMORY_FILES: Mutex<Option<HashMap<String, Arc<[u8]>>>> = Mutex::new(None);

/// Holds `bytes` as the file `name` (a file name with its extension, e.g. `ship.glb`) for the
/// rest of the process, replacing an earlier file of that name, and returns the path that names
/// it in scenes and model arguments: `memory:NAME`. Where there is no file system (a web page),
/// a dropped model goes this way through the same loaders, limits and messages as a file.
pub fn add_memory_file(name: &str, bytes: Vec<u8>) -> String {
    MEMORY_FILES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .get_or_insert_with(HashMap::new)
        .insert(name.to_owned(), bytes.into());
    format!("{MEMORY_PREFIX}{name}")
}

/// The bytes of the memory file `name` (without the prefix), if there is one.
fn memory_file(name: &str) -> Option<Arc<[u8]>> {
    MEMORY_FILES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .as_ref()
        .and_then(|files| files.get(name).cloned())
}

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
    /// A file held in memory ([`add_memory_file`]).
    Memory {
        /// Its name, without the `memory:` prefix.
        name: String,
        /// Its content.
        bytes: Arc<[u8]>,
    },
}

impl Resolved {
    /// How messages and caches name it: the file's path, `builtin:NAME` or `memory:NAME`.
    #[must_use]
    pub fn label(&self) -> String {
        match self {
            Self::File(path) => path.display().to_string(),
            Self::Embedded { name, .. } => format!("{BUILTIN_PREFIX}{name}"),
            Self::Memory { name, .. } => format!("{MEMORY_PREFIX}{name}"),
        }
    }
}

/// Resolves `path` from a scene file whose folder is `base_dir`: `builtin:NAME` is the embedded
/// asset NAME, `memory:NAME` the memory file NAME; other paths are joined to `base_dir`
/// (absolute paths stay as they are).
///
/// # Errors
/// A message if `path` names an embedded asset or a memory file that does not exist.
pub fn resolve(base_dir: &Path, path: &str) -> Result<Resolved, String> {
    if let Some(name) = path.strip_prefix(MEMORY_PREFIX) {
        return memory_file(name)
            .map(|bytes| Resolved::Memory {
                name: name.to_owned(),
                bytes,
            })
            .ok_or_else(|| format!("there is no file \"{name}\" in memory"));
    }
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
            let model = load_model_bytes(&label, bytes.to_vec(), budget)?;
            CACHE
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .get_or_insert_with(HashMap::new)
                .insert(name, model.clone());
            Ok(model)
        }
        // Named as it was given (the dropped file's name), without the prefix.
        Resolved::Memory { name, bytes } => load_model_bytes(name, bytes.to_vec(), budget),
    }
}

/// Loads a model from the bytes of a single-file model (STL, PLY, GLB, or OBJ/glTF without
/// external files) called `name`, whose extension picks the format, with
/// [`import::load_model_bytes_within`] and `budget`.
///
/// # Errors
/// [`ImportError`] naming `name` if the model cannot be loaded.
pub fn load_model_bytes(
    name: &str,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportError> {
    import::load_model_bytes_within(Path::new(name), bytes, budget)
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
        Resolved::Memory { name, bytes } => {
            let extension = Path::new(name).extension().and_then(|e| e.to_str());
            textures::decode_image(bytes, extension, &resolved.label(), budget)
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

    #[test]
    fn a_memory_file_loads_like_the_file_and_names_itself_in_errors() {
        let spider = embedded("models/spider.stl").unwrap().to_vec();
        let path = add_memory_file("test-spider.stl", spider);
        assert_eq!(path, "memory:test-spider.stl");
        let resolved = resolve(Path::new("."), &path).unwrap();
        assert_eq!(resolved.label(), path);
        let model = load_model(&resolved, &mut Budget::new()).unwrap();
        assert_eq!(model.triangle_count(), 1368);

        let broken = add_memory_file("test-broken.glb", b"not a glb".to_vec());
        let error = load_model(
            &resolve(Path::new("."), &broken).unwrap(),
            &mut Budget::new(),
        )
        .unwrap_err()
        .to_string();
        assert!(
            error.contains("\"test-broken.glb\"") && error.contains("glTF"),
            "{error}"
        );

        let missing = resolve(Path::new("."), "memory:nothing.stl").unwrap_err();
        assert!(missing.contains("nothing.stl"), "{missing}");
    }
}
