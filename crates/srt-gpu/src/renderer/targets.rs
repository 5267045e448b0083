//! What a renderer allocates besides the scene: the render targets of one image size, the
//! per-frame uniforms and bind groups, the fragment counter and the timestamp queries.

use super::*;

/// Render targets, the readback of the colour and the LRT shading pass's frame bind groups
/// (which bind the id target) for one image size.
pub(super) struct Targets {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) color: wgpu::Texture,
    pub(super) depth: wgpu::Texture,
    /// The LRT visibility pass's (part id, triangle) per pixel.
    pub(super) ids: wgpu::Texture,
    /// The depth of the part kept at each pixel (lrt.wgsl's `part_depth`), which the shading
    /// pass tests for equality.
    pub(super) part_depth: wgpu::Texture,
    /// [`SHADE_FRAME_GROUP`] per tone map, indexed as [`ToneMap::ALL`].
    pub(super) shade_frame_groups: Vec<wgpu::BindGroup>,
    pub(super) readback: TextureReadback,
}

impl Targets {
    /// Checks the size against the device's limits, then creates the targets.
    pub(super) fn new(
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
        let [spectral_words, spectral_cie] = frame.spectral.entries();
        let shade_frame_groups = frame
            .lut_views
            .iter()
            .map(|lut| {
                ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(SHADE_FRAME_GROUP.label),
                    layout: &pipelines.shade_frame_layout,
                    entries: &[
                        slots::FRAME_UNIFORMS.entry(frame.uniforms.as_entire_binding()),
                        slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(lut)),
                        slots::VISIBLE_IDS.entry(wgpu::BindingResource::TextureView(&ids_view)),
                        spectral_words.clone(),
                        spectral_cie.clone(),
                        slots::SHADOW_SCENE.entry(frame.shadow_scene.as_entire_binding()),
                        slots::FRAME_BOUND.entry(frame.frame_bound.as_entire_binding()),
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
            part_depth: texture(
                "srt part depth",
                DEPTH_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            ),
            ids,
            shade_frame_groups,
            readback: TextureReadback::new(ctx, width, height, ctx.color_format)?,
        })
    }
}

/// The frame uniforms (the lights among them) and, per tone map, the colour table bound with
/// them; the spectral tables; the shadow casters.
pub(super) struct FrameResources {
    /// WGSL `frame_uniforms` ([`FrameUniforms`]), written every frame.
    pub(super) uniforms: wgpu::Buffer,
    /// WGSL `shadow_scene` ([`crate::shadows::ShadowScene`], or one unread row).
    pub(super) shadow_scene: wgpu::Buffer,
    /// WGSL `frame_bound`: the union of the frame's footprints on screen, which the proxy pass
    /// grows (every part's and box's proxy group binds it) and the part-depth pass draws;
    /// cleared before every proxy pass.
    pub(super) frame_bound: wgpu::Buffer,
    /// One bind group per tone map, indexed as [`ToneMap::ALL`] (the colour tables differ).
    pub(super) bind_groups: Vec<wgpu::BindGroup>,
    /// [`POLYGON_FRAME_GROUP`] per tone map, indexed as [`ToneMap::ALL`].
    pub(super) polygon_groups: Vec<wgpu::BindGroup>,
    /// [`SKY_FRAME_GROUP`] per tone map, indexed as [`ToneMap::ALL`].
    pub(super) sky_groups: Vec<wgpu::BindGroup>,
    /// The tables of spectral colour (also bound by [`SHADE_FRAME_GROUP`]).
    pub(super) spectral: SpectralTables,
    /// The colour-table parameters, indexed as [`ToneMap::ALL`].
    pub(super) lut_params: Vec<[f32; 4]>,
    /// The colour tables, indexed as [`ToneMap::ALL`] (also bound by [`SHADE_FRAME_GROUP`]).
    pub(super) lut_views: Vec<wgpu::TextureView>,
}

impl FrameResources {
    /// The frame's resources, binding `shadow_scene` as WGSL `shadow_scene`, and keeping
    /// `frame_bound` (WGSL `frame_bound`, which the objects' proxy groups bind already).
    pub(super) fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        shadow_scene: &wgpu::Buffer,
        frame_bound: wgpu::Buffer,
    ) -> Result<Self, GpuError> {
        let written_per_frame = |label, size| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: BlockSpace::BUFFER_USAGES,
                mapped_at_creation: false,
            })
        };
        let uniforms = written_per_frame("srt frame uniforms", size_of::<FrameUniforms>() as u64);
        let spectral = SpectralTables::new(ctx)?;
        let [spectral_words, spectral_cie] = spectral.entries();
        let mut bind_groups = Vec::new();
        let mut polygon_groups = Vec::new();
        let mut sky_groups = Vec::new();
        let mut params = Vec::new();
        let mut lut_views = Vec::new();
        for tone_map in ToneMap::ALL {
            let lut = TemperatureLut::shared(tone_map);
            params.push(lut_params(lut));
            let view = lut_texture(ctx, lut)?.create_view(&wgpu::TextureViewDescriptor::default());
            bind_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(FRAME_GROUP.label),
                layout: &pipelines.frame_layout,
                entries: &[
                    slots::FRAME_UNIFORMS.entry(uniforms.as_entire_binding()),
                    slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(&view)),
                ],
            }));
            polygon_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(POLYGON_FRAME_GROUP.label),
                layout: &pipelines.polygon_frame_layout,
                entries: &[
                    slots::FRAME_UNIFORMS.entry(uniforms.as_entire_binding()),
                    slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(&view)),
                    spectral_words.clone(),
                    spectral_cie.clone(),
                    slots::SHADOW_SCENE.entry(shadow_scene.as_entire_binding()),
                ],
            }));
            sky_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(SKY_FRAME_GROUP.label),
                layout: &pipelines.sky_frame_layout,
                entries: &[
                    slots::FRAME_UNIFORMS.entry(uniforms.as_entire_binding()),
                    slots::LUT_TABLE.entry(wgpu::BindingResource::TextureView(&view)),
                    spectral_words.clone(),
                    spectral_cie.clone(),
                ],
            }));
            lut_views.push(view);
        }
        Ok(Self {
            uniforms,
            shadow_scene: shadow_scene.clone(),
            frame_bound,
            bind_groups,
            polygon_groups,
            sky_groups,
            spectral,
            lut_params: params,
            lut_views,
        })
    }

    /// Index of `tone_map` in [`ToneMap::ALL`].
    pub(super) fn tone_index(tone_map: ToneMap) -> usize {
        ToneMap::ALL
            .iter()
            .position(|&t| t == tone_map)
            .unwrap_or_default()
    }
}

/// The LRT pass's fragment counter and the buffer it is read back through.
pub(super) struct FragmentCounter {
    pub(super) counter: wgpu::Buffer,
    pub(super) readback: wgpu::Buffer,
}

impl FragmentCounter {
    pub(super) fn new(device: &wgpu::Device) -> Self {
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
pub(super) struct Timestamps {
    pub(super) set: wgpu::QuerySet,
    pub(super) resolve: wgpu::Buffer,
    pub(super) readback: wgpu::Buffer,
}

/// Timestamps written per frame: begin and end of the proxy pass (0, 1) and of the render
/// passes (2, 3), and the beginning of the sky's passes (4), which precede the render passes,
/// so that every method's frame time includes them.
pub(super) const TIMESTAMP_COUNT: u32 = 5;

/// The timestamp written at the beginning of the sky's passes.
pub(super) const SKY_TIMESTAMP: u32 = 4;

impl Timestamps {
    pub(super) fn new(device: &wgpu::Device) -> Self {
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
