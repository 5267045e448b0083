//! STL (stereolithography), ASCII and binary; binary facets are parsed by `stl_io`, ASCII ones
//! here (so that errors give the line).
//!
//! ASCII or binary is decided here rather than by `stl_io` (which treats every file starting with
//! `solid ` as ASCII, although many binary exporters write that into the header): a file whose size
//! is exactly 84 + 50 × (the triangle count in its header) is binary; otherwise one that starts
//! with `solid` and has no NUL byte (text never has one, binary headers and facets almost always
//! do) is ASCII; otherwise a file of at least 84 bytes is binary (truncated ones are errors). ASCII keywords are case-insensitive, and every `solid … endsolid` section becomes one
//! part. Each facet gets its own three vertices and the facet normal (flat shading); a zero or
//! non-finite facet normal is replaced by the geometric one. A binary file's declared facets, and
//! each ASCII facet as it is read, are charged to the budget before they are stored.

use std::io::Cursor;
use std::path::Path;

use glam::DVec3;

use super::{ImportFailure, Model, RawMesh};
use crate::limits::Budget;
use crate::mesh::{Material, Part};
use crate::message::quote;

/// Size of the binary header: 80 bytes of text and the triangle count.
const HEADER: usize = 84;
/// Size of one binary facet record.
const RECORD: usize = 50;

/// Loads an `.stl` file.
pub(super) fn load(
    _path: &Path,
    bytes: Vec<u8>,
    budget: &mut Budget,
) -> Result<Model, ImportFailure> {
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
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"))
        && !bytes.contains(&0);
    if exact_binary || (!ascii && bytes.len() >= HEADER) {
        binary(bytes, declared.unwrap_or(0), budget)
    } else if ascii {
        ascii_solids(&String::from_utf8_lossy(&bytes), budget)
    } else {
        Err(invalid(format!(
            "it is neither ASCII STL (text starting with \"solid\") nor binary STL ({} bytes, \
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
fn binary(
    mut bytes: Vec<u8>,
    declared: usize,
    budget: &mut Budget,
) -> Result<Model, ImportFailure> {
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
    let facets = declared as u64;
    budget.charge_mesh(facets, 3 * facets)?;
    budget.charge_parts(1)?;
    // Blank the header so that `stl_io` does not take a header starting with "solid" for ASCII.
    bytes[..80].fill(0);
    let mut cursor = Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| invalid(e.to_string()))?;
    let mut collector = Facets::default();
    for (index, facet) in reader.enumerate() {
        let facet = facet.map_err(|e| invalid(format!("facet {index}: {e}")))?;
        let corners = facet
            .vertices
            .map(|v| DVec3::new(v[0].into(), v[1].into(), v[2].into()));
        let [x, y, z] = facet.normal.0;
        collector.push(DVec3::new(x.into(), y.into(), z.into()), corners);
    }
    let mut parts = Vec::new();
    collector.finish("the binary facets", "", &mut parts, &mut warnings)?;
    Ok(Model { parts, warnings })
}

/// What the ASCII reader expects on the next non-blank line inside a solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Expect {
    FacetOrEnd,
    OuterLoop,
    Vertex(usize),
    EndLoop,
    EndFacet,
}

impl Expect {
    /// The expected line, for messages.
    const fn describe(self) -> &'static str {
        match self {
            Self::FacetOrEnd => "\"facet normal nx ny nz\" or \"endsolid\"",
            Self::OuterLoop => "\"outer loop\"",
            Self::Vertex(_) => "\"vertex x y z\"",
            Self::EndLoop => "\"endloop\"",
            Self::EndFacet => "\"endfacet\"",
        }
    }

    /// What comes after a line that fits `self`.
    const fn next(self) -> Self {
        match self {
            Self::FacetOrEnd => Self::OuterLoop,
            Self::OuterLoop => Self::Vertex(0),
            Self::Vertex(k) if k < 2 => Self::Vertex(k + 1),
            Self::Vertex(_) => Self::EndLoop,
            Self::EndLoop => Self::EndFacet,
            Self::EndFacet => Self::FacetOrEnd,
        }
    }
}

/// One `solid … endsolid` section being read.
struct Solid {
    name: String,
    facets: Facets,
    normal: DVec3,
    corners: [DVec3; 3],
    expect: Expect,
}

/// Reads every `solid … endsolid` section of an ASCII STL, one part each.
fn ascii_solids(text: &str, budget: &mut Budget) -> Result<Model, ImportFailure> {
    let mut warnings = Vec::new();
    let mut parts = Vec::new();
    let mut solid: Option<Solid> = None;
    let mut index = 0;
    let mut last_line = 0;
    for (number, line) in text.lines().enumerate() {
        let number = number + 1;
        last_line = number;
        let trimmed = line.trim();
        let mut words = trimmed.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let keyword = keyword.to_ascii_lowercase();
        let unexpected = |expected: &str| {
            invalid(format!(
                "line {number}: expected {expected}, found {}",
                quote(trimmed)
            ))
        };
        let Some(current) = solid.as_mut() else {
            if keyword != "solid" {
                return Err(unexpected("\"solid\""));
            }
            budget.charge_parts(1)?;
            solid = Some(Solid {
                name: trimmed[keyword.len()..].trim().to_owned(),
                facets: Facets::default(),
                normal: DVec3::ZERO,
                corners: [DVec3::ZERO; 3],
                expect: Expect::FacetOrEnd,
            });
            continue;
        };
        let expect = current.expect;
        let fits = match (expect, keyword.as_str()) {
            (Expect::FacetOrEnd, "endsolid") => {
                if let Some(done) = solid.take() {
                    done.finish(index, &mut parts, &mut warnings)?;
                }
                index += 1;
                continue;
            }
            (Expect::FacetOrEnd, "facet")
                if words
                    .next()
                    .is_some_and(|w| w.eq_ignore_ascii_case("normal")) =>
            {
                // Non-finite normals are replaced by the geometric one, not refused.
                current.normal = numbers(number, words)?;
                true
            }
            (Expect::OuterLoop, "outer") => {
                words.next().is_some_and(|w| w.eq_ignore_ascii_case("loop"))
                    && words.next().is_none()
            }
            (Expect::Vertex(k), "vertex") => {
                let corner = numbers(number, words)?;
                if !corner.is_finite() {
                    return Err(invalid(format!(
                        "line {number}: the vertex {} is not finite",
                        quote(trimmed)
                    )));
                }
                current.corners[k] = corner;
                true
            }
            (Expect::EndLoop, "endloop") => words.next().is_none(),
            (Expect::EndFacet, "endfacet") => {
                budget.charge_mesh(1, 3)?;
                current.facets.push(current.normal, current.corners);
                current.expect = Expect::FacetOrEnd;
                continue;
            }
            _ => false,
        };
        if !fits {
            return Err(unexpected(expect.describe()));
        }
        current.expect = expect.next();
    }
    if let Some(open) = solid {
        if open.expect != Expect::FacetOrEnd {
            return Err(invalid(format!(
                "line {last_line}: the file ends inside a facet (expected {})",
                open.expect.describe()
            )));
        }
        warnings.push(format!(
            "solid {index} ({}) has no \"endsolid\"",
            quote(&open.name)
        ));
        open.finish(index, &mut parts, &mut warnings)?;
    }
    Ok(Model { parts, warnings })
}

/// The three numbers that follow a keyword on line `number` (NaN and infinities parse).
fn numbers<'a>(
    number: usize,
    mut words: impl Iterator<Item = &'a str>,
) -> Result<DVec3, ImportFailure> {
    let mut values = [0.0; 3];
    for value in &mut values {
        let word = words.next().ok_or_else(|| {
            invalid(format!(
                "line {number}: three numbers expected, found fewer"
            ))
        })?;
        *value = word
            .parse::<f64>()
            .map_err(|_| invalid(format!("line {number}: {} is not a number", quote(word))))?;
    }
    if words.next().is_some() {
        return Err(invalid(format!(
            "line {number}: three numbers expected, found more"
        )));
    }
    Ok(DVec3::from_array(values))
}

impl Solid {
    /// Adds the solid's part (if it has facets) as solid number `index`.
    fn finish(
        self,
        index: usize,
        parts: &mut Vec<Part>,
        warnings: &mut Vec<String>,
    ) -> Result<(), ImportFailure> {
        let label = format!("solid {index} ({})", quote(&self.name));
        if self.facets.raw.triangles.is_empty() {
            warnings.push(format!("{label} has no facets"));
            return Ok(());
        }
        self.facets.finish(&label, &self.name, parts, warnings)
    }
}

/// Facets gathered into one unshared-vertex mesh.
#[derive(Default)]
struct Facets {
    raw: RawMesh,
    normals: Vec<DVec3>,
}

impl Facets {
    /// Adds a facet with its normal and three corners.
    fn push(&mut self, normal: DVec3, corners: [DVec3; 3]) {
        let start = u32::try_from(self.raw.positions.len()).unwrap_or(u32::MAX);
        for corner in corners {
            self.raw.positions.push(corner);
            self.normals.push(normal);
        }
        self.raw
            .triangles
            .push([start, start.saturating_add(1), start.saturating_add(2)]);
    }

    /// Adds the gathered facets as a part labelled `label`, its material named `name`.
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

#[cfg(test)]
mod tests {
    use super::*;

    fn ascii(text: &str) -> Result<Model, String> {
        ascii_solids(text, &mut Budget::new()).map_err(|e| e.to_string())
    }

    const FACET: &str = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
                         vertex 0 1 0\nendloop\nendfacet\n";

    #[test]
    fn ascii_solids_become_parts() {
        let text = format!(
            "solid a\n{FACET}endsolid a\nSOLID b\n{}ENDSOLID\n",
            FACET.repeat(2)
        );
        let model = ascii(&text).unwrap();
        assert_eq!(model.parts.len(), 2);
        assert_eq!(model.triangle_count(), 3);
        assert_eq!(model.parts[1].material.name, "b");
        let unterminated = ascii(&format!("solid a\n{FACET}")).unwrap();
        assert_eq!(unterminated.warnings.len(), 1);
    }

    #[test]
    fn ascii_errors_give_the_line_and_what_was_expected() {
        let error = ascii(&format!("solid a\n{}", FACET.replace("endloop", "endlop"))).unwrap_err();
        assert!(
            error.contains("line 7: expected \"endloop\", found \"endlop\""),
            "{error}"
        );
        let error = ascii("solid a\nfacet normal 0 0 x\n").unwrap_err();
        assert!(error.contains("line 2: \"x\" is not a number"), "{error}");
        let error = ascii("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 inf\n").unwrap_err();
        assert!(error.contains("line 4: the vertex"), "{error}");
        let error = ascii("solid a\nfacet normal 0 0 1\n").unwrap_err();
        assert!(
            error.contains("line 2: the file ends inside a facet"),
            "{error}"
        );
        let error = ascii("\n\nhello\n").unwrap_err();
        assert!(error.contains("line 3: expected \"solid\""), "{error}");
    }
}
