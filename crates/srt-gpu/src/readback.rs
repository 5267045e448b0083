//! Reading textures back to memory. wgpu copies a texture into a buffer whose rows are padded
//! to `COPY_BYTES_PER_ROW_ALIGNMENT` (256 bytes); this module owns that padding, so callers (the
//! renderer, the viewer) get tightly packed rows.

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::{DeviceLimits, padded_row_bytes};

/// A buffer that receives one mip-0 image of a 2D texture, and the row layout to unpack it.
pub struct TextureReadback {
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    row_bytes: u32,
    padded_row_bytes: u32,
}

/// Bytes per texel of `format`, for formats that can be copied to a buffer whole.
///
/// # Errors
/// [`GpuError::Readback`] for formats without a single copy size (depth-stencil, planar).
pub fn texel_bytes(format: wgpu::TextureFormat) -> Result<u32, GpuError> {
    format
        .block_copy_size(None)
        .filter(|_| format.block_dimensions() == (1, 1))
        .ok_or_else(|| GpuError::Readback(format!("{format:?} textures cannot be read back")))
}

impl TextureReadback {
    /// The buffer for a `width` × `height` texture of `format`.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the padded buffer exceeds the device's `max_buffer_size`,
    /// [`GpuError::Readback`] for a format that cannot be copied whole.
    pub fn new(
        ctx: &GpuContext,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> Result<Self, GpuError> {
        let texel = texel_bytes(format)?;
        let padded = padded_row_bytes(width, texel);
        let size = padded * u64::from(height);
        DeviceLimits::of(ctx).check_buffer(
            || format!("the readback buffer of a {width} × {height} texture"),
            size,
        )?;
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt texture readback"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Ok(Self {
            buffer,
            width,
            height,
            row_bytes: width * texel,
            // Below max_buffer_size / height, checked above; a row fits in u32 as wgpu requires.
            padded_row_bytes: u32::try_from(padded).map_err(|_| {
                GpuError::Readback(format!("a row of {padded} bytes is too long to copy"))
            })?,
        })
    }

    /// Records the copy of `texture` (mip 0, the size this buffer was made for) into `encoder`.
    pub fn encode_copy(&self, encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture) {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row_bytes),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// Maps the buffer after the copy was submitted: the texels row by row from the top, rows
    /// tightly packed (width × texel bytes each).
    ///
    /// # Errors
    /// [`GpuError::Readback`] when mapping fails.
    pub fn read(&self, ctx: &GpuContext) -> Result<Vec<u8>, GpuError> {
        ctx.read_buffer_with(&self.buffer, |bytes| {
            unpad_rows(
                bytes,
                self.row_bytes as usize,
                self.padded_row_bytes as usize,
            )
        })
    }
}

/// The first `row_bytes` of every `padded_row_bytes`-long row of `bytes`, concatenated.
fn unpad_rows(bytes: &[u8], row_bytes: usize, padded_row_bytes: usize) -> Vec<u8> {
    let mut rows = Vec::with_capacity(bytes.len() / padded_row_bytes * row_bytes);
    for row in bytes.chunks_exact(padded_row_bytes) {
        rows.extend_from_slice(&row[..row_bytes]);
    }
    rows
}

/// Copies `texture` (mip 0, whole) to memory: its texels row by row from the top, rows tightly
/// packed. Submits its own copy, after whatever was submitted before.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] or [`GpuError::Readback`] as [`TextureReadback::new`] and
/// [`TextureReadback::read`] give them.
pub fn read_texture(ctx: &GpuContext, texture: &wgpu::Texture) -> Result<Vec<u8>, GpuError> {
    let readback = TextureReadback::new(ctx, texture.width(), texture.height(), texture.format())?;
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("srt texture readback"),
        });
    readback.encode_copy(&mut encoder, texture);
    ctx.queue.submit([encoder.finish()]);
    readback.read(ctx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn padding_is_dropped_row_by_row() {
        // Two rows of 3 bytes, each padded to 5.
        let padded = [1, 2, 3, 0, 0, 4, 5, 6, 0, 0];
        assert_eq!(unpad_rows(&padded, 3, 5), [1, 2, 3, 4, 5, 6]);
    }

    #[test]
    fn texel_sizes_of_the_colour_formats() {
        assert_eq!(texel_bytes(wgpu::TextureFormat::Rgba32Float).unwrap(), 16);
        assert_eq!(texel_bytes(wgpu::TextureFormat::Rgba16Float).unwrap(), 8);
        assert_eq!(texel_bytes(wgpu::TextureFormat::Rgba8Unorm).unwrap(), 4);
        assert!(texel_bytes(wgpu::TextureFormat::Depth24PlusStencil8).is_err());
    }
}
