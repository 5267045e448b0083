//! Triangle meshes and materials in an object's rest frame S′.
//!
//! Invariants, checked by [`Mesh::new`] and kept by every method: at least one triangle, every
//! index in range, every position, normal and texture coordinate finite, normals unit length,
//! one normal and one texture coordinate per vertex.

use std::sync::Arc;

use glam::{DMat4, DVec2, DVec3};

/// Why a mesh was rejected.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MeshError {
    /// No triangles at all.
    #[error("the mesh has no triangles")]
    Empty,
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but there are only {vertices} vertices")]
    IndexOutOfRange {
        /// Index of the offending triangle.
        triangle: usize,
        /// The vertex index it uses.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// A vertex attribute is NaN or infinite.
    #[error("vertex {vertex} has a {attribute} that is not finite")]
    NonFinite {
        /// Index of the offending vertex.
        vertex: usize,
        /// Which attribute ("position", "normal", "texture coordinate").
        attribute: &'static str,
    },
    /// Attribute arrays of different lengths.
    #[error("{attribute} count {count} differs from the vertex count {vertices}")]
    AttributeCount {
        /// Which attribute.
        attribute: &'static str,
        /// How many values it has.
        count: usize,
        /// How many vertices there are.
        vertices: usize,
    },
}

/// An indexed triangle mesh at rest in its object's frame S′.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    uvs: Vec<DVec2>,
    colors: Option<Vec<[f32; 4]>>,
    triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// A mesh from positions and triangles, with area-weighted smooth normals and zero texture
    /// coordinates.
    ///
    /// # Errors
    /// [`MeshError`] if there are no triangles, an index is out of range or a position is not
    /// finite.
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                vertex,
                attribute: "position",
            });
        }
        for (triangle, t) in triangles.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertices: positions.len(),
                });
            }
        }
        let uvs = vec![DVec2::ZERO; positions.len()];
        let mut mesh = Self {
            positions,
            normals: Vec::new(),
            uvs,
            colors: None,
            triangles,
        };
        mesh.normals = mesh.smooth_normals();
        Ok(mesh)
    }

    /// Replaces the per-vertex normals (normalised here; zero-length ones are replaced by the
    /// smooth normal).
    ///
    /// # Errors
    /// [`MeshError`] on a count mismatch or a non-finite normal.
    pub fn with_normals(mut self, normals: Vec<DVec3>) -> Result<Self, MeshError> {
        self.check_count("normal", normals.len())?;
        if let Some(vertex) = normals.iter().position(|n| !n.is_finite()) {
            return Err(MeshError::NonFinite {
                vertex,
                attribute: "normal",
            });
        }
        let smooth = self.smooth_normals();
        self.normals = normals
            .into_iter()
            .zip(smooth)
            .map(|(n, fallback)| n.try_normalize().unwrap_or(fallback))
            .collect();
        Ok(self)
    }

    /// Replaces the per-vertex texture coordinates.
    ///
    /// # Errors
    /// [`MeshError`] on a count mismatch or a non-finite coordinate.
    pub fn with_uvs(mut self, uvs: Vec<DVec2>) -> Result<Self, MeshError> {
        self.check_count("texture coordinate", uvs.len())?;
        if let Some(vertex) = uvs.iter().position(|uv| !uv.is_finite()) {
            return Err(MeshError::NonFinite {
                vertex,
                attribute: "texture coordinate",
            });
        }
        self.uvs = uvs;
        Ok(self)
    }

    /// Sets per-vertex colours (RGBA, each in [0, 1], as stored in the file: sRGB-encoded).
    ///
    /// # Errors
    /// [`MeshError`] on a count mismatch or a non-finite colour.
    pub fn with_colors(mut self, colors: Vec<[f32; 4]>) -> Result<Self, MeshError> {
        self.check_count("colour", colors.len())?;
        if let Some(vertex) = colors.iter().position(|c| c.iter().any(|v| !v.is_finite())) {
            return Err(MeshError::NonFinite {
                vertex,
                attribute: "colour",
            });
        }
        self.colors = Some(colors);
        Ok(self)
    }

    fn check_count(&self, attribute: &'static str, count: usize) -> Result<(), MeshError> {
        if count == self.positions.len() {
            Ok(())
        } else {
            Err(MeshError::AttributeCount {
                attribute,
                count,
                vertices: self.positions.len(),
            })
        }
    }

    /// Area-weighted vertex normals; vertices of degenerate triangles only get +z.
    fn smooth_normals(&self) -> Vec<DVec3> {
        let mut sums = vec![DVec3::ZERO; self.positions.len()];
        for &[a, b, c] in &self.triangles {
            let [pa, pb, pc] = [a, b, c].map(|i| self.positions[i as usize]);
            let weighted = (pb - pa).cross(pc - pa);
            for i in [a, b, c] {
                sums[i as usize] += weighted;
            }
        }
        sums.into_iter()
            .map(|n| n.try_normalize().unwrap_or(DVec3::Z))
            .collect()
    }

    /// Vertex positions in S′.
    #[must_use]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Unit vertex normals in S′.
    #[must_use]
    pub fn normals(&self) -> &[DVec3] {
        &self.normals
    }

    /// Vertex texture coordinates.
    #[must_use]
    pub fn uvs(&self) -> &[DVec2] {
        &self.uvs
    }

    /// Per-vertex colours, if the model has them.
    #[must_use]
    pub fn colors(&self) -> Option<&[[f32; 4]]> {
        self.colors.as_deref()
    }

    /// Triangles as vertex index triples (counter-clockwise seen from the front).
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The three corner positions of triangle `index`.
    ///
    /// # Panics
    /// If `index` is out of range.
    #[must_use]
    pub fn triangle_positions(&self, index: usize) -> [DVec3; 3] {
        self.triangles[index].map(|i| self.positions[i as usize])
    }

    /// Whether the mesh is the closed, consistently oriented boundary of a solid with outward
    /// fronts: after welding vertices closer than 10⁻⁹ of the mesh size (rounding differences
    /// between faces that share an edge), every directed edge occurs exactly once and its reverse
    /// exactly once, and the enclosed signed volume is positive. A rare weld miss only makes a
    /// closed mesh look open, which is the safe answer.
    ///
    /// For such a mesh a triangle facing away from a viewpoint is hidden by the others from
    /// that viewpoint, so renderers may skip it (back-face culling in the rest frame, where all
    /// viewing rays start at the observer's position).
    #[must_use]
    pub fn is_closed_outward(&self) -> bool {
        let (lo, hi) = self.bounds();
        let cell = ((hi - lo).length() * 1e-9).max(f64::MIN_POSITIVE);
        // Weld: vertices on the same grid cell get one id (sorted, not hashed: a scan of
        // millions of triangles is checked in a fraction of a second).
        let cells: Vec<[i64; 3]> = self
            .positions
            .iter()
            .map(|p| ((*p - lo) / cell).round().to_array().map(|c| c as i64))
            .collect();
        let mut order: Vec<u32> = (0..cells.len() as u32).collect();
        order.sort_unstable_by_key(|&i| cells[i as usize]);
        let mut ids = vec![0u32; cells.len()];
        for (rank, pair) in order.iter().enumerate() {
            let previous = rank.checked_sub(1).map(|r| order[r]);
            ids[*pair as usize] = match previous {
                Some(p) if cells[p as usize] == cells[*pair as usize] => ids[p as usize],
                _ => *pair,
            };
        }
        let mut edges = Vec::with_capacity(3 * self.triangles.len());
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| ids[i as usize]);
            if a == b || b == c || c == a {
                return false;
            }
            edges.extend([(a, b), (b, c), (c, a)]);
        }
        // Closed and consistently wound: every directed edge once, and its reverse once.
        edges.sort_unstable();
        let mut reversed: Vec<(u32, u32)> = edges.iter().map(|&(a, b)| (b, a)).collect();
        reversed.sort_unstable();
        let paired = edges.windows(2).all(|w| w[0] != w[1]) && edges == reversed;
        let volume: f64 = (0..self.triangles.len())
            .map(|i| {
                let [a, b, c] = self.triangle_positions(i);
                a.dot(b.cross(c))
            })
            .sum();
        paired && volume > 0.0
    }

    /// The generalised winding number of the mesh around `point`: the sum of the solid angles
    /// its triangles subtend, over 4π (Van Oosterom and Strackee's formula). For a closed mesh
    /// with outward fronts it is 1 inside and 0 outside.
    #[must_use]
    pub fn winding_number(&self, point: DVec3) -> f64 {
        let total: f64 = (0..self.triangles.len())
            .map(|i| {
                let [a, b, c] = self.triangle_positions(i).map(|p| p - point);
                let (la, lb, lc) = (a.length(), b.length(), c.length());
                let numerator = a.dot(b.cross(c));
                let denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
                2.0 * numerator.atan2(denominator)
            })
            .sum();
        total / (4.0 * std::f64::consts::PI)
    }

    /// Axis-aligned bounds (min, max) of the vertices.
    #[must_use]
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    }

    /// The mesh with `transform` applied to positions and its inverse transpose to normals.
    ///
    /// # Errors
    /// [`MeshError::NonFinite`] if the transform produces non-finite positions.
    pub fn transformed(mut self, transform: DMat4) -> Result<Self, MeshError> {
        let normal_matrix = transform.inverse().transpose();
        for p in &mut self.positions {
            *p = transform.transform_point3(*p);
        }
        if let Some(vertex) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                vertex,
                attribute: "position",
            });
        }
        let smooth = self.smooth_normals();
        for (n, fallback) in self.normals.iter_mut().zip(smooth) {
            *n = normal_matrix
                .transform_vector3(*n)
                .try_normalize()
                .unwrap_or(fallback);
        }
        if transform.determinant() < 0.0 {
            // A mirroring transform flips the winding; restore counter-clockwise fronts.
            for t in &mut self.triangles {
                t.swap(1, 2);
            }
        }
        Ok(self)
    }
}

/// A texture image: RGBA8 texels as stored in the file (sRGB-encoded), row 0 at the top
/// (texture coordinate v = 0); or a flipbook, `frames` images of one size stacked from the top,
/// shown one after another as the object's proper time advances.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels (of all frames together).
    pub height: u32,
    /// Row-major texels, `width * height` of them.
    pub texels: Vec<[u8; 4]>,
    /// Where it came from (file name or description), for messages.
    pub source: String,
    /// How many frames are stacked (1: a still image); `height` is a multiple of it.
    pub frames: u32,
    /// Frames per unit of the object's proper time ct′ (0 for a still image).
    pub frame_rate: f64,
}

impl Texture {
    /// A still image.
    #[must_use]
    pub fn still(width: u32, height: u32, texels: Vec<[u8; 4]>, source: String) -> Self {
        Self {
            width,
            height,
            texels,
            source,
            frames: 1,
            frame_rate: 0.0,
        }
    }

    /// The frame shown at proper time `proper_time` (ct′): ⌊τ · rate⌋ mod frames, looping (frame
    /// 0 from τ = 0 on).
    #[must_use]
    pub fn frame_at(&self, proper_time: f64) -> u32 {
        let shown = (proper_time * self.frame_rate).floor();
        let count = f64::from(self.frames);
        // In [0, frames); a non-finite time shows the first frame.
        let frame = shown - (shown / count).floor() * count;
        if frame.is_finite() {
            frame as u32 % self.frames
        } else {
            0
        }
    }
}

/// The most two channels of a colour may differ for it to count as grey: a faint tint (the
/// teaser spider's [0.85, 0.85, 0.8]) is not a colour worth a note.
const GREY_TOLERANCE: f32 = 0.1;

/// Whether the colour `rgba` (channels in [0, 1]) has a hue: its red, green and blue differ.
fn has_hue(rgba: [f32; 4]) -> bool {
    let [r, g, b, _] = rgba;
    (r - g).abs().max((g - b).abs()).max((r - b).abs()) > GREY_TOLERANCE
}

impl Part {
    /// Whether the part shows any colour beside grey — its material's base colour, a texel of
    /// its texture or a vertex colour has a hue — which the paper's grey reflectance (Eq. 18)
    /// would lose.
    #[must_use]
    pub fn has_hue(&self) -> bool {
        let material = &self.material;
        has_hue(material.base_color)
            || material.texture.as_ref().is_some_and(|texture| {
                texture
                    .texels
                    .iter()
                    .any(|texel| has_hue(texel.map(|c| f32::from(c) / 255.0)))
            })
            || self
                .mesh
                .colors()
                .is_some_and(|colors| colors.iter().any(|c| has_hue(*c)))
    }
}

/// Surface description of a mesh part.
///
/// The paper (§4.2, Eq. 18) only needs a grey value per surface point: it uses the texel colour
/// times the base colour, G = 0.3R + 0.59G + 0.11B, as an artificial reflectance.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Material name from the file, if any.
    pub name: String,
    /// Base colour RGBA factor in [0, 1], multiplied with the texture and vertex colours.
    pub base_color: [f32; 4],
    /// Optional base-colour texture, shared between parts that use the same image.
    pub texture: Option<Arc<Texture>>,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: String::new(),
            base_color: [1.0; 4],
            texture: None,
        }
    }
}

/// One mesh with one material: models are lists of parts that share one rest frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Geometry in S′.
    pub mesh: Mesh,
    /// Surface description.
    pub material: Material,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grey or faintly tinted part has no hue; a coloured material, texel or vertex has.
    #[test]
    fn a_part_has_a_hue_when_any_of_its_colours_does() {
        let (positions, triangles) = quad();
        let part = |base_color, texture: Option<Arc<Texture>>| Part {
            mesh: Mesh::new(positions.clone(), triangles.clone()).expect("a mesh"),
            material: Material {
                name: String::new(),
                base_color,
                texture,
            },
        };
        assert!(!part([0.85, 0.85, 0.8, 1.0], None).has_hue());
        assert!(part([0.9, 0.1, 0.1, 1.0], None).has_hue());
        let grey = Texture::still(
            2,
            1,
            vec![[10, 10, 10, 255], [200, 200, 200, 255]],
            "g".into(),
        );
        assert!(!part([1.0; 4], Some(Arc::new(grey))).has_hue());
        let green = Texture::still(
            2,
            1,
            vec![[10, 10, 10, 255], [20, 200, 20, 255]],
            "c".into(),
        );
        assert!(part([1.0; 4], Some(Arc::new(green))).has_hue());
        let mut tinted = part([1.0; 4], None);
        tinted.mesh = tinted
            .mesh
            .with_colors(vec![
                [1.0, 1.0, 1.0, 1.0],
                [0.2, 0.4, 1.0, 1.0],
                [1.0; 4],
                [1.0; 4],
            ])
            .expect("one colour per vertex");
        assert!(tinted.has_hue());
    }

    fn quad() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        (
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            vec![[0, 1, 2], [0, 2, 3]],
        )
    }

    #[test]
    fn rejects_bad_meshes() {
        assert_eq!(Mesh::new(vec![DVec3::ZERO], vec![]), Err(MeshError::Empty));
        let (p, _) = quad();
        assert!(matches!(
            Mesh::new(p.clone(), vec![[0, 1, 9]]),
            Err(MeshError::IndexOutOfRange { index: 9, .. })
        ));
        let mut bad = p;
        bad[2].x = f64::NAN;
        assert!(matches!(
            Mesh::new(bad, vec![[0, 1, 2]]),
            Err(MeshError::NonFinite { vertex: 2, .. })
        ));
    }

    #[test]
    fn smooth_normals_of_a_flat_quad_point_up() {
        let (p, t) = quad();
        let mesh = Mesh::new(p, t).unwrap();
        assert!(
            mesh.normals()
                .iter()
                .all(|n| (*n - DVec3::Z).length() < 1e-12)
        );
    }

    #[test]
    fn closedness_is_detected() {
        let (p, t) = quad();
        assert!(
            !Mesh::new(p, t).unwrap().is_closed_outward(),
            "an open quad"
        );
        // A tetrahedron with outward fronts, then inside out.
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        assert!(Mesh::new(p.clone(), t.clone()).unwrap().is_closed_outward());
        let inverted = t.iter().map(|&[a, b, c]| [a, c, b]).collect();
        let tetrahedron = Mesh::new(p.clone(), t).unwrap();
        assert!((tetrahedron.winding_number(DVec3::splat(0.1)) - 1.0).abs() < 1e-12);
        assert!(tetrahedron.winding_number(DVec3::splat(2.0)).abs() < 1e-12);
        assert!(!Mesh::new(p, inverted).unwrap().is_closed_outward());
    }

    #[test]
    fn mirroring_keeps_fronts_facing_out() {
        let (p, t) = quad();
        let mesh = Mesh::new(p, t).unwrap();
        let mirrored = mesh
            .transformed(DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0)))
            .unwrap();
        let [a, b, c] = mirrored.triangle_positions(0);
        let face = (b - a).cross(c - a).normalize();
        assert!((face - mirrored.normals()[0]).length() < 1e-12);
    }
}
