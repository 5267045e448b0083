//! Uploading a scene: its parts grouped into batches (one per texture and culling kind, within
//! the device's buffer limits), each batch's vertices, triangles and footprint slots, and an
//! object's BVH and box for the ray tracer.

use std::ops::Range;

use super::*;

/// One batch's buffer sizes and counts, checked against the device's limits before upload.
pub(super) struct PartSizes {
    pub(super) triangles: u32,
    pub(super) footprint_bytes: u64,
    /// Workgroup grid of the proxy pass.
    pub(super) workgroups: (u32, u32),
}

impl PartSizes {
    /// The sizes of a batch of `triangles` triangles and `vertices` vertices, named in messages
    /// by `describe` (e.g. `parts 0, 3 of object "ship"`).
    pub(super) fn check(
        limits: &DeviceLimits,
        describe: &dyn Fn() -> String,
        triangles: u64,
        vertices: u64,
    ) -> Result<Self, GpuError> {
        let name = |buffer: &str| {
            format!(
                "the {buffer} of {} ({triangles} triangles, {vertices} vertices)",
                describe()
            )
        };
        let footprint_bytes = footprint_slots(triangles) * size_of::<GpuFootprint>() as u64;
        limits.check_storage_buffer(
            || name("vertex buffer"),
            vertices * size_of::<GpuVertex>() as u64,
        )?;
        limits.check_storage_buffer(
            || name("index buffer"),
            triangles * size_of::<[u32; 3]>() as u64,
        )?;
        limits.check_storage_buffer(|| name("footprint buffer"), footprint_bytes)?;
        let workgroups =
            limits.workgroup_grid(|| name("footprint pass"), triangles, WORKGROUP_SIZE)?;
        // The polygon pass draws three vertices per triangle, the LRT pass FOOTPRINT_VERTICES.
        limits.check_u32(|| name("polygon draw"), 3 * triangles, "vertices")?;
        limits.check_u32(
            || name("LRT draw"),
            u64::from(FOOTPRINT_VERTICES) * footprint_slots(triangles),
            "vertices",
        )?;
        limits.check_u32(|| name("index range"), vertices, "vertices")?;
        Ok(Self {
            triangles: limits.check_u32(|| name("batch"), triangles, "triangles")?,
            footprint_bytes,
            workgroups,
        })
    }
}

/// A run of one part's triangles uploaded together: the whole part, or — for a part larger
/// than one batch's buffers may be on the device — one of the slices it is split into.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct PartSlice {
    /// The part's index in its object.
    pub(super) part: usize,
    /// The part's triangles in this slice.
    pub(super) triangles: Range<u32>,
}

impl PartSlice {
    /// How many triangles the slice holds.
    pub(super) fn len(&self) -> u32 {
        self.triangles.end - self.triangles.start
    }

    /// Whether the slice is all of `part`.
    fn is_whole(&self, part: &Part) -> bool {
        self.triangles.start == 0 && self.len() as usize == part.mesh.triangles().len()
    }
}

/// Slices of an object's parts uploaded and drawn together ([`batches`]), and their sizes.
pub(super) struct Batch {
    /// The slices, in the order of their parts and, within a part, of their triangles.
    pub(super) members: Vec<PartSlice>,
    pub(super) sizes: PartSizes,
}

/// Groups the parts of `object` into batches: parts with the same texture and the same
/// back-face culling kind are concatenated (their base colours baked into the vertex colours),
/// as long as the result fits the device's limits. Every draw call costs time of its own — on
/// lavapipe milliseconds for the LRT shading shader — and models often have many parts (the
/// 2CylinderEngine has 115, uploaded as one batch; the spider.obj 19, as 5). A part larger than
/// a batch may be ([`PartSizes::check`]: a storage buffer's binding size, the workgroup grid, the
/// draws' vertex counts) is first split into slices of triangles that fit ([`part_slices`]), so a
/// mesh of millions of triangles draws on an adapter with WebGPU's 128 MiB bindings.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when not even one triangle of a part fits.
pub(super) fn batches(
    limits: &DeviceLimits,
    object: &Object,
    culling: &[BackFaceCulling],
) -> Result<Vec<Batch>, GpuError> {
    let describe = |members: &[PartSlice]| describe_parts(object, members);
    // Open batches, one per key, with their running counts.
    let mut open: Vec<(BatchKey, Batch, u64, u64)> = Vec::new();
    let mut closed = Vec::new();
    for (index, part) in object.parts.iter().enumerate() {
        let key = BatchKey {
            texture: part
                .material
                .texture
                .as_ref()
                .map(|t| Arc::as_ptr(t) as usize),
            closed_outward: culling[index].closed_outward(),
        };
        for (slice, vertices) in part_slices(limits, object, index)? {
            let triangles = u64::from(slice.len());
            if let Some(position) = open.iter().position(|(k, ..)| *k == key) {
                let (_, batch, batch_triangles, batch_vertices) = &mut open[position];
                let mut members = batch.members.clone();
                members.push(slice.clone());
                let (t, v) = (*batch_triangles + triangles, *batch_vertices + vertices);
                if let Ok(sizes) = PartSizes::check(limits, &|| describe(&members), t, v) {
                    *batch = Batch { members, sizes };
                    (*batch_triangles, *batch_vertices) = (t, v);
                    continue;
                }
                closed.push(open.swap_remove(position).1);
            }
            let members = vec![slice];
            let sizes = PartSizes::check(limits, &|| describe(&members), triangles, vertices)?;
            open.push((key, Batch { members, sizes }, triangles, vertices));
        }
    }
    closed.extend(open.into_iter().map(|(_, batch, ..)| batch));
    Ok(closed)
}

/// Part `index` of `object` as slices of triangles that each fit one batch on the device, with
/// a bound on each slice's vertex count (its own vertices: a slice's triangles are uploaded
/// with the vertices they use, [`batch_geometry`]): the whole part when it fits, else the
/// fewest slices of equal size (± 1 triangle) that do.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] naming the part when not even one of its triangles fits.
fn part_slices(
    limits: &DeviceLimits,
    object: &Object,
    index: usize,
) -> Result<Vec<(PartSlice, u64)>, GpuError> {
    let mesh = &object.parts[index].mesh;
    let (triangles, vertices) = (mesh.triangles().len() as u64, mesh.positions().len() as u64);
    let whole = PartSlice {
        part: index,
        triangles: 0..u32::try_from(triangles).unwrap_or(u32::MAX),
    };
    let describe = || describe_parts(object, std::slice::from_ref(&whole));
    let check = |t: u64| PartSizes::check(limits, &describe, t, vertices.min(3 * t));
    if triangles <= u64::from(u32::MAX)
        && PartSizes::check(limits, &describe, triangles, vertices).is_ok()
    {
        return Ok(vec![(whole, vertices)]);
    }
    check(1)?;
    // The largest slice that fits (the sizes grow with the triangle count), by bisection.
    let (mut fits, mut too_many) = (1u64, triangles);
    while too_many - fits > 1 {
        let middle = fits + (too_many - fits) / 2;
        if check(middle).is_ok() {
            fits = middle;
        } else {
            too_many = middle;
        }
    }
    let count = triangles.div_ceil(fits);
    Ok((0..count)
        .map(|k| {
            // Slice k's triangles: the k-th of `count` near-equal runs (each ≤ `fits`).
            let start = (k * triangles / count) as u32;
            let end = ((k + 1) * triangles / count) as u32;
            let slice = PartSlice {
                part: index,
                triangles: start..end,
            };
            let bound = vertices.min(3 * u64::from(slice.len()));
            (slice, bound)
        })
        .collect())
}

/// Names the parts of slices `members` of `object` in messages, e.g. `parts 0, 3 of object
/// "ship"` (a part split into several slices is named once).
pub(super) fn describe_parts(object: &Object, members: &[PartSlice]) -> String {
    let mut parts: Vec<usize> = members.iter().map(|slice| slice.part).collect();
    parts.dedup();
    let list: Vec<String> = parts.iter().map(usize::to_string).collect();
    let noun = if parts.len() == 1 { "part" } else { "parts" };
    format!("{noun} {} of object {:?}", list.join(", "), object.name)
}

/// What parts must share to be batched.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct BatchKey {
    /// The texture's address (textures are shared between parts by `Arc`), if any.
    pub(super) texture: Option<usize>,
    /// Whether the part's back faces may be culled ([`BackFaceCulling::closed_outward`]).
    pub(super) closed_outward: bool,
}

/// Per batch of parts ([`Batch`]): buffers, texture and bind groups.
pub(super) struct PartResources {
    pub(super) uniforms: wgpu::Buffer,
    pub(super) bind_group: wgpu::BindGroup,
    pub(super) proxy_bind_group: wgpu::BindGroup,
    pub(super) lrt_bind_group: wgpu::BindGroup,
    pub(super) footprints: wgpu::Buffer,
    /// The arguments of its footprint and shading draws and its screen bound (WGSL
    /// `draw_args`), reset before every proxy pass.
    pub(super) draw_args: wgpu::Buffer,
    pub(super) sizes: PartSizes,
    pub(super) material: PartUniforms,
    /// The slices of the object's parts in this batch, in upload order (for splitting the
    /// footprints by part).
    pub(super) members: Vec<PartSlice>,
}

/// Per object: its uniform buffer, the culling rule of each of its parts, its batches, and its
/// BVH for the ray tracer.
pub(super) struct ObjectResources {
    pub(super) uniforms: wgpu::Buffer,
    pub(super) bind_group: wgpu::BindGroup,
    pub(super) culling: Vec<BackFaceCulling>,
    pub(super) parts: Vec<PartResources>,
    /// The object's BVH and box, for the ray tracer, or why it has none (the other methods
    /// render the object all the same).
    pub(super) ray_tracing: Result<ObjectRayTracing, GpuError>,
    /// Its meshes' extent, for the uniforms of a spinning or thrusting body.
    pub(super) extent: srt_scene::BodyExtent,
}

/// The vertices of the slices `members` of `object`'s parts, one slice after the other, each
/// colour multiplied by its part's base colour (so the batch's own base colour is white), and
/// their triangles with indices shifted to match. A whole part brings all its vertices; a slice
/// of a part only those its triangles use, in the order they are first used.
pub(super) fn batch_geometry(
    object: &Object,
    members: &[PartSlice],
) -> (Vec<GpuVertex>, Vec<[u32; 3]>) {
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for slice in members {
        let part = &object.parts[slice.part];
        let mesh = &part.mesh;
        let base = part.material.base_color;
        let vertex = |i: usize| {
            let color = mesh.colors().map_or([1.0; 4], |c| c[i]);
            GpuVertex {
                position: vec4(mesh.positions()[i], 1.0),
                normal: vec4(mesh.normals()[i], 0.0),
                color: [0, 1, 2, 3].map(|k| base[k] * color[k]),
                uv: [mesh.uvs()[i].x as f32, mesh.uvs()[i].y as f32, 0.0, 0.0],
            }
        };
        let own = &mesh.triangles()[slice.triangles.start as usize..slice.triangles.end as usize];
        // Checked by PartSizes: the batch's vertex count fits in u32.
        let first = vertices.len() as u32;
        if slice.is_whole(part) {
            vertices.extend((0..mesh.positions().len()).map(vertex));
            triangles.extend(own.iter().map(|t| t.map(|v| v + first)));
            continue;
        }
        // The slice's own numbering of the part's vertices it uses (u32::MAX: unused).
        let mut renumbered = vec![u32::MAX; mesh.positions().len()];
        for triangle in own {
            triangles.push(triangle.map(|v| {
                let number = &mut renumbered[v as usize];
                if *number == u32::MAX {
                    *number = vertices.len() as u32;
                    vertices.push(vertex(v as usize));
                }
                *number
            }));
        }
    }
    (vertices, triangles)
}

/// What every object's upload of one scene uses: the device, its pipelines, the frame-wide
/// buffers, and the part textures uploaded so far (each image once, however many batches show
/// it).
pub(super) struct Uploader<'a> {
    /// The device.
    pub(super) ctx: &'a GpuContext,
    /// The pipelines the bind groups are made for.
    pub(super) pipelines: &'a Pipelines,
    /// The frame-wide buffers every batch binds.
    pub(super) shared: FrameShared<'a>,
    /// The part textures uploaded so far.
    pub(super) textures: PartTextures,
}

/// Uploads one batch of `object`'s parts (sizes already checked), whose vertices and triangles
/// are `geometry`: its buffers, texture and bind groups.
pub(super) fn upload_batch(
    uploader: &Uploader<'_>,
    object: &Object,
    (batch, id): (Batch, u32),
    (vertices, triangles): &(Vec<GpuVertex>, Vec<[u32; 3]>),
) -> PartResources {
    let Uploader {
        ctx,
        pipelines,
        shared,
        textures,
    } = uploader;
    let device = &ctx.device;
    let Batch { members, sizes } = batch;
    let part = &object.parts[members[0].part];
    let image = part.material.texture.as_deref();
    let (texture, frame_height) = textures.of(ctx, part.material.texture.as_ref());
    let material = PartUniforms {
        // The base colours are in the vertex colours.
        base_color: [1.0; 4],
        flags: PartFlags::default()
            .with(PartFlags::TEXTURED, image.is_some())
            .with(PartFlags::VERTEX_COLOURS, true),
        triangle_count: sizes.triangles,
        id,
        frames: image.map_or(1, |t| t.frames),
        frame_height,
        frame_rate: image.map_or(0.0, |t| t.frame_rate as f32),
        padding: [0; 2],
    };
    let uniforms = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("srt part uniforms"),
        contents: bytemuck::bytes_of(&material),
        usage: BlockSpace::BUFFER_USAGES,
    });
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("srt vertices"),
        contents: bytemuck::cast_slice(vertices),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("srt indices"),
        contents: bytemuck::cast_slice(triangles),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let footprints = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("srt footprints"),
        size: sizes.footprint_bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let draw_args = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("srt footprint draw"),
        size: DRAW_ARGS_BYTES,
        // Read back (COPY_SRC) by `read_footprints` for its piece count.
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::INDIRECT
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(PART_GROUP.label),
        layout: &pipelines.part_layout,
        entries: &[
            slots::PART.entry(uniforms.as_entire_binding()),
            slots::VERTICES.entry(vertex_buffer.as_entire_binding()),
            slots::INDICES.entry(index_buffer.as_entire_binding()),
            slots::PART_TEXTURE.entry(wgpu::BindingResource::TextureView(&texture)),
        ],
    });
    let proxy_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(PROXY_OUTPUT_GROUP.label),
        layout: &pipelines.proxy_output_layout,
        entries: &[
            slots::PROXY_FOOTPRINTS.entry(footprints.as_entire_binding()),
            slots::PROXY_FRAME_BOUND.entry(shared.frame_bound.as_entire_binding()),
            slots::PROXY_DRAW_ARGS.entry(draw_args.as_entire_binding()),
        ],
    });
    let lrt_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(LRT_INPUT_GROUP.label),
        layout: &pipelines.lrt_input_layout,
        entries: &[
            slots::LRT_FOOTPRINTS.entry(footprints.as_entire_binding()),
            slots::FRAGMENT_COUNT.entry(shared.fragment_count.as_entire_binding()),
            slots::LRT_DRAW_ARGS.entry(draw_args.as_entire_binding()),
        ],
    });
    PartResources {
        uniforms,
        bind_group,
        proxy_bind_group,
        lrt_bind_group,
        footprints,
        draw_args,
        sizes,
        material,
        members,
    }
}

/// An object's BVH and its triangles in the BVH's leaf order, kept for the scene-wide shadow
/// buffer ([`crate::shadows`]), or why the object has none.
pub(super) type ShadowSource = Result<(ObjectBvh, Vec<GpuRtTriangle>), GpuError>;

/// Uploads one object (batch sizes already checked): its uniform buffer and batches, numbered
/// from `first_id`, and its BVH for the ray tracer; with `for_shadows` also hands back the BVH
/// and its triangles for the shadows of moving lights.
pub(super) fn upload_object(
    uploader: &Uploader<'_>,
    object: &Object,
    first_id: u32,
    (culling, batches): (Vec<BackFaceCulling>, Vec<Batch>),
    for_shadows: bool,
) -> (ObjectResources, Option<ShadowSource>) {
    let &Uploader {
        ctx,
        pipelines,
        shared,
        ..
    } = uploader;
    let uniforms = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("srt object uniforms"),
        size: size_of::<ObjectUniforms>() as u64,
        usage: BlockSpace::BUFFER_USAGES,
        mapped_at_creation: false,
    });
    let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(OBJECT_GROUP.label),
        layout: &pipelines.object_layout,
        entries: &[slots::OBJECT.entry(uniforms.as_entire_binding())],
    });
    let mut rt_triangles = Vec::new();
    let parts = batches
        .into_iter()
        .zip(first_id..)
        .map(|(batch, id)| {
            let geometry = batch_geometry(object, &batch.members);
            let (vertices, triangles) = &geometry;
            rt_triangles.extend(triangles.iter().zip(0..).map(|(&t, number)| {
                let [p0, p1, p2] = crate::bvh::corners(vertices, t);
                GpuRtTriangle {
                    p0,
                    part: id,
                    p1,
                    triangle: number,
                    p2,
                    padding: 0,
                }
            }));
            upload_batch(uploader, object, (batch, id), &geometry)
        })
        .collect();
    let bvh = object_bvh(ctx, &rt_triangles, &format!("object {:?}", object.name));
    let ray_tracing = bvh
        .as_ref()
        .map_err(Clone::clone)
        .map(|bvh| ObjectRayTracing::new(ctx, pipelines, shared, &rt_triangles, bvh));
    // A spinning or thrusting body casts no late shadow on the GPU (the shadow walk treats
    // casters as static in their rest frames): excluded rather than drawn at rest. The CPU
    // reference does shadow with it (srt-trace's `blocks`), so such scenes with moving lights
    // differ there.
    let shadow = (for_shadows && object.motion.is_rest()).then(|| {
        bvh.map(|bvh| {
            let ordered = bvh.in_leaf_order(&rt_triangles);
            (bvh, ordered)
        })
    });
    let resources = ObjectResources {
        uniforms,
        bind_group,
        culling,
        parts,
        ray_tracing,
        extent: object.body_extent(),
    };
    (resources, shadow)
}

#[cfg(test)]
mod tests {
    use srt_scene::SurfaceOptics;
    use std::sync::Arc;

    use glam::DVec3;
    use srt_physics::Frame;
    use srt_scene::shapes::cube;
    use srt_scene::{Material, Mesh, Object, Part, Texture};

    use super::{BackFaceCulling, batches};
    use crate::limits::DeviceLimits;

    fn limits(max_storage_buffer_binding_size: u64) -> DeviceLimits {
        DeviceLimits {
            limits: wgpu::Limits {
                max_storage_buffer_binding_size,
                ..wgpu::Limits::downlevel_defaults()
            },
            adapter: "test".to_owned(),
        }
    }

    /// An object at rest at the origin named `name`, of `parts`.
    fn object(name: &str, parts: Vec<Part>) -> Object {
        Object {
            name: name.to_owned(),
            parts,
            frame: Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap(),
            rest_time_shift: 0.0,
            wireframe: None,
            optics: SurfaceOptics::default(),
            clock: None,
            motion: Default::default(),
        }
    }

    fn part(mesh: Mesh, texture: Option<&Arc<Texture>>) -> Part {
        Part {
            mesh,
            material: Material {
                texture: texture.cloned(),
                ..Material::default()
            },
        }
    }

    /// Parts with the same texture and culling kind share a batch; textures and open meshes
    /// keep theirs apart; the order within a batch is the parts' order.
    #[test]
    fn parts_are_batched_by_texture_and_culling_kind() {
        let texture = Arc::new(Texture::still(1, 1, vec![[255; 4]], "test".to_owned()));
        let open = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let object = object(
            "test",
            vec![
                part(cube(1.0, 1), None),
                part(open.clone(), None),
                part(cube(2.0, 2), None),
                part(cube(1.0, 1), Some(&texture)),
                part(open, None),
                part(cube(1.0, 1), Some(&texture)),
            ],
        );
        let culling: Vec<BackFaceCulling> = object
            .parts
            .iter()
            .map(|p| BackFaceCulling::for_mesh(&p.mesh))
            .collect();
        let mut groups: Vec<Vec<usize>> = batches(&limits(1 << 27), &object, &culling)
            .unwrap()
            .into_iter()
            .map(|b| b.members.iter().map(|slice| slice.part).collect())
            .collect();
        groups.sort();
        assert_eq!(groups, vec![vec![0, 2], vec![1, 4], vec![3, 5]]);
    }

    /// A batch closes when the next part would exceed a storage-buffer limit; a part that does
    /// not fit alone is split into slices; one whose single triangle does not fit is an error
    /// naming it.
    #[test]
    fn batches_stay_within_the_device_limits() {
        // A storage-buffer limit of the footprint buffer of two parts (the largest buffer of a
        // batch): two parts fit in a batch, three do not.
        let object = object("cubes", (0..3).map(|_| part(cube(1.0, 4), None)).collect());
        let culling = vec![BackFaceCulling::for_mesh(&object.parts[0].mesh); 3];
        let triangles = object.parts[0].mesh.triangles().len() as u64;
        let two = crate::types::footprint_slots(2 * triangles)
            * size_of::<crate::types::GpuFootprint>() as u64;
        let sizes: Vec<usize> = batches(&limits(two), &object, &culling)
            .unwrap()
            .iter()
            .map(|b| b.members.len())
            .collect();
        assert_eq!(sizes.iter().sum::<usize>(), 3);
        assert!(sizes.iter().all(|&n| n <= 2), "{sizes:?}");
        let error = batches(&limits(100), &object, &culling)
            .err()
            .expect("a part larger than the limit");
        assert!(
            error.to_string().contains("part 0 of object \"cubes\""),
            "{error}"
        );
    }

    /// A part larger than a batch may be is split into near-equal slices, each within the
    /// limits, covering its triangles once and in order; their geometry holds the vertices each
    /// slice uses, renumbered, and draws the part's triangles.
    #[test]
    fn a_part_too_large_for_a_batch_is_sliced() {
        let mesh = cube(1.0, 20);
        let object = object("big", vec![part(mesh.clone(), None)]);
        let culling = vec![BackFaceCulling::for_mesh(&mesh)];
        let total = mesh.triangles().len() as u64;
        // Room for the footprints of a bit over a quarter of the triangles.
        let limit = crate::types::footprint_slots(total / 4 + 7)
            * size_of::<crate::types::GpuFootprint>() as u64;
        let sliced = batches(&limits(limit), &object, &culling).unwrap();
        let slices: Vec<_> = sliced.iter().flat_map(|b| b.members.clone()).collect();
        assert_eq!(slices.len(), 4, "{slices:?}");
        assert_eq!(slices[0].triangles.start, 0);
        assert_eq!(slices[3].triangles.end as u64, total);
        assert!(
            slices
                .windows(2)
                .all(|w| w[0].triangles.end == w[1].triangles.start)
        );
        let lengths: Vec<u32> = slices.iter().map(super::PartSlice::len).collect();
        assert!(lengths.iter().max().unwrap() - lengths.iter().min().unwrap() <= 1);
        for batch in &sliced {
            assert!(batch.sizes.footprint_bytes <= limit);
            let (vertices, triangles) = super::batch_geometry(&object, &batch.members);
            assert!(vertices.len() < mesh.positions().len());
            let first = batch.members[0].triangles.start as usize;
            for (k, triangle) in triangles.iter().enumerate() {
                let original = mesh.triangles()[first + k];
                for corner in 0..3 {
                    let position = vertices[triangle[corner] as usize].position;
                    let expected = mesh.positions()[original[corner] as usize];
                    assert_eq!(position[..3], expected.as_vec3().to_array());
                }
            }
        }
    }
}
