//! The sky's GPU passes (`shaders/sky.wgsl`, mirror of srt-trace's `sky.rs`): the stars and the
//! sky image are uploaded once; per frame a compute pass splats each star's light into a
//! per-pixel buffer, and a full-screen compose triangle writes background + sky image + star
//! light into the colour target: last in the object pass, only where no object is seen
//! ([`SkyPlacement`]), or in a pass of its own when nothing is in view. A scene without a sky
//! has none of this: its passes clear to the background as before. Like meshes, the stars and the image are
//! uploaded with the scene; per frame only the sky's velocity, direction map and brightness
//! change.

use srt_scene::sky::SkyImage;
use srt_scene::{Scene, Sky};
use wgpu::util::DeviceExt as _;

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::limits::DeviceLimits;
use crate::passes::begin_pass;
use crate::pipelines::{
    DepthTest, FRAME_GROUP, SKY_BEHIND_POLYGONS_ENTRIES, SKY_COMPOSE_ENTRIES, SKY_COMPOSE_GROUP,
    SKY_FRAME_GROUP, SKY_STARS_ENTRIES, SKY_STARS_GROUP, SKY_WHERE_UNSEEN_ENTRIES, pipeline_layout,
    render_pipeline, sky_specs, slots,
};
use crate::shaders::WORKGROUP_SIZE;
use crate::textures::{Texture2d, upload_2d};
use crate::types::{GpuStar, SkyUniforms, mat3, vec4};

/// u32 words of star light per pixel: the largest contribution there, then R, G, B as
/// fixed-point sums scaled to it (WGSL `STAR_LIGHT_WORDS_PER_PIXEL` in sky.wgsl, checked by
/// `tests/reflect.rs`).
pub const STAR_LIGHT_WORDS_PER_PIXEL: u32 = 4;

/// Bytes of star light per pixel.
const STAR_LIGHT_BYTES_PER_PIXEL: u64 = STAR_LIGHT_WORDS_PER_PIXEL as u64 * 4;

/// What is uploaded once per scene and bound with every image size.
struct Uploaded {
    stars: wgpu::Buffer,
    uniforms: wgpu::Buffer,
    image: wgpu::TextureView,
    stars_layout: wgpu::BindGroupLayout,
    compose_layout: wgpu::BindGroupLayout,
}

/// The per-pixel star light buffer and the bind groups that use it, for one image size.
struct StarLight {
    buffer: wgpu::Buffer,
    stars_group: wgpu::BindGroup,
    compose_group: wgpu::BindGroup,
}

/// The uploaded sky and its pipelines.
pub struct SkyResources {
    uploaded: Uploaded,
    star_count: u32,
    image_size: Option<(u32, u32)>,
    /// The star passes, in [`SKY_STARS_ENTRIES`]' order.
    stars_pipelines: Vec<wgpu::ComputePipeline>,
    /// The compose pipeline of each [`SkyPlacement`] (in its order), each made on first use.
    compose_pipelines: [std::sync::OnceLock<wgpu::RenderPipeline>; 3],
    /// The colour target's format, for the compose pipelines.
    color_format: wgpu::TextureFormat,
    workgroups: (u32, u32),
    light: StarLight,
}

/// Where the sky's compose triangle is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SkyPlacement {
    /// In a pass of its own, over the whole colour target, before the objects' passes (which
    /// then draw over it): for a frame whose objects are all out of view.
    OwnPass,
    /// In the polygon pass after its objects, at the far plane with the depth test "equal":
    /// only where no triangle was drawn.
    BehindPolygons,
    /// In the exact methods' shading pass, at the part depth of "no part" with the depth test
    /// "equal": only where the visibility pass kept nothing.
    WhereUnseen,
}

impl SkyPlacement {
    /// The compose pipeline's entry points and depth test for this placement.
    fn pipeline(self) -> ([&'static str; 2], DepthTest) {
        match self {
            Self::OwnPass => (SKY_COMPOSE_ENTRIES, DepthTest::None),
            Self::BehindPolygons => (SKY_BEHIND_POLYGONS_ENTRIES, DepthTest::Equal),
            Self::WhereUnseen => (SKY_WHERE_UNSEEN_ENTRIES, DepthTest::Equal),
        }
    }
}

/// The shape of a sky as the GPU holds it: star count and image size. A scene whose sky has
/// another shape needs a new renderer.
#[must_use]
pub fn sky_shape(sky: &Sky) -> (usize, Option<(u32, u32)>) {
    (
        sky.stars.len(),
        sky.image.as_ref().map(|i| (i.width, i.height)),
    )
}

impl SkyResources {
    /// Uploads the sky of `scene` for images of `width` × `height`; `None` for a scene without
    /// one.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the stars, the image or the star-light buffer exceed the
    /// device's limits.
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Option<Self>, GpuError> {
        if scene.sky.is_empty() {
            return Ok(None);
        }
        let limits = DeviceLimits::of(ctx);
        let mut stars: Vec<GpuStar> = scene.sky.stars.iter().map(GpuStar::from).collect();
        let star_count = limits.check_u32(|| "the sky".to_owned(), stars.len() as u64, "stars")?;
        // A storage buffer may not be empty: a sky of an image alone gets one unused star.
        if stars.is_empty() {
            stars.push(GpuStar::from(&srt_scene::Star {
                direction: glam::DVec3::Z,
                temperature_k: 1.0,
                magnitude: 0.0,
            }));
        }
        let star_bytes = (stars.len() * size_of::<GpuStar>()) as u64;
        limits.check_storage_buffer(|| format!("the sky's {} stars", stars.len()), star_bytes)?;
        // An invocation per star and eye of a stereo pair (sky.wgsl's invocation_splat; the
        // second half returns at once for one picture).
        let workgroups = limits.workgroup_grid(
            || "the sky's star pass".to_owned(),
            2 * u64::from(star_count),
            WORKGROUP_SIZE,
        )?;
        if let Some(image) = &scene.sky.image {
            limits.check_texture(
                &format!("the sky image {}", image.source),
                image.width,
                image.height,
            )?;
        }
        let device = &ctx.device;
        let [stars_spec, _] = sky_specs();
        let stars_module = stars_spec.shader.module(device);
        let stars_layout = pipeline_layout(device, &stars_spec);
        let stars_pipelines = SKY_STARS_ENTRIES
            .iter()
            .map(|&entry| {
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(stars_spec.label),
                    layout: Some(&stars_layout),
                    module: &stars_module,
                    entry_point: Some(entry),
                    compilation_options: stars_spec.shader.compilation_options(),
                    cache: None,
                })
            })
            .collect();
        let uploaded = Uploaded {
            stars: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("srt sky stars"),
                contents: bytemuck::cast_slice(&stars),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            uniforms: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("srt sky uniforms"),
                size: size_of::<SkyUniforms>() as u64,
                usage: crate::shaders::BlockSpace::BUFFER_USAGES,
                mapped_at_creation: false,
            }),
            image: image_texture(ctx, scene.sky.image.as_ref()),
            stars_layout: SKY_STARS_GROUP.create_layout(device),
            compose_layout: SKY_COMPOSE_GROUP.create_layout(device),
        };
        let light = StarLight::new(ctx, &uploaded, width, height)?;
        Ok(Some(Self {
            uploaded,
            star_count,
            image_size: sky_shape(&scene.sky).1,
            stars_pipelines,
            compose_pipelines: Default::default(),
            color_format: ctx.color_format,
            workgroups,
            light,
        }))
    }

    /// The shape of the sky uploaded ([`sky_shape`]).
    #[must_use]
    pub fn shape(&self) -> (usize, Option<(u32, u32)>) {
        (self.star_count as usize, self.image_size)
    }

    /// Recreates the star-light buffer for images of `width` × `height`.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when it exceeds the device's limits.
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) -> Result<(), GpuError> {
        self.light = StarLight::new(ctx, &self.uploaded, width, height)?;
        Ok(())
    }

    /// Writes the sky's uniforms for `scene` (its motion relative to the observer now), for a
    /// target of `supersampling` × `supersampling` pixels per output pixel (see
    /// [`crate::GpuRenderer::set_supersampling`]).
    pub fn write_uniforms(&self, ctx: &GpuContext, scene: &Scene, supersampling: u32) {
        let sky = &scene.sky;
        let saturation = sky.saturation_magnitude;
        let (width, height) = self.image_size.unwrap_or((0, 0));
        let uniforms = SkyUniforms {
            beta_saturation: vec4(sky.beta, saturation),
            counts: [
                self.star_count,
                width,
                height,
                u32::from(self.image_size.is_some()),
            ],
            direction_map: mat3(sky.direction_map),
            direction_unmap: mat3(sky.direction_map.inverse()),
            image: [sky.image_brightness as f32, 0.0, 0.0, 0.0],
            supersampling: [supersampling.max(1), 0, 0, 0],
        };
        ctx.queue
            .write_buffer(&self.uploaded.uniforms, 0, bytemuck::bytes_of(&uniforms));
    }

    /// Records the star pass into `encoder`: the star light of every pixel, which the compose
    /// triangle ([`Self::draw_compose`]) adds. `stars_frame` is the frame's group 0 for it
    /// (uniforms and colour table of the tone map in use); `timestamp` (query set, index), when
    /// given, is written at its beginning (the pass is begun, and so timed, without stars too).
    pub fn encode_stars(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        stars_frame: &wgpu::BindGroup,
        timestamp: Option<(&wgpu::QuerySet, u32)>,
    ) {
        encoder.clear_buffer(&self.light.buffer, 0, None);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(SKY_STARS_GROUP.label),
            timestamp_writes: timestamp.map(|(query_set, index)| {
                wgpu::ComputePassTimestampWrites {
                    query_set,
                    beginning_of_pass_write_index: Some(index),
                    end_of_pass_write_index: None,
                }
            }),
        });
        if self.star_count > 0 {
            pass.set_bind_group(FRAME_GROUP.index, stars_frame, &[]);
            pass.set_bind_group(SKY_STARS_GROUP.index, &self.light.stars_group, &[]);
            for pipeline in &self.stars_pipelines {
                pass.set_pipeline(pipeline);
                pass.dispatch_workgroups(self.workgroups.0, self.workgroups.1, 1);
            }
        }
    }

    /// Records the star pass and a compose pass of its own ([`SkyPlacement::OwnPass`]) into
    /// `encoder`: `color` then holds background + sky image + star light everywhere.
    /// `compose_frame` is the frame's group for the compose triangle (with the spectral
    /// tables); the rest as [`Self::encode_stars`].
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        stars_frame: &wgpu::BindGroup,
        compose_frame: &wgpu::BindGroup,
        color: &wgpu::TextureView,
        timestamp: Option<(&wgpu::QuerySet, u32)>,
    ) {
        self.encode_stars(encoder, stars_frame, timestamp);
        let mut pass = begin_pass(
            encoder,
            SKY_COMPOSE_GROUP.label,
            color,
            wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            None,
            None,
        );
        self.draw_compose(device, &mut pass, compose_frame, SkyPlacement::OwnPass);
    }

    /// Draws the compose triangle into `pass` as `placement` says (after [`Self::encode_stars`]
    /// in the same frame): background + sky image + star light, as the frame's output holds it.
    /// The pass's bind groups 0 and 1 are replaced.
    pub fn draw_compose(
        &self,
        device: &wgpu::Device,
        pass: &mut wgpu::RenderPass<'_>,
        compose_frame: &wgpu::BindGroup,
        placement: SkyPlacement,
    ) {
        let (entries, depth) = placement.pipeline();
        let pipeline = self.compose_pipelines[placement as usize].get_or_init(|| {
            let [_, compose_spec] = sky_specs();
            render_pipeline(
                device,
                &compose_spec,
                entries,
                Some(self.color_format),
                depth,
            )
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(SKY_FRAME_GROUP.index, compose_frame, &[]);
        pass.set_bind_group(SKY_COMPOSE_GROUP.index, &self.light.compose_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// The sky image as an `Rgba32Float` texture read with `textureLoad`, or a 1 × 1 black one.
fn image_texture(ctx: &GpuContext, image: Option<&SkyImage>) -> wgpu::TextureView {
    let (width, height, texels): (u32, u32, Vec<[f32; 4]>) = match image {
        Some(image) => (
            image.width,
            image.height,
            image
                .texels
                .iter()
                .map(|&[r, g, b]| [r, g, b, 1.0])
                .collect(),
        ),
        None => (1, 1, vec![[0.0; 4]]),
    };
    upload_2d(
        ctx,
        &Texture2d {
            label: "srt sky image",
            width,
            height,
            mip_levels: 1,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
        },
        bytemuck::cast_slice(&texels),
    )
    .create_view(&wgpu::TextureViewDescriptor::default())
}

/// Checks that the star light of a `width` × `height` image fits one storage buffer binding.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] when it does not.
pub(crate) fn check_star_light(
    limits: &DeviceLimits,
    width: u32,
    height: u32,
) -> Result<(), GpuError> {
    limits.check_storage_buffer(
        || format!("the star light of a {width}×{height} image"),
        u64::from(width) * u64::from(height) * STAR_LIGHT_BYTES_PER_PIXEL,
    )
}

impl StarLight {
    fn new(
        ctx: &GpuContext,
        uploaded: &Uploaded,
        width: u32,
        height: u32,
    ) -> Result<Self, GpuError> {
        check_star_light(&DeviceLimits::of(ctx), width, height)?;
        let bytes = u64::from(width) * u64::from(height) * STAR_LIGHT_BYTES_PER_PIXEL;
        let device = &ctx.device;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt sky star light"),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let sky_uniforms = || slots::SKY.entry(uploaded.uniforms.as_entire_binding());
        let stars_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(SKY_STARS_GROUP.label),
            layout: &uploaded.stars_layout,
            entries: &[
                sky_uniforms(),
                slots::STARS.entry(uploaded.stars.as_entire_binding()),
                slots::STAR_LIGHT.entry(buffer.as_entire_binding()),
            ],
        });
        let compose_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(SKY_COMPOSE_GROUP.label),
            layout: &uploaded.compose_layout,
            entries: &[
                sky_uniforms(),
                slots::STAR_LIGHT_TOTAL.entry(buffer.as_entire_binding()),
                slots::SKY_IMAGE.entry(wgpu::BindingResource::TextureView(&uploaded.image)),
            ],
        });
        Ok(Self {
            buffer,
            stars_group,
            compose_group,
        })
    }
}
