//! Drawing the scene into textures the UI shows: the srt-gpu passes (the same ones `srt render`
//! uses) render into their `Rgba32Float` target, and a small blit pass copies that into an
//! `Rgba8Unorm` texture registered with egui. The values are already display-encoded (sRGB), and
//! egui expects exactly that of a non-sRGB texture, so the blit only clamps.
//!
//! For the split screen the one uploaded scene is rendered twice, once per method, each into its
//! own display texture; a queue submission between the two keeps their uniforms apart.

use eframe::egui;
use eframe::egui_wgpu;
use srt_gpu::{FootprintShape, GpuContext, GpuError, GpuRenderer, Method};
use srt_scene::Scene;

/// Format of the textures egui shows.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Which method(s) the view shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ViewMethod {
    /// Local ray tracing only (the paper's method).
    #[default]
    Lrt,
    /// The polygon baseline only (§3.2).
    Polygon,
    /// Both, side by side: local ray tracing on the left, polygons on the right.
    Split,
}

impl ViewMethod {
    /// All choices, in the order the panel lists them.
    pub const ALL: [Self; 3] = [Self::Lrt, Self::Polygon, Self::Split];

    /// The methods rendered, left to right.
    #[must_use]
    pub const fn methods(self) -> &'static [Method] {
        match self {
            Self::Lrt => &[Method::Lrt],
            Self::Polygon => &[Method::Polygon],
            Self::Split => &[Method::Lrt, Method::Polygon],
        }
    }

    /// The label in the panel.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::Lrt => "Local ray tracing",
            Self::Polygon => "Polygon",
            Self::Split => "Split screen (both)",
        }
    }
}

const BLIT_WGSL: &str = r"
@group(0) @binding(0) var source: texture_2d<f32>;

@vertex
fn blit_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the whole target.
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn blit_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let colour = textureLoad(source, vec2<i32>(position.xy), 0);
    return vec4<f32>(clamp(colour.rgb, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}
";

/// The blit pipeline: `Rgba32Float` texels → `Rgba8Unorm`.
struct Blit {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl Blit {
    fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("srt-viewer blit"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("srt-viewer blit"),
            source: wgpu::ShaderSource::Wgsl(BLIT_WGSL.into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("srt-viewer blit"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("srt-viewer blit"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("blit_vertex"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("blit_fragment"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: DISPLAY_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { layout, pipeline }
    }

    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        source: &wgpu::Texture,
        target: &wgpu::TextureView,
    ) {
        let source_view = source.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("srt-viewer blit"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&source_view),
            }],
        });
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("srt-viewer blit"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// One texture egui shows.
struct Display {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    size: (u32, u32),
    /// Its egui id once registered; `registered` is false when the texture changed since.
    id: Option<egui::TextureId>,
    registered: bool,
}

impl Display {
    fn new(device: &wgpu::Device, size: (u32, u32), id: Option<egui::TextureId>) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("srt-viewer display"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DISPLAY_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Self {
            texture,
            view,
            size,
            id,
            registered: false,
        }
    }
}

/// The uploaded scene and the textures the UI shows.
pub struct SceneView {
    blit: Blit,
    /// The uploaded scene and the structure version it was uploaded at.
    renderer: Option<(u64, GpuRenderer)>,
    displays: Vec<Display>,
    /// egui ids of displays no longer shown (split screen switched off), reused before new ones
    /// are registered.
    spare_ids: Vec<egui::TextureId>,
    triangles: usize,
}

impl SceneView {
    /// Creates the blit pipeline; nothing is uploaded yet.
    #[must_use]
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            blit: Blit::new(&ctx.device),
            renderer: None,
            displays: Vec::new(),
            spare_ids: Vec::new(),
            triangles: 0,
        }
    }

    /// Uploads `scene` unless the scene of structure `version` is already uploaded.
    ///
    /// # Errors
    /// [`GpuError`] when the upload fails (a model too large for the device…); the previously
    /// uploaded scene is then dropped.
    pub fn upload(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        version: u64,
    ) -> Result<(), GpuError> {
        if self.renderer.as_ref().is_some_and(|(v, _)| *v == version) {
            return Ok(());
        }
        let size = self.renderer.as_ref().map_or((64, 64), |(_, r)| r.size());
        self.renderer = None;
        let renderer = GpuRenderer::new(ctx, scene, size.0, size.1)?;
        self.triangles = scene.triangle_count();
        self.renderer = Some((version, renderer));
        Ok(())
    }

    /// Triangles in the uploaded scene.
    #[must_use]
    pub const fn triangles(&self) -> usize {
        self.triangles
    }

    /// Renders `scene` (which must have the structure last uploaded) with `method` into display
    /// textures filling `size` pixels in all; with `egui_renderer`, (re-)registers them with egui.
    ///
    /// # Errors
    /// [`GpuError`] when nothing was uploaded, the scene's structure changed, or wgpu reports an
    /// error.
    pub fn render(
        &mut self,
        ctx: &GpuContext,
        egui_renderer: Option<&mut egui_wgpu::Renderer>,
        scene: &Scene,
        method: ViewMethod,
        size: (u32, u32),
    ) -> Result<(), GpuError> {
        let Some((_, renderer)) = &mut self.renderer else {
            return Err(GpuError::NotReady("no scene has been uploaded"));
        };
        let methods = method.methods();
        let count = u32::try_from(methods.len()).unwrap_or(1);
        let limit = ctx.device.limits().max_texture_dimension_2d;
        let each = ((size.0 / count).clamp(1, limit), size.1.clamp(1, limit));
        renderer.resize(ctx, each.0, each.1)?;
        // Displays no longer needed keep their egui ids for later reuse.
        while self.displays.len() > methods.len() {
            if let Some(display) = self.displays.pop() {
                self.spare_ids.extend(display.id);
            }
        }
        for (index, method) in methods.iter().enumerate() {
            match self.displays.get(index) {
                Some(display) if display.size == each => {}
                Some(display) => {
                    let id = display.id;
                    self.displays[index] = Display::new(&ctx.device, each, id);
                }
                None => {
                    let id = self.spare_ids.pop();
                    self.displays.push(Display::new(&ctx.device, each, id));
                }
            }
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("srt-viewer frame"),
                });
            renderer.encode(ctx, &mut encoder, scene, *method, FootprintShape::Hull)?;
            self.blit.encode(
                &ctx.device,
                &mut encoder,
                renderer.color_texture(),
                &self.displays[index].view,
            );
            ctx.queue.submit([encoder.finish()]);
        }
        if let Some(egui_renderer) = egui_renderer {
            for display in &mut self.displays {
                match display.id {
                    Some(id) if !display.registered => egui_renderer
                        .update_egui_texture_from_wgpu_texture(
                            &ctx.device,
                            &display.view,
                            wgpu::FilterMode::Linear,
                            id,
                        ),
                    None => {
                        display.id = Some(egui_renderer.register_native_texture(
                            &ctx.device,
                            &display.view,
                            wgpu::FilterMode::Linear,
                        ));
                    }
                    Some(_) => {}
                }
                display.registered = true;
            }
        }
        ctx.take_errors()
    }

    /// The registered textures with their sizes in pixels, left to right.
    pub fn textures(&self) -> impl Iterator<Item = (egui::TextureId, [u32; 2])> + '_ {
        self.displays
            .iter()
            .filter_map(|d| d.id.map(|id| (id, [d.size.0, d.size.1])))
    }

    /// Reads the shown image(s) back, side by side, as 8-bit RGBA.
    ///
    /// # Errors
    /// [`GpuError`] when nothing was rendered yet or the readback fails.
    pub fn read_image(&self, ctx: &GpuContext) -> Result<image::RgbaImage, GpuError> {
        if self.displays.is_empty() {
            return Err(GpuError::NotReady("nothing has been rendered yet"));
        }
        let width: u32 = self.displays.iter().map(|d| d.size.0).sum();
        let height = self.displays.iter().map(|d| d.size.1).max().unwrap_or(1);
        let mut image = image::RgbaImage::new(width, height);
        let mut x0 = 0;
        for display in &self.displays {
            let w = display.size.0;
            let bytes = srt_gpu::read_texture(ctx, &display.texture)?;
            for (y, line) in bytes.chunks_exact(w as usize * 4).enumerate() {
                for (x, texel) in line.chunks_exact(4).enumerate() {
                    #[expect(
                        clippy::cast_possible_truncation,
                        reason = "texture sizes fit in u32"
                    )]
                    image.put_pixel(
                        x0 + x as u32,
                        y as u32,
                        image::Rgba([texel[0], texel[1], texel[2], texel[3]]),
                    );
                }
            }
            x0 += w;
        }
        ctx.take_errors()?;
        Ok(image)
    }
}
