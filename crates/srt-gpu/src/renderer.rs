//! The GPU renderer: uploads a scene once, then renders it (local ray tracing or the polygon
//! baseline) for any observer, time, velocities and effect mode with the same mesh structure,
//! and reads the image back.
//!
//! Everything the renderer allocates is checked against the device's limits first
//! ([`crate::limits`]), so a scene or image size the adapter cannot serve is a
//! [`GpuError::ExceedsLimit`] before any GPU object exists.

use std::sync::Arc;

use srt_color::{TemperatureLut, ToneMap, quantize_8bit, searchlight_reference_ln_y};
use srt_scene::mip::{MipChain, MipLevel};
use srt_scene::{Object, Part, Scene, Texture};
use wgpu::util::DeviceExt as _;

use crate::context::{GpuContext, GpuError};
use crate::culling::BackFaceCulling;
use crate::limits::DeviceLimits;
use crate::lut::{lut_params, lut_texture};
use crate::pipelines::{
    DEPTH_FORMAT, FRAME_GROUP, LRT_INPUT_GROUP, OBJECT_GROUP, PART_GROUP, POLYGON_FRAME_GROUP,
    PROXY_OUTPUT_GROUP, Pipelines, RT_INPUT_GROUP, SHADE_FRAME_GROUP, VISIBLE_ID_FORMAT, slots,
};
use crate::projection::view_projection;
use crate::ray_tracing::{BOX_TRIANGLES, ObjectRayTracing};
use crate::readback::{TextureReadback, texel_bytes};
use crate::shaders::WORKGROUP_SIZE;
use crate::sky::{SkyResources, sky_shape};
use crate::spectral::SpectralTables;
use crate::types::{
    DRAW_ARGS_BYTES, EffectsCode, FOOTPRINT_VERTICES, FRAGMENT_COUNTER_BYTES, FootprintCode,
    FrameUniforms, GpuFootprint, GpuFrame, GpuRtTriangle, GpuVertex, ObjectUniforms,
    PART_BOUND_BYTES, PartFlags, PartUniforms, SHADE_DRAW_OFFSET, SurfaceColourCode, ToneMapCode,
    footprint_slots, mat4, optics4, vec4,
};

/// LRT depth = apparent distance × this (apparent distances up to 10⁶ are ordered correctly;
/// f32 depth has constant relative precision, so the scale costs nothing).
const LRT_DEPTH_SCALE: f32 = 1e-6;

/// Which rendering method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Exact per pixel, each object by whichever of [`Method::Lrt`] and [`Method::Rt`] is faster
    /// for it (by the layers of its triangles, `ObjectRayTracing::preferred`); the two compose
    /// through the depth test.
    #[default]
    Auto,
    /// Local ray tracing (the paper's method, exact per pixel): one footprint per triangle.
    Lrt,
    /// Ray tracing through a BVH per batch of parts in its rest frame (the reference's
    /// algorithm on the GPU), exact per pixel like LRT; its cost does not grow with the layers
    /// of a deep model or with footprints swept beside the camera.
    Rt,
    /// Per-vertex photo-object polygon rendering (§3.2), the approximate baseline.
    Polygon,
}

impl Method {
    /// Whether the method is exact per pixel (what the CPU reference computes).
    #[must_use]
    pub const fn is_exact(self) -> bool {
        !matches!(self, Self::Polygon)
    }

    /// The name used on the command line.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Lrt => "lrt",
            Self::Rt => "rt",
            Self::Polygon => "polygon",
        }
    }
}

/// Which footprint the LRT pass rasterises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FootprintShape {
    /// The convex hull (3–6 points).
    #[default]
    Hull,
    /// The window-aligned rectangle (the paper's choice).
    Rectangle,
}

impl From<FootprintShape> for FootprintCode {
    fn from(shape: FootprintShape) -> Self {
        match shape {
            FootprintShape::Hull => Self::HULL,
            FootprintShape::Rectangle => Self::RECTANGLE,
        }
    }
}

/// A rendered image read back from the GPU: display colours (sRGB-encoded, [0, 1]), RGBA.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major pixels from the top.
    pub pixels: Vec<[f32; 4]>,
}

impl GpuImage {
    /// 8-bit sRGB pixels, rounded as the CPU reference rounds.
    #[must_use]
    pub fn to_rgb8(&self) -> Vec<[u8; 3]> {
        self.pixels
            .iter()
            .map(|p| [p[0], p[1], p[2]].map(|c| quantize_8bit(f64::from(c))))
            .collect()
    }
}

/// Timing and work counters of one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameStats {
    /// GPU time of the passes in milliseconds, where timestamp queries are supported.
    pub gpu_time_ms: Option<f64>,
    /// GPU time of the LRT's footprint (proxy) pass alone, in milliseconds, where timestamp
    /// queries are supported (`None` for the polygon method).
    pub proxy_time_ms: Option<f64>,
    /// The LRT pass's fragments, when the renderer counts them
    /// ([`GpuRenderer::set_fragment_counting`]; zero for the polygon method).
    pub fragments: Option<FragmentCounts>,
}

/// What the LRT pass's fragment shader did in one frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FragmentCounts {
    /// Fragment shader invocations (one per footprint pixel that passed the rasteriser).
    pub run: u64,
    /// Those whose ray hit the triangle and were shaded (the rest discard).
    pub shaded: u64,
}

/// One batch's buffer sizes and counts, checked against the device's limits before upload.
struct PartSizes {
    triangles: u32,
    footprint_bytes: u64,
    /// Workgroup grid of the proxy pass.
    workgroups: (u32, u32),
}

impl PartSizes {
    /// The sizes of a batch of `triangles` triangles and `vertices` vertices, named in messages
    /// by `describe` (e.g. `parts 0, 3 of object "ship"`).
    fn check(
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

/// Parts of one object uploaded and drawn together ([`batches`]), and their sizes.
struct Batch {
    /// Indices of the parts in the object, ascending.
    members: Vec<usize>,
    sizes: PartSizes,
}

/// Groups the parts of `object` into batches: parts with the same texture and the same
/// back-face culling kind are concatenated (their base colours baked into the vertex colours),
/// as long as the result fits the device's limits. Every draw call costs time of its own — on
/// lavapipe milliseconds for the LRT shading shader — and models often have many parts (the
/// 2CylinderEngine has 115, uploaded as one batch; the spider.obj 19, as 5).
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when a single part does not fit.
fn batches(
    limits: &DeviceLimits,
    object: &Object,
    culling: &[BackFaceCulling],
) -> Result<Vec<Batch>, GpuError> {
    let describe = |members: &[usize]| describe_parts(object, members);
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
            culling: culling[index],
        };
        let (triangles, vertices) = (
            part.mesh.triangles().len() as u64,
            part.mesh.positions().len() as u64,
        );
        if let Some(position) = open.iter().position(|(k, ..)| *k == key) {
            let (_, batch, batch_triangles, batch_vertices) = &mut open[position];
            let mut members = batch.members.clone();
            members.push(index);
            let (t, v) = (*batch_triangles + triangles, *batch_vertices + vertices);
            if let Ok(sizes) = PartSizes::check(limits, &|| describe(&members), t, v) {
                *batch = Batch { members, sizes };
                (*batch_triangles, *batch_vertices) = (t, v);
                continue;
            }
            closed.push(open.swap_remove(position).1);
        }
        let members = vec![index];
        let sizes = PartSizes::check(limits, &|| describe(&members), triangles, vertices)?;
        open.push((key, Batch { members, sizes }, triangles, vertices));
    }
    closed.extend(open.into_iter().map(|(_, batch, ..)| batch));
    Ok(closed)
}

/// Names parts `members` of `object` in messages, e.g. `parts 0, 3 of object "ship"`.
fn describe_parts(object: &Object, members: &[usize]) -> String {
    let list: Vec<String> = members.iter().map(usize::to_string).collect();
    let noun = if members.len() == 1 { "part" } else { "parts" };
    format!("{noun} {} of object {:?}", list.join(", "), object.name)
}

/// What parts must share to be batched.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct BatchKey {
    /// The texture's address (textures are shared between parts by `Arc`), if any.
    texture: Option<usize>,
    culling: BackFaceCulling,
}

/// Per batch of parts ([`Batch`]): buffers, texture and bind groups.
struct PartResources {
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    proxy_bind_group: wgpu::BindGroup,
    lrt_bind_group: wgpu::BindGroup,
    footprints: wgpu::Buffer,
    /// The part's screen bound (WGSL `part_bound`), cleared before every proxy pass.
    bound: wgpu::Buffer,
    /// The arguments of its footprint draw (WGSL `draw_args`), reset before every proxy pass.
    draw_args: wgpu::Buffer,
    sizes: PartSizes,
    material: PartUniforms,
    /// The object's parts in this batch, ascending, and their triangle counts (for splitting
    /// the footprints by part).
    members: Vec<(usize, u32)>,
}

/// Per object: its uniform buffer, the culling rule of each of its parts, its batches, and its
/// BVH for the ray tracer.
struct ObjectResources {
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    culling: Vec<BackFaceCulling>,
    parts: Vec<PartResources>,
    /// The object's BVH and box, for the ray tracer, or why it has none (the other methods
    /// render the object all the same).
    ray_tracing: Result<ObjectRayTracing, GpuError>,
}

/// Render targets, the readback of the colour and the LRT shading pass's frame bind groups
/// (which bind the id target) for one image size.
struct Targets {
    width: u32,
    height: u32,
    color: wgpu::Texture,
    depth: wgpu::Texture,
    /// The LRT visibility pass's (part id, triangle) per pixel.
    ids: wgpu::Texture,
    /// [`SHADE_FRAME_GROUP`] per tone map, indexed as [`ToneMap::ALL`].
    shade_frame_groups: Vec<wgpu::BindGroup>,
    readback: TextureReadback,
}

impl Targets {
    /// Checks the size against the device's limits, then creates the targets.
    fn new(
        ctx: &GpuContext,
        width: u32,
        height: u32,
        pipelines: &Pipelines,
        frame: &FrameResources,
    ) -> Result<Self, GpuError> {
        DeviceLimits::of(ctx).check_render_target(width, height, texel_bytes(ctx.color_format)?)?;
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = |label, format, usage| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let ids = texture(
            "srt visible ids",
            VISIBLE_ID_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let ids_view = ids.create_view(&wgpu::TextureViewDescriptor::default());
        let shade_frame_groups = frame
            .lut_views
            .iter()
            .map(|lut| {
                let [cie, scale, coefficients] = frame.spectral.entries();
                ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(SHADE_FRAME_GROUP.label),
                    layout: &pipelines.shade_frame_layout,
                    entries: &[
                        slots::FRAME_UNIFORMS.entry(frame.uniforms.as_entire_binding()),
                        slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(lut)),
                        slots::VISIBLE_IDS.entry(wgpu::BindingResource::TextureView(&ids_view)),
                        cie,
                        scale,
                        coefficients,
                    ],
                })
            })
            .collect();
        Ok(Self {
            width,
            height,
            color: texture(
                "srt color",
                ctx.color_format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::TEXTURE_BINDING,
            ),
            depth: texture(
                "srt depth",
                DEPTH_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            ),
            ids,
            shade_frame_groups,
            readback: TextureReadback::new(ctx, width, height, ctx.color_format)?,
        })
    }
}

/// The frame uniforms and, per tone map, the colour table bound with them; the spectral tables.
struct FrameResources {
    uniforms: wgpu::Buffer,
    /// One bind group per tone map, indexed as [`ToneMap::ALL`] (the colour tables differ).
    bind_groups: Vec<wgpu::BindGroup>,
    /// [`POLYGON_FRAME_GROUP`] per tone map, indexed as [`ToneMap::ALL`].
    polygon_groups: Vec<wgpu::BindGroup>,
    /// The tables of spectral colour (also bound by [`SHADE_FRAME_GROUP`]).
    spectral: SpectralTables,
    /// The colour-table parameters, indexed as [`ToneMap::ALL`].
    lut_params: Vec<[f32; 4]>,
    /// The colour tables, indexed as [`ToneMap::ALL`] (also bound by [`SHADE_FRAME_GROUP`]).
    lut_views: Vec<wgpu::TextureView>,
}

impl FrameResources {
    fn new(ctx: &GpuContext, pipelines: &Pipelines) -> Result<Self, GpuError> {
        let uniforms = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt frame uniforms"),
            size: size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let spectral = SpectralTables::new(ctx)?;
        let mut bind_groups = Vec::new();
        let mut polygon_groups = Vec::new();
        let mut params = Vec::new();
        let mut lut_views = Vec::new();
        for tone_map in ToneMap::ALL {
            let lut = TemperatureLut::with_defaults(tone_map);
            params.push(lut_params(&lut));
            let view = lut_texture(ctx, &lut)?.create_view(&wgpu::TextureViewDescriptor::default());
            bind_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(FRAME_GROUP.label),
                layout: &pipelines.frame_layout,
                entries: &[
                    slots::FRAME_UNIFORMS.entry(uniforms.as_entire_binding()),
                    slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(&view)),
                ],
            }));
            let [cie, scale, coefficients] = spectral.entries();
            polygon_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(POLYGON_FRAME_GROUP.label),
                layout: &pipelines.polygon_frame_layout,
                entries: &[
                    slots::FRAME_UNIFORMS.entry(uniforms.as_entire_binding()),
                    slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(&view)),
                    cie,
                    scale,
                    coefficients,
                ],
            }));
            lut_views.push(view);
        }
        Ok(Self {
            uniforms,
            bind_groups,
            polygon_groups,
            spectral,
            lut_params: params,
            lut_views,
        })
    }

    /// Index of `tone_map` in [`ToneMap::ALL`].
    fn tone_index(tone_map: ToneMap) -> usize {
        ToneMap::ALL
            .iter()
            .position(|&t| t == tone_map)
            .unwrap_or_default()
    }
}

/// The LRT pass's fragment counter and the buffer it is read back through.
struct FragmentCounter {
    counter: wgpu::Buffer,
    readback: wgpu::Buffer,
}

impl FragmentCounter {
    fn new(device: &wgpu::Device) -> Self {
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: FRAGMENT_COUNTER_BYTES,
                usage,
                mapped_at_creation: false,
            })
        };
        Self {
            counter: buffer(
                "srt fragment counter",
                wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
            ),
            readback: buffer(
                "srt fragment counter readback",
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            ),
        }
    }
}

/// Timestamp queries around the two passes (begin and end of each), where supported.
struct Timestamps {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
}

/// Timestamps written per frame: begin and end of the proxy pass (0, 1) and of the render
/// passes (2, 3), and the beginning of the sky's passes (4), which precede the render passes,
/// so that every method's frame time includes them.
const TIMESTAMP_COUNT: u32 = 5;

/// The timestamp written at the beginning of the sky's passes.
const SKY_TIMESTAMP: u32 = 4;

impl Timestamps {
    fn new(device: &wgpu::Device) -> Self {
        let bytes = u64::from(TIMESTAMP_COUNT) * size_of::<u64>() as u64;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        Self {
            set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("srt timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: TIMESTAMP_COUNT,
            }),
            resolve: buffer(
                "srt timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "srt timestamp readback",
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            ),
        }
    }
}

/// A scene uploaded to the GPU, ready to render.
pub struct GpuRenderer {
    pipelines: Pipelines,
    frame: FrameResources,
    objects: Vec<ObjectResources>,
    counter: FragmentCounter,
    timestamps: Option<Timestamps>,
    targets: Targets,
    /// The stars, if the scene has a sky.
    sky: Option<SkyResources>,
    /// Factor on every star's light ([`GpuRenderer::set_star_light_scale`]).
    star_light_scale: f64,
    /// Whether the LRT pass counts its fragments.
    count_fragments: bool,
    /// Whether the LRT draws take their vertex counts from the proxy pass
    /// ([`GpuContext::indirect_draws`]).
    indirect_draws: bool,
}

/// `texture` with its mip chain (levels larger than the device allows are skipped), or, for
/// `None`, a 1×1 white texture.
pub(crate) fn part_texture(ctx: &GpuContext, texture: Option<&Texture>) -> wgpu::TextureView {
    let limit = ctx.device.limits().max_texture_dimension_2d;
    let white = MipLevel {
        width: 1,
        height: 1,
        texels: vec![[255; 4]],
    };
    let chain = texture.map(MipChain::new);
    let mut levels: Vec<&MipLevel> = chain.as_ref().map_or_else(Vec::new, |chain| {
        chain
            .levels()
            .iter()
            .filter(|l| l.width <= limit && l.height <= limit)
            .collect()
    });
    if levels.is_empty() {
        levels.push(&white);
    }
    let data: Vec<u8> = levels
        .iter()
        .flat_map(|l| l.texels.iter().flatten().copied())
        .collect();
    let texture = ctx.device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: Some("srt part texture"),
            size: wgpu::Extent3d {
                width: levels[0].width,
                height: levels[0].height,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}

/// The vertices of `parts`, one after the other, each colour multiplied by its part's base
/// colour (so the batch's own base colour is white), and their triangles with indices shifted
/// to match.
fn batch_geometry(parts: &[&Part]) -> (Vec<GpuVertex>, Vec<[u32; 3]>) {
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for part in parts {
        let mesh = &part.mesh;
        let base = part.material.base_color;
        // Checked by PartSizes: the batch's vertex count fits in u32.
        let first = vertices.len() as u32;
        vertices.extend((0..mesh.positions().len()).map(|i| {
            let color = mesh.colors().map_or([1.0; 4], |c| c[i]);
            GpuVertex {
                position: vec4(mesh.positions()[i], 1.0),
                normal: vec4(mesh.normals()[i], 0.0),
                color: [0, 1, 2, 3].map(|k| base[k] * color[k]),
                uv: [mesh.uvs()[i].x as f32, mesh.uvs()[i].y as f32, 0.0, 0.0],
            }
        }));
        triangles.extend(mesh.triangles().iter().map(|t| t.map(|v| v + first)));
    }
    (vertices, triangles)
}

/// Uploads one batch of `object`'s parts (sizes already checked), whose vertices and triangles
/// are `geometry`: its buffers, texture and bind groups.
fn upload_batch(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    counter: &FragmentCounter,
    object: &Object,
    (batch, id): (Batch, u32),
    (vertices, triangles): &(Vec<GpuVertex>, Vec<[u32; 3]>),
) -> PartResources {
    let device = &ctx.device;
    let Batch { members, sizes } = batch;
    let parts: Vec<&Part> = members.iter().map(|&i| &object.parts[i]).collect();
    let part = parts[0];
    let material = PartUniforms {
        // The base colours are in the vertex colours.
        base_color: [1.0; 4],
        flags: PartFlags::default()
            .with(PartFlags::TEXTURED, part.material.texture.is_some())
            .with(PartFlags::VERTEX_COLOURS, true),
        triangle_count: sizes.triangles,
        id,
        padding: 0,
    };
    let uniforms = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("srt part uniforms"),
        contents: bytemuck::bytes_of(&material),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
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
    let bound = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("srt part bound"),
        size: PART_BOUND_BYTES,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
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
    let texture = part_texture(ctx, part.material.texture.as_deref());
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
            slots::PROXY_PART_BOUND.entry(bound.as_entire_binding()),
            slots::PROXY_DRAW_ARGS.entry(draw_args.as_entire_binding()),
        ],
    });
    let lrt_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(LRT_INPUT_GROUP.label),
        layout: &pipelines.lrt_input_layout,
        entries: &[
            slots::LRT_FOOTPRINTS.entry(footprints.as_entire_binding()),
            slots::FRAGMENT_COUNT.entry(counter.counter.as_entire_binding()),
            slots::LRT_PART_BOUND.entry(bound.as_entire_binding()),
        ],
    });
    PartResources {
        uniforms,
        bind_group,
        proxy_bind_group,
        lrt_bind_group,
        footprints,
        bound,
        draw_args,
        sizes,
        material,
        members: parts
            .iter()
            .zip(&members)
            .map(|(part, &index)| (index, part.mesh.triangles().len() as u32))
            .collect(),
    }
}

/// Uploads one object (batch sizes already checked): its uniform buffer and batches, numbered
/// from `first_id`.
fn upload_object(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    counter: &FragmentCounter,
    object: &Object,
    first_id: u32,
    (culling, batches): (Vec<BackFaceCulling>, Vec<Batch>),
) -> ObjectResources {
    let uniforms = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("srt object uniforms"),
        size: size_of::<ObjectUniforms>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
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
            let members: Vec<&Part> = batch.members.iter().map(|&i| &object.parts[i]).collect();
            let geometry = batch_geometry(&members);
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
            upload_batch(ctx, pipelines, counter, object, (batch, id), &geometry)
        })
        .collect();
    let ray_tracing =
        ObjectRayTracing::new(ctx, pipelines, &counter.counter, &rt_triangles, || {
            format!("object {:?}", object.name)
        });
    ObjectResources {
        uniforms,
        bind_group,
        culling,
        parts,
        ray_tracing,
    }
}

impl GpuRenderer {
    /// Uploads `scene` (meshes, textures, colour tables) for images of `width` × `height`.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the image or a mesh exceeds the device's limits (checked
    /// before anything is allocated), or any wgpu error.
    pub fn new(ctx: &GpuContext, scene: &Scene, width: u32, height: u32) -> Result<Self, GpuError> {
        let limits = DeviceLimits::of(ctx);
        limits.check_render_target(width, height, texel_bytes(ctx.color_format)?)?;
        let sizes = scene
            .objects
            .iter()
            .map(|object| {
                let culling: Vec<BackFaceCulling> = object
                    .parts
                    .iter()
                    .map(|part| BackFaceCulling::for_mesh(&part.mesh))
                    .collect();
                let batches = batches(&limits, object, &culling)?;
                Ok((culling, batches))
            })
            .collect::<Result<Vec<_>, GpuError>>()?;
        let device = &ctx.device;
        let pipelines = Pipelines::new(device, ctx.color_format);
        let frame = FrameResources::new(ctx, &pipelines)?;
        let counter = FragmentCounter::new(device);
        // Batches are numbered from 1 across the scene (0 marks "no triangle" in the LRT's ids).
        let mut first_id = 1u32;
        let objects = scene
            .objects
            .iter()
            .zip(sizes)
            .map(|(object, sizes)| {
                let id = first_id;
                first_id += sizes.1.len() as u32;
                upload_object(ctx, &pipelines, &counter, object, id, sizes)
            })
            .collect();
        let renderer = Self {
            timestamps: ctx.timestamps.then(|| Timestamps::new(device)),
            targets: Targets::new(ctx, width, height, &pipelines, &frame)?,
            sky: SkyResources::new(ctx, scene, width, height)?,
            star_light_scale: 1.0,
            pipelines,
            frame,
            objects,
            counter,
            count_fragments: false,
            indirect_draws: ctx.indirect_draws,
        };
        ctx.take_errors()?;
        Ok(renderer)
    }

    /// Multiplies every star's light by `scale` (default 1). A caller that renders at k× the
    /// output size and box-filters down (supersampling) sets k², so that each star brings the
    /// same light to the output pixels as in the CPU reference, where it lands in one output
    /// pixel's samples.
    pub fn set_star_light_scale(&mut self, scale: f64) {
        self.star_light_scale = scale;
    }

    /// Makes the LRT passes count the fragments they run and shade
    /// ([`FrameStats::fragments`]), or stop counting. Counting is for measurements: it costs
    /// global atomics per fragment.
    pub fn set_fragment_counting(&mut self, counting: bool) {
        self.count_fragments = counting;
    }

    /// Per object, its surface over its box's surface (the layers of triangles `auto` weighs,
    /// `ObjectRayTracing::preferred`), or `None` where it has no ray tracer.
    #[must_use]
    pub fn object_layers(&self) -> Vec<Option<f64>> {
        self.objects
            .iter()
            .map(|o| o.ray_tracing.as_ref().ok().map(ObjectRayTracing::layers))
            .collect()
    }

    /// Image width and height.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.targets.width, self.targets.height)
    }

    /// Changes the image size (recreates the render targets).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the size exceeds the device's limits; the renderer then
    /// keeps its previous size.
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) -> Result<(), GpuError> {
        if (width, height) != self.size() {
            let targets = Targets::new(ctx, width, height, &self.pipelines, &self.frame)?;
            if let Some(sky) = &mut self.sky {
                sky.resize(ctx, width, height)?;
            }
            self.targets = targets;
        }
        Ok(())
    }

    /// The texture the last frame was rendered into, for display.
    #[must_use]
    pub fn color_texture(&self) -> &wgpu::Texture {
        &self.targets.color
    }

    /// Writes the per-frame uniforms for `scene` (observer, light, effects, velocities);
    /// returns the tone map's index in [`ToneMap::ALL`].
    fn write_uniforms(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        footprint: FootprintShape,
    ) -> Result<usize, GpuError> {
        if scene.objects.len() != self.objects.len()
            || scene
                .objects
                .iter()
                .zip(&self.objects)
                .any(|(o, r)| o.parts.len() != r.culling.len())
        {
            return Err(GpuError::SceneChanged);
        }
        let uploaded_sky = self.sky.as_ref().map_or((0, None), SkyResources::shape);
        if sky_shape(&scene.sky) != uploaded_sky {
            return Err(GpuError::SceneChanged);
        }
        if let Some(sky) = &self.sky {
            sky.write_uniforms(ctx, scene, self.star_light_scale);
        }
        let (width, height) = self.size();
        let aspect = f64::from(width) / f64::from(height);
        let observer = &scene.observer;
        let (forward, right, up) = observer.basis();
        let tan_half = (0.5 * observer.fov_y_deg.to_radians()).tan();
        let tone = FrameResources::tone_index(scene.tone_map);
        let uniforms = FrameUniforms {
            view_projection: mat4(view_projection(observer, width, height)),
            camera_forward: vec4(forward, 0.0),
            camera_right: vec4(right * tan_half * aspect, 0.0),
            camera_up: vec4(up * tan_half, 0.0),
            observer: vec4(observer.position, observer.ct),
            light: vec4(scene.light.position, scene.light.temperature_k),
            shading: [
                scene.shading.ambient as f32,
                scene.shading.diffuse as f32,
                scene.shading.specular as f32,
                scene.shading.shininess as f32,
            ],
            background: vec4(scene.background, 1.0),
            lut: self.frame.lut_params[tone],
            viewport: [
                width as f32,
                height as f32,
                1.0 / width as f32,
                1.0 / height as f32,
            ],
            effects: EffectsCode::from(scene.effects),
            footprint_shape: FootprintCode::from(footprint),
            depth_scale: LRT_DEPTH_SCALE,
            colour: SurfaceColourCode::from(scene.colour),
            tone_map: ToneMapCode::from(scene.tone_map),
            exposure: scene.exposure as f32,
            searchlight_ln_y: searchlight_reference_ln_y() as f32,
            padding: 0,
        };
        ctx.queue
            .write_buffer(&self.frame.uniforms, 0, bytemuck::bytes_of(&uniforms));
        let event = observer.event();
        for (object, resources) in scene.objects.iter().zip(&self.objects) {
            let uniforms = ObjectUniforms {
                frame: GpuFrame::new(&object.frame, event),
                style: [object.wireframe.unwrap_or(0.0) as f32, 0.0, 0.0, 0.0],
                optics: optics4(&object.optics),
            };
            ctx.queue
                .write_buffer(&resources.uniforms, 0, bytemuck::bytes_of(&uniforms));
            for batch in &resources.parts {
                // Back faces of a batch of closed solids are hidden when the observer is
                // outside every one of them.
                let cull = batch.members.iter().all(|&(index, _)| {
                    resources.culling[index].applies(
                        &object.parts[index].mesh,
                        &object.frame,
                        event,
                    )
                });
                let mut material = batch.material;
                material.flags = material.flags.with(PartFlags::CULL_BACK_FACES, cull);
                ctx.queue
                    .write_buffer(&batch.uniforms, 0, bytemuck::bytes_of(&material));
            }
            if let Ok(rt) = &resources.ray_tracing {
                rt.write_culling(&ctx.queue, object.frame.to_rest(event).position);
            }
        }
        Ok(tone)
    }

    /// Records the passes of one frame into `encoder`, leaving the image in
    /// [`GpuRenderer::color_texture`].
    ///
    /// # Errors
    /// [`GpuError::SceneChanged`] if the scene's structure differs from the uploaded one.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
    ) -> Result<(), GpuError> {
        let tone = self.write_uniforms(ctx, scene, footprint)?;
        let traced = self.traced_objects(method)?;
        if self.count_fragments {
            encoder.clear_buffer(&self.counter.counter, 0, None);
        }
        if method != Method::Polygon {
            let no_draw = wgpu::util::DrawIndirectArgs {
                vertex_count: 0,
                instance_count: 1,
                first_vertex: 0,
                first_instance: 0,
            };
            // Both draws empty, no piece slot taken.
            let both = [no_draw.as_bytes(), no_draw.as_bytes(), &[0; 4]].concat();
            let mut outputs: Vec<(&wgpu::Buffer, &wgpu::Buffer)> = Vec::new();
            for (object, traced) in self.objects.iter().zip(&traced) {
                match traced {
                    Some(rt) => outputs.push((&rt.box_bound, &rt.box_draw_args)),
                    None => outputs.extend(object.parts.iter().map(|p| (&p.bound, &p.draw_args))),
                }
            }
            for (bound, draw_args) in outputs {
                encoder.clear_buffer(bound, 0, None);
                ctx.queue.write_buffer(draw_args, 0, &both);
            }
            self.encode_proxy_pass(encoder, tone, &traced);
        }
        self.encode_render_pass(&ctx.device, encoder, scene, method, tone, &traced);
        if let Some(t) = &self.timestamps {
            encoder.resolve_query_set(&t.set, 0..TIMESTAMP_COUNT, &t.resolve, 0);
            encoder.copy_buffer_to_buffer(&t.resolve, 0, &t.readback, 0, t.resolve.size());
        }
        if self.count_fragments {
            encoder.copy_buffer_to_buffer(
                &self.counter.counter,
                0,
                &self.counter.readback,
                0,
                FRAGMENT_COUNTER_BYTES,
            );
        }
        Ok(())
    }

    /// Per object, its ray tracer if `method` traces it through its BVH (`None`: LRT, its
    /// footprints): every object for [`Method::Rt`], none for [`Method::Lrt`] and
    /// [`Method::Polygon`], and for [`Method::Auto`] those for which
    /// [`ObjectRayTracing::preferred`] says so.
    ///
    /// # Errors
    /// Why an object has no ray tracer, when [`Method::Rt`] needs it.
    fn traced_objects(&self, method: Method) -> Result<Vec<Option<&ObjectRayTracing>>, GpuError> {
        self.objects
            .iter()
            .map(|object| match (method, &object.ray_tracing) {
                (Method::Rt, Ok(rt)) => Ok(Some(rt)),
                (Method::Rt, Err(error)) => Err(error.clone()),
                (Method::Auto, Ok(rt)) => Ok(rt.preferred().then_some(rt)),
                _ => Ok(None),
            })
            .collect()
    }

    /// The footprint compute pass (timestamps 0 and 1) over the triangles of every object drawn
    /// by its footprints and the box of every object `traced`.
    fn encode_proxy_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        tone: usize,
        traced: &[Option<&ObjectRayTracing>],
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("srt proxy"),
            timestamp_writes: self
                .timestamps
                .as_ref()
                .map(|t| wgpu::ComputePassTimestampWrites {
                    query_set: &t.set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                }),
        });
        pass.set_pipeline(&self.pipelines.proxy);
        pass.set_bind_group(FRAME_GROUP.index, &self.frame.bind_groups[tone], &[]);
        for (object, traced) in self.objects.iter().zip(traced) {
            pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
            if let Some(rt) = traced {
                pass.set_bind_group(PART_GROUP.index, &rt.box_part_group, &[]);
                pass.set_bind_group(PROXY_OUTPUT_GROUP.index, &rt.box_proxy_group, &[]);
                pass.dispatch_workgroups(1, 1, 1);
                continue;
            }
            for part in &object.parts {
                pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                pass.set_bind_group(PROXY_OUTPUT_GROUP.index, &part.proxy_bind_group, &[]);
                let (x, y) = part.sizes.workgroups;
                pass.dispatch_workgroups(x, y, 1);
            }
        }
    }

    /// The render passes into the targets (timestamps 2 and 3): for the polygon method one
    /// pass into colour and depth; for the exact methods the visibility pass into ids and depth
    /// (each object by its triangles' footprints, or, where `traced`, by its box's footprints
    /// and its BVH), then the shading pass into colour.
    fn encode_render_pass(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        method: Method,
        tone: usize,
        traced: &[Option<&ObjectRayTracing>],
    ) {
        let view = |texture: &wgpu::Texture| texture.create_view(&Default::default());
        let (color_view, depth_view, ids_view) = (
            view(&self.targets.color),
            view(&self.targets.depth),
            view(&self.targets.ids),
        );
        // Without stars the object passes clear to the background; with them, the sky's passes
        // draw background and stars first and the object passes draw over them.
        let background = match &self.sky {
            Some(sky) => {
                sky.encode(
                    encoder,
                    &self.frame.bind_groups[tone],
                    &self.frame.polygon_groups[tone],
                    &color_view,
                    self.timestamps.as_ref().map(|t| (&t.set, SKY_TIMESTAMP)),
                );
                wgpu::LoadOp::Load
            }
            None => {
                let b = scene.background;
                wgpu::LoadOp::Clear(wgpu::Color {
                    r: b.x,
                    g: b.y,
                    b: b.z,
                    a: 1.0,
                })
            }
        };
        let depth = wgpu::RenderPassDepthStencilAttachment {
            view: &depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        };
        let lrt = if self.count_fragments {
            self.pipelines.lrt_counting(device)
        } else {
            &self.pipelines.lrt
        };
        match method {
            Method::Polygon => {
                let mut pass = self.begin_pass(
                    encoder,
                    "srt polygon",
                    &color_view,
                    background,
                    Some(depth),
                    [Some(2), Some(3)],
                );
                pass.set_pipeline(&self.pipelines.polygon);
                pass.set_bind_group(
                    POLYGON_FRAME_GROUP.index,
                    &self.frame.polygon_groups[tone],
                    &[],
                );
                self.draw_parts(&mut pass, |pass, part| {
                    // Checked at upload: 3 × triangles fits in u32.
                    pass.draw(0..3 * part.sizes.triangles, 0..1);
                });
            }
            Method::Lrt | Method::Rt | Method::Auto => {
                let none = wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT);
                let mut pass = self.begin_pass(
                    encoder,
                    "srt lrt visibility",
                    &ids_view,
                    none,
                    Some(depth),
                    [Some(2), None],
                );
                pass.set_bind_group(FRAME_GROUP.index, &self.frame.bind_groups[tone], &[]);
                // Objects drawn by their footprints, then those traced through their BVH; the
                // depth test keeps the nearest hit across both.
                pass.set_pipeline(&lrt.visibility);
                for (object, _) in self.objects.iter().zip(traced).filter(|(_, t)| t.is_none()) {
                    pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
                    for part in &object.parts {
                        pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                        self.draw_footprints(&mut pass, part);
                    }
                }
                pass.set_pipeline(&lrt.rt_visibility);
                for (object, rt) in self.objects.iter().zip(traced) {
                    if let Some(rt) = rt {
                        pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
                        pass.set_bind_group(PART_GROUP.index, &rt.box_part_group, &[]);
                        pass.set_bind_group(RT_INPUT_GROUP.index, &rt.visibility_group, &[]);
                        self.draw_box_footprints(&mut pass, &rt.box_draw_args);
                    }
                }
                drop(pass);
                let mut pass = self.begin_pass(
                    encoder,
                    "srt lrt shading",
                    &color_view,
                    background,
                    None,
                    [None, Some(3)],
                );
                pass.set_pipeline(&lrt.shade);
                pass.set_bind_group(
                    SHADE_FRAME_GROUP.index,
                    &self.targets.shade_frame_groups[tone],
                    &[],
                );
                for (object, traced) in self.objects.iter().zip(traced) {
                    pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
                    for part in &object.parts {
                        pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                        // Group 3 for the part's bound (for a traced object its box's).
                        let (group, draw_args) = match traced {
                            Some(rt) => (&rt.shade_group, &rt.box_draw_args),
                            None => (&part.lrt_bind_group, &part.draw_args),
                        };
                        pass.set_bind_group(LRT_INPUT_GROUP.index, group, &[]);
                        self.draw_bound(&mut pass, draw_args);
                    }
                }
            }
        }
    }

    /// Begins a render pass into `target` (loaded as `load` says) and `depth`, writing
    /// timestamps at the indices `[beginning, end]` given.
    fn begin_pass<'a>(
        &self,
        encoder: &'a mut wgpu::CommandEncoder,
        label: &str,
        target: &wgpu::TextureView,
        load: wgpu::LoadOp<wgpu::Color>,
        depth: Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
        [beginning, end]: [Option<u32>; 2],
    ) -> wgpu::RenderPass<'a> {
        let timestamps = self
            .timestamps
            .as_ref()
            .map(|t| wgpu::RenderPassTimestampWrites {
                query_set: &t.set,
                beginning_of_pass_write_index: beginning,
                end_of_pass_write_index: end,
            });
        crate::passes::begin_pass(encoder, label, target, load, depth, timestamps)
    }

    /// Binds each object's and part's groups in `pass` (groups 1 and 2) and lets `draw` draw the
    /// part.
    fn draw_parts(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        draw: impl Fn(&mut wgpu::RenderPass<'_>, &PartResources),
    ) {
        for object in &self.objects {
            pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
            for part in &object.parts {
                pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                draw(pass, part);
            }
        }
    }

    /// Draws a part's screen bound as two triangles (`part_bound_vertex`), if any footprint
    /// behind it is on screen: the proxy pass wrote the vertex count into `draw_args` where the
    /// device has indirect draws.
    fn draw_bound(&self, pass: &mut wgpu::RenderPass<'_>, draw_args: &wgpu::Buffer) {
        if self.indirect_draws {
            pass.draw_indirect(draw_args, SHADE_DRAW_OFFSET);
        } else {
            pass.draw(0..6, 0..1);
        }
    }

    /// Draws the footprints of an object's box (group 3 bound by the caller), up to the last
    /// one on screen where the device has indirect draws.
    fn draw_box_footprints(&self, pass: &mut wgpu::RenderPass<'_>, draw_args: &wgpu::Buffer) {
        if self.indirect_draws {
            pass.draw_indirect(draw_args, 0);
        } else {
            pass.draw(0..FOOTPRINT_VERTICES * BOX_TRIANGLES, 0..1);
        }
    }

    /// Draws the footprints of `part`, `FOOTPRINT_VERTICES` vertices per triangle in one draw
    /// (not instanced: a 12-vertex instance per triangle leaves most of a software rasteriser's
    /// vertex batch empty), up to the last triangle on screen where the device has indirect
    /// draws (the proxy pass wrote the count); group 3: footprints and counter.
    fn draw_footprints(&self, pass: &mut wgpu::RenderPass<'_>, part: &PartResources) {
        pass.set_bind_group(LRT_INPUT_GROUP.index, &part.lrt_bind_group, &[]);
        if self.indirect_draws {
            pass.draw_indirect(&part.draw_args, 0);
        } else {
            // Checked at upload: FOOTPRINT_VERTICES × triangles fits in u32.
            pass.draw(0..FOOTPRINT_VERTICES * part.sizes.triangles, 0..1);
        }
    }

    /// Renders one frame of `scene` and reads it back.
    ///
    /// # Errors
    /// wgpu errors, a lost device, or a scene whose structure differs from the uploaded one.
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
    ) -> Result<(GpuImage, FrameStats), GpuError> {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("srt frame"),
            });
        self.encode(ctx, &mut encoder, scene, method, footprint)?;
        let t = &self.targets;
        t.readback.encode_copy(&mut encoder, &t.color);
        ctx.queue.submit([encoder.finish()]);
        let bytes = t.readback.read(ctx)?;
        let pixel_bytes = texel_bytes(ctx.color_format)? as usize;
        let pixels = bytes.chunks_exact(pixel_bytes).map(decode_pixel).collect();
        let fragments = if self.count_fragments {
            let [run, shaded] =
                bytemuck::pod_read_unaligned::<[u32; 2]>(&ctx.read_buffer(&self.counter.readback)?);
            Some(FragmentCounts {
                run: u64::from(run),
                shaded: u64::from(shaded),
            })
        } else {
            None
        };
        let (gpu_time_ms, proxy_time_ms) = match &self.timestamps {
            Some(t) => {
                let stamps: Vec<u64> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(&t.readback)?);
                let ms = |from: usize, to: usize| {
                    stamps[to].saturating_sub(stamps[from]) as f64
                        * f64::from(ctx.queue.get_timestamp_period())
                        * 1e-6
                };
                // From the first pass of the frame (the proxy pass, or else the sky's, or
                // else the polygon pass) to the end of the last.
                match method {
                    Method::Lrt | Method::Rt | Method::Auto => (Some(ms(0, 3)), Some(ms(0, 1))),
                    Method::Polygon => {
                        let first = if self.sky.is_some() { SKY_TIMESTAMP } else { 2 };
                        (Some(ms(first as usize, 3)), None)
                    }
                }
            }
            None => (None, None),
        };
        ctx.take_errors()?;
        Ok((
            GpuImage {
                width: t.width,
                height: t.height,
                pixels,
            },
            FrameStats {
                gpu_time_ms,
                proxy_time_ms,
                fragments,
            },
        ))
    }

    /// Runs the proxy pass for `scene` and reads back every part's footprints (split out of the
    /// batches the parts are uploaded in), indexed `[object][part][triangle]`: each triangle's
    /// own footprint and the pieces it was split into (for validation against srt-proxy).
    ///
    /// # Errors
    /// wgpu or readback errors.
    pub fn read_footprints(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
    ) -> Result<Vec<Vec<Vec<TriangleFootprints>>>, GpuError> {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("srt footprints"),
            });
        self.encode(ctx, &mut encoder, scene, Method::Lrt, FootprintShape::Hull)?;
        let readback = |encoder: &mut wgpu::CommandEncoder, source: &wgpu::Buffer, size| {
            let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("srt footprint readback"),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, size);
            buffer
        };
        let readbacks: Vec<Vec<(wgpu::Buffer, wgpu::Buffer)>> = self
            .objects
            .iter()
            .map(|object| {
                object
                    .parts
                    .iter()
                    .map(|part| {
                        (
                            readback(&mut encoder, &part.footprints, part.sizes.footprint_bytes),
                            readback(&mut encoder, &part.draw_args, DRAW_ARGS_BYTES),
                        )
                    })
                    .collect()
            })
            .collect();
        ctx.queue.submit([encoder.finish()]);
        let mut footprints = Vec::new();
        for (object, buffers) in self.objects.iter().zip(&readbacks) {
            // Split each batch's footprints among its parts, back in part order, and hand each
            // piece to its triangle.
            let mut parts = vec![Vec::new(); object.culling.len()];
            for (batch, (slots, draw_args)) in object.parts.iter().zip(buffers) {
                let all: Vec<GpuFootprint> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(slots)?);
                let args: Vec<u32> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(draw_args)?);
                let (own, piece_slots) = all.split_at(batch.sizes.triangles as usize);
                let pieces = &piece_slots[..(args[8] as usize).min(piece_slots.len())];
                let mut first = 0;
                for &(index, triangles) in &batch.members {
                    let mine = first..first + triangles;
                    parts[index] = own[mine.start as usize..mine.end as usize]
                        .iter()
                        .enumerate()
                        .map(|(t, &own)| TriangleFootprints {
                            own,
                            pieces: pieces
                                .iter()
                                .filter(|p| p.triangle == mine.start + t as u32)
                                .copied()
                                .collect(),
                        })
                        .collect();
                    first = mine.end;
                }
            }
            footprints.push(parts);
        }
        ctx.take_errors()?;
        Ok(footprints)
    }
}

/// What the proxy pass drew for one triangle ([`GpuRenderer::read_footprints`]).
#[derive(Debug, Clone)]
pub struct TriangleFootprints {
    /// The footprint in the triangle's own slot.
    pub own: GpuFootprint,
    /// The footprints of the pieces it was split into, beyond `own` (drawn as well).
    pub pieces: Vec<GpuFootprint>,
}

/// One RGBA pixel of the colour target: four little-endian f32 (16 bytes) or f16 (8 bytes).
fn decode_pixel(bytes: &[u8]) -> [f32; 4] {
    let channel = |k: usize| {
        if bytes.len() == 16 {
            f32::from_le_bytes([
                bytes[4 * k],
                bytes[4 * k + 1],
                bytes[4 * k + 2],
                bytes[4 * k + 3],
            ])
        } else {
            half::f16::from_le_bytes([bytes[2 * k], bytes[2 * k + 1]]).to_f32()
        }
    };
    [channel(0), channel(1), channel(2), channel(3)]
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
        let texture = Arc::new(Texture {
            width: 1,
            height: 1,
            texels: vec![[255; 4]],
            source: "test".to_owned(),
        });
        let open = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let object = Object {
            name: "test".to_owned(),
            parts: vec![
                part(cube(1.0, 1), None),
                part(open.clone(), None),
                part(cube(2.0, 2), None),
                part(cube(1.0, 1), Some(&texture)),
                part(open, None),
                part(cube(1.0, 1), Some(&texture)),
            ],
            frame: Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap(),
            wireframe: None,
            optics: SurfaceOptics::default(),
        };
        let culling: Vec<BackFaceCulling> = object
            .parts
            .iter()
            .map(|p| BackFaceCulling::for_mesh(&p.mesh))
            .collect();
        let mut groups: Vec<Vec<usize>> = batches(&limits(1 << 27), &object, &culling)
            .unwrap()
            .into_iter()
            .map(|b| b.members)
            .collect();
        groups.sort();
        assert_eq!(groups, vec![vec![0, 2], vec![1, 4], vec![3, 5]]);
    }

    /// A batch closes when the next part would exceed a storage-buffer limit; a part that does
    /// not fit alone is an error naming it.
    #[test]
    fn batches_stay_within_the_device_limits() {
        // A storage-buffer limit of the footprint buffer of two parts (the largest buffer of a
        // batch): two parts fit in a batch, three do not.
        let object = Object {
            name: "cubes".to_owned(),
            parts: (0..3).map(|_| part(cube(1.0, 4), None)).collect(),
            frame: Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap(),
            wireframe: None,
            optics: SurfaceOptics::default(),
        };
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
}
