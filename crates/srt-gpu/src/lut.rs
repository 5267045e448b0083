//! The apparent-temperature colour table on the GPU: the parameters `lut_sample`
//! (`shaders/colour.wgsl`) takes and the texture it reads, built from a CPU
//! [`TemperatureLut`] so that both sides sample the same texels.

use srt_color::TemperatureLut;

use crate::context::{GpuContext, GpuError};
use crate::limits::DeviceLimits;

/// The `lut_sample` parameters of `lut`: (ln T_min, ln T_max, N, 0) in `f32`, as
/// `FrameUniforms::lut` holds them.
#[must_use]
pub fn lut_params(lut: &TemperatureLut) -> [f32; 4] {
    [
        lut.t_min().ln() as f32,
        lut.t_max().ln() as f32,
        lut.size() as f32,
        0.0,
    ]
}

/// Uploads `lut` as the N × 1 `rgba32float` 2D texture `lut_sample` reads (usage
/// `TEXTURE_BINDING`, bound with sample type `Float { filterable: false }`, view dimension `D2`).
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when the table is wider than the device's 2D texture limit.
pub fn lut_texture(ctx: &GpuContext, lut: &TemperatureLut) -> Result<wgpu::Texture, GpuError> {
    let width = u32::try_from(lut.size()).unwrap_or(u32::MAX);
    DeviceLimits::of(ctx).check_texture("colour table", width, 1)?;
    let size = wgpu::Extent3d {
        width,
        height: 1,
        depth_or_array_layers: 1,
    };
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("temperature LUT"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        bytemuck::cast_slice(lut.texels()),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * 16),
            rows_per_image: None,
        },
        size,
    );
    Ok(texture)
}
