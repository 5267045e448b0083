//! Bind group layouts and the three pipelines (proxy compute, LRT, polygon). The layouts match
//! the declarations in `shaders/render_bindings.wgsl` (groups 0–2) and each pass's group 3.

use crate::shaders;

/// Colour target format: f32 display colours, quantised to 8 bits on the CPU like the
/// reference. Backends that cannot render to it (OpenGL ES through wgpu's downlevel rules) use
/// [`FALLBACK_COLOR_FORMAT`].
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// Colour target format where `Rgba32Float` is not renderable: half floats (11-bit mantissa,
/// ample for 8-bit output).
pub const FALLBACK_COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Depth format (apparent distance × depth scale for LRT, clip depth for polygons).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Proxy workgroup size (must match `@workgroup_size` in proxy.wgsl).
pub const PROXY_WORKGROUP: u32 = 64;
/// Vertices drawn per footprint instance: four fan triangles (hull of up to six points).
pub const FOOTPRINT_VERTICES: u32 = 12;

fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn storage_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    read_only: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The bind group layouts and pipelines, created once per device.
pub struct Pipelines {
    /// Group 0: frame uniforms and colour table.
    pub frame_layout: wgpu::BindGroupLayout,
    /// Group 1: object uniforms.
    pub object_layout: wgpu::BindGroupLayout,
    /// Group 2: part uniforms, vertices, indices, texture, sampler.
    pub part_layout: wgpu::BindGroupLayout,
    /// Group 3 of the proxy pass: footprints, writable.
    pub proxy_output_layout: wgpu::BindGroupLayout,
    /// Group 3 of the LRT pass: footprints (read) and the fragment counter.
    pub lrt_input_layout: wgpu::BindGroupLayout,
    /// The footprint compute pipeline.
    pub proxy: wgpu::ComputePipeline,
    /// The local ray tracing pipeline.
    pub lrt: wgpu::RenderPipeline,
    /// The polygon-rendering pipeline.
    pub polygon: wgpu::RenderPipeline,
    /// Trilinear, repeating sampler for part textures.
    pub sampler: wgpu::Sampler,
}

impl Pipelines {
    /// Creates layouts, shader modules and pipelines on `device`, rendering into
    /// `color_format`.
    #[must_use]
    pub fn new(device: &wgpu::Device, color_format: wgpu::TextureFormat) -> Self {
        let all = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("srt frame"),
            entries: &[
                uniform_entry(0),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: all,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("srt object"),
            entries: &[uniform_entry(0)],
        });
        let part_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("srt part"),
            entries: &[
                uniform_entry(0),
                storage_entry(1, all, true),
                storage_entry(2, all, true),
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let proxy_output_layout =
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("srt proxy output"),
                entries: &[storage_entry(0, wgpu::ShaderStages::COMPUTE, false)],
            });
        let lrt_input_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("srt lrt input"),
            entries: &[
                storage_entry(0, wgpu::ShaderStages::VERTEX, true),
                storage_entry(1, wgpu::ShaderStages::FRAGMENT, false),
            ],
        });
        let module = |label: &str, source: String| {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            })
        };
        let layout = |label: &str, groups: &[Option<&wgpu::BindGroupLayout>]| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: groups,
                immediate_size: 0,
            })
        };
        let base = [
            Some(&frame_layout),
            Some(&object_layout),
            Some(&part_layout),
        ];
        let proxy_module = module("srt proxy", shaders::proxy());
        let proxy = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("srt proxy"),
            layout: Some(&layout(
                "srt proxy",
                &[base[0], base[1], base[2], Some(&proxy_output_layout)],
            )),
            module: &proxy_module,
            entry_point: Some("footprint_main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        let lrt_module = module("srt lrt", shaders::lrt());
        let lrt = render_pipeline(
            device,
            "srt lrt",
            &layout(
                "srt lrt",
                &[base[0], base[1], base[2], Some(&lrt_input_layout)],
            ),
            &lrt_module,
            ("lrt_vertex", "lrt_fragment"),
            color_format,
        );
        let polygon_module = module("srt polygon", shaders::polygon());
        let polygon = render_pipeline(
            device,
            "srt polygon",
            &layout("srt polygon", &base),
            &polygon_module,
            ("polygon_vertex", "polygon_fragment"),
            color_format,
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("srt texture"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            address_mode_w: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        Self {
            frame_layout,
            object_layout,
            part_layout,
            proxy_output_layout,
            lrt_input_layout,
            proxy,
            lrt,
            polygon,
            sampler,
        }
    }
}

fn render_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    (vertex, fragment): (&str, &str),
    color_format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vertex),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        }),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: color_format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
