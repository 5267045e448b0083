//! Procedural shapes in the rest frame S′: a subdivided cube (the paper's Fig. 4, 7 and 10) and
//! a latitude–longitude sphere.
//!
//! Both are centred at the origin, have outward unit normals, counter-clockwise front faces seen
//! from outside and texture coordinates with v = 0 at the top row of the image (as
//! [`Texture`](crate::mesh::Texture) stores it).

use glam::{DVec2, DVec3};

use crate::limits::MAX_SCENE_TRIANGLES;
use crate::mesh::Mesh;

/// The largest `subdivisions` [`cube`] accepts: 12 · 400² = 1.92 million triangles, the most
/// that fits in [`MAX_SCENE_TRIANGLES`] with a round number.
pub const MAX_CUBE_SUBDIVISIONS: u32 = 400;

/// The fewest `segments` [`uv_sphere`] accepts.
pub const MIN_SPHERE_SEGMENTS: u32 = 3;

/// The most `segments` [`uv_sphere`] accepts: 1400 give 1.96 million triangles, the most that
/// fits in [`MAX_SCENE_TRIANGLES`] with a round number.
pub const MAX_SPHERE_SEGMENTS: u32 = 1400;

const _: () = assert!(cube_triangle_count(MAX_CUBE_SUBDIVISIONS) <= MAX_SCENE_TRIANGLES as u64);
const _: () = assert!(uv_sphere_triangle_count(MAX_SPHERE_SEGMENTS) <= MAX_SCENE_TRIANGLES as u64);

/// Triangles of [`cube`] with `subdivisions` (clamped like `cube` does): 12 · n².
#[must_use]
pub const fn cube_triangle_count(subdivisions: u32) -> u64 {
    let n = clamp(subdivisions, 1, MAX_CUBE_SUBDIVISIONS) as u64;
    12 * n * n
}

/// Vertices of [`cube`] with `subdivisions` (clamped like `cube` does): 6 · (n + 1)².
#[must_use]
pub const fn cube_vertex_count(subdivisions: u32) -> u64 {
    let n = clamp(subdivisions, 1, MAX_CUBE_SUBDIVISIONS) as u64;
    6 * (n + 1) * (n + 1)
}

/// Triangles of [`uv_sphere`] with `segments` (clamped like `uv_sphere` does):
/// 2 · slices · (rings − 1).
#[must_use]
pub const fn uv_sphere_triangle_count(segments: u32) -> u64 {
    let (slices, rings) = sphere_grid(segments);
    2 * slices as u64 * (rings as u64 - 1)
}

/// Vertices of [`uv_sphere`] with `segments` (clamped like `uv_sphere` does): one per slice at
/// each pole and slices + 1 on each inner ring.
#[must_use]
pub const fn uv_sphere_vertex_count(segments: u32) -> u64 {
    let (slices, rings) = sphere_grid(segments);
    2 * slices as u64 + (rings as u64 - 1) * (slices as u64 + 1)
}

/// Slices and rings of a sphere of `segments`.
const fn sphere_grid(segments: u32) -> (u32, u32) {
    let slices = clamp(segments, MIN_SPHERE_SEGMENTS, MAX_SPHERE_SEGMENTS);
    let rings = if slices / 2 > 2 { slices / 2 } else { 2 };
    (slices, rings)
}

/// `value` clamped to `lo..=hi` (`Ord::clamp` is not `const`).
const fn clamp(value: u32, lo: u32, hi: u32) -> u32 {
    if value < lo {
        lo
    } else if value > hi {
        hi
    } else {
        value
    }
}

/// The faces of a cube: (outward normal, texture right, texture up), with right × up = normal.
/// Side faces have +z up, the top face +y up and the bottom face −y up.
const CUBE_FACES: [(DVec3, DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::Y, DVec3::Z),
    (DVec3::NEG_X, DVec3::NEG_Y, DVec3::Z),
    (DVec3::Y, DVec3::NEG_X, DVec3::Z),
    (DVec3::NEG_Y, DVec3::X, DVec3::Z),
    (DVec3::Z, DVec3::X, DVec3::Y),
    (DVec3::NEG_Z, DVec3::X, DVec3::NEG_Y),
];

/// An axis-aligned cube of edge length `size` centred at the origin; each face is a grid of
/// `subdivisions` × `subdivisions` squares, two triangles each (2·n² triangles per face, so
/// n = 5 gives the paper's 50 and n = 10 its 200 triangles per face).
///
/// Every face has its own vertices with the flat face normal and texture coordinates running
/// over the whole texture (0..1 in u and v, v = 0 at the face's top edge; side faces have +z up,
/// the top face +y and the bottom face −y). `subdivisions` is clamped to
/// 1..=[`MAX_CUBE_SUBDIVISIONS`].
///
/// # Panics
/// If `size` is not finite and positive (scene files are validated before they get here).
#[must_use]
pub fn cube(size: f64, subdivisions: u32) -> Mesh {
    assert!(
        size.is_finite() && size > 0.0,
        "cube size must be finite and positive, got {size}"
    );
    let n = clamp(subdivisions, 1, MAX_CUBE_SUBDIVISIONS);
    let half = 0.5 * size;
    let vertex_count = usize::try_from(cube_vertex_count(n)).unwrap_or(0);
    let mut positions = Vec::with_capacity(vertex_count);
    let mut normals = Vec::with_capacity(vertex_count);
    let mut uvs = Vec::with_capacity(vertex_count);
    let mut triangles = Vec::with_capacity(usize::try_from(cube_triangle_count(n)).unwrap_or(0));
    let step = 1.0 / f64::from(n);
    for (normal, right, up) in CUBE_FACES {
        let base = u32::try_from(positions.len()).expect("fewer than 2³² cube vertices");
        for row in 0..=n {
            let t = f64::from(row) * step;
            for column in 0..=n {
                let s = f64::from(column) * step;
                positions.push(half * (normal + (2.0 * s - 1.0) * right + (2.0 * t - 1.0) * up));
                normals.push(normal);
                uvs.push(DVec2::new(s, 1.0 - t));
            }
        }
        let index = |row: u32, column: u32| base + row * (n + 1) + column;
        for row in 0..n {
            for column in 0..n {
                let a = index(row, column);
                let b = index(row, column + 1);
                let c = index(row + 1, column + 1);
                let d = index(row + 1, column);
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
    }
    finish(positions, normals, uvs, triangles)
}

/// A latitude–longitude sphere of `radius` centred at the origin with its poles on the z axis:
/// `segments` slices around z and max(2, `segments` / 2) rings from pole to pole.
///
/// Normals are smooth (radial); u runs with the longitude φ = atan2(y, x) from 0 at φ = 0 to 1
/// after a full turn (the seam has doubled vertices), v from 0 at the north pole (+z) to 1 at
/// the south pole. Each pole has one vertex per slice (u at the slice's middle), so the pole caps
/// are proper triangles: there are 2·`segments`·(rings − 1) triangles and none is degenerate.
/// `segments` is clamped to [`MIN_SPHERE_SEGMENTS`]..=[`MAX_SPHERE_SEGMENTS`].
///
/// # Panics
/// If `radius` is not finite and positive (scene files are validated before they get here).
#[must_use]
pub fn uv_sphere(radius: f64, segments: u32) -> Mesh {
    assert!(
        radius.is_finite() && radius > 0.0,
        "sphere radius must be finite and positive, got {radius}"
    );
    let (slices, rings) = sphere_grid(segments);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    let mut push = |normal: DVec3, uv: DVec2| {
        positions.push(radius * normal);
        normals.push(normal);
        uvs.push(uv);
    };
    // North pole: one vertex per slice.
    for j in 0..slices {
        push(
            DVec3::Z,
            DVec2::new((f64::from(j) + 0.5) / f64::from(slices), 0.0),
        );
    }
    // Inner rings 1..rings−1, each with slices + 1 vertices (the seam is doubled).
    for i in 1..rings {
        let v = f64::from(i) / f64::from(rings);
        let (sin_theta, cos_theta) = (std::f64::consts::PI * v).sin_cos();
        for j in 0..=slices {
            let u = f64::from(j) / f64::from(slices);
            let (sin_phi, cos_phi) = (std::f64::consts::TAU * u).sin_cos();
            let normal = if j == slices {
                // Exactly the seam's first vertex, so the sphere closes without a sliver.
                DVec3::new(sin_theta, 0.0, cos_theta)
            } else {
                DVec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
            };
            push(normal, DVec2::new(u, v));
        }
    }
    // South pole: one vertex per slice.
    for j in 0..slices {
        push(
            DVec3::NEG_Z,
            DVec2::new((f64::from(j) + 0.5) / f64::from(slices), 1.0),
        );
    }
    let ring = |i: u32, j: u32| slices + (i - 1) * (slices + 1) + j;
    let south = slices + (rings - 1) * (slices + 1);
    let mut triangles = Vec::with_capacity(2 * (slices * (rings - 1)) as usize);
    for j in 0..slices {
        triangles.push([j, ring(1, j), ring(1, j + 1)]);
    }
    for i in 1..rings - 1 {
        for j in 0..slices {
            let (a, b) = (ring(i, j), ring(i, j + 1));
            let (c, d) = (ring(i + 1, j + 1), ring(i + 1, j));
            triangles.push([a, d, c]);
            triangles.push([a, c, b]);
        }
    }
    for j in 0..slices {
        triangles.push([ring(rings - 1, j), south + j, ring(rings - 1, j + 1)]);
    }
    finish(positions, normals, uvs, triangles)
}

/// Assembles a mesh from attributes that are valid by construction.
fn finish(
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    uvs: Vec<DVec2>,
    triangles: Vec<[u32; 3]>,
) -> Mesh {
    Mesh::new(positions, triangles)
        .and_then(|mesh| mesh.with_normals(normals))
        .and_then(|mesh| mesh.with_uvs(uvs))
        .expect("procedural shapes are valid meshes")
}

#[cfg(test)]
mod tests {

    #[test]
    fn counts_are_known_before_building() {
        for n in [0, 1, 2, 5, 17] {
            let mesh = cube(1.0, n);
            assert_eq!(mesh.triangles().len() as u64, cube_triangle_count(n), "{n}");
            assert_eq!(mesh.positions().len() as u64, cube_vertex_count(n), "{n}");
        }
        for segments in [0, 3, 4, 5, 8, 31, 64] {
            let mesh = uv_sphere(1.0, segments);
            let (triangles, vertices) = (mesh.triangles().len(), mesh.positions().len());
            assert_eq!(
                triangles as u64,
                uv_sphere_triangle_count(segments),
                "{segments}"
            );
            assert_eq!(
                vertices as u64,
                uv_sphere_vertex_count(segments),
                "{segments}"
            );
        }
        assert_eq!(
            cube_triangle_count(1000),
            cube_triangle_count(MAX_CUBE_SUBDIVISIONS)
        );
    }

    #[test]
    fn procedural_shapes_are_closed_solids() {
        assert!(cube(5.0, 5).is_closed_outward());
        assert!(cube(1.0, 1).is_closed_outward());
        assert!(uv_sphere(1.0, 24).is_closed_outward());
    }

    use std::collections::HashMap;

    use super::*;

    /// Quantised position, so that coincident vertices of different faces compare equal.
    fn key(p: DVec3) -> [i64; 3] {
        #[expect(clippy::cast_possible_truncation, reason = "test positions are small")]
        p.to_array().map(|c| (c * 1e6).round() as i64)
    }

    /// Undirected edges (by position) and how many triangles use each.
    fn edge_uses(mesh: &Mesh) -> HashMap<([i64; 3], [i64; 3]), usize> {
        let mut uses = HashMap::new();
        for t in 0..mesh.triangles().len() {
            let corners = mesh.triangle_positions(t).map(key);
            for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                let edge = if corners[a] < corners[b] {
                    (corners[a], corners[b])
                } else {
                    (corners[b], corners[a])
                };
                *uses.entry(edge).or_insert(0) += 1;
            }
        }
        uses
    }

    /// Every triangle's geometric normal points away from the origin and agrees with its
    /// vertex normals; no triangle is degenerate.
    fn assert_outward(mesh: &Mesh) {
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let [a, b, c] = mesh.triangle_positions(t);
            let face = (b - a).cross(c - a);
            assert!(face.length() > 1e-12, "triangle {t} is degenerate");
            let centroid = (a + b + c) / 3.0;
            assert!(face.dot(centroid) > 0.0, "triangle {t} faces inwards");
            for &i in tri {
                assert!(
                    mesh.normals()[i as usize].dot(face) > 0.0,
                    "normal of vertex {i}"
                );
            }
        }
    }

    #[test]
    fn cube_counts_match_the_paper() {
        for (n, per_face) in [(1, 2), (5, 50), (10, 200)] {
            let mesh = cube(5.0, n);
            assert_eq!(mesh.triangles().len(), 6 * per_face);
            let (lo, hi) = mesh.bounds();
            assert!((lo + DVec3::splat(2.5)).length() < 1e-12);
            assert!((hi - DVec3::splat(2.5)).length() < 1e-12);
        }
    }

    #[test]
    fn cube_is_closed_and_faces_outwards() {
        let mesh = cube(2.0, 4);
        assert_outward(&mesh);
        let uses = edge_uses(&mesh);
        assert!(
            uses.values().all(|&n| n == 2),
            "every edge is shared by two triangles"
        );
        assert!(
            mesh.uvs()
                .iter()
                .all(|uv| (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y))
        );
    }

    #[test]
    fn cube_texture_is_upright_on_side_faces() {
        let mesh = cube(2.0, 1);
        // On the +x face, the vertex with v = 0 is at the top (z = +1).
        let top = mesh
            .positions()
            .iter()
            .zip(mesh.uvs())
            .zip(mesh.normals())
            .filter(|((_, _), n)| **n == DVec3::X)
            .find(|((_, uv), _)| uv.y == 0.0)
            .map(|((p, _), _)| *p)
            .unwrap();
        assert!((top.z - 1.0).abs() < 1e-12);
    }

    #[test]
    fn sphere_is_well_formed() {
        for segments in [3, 4, 7, 32] {
            let mesh = uv_sphere(2.0, segments);
            let rings = (segments / 2).max(2);
            assert_eq!(
                mesh.triangles().len(),
                (2 * segments * (rings - 1)) as usize
            );
            assert_outward(&mesh);
            for (p, n) in mesh.positions().iter().zip(mesh.normals()) {
                assert!((p.length() - 2.0).abs() < 1e-12);
                assert!((*p / 2.0 - *n).length() < 1e-12);
            }
            let uses = edge_uses(&mesh);
            assert!(
                uses.values().all(|&n| n == 2),
                "sphere with {segments} segments is closed"
            );
        }
    }
}
