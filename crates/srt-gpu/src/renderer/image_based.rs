//! The image-based method ([`Method::ImageBased`], the paper's Table 1 "IB"): per velocity
//! group, its objects rasterised at rest into a cube map around the observation event's
//! position in the group's rest frame, then every pixel's direction aberrated into that frame
//! and looked up (`shaders/image_based.wgsl`). The groups compose by apparent distance through
//! the depth test; the sky is drawn behind them as in the polygon pass.

use super::encode::variant_of_part;
use super::*;
use crate::pipelines::IB_CUBE_GROUP;
use crate::shaders::ObjectVariant;
use crate::sky::SkyPlacement;

/// The cube-map faces, in the order of `ib_face_basis` (image_based.wgsl): +x, −x, +y, −y, +z,
/// −z of the group's rest frame.
const CUBE_FACES: u32 = 6;

/// One velocity group's cube map (reused by each group in turn) and its depth.
pub(super) struct CubeMap {
    /// Texels a side of each face.
    size: u32,
    /// One view per face (a layer of the colour texture), the faces' render targets.
    face_views: Vec<wgpu::TextureView>,
    /// The faces' depth (cleared for each face).
    depth_view: wgpu::TextureView,
    /// The look-up's group 3: the six faces as one array.
    bind_group: wgpu::BindGroup,
}

impl CubeMap {
    /// A cube map of `size` × `size` texels per face in the colour target's format.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when a face of that size is larger than the device allows,
    /// [`GpuError::Unsupported`] for a side of 0.
    pub(super) fn new(ctx: &GpuContext, size: u32) -> Result<Self, GpuError> {
        if size == 0 {
            return Err(GpuError::Unsupported(
                "an image-based cube map of 0 texels a side".into(),
            ));
        }
        DeviceLimits::of(ctx).check_texture("image-based cube map face", size, size)?;
        let device = &ctx.device;
        let extent = |layers| wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        };
        // wgpu's GL backend makes a 2D texture of 6 layers a cube map (its target is chosen at
        // creation, gfx-rs/wgpu#7428), which a 2D-array binding then reads as zeros: one spare
        // layer there keeps it an array.
        let layers = if ctx.adapter_info.backend == wgpu::Backend::Gl {
            CUBE_FACES + 1
        } else {
            CUBE_FACES
        };
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("srt image-based cube map"),
            size: extent(layers),
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: ctx.color_format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let depth = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("srt image-based face depth"),
            size: extent(1),
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let face_views = (0..CUBE_FACES)
            .map(|face| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("srt image-based face"),
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: face,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        let array = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("srt image-based cube map"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(IB_CUBE_GROUP.label),
            layout: &IB_CUBE_GROUP.create_layout(device),
            entries: &[slots::IB_CUBE.entry(wgpu::BindingResource::TextureView(&array))],
        });
        Ok(Self {
            size,
            face_views,
            depth_view: depth.create_view(&Default::default()),
            bind_group,
        })
    }
}

/// The objects `shown` (indices into `scene.objects`) grouped by the velocity of their rest
/// frame, each group in the order of its first member in `shown`.
pub(super) fn velocity_groups(scene: &Scene, shown: &[usize]) -> Vec<Vec<usize>> {
    let mut groups: Vec<(DVec3, Vec<usize>)> = Vec::new();
    for &index in shown {
        let beta = scene.objects[index].frame.beta();
        match groups.iter_mut().find(|(velocity, _)| *velocity == beta) {
            Some((_, members)) => members.push(index),
            None => groups.push((beta, vec![index])),
        }
    }
    groups.into_iter().map(|(_, members)| members).collect()
}

impl super::GpuRenderer {
    /// The cube map of `size` texels a side: the one of the last image-based frame, or a new
    /// one where the size changed.
    fn cube_map(&self, ctx: &GpuContext, size: u32) -> Result<Arc<CubeMap>, GpuError> {
        let mut kept = self
            .cube_map
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(cube) = kept.as_ref().filter(|cube| cube.size == size) {
            return Ok(Arc::clone(cube));
        }
        *kept = None;
        let cube = Arc::new(CubeMap::new(ctx, size)?);
        *kept = Some(Arc::clone(&cube));
        Ok(cube)
    }

    /// Encodes the image-based frame (timestamps 2 and 3): the sky's passes, then per velocity
    /// group of the objects `shown` ([`velocity_groups`]) its six faces and its look-up into
    /// `color_view` and `depth_view` (apparent distance), the sky composed behind them in the
    /// last look-up.
    #[expect(
        clippy::too_many_arguments,
        reason = "the frame's state as encode_render_pass has it"
    )]
    pub(super) fn encode_image_based(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        background: DVec4,
        tone: usize,
        variants: &[ObjectVariant],
        shown: &[usize],
        (color_view, depth_view): (&wgpu::TextureView, &wgpu::TextureView),
    ) -> Result<(), GpuError> {
        let device = &ctx.device;
        let placement = SkyPlacement::BehindPolygons;
        let background =
            self.encode_background(device, encoder, background, tone, color_view, placement);
        let groups = velocity_groups(scene, shown);
        let frame_group = &self.frame.polygon_groups[tone];
        let target_depth = |first: bool| wgpu::RenderPassDepthStencilAttachment {
            view: depth_view,
            depth_ops: Some(wgpu::Operations {
                load: if first {
                    wgpu::LoadOp::Clear(1.0)
                } else {
                    wgpu::LoadOp::Load
                },
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        };
        if groups.is_empty() {
            let mut pass = self.begin_pass(
                encoder,
                "srt image-based empty frame",
                color_view,
                background,
                Some(target_depth(true)),
                [Some(2), Some(3)],
            );
            self.draw_sky(device, &mut pass, tone, placement);
            return Ok(());
        }
        let cube = self.cube_map(ctx, scene.cube_map_size)?;
        // Nothing drawn: object index + 1 = 0 (image_based.wgsl).
        let empty = wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT);
        for (number, members) in groups.iter().enumerate() {
            let (first, last) = (number == 0, number + 1 == groups.len());
            for (face, face_view) in (0..CUBE_FACES).zip(&cube.face_views) {
                let face_depth = wgpu::RenderPassDepthStencilAttachment {
                    view: &cube.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                };
                let stamp = (first && face == 0).then_some(2);
                let mut pass = self.begin_pass(
                    encoder,
                    "srt image-based face",
                    face_view,
                    empty,
                    Some(face_depth),
                    [stamp, None],
                );
                pass.set_bind_group(POLYGON_FRAME_GROUP.index, frame_group, &[]);
                for &index in members {
                    let object = &self.objects[index];
                    pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
                    for part in &object.parts {
                        let variant = variant_of_part(variants[index], part);
                        pass.set_pipeline(&self.pipelines.image_based(device, variant).face);
                        pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                        // Checked at upload: 3 × triangles fits in u32; six faces' vertex
                        // indices fit too below 238 M triangles a part.
                        let per_face = 3 * part.sizes.triangles;
                        pass.draw(face * per_face..(face + 1) * per_face, 0..1);
                    }
                }
            }
            let load = if first {
                background
            } else {
                wgpu::LoadOp::Load
            };
            let mut pass = self.begin_pass(
                encoder,
                "srt image-based look-up",
                color_view,
                load,
                Some(target_depth(first)),
                [None, last.then_some(3)],
            );
            let representative = &self.objects[members[0]];
            let variant = variants[members[0]];
            pass.set_pipeline(&self.pipelines.image_based(device, variant).lookup);
            pass.set_bind_group(POLYGON_FRAME_GROUP.index, frame_group, &[]);
            pass.set_bind_group(OBJECT_GROUP.index, &representative.bind_group, &[]);
            pass.set_bind_group(PART_GROUP.index, &representative.parts[0].bind_group, &[]);
            pass.set_bind_group(IB_CUBE_GROUP.index, &cube.bind_group, &[]);
            pass.draw(0..3, 0..1);
            if last {
                self.draw_sky(device, &mut pass, tone, placement);
            }
        }
        Ok(())
    }
}
