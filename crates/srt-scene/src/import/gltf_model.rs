//! glTF 2.0 (`.gltf` with embedded or external buffers, `.glb`).
//!
//! The document is parsed and validated by the `gltf` crate; buffers, images and accessors are
//! read here, so that a missing image is a warning naming its file (a missing buffer stays an
//! error) and malformed data is an error rather than a panic.
//!
//! What is read: the default scene (or, without one, every root node), walking the node
//! hierarchy and multiplying the transforms; triangle, triangle-strip and triangle-fan
//! primitives (points and lines are skipped with a warning); `POSITION`, `NORMAL`, the
//! `TEXCOORD_n` set the base-colour texture uses (else `TEXCOORD_0`) and `COLOR_0`; the
//! material's `baseColorFactor` and base-colour texture. Skins, morph targets, animations,
//! cameras and the other material properties are ignored; required extensions that only change
//! materials or lights (`KHR_materials_*`, `KHR_texture_transform`, `KHR_lights_punctual`,
//! `KHR_technique_webgl`) are
//! ignored with a warning, as is `KHR_mesh_quantization` (its integer attributes are read like any
//! others). Other required extensions (Draco or meshopt compression…) make the file an error.
//! `POSITION` accessors without the `min`/`max` the specification requires get placeholders (with
//! a warning) so that validation accepts them.
//!
//! Before anything is instanced, the node graph is counted: the parts and triangles one instance
//! of each node's subtree gives, from accessor counts alone, memoised per node, so a graph that
//! shares subtrees (a DAG whose instances multiply exponentially) costs one visit per node and
//! edge. A cycle (invalid glTF) is an error, and the total is charged to the scene's budget; the
//! walk then skips subtrees that give nothing. The JSON is refused before parsing when it has
//! more objects than [`MAX_JSON_OBJECTS`]. External buffers and images are read through
//! [`crate::input_file`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DMat4, DQuat, DVec2, DVec3};
use gltf::mesh::Mode;
use gltf::{Document, Gltf, Semantic};

use super::gltf_accessor::{read, read_indices, view_bytes};
use super::texture::TextureCache;
use super::{ImportFailure, Model, RawMesh, encode_srgb};
use crate::input_file::{self, FileKind};
use crate::limits::Budget;
use crate::mesh::{Material, Mesh, Part, Texture};
use crate::textures::decode_image;

/// Node hierarchies deeper than this are cut (with a warning).
const MAX_DEPTH: usize = 256;

/// The most JSON objects (`{`, counted before parsing) a glTF document may have. Parsed, an
/// object (a node, an accessor…) takes up to a few hundred bytes, so this keeps the parsed
/// document below about 100 MB; large real scenes have tens of thousands.
pub const MAX_JSON_OBJECTS: usize = 250_000;

/// Loads a `.gltf` or `.glb` file: parses it, counts what its node graph gives (charged to the
/// budget) and instances the meshes of the default scene.
pub(super) fn load(
    path: &Path,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportFailure> {
    let invalid = |message: String| ImportFailure::Invalid {
        format: "glTF",
        message,
    };
    let mut warnings = Vec::new();
    let (document, blob) = parse(&bytes, &mut warnings).map_err(invalid)?;
    let base = path.parent().unwrap_or_else(|| Path::new(""));
    let buffers = load_buffers(&document, base, blob)?;
    let roots = root_nodes(&document);
    let meshes: Vec<Tally> = document
        .meshes()
        .map(|mesh| Tally::of_mesh(&mesh))
        .collect();
    let nodes = node_tallies(&document, &meshes).map_err(invalid)?;
    let unplaced_meshes = document.nodes().len() == 0 && document.meshes().len() > 0;
    let mut total = roots
        .iter()
        .fold(Tally::default(), |sum, node| sum.plus(nodes[node.index()]));
    if unplaced_meshes {
        total = meshes.iter().fold(total, |sum, &mesh| sum.plus(mesh));
    }
    budget.charge_parts(total.parts)?;
    budget.charge_mesh(total.triangles, 0)?;
    let mut loader = Loader {
        document: &document,
        buffers: &buffers,
        base,
        file_name: file_name(path),
        images: HashMap::new(),
        files: TextureCache::default(),
        primitives: HashMap::new(),
        nodes: &nodes,
        budget,
        warned_skin: false,
    };
    let mut parts = Vec::new();
    if unplaced_meshes {
        warnings
            .push("the file has meshes but no nodes; the meshes are placed untransformed".into());
        for mesh in document.meshes() {
            loader.instance(&mesh, DMat4::IDENTITY, &mut parts, &mut warnings)?;
        }
    }
    for node in roots {
        loader.visit(&node, DMat4::IDENTITY, 0, &mut parts, &mut warnings)?;
    }
    Ok(Model { parts, warnings })
}

/// Parses and validates the document (refusing one with more than [`MAX_JSON_OBJECTS`] JSON
/// objects or with required extensions that change geometry, ignoring the others with a
/// warning); returns it with the binary chunk of a `.glb`.
fn parse(bytes: &[u8], warnings: &mut Vec<String>) -> Result<(Document, Option<Vec<u8>>), String> {
    check_glb_header(bytes)?;
    let objects = json_part(bytes).iter().filter(|&&b| b == b'{').count();
    if objects > MAX_JSON_OBJECTS {
        return Err(format!(
            "the JSON has {objects} objects, more than the {MAX_JSON_OBJECTS} a glTF file may have"
        ));
    }
    let Gltf { document, blob } =
        Gltf::from_slice_without_validation(bytes).map_err(|e| e.to_string())?;
    let mut root = document.into_json();
    let (ignored, kept): (Vec<String>, Vec<String>) = root
        .extensions_required
        .drain(..)
        .partition(|e| ignorable_extension(e));
    if !ignored.is_empty() {
        warnings.push(format!(
            "required glTF extensions ignored: {} (their effect on materials is not imported)",
            ignored.join(", ")
        ));
    }
    if !kept.is_empty() {
        return Err(format!(
            "the file requires glTF extensions this importer does not support: {}",
            kept.join(", ")
        ));
    }
    fill_missing_position_bounds(&mut root, warnings)?;
    let document = Document::from_json(root).map_err(|e| e.to_string())?;
    Ok((document, blob))
}

/// The nodes the walk starts from: the default scene's, or without one every node that is no
/// other node's child.
fn root_nodes(document: &Document) -> Vec<gltf::Node<'_>> {
    if let Some(scene) = document.default_scene() {
        return scene.nodes().collect();
    }
    let mut is_child = vec![false; document.nodes().len()];
    for node in document.nodes() {
        for child in node.children() {
            if let Some(flag) = is_child.get_mut(child.index()) {
                *flag = true;
            }
        }
    }
    document.nodes().filter(|n| !is_child[n.index()]).collect()
}

/// The JSON of a glTF file: the whole of a `.gltf`, the first chunk of a binary glTF.
fn json_part(bytes: &[u8]) -> &[u8] {
    if !bytes.starts_with(b"glTF") {
        return bytes;
    }
    let length = bytes
        .get(12..16)
        .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let end = 20usize.saturating_add(length).min(bytes.len());
    bytes.get(20..end).unwrap_or_default()
}

/// What one instance of a mesh or a node's subtree gives: parts and triangles, counted from
/// accessor counts without reading any data (a primitive whose data turns out unusable gives
/// less, never more).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Tally {
    parts: u64,
    triangles: u64,
}

impl Tally {
    /// The sum, saturating.
    const fn plus(self, other: Self) -> Self {
        Self {
            parts: self.parts.saturating_add(other.parts),
            triangles: self.triangles.saturating_add(other.triangles),
        }
    }

    /// One instance of `mesh`: its triangle primitives that have positions.
    fn of_mesh(mesh: &gltf::Mesh<'_>) -> Self {
        mesh.primitives()
            .filter_map(|primitive| {
                let positions = primitive.get(&Semantic::Positions)?;
                let count = primitive
                    .indices()
                    .map_or(positions.count(), |indices| indices.count())
                    as u64;
                let triangles = match primitive.mode() {
                    Mode::Triangles => count / 3,
                    Mode::TriangleStrip | Mode::TriangleFan => count.saturating_sub(2),
                    _ => 0,
                };
                (triangles > 0).then_some(Self {
                    parts: 1,
                    triangles,
                })
            })
            .fold(Self::default(), Self::plus)
    }
}

/// Where the depth-first count is with a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Visit {
    New,
    /// On the current path (meeting it again means a cycle).
    Open,
    Done,
}

/// The [`Tally`] of one instance of every node's subtree (its mesh and its children's subtrees,
/// a child listed twice counting twice), each node computed once: an iterative depth-first
/// count that needs no stack for deep hierarchies.
///
/// # Errors
/// A message naming a node that is its own ancestor (glTF node graphs must be acyclic).
fn node_tallies(document: &Document, meshes: &[Tally]) -> Result<Vec<Tally>, String> {
    let json = &document.as_json().nodes;
    let children = |node: usize| json[node].children.as_deref().unwrap_or_default();
    let mut state = vec![Visit::New; json.len()];
    let mut tallies = vec![Tally::default(); json.len()];
    for start in 0..json.len() {
        if state[start] != Visit::New {
            continue;
        }
        state[start] = Visit::Open;
        let mut path = vec![(start, 0usize)];
        while let Some((node, next)) = path.last_mut() {
            let node = *node;
            if let Some(child) = children(node).get(*next) {
                *next += 1;
                let child = child.value();
                match state.get(child) {
                    Some(Visit::Open) => {
                        return Err(format!(
                            "node {child} is its own ancestor: the node graph has a cycle, which \
                             glTF does not allow"
                        ));
                    }
                    Some(Visit::New) => {
                        state[child] = Visit::Open;
                        path.push((child, 0));
                    }
                    _ => {}
                }
                continue;
            }
            let own = json[node]
                .mesh
                .and_then(|mesh| meshes.get(mesh.value()).copied())
                .unwrap_or_default();
            tallies[node] = children(node)
                .iter()
                .filter_map(|child| tallies.get(child.value()))
                .fold(own, |sum, &child| sum.plus(child));
            state[node] = Visit::Done;
            path.pop();
        }
    }
    Ok(tallies)
}

/// The file name (without directories) for messages.
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Rejects binary glTF headers the `gltf` crate would mis-handle (a declared length below the
/// header's own size underflows there).
fn check_glb_header(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let length = bytes
        .get(8..12)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
    match length {
        None => Err("the binary glTF header is truncated".to_owned()),
        Some(length) if length < 20 => Err(format!(
            "the binary glTF header declares a length of {length} bytes"
        )),
        Some(_) => Ok(()),
    }
}

/// Whether a required extension can be ignored while still importing the geometry correctly.
fn ignorable_extension(name: &str) -> bool {
    name.starts_with("KHR_materials_")
        || matches!(
            name,
            "KHR_texture_transform"
                | "KHR_mesh_quantization"
                | "KHR_lights_punctual"
                | "KHR_xmp_json_ld"
                | "KHR_technique_webgl"
        )
}

/// Gives `POSITION` accessors without `min`/`max` placeholder bounds, with a warning: the glTF
/// specification requires them and the `gltf` crate's validation rejects files without them, but
/// we compute bounds ourselves and many exporters leave them out.
///
/// # Errors
/// A message if a `POSITION` attribute names an accessor that does not exist (the `gltf` crate's
/// validation would index out of bounds on it).
fn fill_missing_position_bounds(
    root: &mut gltf::json::Root,
    warnings: &mut Vec<String>,
) -> Result<(), String> {
    use gltf::json::validation::Checked;
    let mut targets = Vec::new();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let Some(index) = primitive
                .attributes
                .get(&Checked::Valid(Semantic::Positions))
            else {
                continue;
            };
            if index.value() >= root.accessors.len() {
                return Err(format!(
                    "mesh {m} primitive {p}: POSITION names accessor {}, but there are only {}",
                    index.value(),
                    root.accessors.len()
                ));
            }
            targets.push(index.value());
        }
    }
    targets.sort_unstable();
    targets.dedup();
    let mut filled = Vec::new();
    for index in targets {
        let Some(accessor) = root.accessors.get_mut(index) else {
            continue;
        };
        if accessor.min.is_some() && accessor.max.is_some() {
            continue;
        }
        let components = match accessor.type_ {
            Checked::Valid(kind) => kind.multiplicity(),
            Checked::Invalid => 3,
        };
        let zeros = gltf::json::Value::Array(vec![gltf::json::Value::from(0.0); components]);
        accessor.min.get_or_insert_with(|| zeros.clone());
        accessor.max.get_or_insert(zeros);
        filled.push(index.to_string());
    }
    if !filled.is_empty() {
        warnings.push(format!(
            "POSITION accessor(s) {} lack the min/max bounds glTF requires (not needed here)",
            filled.join(", ")
        ));
    }
    Ok(())
}

/// Reads every buffer: the GLB binary chunk, a data URI or an external file.
fn load_buffers(
    document: &Document,
    base: &Path,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, ImportFailure> {
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let index = buffer.index();
        let (resource, data) = match buffer.source() {
            gltf::buffer::Source::Bin => (
                format!("buffer {index} (the binary chunk)"),
                blob.take()
                    .ok_or_else(|| "the file has no binary chunk".to_owned()),
            ),
            gltf::buffer::Source::Uri(uri) => {
                let resource = if uri.starts_with("data:") {
                    format!("buffer {index} (embedded data URI)")
                } else {
                    format!("buffer {index} (\"{uri}\")")
                };
                (resource, resolve_uri(uri, base))
            }
        };
        let data = data.map_err(|message| ImportFailure::Resource {
            resource: resource.clone(),
            message,
        })?;
        if data.len() < buffer.length() {
            return Err(ImportFailure::Resource {
                resource,
                message: format!(
                    "it has {} bytes but the file declares {}",
                    data.len(),
                    buffer.length()
                ),
            });
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// The bytes a URI (a data URI or a file relative to `base`) refers to.
fn resolve_uri(uri: &str, base: &Path) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((header, payload)) = rest.split_once(',') else {
            return Err("malformed data URI (no comma)".to_owned());
        };
        let data = if header.ends_with(";base64") {
            base64_decode(payload)?
        } else {
            percent_decode(payload)
        };
        return Ok(data);
    }
    let path = resolve_uri_path(uri, base)?;
    input_file::read(&path, FileKind::Model).map_err(|e| format!("\"{}\": {e}", path.display()))
}

/// Decodes `%XX` escapes (the `percent-encoding` crate; malformed escapes are kept as they are).
fn percent_decode(text: &str) -> Vec<u8> {
    percent_encoding::percent_decode_str(text).collect()
}

/// Decodes standard or URL-safe base64 (the `base64` crate), ignoring whitespace; padding is
/// optional.
fn base64_decode(text: &str) -> Result<Vec<u8>, String> {
    use base64::Engine as _;
    use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
    const CONFIG: GeneralPurposeConfig = GeneralPurposeConfig::new()
        .with_decode_padding_mode(DecodePaddingMode::Indifferent)
        .with_decode_allow_trailing_bits(true);
    let compact: String = text.chars().filter(|c| !c.is_ascii_whitespace()).collect();
    let alphabet = if compact.contains(['-', '_']) {
        &base64::alphabet::URL_SAFE
    } else {
        &base64::alphabet::STANDARD
    };
    GeneralPurpose::new(alphabet, CONFIG)
        .decode(compact)
        .map_err(|e| format!("invalid base64: {e}"))
}

/// A node's local transform, composed in `f64`.
fn local_transform(node: &gltf::Node<'_>) -> DMat4 {
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|column| column.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let [x, y, z, w] = rotation.map(f64::from);
            let rotation = DQuat::from_xyzw(x, y, z, w);
            let rotation = if rotation.length_squared() > 0.0 {
                rotation.normalize()
            } else {
                DQuat::IDENTITY
            };
            DMat4::from_scale_rotation_translation(
                DVec3::from_array(scale.map(f64::from)),
                rotation,
                DVec3::from_array(translation.map(f64::from)),
            )
        }
    }
}

/// State while converting one document.
struct Loader<'a> {
    document: &'a Document,
    buffers: &'a [Vec<u8>],
    base: &'a Path,
    file_name: String,
    /// Decoded images by index (`None`: failed, already warned about).
    images: HashMap<usize, Option<Arc<Texture>>>,
    /// External image files.
    files: TextureCache,
    /// Converted primitives by (mesh, primitive) index, untransformed (`None`: skipped).
    primitives: HashMap<(usize, usize), Option<(Mesh, Material)>>,
    /// What each node's subtree gives (already charged to the budget).
    nodes: &'a [Tally],
    /// The scene's budget, charged with the vertices and texels read.
    budget: &'a mut Budget,
    warned_skin: bool,
}

impl Loader<'_> {
    /// Emits the parts of `node` (at `depth`, 0 for a root) and its descendants, skipping
    /// subtrees that give no parts.
    fn visit(
        &mut self,
        node: &gltf::Node<'_>,
        parent: DMat4,
        depth: usize,
        parts: &mut Vec<Part>,
        warnings: &mut Vec<String>,
    ) -> Result<(), ImportFailure> {
        if self
            .nodes
            .get(node.index())
            .is_none_or(|tally| tally.parts == 0)
        {
            return Ok(());
        }
        if depth >= MAX_DEPTH {
            warnings.push(format!(
                "the node hierarchy is deeper than {MAX_DEPTH} levels; node {} and below are skipped",
                node.index()
            ));
            return Ok(());
        }
        let world = parent * local_transform(node);
        if let Some(mesh) = node.mesh() {
            if node.skin().is_some() && !self.warned_skin {
                self.warned_skin = true;
                warnings.push(
                    "skins are ignored: skinned meshes are imported in their bind pose".into(),
                );
            }
            self.instance(&mesh, world, parts, warnings)?;
        }
        for child in node.children() {
            self.visit(&child, world, depth + 1, parts, warnings)?;
        }
        Ok(())
    }

    /// Emits the parts of `mesh` transformed by `world`.
    fn instance(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        world: DMat4,
        parts: &mut Vec<Part>,
        warnings: &mut Vec<String>,
    ) -> Result<(), ImportFailure> {
        for primitive in mesh.primitives() {
            let key = (mesh.index(), primitive.index());
            if !self.primitives.contains_key(&key) {
                let converted = self.convert(mesh, &primitive, warnings)?;
                self.primitives.insert(key, converted);
            }
            let Some(Some((local, material))) = self.primitives.get(&key) else {
                continue;
            };
            let mesh = local
                .clone()
                .transformed(world)
                .map_err(|error| ImportFailure::Mesh {
                    part: format!("{} (transformed by its node)", label(mesh, &primitive)),
                    error,
                })?;
            parts.push(Part {
                mesh,
                material: material.clone(),
            });
        }
        Ok(())
    }

    /// Converts one primitive, untransformed. `Ok(None)` if it is skipped (with a warning).
    fn convert(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        primitive: &gltf::Primitive<'_>,
        warnings: &mut Vec<String>,
    ) -> Result<Option<(Mesh, Material)>, ImportFailure> {
        let label = label(mesh, primitive);
        let mode = primitive.mode();
        if matches!(
            mode,
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
        ) {
            warnings.push(format!(
                "{label}: {mode:?} primitive skipped (only triangles are imported)"
            ));
            return Ok(None);
        }
        let Some(position_accessor) = primitive.get(&Semantic::Positions) else {
            warnings.push(format!("{label}: no POSITION attribute; skipped"));
            return Ok(None);
        };
        let (positions, triangles) =
            self.geometry(primitive, &position_accessor, &label, warnings)?;
        let material = primitive.material();
        let texture_info = material.pbr_metallic_roughness().base_color_texture();
        let uv_set = texture_info
            .as_ref()
            .map_or(0, gltf::texture::Info::tex_coord);
        let raw = self.vertex_attributes(primitive, positions, triangles, uv_set, &label, warnings);
        let Some(built) = raw.build(&label, warnings)? else {
            warnings.push(format!("{label}: no triangles; skipped"));
            return Ok(None);
        };
        let material = self.material(&material, texture_info, &label, warnings);
        Ok(Some((built, material)))
    }

    /// The positions of a primitive (charged to the budget) and its triangles, assembled from
    /// its indices (or, without any, from its vertices in order) in its triangle mode.
    fn geometry(
        &mut self,
        primitive: &gltf::Primitive<'_>,
        position_accessor: &gltf::Accessor<'_>,
        label: &str,
        warnings: &mut Vec<String>,
    ) -> Result<(Vec<DVec3>, Vec<[u32; 3]>), ImportFailure> {
        let invalid = |message: String| ImportFailure::Invalid {
            format: "glTF",
            message: format!("{label}: {message}"),
        };
        self.budget
            .charge_vertices(position_accessor.count() as u64)?;
        let positions: Vec<DVec3> = read::<3>(position_accessor, self.buffers, true)
            .map_err(invalid)?
            .into_iter()
            .map(DVec3::from_array)
            .collect();
        let indices = match primitive.indices() {
            Some(accessor) => read_indices(&accessor, self.buffers).map_err(invalid)?,
            None => (0..u32::try_from(positions.len())
                .map_err(|_| invalid("too many vertices".into()))?)
                .collect(),
        };
        let mode = primitive.mode();
        let triangles = assemble(mode, &indices);
        if mode == Mode::Triangles && indices.len() % 3 != 0 {
            warnings.push(format!(
                "{label}: {} indices is not a multiple of 3; the last {} are ignored",
                indices.len(),
                indices.len() % 3
            ));
        }
        Ok((positions, triangles))
    }

    /// The mesh of `positions` and `triangles` with the primitive's normals, texture
    /// coordinates of set `uv_set` and vertex colours, each where it is usable (otherwise
    /// ignored with a warning).
    fn vertex_attributes(
        &self,
        primitive: &gltf::Primitive<'_>,
        positions: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        uv_set: u32,
        label: &str,
        warnings: &mut Vec<String>,
    ) -> RawMesh {
        let mut attribute = |semantic: Semantic, what: &str| {
            self.attribute(primitive, &semantic, what, positions.len(), label, warnings)
        };
        let normals = attribute(Semantic::Normals, "NORMAL").map(|v| {
            v.into_iter()
                .map(|[x, y, z, _]| DVec3::new(x, y, z))
                .collect()
        });
        let uvs = attribute(Semantic::TexCoords(uv_set), "texture coordinates")
            .map(|v| v.into_iter().map(|[u, v, _, _]| DVec2::new(u, v)).collect());
        #[expect(
            clippy::cast_possible_truncation,
            reason = "colour components in [0, 1]"
        )]
        let colors = attribute(Semantic::Colors(0), "COLOR_0").map(|v| {
            v.into_iter()
                .map(|[r, g, b, a]| {
                    [
                        encode_srgb(r as f32),
                        encode_srgb(g as f32),
                        encode_srgb(b as f32),
                        (a as f32).clamp(0.0, 1.0),
                    ]
                })
                .collect()
        });
        RawMesh {
            positions,
            normals,
            uvs,
            colors,
            triangles,
        }
    }

    /// A vertex attribute of the primitive (called `what` in warnings) as four components per
    /// vertex (missing ones 0, alpha 1); `None` if the primitive has none, or (with a warning)
    /// if it does not have one value per vertex or cannot be read.
    fn attribute(
        &self,
        primitive: &gltf::Primitive<'_>,
        semantic: &Semantic,
        what: &str,
        vertex_count: usize,
        label: &str,
        warnings: &mut Vec<String>,
    ) -> Option<Vec<[f64; 4]>> {
        let accessor = primitive.get(semantic)?;
        if accessor.count() != vertex_count {
            warnings.push(format!(
                "{label}: {what} ignored: {} values for {vertex_count} vertices",
                accessor.count(),
            ));
            return None;
        }
        let result = match accessor.dimensions().multiplicity() {
            2 => read::<2>(&accessor, self.buffers, true).map(|v| {
                v.into_iter()
                    .map(|[a, b]| [a, b, 0.0, 1.0])
                    .collect::<Vec<_>>()
            }),
            3 => read::<3>(&accessor, self.buffers, true)
                .map(|v| v.into_iter().map(|[a, b, c]| [a, b, c, 1.0]).collect()),
            _ => read::<4>(&accessor, self.buffers, true),
        };
        result
            .map_err(|e| warnings.push(format!("{label}: {what} ignored: {e}")))
            .ok()
    }

    /// The primitive's material: its name, `baseColorFactor` and base-colour texture (`None`,
    /// with a warning, if the image cannot be loaded).
    fn material(
        &mut self,
        material: &gltf::Material<'_>,
        texture_info: Option<gltf::texture::Info<'_>>,
        label: &str,
        warnings: &mut Vec<String>,
    ) -> Material {
        let name = material.name().unwrap_or_default().to_owned();
        let user = if name.is_empty() {
            label.to_owned()
        } else {
            format!("material \"{name}\"")
        };
        let texture =
            texture_info.and_then(|info| self.image(&info.texture().source(), &user, warnings));
        let [r, g, b, a] = material.pbr_metallic_roughness().base_color_factor();
        let base_color = [
            encode_srgb(r),
            encode_srgb(g),
            encode_srgb(b),
            a.clamp(0.0, 1.0),
        ];
        Material {
            name,
            base_color,
            texture,
        }
    }

    /// Decodes an image once; `None` (with a warning naming it) if it cannot be loaded.
    fn image(
        &mut self,
        image: &gltf::Image<'_>,
        user: &str,
        warnings: &mut Vec<String>,
    ) -> Option<Arc<Texture>> {
        let index = image.index();
        if let Some(texture) = self.images.get(&index) {
            return texture.clone();
        }
        let json = self.document.as_json().images.get(index)?;
        let hint = json
            .mime_type
            .as_ref()
            .and_then(|m| m.0.strip_prefix("image/"))
            .map(str::to_owned);
        let source = format!("image {index} of \"{}\"", self.file_name);
        let result = if let Some(view) = json
            .buffer_view
            .and_then(|v| self.document.views().nth(v.value()))
        {
            match view_bytes(&view, self.buffers) {
                Some(bytes) => {
                    decode_image(bytes, hint.as_deref(), &source, self.budget).map(Arc::new)
                }
                None => Err(format!(
                    "buffer view {} lies outside its buffer",
                    view.index()
                )),
            }
        } else if let Some(uri) = &json.uri {
            if uri.starts_with("data:") {
                resolve_uri(uri, self.base)
                    .and_then(|bytes| decode_image(&bytes, hint.as_deref(), &source, self.budget))
                    .map(Arc::new)
            } else {
                match resolve_uri_path(uri, self.base) {
                    Ok(path) => {
                        // The file cache warns itself, naming the file.
                        let texture = self.files.file(&path, user, warnings, self.budget);
                        self.images.insert(index, texture.clone());
                        return texture;
                    }
                    Err(e) => Err(e),
                }
            }
        } else {
            Err("it has neither a URI nor a buffer view".to_owned())
        };
        let texture = match result {
            Ok(texture) => Some(texture),
            Err(error) => {
                warnings.push(format!(
                    "{source} (used by {user}) cannot be loaded ({error}); using the base colour"
                ));
                None
            }
        };
        self.images.insert(index, texture.clone());
        texture
    }
}

/// The file a non-data URI names.
fn resolve_uri_path(uri: &str, base: &Path) -> Result<PathBuf, String> {
    if let Some(rest) = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))
    {
        Ok(PathBuf::from(
            String::from_utf8_lossy(&percent_decode(rest)).into_owned(),
        ))
    } else if uri
        .split('/')
        .next()
        .is_some_and(|first| first.contains(':'))
    {
        Err(format!("unsupported URI scheme in \"{uri}\""))
    } else {
        Ok(base.join(String::from_utf8_lossy(&percent_decode(uri)).as_ref()))
    }
}

/// `mesh 3 ("Wheel") primitive 0`, for messages.
fn label(mesh: &gltf::Mesh<'_>, primitive: &gltf::Primitive<'_>) -> String {
    match mesh.name() {
        Some(name) => format!(
            "mesh {} (\"{name}\") primitive {}",
            mesh.index(),
            primitive.index()
        ),
        None => format!("mesh {} primitive {}", mesh.index(), primitive.index()),
    }
}

/// Triangles from an index list in a triangle mode (glTF 2.0 §3.7.2.1).
fn assemble(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..indices.len().saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [indices[i], indices[i + 1], indices[i + 2]]
                } else {
                    [indices[i], indices[i + 2], indices[i + 1]]
                }
            })
            .collect(),
        Mode::TriangleFan => (1..indices.len().saturating_sub(1))
            .map(|i| [indices[i], indices[i + 1], indices[0]])
            .collect(),
        _ => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips_known_vectors() {
        assert_eq!(base64_decode("").unwrap(), b"");
        assert_eq!(base64_decode("Zg==").unwrap(), b"f");
        assert_eq!(base64_decode("Zm8=").unwrap(), b"fo");
        assert_eq!(base64_decode("Zm9v").unwrap(), b"foo");
        assert_eq!(base64_decode("Zm9vYmFy").unwrap(), b"foobar");
        assert_eq!(base64_decode("Zm9v\nYmFy").unwrap(), b"foobar");
        assert!(base64_decode("Zm9v*").is_err());
    }

    #[test]
    fn percent_decoding_keeps_malformed_escapes() {
        assert_eq!(percent_decode("a%20b"), b"a b");
        assert_eq!(percent_decode("100%"), b"100%");
        assert_eq!(percent_decode("%zz%4"), b"%zz%4");
        assert_eq!(percent_decode("%FF"), [0xff]);
    }

    #[test]
    fn strips_and_fans_follow_the_spec() {
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 2, 3]),
            [[0, 1, 2], [1, 3, 2]]
        );
        assert_eq!(
            assemble(Mode::TriangleFan, &[0, 1, 2, 3]),
            [[1, 2, 0], [2, 3, 0]]
        );
        assert_eq!(assemble(Mode::Triangles, &[0, 1, 2, 3]), [[0, 1, 2]]);
        assert!(assemble(Mode::TriangleStrip, &[0, 1]).is_empty());
        assert!(assemble(Mode::TriangleFan, &[]).is_empty());
    }

    #[test]
    fn short_glb_headers_are_rejected() {
        assert!(check_glb_header(b"glTF\x02\0\0\0").is_err());
        assert!(check_glb_header(b"glTF\x02\0\0\0\x04\0\0\0").is_err());
        assert!(check_glb_header(b"{}").is_ok());
    }
}
