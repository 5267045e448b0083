//! STL (stereolithography), ASCII and binary; facets are parsed by `stl_io`.
//!
//! ASCII or binary is decided here rather than by `stl_io` (which treats every file starting with
//! `solid ` as ASCII, although many binary exporters write that into the header): a file whose size
//! is exactly 84 + 50 × (the triangle count in its header) is binary; otherwise one that starts
//! with `solid` is ASCII; otherwise a file of at least 84 bytes is binary (truncated ones are
//! errors). ASCII keywords are case-insensitive, and every `solid … endsolid` section becomes one
//! part (`stl_io` alone stops at the first). Each facet gets its own three vertices and the
//! facet normal (flat shading); a zero or non-finite facet normal is replaced by the geometric one.

use std::fmt::Write as _;
use std::io::Cursor;
use std::path::Path;

use glam::DVec3;

use super::{ImportFailure, Model, RawMesh, read_file};
use crate::mesh::{Material, Part};

/// Size of the binary header: 80 bytes of text and the triangle count.
const HEADER: usize = 84;
/// Size of one binary facet record.
const RECORD: usize = 50;

/// Loads an `.stl` file.
pub(super) fn load(path: &Path) -> Result<Model, ImportFailure> {
    let bytes = read_file(path)?;
    let declared = bytes
        .get(80..HEADER)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let exact_binary = declared
        .and_then(|n| n.checked_mul(RECORD))
        .and_then(|n| n.checked_add(HEADER))
        .is_some_and(|size| size == bytes.len());
    let text_start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    let ascii = bytes
        .get(text_start..text_start + 5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"));
    if exact_binary || (!ascii && bytes.len() >= HEADER) {
        binary(bytes, declared.unwrap_or(0))
    } else if ascii {
        ascii_solids(&String::from_utf8_lossy(&bytes))
    } else {
        Err(invalid(format!(
            "it is neither ASCII STL (it does not start with \"solid\") nor binary STL ({} bytes, \
             shorter than the {HEADER}-byte header)",
            bytes.len()
        )))
    }
}

/// An STL format error.
fn invalid(message: String) -> ImportFailure {
    ImportFailure::Invalid {
        format: "STL",
        message,
    }
}

/// Reads a binary STL with `declared` facets.
fn binary(mut bytes: Vec<u8>, declared: usize) -> Result<Model, ImportFailure> {
    let mut warnings = Vec::new();
    let needed = declared
        .checked_mul(RECORD)
        .and_then(|n| n.checked_add(HEADER));
    match needed {
        Some(needed) if needed <= bytes.len() => {
            if needed < bytes.len() {
                warnings.push(format!(
                    "{} bytes after the {declared} facets the binary header declares are ignored",
                    bytes.len() - needed
                ));
                bytes.truncate(needed);
            }
        }
        _ => {
            return Err(invalid(format!(
                "the binary header declares {declared} facets ({} bytes), but the file has only {} bytes",
                declared.saturating_mul(RECORD).saturating_add(HEADER),
                bytes.len()
            )));
        }
    }
    // Blank the header so that `stl_io` does not take a header starting with "solid" for ASCII.
    bytes[..80].fill(0);
    let mut cursor = Cursor::new(bytes);
    let facets = stl_io::create_stl_reader(&mut cursor).map_err(|e| invalid(e.to_string()))?;
    let mut collector = Facets::default();
    for facet in facets {
        collector.push(&facet.map_err(|e| invalid(e.to_string()))?);
    }
    let mut parts = Vec::new();
    collector.finish("the binary facets", "", &mut parts, &mut warnings)?;
    Ok(Model { parts, warnings })
}

/// Reads every `solid … endsolid` section of an ASCII STL.
fn ascii_solids(text: &str) -> Result<Model, ImportFailure> {
    let mut warnings = Vec::new();
    let mut parts = Vec::new();
    let mut section: Option<(String, String)> = None; // (name, normalised text)
    let mut index = 0;
    for (number, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        let keyword = trimmed
            .split_whitespace()
            .next()
            .unwrap_or("")
            .to_ascii_lowercase();
        match (&mut section, keyword.as_str()) {
            (None, "") => {}
            (None, "solid") => {
                let name = trimmed[5..].trim().to_owned();
                section = Some((name, "solid x\n".to_owned()));
            }
            (None, _) => {
                return Err(invalid(format!(
                    "line {}: expected \"solid\", found \"{trimmed}\"",
                    number + 1
                )));
            }
            (Some(_), "endsolid") => {
                let (name, mut body) = section.take().unwrap_or_default();
                body.push_str("endsolid\n");
                parse_solid(&body, &name, index, &mut parts, &mut warnings)?;
                index += 1;
            }
            (Some((_, body)), _) => {
                let _ = writeln!(body, "{}", trimmed.to_ascii_lowercase());
            }
        }
    }
    if let Some((name, mut body)) = section {
        warnings.push(format!("solid {index} (\"{name}\") has no \"endsolid\""));
        body.push_str("endsolid\n");
        parse_solid(&body, &name, index, &mut parts, &mut warnings)?;
    }
    Ok(Model { parts, warnings })
}

/// Parses one normalised `solid x … endsolid` section into a part.
fn parse_solid(
    body: &str,
    name: &str,
    index: usize,
    parts: &mut Vec<Part>,
    warnings: &mut Vec<String>,
) -> Result<(), ImportFailure> {
    let label = format!("solid {index} (\"{name}\")");
    let mut cursor = Cursor::new(body.as_bytes());
    let facets =
        stl_io::create_stl_reader(&mut cursor).map_err(|e| invalid(format!("{label}: {e}")))?;
    let mut collector = Facets::default();
    for facet in facets {
        collector.push(&facet.map_err(|e| invalid(format!("{label}: {e}")))?);
    }
    if collector.raw.triangles.is_empty() {
        warnings.push(format!("{label} has no facets"));
        return Ok(());
    }
    collector.finish(&label, name, parts, warnings)
}

/// Facets gathered into one unshared-vertex mesh.
#[derive(Default)]
struct Facets {
    raw: RawMesh,
    normals: Vec<DVec3>,
}

impl Facets {
    fn push(&mut self, facet: &stl_io::Triangle) {
        let start = u32::try_from(self.raw.positions.len()).unwrap_or(u32::MAX);
        let normal = DVec3::new(
            facet.normal[0].into(),
            facet.normal[1].into(),
            facet.normal[2].into(),
        );
        for v in &facet.vertices {
            self.raw
                .positions
                .push(DVec3::new(v[0].into(), v[1].into(), v[2].into()));
            self.normals.push(normal);
        }
        self.raw
            .triangles
            .push([start, start.saturating_add(1), start.saturating_add(2)]);
    }

    fn finish(
        mut self,
        label: &str,
        name: &str,
        parts: &mut Vec<Part>,
        warnings: &mut Vec<String>,
    ) -> Result<(), ImportFailure> {
        self.raw.normals = Some(self.normals);
        if let Some(mesh) = self.raw.build(label, warnings)? {
            let material = Material {
                name: name.to_owned(),
                ..Material::default()
            };
            parts.push(Part { mesh, material });
        }
        Ok(())
    }
}
