//! Objects' BVHs ([`ObjectBvh`]: the tree and its leaves' triangles), shared: by the objects of one scene whose parts hold the same meshes (instances of
//! one model placed by their frames' `offset`s), and kept from one tracer to the next, so that
//! a sequence of frames (an animation, the viewer's loop, `srt.Renderer`, the web page's
//! worker) builds each object's BVH once. A BVH is reused only where it is the one the object
//! would build: the same triangles at the same rest coordinates, bit for bit, with the same
//! padding of their boxes; nothing traced changes.

use std::sync::{Arc, Mutex, PoisonError};

use glam::DVec3;
use srt_scene::Part;

use crate::walk::FlatBvh;

/// A triangle of one of an object's parts, as a leaf of the object's BVH: its corners (the
/// mesh's, copied in the order the BVH's leaves are laid out, so that a walk reads them side by
/// side and without the mesh's index) and where it comes from.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PartTriangle {
    /// The corners in the object's rest coordinates ([`srt_scene::Mesh::triangle_positions`]).
    pub(crate) corners: [DVec3; 3],
    /// The part.
    pub(crate) part: u32,
    /// The triangle in the part's mesh.
    pub(crate) triangle: u32,
}

/// An object's BVH and its leaves' triangles, in leaf order.
pub(crate) type ObjectBvh = (FlatBvh, Vec<PartTriangle>);

/// The BVHs of a scene's objects as its tracer is made: those built or found so far for this
/// scene, by the parts they were made for, and the generation of tracers this one is.
pub(crate) struct SharedBvhs<'a> {
    shared: Vec<SharedBvh<'a>>,
    generation: u64,
}

/// A BVH of [`SharedBvhs`] and what it was built from.
struct SharedBvh<'a> {
    /// [`fingerprint`] of the parts and the padding.
    fingerprint: u64,
    parts: &'a [Part],
    /// The padding's bits.
    pad: u64,
    bvh: Arc<ObjectBvh>,
}

/// The BVHs the tracers made before in this process built or used, for the next ones: those
/// of the last two generations of tracers (a tracer's own are also held by it).
static KEPT: Mutex<Kept> = Mutex::new(Kept {
    generation: 0,
    bvhs: Vec::new(),
});

/// [`KEPT`]'s contents.
struct Kept {
    /// The generation of the last tracer begun.
    generation: u64,
    bvhs: Vec<KeptBvh>,
}

/// A BVH kept from an earlier tracer: what it was built for and the last generation that used
/// it.
struct KeptBvh {
    fingerprint: u64,
    pad: u64,
    /// Each part's number of triangles.
    triangles: Vec<usize>,
    bvh: Arc<ObjectBvh>,
    used: u64,
}

/// The words a part's mesh is told by: its vertex positions' bits and its triangles' indices.
fn mesh_words(part: &Part) -> impl Iterator<Item = u64> + '_ {
    let positions = (part.mesh.positions().iter()).flat_map(|p| p.to_array().map(f64::to_bits));
    let triangles = (part.mesh.triangles().iter())
        .map(|&[a, b, c]| u64::from(a) | u64::from(b) << 21 ^ u64::from(c) << 42);
    positions.chain(triangles)
}

/// A quick hash of parts' meshes and a padding (FxHash's multiply and rotate): equal meshes
/// have equal fingerprints; equal fingerprints are checked bit by bit.
fn fingerprint(parts: &[Part], pad: u64) -> u64 {
    (parts.iter().flat_map(mesh_words)).fold(pad, |hash, word| {
        (hash.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
    })
}

/// A point's bits.
fn bits(point: DVec3) -> [u64; 3] {
    point.to_array().map(f64::to_bits)
}

/// Whether two lists of parts hold the same meshes: positions bit for bit, the same triangles.
fn same_meshes(a: &[Part], b: &[Part]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(a, b)| {
            a.mesh.triangles() == b.mesh.triangles()
                && a.mesh.positions().len() == b.mesh.positions().len()
                && (a.mesh.positions().iter().zip(b.mesh.positions()))
                    .all(|(&p, &q)| bits(p) == bits(q))
        })
}

/// Whether the leaves of a BVH built for parts with `triangles` triangles each are the
/// triangles of `parts`, corner for corner and bit for bit: then it is the BVH `parts` would
/// build (its leaves name each triangle of each part once).
fn same_triangles(leaves: &[PartTriangle], triangles: &[usize], parts: &[Part]) -> bool {
    triangles.len() == parts.len()
        && (triangles.iter().zip(parts)).all(|(&count, part)| part.mesh.triangles().len() == count)
        && leaves.iter().all(|leaf| {
            let mesh = &parts[leaf.part as usize].mesh;
            let corners = mesh.triangle_positions(leaf.triangle as usize);
            (0..3).all(|k| bits(corners[k]) == bits(leaf.corners[k]))
        })
}

impl<'a> SharedBvhs<'a> {
    /// The BVHs of a new tracer: a new generation (the BVHs no tracer of this generation or
    /// the last used are forgotten when it is [`SharedBvhs::finish`]ed).
    pub(crate) fn begin() -> Self {
        let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
        kept.generation += 1;
        Self {
            shared: Vec::new(),
            generation: kept.generation,
        }
    }

    /// The BVH over the triangles of `parts` (their boxes padded by `pad`): an earlier
    /// object's of this scene where its parts held the same meshes, else an earlier tracer's
    /// built for the same triangles, else `build()`'s.
    pub(crate) fn of(
        &mut self,
        parts: &'a [Part],
        pad: f64,
        build: impl FnOnce() -> Option<ObjectBvh>,
    ) -> Option<Arc<ObjectBvh>> {
        let pad = pad.to_bits();
        let fingerprint = fingerprint(parts, pad);
        let same = |shared: &&SharedBvh<'a>| {
            shared.fingerprint == fingerprint
                && shared.pad == pad
                && same_meshes(shared.parts, parts)
        };
        if let Some(shared) = self.shared.iter().find(same) {
            return Some(Arc::clone(&shared.bvh));
        }
        let bvh = self.kept(fingerprint, pad, parts, build)?;
        self.shared.push(SharedBvh {
            fingerprint,
            parts,
            pad,
            bvh: Arc::clone(&bvh),
        });
        Some(bvh)
    }

    /// An earlier tracer's BVH for the same triangles, else `build()`'s, kept for the next
    /// tracers.
    fn kept(
        &self,
        fingerprint: u64,
        pad: u64,
        parts: &[Part],
        build: impl FnOnce() -> Option<ObjectBvh>,
    ) -> Option<Arc<ObjectBvh>> {
        {
            let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
            let found = kept.bvhs.iter_mut().find(|k| {
                k.fingerprint == fingerprint
                    && k.pad == pad
                    && same_triangles(&k.bvh.1, &k.triangles, parts)
            });
            if let Some(found) = found {
                found.used = found.used.max(self.generation);
                return Some(Arc::clone(&found.bvh));
            }
        }
        // Built without the lock: another tracer may build the same meanwhile.
        let bvh = Arc::new(build()?);
        let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
        kept.bvhs.push(KeptBvh {
            fingerprint,
            pad,
            triangles: parts.iter().map(|p| p.mesh.triangles().len()).collect(),
            bvh: Arc::clone(&bvh),
            used: self.generation,
        });
        Some(bvh)
    }

    /// Forgets the kept BVHs that neither this generation of tracers nor the last used.
    pub(crate) fn finish(self) {
        let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
        let generation = self.generation;
        kept.bvhs.retain(|k| k.used + 1 >= generation);
    }
}

/// Forgets every BVH kept from earlier tracers, so that the next tracer builds its own: for
/// measuring what a first frame's build costs.
pub fn forget_kept_bvhs() {
    KEPT.lock()
        .unwrap_or_else(PoisonError::into_inner)
        .bvhs
        .clear();
}
