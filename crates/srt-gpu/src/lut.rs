//! The apparent-temperature colour table on the GPU: the parameters `lut_sample`
//! (`shaders/colour.wgsl`) takes and the texture it reads, built from a CPU
//! [`TemperatureLut`] so that both sides sample the same texels; beside it, over the same
//! temperatures, the [`RadianceTable`] that `radiance_table_sample` reads.

use srt_color::{RadianceTable, TemperatureLut};

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::textures::{Texture2d, upload_2d};

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

/// Uploads `lut` as the N × 2 `rgba32float` 2D texture `lut_sample` reads (usage
/// `TEXTURE_BINDING`, bound with sample type `Float { filterable: false }`, view dimension `D2`):
/// row 0 the colour table, row 1 the radiance table over the same temperatures
/// ([`RadianceTable::for_lut`]).
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when the table is wider than the device's 2D texture limit.
pub fn lut_texture(ctx: &GpuContext, lut: &TemperatureLut) -> Result<wgpu::Texture, GpuError> {
    let width = u32::try_from(lut.size()).unwrap_or(u32::MAX);
    DeviceLimits::of(ctx).check_texture("colour table", width, 2)?;
    let radiance = RadianceTable::for_lut(lut);
    let texels: Vec<[f32; 4]> = lut
        .texels()
        .iter()
        .chain(radiance.texels())
        .copied()
        .collect();
    let texture = upload_2d(
        ctx,
        &Texture2d {
            label: "temperature LUT",
            width,
            height: 2,
            mip_levels: 1,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
        },
        bytemuck::cast_slice(&texels),
    );
    Ok(texture)
}
