//! Showing a rendered frame: a full-screen pass copies the renderer's display colours
//! ([`crate::GpuRenderer::color_texture`], sRGB-encoded floats) into an 8-bit target — the
//! texture a window's UI shows, or a web page's canvas — quantised as the CPU reference quantises
//! them (`srt_color::quantize_8bit`), so that the screen shows the bytes `srt render` writes.
//! The pass can cover a range of columns only, so that two renderers share one target (the split
//! view: the exact picture on the left, the polygon method's on the right). WGSL:
//! `shaders/display.wgsl`.

use std::ops::Range;

use crate::pipelines::{BindGroupSpec, PipelineSpec, Slot};
use crate::shaders;

/// The display pass's only binding: the frame to show.
const SOURCE_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt display source",
    index: 0,
    slots: &[Slot {
        wgsl_name: "display_source",
        binding: 0,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
    }],
};

/// Entry points of the display pass (vertex, fragment).
const ENTRIES: [&str; 2] = ["display_vertex", "display_fragment"];

/// The display pipeline as its bindings see it, for reflection against the WGSL.
#[must_use]
pub fn spec() -> PipelineSpec {
    PipelineSpec {
        label: "srt display",
        shader: shaders::display(),
        entry_points: &ENTRIES,
        groups: vec![SOURCE_GROUP],
    }
}

/// The display pass for targets of one format (an 8-bit, non-sRGB format: the values are
/// already sRGB-encoded).
pub struct DisplayPass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl DisplayPass {
    /// Creates the pipeline for targets of `format`.
    #[must_use]
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let layout = SOURCE_GROUP.create_layout(device);
        let shader = shaders::display();
        let module = shader.module(device);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("srt display"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("srt display"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(ENTRIES[0]),
                compilation_options: shader.compilation_options(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(ENTRIES[1]),
                compilation_options: shader.compilation_options(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { layout, pipeline }
    }

    /// Records the copy of `source` (a frame as large as `target`, or larger) into `target`:
    /// all of it, or only `columns` (the rest of the target is kept, or cleared to black when
    /// `clear` is set).
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        source: &wgpu::Texture,
        target: &wgpu::TextureView,
        columns: Option<Range<u32>>,
        clear: bool,
    ) {
        let source_view = source.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("srt display source"),
            layout: &self.layout,
            entries: &[
                SOURCE_GROUP.slots[0].entry(wgpu::BindingResource::TextureView(&source_view))
            ],
        });
        let load = if clear {
            wgpu::LoadOp::Clear(wgpu::Color::BLACK)
        } else {
            wgpu::LoadOp::Load
        };
        let mut pass = crate::passes::begin_colour_pass(encoder, "srt display", target, load);
        if let Some(columns) = columns {
            let height = source.height();
            pass.set_scissor_rect(columns.start, 0, columns.len() as u32, height);
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
