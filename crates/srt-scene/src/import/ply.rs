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
//!
//! The counts the header declares are checked before the payload is read (vertices and faces
//! against the scene's budget, every element against the file's size), and the parser's errors
//! are put into words with the line they give (for ASCII files).

use std::io::{BufReader, Cursor};
use std::path::Path;
use std::sync::Arc;

use glam::{DVec2, DVec3};
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{Encoding, Header, Property, PropertyAccess};

use super::texture::TextureCache;
use super::{ImportFailure, Model, RawMesh, fan};
use crate::limits::{Budget, MAX_SCENE_TRIANGLES, OverBudget};
use crate::mesh::{Material, Part, Texture};
use crate::message::quote;

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

/// The `ImportFailure::Invalid` of a PLY file saying `message`.
fn invalid(message: String) -> ImportFailure {
    ImportFailure::Invalid {
        format: "PLY",
        message,
    }
}

/// Loads a `.ply` file: reads and checks the header, reads the vertex and face elements, and
/// builds one part from them.
pub(super) fn load(
    path: &Path,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportFailure> {
    let mut warnings = Vec::new();
    let file_bytes = bytes.len();
    let bytes = repair_header(bytes, &mut warnings);
    let mut reader = Reader::new(BufReader::new(Cursor::new(bytes)));
    let header = read_header(&mut reader, file_bytes, budget)?;
    let Elements { vertices, faces } = read_elements(&mut reader, &header)?;
    let vertices = vertices.ok_or_else(|| invalid("the file has no vertex element".to_owned()))?;
    let Some(faces) = faces else {
        warnings.push("the file has no face element (a point cloud)".to_owned());
        return Ok(Model {
            parts: Vec::new(),
            warnings,
        });
    };
    let triangles = triangulate(&faces, budget, &mut warnings)?;
    let Some(mesh) =
        vertex_mesh(&vertices, triangles).build("the vertex/face data", &mut warnings)?
    else {
        warnings.push("the faces give no triangles".to_owned());
        return Ok(Model {
            parts: Vec::new(),
            warnings,
        });
    };
    let material = Material {
        texture: texture_file(path, &header, budget, &mut warnings),
        ..Material::default()
    };
    Ok(Model {
        parts: vec![Part { mesh, material }],
        warnings,
    })
}

/// The file's reader, positioned after the header.
type PlyReader = Reader<BufReader<Cursor<Vec<u8>>>>;

/// Reads the header and checks the counts it declares before any payload is read: vertices and
/// faces against the scene's budget (charged with the one part), every element against the
/// file's `file_bytes`.
fn read_header(
    reader: &mut PlyReader,
    file_bytes: usize,
    budget: &mut Budget,
) -> Result<Header, ImportFailure> {
    let header = Parser::<Vertex>::new()
        .read_header(reader)
        .map_err(|e| invalid(describe(&e, true)))?;
    if let Some(vertex) = header.elements.get("vertex") {
        budget.charge_vertices(vertex.count as u64)?;
    }
    if let Some(face) = header.elements.get("face")
        && face.count > MAX_SCENE_TRIANGLES
    {
        return Err(OverBudget {
            resource: "faces",
            needed: face.count as u64,
            used: 0,
            max: MAX_SCENE_TRIANGLES as u64,
        }
        .into());
    }
    for (name, element) in &header.elements {
        // Every element takes at least one byte (a binary one with no properties takes none,
        // and is useless).
        if element.count > file_bytes {
            return Err(invalid(format!(
                "element \"{name}\" declares {} entries, more than the file's {file_bytes} bytes can hold",
                element.count
            )));
        }
    }
    budget.charge_parts(1)?;
    Ok(header)
}

/// The elements of a PLY file that are read (`None`: the file has none).
struct Elements {
    /// The first `vertex` element.
    vertices: Option<Vec<Vertex>>,
    /// The first `face` element.
    faces: Option<Vec<Face>>,
}

/// Reads the elements in the header's order up to the first `vertex` and `face` ones (the
/// others are skipped over).
fn read_elements(reader: &mut PlyReader, header: &Header) -> Result<Elements, ImportFailure> {
    let ascii = header.encoding == Encoding::Ascii;
    let mut vertices = None;
    let mut faces = None;
    for (name, element) in &header.elements {
        if vertices.is_some() && faces.is_some() {
            break;
        }
        let context =
            |e: ParseError| invalid(format!("element \"{name}\": {}", describe(&e, ascii)));
        match name.as_str() {
            "vertex" if vertices.is_none() => {
                vertices = Some(
                    Parser::<Vertex>::new()
                        .read_payload_for_element(reader, element, header)
                        .map_err(context)?,
                );
            }
            "face" if faces.is_none() => {
                faces = Some(
                    Parser::<Face>::new()
                        .read_payload_for_element(reader, element, header)
                        .map_err(context)?,
                );
            }
            _ => {
                Parser::<Skipped>::new()
                    .read_payload_for_element(reader, element, header)
                    .map_err(context)?;
            }
        }
    }
    Ok(Elements { vertices, faces })
}

/// The faces' polygons fan-triangulated, charged to the budget; faces with fewer than three
/// vertices are skipped with a warning.
fn triangulate(
    faces: &[Face],
    budget: &mut Budget,
    warnings: &mut Vec<String>,
) -> Result<Vec<[u32; 3]>, ImportFailure> {
    let mut triangle_count = 0u64;
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
        triangle_count += face.indices.len().saturating_sub(2) as u64;
    }
    budget.charge_mesh(triangle_count, 0)?;
    let mut triangles = Vec::with_capacity(usize::try_from(triangle_count).unwrap_or(0));
    for face in faces {
        fan(&face.indices, &mut triangles);
    }
    if short_faces > 0 {
        warnings.push(format!(
            "{short_faces} faces with fewer than 3 vertices are ignored"
        ));
    }
    Ok(triangles)
}

/// The mesh of `vertices` and `triangles`: normals, texture coordinates and colours where every
/// vertex has them.
fn vertex_mesh(vertices: &[Vertex], triangles: Vec<[u32; 3]>) -> RawMesh {
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
    RawMesh {
        positions: vertices
            .iter()
            .map(|v| DVec3::from_array(v.position))
            .collect(),
        normals,
        uvs,
        colors,
        triangles,
    }
}

/// The texture a MeshLab-style `comment TextureFile NAME` header line names (relative to the
/// file's folder); `None`, with a warning if it cannot be loaded.
fn texture_file(
    path: &Path,
    header: &Header,
    budget: &mut Budget,
    warnings: &mut Vec<String>,
) -> Option<Arc<Texture>> {
    let name = header
        .comments
        .iter()
        .find_map(|c| c.trim().strip_prefix("TextureFile").map(str::trim))
        .filter(|name| !name.is_empty())?;
    let dir = path.parent().unwrap_or_else(|| Path::new(""));
    TextureCache::default().file(&dir.join(name), "the TextureFile comment", warnings, budget)
}

/// A `ply-rs` parse error in words, on one line: "line N: " (when `with_line` and the parser
/// knows it) and what is wrong, without the Rust debug output its messages carry.
fn describe(error: &ParseError, with_line: bool) -> String {
    let text = error.to_string();
    let message = error
        .line()
        .and_then(|line| text.strip_prefix(&format!("Line {line}: ")))
        .unwrap_or(&text);
    let words = in_words(message);
    match error.line() {
        Some(line) if with_line => format!("line {line}: {words}"),
        _ => words,
    }
}

/// The (possibly multi-line) message of a `ply-rs` error in words.
fn in_words(message: &str) -> String {
    // The parser appends details as "\tName: value" lines; values are quoted with '…'.
    let detail = |name: &str| {
        message.lines().find_map(|line| {
            let value = line.trim().strip_prefix(name)?.trim();
            Some(quote(value.trim_end_matches(',').trim().trim_matches('\'')))
        })
    };
    let first = message.lines().next().unwrap_or("").trim();
    if let Some(value) = detail("Value:") {
        format!("{value} is not a number of the type the header declares")
    } else if message.contains("but found nothing") {
        "a data line has fewer values than the header declares".to_owned()
    } else if message.contains("list elements, but found only") {
        "a list has fewer values than its count says".to_owned()
    } else if message.contains("Couldn't parse element at index") {
        "a list value is not a number of the declared type".to_owned()
    } else if first.starts_with("Expected magic number") {
        "the file does not start with \"ply\"".to_owned()
    } else if first.starts_with("Unexpected 'ply'") {
        "\"ply\" appears again inside the header".to_owned()
    } else if first.starts_with("Found contradicting format") {
        "the header has two different format lines".to_owned()
    } else if first.starts_with("Property") && first.ends_with("found without preceding element.") {
        "a property is declared before any element".to_owned()
    } else if first.starts_with("Couldn't parse line") {
        let line = detail("String:").unwrap_or_default();
        format!("{line} is not a PLY header statement")
    } else if message.contains("Couldn't parse element line") {
        let line = detail("String:").unwrap_or_default();
        format!("the data line {line} is not a list of numbers")
    } else if first.starts_with("Couldn't read element line") {
        let line = detail("String:").unwrap_or_default();
        format!("the data line {line} does not match the header")
    } else if let Some(rest) = first.strip_prefix("PLY property '") {
        let name = rest.split('\'').next().unwrap_or_default();
        format!(
            "property {} has a type this importer cannot read",
            quote(name)
        )
    } else {
        without_debug(first)
    }
}

/// `text` with every `Name { … }` or `{ … }` group (Rust debug output) replaced by "…".
fn without_debug(text: &str) -> String {
    let mut out = String::new();
    let mut depth = 0usize;
    for c in text.chars() {
        match c {
            '{' => {
                if depth == 0 {
                    // Drop the type name before the brace.
                    let kept = out
                        .trim_end()
                        .rsplit_once([' ', '\'', '('])
                        .map_or(0, |(head, _)| head.len() + 1);
                    out.truncate(kept);
                    out.push('…');
                }
                depth += 1;
            }
            '}' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out.trim().to_owned()
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

    #[test]
    fn parser_messages_lose_their_debug_output() {
        assert_eq!(
            in_words(
                "Property 'PropertyDef { name: \"x\", data_type: Scalar(Float) }' found without \
                 preceding element.\n\tString: 'property float x'"
            ),
            "a property is declared before any element"
        );
        assert_eq!(
            in_words(
                "Couldn't read element line.\n\tString: '1 2 x\n'\n\tError: Parse error.\n\t\
                 Value: 'x'\n\tError: ParseFloatError { kind: Invalid }, "
            ),
            "\"x\" is not a number of the type the header declares"
        );
        assert_eq!(
            without_debug("bad PropertyDef { name: \"x\" } here"),
            "bad … here"
        );
    }
}
