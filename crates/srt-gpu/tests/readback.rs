//! `read_texture` returns a texture's texels with the copy's row padding removed.

use srt_gpu::{context_or_skip, read_texture};
use wgpu::util::DeviceExt as _;

#[test]
fn read_texture_returns_tightly_packed_rows() {
    let Some(ctx) = context_or_skip("read_texture_returns_tightly_packed_rows") else {
        return;
    };
    // 13 × 5 RGBA8 texels: 52-byte rows, padded to 256 in the copy.
    let (width, height) = (13u32, 5u32);
    let texels: Vec<u8> = (0..width * height * 4).map(|i| (i % 251) as u8).collect();
    let texture = ctx.device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: Some("readback test"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &texels,
    );
    assert_eq!(read_texture(&ctx, &texture).unwrap(), texels);
    ctx.take_errors().unwrap();
}
