//! What the GPU ray tracer (`Method::Rt`, `shaders/rt.wgsl`) keeps per object: a BVH over all
//! the object's triangles in its rest frame S′ ([`crate::bvh::ObjectBvh`]), the triangles in
//! the BVH's leaf order with the ids the visibility pass writes, and the BVH's box, uploaded as
//! a 12-triangle stand-in for the proxy pass. The proxy pass turns the box's triangles into
//! conservative footprints (the near faces culled when the observer is clearly outside the box,
//! [`crate::culling::box_near_faces_cullable`]); the ray tracer's visibility pass draws those
//! footprints and traces each fragment's ray through the BVH; the shading pass (the LRT's)
//! shades each batch inside the box's screen bound.
//!
//! Why the box's footprints hold the object's image: a pixel sees a triangle of the object only
//! if its backward ray in S′ reaches a point inside the box, and a half-line that reaches a
//! point inside a box leaves it through the box's surface, through a face turned away from its
//! origin; the footprint of the surface triangle it crosses holds the pixel (srt-proxy's
//! guarantee, checked by `cargo xtask validate`).
//!
//! A body that spins or thrusts in its rest frame ([`crate::motion`]) is drawn through the box
//! that holds it at every event a backward ray may meet it ([`crate::motion::sweep_bounds`]),
//! rewritten every frame; its fragments march the ray's body-space curve (`motion.wgsl`).

use glam::DVec3;
use wgpu::util::DeviceExt as _;

use crate::bvh::{ObjectBvh, box_geometry};
use crate::context::GpuContext;
use crate::culling::box_near_faces_cullable;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::passes::FrameShared;
use crate::pipelines::{Pipelines, slots};
use crate::textures::part_texture;
use crate::types::{
    DRAW_ARGS_BYTES, GpuFootprint, GpuRtTriangle, PartFlags, PartUniforms, footprint_slots,
};

/// Triangles of an object's box.
pub(crate) const BOX_TRIANGLES: u32 = 12;

/// Per object: the BVH, the box's proxy inputs and outputs, and the ray tracer's bind groups.
pub(crate) struct ObjectRayTracing {
    /// The box's uniforms (their culling flag is written every frame).
    box_uniforms: wgpu::Buffer,
    /// The box's corners, rewritten every frame for a moving body.
    box_vertices: wgpu::Buffer,
    /// The BVH's (widened) box in S′.
    bounds: ([f32; 3], [f32; 3]),
    /// The object's surface area over its box's: how many layers of triangles an average
    /// line of sight through the box crosses, against the box's two faces.
    layers: f64,
    /// Group 2 of the proxy pass for the box (its uniforms, corners and triangles); also bound
    /// in the visibility pass, which reads nothing of it.
    pub box_part_group: wgpu::BindGroup,
    /// Group 3 of the proxy pass for the box: its footprints, the frame's screen bound and the
    /// box's draw arguments.
    pub box_proxy_group: wgpu::BindGroup,
    /// The box's two draws (its footprints, then the bound's rectangle) and its screen bound,
    /// reset before every proxy pass.
    pub box_draw_args: wgpu::Buffer,
    /// Group 3 of the ray tracer's visibility pass: the box's footprints, counter, BVH.
    pub visibility_group: wgpu::BindGroup,
    /// Group 3 of the shading pass after the ray tracer: the box's footprints, the counter and
    /// the box's draw arguments with its bound.
    pub shade_group: wgpu::BindGroup,
}

/// How many layers of triangles an average line of sight through the box `bounds` crosses:
/// the triangles' total area over the box's surface ([`ObjectRayTracing::layers`]).
fn layers(corners: &[[[f32; 3]; 3]], bounds: ([f32; 3], [f32; 3])) -> f64 {
    let area = |[a, b, c]: [[f32; 3]; 3]| {
        let [a, b, c] = [a, b, c].map(|p| DVec3::from(p.map(f64::from)));
        0.5 * (b - a).cross(c - a).length()
    };
    let size = DVec3::from(bounds.1.map(f64::from)) - DVec3::from(bounds.0.map(f64::from));
    let box_area = 2.0 * (size.x * size.y + size.y * size.z + size.z * size.x);
    corners.iter().map(|&t| area(t)).sum::<f64>() / box_area.max(f64::MIN_POSITIVE)
}

/// A storage buffer holding `contents`.
fn storage_buffer(device: &wgpu::Device, label: &str, contents: &[u8]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::STORAGE,
    })
}

/// The buffers of an object's box as the proxy pass's input (uniforms, corners, triangles) and
/// output (footprints, draw arguments with the screen bound).
struct BoxBuffers {
    uniforms: wgpu::Buffer,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    footprints: wgpu::Buffer,
    draw_args: wgpu::Buffer,
}

impl BoxBuffers {
    /// Uploads the box `bounds` (S′) and allocates its proxy outputs.
    fn new(device: &wgpu::Device, bounds: ([f32; 3], [f32; 3])) -> Self {
        let (vertices, triangles) = box_geometry(bounds.0, bounds.1);
        let storage = |label, contents: &[u8]| storage_buffer(device, label, contents);
        let zeroed = |label, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        Self {
            uniforms: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("srt box uniforms"),
                contents: bytemuck::bytes_of(&box_uniforms(false)),
                usage: crate::shaders::BlockSpace::BUFFER_USAGES,
            }),
            vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("srt box vertices"),
                contents: bytemuck::cast_slice(&vertices),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            }),
            indices: storage("srt box indices", bytemuck::cast_slice(&triangles)),
            footprints: zeroed(
                "srt box footprints",
                footprint_slots(u64::from(BOX_TRIANGLES)) * size_of::<GpuFootprint>() as u64,
                wgpu::BufferUsages::empty(),
            ),
            draw_args: zeroed(
                "srt box draw",
                DRAW_ARGS_BYTES,
                wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_DST,
            ),
        }
    }
}

/// The BVH over an object's `triangles` (every triangle of the object, with its batch's part id
/// and its number there; the object named `what` in errors), for the ray tracer and the shadows
/// of moving lights ([`crate::shadows`]).
///
/// # Errors
/// [`GpuError::BvhTooDeep`] when the BVH is deeper than the traversal's stack,
/// [`GpuError::ExceedsLimit`] when the triangles or the nodes exceed a storage buffer,
/// [`GpuError::NotReady`] when there are no triangles.
pub fn object_bvh(
    ctx: &GpuContext,
    triangles: &[GpuRtTriangle],
    what: &str,
) -> Result<ObjectBvh, GpuError> {
    if triangles.is_empty() {
        return Err(GpuError::NotReady("an object without triangles has no BVH"));
    }
    DeviceLimits::of(ctx).check_storage_buffer(
        || format!("the ray tracer's triangle buffer of {what}"),
        std::mem::size_of_val(triangles) as u64,
    )?;
    let bvh = ObjectBvh::build(&triangle_corners(triangles), || what.to_owned())?;
    DeviceLimits::of(ctx).check_storage_buffer(
        || format!("the BVH of {what}"),
        std::mem::size_of_val(bvh.nodes.as_slice()) as u64,
    )?;
    Ok(bvh)
}

/// The corners of `triangles`.
fn triangle_corners(triangles: &[GpuRtTriangle]) -> Vec<[[f32; 3]; 3]> {
    triangles.iter().map(|t| [t.p0, t.p1, t.p2]).collect()
}

impl ObjectRayTracing {
    /// Uploads the BVH `bvh` ([`object_bvh`]) over `triangles` and the BVH's box, and makes the
    /// bind groups, which bind the frame-wide buffers `shared`.
    pub(crate) fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        shared: FrameShared<'_>,
        triangles: &[GpuRtTriangle],
        bvh: &ObjectBvh,
    ) -> Self {
        let device = &ctx.device;
        let corners = triangle_corners(triangles);
        let storage = |label, contents: &[u8]| storage_buffer(device, label, contents);
        let nodes = storage("srt bvh nodes", bytemuck::cast_slice(&bvh.nodes));
        let ordered = storage(
            "srt bvh triangles",
            bytemuck::cast_slice(&bvh.in_leaf_order(triangles)),
        );
        let bounds = bvh.bounds();
        let layers = layers(&corners, bounds);
        let boxed = BoxBuffers::new(device, bounds);
        // The box has no texture; group 2 wants one.
        let (blank, _) = part_texture(ctx, None);
        let group = |label, layout, entries: &[wgpu::BindGroupEntry<'_>]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout,
                entries,
            })
        };
        Self {
            box_part_group: group(
                "srt box part",
                &pipelines.part_layout,
                &[
                    slots::PART.entry(boxed.uniforms.as_entire_binding()),
                    slots::VERTICES.entry(boxed.vertices.as_entire_binding()),
                    slots::INDICES.entry(boxed.indices.as_entire_binding()),
                    slots::PART_TEXTURE.entry(wgpu::BindingResource::TextureView(&blank)),
                ],
            ),
            box_proxy_group: group(
                "srt box proxy output",
                &pipelines.proxy_output_layout,
                &[
                    slots::PROXY_FOOTPRINTS.entry(boxed.footprints.as_entire_binding()),
                    slots::PROXY_FRAME_BOUND.entry(shared.frame_bound.as_entire_binding()),
                    slots::PROXY_DRAW_ARGS.entry(boxed.draw_args.as_entire_binding()),
                ],
            ),
            visibility_group: group(
                "srt rt input",
                &pipelines.rt_input_layout,
                &[
                    slots::LRT_FOOTPRINTS.entry(boxed.footprints.as_entire_binding()),
                    slots::FRAGMENT_COUNT.entry(shared.fragment_count.as_entire_binding()),
                    slots::BVH_NODES.entry(nodes.as_entire_binding()),
                    slots::BVH_TRIANGLES.entry(ordered.as_entire_binding()),
                ],
            ),
            shade_group: group(
                "srt rt shading input",
                &pipelines.lrt_input_layout,
                &[
                    slots::LRT_FOOTPRINTS.entry(boxed.footprints.as_entire_binding()),
                    slots::FRAGMENT_COUNT.entry(shared.fragment_count.as_entire_binding()),
                    slots::LRT_DRAW_ARGS.entry(boxed.draw_args.as_entire_binding()),
                ],
            ),
            box_uniforms: boxed.uniforms,
            box_vertices: boxed.vertices,
            bounds,
            layers,
            box_draw_args: boxed.draw_args,
        }
    }

    /// The object's surface over its box's: how many layers of triangles an average line of
    /// sight through the box crosses (what `auto` weighs, [`crate::auto::ObjectLoad::layers`]).
    #[must_use]
    pub const fn layers(&self) -> f64 {
        self.layers
    }

    /// How many layers of its box's footprints the ray tracer draws for an observer at
    /// `observer` (S′) while the object rests: 1 when the box's near faces are culled (the
    /// observer outside it, [`box_near_faces_cullable`]), else 2.
    #[must_use]
    pub fn box_layers(&self, observer: DVec3) -> u32 {
        if box_near_faces_cullable(self.bounds.0, self.bounds.1, observer) {
            1
        } else {
            2
        }
    }

    /// Sets, for the observer at `observer` in S′, whether the proxy pass culls the box's faces
    /// turned towards it; for a moving body also its box this frame, `sweep`
    /// ([`crate::motion::sweep_bounds`]).
    pub fn write_culling(
        &self,
        queue: &wgpu::Queue,
        observer: DVec3,
        sweep: Option<(DVec3, DVec3)>,
    ) {
        let (min, max) = match sweep {
            Some((lo, hi)) => {
                let (lo, hi) = (lo.as_vec3().to_array(), hi.as_vec3().to_array());
                let (vertices, _) = box_geometry(lo, hi);
                queue.write_buffer(&self.box_vertices, 0, bytemuck::cast_slice(&vertices));
                (lo, hi)
            }
            None => self.bounds,
        };
        let uniforms = box_uniforms(box_near_faces_cullable(min, max, observer));
        queue.write_buffer(&self.box_uniforms, 0, bytemuck::bytes_of(&uniforms));
    }
}

/// The box's part uniforms, culling back faces or not.
fn box_uniforms(cull_back_faces: bool) -> PartUniforms {
    PartUniforms {
        base_color: [1.0; 4],
        flags: PartFlags::ENCLOSING_BOX.with(PartFlags::CULL_BACK_FACES, cull_back_faces),
        triangle_count: BOX_TRIANGLES,
        id: 0,
        frames: 1,
        frame_height: 1,
        frame_rate: 0.0,
        padding: [0; 2],
    }
}
