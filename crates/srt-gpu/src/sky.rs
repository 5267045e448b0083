//! The sky's GPU passes (`shaders/sky.wgsl`, mirror of srt-trace's `sky.rs`): the stars are
//! uploaded once; per frame a compute pass splats each star's light into a per-pixel buffer and
//! a full-screen pass writes background + star light into the colour target, which the object
//! passes then draw over. A scene without stars has none of this: its passes clear to the
//! background as before.

use srt_scene::Scene;
use wgpu::util::DeviceExt as _;

use crate::context::{GpuContext, GpuError};
use crate::limits::DeviceLimits;
use crate::passes::begin_colour_pass;
use crate::pipelines::{
    FRAME_GROUP, SKY_COMPOSE_ENTRIES, SKY_COMPOSE_GROUP, SKY_STARS_ENTRY, SKY_STARS_GROUP,
    pipeline_layout, render_pipeline, sky_specs, slots,
};
use crate::shaders::WORKGROUP_SIZE;
use crate::types::{GpuStar, SkyUniforms, vec4};

/// Bytes of star light per pixel: three u32 channels.
const STAR_LIGHT_BYTES_PER_PIXEL: u64 = 12;

/// The per-pixel star light buffer and the bind groups that use it, for one image size.
struct StarLight {
    buffer: wgpu::Buffer,
    stars_group: wgpu::BindGroup,
    compose_group: wgpu::BindGroup,
}

/// The uploaded stars and the sky's pipelines.
pub struct SkyResources {
    stars: wgpu::Buffer,
    star_count: u32,
    uniforms: wgpu::Buffer,
    stars_pipeline: wgpu::ComputePipeline,
    compose_pipeline: wgpu::RenderPipeline,
    stars_layout: wgpu::BindGroupLayout,
    compose_layout: wgpu::BindGroupLayout,
    workgroups: (u32, u32),
    light: StarLight,
}

impl SkyResources {
    /// Uploads the stars of `scene` for images of `width` × `height` rendered into
    /// `color_format`; `None` for a scene without stars.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the stars or the star-light buffer exceed the device's
    /// limits.
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
        let stars: Vec<GpuStar> = scene.sky.stars.iter().map(GpuStar::from).collect();
        let star_bytes = (stars.len() * size_of::<GpuStar>()) as u64;
        limits.check_storage_buffer(|| format!("the sky's {} stars", stars.len()), star_bytes)?;
        let star_count = limits.check_u32(|| "the sky".to_owned(), stars.len() as u64, "stars")?;
        let workgroups = limits.workgroup_grid(
            || "the sky's star pass".to_owned(),
            u64::from(star_count),
            WORKGROUP_SIZE,
        )?;
        let device = &ctx.device;
        let [stars_spec, compose_spec] = sky_specs();
        let stars_module = stars_spec.shader.module(device);
        let stars_pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(stars_spec.label),
            layout: Some(&pipeline_layout(device, &stars_spec)),
            module: &stars_module,
            entry_point: Some(SKY_STARS_ENTRY),
            compilation_options: stars_spec.shader.compilation_options(),
            cache: None,
        });
        let compose_pipeline = render_pipeline(
            device,
            &compose_spec,
            SKY_COMPOSE_ENTRIES,
            ctx.color_format,
            false,
        );
        let stars_layout = SKY_STARS_GROUP.create_layout(device);
        let compose_layout = SKY_COMPOSE_GROUP.create_layout(device);
        let stars = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("srt sky stars"),
            contents: bytemuck::cast_slice(&stars),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt sky uniforms"),
            size: size_of::<SkyUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let light = StarLight::new(
            ctx,
            &stars,
            &uniforms,
            &stars_layout,
            &compose_layout,
            width,
            height,
        )?;
        Ok(Some(Self {
            stars,
            star_count,
            uniforms,
            stars_pipeline,
            compose_pipeline,
            stars_layout,
            compose_layout,
            workgroups,
            light,
        }))
    }

    /// The number of stars uploaded.
    #[must_use]
    pub const fn star_count(&self) -> u32 {
        self.star_count
    }

    /// Recreates the star-light buffer for images of `width` × `height`.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when it exceeds the device's limits.
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) -> Result<(), GpuError> {
        self.light = StarLight::new(
            ctx,
            &self.stars,
            &self.uniforms,
            &self.stars_layout,
            &self.compose_layout,
            width,
            height,
        )?;
        Ok(())
    }

    /// Writes the sky's uniforms for `scene` (its motion relative to the observer now), each
    /// star's light multiplied by `light_scale` (see [`crate::GpuRenderer::set_star_light_scale`]):
    /// the saturation magnitude moves by 2.5 log₁₀ of it (Pogson).
    pub fn write_uniforms(&self, ctx: &GpuContext, scene: &Scene, light_scale: f64) {
        let saturation = scene.sky.saturation_magnitude + 2.5 * light_scale.log10();
        let uniforms = SkyUniforms {
            beta_saturation: vec4(scene.sky.beta, saturation),
            counts: [self.star_count, 0, 0, 0],
        };
        ctx.queue
            .write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
    }

    /// Records the star pass and the background pass into `encoder`: `color` then holds
    /// background + star light. `frame_group` is the frame's group 0 (uniforms and colour
    /// table of the tone map in use).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame_group: &wgpu::BindGroup,
        color: &wgpu::TextureView,
    ) {
        encoder.clear_buffer(&self.light.buffer, 0, None);
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(SKY_STARS_GROUP.label),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.stars_pipeline);
            pass.set_bind_group(FRAME_GROUP.index, frame_group, &[]);
            pass.set_bind_group(SKY_STARS_GROUP.index, &self.light.stars_group, &[]);
            pass.dispatch_workgroups(self.workgroups.0, self.workgroups.1, 1);
        }
        let mut pass = begin_colour_pass(
            encoder,
            SKY_COMPOSE_GROUP.label,
            color,
            wgpu::LoadOp::Clear(wgpu::Color::BLACK),
        );
        pass.set_pipeline(&self.compose_pipeline);
        pass.set_bind_group(FRAME_GROUP.index, frame_group, &[]);
        pass.set_bind_group(SKY_COMPOSE_GROUP.index, &self.light.compose_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

impl StarLight {
    fn new(
        ctx: &GpuContext,
        stars: &wgpu::Buffer,
        uniforms: &wgpu::Buffer,
        stars_layout: &wgpu::BindGroupLayout,
        compose_layout: &wgpu::BindGroupLayout,
        width: u32,
        height: u32,
    ) -> Result<Self, GpuError> {
        let bytes = u64::from(width) * u64::from(height) * STAR_LIGHT_BYTES_PER_PIXEL;
        DeviceLimits::of(ctx).check_storage_buffer(
            || format!("the star light of a {width}×{height} image"),
            bytes,
        )?;
        let device = &ctx.device;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt sky star light"),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let stars_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(SKY_STARS_GROUP.label),
            layout: stars_layout,
            entries: &[
                slots::SKY.entry(uniforms.as_entire_binding()),
                slots::STARS.entry(stars.as_entire_binding()),
                slots::STAR_LIGHT.entry(buffer.as_entire_binding()),
            ],
        });
        let compose_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(SKY_COMPOSE_GROUP.label),
            layout: compose_layout,
            entries: &[slots::STAR_LIGHT_TOTAL.entry(buffer.as_entire_binding())],
        });
        Ok(Self {
            buffer,
            stars_group,
            compose_group,
        })
    }
}
