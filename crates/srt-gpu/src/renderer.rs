//! The GPU renderer: uploads a scene once, then renders it (local ray tracing or the polygon
//! baseline) for any observer, time, velocities and effect mode with the same mesh structure,
//! and reads the image back.

use srt_color::{TemperatureLut, ToneMap};
use srt_scene::mip::MipChain;
use srt_scene::{Effects, Part, Scene};
use wgpu::util::DeviceExt as _;

use crate::context::{GpuContext, GpuError};
use crate::pipelines::{DEPTH_FORMAT, FOOTPRINT_VERTICES, PROXY_WORKGROUP, Pipelines};
use crate::probe::{lut_params as lut_params_of, lut_texture};
use crate::types::{
    FrameUniforms, GpuFootprint, GpuFrame, GpuVertex, ObjectUniforms, PartUniforms, mat4, vec4,
};

/// Near and far planes of the polygon method's projection.
const NEAR: f64 = 1e-3;
const FAR: f64 = 1e5;
/// LRT depth = apparent distance × this (apparent distances up to 10⁶ are ordered correctly;
/// f32 depth has constant relative precision, so the scale costs nothing).
const LRT_DEPTH_SCALE: f32 = 1e-6;

/// Which rendering method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Local ray tracing (the paper's method, exact per pixel).
    #[default]
    Lrt,
    /// Per-vertex photo-object polygon rendering (§3.2), the approximate baseline.
    Polygon,
}

impl Method {
    /// The name used on the command line.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Lrt => "lrt",
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
            .map(|p| {
                [p[0], p[1], p[2]].map(|c| (f64::from(c).clamp(0.0, 1.0) * 255.0).round() as u8)
            })
            .collect()
    }
}

/// Timing and work counters of one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameStats {
    /// GPU time of the passes in milliseconds, where timestamp queries are supported.
    pub gpu_time_ms: Option<f64>,
    /// Fragments the LRT pass ran (0 for the polygon method).
    pub fragments_shaded: u64,
}

/// Per part: buffers, texture and bind groups.
struct PartResources {
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    proxy_bind_group: wgpu::BindGroup,
    lrt_bind_group: wgpu::BindGroup,
    footprints: wgpu::Buffer,
    triangles: u32,
    material: PartUniforms,
    /// Whether the mesh is a closed solid (back faces may be culled while the observer is
    /// outside it).
    closed: bool,
}

/// Per object: its uniform buffer and parts.
struct ObjectResources {
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    parts: Vec<PartResources>,
}

/// Render targets and readback buffers for one image size.
struct Targets {
    width: u32,
    height: u32,
    color: wgpu::Texture,
    depth: wgpu::Texture,
    readback: wgpu::Buffer,
    padded_row: u32,
    format: wgpu::TextureFormat,
}

impl Targets {
    fn new(device: &wgpu::Device, format: wgpu::TextureFormat, width: u32, height: u32) -> Self {
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
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
        let color = texture(
            "srt color",
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let depth = texture(
            "srt depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let pixel_bytes = format.block_copy_size(None).unwrap_or(16);
        let padded_row = (width * pixel_bytes).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt color readback"),
            size: u64::from(padded_row) * u64::from(height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Self {
            width,
            height,
            color,
            depth,
            readback,
            padded_row,
            format,
        }
    }
}

/// A scene uploaded to the GPU, ready to render.
pub struct GpuRenderer {
    pipelines: Pipelines,
    frame_uniforms: wgpu::Buffer,
    /// One frame bind group per tone map (the colour tables differ).
    frame_bind_groups: [wgpu::BindGroup; 2],
    lut_params: [[f32; 4]; 2],
    objects: Vec<ObjectResources>,
    counter: wgpu::Buffer,
    counter_readback: wgpu::Buffer,
    timestamps: Option<(wgpu::QuerySet, wgpu::Buffer, wgpu::Buffer)>,
    targets: Targets,
    /// Draw rectangles even when hulls are asked for (see [`GpuRenderer::hulls_supported`]).
    rectangles_only: bool,
}

/// The part's texture with its mip chain (levels larger than the device allows are skipped),
/// or a 1×1 white texture.
fn part_texture(ctx: &GpuContext, part: &Part) -> wgpu::TextureView {
    let limit = ctx.device.limits().max_texture_dimension_2d;
    let white = srt_scene::mip::MipLevel {
        width: 1,
        height: 1,
        texels: vec![[255; 4]],
    };
    let chain = part.material.texture.as_deref().map(MipChain::new);
    let levels: Vec<&srt_scene::mip::MipLevel> = match &chain {
        Some(chain) => chain
            .levels()
            .iter()
            .filter(|l| l.width <= limit && l.height <= limit)
            .collect(),
        None => vec![&white],
    };
    let first = levels[0];
    let data: Vec<u8> = levels
        .iter()
        .flat_map(|l| l.texels.iter().flatten().copied())
        .collect();
    let texture = ctx.device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: Some("srt part texture"),
            size: wgpu::Extent3d {
                width: first.width,
                height: first.height,
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

fn vertices(part: &Part) -> Vec<GpuVertex> {
    let mesh = &part.mesh;
    (0..mesh.positions().len())
        .map(|i| GpuVertex {
            position: vec4(mesh.positions()[i], 1.0),
            normal: vec4(mesh.normals()[i], 0.0),
            color: mesh.colors().map_or([1.0; 4], |c| c[i]),
            uv: [mesh.uvs()[i].x as f32, mesh.uvs()[i].y as f32, 0.0, 0.0],
        })
        .collect()
}

impl GpuRenderer {
    /// Uploads `scene` (meshes, textures, colour tables) for images of `width` × `height`.
    ///
    /// # Errors
    /// [`GpuError::Limits`] when a mesh exceeds the device's buffer limits, or any wgpu error.
    pub fn new(ctx: &GpuContext, scene: &Scene, width: u32, height: u32) -> Result<Self, GpuError> {
        let device = &ctx.device;
        let pipelines = Pipelines::new(device, ctx.color_format);
        let frame_uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt frame uniforms"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut lut_params = [[0.0; 4]; 2];
        let mut frame_groups = Vec::new();
        for (k, tone_map) in ToneMap::ALL.into_iter().enumerate() {
            let lut = TemperatureLut::with_defaults(tone_map);
            lut_params[k] = lut_params_of(&lut);
            let view = lut_texture(ctx, &lut)?.create_view(&wgpu::TextureViewDescriptor::default());
            frame_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("srt frame"),
                layout: &pipelines.frame_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: frame_uniforms.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&view),
                    },
                ],
            }));
        }
        let counter = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt fragment counter"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let counter_readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt fragment counter readback"),
            size: 4,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let max_binding = device.limits().max_storage_buffer_binding_size;
        let mut objects = Vec::new();
        for object in &scene.objects {
            let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("srt object uniforms"),
                size: std::mem::size_of::<ObjectUniforms>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("srt object"),
                layout: &pipelines.object_layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniforms.as_entire_binding(),
                }],
            });
            let mut parts = Vec::new();
            for part in &object.parts {
                let triangles = part.mesh.triangles().len();
                let vertex_data = vertices(part);
                let index_data: Vec<u32> =
                    part.mesh.triangles().iter().flatten().copied().collect();
                let footprint_bytes = (triangles * std::mem::size_of::<GpuFootprint>()) as u64;
                let largest = footprint_bytes
                    .max((vertex_data.len() * std::mem::size_of::<GpuVertex>()) as u64);
                if largest > max_binding {
                    return Err(GpuError::Limits(format!(
                        "object {:?} has a part with {triangles} triangles, which needs a {largest}-byte buffer; this GPU allows {max_binding} bytes per buffer",
                        object.name
                    )));
                }
                let triangles = u32::try_from(triangles)
                    .map_err(|_| GpuError::Limits("too many triangles".into()))?;
                let material = PartUniforms {
                    base_color: part.material.base_color,
                    flags: [
                        u32::from(part.material.texture.is_some()),
                        u32::from(part.mesh.colors().is_some()),
                        triangles,
                        0,
                    ],
                };
                let closed = part.mesh.is_closed_outward();
                let part_uniforms = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("srt part uniforms"),
                    contents: bytemuck::bytes_of(&material),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                });
                let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("srt vertices"),
                    contents: bytemuck::cast_slice(&vertex_data),
                    usage: wgpu::BufferUsages::STORAGE,
                });
                let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("srt indices"),
                    contents: bytemuck::cast_slice(&index_data),
                    usage: wgpu::BufferUsages::STORAGE,
                });
                let footprints = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("srt footprints"),
                    size: footprint_bytes,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                });
                let texture = part_texture(ctx, part);
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("srt part"),
                    layout: &pipelines.part_layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: part_uniforms.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: vertex_buffer.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: index_buffer.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: wgpu::BindingResource::TextureView(&texture),
                        },
                        wgpu::BindGroupEntry {
                            binding: 4,
                            resource: wgpu::BindingResource::Sampler(&pipelines.sampler),
                        },
                    ],
                });
                let proxy_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("srt proxy output"),
                    layout: &pipelines.proxy_output_layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: footprints.as_entire_binding(),
                    }],
                });
                let lrt_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("srt lrt input"),
                    layout: &pipelines.lrt_input_layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: footprints.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: counter.as_entire_binding(),
                        },
                    ],
                });
                parts.push(PartResources {
                    uniforms: part_uniforms,
                    bind_group,
                    proxy_bind_group,
                    lrt_bind_group,
                    footprints,
                    triangles,
                    material,
                    closed,
                });
            }
            objects.push(ObjectResources {
                uniforms,
                bind_group,
                parts,
            });
        }
        let timestamps = ctx.timestamps.then(|| {
            let set = device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("srt timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 4,
            });
            let resolve = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("srt timestamp resolve"),
                size: 32,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let readback = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("srt timestamp readback"),
                size: 32,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            (set, resolve, readback)
        });
        let targets = Targets::new(device, ctx.color_format, width, height);
        let [luminance, searchlight]: [wgpu::BindGroup; 2] = frame_groups
            .try_into()
            .map_err(|_| GpuError::Wgpu("colour tables".into()))?;
        let renderer = Self {
            pipelines,
            frame_uniforms,
            frame_bind_groups: [luminance, searchlight],
            lut_params,
            objects,
            counter,
            counter_readback,
            timestamps,
            targets,
            rectangles_only: ctx.adapter_info.backend == wgpu::Backend::Gl,
        };
        ctx.take_errors()?;
        Ok(renderer)
    }

    /// Whether this device draws convex-hull footprints. On wgpu's OpenGL backend the hull
    /// computed by the proxy pass is wrong (a shader-translation problem we have not isolated;
    /// `cargo xtask validate` shows it), so there the renderer always draws the rectangles,
    /// which are correct, at the cost of more overdraw.
    #[must_use]
    pub fn hulls_supported(&self) -> bool {
        !self.rectangles_only
    }

    /// Image width and height.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.targets.width, self.targets.height)
    }

    /// Changes the image size (recreates the render targets).
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) {
        if (width, height) != self.size() {
            self.targets = Targets::new(&ctx.device, ctx.color_format, width, height);
        }
    }

    /// The texture the last frame was rendered into (`Rgba32Float`), for display.
    #[must_use]
    pub fn color_texture(&self) -> &wgpu::Texture {
        &self.targets.color
    }

    /// Writes the per-frame uniforms for `scene` (observer, light, effects, velocities).
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
                .any(|(o, r)| o.parts.len() != r.parts.len())
        {
            return Err(GpuError::Limits(
                "the scene's objects changed since it was uploaded".into(),
            ));
        }
        let (width, height) = self.size();
        let aspect = f64::from(width) / f64::from(height);
        let observer = &scene.observer;
        let (forward, right, up) = observer.basis();
        let tan_half = (0.5 * observer.fov_y_deg.to_radians()).tan();
        let tone = usize::from(scene.tone_map == ToneMap::Searchlight);
        let uniforms = FrameUniforms {
            view_projection: mat4(observer.view_projection(aspect, NEAR, FAR)),
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
            lut: self.lut_params[tone],
            viewport: [
                width as f32,
                height as f32,
                1.0 / width as f32,
                1.0 / height as f32,
            ],
            modes: [
                match scene.effects {
                    Effects::Geometry => 0,
                    Effects::Doppler => 1,
                    Effects::Searchlight => 2,
                },
                u32::from(footprint == FootprintShape::Rectangle || self.rectangles_only),
                0,
                0,
            ],
            depth_scale: [LRT_DEPTH_SCALE, 0.0, 0.0, 0.0],
        };
        ctx.queue
            .write_buffer(&self.frame_uniforms, 0, bytemuck::bytes_of(&uniforms));
        for (object, resources) in scene.objects.iter().zip(&self.objects) {
            let uniforms = ObjectUniforms {
                frame: GpuFrame::new(&object.frame, observer.event()),
                style: [object.wireframe.unwrap_or(0.0) as f32, 0.0, 0.0, 0.0],
            };
            ctx.queue
                .write_buffer(&resources.uniforms, 0, bytemuck::bytes_of(&uniforms));
            let observer_rest = object.frame.to_rest(observer.event()).position;
            for (part, part_resources) in object.parts.iter().zip(&resources.parts) {
                let mut material = part_resources.material;
                material.base_color = part.material.base_color;
                // Back-face culling is exact only while the observer is outside the solid (in
                // S′, where every viewing ray starts at the observer).
                material.flags[3] = u32::from(
                    part_resources.closed && part.mesh.winding_number(observer_rest).abs() < 0.5,
                );
                ctx.queue
                    .write_buffer(&part_resources.uniforms, 0, bytemuck::bytes_of(&material));
            }
        }
        Ok(tone)
    }

    /// Records the passes of one frame into `encoder`, leaving the image in
    /// [`GpuRenderer::color_texture`].
    ///
    /// # Errors
    /// If the scene's structure differs from the uploaded one.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
    ) -> Result<(), GpuError> {
        let tone = self.write_uniforms(ctx, scene, footprint)?;
        let frame_group = &self.frame_bind_groups[tone];
        let timestamp = |begin: u32| self.timestamps.as_ref().map(|(set, _, _)| (set, begin));
        encoder.clear_buffer(&self.counter, 0, None);
        if method == Method::Lrt {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("srt proxy"),
                timestamp_writes: timestamp(0).map(|(set, i)| wgpu::ComputePassTimestampWrites {
                    query_set: set,
                    beginning_of_pass_write_index: Some(i),
                    end_of_pass_write_index: Some(i + 1),
                }),
            });
            pass.set_pipeline(&self.pipelines.proxy);
            pass.set_bind_group(0, frame_group, &[]);
            let max_groups = ctx.device.limits().max_compute_workgroups_per_dimension;
            for object in &self.objects {
                pass.set_bind_group(1, &object.bind_group, &[]);
                for part in &object.parts {
                    pass.set_bind_group(2, &part.bind_group, &[]);
                    pass.set_bind_group(3, &part.proxy_bind_group, &[]);
                    let groups = part.triangles.div_ceil(PROXY_WORKGROUP);
                    let x = groups.min(max_groups);
                    pass.dispatch_workgroups(x, groups.div_ceil(x.max(1)), 1);
                }
            }
        }
        {
            let color_view = self
                .targets
                .color
                .create_view(&wgpu::TextureViewDescriptor::default());
            let depth_view = self
                .targets
                .depth
                .create_view(&wgpu::TextureViewDescriptor::default());
            let b = scene.background;
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("srt render"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &color_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: b.x,
                            g: b.y,
                            b: b.z,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: timestamp(2).map(|(set, i)| wgpu::RenderPassTimestampWrites {
                    query_set: set,
                    beginning_of_pass_write_index: Some(i),
                    end_of_pass_write_index: Some(i + 1),
                }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(match method {
                Method::Lrt => &self.pipelines.lrt,
                Method::Polygon => &self.pipelines.polygon,
            });
            pass.set_bind_group(0, frame_group, &[]);
            for object in &self.objects {
                pass.set_bind_group(1, &object.bind_group, &[]);
                for part in &object.parts {
                    pass.set_bind_group(2, &part.bind_group, &[]);
                    match method {
                        Method::Lrt => {
                            pass.set_bind_group(3, &part.lrt_bind_group, &[]);
                            pass.draw(0..FOOTPRINT_VERTICES, 0..part.triangles);
                        }
                        Method::Polygon => pass.draw(0..3 * part.triangles, 0..1),
                    }
                }
            }
        }
        if let Some((set, resolve, readback)) = &self.timestamps {
            encoder.resolve_query_set(set, 0..4, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, readback, 0, 32);
        }
        encoder.copy_buffer_to_buffer(&self.counter, 0, &self.counter_readback, 0, 4);
        Ok(())
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
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &t.color,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &t.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(t.padded_row),
                    rows_per_image: Some(t.height),
                },
            },
            wgpu::Extent3d {
                width: t.width,
                height: t.height,
                depth_or_array_layers: 1,
            },
        );
        ctx.queue.submit([encoder.finish()]);
        let bytes = ctx.read_buffer(&t.readback)?;
        let pixel_bytes = t.format.block_copy_size(None).unwrap_or(16) as usize;
        let mut pixels = Vec::with_capacity((t.width * t.height) as usize);
        for row in bytes.chunks_exact(t.padded_row as usize) {
            let row = &row[..t.width as usize * pixel_bytes];
            pixels.extend(row.chunks_exact(pixel_bytes).map(decode_pixel));
        }
        let fragments =
            bytemuck::pod_read_unaligned::<u32>(&ctx.read_buffer(&self.counter_readback)?);
        let gpu_time_ms = match &self.timestamps {
            Some((_, _, readback)) => {
                let stamps: Vec<u64> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(readback)?);
                let first = if method == Method::Lrt { 0 } else { 2 };
                let ns = stamps[3].saturating_sub(stamps[first]) as f64
                    * f64::from(ctx.queue.get_timestamp_period());
                Some(ns * 1e-6)
            }
            None => None,
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
                fragments_shaded: u64::from(fragments),
            },
        ))
    }

    /// Runs the proxy pass for `scene` and reads back every part's footprints, indexed
    /// `[object][part][triangle]` (for validation against srt-proxy).
    ///
    /// # Errors
    /// wgpu or readback errors.
    pub fn read_footprints(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
    ) -> Result<Vec<Vec<Vec<GpuFootprint>>>, GpuError> {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("srt footprints"),
            });
        self.encode(ctx, &mut encoder, scene, Method::Lrt, FootprintShape::Hull)?;
        let mut readbacks = Vec::new();
        for object in &self.objects {
            let mut parts = Vec::new();
            for part in &object.parts {
                let size = u64::from(part.triangles) * std::mem::size_of::<GpuFootprint>() as u64;
                let readback = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("srt footprint readback"),
                    size,
                    usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                    mapped_at_creation: false,
                });
                encoder.copy_buffer_to_buffer(&part.footprints, 0, &readback, 0, size);
                parts.push(readback);
            }
            readbacks.push(parts);
        }
        ctx.queue.submit([encoder.finish()]);
        let footprints = readbacks
            .iter()
            .map(|parts| {
                parts
                    .iter()
                    .map(|buffer| Ok(bytemuck::pod_collect_to_vec(&ctx.read_buffer(buffer)?)))
                    .collect::<Result<Vec<_>, GpuError>>()
            })
            .collect::<Result<Vec<_>, GpuError>>()?;
        ctx.take_errors()?;
        Ok(footprints)
    }
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
