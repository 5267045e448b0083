//! PLY (Stanford polygon files), ASCII and binary of either byte order, parsed by `ply-rs-bw`.
//!
//! Read: the `vertex` element's `x y z`, normals `nx ny nz`, texture coordinates (`s t`, `u v` or
//! `texture_u texture_v`; flipped to v = 0 at the top) and colours (`red green blue [alpha]`, also
//! with a `diffuse_` prefix: integer types are scaled by their maximum, e.g. uchar / 255, float
//! types taken as they are); the `face` element's `vertex_indices` (or `vertex_index`) polygons,
//! fan-triangulated. A MeshLab-style `comment TextureFile name.png` header line gives the texture.
//! Everything else (edges, per-face colours, materials…) is ignored. One part per file. Header
//! lines that are not PLY statements (free text some exporters write) are read as comments, with
//! a warning.

use std::io::{BufReader, Cursor};
use std::path::Path;

use glam::{DVec2, DVec3};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{Property, PropertyAccess};

use super::texture::TextureCache;
use super::{ImportFailure, Model, RawMesh, fan, read_file};
use crate::mesh::{Material, Part};

/// One vertex as read.
#[derive(Debug, Default)]
struct Vertex {
    position: [f64; 3],
    normal: [Option<f64>; 3],
    uv: [Option<f64>; 2],
    color: [Option<f64>; 4],
}

/// A scalar property as `f64`, with the scale that maps its type's range to [0, 1] for colours.
fn scalar(property: &Property) -> Option<(f64, f64)> {
    Some(match *property {
        Property::Char(v) => (f64::from(v), f64::from(i8::MAX)),
        Property::UChar(v) => (f64::from(v), f64::from(u8::MAX)),
        Property::Short(v) => (f64::from(v), f64::from(i16::MAX)),
        Property::UShort(v) => (f64::from(v), f64::from(u16::MAX)),
        // 32-bit integer colours are rare; treat them like 8-bit ones (the usual intent).
        Property::Int(v) => (f64::from(v), f64::from(u8::MAX)),
        Property::UInt(v) => (f64::from(v), f64::from(u8::MAX)),
        Property::Float(v) => (f64::from(v), 1.0),
        Property::Double(v) => (v, 1.0),
        _ => return None,
    })
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Self::default()
    }

    fn set_property(
        &mut self,
        name: &str,
        property: Property,
    ) -> ply_rs_bw::ply::PropertyAccessResult {
        use ply_rs_bw::ply::PropertyAccessResult::{Ignored, Set};
        let Some((value, scale)) = scalar(&property) else {
            return Ignored;
        };
        let name = name.strip_prefix("diffuse_").unwrap_or(name);
        match name {
            "x" => self.position[0] = value,
            "y" => self.position[1] = value,
            "z" => self.position[2] = value,
            "nx" => self.normal[0] = Some(value),
            "ny" => self.normal[1] = Some(value),
            "nz" => self.normal[2] = Some(value),
            "s" | "u" | "texture_u" | "texture_s" => self.uv[0] = Some(value),
            "t" | "v" | "texture_v" | "texture_t" => self.uv[1] = Some(value),
            "red" | "r" => self.color[0] = Some(value / scale),
            "green" | "g" => self.color[1] = Some(value / scale),
            "blue" | "b" => self.color[2] = Some(value / scale),
            "alpha" | "a" => self.color[3] = Some(value / scale),
            _ => return Ignored,
        }
        Set
    }
}

/// One face as read.
#[derive(Debug, Default)]
struct Face {
    indices: Vec<u32>,
    /// The index list had negative or non-integer values.
    negative: bool,
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Self::default()
    }

    fn set_property(
        &mut self,
        name: &str,
        property: Property,
    ) -> ply_rs_bw::ply::PropertyAccessResult {
        use ply_rs_bw::ply::PropertyAccessResult::{Ignored, Set};
        if name != "vertex_indices" && name != "vertex_index" {
            return Ignored;
        }
        match property.to_u32_list() {
            Some(indices) => self.indices = indices,
            None => self.negative = true,
        }
        Set
    }
}

/// An element we skip over.
#[derive(Debug)]
struct Skipped;

impl PropertyAccess for Skipped {
    fn new() -> Self {
        Self
    }
}

/// Turns header lines that start with no PLY keyword (free text some exporters write, e.g.
/// Blender 2.4's "Created by …") into comments, with a warning; the parser rejects them.
fn repair_header(bytes: Vec<u8>, warnings: &mut Vec<String>) -> Vec<u8> {
    const KEYWORDS: [&str; 7] = [
        "ply",
        "format",
        "comment",
        "obj_info",
        "element",
        "property",
        "end_header",
    ];
    let Some(end) = bytes.windows(10).position(|w| w == b"end_header") else {
        return bytes;
    };
    let Ok(header) = std::str::from_utf8(&bytes[..end]) else {
        return bytes;
    };
    let mut repaired = String::with_capacity(end + 64);
    let mut fixed = Vec::new();
    for (number, line) in header.split_inclusive('\n').enumerate() {
        let keyword = line.split_whitespace().next();
        match keyword {
            Some(word) if !KEYWORDS.contains(&word) => {
                repaired.push_str("comment ");
                fixed.push(number + 1);
            }
            None if number > 0 => {
                fixed.push(number + 1);
                continue;
            }
            _ => {}
        }
        repaired.push_str(line);
    }
    if fixed.is_empty() {
        return bytes;
    }
    warnings.push(format!(
        "header line(s) {} are not PLY header statements; they are read as comments",
        fixed
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    ));
    let mut out = repaired.into_bytes();
    out.extend_from_slice(&bytes[end..]);
    out
}

/// Loads a `.ply` file.
pub(super) fn load(path: &Path) -> Result<Model, ImportFailure> {
    let mut warnings = Vec::new();
    let bytes = repair_header(read_file(path)?, &mut warnings);
    let invalid = |message: String| ImportFailure::Invalid {
        format: "PLY",
        message,
    };
    let mut reader = Reader::new(BufReader::new(Cursor::new(bytes)));
    let header = Parser::<Vertex>::new()
        .read_header(&mut reader)
        .map_err(|e| invalid(e.to_string()))?;
    let mut vertices = None;
    let mut faces = None;
    for (name, element) in &header.elements {
        if vertices.is_some() && faces.is_some() {
            break;
        }
        let context =
            |e: ply_rs_bw::parser::ParseError| invalid(format!("element \"{name}\": {e}"));
        match name.as_str() {
            "vertex" if vertices.is_none() => {
                vertices = Some(
                    Parser::<Vertex>::new()
                        .read_payload_for_element(&mut reader, element, &header)
                        .map_err(context)?,
                );
            }
            "face" if faces.is_none() => {
                faces = Some(
                    Parser::<Face>::new()
                        .read_payload_for_element(&mut reader, element, &header)
                        .map_err(context)?,
                );
            }
            _ => {
                Parser::<Skipped>::new()
                    .read_payload_for_element(&mut reader, element, &header)
                    .map_err(context)?;
            }
        }
    }
    let vertices = vertices.ok_or_else(|| invalid("the file has no vertex element".to_owned()))?;
    let Some(faces) = faces else {
        warnings.push("the file has no face element (a point cloud)".to_owned());
        return Ok(Model {
            parts: Vec::new(),
            warnings,
        });
    };

    let mut triangles = Vec::with_capacity(faces.len());
    let mut short_faces = 0usize;
    for (i, face) in faces.iter().enumerate() {
        if face.negative {
            return Err(invalid(format!(
                "face {i} has vertex indices that are negative or not integers"
            )));
        }
        if face.indices.len() < 3 {
            short_faces += 1;
        }
        fan(&face.indices, &mut triangles);
    }
    if short_faces > 0 {
        warnings.push(format!(
            "{short_faces} faces with fewer than 3 vertices are ignored"
        ));
    }
    let all = |f: &dyn Fn(&Vertex) -> bool| !vertices.is_empty() && vertices.iter().all(f);
    let normals = all(&|v| v.normal.iter().all(Option::is_some)).then(|| {
        vertices
            .iter()
            .map(|v| DVec3::from_array(v.normal.map(|c| c.unwrap_or(0.0))))
            .collect()
    });
    let uvs = all(&|v| v.uv.iter().all(Option::is_some)).then(|| {
        vertices
            .iter()
            .map(|v| DVec2::new(v.uv[0].unwrap_or(0.0), 1.0 - v.uv[1].unwrap_or(0.0)))
            .collect()
    });
    #[expect(
        clippy::cast_possible_truncation,
        reason = "colour components in [0, 1]"
    )]
    let colors = all(&|v| v.color[..3].iter().all(Option::is_some)).then(|| {
        vertices
            .iter()
            .map(|v| v.color.map(|c| c.unwrap_or(1.0).clamp(0.0, 1.0) as f32))
            .collect()
    });
    let raw = RawMesh {
        positions: vertices
            .iter()
            .map(|v| DVec3::from_array(v.position))
            .collect(),
        normals,
        uvs,
        colors,
        triangles,
    };
    let Some(mesh) = raw.build("the vertex/face data", &mut warnings)? else {
        warnings.push("the faces give no triangles".to_owned());
        return Ok(Model {
            parts: Vec::new(),
            warnings,
        });
    };
    let texture = header
        .comments
        .iter()
        .find_map(|c| c.trim().strip_prefix("TextureFile").map(str::trim))
        .filter(|name| !name.is_empty())
        .and_then(|name| {
            let dir = path.parent().unwrap_or_else(|| Path::new(""));
            TextureCache::default().file(&dir.join(name), "the TextureFile comment", &mut warnings)
        });
    let material = Material {
        texture,
        ..Material::default()
    };
    Ok(Model {
        parts: vec![Part { mesh, material }],
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_text_header_lines_become_comments() {
        let mut warnings = Vec::new();
        let fixed = repair_header(
            b"ply\nformat ascii 1.0\nCreated by me\n\nend_header\n1 2".to_vec(),
            &mut warnings,
        );
        assert_eq!(
            fixed,
            b"ply\nformat ascii 1.0\ncomment Created by me\nend_header\n1 2"
        );
        assert_eq!(warnings.len(), 1);
        let good = b"ply\nformat ascii 1.0\nend_header\n".to_vec();
        assert_eq!(repair_header(good.clone(), &mut warnings), good);
        assert_eq!(warnings.len(), 1);
    }
}
