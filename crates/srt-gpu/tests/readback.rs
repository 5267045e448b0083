//! `read_texture` returns a texture's texels with the copy's row padding removed.

use srt_gpu::textures::{Texture2d, upload_2d};
use srt_gpu::{context_or_skip, read_texture};

#[test]
fn read_texture_returns_tightly_packed_rows() {
    let Some(ctx) = context_or_skip("read_texture_returns_tightly_packed_rows") else {
        return;
    };
    // 13 × 5 RGBA8 texels: 52-byte rows, padded to 256 in the copy.
    let (width, height) = (13u32, 5u32);
    let texels: Vec<u8> = (0..width * height * 4).map(|i| (i % 251) as u8).collect();
    let texture = upload_2d(
        &ctx,
        &Texture2d {
            label: "readback test",
            width,
            height,
            mip_levels: 1,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::COPY_SRC,
        },
        &texels,
    );
    assert_eq!(read_texture(&ctx, &texture).unwrap(), texels);
    ctx.take_errors().unwrap();
}
