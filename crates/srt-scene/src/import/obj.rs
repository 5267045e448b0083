//! Wavefront OBJ with MTL materials, parsed by `tobj`.
//!
//! One part per object/group and material (as `tobj` splits them). Polygons are fan-triangulated,
//! points and lines ignored. Material: diffuse colour `Kd` and dissolve `d` as the base colour,
//! diffuse texture `map_Kd` (relative to the MTL file; texture options such as `-s 1 1 1` before
//! the file name are skipped). Texture coordinates are flipped to v = 0 at the top. A missing
//! MTL file or texture is a warning, and so is a `Kd` or `d` that reads as NaN or ±∞, named by
//! the MTL file and line (the material gets the default instead). Text that `tobj` would
//! reject or panic on for reasons that do not touch the geometry is repaired first (UTF-16 or
//! Latin-1 text, material statements without a name, one-component MTL colours), and face
//! indices on which its arithmetic would overflow are rejected first, in a first pass that also
//! counts the triangles and vertices and charges them to the budget before `tobj` allocates
//! them. `tobj`'s errors carry no position: the line is where it stopped reading (or, for an
//! index out of range, the first face that refers to an element not defined before it).

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};

use super::texture::TextureCache;
use super::{ImportFailure, Model, RawMesh};
use crate::input_file::{self, FileKind};
use crate::limits::Budget;
use crate::mesh::{Material, Part};
use crate::message::quote;

/// Loads an `.obj` file and the MTL files it names: one part per object/group and material.
pub(super) fn load(
    path: &Path,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportFailure> {
    let Parsed {
        models,
        materials,
        material_dirs,
        mut warnings,
    } = parse(path, &bytes, budget)?;
    let parts_with_faces = models.iter().filter(|m| !m.mesh.indices.is_empty()).count();
    budget.charge_parts(parts_with_faces as u64)?;
    let mut textures = TextureCache::default();
    let mut converted = HashMap::new();
    let mut parts = Vec::new();
    for model in models {
        let mesh = model.mesh;
        let label = format!("object \"{}\"", model.name);
        if mesh.indices.is_empty() {
            warnings.push(format!(
                "{label} has no faces (points and lines are not imported)"
            ));
            continue;
        }
        let Some(built) = raw_mesh(&mesh).build(&label, &mut warnings)? else {
            continue;
        };
        let material = match mesh
            .material_id
            .and_then(|id| materials.get(id).map(|m| (id, m)))
        {
            None => Material::default(),
            Some((id, m)) => converted
                .entry(id)
                .or_insert_with(|| {
                    convert_material(m, &material_dirs, &mut textures, &mut warnings, budget)
                })
                .clone(),
        };
        parts.push(Part {
            mesh: built,
            material,
        });
    }
    Ok(Model { parts, warnings })
}

/// What `tobj` read of an OBJ file and its material libraries.
struct Parsed {
    /// The objects/groups, split by material.
    models: Vec<tobj::Model>,
    /// The materials (none if a library failed, which was warned about).
    materials: Vec<tobj::Material>,
    /// Material name → folder of its MTL file, for texture paths.
    material_dirs: HashMap<String, PathBuf>,
    /// Problems worked around so far.
    warnings: Vec<String>,
}

/// Repairs the text, checks and counts it in a first pass (charging triangles and vertices to
/// `budget`), and parses it and its material libraries (relative to `path`'s folder) with
/// `tobj`.
fn parse(path: &Path, bytes: &[u8], budget: &mut Budget) -> Result<Parsed, ImportFailure> {
    let invalid = |message| ImportFailure::Invalid {
        format: "OBJ",
        message,
    };
    let base = path.parent().unwrap_or_else(|| Path::new(""));
    let material_dirs = RefCell::new(HashMap::<String, PathBuf>::new());
    let warnings = RefCell::new(Vec::<String>::new());
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (text, note) = normalize_text(bytes, Kind::Obj);
    if let Some(note) = note {
        warnings.borrow_mut().push(format!("the OBJ file {note}"));
    }
    let counts = prescan(&text).map_err(invalid)?;
    budget.charge_mesh(counts.triangles, counts.vertices)?;
    let mut cursor = Cursor::new(text.as_bytes());
    let (models, materials) = tobj::load_obj_buf(&mut cursor, &options, |library: &Path| {
        load_library(&base.join(library), &material_dirs, &warnings)
    })
    .map_err(|e| invalid(describe_error(&e, &text, stopped_at(&cursor), Kind::Obj)))?;
    Ok(Parsed {
        models,
        // A failed library was warned about; the materials that did load are kept by tobj only
        // when all succeeded.
        materials: materials.unwrap_or_default(),
        material_dirs: material_dirs.into_inner(),
        warnings: warnings.into_inner(),
    })
}

/// Reads the material library at `full` for `tobj`, noting its materials' folder in
/// `material_dirs`; a library that cannot be loaded is a warning (default materials are used).
fn load_library(
    full: &Path,
    material_dirs: &RefCell<HashMap<String, PathBuf>>,
    warnings: &RefCell<Vec<String>>,
) -> tobj::MTLLoadResult {
    let loaded = input_file::read(full, FileKind::Model)
        .map_err(|e| e.to_string())
        .and_then(|bytes| {
            let (text, note) = normalize_text(&bytes, Kind::Mtl);
            if let Some(note) = note {
                warnings
                    .borrow_mut()
                    .push(format!("material library \"{}\" {note}", full.display()));
            }
            let text = drop_non_finite(&text, full, &mut warnings.borrow_mut());
            let mut cursor = Cursor::new(text.as_bytes());
            tobj::load_mtl_buf(&mut cursor)
                .map_err(|e| describe_error(&e, &text, stopped_at(&cursor), Kind::Mtl))
        });
    match loaded {
        Ok((materials, names)) => {
            let dir = full.parent().map(Path::to_path_buf).unwrap_or_default();
            let mut dirs = material_dirs.borrow_mut();
            for material in &materials {
                dirs.insert(material.name.clone(), dir.clone());
            }
            Ok((materials, names))
        }
        Err(error) => {
            warnings.borrow_mut().push(format!(
                "material library \"{}\" cannot be loaded ({error}); default materials are used",
                full.display()
            ));
            Err(tobj::LoadError::OpenFileFailed)
        }
    }
}

/// The mesh of a `tobj` mesh: texture coordinates flipped to v = 0 at the top, colours opaque.
fn raw_mesh(mesh: &tobj::Mesh) -> RawMesh {
    RawMesh {
        positions: mesh
            .positions
            .chunks_exact(3)
            .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
            .collect(),
        normals: (!mesh.normals.is_empty()).then(|| {
            mesh.normals
                .chunks_exact(3)
                .map(|n| DVec3::new(n[0].into(), n[1].into(), n[2].into()))
                .collect()
        }),
        uvs: (!mesh.texcoords.is_empty()).then(|| {
            mesh.texcoords
                .chunks_exact(2)
                .map(|t| DVec2::new(t[0].into(), 1.0 - f64::from(t[1])))
                .collect()
        }),
        colors: (!mesh.vertex_color.is_empty()).then(|| {
            mesh.vertex_color
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2], 1.0])
                .collect()
        }),
        triangles: mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    }
}

/// Which kind of file [`normalize_text`] prepares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Obj,
    Mtl,
}

/// Text for `tobj`, which wants UTF-8 and panics or fails on a few things that do not touch the
/// geometry: UTF-16 with a byte-order mark is converted; other bytes that are not UTF-8 are
/// replaced (with a note saying so); leading blanks are trimmed; `usemtl`/`newmtl` without a name
/// get the name `(unnamed)`; MTL colours with fewer than three components (`Ks 0`, which the
/// MTL format allows and on which `tobj` panics) are completed (g = b = r).
fn normalize_text(bytes: &[u8], kind: Kind) -> (String, Option<&'static str>) {
    let utf16 = |big_endian: bool| {
        let units = bytes[2..].chunks_exact(2).map(|pair| {
            let pair = [pair[0], pair[1]];
            if big_endian {
                u16::from_be_bytes(pair)
            } else {
                u16::from_le_bytes(pair)
            }
        });
        char::decode_utf16(units)
            .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
            .collect::<String>()
    };
    let (text, note) = if bytes.starts_with(&[0xfe, 0xff]) {
        (utf16(true), Some("is UTF-16; it was converted"))
    } else if bytes.starts_with(&[0xff, 0xfe]) {
        (utf16(false), Some("is UTF-16; it was converted"))
    } else {
        let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        match std::str::from_utf8(bytes) {
            Ok(text) => (text.to_owned(), None),
            Err(_) => (
                String::from_utf8_lossy(bytes).into_owned(),
                Some("is not UTF-8; its undecodable bytes were replaced"),
            ),
        }
    };
    let name_keyword = match kind {
        Kind::Obj => "usemtl",
        Kind::Mtl => "newmtl",
    };
    let mut out = String::with_capacity(text.len() + 16);
    for line in text.lines() {
        let line = line.trim_start();
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        if keyword == name_keyword && line[keyword.len()..].trim().is_empty() {
            out.push_str(keyword);
            out.push_str(" (unnamed)");
        } else if kind == Kind::Mtl && matches!(keyword, "Ka" | "Kd" | "Ks" | "Ke") {
            let values: Vec<&str> = words.collect();
            match values.as_slice() {
                [] => {}
                [r] => out.push_str(&format!("{keyword} {r} {r} {r}")),
                [r, g] => out.push_str(&format!("{keyword} {r} {g} {g}")),
                _ => out.push_str(line),
            }
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    (out, note)
}

/// The MTL keys the importer reads a number from ([`convert_material`]) and what a material
/// without the key gets: `Kd` the default colour (white), `d` the default opacity (1).
const READ_NUMBER_KEYS: [(&str, &str); 2] = [
    ("Kd", "the default colour"),
    ("d", "the default opacity (1)"),
];

/// The MTL `text` of the library `file` without the statements of [`READ_NUMBER_KEYS`] that
/// hold a number `tobj` would read as NaN or ±∞ (`Kd nan nan nan`, `d inf`): each is blanked,
/// so that its material gets the default, and warned about with the file and the line
/// (`normalize_text` keeps the lines where they were). A NaN colour would otherwise draw the
/// model black, or dim one channel, without a word.
fn drop_non_finite(text: &str, file: &Path, warnings: &mut Vec<String>) -> String {
    let mut out = String::with_capacity(text.len());
    for (index, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        let bad = READ_NUMBER_KEYS
            .iter()
            .find(|(key, _)| *key == keyword)
            .and_then(|(key, default)| {
                // tobj reads f32; a word it cannot parse is its own error, left to it.
                let value = words.find(|word| word.parse::<f32>().is_ok_and(|v| !v.is_finite()))?;
                Some((key, value, default))
            });
        if let Some((key, value, default)) = bad {
            warnings.push(format!(
                "{}:{}: {key} has a non-finite value ({value}); using {default}",
                file.display(),
                index + 1
            ));
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

/// What the first pass over an OBJ file counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Counts {
    /// Triangles the faces give after fan triangulation.
    triangles: u64,
    /// Vertex positions (`v` statements).
    vertices: u64,
}

/// The first pass over an OBJ text: counts triangles and vertices, and rejects face, line and
/// point statements with indices on which `tobj`'s arithmetic overflows: 0 (OBJ counts from 1),
/// relative indices reaching before the first element, and indices beyond the 32-bit range.
fn prescan(text: &str) -> Result<Counts, String> {
    let mut counts = [0i64; 3]; // v, vt, vn so far
    let mut triangles = 0u64;
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let keyword = words.next();
        match keyword {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f" | "l" | "p") => {
                let mut corners = 0u64;
                for word in words {
                    corners += 1;
                    for (slot, part) in word.split('/').enumerate() {
                        let Some(&count) = counts.get(slot) else {
                            return Err(format!(
                                "line {}: {} has more than three indices",
                                number + 1,
                                quote(word)
                            ));
                        };
                        // Unparsable numbers are left to tobj, which reports them.
                        let Ok(index) = part.parse::<i64>() else {
                            continue;
                        };
                        if index == 0 || index < -count || index > i64::from(u32::MAX) {
                            return Err(format!(
                                "line {}: index {index} in {} is out of range",
                                number + 1,
                                quote(word)
                            ));
                        }
                    }
                }
                if keyword == Some("f") {
                    triangles += corners.saturating_sub(2);
                }
            }
            _ => {}
        }
    }
    Ok(Counts {
        triangles,
        vertices: counts[0].unsigned_abs(),
    })
}

/// How far `tobj` read before it stopped, in bytes.
fn stopped_at(cursor: &Cursor<&[u8]>) -> usize {
    usize::try_from(cursor.position()).unwrap_or(usize::MAX)
}

/// A `tobj` error on the OBJ or MTL `text` in words, with its line: the last line `tobj` read
/// (it stops on the line it rejects) or, for an index out of range, the first face that refers
/// to an element not defined before it.
fn describe_error(error: &tobj::LoadError, text: &str, consumed: usize, kind: Kind) -> String {
    use tobj::LoadError as E;
    let what = match (error, kind) {
        (E::PositionParseError, _) => "a vertex position (v) needs three numbers",
        (E::ScalingByZeroError, _) => "a vertex has the weight w = 0",
        (E::ColorParseError, _) => "a vertex colour needs three numbers after the position",
        (E::NormalParseError, _) => "a normal (vn) needs three numbers",
        (E::TexcoordParseError, _) => "a texture coordinate (vt) needs two numbers",
        (E::FaceParseError, _) => "a face or line has an index that is not a number",
        (E::MaterialParseError, Kind::Obj) => "usemtl needs a material name",
        (E::MaterialParseError, Kind::Mtl) => {
            "a material statement has a missing or malformed value"
        }
        (E::InvalidObjectName, _) => "newmtl needs a material name",
        (E::FaceVertexOutOfBounds, _) => "a face refers to a vertex that does not exist",
        (E::FaceTexCoordOutOfBounds, _) => {
            "a face refers to a texture coordinate that does not exist"
        }
        (E::FaceNormalOutOfBounds, _) => "a face refers to a normal that does not exist",
        (E::FaceColorOutOfBounds, _) => "some vertices have colours and others do not",
        (E::InvalidPolygon, _) => "a face has fewer than three vertices",
        (E::UnrecognizedCharacter, _) => "the file has a character the parser does not accept",
        _ => "the parser failed",
    };
    let slot = match error {
        E::FaceVertexOutOfBounds => Some(0),
        E::FaceTexCoordOutOfBounds => Some(1),
        E::FaceNormalOutOfBounds => Some(2),
        _ => None,
    };
    let number = slot
        .and_then(|slot| first_undefined_reference(text, slot))
        .unwrap_or_else(|| line_of_offset(text, consumed));
    match text.lines().nth(number.saturating_sub(1)) {
        Some(line) if number > 0 => format!("line {number} ({}): {what}", quote(line)),
        _ => what.to_owned(),
    }
}

/// The line (from 1) that byte `offset` of `text` ends; 0 for offset 0.
fn line_of_offset(text: &str, offset: usize) -> usize {
    let read = text.as_bytes().get(..offset).unwrap_or(text.as_bytes());
    let newlines = read.iter().filter(|&&b| b == b'\n').count();
    if read.is_empty() || read.ends_with(b"\n") {
        newlines
    } else {
        newlines + 1
    }
}

/// The first face line (from 1) whose index in `slot` (0: vertex, 1: texture coordinate,
/// 2: normal) refers to an element not defined before the line.
fn first_undefined_reference(text: &str, slot: usize) -> Option<usize> {
    let keyword = ["v", "vt", "vn"][slot];
    let mut defined = 0i64;
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some(word) if word == keyword => defined += 1,
            Some("f") => {
                let undefined = words.any(|word| {
                    word.split('/')
                        .nth(slot)
                        .and_then(|part| part.parse::<i64>().ok())
                        .is_some_and(|index| index > defined || index < -defined)
                });
                if undefined {
                    return Some(number + 1);
                }
            }
            _ => {}
        }
    }
    None
}

/// Our material for an MTL material.
fn convert_material(
    m: &tobj::Material,
    material_dirs: &HashMap<String, PathBuf>,
    textures: &mut TextureCache,
    warnings: &mut Vec<String>,
    budget: &mut Budget,
) -> Material {
    let [r, g, b] = m.diffuse.unwrap_or([1.0; 3]).map(|c| c.clamp(0.0, 1.0));
    let alpha = m.dissolve.unwrap_or(1.0).clamp(0.0, 1.0);
    let texture = m.diffuse_texture.as_deref().and_then(|spec| {
        let dir = material_dirs
            .get(&m.name)
            .map_or(Path::new(""), PathBuf::as_path);
        let path = texture_path(dir, spec);
        textures.file(&path, &format!("material \"{}\"", m.name), warnings, budget)
    });
    Material {
        name: m.name.clone(),
        base_color: [r, g, b, alpha],
        texture,
    }
}

/// The texture file a `map_Kd` value names: the whole value if that file exists, else the value
/// with options (`-o 0 0 0`, `-clamp on`, …) skipped, else its last word; backslashes are tried as
/// separators too.
fn texture_path(dir: &Path, spec: &str) -> PathBuf {
    let spec = spec.trim();
    let primary = if spec.starts_with('-') {
        skip_options(spec)
    } else {
        spec
    };
    let mut candidates = vec![primary.to_owned(), spec.to_owned()];
    if let Some(last) = spec.split_whitespace().next_back() {
        candidates.push(last.to_owned());
    }
    let with_slashes: Vec<String> = candidates.iter().map(|c| c.replace('\\', "/")).collect();
    candidates.extend(with_slashes);
    candidates
        .iter()
        .map(|c| dir.join(c))
        .find(|p| p.is_file())
        .unwrap_or_else(|| dir.join(primary))
}

/// The part of a `map_*` value after its options.
fn skip_options(spec: &str) -> &str {
    // Number of arguments each MTL texture option takes (most take up to three numbers).
    let mut rest = spec.trim_start();
    while let Some(option) = rest.strip_prefix('-') {
        let (name, after) = option
            .split_once(char::is_whitespace)
            .unwrap_or((option, ""));
        let max_args = match name {
            "blendu" | "blendv" | "cc" | "clamp" | "imfchan" | "texres" | "bm" | "boost" => 1,
            "mm" => 2,
            "o" | "s" | "t" => 3,
            _ => 0,
        };
        rest = after.trim_start();
        for _ in 0..max_args {
            let (word, after) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
            let is_arg = word.parse::<f64>().is_ok()
                || matches!(word, "on" | "off" | "r" | "g" | "b" | "m" | "l" | "z");
            if !is_arg || after.is_empty() {
                break;
            }
            rest = after.trim_start();
        }
    }
    rest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_normalised_for_tobj() {
        let (text, note) = normalize_text(b"  usemtl \r\nf 1 2 3", Kind::Obj);
        assert_eq!((text.as_str(), note), ("usemtl (unnamed)\nf 1 2 3\n", None));
        let (text, note) = normalize_text(b"usemtl Terraind\xe4k\n", Kind::Obj);
        assert_eq!(text, "usemtl Terraind\u{fffd}k\n");
        assert!(note.is_some());
        let (text, note) = normalize_text(b"\xfe\xff\0v\0 \x001", Kind::Obj);
        assert_eq!(text, "v 1\n");
        assert!(note.is_some());
        let (text, _) = normalize_text(b"newmtl\nKs 0\nKd 1 0.5\nKa\nKe 1 2 3", Kind::Mtl);
        assert_eq!(
            text,
            "newmtl (unnamed)\nKs 0 0 0\nKd 1 0.5 0.5\n\nKe 1 2 3\n"
        );
    }

    /// A colour or opacity tobj would read as NaN or ∞ is dropped with a warning naming the
    /// file and line, and the material gets the default colour (not black, not dimmed).
    #[test]
    fn non_finite_material_numbers_are_warned_about_and_replaced_by_the_default() {
        let text = "newmtl a\nKd nan nan nan\nd 0.5\nnewmtl b\nKd 0.2 nan 0.4\nd inf\n\
                    newmtl c\nKd 1e99 0 0\nKs nan 0 0\nnewmtl d\nKd 0.25 0.5 0.75\n";
        let mut warnings = Vec::new();
        let kept = drop_non_finite(text, Path::new("lib/model.mtl"), &mut warnings);
        assert_eq!(
            warnings,
            [
                "lib/model.mtl:2: Kd has a non-finite value (nan); using the default colour",
                "lib/model.mtl:5: Kd has a non-finite value (nan); using the default colour",
                "lib/model.mtl:6: d has a non-finite value (inf); using the default opacity (1)",
                "lib/model.mtl:8: Kd has a non-finite value (1e99); using the default colour",
            ]
        );
        let (materials, _) = tobj::load_mtl_buf(&mut Cursor::new(kept.as_bytes())).unwrap();
        let converted: Vec<[f32; 4]> = materials
            .iter()
            .map(|m| {
                let dirs = HashMap::new();
                let mut budget = Budget::default();
                convert_material(
                    m,
                    &dirs,
                    &mut TextureCache::default(),
                    &mut Vec::new(),
                    &mut budget,
                )
                .base_color
            })
            .collect();
        assert_eq!(
            converted,
            [
                [1.0, 1.0, 1.0, 0.5],
                [1.0, 1.0, 1.0, 1.0],
                [1.0, 1.0, 1.0, 1.0],
                [0.25, 0.5, 0.75, 1.0],
            ]
        );
    }

    #[test]
    fn indices_tobj_would_overflow_on_are_rejected() {
        let counts = prescan("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -3\n").unwrap();
        assert_eq!(
            counts,
            Counts {
                triangles: 2,
                vertices: 3
            }
        );
        assert!(prescan("v 0 0 0\nf 0 1 1\n").is_err());
        assert!(prescan("v 0 0 0\nf -2 1 1\n").is_err());
        assert!(prescan("v 0 0 0\nf 1/0 1 1\n").is_err());
        assert!(prescan("v 0 0 0\nf 1/1/1/1 1 1\n").is_err());
        assert!(prescan("f 99999999999 1 1\n").is_err());
        // Unparsable numbers are left to tobj.
        assert!(prescan("f a b c\n").is_ok());
        // Polygons are fan-triangulated; lines and points give no triangles.
        assert_eq!(prescan("f 1 2 3 4 5\nl 1 2\np 1\n").unwrap().triangles, 3);
    }

    #[test]
    fn errors_name_the_line_tobj_stopped_on() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n";
        let (_, consumed) = tobj_error(text);
        let message = describe_error(
            &tobj::LoadError::PositionParseError,
            text,
            consumed,
            Kind::Obj,
        );
        assert_eq!(
            message,
            "line 3 (\"v 0 x 0\"): a vertex position (v) needs three numbers"
        );
        assert_eq!(line_of_offset("a\nb", 3), 2);
        assert_eq!(line_of_offset("a\nb\n", 4), 2);
        assert_eq!(line_of_offset("a", 0), 0);
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n";
        assert_eq!(first_undefined_reference(text, 0), Some(5));
        assert_eq!(first_undefined_reference(text, 2), None);
    }

    /// Runs tobj on `text`, expecting an error; returns it and how far tobj read.
    fn tobj_error(text: &str) -> (tobj::LoadError, usize) {
        let mut cursor = Cursor::new(text.as_bytes());
        let options = tobj::LoadOptions::default();
        let error = tobj::load_obj_buf(&mut cursor, &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .unwrap_err();
        (error, stopped_at(&cursor))
    }

    #[test]
    fn texture_options_are_skipped() {
        assert_eq!(skip_options("-s 1 1 1 wood.png"), "wood.png");
        assert_eq!(skip_options("-clamp on -mm 0 1 my file.jpg"), "my file.jpg");
        assert_eq!(skip_options("-o 0.5 wood.png"), "wood.png");
        assert_eq!(skip_options("plain.png"), "plain.png");
    }

    #[test]
    fn missing_texture_paths_keep_the_named_file() {
        let path = texture_path(Path::new("/nonexistent"), "-s 2 2 1 tex.png");
        assert_eq!(path, Path::new("/nonexistent/tex.png"));
        let path = texture_path(Path::new("/nonexistent"), "tex ture.png");
        assert_eq!(path, Path::new("/nonexistent/tex ture.png"));
    }
}
