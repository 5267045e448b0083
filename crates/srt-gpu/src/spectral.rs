//! The tables of spectral colour on the GPU (`shaders/spectral.wgsl`): the CIE 1931 table and
//! the Jakob–Hanika coefficient table, uploaded once per renderer from the CPU's own tables
//! (`srt_color::cie_1931`, `srt_color::srgb_coefficient_table`), so that both sides use the same
//! numbers.

use srt_color::{cie_1931, srgb_coefficient_table};
use wgpu::util::DeviceExt as _;

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::pipelines::slots;
use crate::types::GpuCieSample;

/// The CIE table as WGSL `cie_table` reads it, in f32.
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

/// The three storage buffers of spectral colour.
pub struct SpectralTables {
    cie: wgpu::Buffer,
    scale: wgpu::Buffer,
    coefficients: wgpu::Buffer,
}

impl SpectralTables {
    /// Uploads the tables (the coefficient table is built on first use, on the CPU).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when a table exceeds the device's storage-buffer limit.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let table = srgb_coefficient_table();
        let scale: Vec<f32> = table.scale().iter().map(|&z| z as f32).collect();
        let limits = DeviceLimits::of(ctx);
        let buffer = |label: &'static str, contents: &[u8]| {
            limits.check_storage_buffer(|| label.to_owned(), contents.len() as u64)?;
            Ok(ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: wgpu::BufferUsages::STORAGE,
                }))
        };
        Ok(Self {
            cie: buffer("the CIE 1931 table", bytemuck::cast_slice(&cie_rows()))?,
            scale: buffer("the coefficient scale", bytemuck::cast_slice(&scale))?,
            coefficients: buffer(
                "the coefficient table",
                bytemuck::cast_slice(table.texels()),
            )?,
        })
    }

    /// The bind group entries of the tables (WGSL `cie_table`, `coefficient_scale`,
    /// `coefficient_table`).
    #[must_use]
    pub fn entries(&self) -> [wgpu::BindGroupEntry<'_>; 3] {
        [
            slots::CIE_TABLE.entry(self.cie.as_entire_binding()),
            slots::COEFFICIENT_SCALE.entry(self.scale.as_entire_binding()),
            slots::COEFFICIENT_TABLE.entry(self.coefficients.as_entire_binding()),
        ]
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
}
