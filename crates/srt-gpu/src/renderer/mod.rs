//! The GPU renderer: uploads a scene once, then renders it (local ray tracing, the ray tracer,
//! or the approximate polygon and image-based methods) for any observer, time, velocities and
//! effect mode with the same mesh structure, and reads the image back.
//!
//! Everything the renderer allocates is checked against the device's limits first
//! ([`crate::limits`]), so a scene or image size the adapter cannot serve is a
//! [`GpuError::ExceedsLimit`] before any GPU object exists.

use std::sync::Arc;

use glam::{DVec3, DVec4};
use srt_color::{
    Output, RadianceTable, TemperatureLut, ToneMap, quantize_8bit, searchlight_reference_ln_y,
    srgb_decode,
};
use srt_scene::{Object, Part, Scene};
use wgpu::util::DeviceExt as _;

use crate::bvh::ObjectBvh;
use crate::context::GpuContext;
use crate::culling::BackFaceCulling;
use crate::error::GpuError;
use crate::formats::{DEPTH_FORMAT, VISIBLE_ID_FORMAT, largest_value};
use crate::limits::DeviceLimits;
use crate::lut::{lut_params, lut_texture};
use crate::passes::FrameShared;
use crate::pipelines::{
    FRAME_GROUP, LRT_INPUT_GROUP, OBJECT_GROUP, PART_GROUP, POLYGON_FRAME_GROUP,
    PROXY_OUTPUT_GROUP, Pipelines, RT_INPUT_GROUP, SHADE_FRAME_GROUP, SKY_FRAME_GROUP, slots,
};
use crate::projection::{ImageWindow, target_camera};
use crate::ray_tracing::{BOX_TRIANGLES, ObjectRayTracing, object_bvh};
use crate::readback::{TextureReadback, texel_bytes};
use crate::shaders::{BlockSpace, WORKGROUP_SIZE};
use crate::shadows::{
    ShadowRows, ShadowScene, empty_shadow_buffer, frame_has_casters, light_uniforms,
};
use crate::sky::{SkyResources, sky_shape};
use crate::spectral::SpectralTables;
use crate::textures::PartTextures;
use crate::types::{
    ClockUniforms, DRAW_ARGS_BYTES, DRAW_ARGS_PIECES_TAKEN, EffectsCode, FOOTPRINT_VERTICES,
    FRAGMENT_COUNTER_BYTES, FRAME_BOUND_BYTES, FootprintCode, FrameUniforms, GpuFootprint,
    GpuFrame, GpuRtTriangle, GpuVertex, ObjectUniforms, OutputCode, PartFlags, PartUniforms,
    SHADE_DRAW_OFFSET, SurfaceColourCode, ToneMapCode, blink4, footprint_slots, mat4, object_time,
    optics4, radiance_params, vec4,
};

mod encode;
mod image_based;
mod targets;
mod upload;

use targets::{
    FragmentCounter, FrameResources, SKY_TIMESTAMP, TIMESTAMP_COUNT, Targets, Timestamps,
};
use upload::{ObjectResources, PartResources, ShadowSource, Uploader, batches, upload_object};

/// LRT depth = apparent distance × this (apparent distances up to 10⁶ are ordered correctly;
/// f32 depth has constant relative precision, so the scale costs nothing).
const LRT_DEPTH_SCALE: f32 = 1e-6;

/// The channels of [`GpuRenderer::render_seen`], in its order (srt's `--aov` channels).
pub const SEEN_CHANNELS: [&str; 5] = [
    "emission_ct",
    "proper_time",
    "distance",
    "doppler",
    "object",
];

/// Which rendering method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Exact per pixel, each object by whichever of [`Method::Lrt`] and [`Method::Rt`] is
    /// expected faster for it in this frame on this adapter (by its triangles, their layers
    /// and its seen pixels, [`crate::auto`]); the two compose through the depth test. A body
    /// that spins or thrusts in its rest frame is always traced, and so is every object in a
    /// wide projection (equirectangular, fisheye), which no footprint of the pinhole serves.
    #[default]
    Auto,
    /// Local ray tracing (the paper's method, exact per pixel): one footprint per triangle. A
    /// body that spins or thrusts in its rest frame has no static triangles to draw footprints
    /// of: it is traced as by [`Method::Rt`] (`motion.wgsl`), the rest of the scene by LRT.
    Lrt,
    /// Ray tracing through a BVH per batch of parts in its rest frame (the reference's
    /// algorithm on the GPU), exact per pixel like LRT; its cost does not grow with the layers
    /// of a deep model or with footprints swept beside the camera. It traces every projection:
    /// in a wide one each object's box covers the whole picture.
    Rt,
    /// Per-vertex photo-object polygon rendering (§3.2), the approximate baseline; a spinning
    /// or thrusting body's vertices each show their point's emission event on the observer's
    /// past light cone.
    Polygon,
    /// The image-based method (Table 1's "IB"): per velocity group a cube map of the objects
    /// at rest around the observation event, looked up along each pixel's aberrated direction
    /// and Doppler-shifted; approximate by design (each texel stands for all the directions it
    /// covers), it draws every projection; the scene's `cube_map_size` sets its resolution.
    ImageBased,
}

impl Method {
    /// Why this method cannot draw `scene` on the GPU, if it cannot: a wide projection
    /// (equirectangular, fisheye) or a stereo pair by the local ray tracer or the polygon
    /// method, which draw triangles through one pinhole's projection (the ray tracer, and so `auto`, traces any
    /// pixel's ray); a stereo pair, spectral colour or moving lights by the image-based method
    /// (one eye point, one colour-table light per texel); or late shadows of moving lights cast by a body that spins or thrusts (the
    /// GPU's shadow walk meets static triangles only). The CPU reference draws all of them
    /// exactly.
    #[must_use]
    pub fn cannot_draw(self, scene: &Scene) -> Option<String> {
        let projection = scene.observer.projection;
        if matches!(self, Self::Lrt | Self::Polygon) {
            let what = if !projection.is_pinhole() {
                Some(format!("the {projection} projection"))
            } else {
                scene.observer.stereo.map(|_| "a stereo pair".to_owned())
            };
            if let Some(what) = what {
                return Some(format!(
                    "the {} method draws triangles through one pinhole, not {what}; use \
                     --method rt or auto (the GPU's ray tracer traces every projection and \
                     stereo pair), or --backend cpu",
                    self.name()
                ));
            }
        }
        if self == Self::ImageBased {
            let why = if scene.observer.stereo.is_some() {
                Some("a stereo pair (its cube map is seen from one point)")
            } else if scene.colour == srt_scene::SurfaceColour::Spectral {
                Some("spectral colour (its cube map holds one colour-table light per texel)")
            } else if !scene.lights.is_empty() {
                Some("moving lights (its cube map holds one colour-table light per texel)")
            } else {
                None
            };
            if let Some(why) = why {
                return Some(format!(
                    "the image-based method does not draw {why}; use --method auto, or \
                     --backend cpu"
                ));
            }
        }
        let moving = scene.objects.iter().find(|o| !o.motion.is_rest())?;
        (scene.shadows && !scene.lights.is_empty()).then(|| {
            format!(
                "the GPU does not draw the late shadows {} casts while it spins or thrusts; \
                 use --backend cpu, or render.shadows = false",
                moving.name
            )
        })
    }

    /// Whether the method is exact per pixel (what the CPU reference computes).
    #[must_use]
    pub const fn is_exact(self) -> bool {
        !matches!(self, Self::Polygon | Self::ImageBased)
    }

    /// Whether the method draws footprints (the proxy pass runs): the exact methods.
    #[must_use]
    pub const fn has_footprints(self) -> bool {
        self.is_exact()
    }
}

srt_scene::choice!(Method, "method", {
    Auto => "auto",
        "exact per pixel, each object by whichever of lrt and rt is faster for it in each frame";
    Lrt => "lrt",
        "local ray tracing: exact per pixel (the paper's method; what the CPU renderer computes)";
    Rt => "rt",
        "ray tracing through a BVH per object in its rest frame: exact per pixel like lrt, \
         faster for deep models and objects passing the camera";
    Polygon => "polygon", "per-vertex polygon rendering (§3.2), the approximate baseline; GPU only";
    ImageBased => "image-based",
        "the image-based method (a cube map per velocity group, aberrated and Doppler-shifted; \
         the paper's Table 1 \"IB\"), approximate; GPU only";
});

/// Which footprint the LRT pass rasterises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FootprintShape {
    /// The convex hull (3–6 points).
    #[default]
    Hull,
    /// The window-aligned rectangle (the paper's choice).
    Rectangle,
}

impl From<FootprintShape> for FootprintCode {
    fn from(shape: FootprintShape) -> Self {
        match shape {
            FootprintShape::Hull => Self::HULL,
            FootprintShape::Rectangle => Self::RECTANGLE,
        }
    }
}

/// A rendered image read back from the GPU, RGBA: display colours (sRGB-encoded, [0, 1]), or
/// radiance ([`GpuRenderer::render_as`]).
#[derive(Debug, Clone, PartialEq)]
pub struct GpuImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major pixels from the top. For display colours and radiance, alpha is 1 where an
    /// object is seen and 0 where the background or the sky is (`srt render`'s test of an
    /// empty picture reads it; every method writes it so).
    pub pixels: Vec<[f32; 4]>,
}

impl GpuImage {
    /// 8-bit sRGB pixels, rounded as the CPU reference rounds.
    #[must_use]
    pub fn to_rgb8(&self) -> Vec<[u8; 3]> {
        self.pixels
            .iter()
            .map(|p| [p[0], p[1], p[2]].map(|c| quantize_8bit(f64::from(c))))
            .collect()
    }
}

/// Timing and work counters of one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameStats {
    /// GPU time of the passes in milliseconds, where timestamp queries are supported.
    pub gpu_time_ms: Option<f64>,
    /// GPU time of the LRT's footprint (proxy) pass alone, in milliseconds, where timestamp
    /// queries are supported (`None` for the polygon method).
    pub proxy_time_ms: Option<f64>,
    /// The LRT pass's fragments, when the renderer counts them
    /// ([`GpuRenderer::set_fragment_counting`]; zero for the polygon method).
    pub fragments: Option<FragmentCounts>,
}

/// What the LRT pass's fragment shader did in one frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FragmentCounts {
    /// Fragment shader invocations (one per footprint pixel that passed the rasteriser).
    pub run: u64,
    /// Those whose ray hit the triangle and were shaded (the rest discard).
    pub shaded: u64,
    /// Visibility fragments whose hit came out nearer than the depth their footprint was drawn
    /// at (`nearest_depth`, a bound that must hold for the visibility passes' "greater or
    /// equal" depth): 0 unless that bound is wrong.
    pub nearer_than_footprint: u64,
}

/// Checks, against `limits`, everything a `width` × `height` render target holds per pixel:
/// the target itself ([`DeviceLimits::check_render_target`], texels of `texel_bytes`) and the
/// star light a sky splats per pixel, whether or not the scene has a sky, for choosing a tile
/// size that every scene can use.
///
/// # Errors
/// [`GpuError::ExceedsLimit`] naming the first limit exceeded.
pub fn check_per_pixel_resources(
    limits: &DeviceLimits,
    width: u32,
    height: u32,
    texel_bytes: u32,
) -> Result<(), GpuError> {
    limits.check_render_target(width, height, texel_bytes)?;
    crate::sky::check_star_light(limits, width, height)
}

/// A scene uploaded to the GPU, ready to render.
pub struct GpuRenderer {
    /// The context's pipelines, shared with its other renderers ([`GpuContext::pipelines`]).
    pipelines: Arc<Pipelines>,
    frame: FrameResources,
    objects: Vec<ObjectResources>,
    counter: FragmentCounter,
    timestamps: Option<Timestamps>,
    targets: Targets,
    /// The stars, if the scene has a sky.
    sky: Option<SkyResources>,
    /// Every object's BVH for the shadows of moving lights, if the scene has moving lights.
    shadows: Option<ShadowScene>,
    /// Target pixels per output pixel along each side ([`GpuRenderer::set_supersampling`]).
    supersampling: u32,
    /// Whether the LRT pass counts its fragments.
    count_fragments: bool,
    /// Whether the LRT draws take their vertex counts from the proxy pass
    /// ([`GpuContext::indirect_draws`]).
    indirect_draws: bool,
    /// How `auto` weighs LRT against the ray tracer on this adapter
    /// ([`crate::auto::MethodCosts::for_adapter`]).
    auto_costs: crate::auto::MethodCosts,
    /// The part of a larger picture the target holds, if it holds a part
    /// ([`GpuRenderer::set_window`]).
    window: Option<ImageWindow>,
    /// The image-based method's cube map (of the scene's `cube_map_size`), made when it first
    /// draws and kept while the size stays.
    cube_map: std::sync::Mutex<Option<Arc<image_based::CubeMap>>>,
}

impl GpuRenderer {
    /// Uploads `scene` (meshes, textures, colour tables) for images of `width` × `height`.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the image or a mesh exceeds the device's limits (checked
    /// before anything is allocated), or any wgpu error.
    pub fn new(ctx: &GpuContext, scene: &Scene, width: u32, height: u32) -> Result<Self, GpuError> {
        let limits = DeviceLimits::of(ctx);
        limits.check_render_target(width, height, texel_bytes(ctx.color_format)?)?;
        let sizes = scene
            .objects
            .iter()
            .map(|object| {
                let culling: Vec<BackFaceCulling> = object
                    .parts
                    .iter()
                    .map(|part| BackFaceCulling::for_mesh(&part.mesh))
                    .collect();
                let batches = batches(&limits, object, &culling)?;
                Ok((culling, batches))
            })
            .collect::<Result<Vec<_>, GpuError>>()?;
        let device = &ctx.device;
        // Only a scene with moving lights needs them compiled into the shading passes, and
        // every object's BVH there.
        let lit = !scene.lights.is_empty();
        let pipelines = ctx.pipelines(lit);
        let counter = FragmentCounter::new(device);
        let frame_bound = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt frame bound"),
            size: FRAME_BOUND_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let shared = FrameShared {
            fragment_count: &counter.counter,
            frame_bound: &frame_bound,
        };
        let uploader = Uploader {
            ctx,
            pipelines: &pipelines,
            shared,
            textures: PartTextures::default(),
        };
        // Batches are numbered from 1 across the scene (0 marks "no triangle" in the LRT's ids).
        let mut first_id = 1u32;
        let (objects, sources): (Vec<ObjectResources>, Vec<Option<ShadowSource>>) = scene
            .objects
            .iter()
            .zip(sizes)
            .map(|(object, sizes)| {
                let id = first_id;
                first_id += sizes.1.len() as u32;
                upload_object(&uploader, object, id, sizes, lit)
            })
            .unzip();
        let shadows = if lit {
            Some(shadow_scene(ctx, sources)?)
        } else {
            None
        };
        let frame = FrameResources::new(
            ctx,
            &pipelines,
            &shadows
                .as_ref()
                .map_or_else(|| empty_shadow_buffer(device), |s| s.buffer().clone()),
            frame_bound,
        )?;
        let renderer = Self {
            timestamps: ctx.timestamps.then(|| Timestamps::new(device)),
            targets: Targets::new(ctx, width, height, &pipelines, &frame)?,
            sky: SkyResources::new(ctx, scene, width, height)?,
            shadows,
            supersampling: 1,
            pipelines,
            frame,
            objects,
            counter,
            count_fragments: false,
            indirect_draws: ctx.indirect_draws,
            auto_costs: crate::auto::MethodCosts::for_adapter(ctx.adapter_info.device_type),
            window: None,
            cube_map: std::sync::Mutex::new(None),
        };
        ctx.take_errors()?;
        Ok(renderer)
    }

    /// Tells the renderer that its target is `scale`× the output size along each side (a
    /// caller that box-filters it down: supersampling; default 1). A star then lights every
    /// target pixel of the output pixels around it, as the CPU reference adds its light to every
    /// sample of those pixels, so that a bright star clamps as it does there.
    pub fn set_supersampling(&mut self, scale: u32) {
        self.supersampling = scale.max(1);
    }

    /// Makes the LRT passes count the fragments they run and shade
    /// ([`FrameStats::fragments`]), or stop counting. Counting is for measurements: it costs
    /// global atomics per fragment.
    pub fn set_fragment_counting(&mut self, counting: bool) {
        self.count_fragments = counting;
    }

    /// Per object, what `auto` weighs of it in the frame `scene` shows
    /// ([`crate::auto::ObjectLoad`]), or `None` where it has no choice to make (no ray tracer,
    /// out of view, moving in its rest frame, a wide projection).
    #[must_use]
    pub fn object_loads(&self, scene: &Scene) -> Vec<Option<crate::auto::ObjectLoad>> {
        self.loads(scene)
    }

    /// How many objects `auto` traces through their BVH in the frame `scene` shows because
    /// the adapter's costs expect the ray tracer faster for them ([`crate::auto`]; moving
    /// bodies and every object of a wide projection are traced by every exact method and not
    /// counted here).
    #[must_use]
    pub fn auto_traced_objects(&self, scene: &Scene) -> usize {
        let in_view = self.objects_in_view(scene);
        self.auto_traced(scene, &in_view)
            .into_iter()
            .filter(|&t| t)
            .count()
    }

    /// Per object, how many batches its triangles were uploaded in (each drawn by its own
    /// calls): one per texture and culling kind of its parts, more where a part is larger than
    /// the device's storage bindings allow one batch and was split into slices.
    #[must_use]
    pub fn object_batches(&self) -> Vec<usize> {
        self.objects.iter().map(|o| o.parts.len()).collect()
    }

    /// Image width and height.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.targets.width, self.targets.height)
    }

    /// Makes the target hold `window` of a larger picture (a tile: the same rays through its
    /// pixels as through those pixels of the whole picture), or the whole picture (`None`, the
    /// default). A resize returns to the whole picture.
    ///
    /// # Panics
    /// If the window at the target's size reaches beyond its picture.
    pub fn set_window(&mut self, window: Option<ImageWindow>) {
        if let Some(window) = window {
            let (width, height) = self.size();
            window.check_holds(width, height);
        }
        self.window = window;
    }

    /// Changes the image size (recreates the render targets) and returns to the whole picture
    /// ([`GpuRenderer::set_window`]).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when the size exceeds the device's limits; the renderer then
    /// keeps its previous size.
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) -> Result<(), GpuError> {
        self.window = None;
        if (width, height) != self.size() {
            let targets = Targets::new(ctx, width, height, &self.pipelines, &self.frame)?;
            if let Some(sky) = &mut self.sky {
                sky.resize(ctx, width, height)?;
            }
            self.targets = targets;
        }
        Ok(())
    }

    /// The texture the last frame was rendered into, for display.
    #[must_use]
    pub fn color_texture(&self) -> &wgpu::Texture {
        &self.targets.color
    }

    /// Renders one frame of `scene` (display colours) and reads it back.
    ///
    /// # Errors
    /// wgpu errors, a lost device, or a scene whose structure differs from the uploaded one.
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
    ) -> Result<(GpuImage, FrameStats), GpuError> {
        self.render_as(ctx, scene, method, footprint, Output::Display)
    }

    /// Renders one frame of `scene` writing `output` and reads it back: display colours as
    /// [`GpuRenderer::render`], radiance (linear BT.709, unclamped, the unit of srt-color's
    /// `radiance` module; held to ±65 504 where the colour target is half float), or what
    /// pixels see of time ([`GpuRenderer::render_seen`] composes those).
    ///
    /// # Errors
    /// As [`GpuRenderer::render`].
    pub fn render_as(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
        output: impl Into<OutputCode>,
    ) -> Result<(GpuImage, FrameStats), GpuError> {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("srt frame"),
            });
        self.encode_as(ctx, &mut encoder, scene, method, footprint, output)?;
        let t = &self.targets;
        t.readback.encode_copy(&mut encoder, &t.color);
        ctx.queue.submit([encoder.finish()]);
        let bytes = t.readback.read(ctx)?;
        let pixel_bytes = texel_bytes(ctx.color_format)? as usize;
        let pixels = bytes.chunks_exact(pixel_bytes).map(decode_pixel).collect();
        let fragments = if self.count_fragments {
            let [run, shaded, nearer] =
                bytemuck::pod_read_unaligned::<[u32; 3]>(&ctx.read_buffer(&self.counter.readback)?);
            Some(FragmentCounts {
                run: u64::from(run),
                shaded: u64::from(shaded),
                nearer_than_footprint: u64::from(nearer),
            })
        } else {
            None
        };
        let (gpu_time_ms, proxy_time_ms) = self.frame_times(ctx, method)?;
        ctx.take_errors()?;
        Ok((
            GpuImage {
                width: t.width,
                height: t.height,
                pixels,
            },
            FrameStats {
                gpu_time_ms,
                proxy_time_ms,
                fragments,
            },
        ))
    }

    /// GPU time in ms of the last frame encoded ([`GpuRenderer::encode`]) and finished, and of
    /// its proxy pass (`None` for the polygon method), by timestamp queries; `(None, None)`
    /// where the device has none ([`GpuContext::timestamps`]). Call it once the frame's
    /// submission has finished (after [`GpuContext::wait`]).
    ///
    /// # Errors
    /// A failed readback.
    pub fn frame_times(
        &self,
        ctx: &GpuContext,
        method: Method,
    ) -> Result<(Option<f64>, Option<f64>), GpuError> {
        let Some(t) = &self.timestamps else {
            return Ok((None, None));
        };
        let stamps: Vec<u64> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(&t.readback)?);
        let ms = |from: usize, to: usize| {
            stamps[to].saturating_sub(stamps[from]) as f64
                * f64::from(ctx.queue.get_timestamp_period())
                * 1e-6
        };
        // From the first pass of the frame (the proxy pass, or else the sky's, or else the
        // polygon pass) to the end of the last.
        Ok(match method {
            Method::Lrt | Method::Rt | Method::Auto => (Some(ms(0, 3)), Some(ms(0, 1))),
            Method::Polygon | Method::ImageBased => {
                let first = if self.sky.is_some() { SKY_TIMESTAMP } else { 2 };
                (Some(ms(first as usize, 3)), None)
            }
        })
    }

    /// What each pixel sees of time (the `--aov` channels), row-major from the top, as
    /// [`SEEN_CHANNELS`] orders them: emission ct_W, proper time, apparent distance, Doppler
    /// factor and the object's index, or `[0, 0, 0, 0, −1]` where no object is seen (mirror of
    /// srt-trace's `SeenEvent`; the polygon method gives the events of the rest points it
    /// draws). Two frames: the events, then the object indices.
    ///
    /// # Errors
    /// As [`GpuRenderer::render`].
    pub fn render_seen(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
    ) -> Result<Vec<[f32; 5]>, GpuError> {
        let (events, _) = self.render_as(ctx, scene, method, footprint, OutputCode::SEEN_EVENT)?;
        let (objects, _) =
            self.render_as(ctx, scene, method, footprint, OutputCode::SEEN_OBJECT)?;
        Ok(events
            .pixels
            .iter()
            .zip(&objects.pixels)
            .map(|(event, object)| {
                if object[0] < 0.0 {
                    [0.0, 0.0, 0.0, 0.0, -1.0]
                } else {
                    [event[0], event[1], event[2], event[3], object[0]]
                }
            })
            .collect())
    }

    /// Runs the proxy pass for `scene` and reads back every part's footprints (split out of the
    /// batches the parts are uploaded in), indexed `[object][part][triangle]`: each triangle's
    /// own footprint and the pieces it was split into (for validation against srt-proxy). Every
    /// object is run, those out of view too.
    ///
    /// # Errors
    /// wgpu or readback errors.
    pub fn read_footprints(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
    ) -> Result<Vec<Vec<Vec<TriangleFootprints>>>, GpuError> {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("srt footprints"),
            });
        let every_object: Vec<usize> = (0..self.objects.len()).collect();
        self.encode_objects(
            ctx,
            &mut encoder,
            scene,
            Method::Lrt,
            FootprintShape::Hull,
            Output::Display.into(),
            &every_object,
        )?;
        let readback = |encoder: &mut wgpu::CommandEncoder, source: &wgpu::Buffer, size| {
            let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("srt footprint readback"),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, size);
            buffer
        };
        let readbacks: Vec<Vec<(wgpu::Buffer, wgpu::Buffer)>> = self
            .objects
            .iter()
            .map(|object| {
                object
                    .parts
                    .iter()
                    .map(|part| {
                        (
                            readback(&mut encoder, &part.footprints, part.sizes.footprint_bytes),
                            readback(&mut encoder, &part.draw_args, DRAW_ARGS_BYTES),
                        )
                    })
                    .collect()
            })
            .collect();
        ctx.queue.submit([encoder.finish()]);
        let mut footprints = Vec::new();
        for (object, buffers) in self.objects.iter().zip(&readbacks) {
            // Split each batch's footprints among its slices, hand each piece to its triangle,
            // and put every part's slices back in triangle order.
            let mut slices: Vec<Vec<(u32, Vec<TriangleFootprints>)>> =
                vec![Vec::new(); object.culling.len()];
            for (batch, (slots, draw_args)) in object.parts.iter().zip(buffers) {
                let all: Vec<GpuFootprint> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(slots)?);
                let args: Vec<u32> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(draw_args)?);
                let (own, piece_slots) = all.split_at(batch.sizes.triangles as usize);
                let taken = args[DRAW_ARGS_PIECES_TAKEN as usize] as usize;
                let pieces = &piece_slots[..taken.min(piece_slots.len())];
                let mut first = 0;
                for slice in &batch.members {
                    let mine = first..first + slice.len();
                    let drawn = own[mine.start as usize..mine.end as usize]
                        .iter()
                        .enumerate()
                        .map(|(t, &own)| TriangleFootprints {
                            own,
                            pieces: pieces
                                .iter()
                                .filter(|p| p.triangle == mine.start + t as u32)
                                .copied()
                                .collect(),
                        })
                        .collect();
                    slices[slice.part].push((slice.triangles.start, drawn));
                    first = mine.end;
                }
            }
            footprints.push(
                slices
                    .into_iter()
                    .map(|mut part| {
                        part.sort_by_key(|&(start, _)| start);
                        part.into_iter().flat_map(|(_, drawn)| drawn).collect()
                    })
                    .collect(),
            );
        }
        ctx.take_errors()?;
        Ok(footprints)
    }
}

/// The shadow buffer of the objects whose BVHs `sources` holds (one entry per object of the
/// scene): objects without triangles cast nothing.
///
/// # Errors
/// Why an object with triangles has no BVH (e.g. [`GpuError::BvhTooDeep`]): its shadows could not
/// be drawn; [`GpuError::ExceedsLimit`] when the buffer is too large.
fn shadow_scene(
    ctx: &GpuContext,
    sources: Vec<Option<ShadowSource>>,
) -> Result<ShadowScene, GpuError> {
    let mut casters: Vec<(usize, ObjectBvh, Vec<GpuRtTriangle>)> = Vec::new();
    for (index, source) in sources.into_iter().enumerate() {
        match source {
            Some(Ok((bvh, triangles))) => casters.push((index, bvh, triangles)),
            Some(Err(GpuError::NotReady(_))) | None => {}
            Some(Err(error)) => return Err(error),
        }
    }
    let input: Vec<(usize, &ObjectBvh, &[GpuRtTriangle])> = casters
        .iter()
        .map(|(index, bvh, triangles)| (*index, bvh, triangles.as_slice()))
        .collect();
    ShadowScene::new(ctx, &ShadowRows::new(&input))
}

/// What the proxy pass drew for one triangle ([`GpuRenderer::read_footprints`]).
#[derive(Debug, Clone)]
pub struct TriangleFootprints {
    /// The footprint in the triangle's own slot.
    pub own: GpuFootprint,
    /// The footprints of the pieces it was split into, beyond `own` (drawn as well).
    pub pieces: Vec<GpuFootprint>,
}

/// One RGBA pixel of the colour target: four little-endian f32 (16 bytes) or f16 (8 bytes).
fn decode_pixel(bytes: &[u8]) -> [f32; 4] {
    let channel = |k: usize| {
        if bytes.len() == 16 {
            f32::from_le_bytes([
                bytes[4 * k],
                bytes[4 * k + 1],
                bytes[4 * k + 2],
                bytes[4 * k + 3],
            ])
        } else {
            half::f16::from_le_bytes([bytes[2 * k], bytes[2 * k + 1]]).to_f32()
        }
    };
    [channel(0), channel(1), channel(2), channel(3)]
}
