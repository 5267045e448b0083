//! Textures uploaded from the CPU, in one place: the one 2D upload every texture goes
//! through ([`upload_2d`]: the sky image, the colour table, the parts' textures with their mip
//! chains) and the part texture the shading passes sample.

use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::Arc;

use srt_scene::Texture;
use srt_scene::mip::{MipChain, MipLevel};
use wgpu::util::DeviceExt as _;

use crate::context::GpuContext;

/// What a 2D texture uploaded by [`upload_2d`] is.
#[derive(Debug, Clone, Copy)]
pub struct Texture2d<'a> {
    /// wgpu's debug label.
    pub label: &'a str,
    /// Width of the first level in texels.
    pub width: u32,
    /// Height of the first level in texels.
    pub height: u32,
    /// Mip levels in the data, each half the size of the one before (1: no mip chain).
    pub mip_levels: u32,
    /// Texel format of the data.
    pub format: wgpu::TextureFormat,
    /// How the texture is used, besides being written by the upload (`COPY_DST` is added).
    pub usage: wgpu::TextureUsages,
}

/// Creates the texture `texture` describes holding `data`: its levels one after the other,
/// each in rows of tightly packed texels.
#[must_use]
pub fn upload_2d(ctx: &GpuContext, texture: &Texture2d<'_>, data: &[u8]) -> wgpu::Texture {
    ctx.device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: Some(texture.label),
            size: wgpu::Extent3d {
                width: texture.width,
                height: texture.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: texture.mip_levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: texture.format,
            usage: texture.usage | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        data,
    )
}

/// The part textures of one scene's upload, each image uploaded once however many batches show
/// it (the scene's builder shares one texture among the parts that describe the same one).
#[derive(Default)]
pub(crate) struct PartTextures(RefCell<HashMap<*const Texture, (wgpu::TextureView, u32)>>);

impl PartTextures {
    /// [`part_texture`] of `texture`, uploaded on first use.
    pub(crate) fn of(
        &self,
        ctx: &GpuContext,
        texture: Option<&Arc<Texture>>,
    ) -> (wgpu::TextureView, u32) {
        let key = texture.map_or(std::ptr::null(), Arc::as_ptr);
        self.0
            .borrow_mut()
            .entry(key)
            .or_insert_with(|| part_texture(ctx, texture.map(Arc::as_ref)))
            .clone()
    }
}

/// `texture` with its mip chain (levels larger than the device allows are skipped), or, for
/// `None`, a 1×1 white texture: the `part_texture` the shading passes sample by hand, and the
/// height of one of its frames in the first level uploaded.
pub(crate) fn part_texture(
    ctx: &GpuContext,
    texture: Option<&Texture>,
) -> (wgpu::TextureView, u32) {
    let limit = ctx.device.limits().max_texture_dimension_2d;
    let white = MipLevel {
        width: 1,
        height: 1,
        frame_height: 1,
        texels: vec![[255; 4]],
    };
    let chain = texture.map(MipChain::new);
    let mut levels: Vec<&MipLevel> = chain.as_ref().map_or_else(Vec::new, |chain| {
        chain
            .levels()
            .iter()
            .filter(|l| l.width <= limit && l.height <= limit)
            .collect()
    });
    if levels.is_empty() {
        levels.push(&white);
    }
    let data: Vec<u8> = levels
        .iter()
        .flat_map(|l| l.texels.iter().flatten().copied())
        .collect();
    let view = upload_2d(
        ctx,
        &Texture2d {
            label: "srt part texture",
            width: levels[0].width,
            height: levels[0].height,
            mip_levels: levels.len() as u32,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
        },
        &data,
    )
    .create_view(&wgpu::TextureViewDescriptor::default());
    (view, levels[0].frame_height)
}
