//! Model import: glTF 2.0 (`.gltf`, `.glb`), Wavefront OBJ + MTL, PLY and STL files into
//! [`Part`]s (one [`Mesh`] with one [`Material`] each).
//!
//! Conventions shared by every format:
//!
//! - **One part per mesh primitive / material**: a glTF primitive (instanced once per node that
//!   uses it, with the node's world transform applied), an OBJ object/group with one material, a
//!   PLY file, an STL solid.
//! - **Normals** come from the file where it has them, otherwise [`Mesh::new`] computes smooth
//!   ones. STL facets get their own three vertices each and the facet normal (flat shading).
//! - **Texture coordinates** follow glTF: v = 0 is the top row of the image (row 0 of
//!   [`Texture::texels`]). OBJ and PLY store v = 0 at the bottom, so their v is flipped (v ↦ 1 − v).
//! - **Colours** (material base colour and vertex colours) are sRGB-encoded, like texels: glTF's
//!   linear `baseColorFactor` and `COLOR_0` are encoded with the sRGB curve; OBJ `Kd` and PLY
//!   vertex colours are taken as stored.
//! - **Vertices no triangle uses are dropped**, so a part's bounds are those of its surface.
//! - **Errors and warnings**: unreadable or malformed files, non-finite positions, out-of-range
//!   indices, missing glTF buffers and models without a single triangle are errors
//!   ([`ImportError`], whose message names the file). A part whose geometry is invalid fails the
//!   whole model (corrupt data is not silently dropped). Problems that leave a usable model — a
//!   missing or undecodable texture (the base colour is used instead), a missing MTL file, point
//!   or line primitives (skipped), ignored glTF extensions — are collected in
//!   [`Model::warnings`], each naming the file or element concerned.
//! - **Hostile input**: files are read through [`input_file::read`] (regular files only, size
//!   capped); every triangle, vertex, part and texel is charged to a [`Budget`] before it is
//!   allocated ([`crate::limits`]); a glTF node graph is counted before it is walked. Error and
//!   warning messages are one bounded line ([`crate::message`]) naming the file and, where the
//!   format has lines, the line.
//! - Third-party parsers run inside [`std::panic::catch_unwind`] as a last line of defence: a
//!   panic becomes an [`ImportError`] ("the loader crashed on this file"), not an abort of the
//!   caller. Inputs that are known to crash them are rejected before they get there.

mod gltf_accessor;
mod gltf_model;
mod obj;
mod ply;
mod stl;
mod texture;

use std::fmt::{self, Write as _};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};

pub use gltf_model::MAX_JSON_OBJECTS;

use crate::input_file::{self, FileKind, InputFileError};
use crate::limits::{Budget, OverBudget};
use crate::message::one_line;

#[cfg(doc)]
use crate::mesh::{Material, Texture};
use crate::mesh::{Mesh, MeshError, Part};

/// The file extensions [`load_model`] understands (compared case-insensitively).
pub const SUPPORTED_EXTENSIONS: [&str; 5] = ["gltf", "glb", "obj", "ply", "stl"];

/// A model loaded from a file: its parts, all in one rest frame, and non-fatal problems met on
/// the way.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// Parts (one mesh and one material each); never empty for a model returned by
    /// [`load_model`].
    pub parts: Vec<Part>,
    /// Non-fatal problems, one sentence each, naming the file or element concerned (a missing
    /// texture, a skipped point primitive, an ignored extension…).
    pub warnings: Vec<String>,
}

impl Model {
    /// Total number of triangles over all parts.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.mesh.triangles().len()).sum()
    }

    /// Total number of vertices over all parts.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.parts.iter().map(|p| p.mesh.positions().len()).sum()
    }

    /// Axis-aligned bounds (min, max) over all parts, or `None` for a model without parts.
    #[must_use]
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.parts
            .iter()
            .map(|p| p.mesh.bounds())
            .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
    }
}

/// Why a model file could not be loaded: the file and the reason.
///
/// Its message always names the file, e.g.
/// `cannot load model "foo.glb": the file is not valid glTF: …`, and is one line of at most
/// [`MAX_MESSAGE_CHARS`](crate::message::MAX_MESSAGE_CHARS) characters.
#[derive(Debug)]
pub struct ImportError {
    path: PathBuf,
    reason: ImportFailure,
}

impl ImportError {
    /// An error about `path`.
    #[must_use]
    pub fn new(path: impl Into<PathBuf>, reason: ImportFailure) -> Self {
        Self {
            path: path.into(),
            reason,
        }
    }

    /// The model file that failed to load.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Why it failed.
    #[must_use]
    pub fn reason(&self) -> &ImportFailure {
        &self.reason
    }
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&one_line(&format!(
            "cannot load model \"{}\": {}",
            self.path.display(),
            self.reason
        )))
    }
}

impl std::error::Error for ImportError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.reason)
    }
}

/// The reason part of an [`ImportError`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ImportFailure {
    /// The file could not be opened or read, is not a regular file, or is too large.
    #[error("the file cannot be read: {0}")]
    Io(InputFileError),
    /// The model needs more triangles, vertices or parts than a scene may have.
    #[error("the model is too large: {0}")]
    TooLarge(#[from] OverBudget),
    /// The file name has no extension, or one no loader handles.
    #[error(
        "the file extension {extension:?} is not supported (supported: gltf, glb, obj, ply, stl)"
    )]
    UnsupportedExtension {
        /// The extension as written (empty if there is none).
        extension: String,
    },
    /// The file is not a valid file of its format.
    #[error("the file is not valid {format}: {message}")]
    Invalid {
        /// Format name ("glTF", "OBJ", "PLY", "STL").
        format: &'static str,
        /// What the parser found wrong.
        message: String,
    },
    /// A file the model needs (a glTF buffer) is missing or unreadable.
    #[error("{resource} cannot be loaded: {message}")]
    Resource {
        /// The resource, naming its file (e.g. `buffer 0 ("engine.bin")`).
        resource: String,
        /// Why it could not be loaded.
        message: String,
    },
    /// A part's geometry is invalid (non-finite positions, indices out of range…).
    #[error("{part} is invalid: {error}")]
    Mesh {
        /// The part (e.g. `mesh "Cube" primitive 0`).
        part: String,
        /// What is wrong with it.
        error: MeshError,
    },
    /// Nothing to render: the model has no triangles at all.
    #[error("the model has no triangles{detail}")]
    Empty {
        /// Extra explanation, starting with a space or a separator (may be empty).
        detail: String,
    },
    /// A third-party parser panicked on the file.
    #[error("the loader crashed on this file: {0}")]
    Crashed(String),
}

/// Loads a model file, choosing the format by the file extension (case-insensitive: `gltf`,
/// `glb`, `obj`, `ply`, `stl`), with a budget of its own ([`load_model_within`]).
///
/// See the [module documentation](self) for the conventions (parts, normals, texture
/// coordinates, colours, what is a warning and what an error).
///
/// # Errors
/// [`ImportError`] naming the file if the extension is not supported, the file cannot be read
/// or is malformed, a needed resource (glTF buffer) is missing, a part's geometry is invalid,
/// the model is larger than a scene may be, or it has no triangles.
pub fn load_model(path: &Path) -> Result<Model, ImportError> {
    load_model_within(path, &mut Budget::new())
}

/// Loads a model file like [`load_model`], charging its triangles, vertices, parts and texture
/// texels to `budget` (a scene's) before they are allocated.
///
/// # Errors
/// As [`load_model`]; [`ImportFailure::TooLarge`] when the model does not fit in what is left
/// of `budget`.
pub fn load_model_within(path: &Path, budget: &mut Budget) -> Result<Model, ImportError> {
    let loader = loader_for(path)?;
    let bytes = input_file::read(path, FileKind::Model)
        .map_err(|e| ImportError::new(path, ImportFailure::Io(e)))?;
    load_with(loader, path, bytes, budget)
}

/// Loads a model from `bytes`, the content of a single-file model (STL, PLY, GLB, or OBJ/glTF
/// whose other files are not needed) called `path`: the extension of `path` picks the format,
/// and messages name `path`. Nothing is read from disk except the files the model itself names
/// (a glTF's buffers, an OBJ's materials), relative to `path`'s folder: a web page or a script
/// hands over bytes, with the limits and messages of [`load_model_within`].
///
/// # Errors
/// As [`load_model_within`] (the size limit of a model file included).
pub fn load_model_bytes_within(
    path: &Path,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportError> {
    let loader = loader_for(path)?;
    let max = FileKind::Model.max_bytes();
    let size = u64::try_from(bytes.len()).unwrap_or(u64::MAX);
    if size > max {
        let error = input_file::too_large(size, FileKind::Model);
        return Err(ImportError::new(path, ImportFailure::Io(error)));
    }
    load_with(loader, path, bytes, budget)
}

/// The loader of `path`'s format, chosen by its extension (case-insensitive).
fn loader_for(path: &Path) -> Result<Loader, ImportError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    Ok(match extension.as_str() {
        "gltf" | "glb" => gltf_model::load,
        "obj" => obj::load,
        "ply" => ply::load,
        "stl" => stl::load,
        _ => {
            let extension = path
                .extension()
                .map(|e| e.to_string_lossy().into_owned())
                .unwrap_or_default();
            return Err(ImportError::new(
                path,
                ImportFailure::UnsupportedExtension { extension },
            ));
        }
    })
}

/// Runs `loader` on the model file `path`'s `bytes`: an empty file, a panicking parser and a
/// model without triangles are errors naming `path`; a model that fails is not charged.
fn load_with(
    loader: Loader,
    path: &Path,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportError> {
    if bytes.is_empty() {
        let detail = " (the file is empty)".to_owned();
        return Err(ImportError::new(path, ImportFailure::Empty { detail }));
    }
    // A model that fails is not charged (loaders charge as they go).
    let before = budget.clone();
    let mut model = match catch_unwind(AssertUnwindSafe(|| loader(path, bytes, budget))) {
        Ok(result) => result,
        Err(payload) => Err(ImportFailure::Crashed(panic_message(payload.as_ref()))),
    }
    .map_err(|reason| {
        *budget = before;
        ImportError::new(path, reason)
    })?;
    for warning in &mut model.warnings {
        *warning = one_line(warning);
    }
    if model.parts.is_empty() || model.triangle_count() == 0 {
        let mut detail = String::new();
        if !model.warnings.is_empty() {
            const SHOWN: usize = 3;
            let shown = model
                .warnings
                .iter()
                .take(SHOWN)
                .map(String::as_str)
                .collect::<Vec<_>>();
            let _ = write!(detail, " ({}", shown.join("; "));
            if model.warnings.len() > SHOWN {
                let _ = write!(
                    detail,
                    "; and {} more warnings",
                    model.warnings.len() - SHOWN
                );
            }
            detail.push(')');
        }
        return Err(ImportError::new(path, ImportFailure::Empty { detail }));
    }
    Ok(model)
}

/// A format's loader: the file's path (for messages and the files it names), its bytes, and the
/// budget to charge.
type Loader = fn(&Path, Vec<u8>, &mut Budget) -> Result<Model, ImportFailure>;

/// The text of a panic payload.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_owned()
    }
}

/// Geometry as read from a file, before validation into a [`Mesh`].
#[derive(Debug, Default)]
struct RawMesh {
    positions: Vec<DVec3>,
    normals: Option<Vec<DVec3>>,
    uvs: Option<Vec<DVec2>>,
    colors: Option<Vec<[f32; 4]>>,
    triangles: Vec<[u32; 3]>,
}

impl RawMesh {
    /// Validates the geometry into a [`Mesh`], dropping vertices no triangle uses and attributes
    /// whose counts do not match the positions (with a warning). `Ok(None)` if there are no
    /// triangles.
    fn build(self, part: &str, warnings: &mut Vec<String>) -> Result<Option<Mesh>, ImportFailure> {
        let Self {
            positions,
            normals,
            uvs,
            colors,
            triangles,
        } = self;
        if triangles.is_empty() {
            return Ok(None);
        }
        let fail = |error| ImportFailure::Mesh {
            part: part.to_owned(),
            error,
        };
        let n = positions.len();
        // Compact: new index for every used vertex, in first-use order of the old index.
        let mut remap = vec![u32::MAX; n];
        let mut used = Vec::new();
        let mut new_triangles = Vec::with_capacity(triangles.len());
        for (triangle, t) in triangles.iter().enumerate() {
            let mut out = [0; 3];
            for (o, &index) in out.iter_mut().zip(t) {
                let Some(slot) = remap.get_mut(index as usize) else {
                    return Err(fail(MeshError::IndexOutOfRange {
                        triangle,
                        index,
                        vertices: n,
                    }));
                };
                if *slot == u32::MAX {
                    // `used.len() < n <= u32::MAX` because every index fits in a u32.
                    *slot = u32::try_from(used.len()).unwrap_or(u32::MAX);
                    used.push(index as usize);
                }
                *o = *slot;
            }
            new_triangles.push(out);
        }
        let pick = |v: &[DVec3]| used.iter().map(|&i| v[i]).collect::<Vec<_>>();
        let mut checked = |name: &str, len: usize| {
            if len == n {
                true
            } else {
                warnings.push(format!(
                    "{part}: {len} {name}s for {n} vertices; the {name}s are ignored"
                ));
                false
            }
        };
        let normals = normals.filter(|v| checked("normal", v.len()));
        let uvs = uvs.filter(|v| checked("texture coordinate", v.len()));
        let colors = colors.filter(|v| checked("vertex colour", v.len()));
        let mut mesh = Mesh::new(pick(&positions), new_triangles).map_err(fail)?;
        if let Some(normals) = normals {
            // Non-finite normals are a lesser fault than non-finite positions: fall back to the
            // smooth normal (a zero vector makes `with_normals` do that).
            let normals = used
                .iter()
                .map(|&i| {
                    if normals[i].is_finite() {
                        normals[i]
                    } else {
                        DVec3::ZERO
                    }
                })
                .collect();
            mesh = mesh.with_normals(normals).map_err(fail)?;
        }
        if let Some(uvs) = uvs {
            let uvs = used.iter().map(|&i| uvs[i]).collect();
            mesh = mesh.with_uvs(uvs).map_err(fail)?;
        }
        if let Some(colors) = colors {
            let colors = used.iter().map(|&i| colors[i]).collect();
            mesh = mesh.with_colors(colors).map_err(fail)?;
        }
        Ok(Some(mesh))
    }
}

/// Fan triangulation of a polygon given by vertex indices: (0, i, i + 1) for i in 1..n − 1.
/// Polygons with fewer than three vertices give no triangles.
fn fan(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    if let [first, rest @ ..] = polygon {
        for pair in rest.windows(2) {
            out.push([*first, pair[0], pair[1]]);
        }
    }
}

/// sRGB encoding of a linear colour component, clamped to [0, 1] first.
fn encode_srgb(linear: f32) -> f32 {
    let clamped = f64::from(linear.clamp(0.0, 1.0));
    #[expect(
        clippy::cast_possible_truncation,
        reason = "a value in [0, 1] fits an f32"
    )]
    let encoded = srt_color::srgb_encode(clamped) as f32;
    encoded
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_triangulates_polygons() {
        let mut out = Vec::new();
        fan(&[0, 1, 2, 3, 4], &mut out);
        assert_eq!(out, [[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
        out.clear();
        fan(&[0, 1], &mut out);
        fan(&[], &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn build_drops_unused_vertices_and_checks_indices() {
        let raw = RawMesh {
            positions: vec![DVec3::splat(f64::NAN), DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[1, 2, 3]],
            ..RawMesh::default()
        };
        let mut warnings = Vec::new();
        let mesh = raw.build("test", &mut warnings).unwrap().unwrap();
        assert_eq!(mesh.positions(), [DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert_eq!(mesh.triangles(), [[0, 1, 2]]);

        let raw = RawMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 7]],
            ..RawMesh::default()
        };
        let err = raw.build("test", &mut warnings).unwrap_err();
        assert!(matches!(
            err,
            ImportFailure::Mesh {
                error: MeshError::IndexOutOfRange { .. },
                ..
            }
        ));
    }

    #[test]
    fn mismatched_attributes_are_dropped_with_a_warning() {
        let raw = RawMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            normals: Some(vec![DVec3::Z]),
            triangles: vec![[0, 1, 2]],
            ..RawMesh::default()
        };
        let mut warnings = Vec::new();
        assert!(raw.build("part", &mut warnings).unwrap().is_some());
        assert_eq!(warnings.len(), 1);
        assert!(warnings[0].contains("normal"));
    }

    #[test]
    fn srgb_encoding_clamps() {
        assert!(encode_srgb(-1.0).abs() < 1e-7);
        assert!((encode_srgb(2.0) - 1.0).abs() < 1e-6);
        assert!((encode_srgb(0.214_041_14) - 0.5).abs() < 1e-4);
    }
}
