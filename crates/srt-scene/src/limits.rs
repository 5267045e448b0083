//! What srt-scene accepts from files it did not write: the bounds and budgets that keep hostile
//! or careless input (absurd sizes, huge counts, decompression bombs, node graphs that multiply
//! geometry) from exhausting memory, hanging, or reaching a library that assumes sane input.
//!
//! Every budget is charged *before* the allocation it protects: a count is computed from what a
//! file or a key declares (a cube's subdivisions, a PLY header, a glTF node graph, an image
//! header) and refused when it does not fit, with a message naming the file or the key.
//!
//! One [`Budget`] covers one scene: [`SceneDescription::build`] charges every shape, model and
//! texture of every object to the same budget, and [`load_model`] alone gets a fresh one. The
//! numbers and why they were chosen:
//!
//! - [`MAX_SCENE_TRIANGLES`] = 2 million. The largest real model we know of in use here,
//!   2CylinderEngine, has 121 496; the Stanford dragon has 871 414. Rendering a cube of 1.92
//!   million triangles with the CPU renderer (`srt render --backend cpu`, 32 × 32 pixels) peaked
//!   at 0.73 GB, a binary STL triangle soup of 1.99 million triangles (three vertices each) at
//!   1.15 GB: a scene stays well under 4 GB.
//! - [`MAX_SCENE_VERTICES`] = three per budgeted triangle (a triangle soup needs that many).
//! - [`MAX_SCENE_PARTS`] = 100 000 parts (each has its own mesh, material and, in the
//!   renderers, its own BVH), so a million one-triangle instances are refused.
//! - [`MAX_SCENE_TEXELS`] = 2²⁶ texels (256 MiB as RGBA8, e.g. one 8192 × 8192 image) over all
//!   distinct textures; a decoder may use twice that while decoding 16-bit images.
//! - [`MAX_COORDINATE`] = 10⁹ scene units for every rest-frame coordinate after placement, every
//!   position and offset in S and the observation time ct. The GPU renderer works in `f32`
//!   (largest value 3.4 · 10³⁸) and squares lengths: with |β| < 1 in `f64`, γ < 10⁸, so even
//!   γ · x < 10¹⁷ and its square stays below 10³⁵. The BVH library panics on non-finite bounds,
//!   which sizes like 10³⁰⁰ produce.
//!
//! Files are capped by kind in [`crate::input_file`].
//!
//! [`SceneDescription::build`]: crate::description::SceneDescription::build
//! [`load_model`]: crate::import::load_model

use std::sync::Arc;

use crate::mesh::{Part, Texture};

/// The largest absolute value of any coordinate in scene units: rest-frame vertex positions after
/// placement, positions and offsets in S, and the observation time ct.
pub const MAX_COORDINATE: f64 = 1e9;

/// The most triangles one scene may have, all objects together (and so one model loaded alone).
pub const MAX_SCENE_TRIANGLES: usize = 2_000_000;

/// The most vertices one scene may read from files or generate: three per budgeted triangle.
pub const MAX_SCENE_VERTICES: usize = 3 * MAX_SCENE_TRIANGLES;

/// The most parts (one mesh with one material each, after glTF node instancing) one scene may
/// have.
pub const MAX_SCENE_PARTS: usize = 100_000;

/// The most texels all distinct textures of one scene may have together (2²⁶, 256 MiB as RGBA8).
pub const MAX_SCENE_TEXELS: u64 = 1 << 26;

/// The longest side of a texture image, in texels.
pub const MAX_TEXTURE_SIDE: u32 = 16_384;

/// The most memory an image decoder may allocate for one image (enough for a 16-bit RGBA image
/// of [`MAX_SCENE_TEXELS`] texels).
pub const MAX_IMAGE_DECODE_BYTES: u64 = 8 * MAX_SCENE_TEXELS;

/// What a scene has used of its budgets so far.
///
/// Charges are made before the memory they stand for is allocated; a refused charge leaves the
/// budget unchanged.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Budget {
    triangles: usize,
    vertices: usize,
    parts: usize,
    texels: u64,
}

/// A charge that does not fit in a [`Budget`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", describe(resource, *.needed, *.used, *.max))]
pub struct OverBudget {
    /// What ran out: `"triangles"`, `"vertices"`, `"parts"` or `"texels"`.
    pub resource: &'static str,
    /// How many were asked for.
    pub needed: u64,
    /// How many were already used.
    pub used: u64,
    /// The budget.
    pub max: u64,
}

fn describe(resource: &str, needed: u64, used: u64, max: u64) -> String {
    if used == 0 {
        format!("it would have {needed} {resource}, more than the {max} a scene may have")
    } else {
        format!(
            "it would have {needed} {resource}, which with the {used} already loaded is more \
             than the {max} a scene may have"
        )
    }
}

/// `n` as a `u64` (saturating on exotic platforms).
fn wide(n: usize) -> u64 {
    u64::try_from(n).unwrap_or(u64::MAX)
}

impl Budget {
    /// A budget nothing has been charged to.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Triangles charged so far.
    #[must_use]
    pub const fn triangles(&self) -> usize {
        self.triangles
    }

    /// Charges a mesh of `triangles` triangles and `vertices` vertices.
    ///
    /// # Errors
    /// [`OverBudget`] (and nothing is charged) if either count does not fit.
    pub fn charge_mesh(&mut self, triangles: u64, vertices: u64) -> Result<(), OverBudget> {
        let triangles_after = fit("triangles", triangles, self.triangles, MAX_SCENE_TRIANGLES)?;
        let vertices_after = fit("vertices", vertices, self.vertices, MAX_SCENE_VERTICES)?;
        self.triangles = triangles_after;
        self.vertices = vertices_after;
        Ok(())
    }

    /// Charges `vertices` vertices read from a file before they are known to be used.
    ///
    /// # Errors
    /// [`OverBudget`] (and nothing is charged) if they do not fit.
    pub fn charge_vertices(&mut self, vertices: u64) -> Result<(), OverBudget> {
        self.vertices = fit("vertices", vertices, self.vertices, MAX_SCENE_VERTICES)?;
        Ok(())
    }

    /// Charges `parts` parts.
    ///
    /// # Errors
    /// [`OverBudget`] (and nothing is charged) if they do not fit.
    pub fn charge_parts(&mut self, parts: u64) -> Result<(), OverBudget> {
        self.parts = fit("parts", parts, self.parts, MAX_SCENE_PARTS)?;
        Ok(())
    }

    /// Charges a texture of `width` × `height` texels.
    ///
    /// # Errors
    /// [`OverBudget`] (and nothing is charged) if it does not fit.
    pub fn charge_texels(&mut self, width: u32, height: u32) -> Result<(), OverBudget> {
        let needed = u64::from(width) * u64::from(height);
        let after = self.texels.saturating_add(needed);
        if after > MAX_SCENE_TEXELS {
            return Err(OverBudget {
                resource: "texels",
                needed,
                used: self.texels,
                max: MAX_SCENE_TEXELS,
            });
        }
        self.texels = after;
        Ok(())
    }
}

impl Budget {
    /// Charges parts a scene already holds from an earlier build (the viewer keeps the parts of
    /// objects an edit did not change): one part each, its mesh's triangles and vertices, and the
    /// texels of each distinct texture once.
    ///
    /// # Errors
    /// [`OverBudget`] if they do not fit; the budget may then hold part of them.
    pub fn charge_held_parts<'a>(
        &mut self,
        parts: impl IntoIterator<Item = &'a Part>,
    ) -> Result<(), OverBudget> {
        let mut textures_seen: Vec<*const Texture> = Vec::new();
        for part in parts {
            self.charge_parts(1)?;
            self.charge_mesh(
                wide(part.mesh.triangles().len()),
                wide(part.mesh.positions().len()),
            )?;
            if let Some(texture) = &part.material.texture {
                let identity = Arc::as_ptr(texture);
                if !textures_seen.contains(&identity) {
                    textures_seen.push(identity);
                    self.charge_texels(texture.width, texture.height)?;
                }
            }
        }
        Ok(())
    }
}

/// `used + needed` if it is at most `max`.
fn fit(resource: &'static str, needed: u64, used: usize, max: usize) -> Result<usize, OverBudget> {
    wide(used)
        .checked_add(needed)
        .filter(|&after| after <= wide(max))
        .and_then(|after| usize::try_from(after).ok())
        .ok_or(OverBudget {
            resource,
            needed,
            used: wide(used),
            max: wide(max),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charges_add_up_and_refusals_charge_nothing() {
        let mut budget = Budget::new();
        budget.charge_mesh(1_500_000, 10).unwrap();
        let refused = budget.charge_mesh(600_000, 10).unwrap_err();
        assert_eq!(
            (refused.needed, refused.used, refused.max),
            (600_000, 1_500_000, 2_000_000)
        );
        assert!(refused.to_string().contains("already loaded"), "{refused}");
        assert_eq!(budget.triangles(), 1_500_000);
        budget.charge_mesh(500_000, 10).unwrap();
        assert!(budget.charge_mesh(1, 0).is_err());
        assert!(budget.charge_mesh(u64::MAX, 0).is_err());
        assert!(
            Budget::new()
                .charge_vertices(wide(MAX_SCENE_VERTICES) + 1)
                .is_err()
        );
    }

    #[test]
    fn texels_and_parts_are_budgeted() {
        let mut budget = Budget::new();
        budget.charge_texels(8192, 8192).unwrap();
        let refused = budget.charge_texels(1, 1).unwrap_err();
        assert_eq!(refused.resource, "texels");
        let refused = Budget::new().charge_texels(65_535, 65_535).unwrap_err();
        assert!(
            refused
                .to_string()
                .starts_with("it would have 4294836225 texels")
        );
        assert!(
            Budget::new()
                .charge_parts(wide(MAX_SCENE_PARTS) + 1)
                .is_err()
        );
    }
}
