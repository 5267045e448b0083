//! The tables of spectral colour on the GPU (`shaders/spectral.wgsl`): the CIE 1931 table and
//! the Jakob–Hanika coefficient table, in one buffer uploaded once per renderer from the CPU's own tables
//! (`srt_color::cie_1931`, `srt_color::srgb_coefficient_table`), so that both sides use the same
//! numbers.

use srt_color::{cie_1931, srgb_coefficient_table};
use wgpu::util::DeviceExt as _;

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::pipelines::slots;
use crate::types::GpuCieSample;

/// The CIE table as WGSL `cie_sample` reads it, in f32.
#[must_use]
pub fn cie_rows() -> Vec<GpuCieSample> {
    cie_1931()
        .iter()
        .map(|s| GpuCieSample {
            xyz_bar: [s.xbar, s.ybar, s.zbar].map(|v| v as f32),
            wavelength_nm: s.wavelength_nm as f32,
        })
        .collect()
}

/// Words before the tables in [`SpectralTables`]' buffer: the number of brightness-scale
/// entries and of CIE rows (as f32, exact for any table size up to 2²⁴).
pub const SPECTRAL_HEADER_WORDS: usize = 2;

/// The spectral tables as WGSL `spectral_tables` reads them (spectral.wgsl's accessors), one
/// array of f32: the header ([`SPECTRAL_HEADER_WORDS`]: n scale entries, c CIE rows), the
/// coefficient table's brightness scale (n), the CIE rows ([`GpuCieSample`], four words each),
/// then the coefficient texels (three words each, in `CoefficientTable::texels`' layout). One
/// buffer, not three: every storage binding counts against the shading pass's limit of eight
/// per stage, which its uniforms now share (docs/ARCHITECTURE.md, "No uniform buffers").
#[must_use]
pub fn spectral_words() -> Vec<f32> {
    let table = srgb_coefficient_table();
    let rows = cie_rows();
    let scale = table.scale();
    let mut words = Vec::with_capacity(
        SPECTRAL_HEADER_WORDS + scale.len() + 4 * rows.len() + 3 * table.texels().len(),
    );
    words.push(scale.len() as f32);
    words.push(rows.len() as f32);
    words.extend(scale.iter().map(|&z| z as f32));
    words.extend_from_slice(bytemuck::cast_slice(&rows));
    words.extend_from_slice(bytemuck::cast_slice(table.texels()));
    words
}

/// The storage buffer of spectral colour ([`spectral_words`]).
pub struct SpectralTables {
    words: wgpu::Buffer,
}

impl SpectralTables {
    /// Uploads the tables (the coefficient table is built on first use, on the CPU).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the tables exceed the device's storage-buffer limit.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let label = "the spectral tables";
        let words = spectral_words();
        let contents: &[u8] = bytemuck::cast_slice(&words);
        DeviceLimits::of(ctx).check_storage_buffer(|| label.to_owned(), contents.len() as u64)?;
        Ok(Self {
            words: ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: wgpu::BufferUsages::STORAGE,
                }),
        })
    }

    /// The bind group entry of the tables (WGSL `spectral_tables`).
    #[must_use]
    pub fn entry(&self) -> wgpu::BindGroupEntry<'_> {
        slots::SPECTRAL_TABLES.entry(self.words.as_entire_binding())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cie_rows_are_the_cpu_table_in_f32() {
        let rows = cie_rows();
        assert_eq!(rows.len(), cie_1931().len());
        assert_eq!(rows.first().map(|r| r.wavelength_nm), Some(360.0));
        assert_eq!(rows.last().map(|r| r.wavelength_nm), Some(830.0));
        for (row, sample) in rows.iter().zip(cie_1931()) {
            let cpu = [sample.xbar, sample.ybar, sample.zbar].map(|v| v as f32);
            assert_eq!(row.xyz_bar, cpu);
        }
    }

    #[test]
    fn cie_rows_are_evenly_spaced_as_the_shader_computes_them() {
        // spectral.wgsl's reflected_light computes row s's wavelength as first + s · step.
        let rows = cie_rows();
        let (first, last) = (rows[0].wavelength_nm, rows[rows.len() - 1].wavelength_nm);
        let step = (last - first) / (rows.len() - 1) as f32;
        for (s, row) in rows.iter().enumerate() {
            assert_eq!(row.wavelength_nm, first + s as f32 * step, "row {s}");
        }
    }

    #[test]
    fn spectral_words_hold_the_header_then_each_table() {
        let words = spectral_words();
        let table = srgb_coefficient_table();
        let (n, c) = (words[0] as usize, words[1] as usize);
        assert_eq!((n, c), (table.scale().len(), cie_1931().len()));
        let scale = &words[SPECTRAL_HEADER_WORDS..SPECTRAL_HEADER_WORDS + n];
        assert_eq!(scale[n - 1], table.scale()[n - 1] as f32);
        let rows = &words[SPECTRAL_HEADER_WORDS + n..SPECTRAL_HEADER_WORDS + n + 4 * c];
        assert_eq!(rows[3], 360.0, "the first row's wavelength");
        assert_eq!(rows[4 * c - 1], 830.0, "the last row's wavelength");
        let texels: &[f32] = bytemuck::cast_slice(table.texels());
        assert_eq!(&words[SPECTRAL_HEADER_WORDS + n + 4 * c..], texels);
    }
}
