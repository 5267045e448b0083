//! Lights on their own worldlines and their late shadows on the GPU (docs/physics.md, "Moving
//! lights"; `shaders/shadows.wgsl`): the per-frame [`LightUniforms`] (the lamp's strength and up
//! to [`MAX_MOVING_LIGHTS`] moving lights) and, for scenes with moving lights, one scene-wide
//! storage buffer holding every object's BVH for the shadow test (WGSL `shadow_scene`).
//!
//! A surface point is lit by a moving light as it was at the light's retarded event (the mirror
//! of `srt_physics::RetardedLight`), unless an object blocked the light on its null ray from
//! there: `srt_trace`'s `Tracer::shadowed` takes the surface event and the retarded event into
//! each non-emitting object's rest frame, where the object is static and the null ray a straight
//! segment, and tests the segment against the object's triangles. The shading pass does the
//! same per pixel, so it needs every object's triangles at once: their BVHs (the ray tracer's,
//! [`crate::bvh::ObjectBvh`]) are concatenated into `shadow_scene`, in rows of 16 bytes:
//!
//! 1. one [`GpuShadowObject`] per object with triangles ([`SHADOW_OBJECT_ROWS`] rows each,
//!    rewritten every frame: its frame and whether it emits);
//! 2. every BVH's nodes ([`GpuBvhNode`], [`SHADOW_NODE_ROWS`] rows each), an inner node's
//!    `first` its first child's index among all nodes, a leaf's `first` its first triangle's
//!    index among all triangles;
//! 3. every triangle in its BVH's leaf order ([`GpuRtTriangle`],
//!    [`SHADOW_TRIANGLE_ROWS`](crate::types::SHADOW_TRIANGLE_ROWS) rows each).
//!
//! One buffer rather than three: the LRT shading pass's fragment stage already reads six storage
//! buffers, and srt asks for at most eight per stage (`context::device_descriptor`; WebGPU's
//! default, and what llvmpipe's GL serves). A scene without moving lights binds a one-row
//! buffer and the shaders never read it.
//!
//! Bodies that spin or thrust in their rest frames ([`crate::motion`]) are not shadow casters
//! here: the walk meets static triangles only. A scene whose moving lights' shadows such a body
//! would cast is refused ([`crate::Method::cannot_draw`]); the CPU reference draws it exactly.

use bytemuck::Zeroable as _;
use srt_scene::Scene;
use wgpu::util::DeviceExt as _;

use crate::bvh::ObjectBvh;
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::types::{
    GpuBvhNode, GpuMovingLight, GpuRtTriangle, GpuShadowObject, LightUniforms, MAX_MOVING_LIGHTS,
    SHADOW_NODE_ROWS, SHADOW_OBJECT_ROWS, mat4, vec4,
};

/// The per-frame light uniforms of `scene`: its lamp's strength and its first
/// [`MAX_MOVING_LIGHTS`] moving lights (scenes have at most that many), with where `shadows`'
/// casters are (none without, or where the scene's objects cast no shadows:
/// [`Scene::shadows`]).
#[must_use]
pub fn light_uniforms(scene: &Scene, shadows: Option<&ShadowScene>) -> LightUniforms {
    let mut moving = [GpuMovingLight::zeroed(); MAX_MOVING_LIGHTS];
    let count = scene.lights.len().min(MAX_MOVING_LIGHTS);
    for (slot, light) in moving.iter_mut().zip(&scene.lights) {
        *slot = GpuMovingLight::from(light);
    }
    let (casters, node_row, triangle_row) = frame_shadows(scene, shadows)
        .map_or((0, 0, 0), |s| (s.casters.len(), s.node_row, s.triangle_row));
    LightUniforms {
        lamp: [scene.light.strength as f32, 0.0, 0.0, 0.0],
        counts: [count as u32, casters as u32, node_row, triangle_row],
        moving,
    }
}

/// The shadow casters the frame of `scene` tests: `shadows`, unless the scene's objects cast no
/// shadows ([`Scene::shadows`]).
#[must_use]
pub fn frame_shadows<'a>(
    scene: &Scene,
    shadows: Option<&'a ShadowScene>,
) -> Option<&'a ShadowScene> {
    shadows.filter(|_| scene.shadows)
}

/// Whether the frame of `scene` tests any shadow caster (the shading variant's `shadowed`).
#[must_use]
pub fn frame_has_casters(scene: &Scene, shadows: Option<&ShadowScene>) -> bool {
    frame_shadows(scene, shadows).is_some_and(|s| !s.casters.is_empty())
}

/// One shadow caster: the object's index in scene order and its BVH's root among all nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Caster {
    /// The object's index in the scene.
    pub object: usize,
    /// Its BVH's root node in [`ShadowRows::nodes`].
    pub root: u32,
}

/// The static part of `shadow_scene`: every caster's BVH nodes and triangles, concatenated.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowRows {
    /// The casters, in scene order.
    pub casters: Vec<Caster>,
    /// Every BVH's nodes, children and leaves indexing the concatenation.
    pub nodes: Vec<GpuBvhNode>,
    /// Every BVH's triangles in its leaf order.
    pub triangles: Vec<GpuRtTriangle>,
}

impl ShadowRows {
    /// Concatenates `objects`: (index in the scene, its BVH, its triangles in the BVH's leaf
    /// order), each BVH's node and triangle indices moved by the entries before it.
    #[must_use]
    pub fn new(objects: &[(usize, &ObjectBvh, &[GpuRtTriangle])]) -> Self {
        let mut rows = Self {
            casters: Vec::with_capacity(objects.len()),
            nodes: Vec::new(),
            triangles: Vec::new(),
        };
        for &(object, bvh, triangles) in objects {
            let node_base = rows.nodes.len() as u32;
            let triangle_base = rows.triangles.len() as u32;
            rows.casters.push(Caster {
                object,
                root: node_base,
            });
            rows.nodes.extend(bvh.nodes.iter().map(|n| GpuBvhNode {
                first: n.first
                    + if n.primitive_count > 0 {
                        triangle_base
                    } else {
                        node_base
                    },
                ..*n
            }));
            rows.triangles.extend_from_slice(triangles);
        }
        rows
    }
}

/// The scene-wide shadow buffer of a scene with moving lights (the module documentation).
pub struct ShadowScene {
    /// WGSL `shadow_scene`.
    buffer: wgpu::Buffer,
    /// The casters, in buffer order.
    casters: Vec<Caster>,
    /// The row of the first BVH node.
    node_row: u32,
    /// The row of the first triangle.
    triangle_row: u32,
}

impl ShadowScene {
    /// Uploads `rows` (the caster records are written per frame, [`ShadowScene::write`]).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the buffer exceeds a storage buffer of the device.
    pub fn new(ctx: &GpuContext, rows: &ShadowRows) -> Result<Self, GpuError> {
        let objects = rows.casters.len() * size_of::<GpuShadowObject>();
        let nodes: &[u8] = bytemuck::cast_slice(&rows.nodes);
        let triangles: &[u8] = bytemuck::cast_slice(&rows.triangles);
        let bytes = objects + nodes.len() + triangles.len();
        DeviceLimits::of(ctx).check_storage_buffer(
            || {
                format!(
                    "the shadow buffer of {} objects' {} triangles",
                    rows.casters.len(),
                    rows.triangles.len()
                )
            },
            bytes as u64,
        )?;
        let mut contents = vec![0; bytes.max(16)];
        contents[objects..objects + nodes.len()].copy_from_slice(nodes);
        contents[objects + nodes.len()..bytes].copy_from_slice(triangles);
        let node_row = rows.casters.len() as u32 * SHADOW_OBJECT_ROWS;
        Ok(Self {
            buffer: shadow_buffer(&ctx.device, &contents),
            casters: rows.casters.clone(),
            node_row,
            triangle_row: node_row + rows.nodes.len() as u32 * SHADOW_NODE_ROWS,
        })
    }

    /// WGSL `shadow_scene`.
    #[must_use]
    pub const fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Writes every caster's record for `scene` (same objects as uploaded): its rest frame and
    /// whether it emits (emitters, the lamps' visible bulbs, cast no shadow).
    pub fn write(&self, queue: &wgpu::Queue, scene: &Scene) {
        let records: Vec<GpuShadowObject> = self
            .casters
            .iter()
            .map(|caster| {
                let object = &scene.objects[caster.object];
                GpuShadowObject {
                    observer_to_rest: mat4(object.frame.observer_to_rest_matrix()),
                    offset: vec4(object.frame.offset(), 0.0),
                    bvh: [
                        caster.root,
                        u32::from(object.optics.emission.is_some()),
                        caster.object as u32,
                        0,
                    ],
                }
            })
            .collect();
        if !records.is_empty() {
            queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(&records));
        }
    }
}

/// A `shadow_scene` buffer holding `contents` (at least one row), written to per frame.
fn shadow_buffer(device: &wgpu::Device, contents: &[u8]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("srt shadow scene"),
        contents,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    })
}

/// The one-row `shadow_scene` of a renderer without moving lights (never read).
#[must_use]
pub fn empty_shadow_buffer(device: &wgpu::Device) -> wgpu::Buffer {
    shadow_buffer(device, &[0; 16])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The leaves reached from `root` in `nodes`: (first triangle, count) each.
    fn leaves(nodes: &[GpuBvhNode], root: u32) -> Vec<(u32, u32)> {
        let mut pending = vec![root];
        let mut found = Vec::new();
        while let Some(node) = pending.pop() {
            let n = nodes[node as usize];
            if n.primitive_count > 0 {
                found.push((n.first, n.primitive_count));
            } else {
                pending.extend([n.first, n.first + 1]);
            }
        }
        found.sort_unstable();
        found
    }

    fn triangle(x: f32) -> GpuRtTriangle {
        GpuRtTriangle {
            p0: [x, 0.0, 0.0],
            part: 1,
            p1: [x + 1.0, 0.0, 0.0],
            triangle: 0,
            p2: [x, 1.0, 0.0],
            padding: 0,
        }
    }

    /// Each caster's tree, walked from its root among all nodes, reaches exactly its own
    /// triangles, each once.
    #[test]
    fn concatenated_trees_reach_their_own_triangles() {
        let objects: Vec<Vec<GpuRtTriangle>> = [3usize, 40, 1]
            .iter()
            .enumerate()
            .map(|(k, &n)| (0..n).map(|i| triangle((10 * k + i) as f32)).collect())
            .collect();
        let bvhs: Vec<ObjectBvh> = objects
            .iter()
            .map(|t| {
                let corners: Vec<_> = t.iter().map(|t| [t.p0, t.p1, t.p2]).collect();
                ObjectBvh::build(&corners, || "test".into()).unwrap()
            })
            .collect();
        let ordered: Vec<Vec<GpuRtTriangle>> = bvhs
            .iter()
            .zip(&objects)
            .map(|(b, t)| b.in_leaf_order(t))
            .collect();
        let input: Vec<(usize, &ObjectBvh, &[GpuRtTriangle])> = (0..3)
            .map(|k| (2 * k, &bvhs[k], ordered[k].as_slice()))
            .collect();
        let rows = ShadowRows::new(&input);
        assert_eq!(rows.triangles.len(), 44);
        let mut start = 0;
        for (k, caster) in rows.casters.iter().enumerate() {
            assert_eq!(caster.object, 2 * k);
            let mut covered: Vec<u32> = leaves(&rows.nodes, caster.root)
                .into_iter()
                .flat_map(|(first, count)| first..first + count)
                .collect();
            covered.sort_unstable();
            let own = objects[k].len() as u32;
            assert_eq!(
                covered,
                (start..start + own).collect::<Vec<_>>(),
                "caster {k}"
            );
            for t in covered {
                assert!(objects[k].contains(&rows.triangles[t as usize]));
            }
            start += own;
        }
    }
}
