//! The texture formats the passes render into, in one leaf module: the device code picks the
//! colour format, the pipelines and the renderer's targets use all of them.

/// Colour target format: f32 display colours, quantised to 8 bits on the CPU like the
/// reference. Backends that cannot render to it (OpenGL ES through wgpu's downlevel rules) use
/// [`FALLBACK_COLOR_FORMAT`].
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// Colour target format where `Rgba32Float` is not renderable: half floats (11-bit mantissa,
/// ample for 8-bit output).
pub const FALLBACK_COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the LRT visibility pass's id target: (part id, triangle) per pixel.
pub const VISIBLE_ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Uint;
/// Depth format (apparent distance × depth scale for LRT, clip depth for polygons).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The largest finite value a colour target of `format` holds: what radiance is held to
/// (half floats end at 65 504).
#[must_use]
pub fn largest_value(format: wgpu::TextureFormat) -> f32 {
    if format == FALLBACK_COLOR_FORMAT {
        half::f16::MAX.to_f32()
    } else {
        f32::MAX
    }
}
