//! The tables of spectral colour on the GPU (`shaders/spectral.wgsl`): the Jakob–Hanika
//! coefficient table in a storage buffer and the CIE 1931 table in a texture, uploaded once per
//! renderer from the CPU's own tables (`srt_color::srgb_coefficient_table`,
//! `srt_color::cie_1931`), so that both sides use the same numbers.
//!
//! The CIE table is a texture because every spectral sum reads all of its rows, and a software
//! rasteriser (Mesa's llvmpipe) reads a storage buffer in a fragment shader one lane at a time,
//! while it fetches a texel for all lanes at once: the teaser's spectral frame took 20 % less
//! with the rows in a texture (docs/performance-log.md, 2026-11-27).

use srt_color::{cie_1931, srgb_coefficient_table};
use wgpu::util::DeviceExt as _;

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::pipelines::slots;
use crate::textures::{Texture2d, upload_2d};

/// The CIE table as WGSL `cie_row` reads it, one texel per row in f32: x̄, ȳ, z̄ and 1/λ in
/// nm⁻¹ (the reciprocal taken in f64, then rounded once).
#[must_use]
pub fn cie_texels() -> Vec<[f32; 4]> {
    cie_1931()
        .iter()
        .map(|s| [s.xbar, s.ybar, s.zbar, 1.0 / s.wavelength_nm].map(|v| v as f32))
        .collect()
}

/// Words before the brightness scale in [`SpectralTables`]' buffer: the number of scale entries
/// (as f32, exact for any table size up to 2²⁴) and the CIE table's first and last wavelengths
/// in nm (its rows, 1 nm apart, are the texture's width).
pub const SPECTRAL_HEADER_WORDS: usize = 3;

/// The storage buffer's half of the spectral tables as WGSL `spectral_tables` reads it
/// (spectral.wgsl's accessors), one array of f32: the header ([`SPECTRAL_HEADER_WORDS`]), the
/// coefficient table's brightness scale (n entries), then the coefficient texels (three words
/// each, in `CoefficientTable::texels`' layout). One buffer, not two: every storage binding
/// counts against the shading pass's limit of eight per stage (docs/ARCHITECTURE.md, "No
/// uniform buffers").
#[must_use]
pub fn spectral_words() -> Vec<f32> {
    let table = srgb_coefficient_table();
    let scale = table.scale();
    let rows = cie_1931();
    let (first, last) = (rows[0].wavelength_nm, rows[rows.len() - 1].wavelength_nm);
    let mut words =
        Vec::with_capacity(SPECTRAL_HEADER_WORDS + scale.len() + 3 * table.texels().len());
    words.extend([scale.len() as f32, first as f32, last as f32]);
    words.extend(scale.iter().map(|&z| z as f32));
    words.extend_from_slice(bytemuck::cast_slice(table.texels()));
    words
}

/// The spectral tables on the GPU: the storage buffer of [`spectral_words`] and the
/// `rgba32float` texture of [`cie_texels`] (one row of texels).
pub struct SpectralTables {
    words: wgpu::Buffer,
    cie: wgpu::TextureView,
}

impl SpectralTables {
    /// Uploads the tables (the coefficient table is built on first use, on the CPU).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the tables exceed the device's storage-buffer or 2D
    /// texture limit.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let label = "the spectral tables";
        let words = spectral_words();
        let contents: &[u8] = bytemuck::cast_slice(&words);
        let limits = DeviceLimits::of(ctx);
        limits.check_storage_buffer(|| label.to_owned(), contents.len() as u64)?;
        let texels = cie_texels();
        let width = texels.len() as u32;
        limits.check_texture("the CIE 1931 table", width, 1)?;
        let cie = upload_2d(
            ctx,
            &Texture2d {
                label: "the CIE 1931 table",
                width,
                height: 1,
                mip_levels: 1,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
            },
            bytemuck::cast_slice(&texels),
        );
        Ok(Self {
            words: ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: wgpu::BufferUsages::STORAGE,
                }),
            cie: cie.create_view(&wgpu::TextureViewDescriptor::default()),
        })
    }

    /// The bind group entries of the tables (WGSL `spectral_tables` and `spectral_cie`).
    #[must_use]
    pub fn entries(&self) -> [wgpu::BindGroupEntry<'_>; 2] {
        [
            slots::SPECTRAL_TABLES.entry(self.words.as_entire_binding()),
            slots::SPECTRAL_CIE.entry(wgpu::BindingResource::TextureView(&self.cie)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cie_texels_are_the_cpu_table_in_f32() {
        let texels = cie_texels();
        assert_eq!(texels.len(), cie_1931().len());
        for (texel, sample) in texels.iter().zip(cie_1931()) {
            let cpu = [
                sample.xbar,
                sample.ybar,
                sample.zbar,
                1.0 / sample.wavelength_nm,
            ];
            assert_eq!(*texel, cpu.map(|v| v as f32));
        }
    }

    #[test]
    fn cie_rows_are_evenly_spaced_as_the_shader_computes_them() {
        // spectral.wgsl's reflected_light computes row s's wavelength as first + s · step from
        // the header's first and last wavelengths and the texture's width.
        let words = spectral_words();
        let (first, last) = (words[1], words[2]);
        let rows = cie_1931();
        let step = (last - first) / (rows.len() - 1) as f32;
        for (s, row) in rows.iter().enumerate() {
            assert_eq!(first + s as f32 * step, row.wavelength_nm as f32, "row {s}");
        }
    }

    #[test]
    fn spectral_words_hold_the_header_then_each_table() {
        let words = spectral_words();
        let table = srgb_coefficient_table();
        let n = words[0] as usize;
        assert_eq!(n, table.scale().len());
        assert_eq!(
            (words[1], words[2]),
            (360.0, 830.0),
            "the CIE table's wavelengths"
        );
        let scale = &words[SPECTRAL_HEADER_WORDS..SPECTRAL_HEADER_WORDS + n];
        assert_eq!(scale[n - 1], table.scale()[n - 1] as f32);
        let texels: &[f32] = bytemuck::cast_slice(table.texels());
        assert_eq!(&words[SPECTRAL_HEADER_WORDS + n..], texels);
    }
}
