//! Small helpers for recording passes that several modules (and the viewer) share.

/// The frame-wide buffers that every batch's (and every traced object's box's) proxy and LRT
/// bind groups bind.
#[derive(Clone, Copy)]
pub(crate) struct FrameShared<'a> {
    /// The LRT passes' fragment counter (WGSL `fragment_count`).
    pub(crate) fragment_count: &'a wgpu::Buffer,
    /// The frame's screen bound (WGSL `frame_bound`, [`crate::types::FRAME_BOUND_BYTES`]), grown by the
    /// proxy pass and drawn by the part-depth pass.
    pub(crate) frame_bound: &'a wgpu::Buffer,
}

/// Begins a render pass into the colour target `target` (loaded as `load` says, stored) and the
/// optional `depth` attachment, with the optional timestamp writes.
pub fn begin_pass<'a>(
    encoder: &'a mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
    depth: Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'a> {
    encoder
        .begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: depth,
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        })
        .forget_lifetime()
}

/// [`begin_pass`] into the colour target alone: no depth, no timestamps.
pub fn begin_colour_pass(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> wgpu::RenderPass<'static> {
    begin_pass(encoder, label, target, load, None, None).forget_lifetime()
}
