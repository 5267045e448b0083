//! Wavefront OBJ with MTL materials, parsed by `tobj`.
//!
//! One part per object/group and material (as `tobj` splits them). Polygons are fan-triangulated,
//! points and lines ignored. Material: diffuse colour `Kd` and dissolve `d` as the base colour,
//! diffuse texture `map_Kd` (relative to the MTL file; texture options such as `-s 1 1 1` before
//! the file name are skipped). Texture coordinates are flipped to v = 0 at the top. A missing
//! MTL file or texture is a warning. Text that `tobj` would reject or panic on for reasons that
//! do not touch the geometry is repaired first (UTF-16 or Latin-1 text, material statements
//! without a name, one-component MTL colours), and face indices on which its arithmetic would
//! overflow are rejected first.

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};

use super::texture::TextureCache;
use super::{ImportFailure, Model, RawMesh, read_file};
use crate::mesh::{Material, Part};

/// Loads an `.obj` file and the MTL files it names.
pub(super) fn load(path: &Path) -> Result<Model, ImportFailure> {
    let bytes = read_file(path)?;
    let base = path.parent().unwrap_or_else(|| Path::new(""));
    // Material name → directory of its MTL file, for texture paths.
    let material_dirs = RefCell::new(HashMap::<String, PathBuf>::new());
    let warnings = RefCell::new(Vec::<String>::new());
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (text, note) = normalize_text(&bytes, Kind::Obj);
    if let Some(note) = note {
        warnings.borrow_mut().push(format!("the OBJ file {note}"));
    }
    check_indices(&text).map_err(|message| ImportFailure::Invalid {
        format: "OBJ",
        message,
    })?;
    let result = tobj::load_obj_buf(&mut Cursor::new(text), &options, |library: &Path| {
        let full = base.join(library);
        let loaded = std::fs::read(&full)
            .map_err(|e| e.to_string())
            .and_then(|bytes| {
                let (text, note) = normalize_text(&bytes, Kind::Mtl);
                if let Some(note) = note {
                    warnings
                        .borrow_mut()
                        .push(format!("material library \"{}\" {note}", full.display()));
                }
                tobj::load_mtl_buf(&mut Cursor::new(text)).map_err(|e| e.to_string())
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
    });
    let (models, materials) = result.map_err(|e| ImportFailure::Invalid {
        format: "OBJ",
        message: e.to_string(),
    })?;
    // A failed library was warned about above; the materials that did load are kept by tobj
    // only when all succeeded.
    let materials = materials.unwrap_or_default();
    let material_dirs = material_dirs.into_inner();
    let mut warnings = warnings.into_inner();
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
        let raw = RawMesh {
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
        };
        let Some(built) = raw.build(&label, &mut warnings)? else {
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
                    convert_material(m, &material_dirs, &mut textures, &mut warnings)
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

/// Rejects face, line and point statements with indices on which `tobj`'s arithmetic overflows:
/// 0 (OBJ counts from 1), relative indices reaching before the first element, and indices beyond
/// the 32-bit range.
fn check_indices(text: &str) -> Result<(), String> {
    let mut counts = [0i64; 3]; // v, vt, vn so far
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f" | "l" | "p") => {
                for word in words {
                    for (slot, part) in word.split('/').enumerate() {
                        let Some(&count) = counts.get(slot) else {
                            return Err(format!(
                                "line {}: \"{word}\" has more than three indices",
                                number + 1
                            ));
                        };
                        // Unparsable numbers are left to tobj, which reports them.
                        let Ok(index) = part.parse::<i64>() else {
                            continue;
                        };
                        if index == 0 || index < -count || index > i64::from(u32::MAX) {
                            return Err(format!(
                                "line {}: index {index} in \"{word}\" is out of range",
                                number + 1
                            ));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Our material for an MTL material.
fn convert_material(
    m: &tobj::Material,
    material_dirs: &HashMap<String, PathBuf>,
    textures: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Material {
    let [r, g, b] = m.diffuse.unwrap_or([1.0; 3]).map(|c| c.clamp(0.0, 1.0));
    let alpha = m.dissolve.unwrap_or(1.0).clamp(0.0, 1.0);
    let texture = m.diffuse_texture.as_deref().and_then(|spec| {
        let dir = material_dirs
            .get(&m.name)
            .map_or(Path::new(""), PathBuf::as_path);
        let path = texture_path(dir, spec);
        textures.file(&path, &format!("material \"{}\"", m.name), warnings)
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

    #[test]
    fn indices_tobj_would_overflow_on_are_rejected() {
        assert!(check_indices("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -3\n").is_ok());
        assert!(check_indices("v 0 0 0\nf 0 1 1\n").is_err());
        assert!(check_indices("v 0 0 0\nf -2 1 1\n").is_err());
        assert!(check_indices("v 0 0 0\nf 1/0 1 1\n").is_err());
        assert!(check_indices("v 0 0 0\nf 1/1/1/1 1 1\n").is_err());
        assert!(check_indices("f 99999999999 1 1\n").is_err());
        // Unparsable numbers are left to tobj.
        assert!(check_indices("f a b c\n").is_ok());
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
