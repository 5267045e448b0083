//! Encoding a frame: the per-frame uniforms, the proxy pass (footprints), and the render pass
//! (sky, LRT or ray-tracer visibility, shading, or the polygon method), with timestamps.

use super::*;
use crate::auto::ObjectLoad;
use crate::culling::{
    ball_between_pixel_centres, ball_nearest_apparent_distance, ball_out_of_view, ball_seen_pixels,
    ball_wide_bound,
};
use crate::motion::{MotionCode, MotionUniforms, sweep_bounds};
use crate::shaders::ObjectVariant;
use crate::sky::SkyPlacement;
use crate::types::ProjectionCode;
use srt_scene::Projection;

impl super::GpuRenderer {
    /// Writes the per-frame uniforms for `scene` (observer, light, effects, velocities) and
    /// what the passes write (`output`); returns the tone map's index in [`ToneMap::ALL`].
    pub(super) fn write_uniforms(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        footprint: FootprintShape,
        output: OutputCode,
    ) -> Result<usize, GpuError> {
        if scene.objects.len() != self.objects.len()
            || scene
                .objects
                .iter()
                .zip(&self.objects)
                .any(|(o, r)| o.parts.len() != r.culling.len())
        {
            return Err(GpuError::SceneChanged);
        }
        // Moving lights need the shadow casters, uploaded only for a scene that had them.
        if !scene.lights.is_empty() && self.shadows.is_none() {
            return Err(GpuError::SceneChanged);
        }
        let uploaded_sky = self.sky.as_ref().map_or((0, None), SkyResources::shape);
        if sky_shape(&scene.sky) != uploaded_sky {
            return Err(GpuError::SceneChanged);
        }
        if let Some(sky) = &self.sky {
            sky.write_uniforms(ctx, scene, self.supersampling);
        }
        let (width, height) = self.size();
        let observer = &scene.observer;
        let camera = target_camera(observer, width, height, self.window);
        let tone = FrameResources::tone_index(scene.tone_map);
        let uniforms = FrameUniforms {
            view_projection: mat4(camera.view_projection),
            camera_forward: vec4(camera.forward, 0.0),
            camera_right: vec4(camera.right, camera.offset.x),
            camera_up: vec4(camera.up, camera.offset.y),
            observer: vec4(observer.position, 0.0),
            light: vec4(scene.light.position, scene.light.temperature_k),
            shading: [
                scene.shading.ambient as f32,
                scene.shading.diffuse as f32,
                scene.shading.specular as f32,
                scene.shading.shininess as f32,
            ],
            background: background_as(output, scene.background).as_vec4().to_array(),
            lut: self.frame.lut_params[tone],
            viewport: [
                width as f32,
                height as f32,
                1.0 / width as f32,
                1.0 / height as f32,
            ],
            picture: self.picture_uniform(),
            effects: EffectsCode::from(scene.effects),
            footprint_shape: FootprintCode::from(footprint),
            depth_scale: LRT_DEPTH_SCALE,
            colour: SurfaceColourCode::from(scene.colour),
            tone_map: ToneMapCode::from(scene.tone_map),
            exposure: scene.exposure as f32,
            searchlight_ln_y: searchlight_reference_ln_y() as f32,
            output,
            projection: ProjectionCode::from(observer.projection),
            fisheye_half_fov: match observer.projection {
                Projection::Fisheye { fov_deg } => (0.5 * fov_deg.to_radians()) as f32,
                _ => 0.0,
            },
            eye_separation: observer.stereo.map_or(-1.0, |s| s.eye_separation as f32),
            projection_padding: 0,
            radiance: radiance_params(
                &scene.radiance_scale(RadianceTable::shared()),
                largest_value(ctx.color_format),
            ),
            lights: light_uniforms(scene, self.shadows.as_ref()),
        };
        ctx.queue
            .write_buffer(&self.frame.uniforms, 0, bytemuck::bytes_of(&uniforms));
        if let Some(shadows) = &self.shadows {
            shadows.write(&ctx.queue, scene);
        }
        let event = observer.event();
        for (index, (object, resources)) in scene.objects.iter().zip(&self.objects).enumerate() {
            let (time, world_time) = object_time(object, index, &scene.world);
            let clock = ClockUniforms::from(object.clock.as_ref());
            let mut uniforms = ObjectUniforms {
                frame: GpuFrame::new(&object.frame, event),
                style: [object.wireframe.unwrap_or(0.0) as f32, 0.0, 0.0, 0.0],
                optics: optics4(&object.optics),
                time,
                world_time,
                blink: blink4(&object.optics),
                clock: clock.clock,
                clock_face: clock.face,
                clock_ink: clock.ink,
                ..bytemuck::Zeroable::zeroed()
            };
            MotionUniforms::new(object, &resources.extent, event).apply(&mut uniforms);
            uniforms.view_bound = self.view_bound(object, resources, observer);
            ctx.queue
                .write_buffer(&resources.uniforms, 0, bytemuck::bytes_of(&uniforms));
            write_part_culling(ctx, object, resources, event);
            if let Ok(rt) = &resources.ray_tracing {
                rt.write_culling(
                    &ctx.queue,
                    object.frame.to_rest(event).position,
                    sweep_bounds(object, &resources.extent, event),
                );
            }
        }
        Ok(tone)
    }

    /// Records the passes of one frame into `encoder`, leaving the image (display colours) in
    /// [`GpuRenderer::color_texture`].
    ///
    /// # Errors
    /// [`GpuError::SceneChanged`] if the scene's structure differs from the uploaded one.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
    ) -> Result<(), GpuError> {
        self.encode_as(ctx, encoder, scene, method, footprint, Output::Display)
    }

    /// [`GpuRenderer::encode`] writing `output`: display colours or radiance (an [`Output`]), or
    /// what pixels see of time ([`OutputCode::SEEN_EVENT`], [`OutputCode::SEEN_OBJECT`]).
    ///
    /// # Errors
    /// As [`GpuRenderer::encode`].
    pub fn encode_as(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
        output: impl Into<OutputCode>,
    ) -> Result<(), GpuError> {
        let shown = self.objects_in_view(scene);
        self.encode_objects(
            ctx,
            encoder,
            scene,
            method,
            footprint,
            output.into(),
            &shown,
        )
    }

    /// [`GpuRenderer::encode_as`] drawing the objects `shown` (indices) and skipping the others:
    /// all of them where a test reads back every footprint, those in view otherwise.
    ///
    /// # Errors
    /// As [`GpuRenderer::encode`].
    #[allow(clippy::too_many_arguments)]
    pub(super) fn encode_objects(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        method: Method,
        footprint: FootprintShape,
        output: OutputCode,
        shown: &[usize],
    ) -> Result<(), GpuError> {
        let tone = self.write_uniforms(ctx, scene, footprint, output)?;
        let traced = self.traced_objects(scene, method, shown)?;
        if self.count_fragments {
            encoder.clear_buffer(&self.counter.counter, 0, None);
        }
        if method.has_footprints() {
            let no_draw = wgpu::util::DrawIndirectArgs {
                vertex_count: 0,
                instance_count: 1,
                first_vertex: 0,
                first_instance: 0,
            };
            // Both draws empty, no piece slot taken, the bound empty (all four words 0).
            let reset = [no_draw.as_bytes(), no_draw.as_bytes(), &[0; 4], &[0; 16]].concat();
            debug_assert_eq!(reset.len() as u64, DRAW_ARGS_BYTES);
            for &index in shown {
                let object = &self.objects[index];
                match traced[index] {
                    Some(rt) => ctx.queue.write_buffer(&rt.box_draw_args, 0, &reset),
                    None => {
                        for part in &object.parts {
                            ctx.queue.write_buffer(&part.draw_args, 0, &reset);
                        }
                    }
                }
            }
            encoder.clear_buffer(&self.frame.frame_bound, 0, None);
            self.encode_proxy_pass(encoder, tone, &traced, shown);
        }
        let background = background_as(output, scene.background);
        let frame = ObjectVariant {
            counting: self.count_fragments,
            lit: self.pipelines.lit(),
            shadowed: frame_has_casters(scene, self.shadows.as_ref()),
            colour: SurfaceColourCode::from(scene.colour),
            seen: output == OutputCode::SEEN_EVENT || output == OutputCode::SEEN_OBJECT,
            ..ObjectVariant::PLAIN
        };
        // Each object's variant; each part's adds whether it is textured (variant_of_part).
        let variants: Vec<ObjectVariant> = scene
            .objects
            .iter()
            .map(|o| ObjectVariant {
                motion: MotionCode::of(&o.motion),
                clock: o.clock.is_some(),
                wireframe: o.wireframe.is_some_and(|width| width > 0.0),
                ..frame
            })
            .collect();
        if method == Method::ImageBased {
            if frame.seen {
                return Err(GpuError::Unsupported(
                    "the image-based method does not write what pixels see of time (--aov); \
                     use --method auto"
                        .into(),
                ));
            }
            let view = |texture: &wgpu::Texture| texture.create_view(&Default::default());
            let targets = (&view(&self.targets.color), &view(&self.targets.depth));
            self.encode_image_based(
                ctx, encoder, scene, background, tone, &variants, shown, targets,
            )?;
        } else {
            self.encode_render_pass(
                &ctx.device,
                encoder,
                background,
                method,
                tone,
                &traced,
                &variants,
                shown,
            );
        }
        if let Some(t) = &self.timestamps {
            encoder.resolve_query_set(&t.set, 0..TIMESTAMP_COUNT, &t.resolve, 0);
            encoder.copy_buffer_to_buffer(&t.resolve, 0, &t.readback, 0, t.resolve.size());
        }
        if self.count_fragments {
            encoder.copy_buffer_to_buffer(
                &self.counter.counter,
                0,
                &self.counter.readback,
                0,
                FRAGMENT_COUNTER_BYTES,
            );
        }
        Ok(())
    }

    /// Per object, its ray tracer if `method` traces it through its BVH (`None`: LRT, its
    /// footprints): every object for [`Method::Rt`], none for [`Method::Lrt`] and
    /// [`Method::Polygon`] and [`Method::ImageBased`], and for [`Method::Auto`] those the
    /// adapter's [`crate::auto::MethodCosts`] expect cheaper traced this frame among those
    /// `shown` ([`Self::auto_traced`]); every object in a wide projection (no footprint of the pinhole
    /// serves it). A body that spins or thrusts in its rest frame
    /// is traced by every exact method ([`Method::Lrt`] included: footprints of static
    /// triangles do not hold a moving body's image); the polygon method moves its vertices.
    ///
    /// # Errors
    /// Why an object has no ray tracer, when [`Method::Rt`] or a moving body needs it;
    /// [`GpuError::Unsupported`] for what [`Method::cannot_draw`] names.
    pub(super) fn traced_objects(
        &self,
        scene: &Scene,
        method: Method,
        shown: &[usize],
    ) -> Result<Vec<Option<&ObjectRayTracing>>, GpuError> {
        if let Some(why) = method.cannot_draw(scene) {
            return Err(GpuError::Unsupported(why));
        }
        // A wide projection or a stereo pair is traced: footprints are drawn through one pinhole.
        let wide = scene.observer.picture_decides();
        let auto_traced = if method == Method::Auto {
            self.auto_traced(scene, shown)
        } else {
            Vec::new()
        };
        self.objects
            .iter()
            .zip(&scene.objects)
            .enumerate()
            .map(|(index, (object, seen))| {
                let moving = !seen.motion.is_rest();
                let traced = moving || wide;
                match (method, &object.ray_tracing) {
                    (Method::Polygon | Method::ImageBased, _) => Ok(None),
                    (Method::Rt, Ok(rt)) => Ok(Some(rt)),
                    (_, Ok(rt)) if traced => Ok(Some(rt)),
                    (Method::Rt, Err(error)) => Err(error.clone()),
                    (_, Err(error)) if traced => Err(error.clone()),
                    (Method::Auto, Ok(rt)) => Ok(auto_traced[index].then_some(rt)),
                    _ => Ok(None),
                }
            })
            .collect()
    }

    /// What `auto` weighs of each object this frame ([`ObjectLoad`]); `None` where there is no
    /// choice: an object without a ray tracer (LRT draws it), one out of view (neither method
    /// draws it, [`GpuRenderer::objects_in_view`]), a body that spins or thrusts in its rest
    /// frame, every object of a wide projection or a stereo pair (all traced).
    pub(super) fn loads(&self, scene: &Scene) -> Vec<Option<ObjectLoad>> {
        self.choices(scene, &self.objects_in_view(scene), |_, _| true)
    }

    /// Per object, whether `auto` traces it this frame ([`crate::auto::MethodCosts::traces`]
    /// on its [`ObjectLoad`]), of the objects `in_view` ([`GpuRenderer::objects_in_view`],
    /// which the frame has already found); objects the costs send to LRT whatever they cover
    /// are not measured.
    pub(super) fn auto_traced(&self, scene: &Scene, in_view: &[usize]) -> Vec<bool> {
        let costs = &self.auto_costs;
        self.choices(scene, in_view, |triangles, layers| {
            !costs.lrt_whatever_seen(triangles, layers)
        })
        .iter()
        .map(|load| load.is_some_and(|load| costs.traces(&load)))
        .collect()
    }

    /// [`Self::loads`] for the objects `in_view` whose triangles and layers `open` finds the
    /// choice open for, `None` for the others.
    fn choices(
        &self,
        scene: &Scene,
        in_view: &[usize],
        open: impl Fn(u64, f64) -> bool,
    ) -> Vec<Option<ObjectLoad>> {
        let (width, height) = self.picture_size();
        let observer = &scene.observer;
        let wide = observer.picture_decides();
        let mut viewed = vec![false; self.objects.len()];
        for &index in in_view {
            viewed[index] = true;
        }
        self.objects
            .iter()
            .zip(&scene.objects)
            .zip(viewed)
            .map(|((resources, object), in_view)| {
                if wide || !object.motion.is_rest() || !in_view {
                    return None;
                }
                let rt = resources.ray_tracing.as_ref().ok()?;
                let triangles = object.triangle_count() as u64;
                if !open(triangles, rt.layers()) {
                    return None;
                }
                let (centre, radius) = object_ball(object, resources, observer.event());
                let rest_position = object.frame.to_rest(observer.event()).position;
                Some(ObjectLoad {
                    triangles,
                    layers: rt.layers(),
                    box_layers: rt.box_layers(rest_position),
                    seen_pixels: ball_seen_pixels(
                        centre,
                        radius,
                        &object.frame,
                        observer,
                        width,
                        height,
                    ),
                })
            })
            .collect()
    }

    /// `ObjectUniforms::view_bound` of `object`: in a wide projection, the rectangle of the
    /// picture where its ball can be seen ([`ball_wide_bound`]); for a stereo pair the whole
    /// picture (the bound is the observer's view, not the eyes'); unused for the pinhole.
    fn view_bound(
        &self,
        object: &Object,
        resources: &ObjectResources,
        observer: &srt_scene::Observer,
    ) -> [f32; 4] {
        let (width, height) = self.picture_size();
        if observer.stereo.is_some() || observer.projection.is_pinhole() {
            return [0.0, 0.0, width as f32, height as f32];
        }
        let (centre, radius) = object_ball(object, resources, observer.event());
        ball_wide_bound(centre, radius, &object.frame, observer, width, height).map(|v| v as f32)
    }

    /// The whole picture's width and height: the target's, unless it holds a window.
    fn picture_size(&self) -> (u32, u32) {
        self.window.map_or_else(
            || self.size(),
            |window| (window.image_width, window.image_height),
        )
    }

    /// `FrameUniforms::picture`: the whole picture's size and the target's first column and
    /// row in it (the target itself unless it holds a window).
    fn picture_uniform(&self) -> [f32; 4] {
        let (width, height) = self.size();
        self.window
            .map_or([width as f32, height as f32, 0.0, 0.0], |window| {
                [
                    window.image_width as f32,
                    window.image_height as f32,
                    window.left as f32,
                    window.top as f32,
                ]
            })
    }

    /// The indices of the objects of `scene` that may be seen in this frame, nearest first
    /// ([`ball_nearest_apparent_distance`]; objects as near keep the scene's order): all but
    /// those whose ball (around their vertices at rest, [`BodyExtent::ball`](srt_scene::BodyExtent::ball),
    /// or around the box swept by their motion, [`sweep_bounds`]) is out of view
    /// ([`ball_out_of_view`]) or covers no pixel's centre ([`ball_between_pixel_centres`]). The
    /// others' footprints and draws are skipped, whatever the method.
    pub fn objects_in_view(&self, scene: &Scene) -> Vec<usize> {
        // Culled against the whole picture (its view and its grid of pixel centres): an object
        // outside the window but in the picture is drawn and clipped.
        let (width, height) = self.picture_size();
        let aspect = f64::from(width) / f64::from(height);
        let event = scene.observer.event();
        // Zipped, not indexed: a scene of another structure is refused later (SceneChanged).
        let mut shown: Vec<(f64, usize)> = (scene.objects.iter().zip(&self.objects).enumerate())
            .filter_map(|(index, (object, resources))| {
                let (centre, radius) = object_ball(object, resources, event);
                let (frame, observer) = (&object.frame, &scene.observer);
                let unseen = if observer.stereo.is_some() {
                    // Two eyes' views: nothing is culled.
                    false
                } else if observer.projection.is_pinhole() {
                    ball_out_of_view(centre, radius, frame, observer, aspect)
                        || ball_between_pixel_centres(
                            centre, radius, frame, observer, width, height,
                        )
                } else {
                    // Outside a fisheye's field: an empty rectangle.
                    let [x0, y0, x1, y1] =
                        ball_wide_bound(centre, radius, frame, observer, width, height);
                    x0 >= x1 || y0 >= y1
                };
                (!unseen).then(|| {
                    let nearest = ball_nearest_apparent_distance(centre, radius, frame, event);
                    (nearest, index)
                })
            })
            .collect();
        shown.sort_by(|a, b| a.0.total_cmp(&b.0));
        shown.into_iter().map(|(_, index)| index).collect()
    }

    /// The footprint compute pass (timestamps 0 and 1) over the triangles of every object
    /// `shown` drawn by its footprints and the box of every one `traced`.
    pub(super) fn encode_proxy_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        tone: usize,
        traced: &[Option<&ObjectRayTracing>],
        shown: &[usize],
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("srt proxy"),
            timestamp_writes: self
                .timestamps
                .as_ref()
                .map(|t| wgpu::ComputePassTimestampWrites {
                    query_set: &t.set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                }),
        });
        pass.set_pipeline(&self.pipelines.proxy);
        pass.set_bind_group(FRAME_GROUP.index, &self.frame.bind_groups[tone], &[]);
        for &index in shown {
            let object = &self.objects[index];
            pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
            if let Some(rt) = traced[index] {
                pass.set_bind_group(PART_GROUP.index, &rt.box_part_group, &[]);
                pass.set_bind_group(PROXY_OUTPUT_GROUP.index, &rt.box_proxy_group, &[]);
                pass.dispatch_workgroups(1, 1, 1);
                continue;
            }
            for part in &object.parts {
                pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                pass.set_bind_group(PROXY_OUTPUT_GROUP.index, &part.proxy_bind_group, &[]);
                let (x, y) = part.sizes.workgroups;
                pass.dispatch_workgroups(x, y, 1);
            }
        }
    }

    /// The render passes into the targets (timestamps 2 and 3): for the polygon method one
    /// pass into colour and depth; for the exact methods the visibility pass into ids and depth
    /// (each object by its triangles' footprints, or, where `traced`, by its box's footprints
    /// and its BVH), then the shading pass into colour. Each part is drawn by the pipelines of its
    /// variant: its object's (`variants`, one per object) with its own texture. Only the objects
    /// `shown` are drawn.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn encode_render_pass(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        background: DVec4,
        method: Method,
        tone: usize,
        traced: &[Option<&ObjectRayTracing>],
        variants: &[ObjectVariant],
        shown: &[usize],
    ) {
        let view = |texture: &wgpu::Texture| texture.create_view(&Default::default());
        let (color_view, depth_view, ids_view) = (
            view(&self.targets.color),
            view(&self.targets.depth),
            view(&self.targets.ids),
        );
        let depth = wgpu::RenderPassDepthStencilAttachment {
            view: &depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        };
        if method == Method::Polygon {
            let target = (&color_view, depth);
            self.encode_polygon_pass(device, encoder, background, tone, variants, shown, target);
            return;
        }
        if shown.is_empty() {
            let background = self.encode_background(
                device,
                encoder,
                background,
                tone,
                &color_view,
                SkyPlacement::OwnPass,
            );
            // Nothing in view: the colour target holds the sky or the background, as the
            // shading pass would leave it, without the visibility and part-depth passes.
            drop(self.begin_pass(
                encoder,
                "srt empty frame",
                &color_view,
                background,
                None,
                [Some(2), Some(3)],
            ));
            return;
        }
        let placement = SkyPlacement::WhereUnseen;
        let background =
            self.encode_background(device, encoder, background, tone, &color_view, placement);
        let none = wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT);
        let mut pass = self.begin_pass(
            encoder,
            "srt lrt visibility",
            &ids_view,
            none,
            Some(depth),
            [Some(2), None],
        );
        pass.set_bind_group(FRAME_GROUP.index, &self.frame.bind_groups[tone], &[]);
        self.draw_visibility(device, &mut pass, traced, variants, shown);
        drop(pass);
        let part_depth_view = view(&self.targets.part_depth);
        self.encode_part_depth(encoder, tone, &part_depth_view);
        let tested = wgpu::RenderPassDepthStencilAttachment {
            view: &part_depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        };
        let mut pass = self.begin_pass(
            encoder,
            "srt lrt shading",
            &color_view,
            background,
            Some(tested),
            [None, Some(3)],
        );
        pass.set_bind_group(
            SHADE_FRAME_GROUP.index,
            &self.targets.shade_frame_groups[tone],
            &[],
        );
        self.draw_shading(device, &mut pass, traced, variants, shown);
        self.draw_sky(device, &mut pass, tone, placement);
    }

    /// Encodes the polygon method's frame (§3.2): the sky behind, then every shown object's
    /// parts drawn per vertex into `color_view`, depth-tested in `depth`.
    #[expect(
        clippy::too_many_arguments,
        reason = "the frame's state as encode_render_pass has it"
    )]
    fn encode_polygon_pass(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        background: DVec4,
        tone: usize,
        variants: &[ObjectVariant],
        shown: &[usize],
        (color_view, depth): (
            &wgpu::TextureView,
            wgpu::RenderPassDepthStencilAttachment<'_>,
        ),
    ) {
        let placement = SkyPlacement::BehindPolygons;
        let background =
            self.encode_background(device, encoder, background, tone, color_view, placement);
        let mut pass = self.begin_pass(
            encoder,
            "srt polygon",
            color_view,
            background,
            Some(depth),
            [Some(2), Some(3)],
        );
        pass.set_bind_group(
            POLYGON_FRAME_GROUP.index,
            &self.frame.polygon_groups[tone],
            &[],
        );
        let mut set = PipelineVariant::default();
        for &index in shown {
            let object = &self.objects[index];
            pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
            for part in &object.parts {
                let variant = variant_of_part(variants[index], part);
                set.set(&mut pass, variant, || {
                    self.pipelines.polygon(device, variant)
                });
                pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                // Checked at upload: 3 × triangles fits in u32.
                pass.draw(0..3 * part.sizes.triangles, 0..1);
            }
        }
        self.draw_sky(device, &mut pass, tone, placement);
    }

    /// Encodes the part-depth pass: the nearest visible part's depth per pixel, into
    /// `part_depth_view`, which the shading pass tests against.
    fn encode_part_depth(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        tone: usize,
        part_depth_view: &wgpu::TextureView,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("srt lrt part depth"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: part_depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipelines.part_depth);
        pass.set_bind_group(
            SHADE_FRAME_GROUP.index,
            &self.targets.shade_frame_groups[tone],
            &[],
        );
        // The frame's screen bound as two triangles (`id_depth_vertex`).
        pass.draw(0..6, 0..1);
    }

    /// Encodes the sky's passes that precede the object passes, if the scene has a sky, for
    /// its compose triangle at `placement`: the star pass, and for [`SkyPlacement::OwnPass`]
    /// the compose pass. Returns how the object passes load the colour target: over the sky
    /// (own pass), or cleared to `background` (the scene's, as the output holds it; with a
    /// sky drawn in the object pass, [`Self::draw_sky`] then covers every pixel no object does).
    pub(super) fn encode_background(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        background: DVec4,
        tone: usize,
        color_view: &wgpu::TextureView,
        placement: SkyPlacement,
    ) -> wgpu::LoadOp<wgpu::Color> {
        let b = background;
        let clear = wgpu::LoadOp::Clear(wgpu::Color {
            r: b.x,
            g: b.y,
            b: b.z,
            a: b.w,
        });
        let Some(sky) = &self.sky else {
            return clear;
        };
        let stars_frame = &self.frame.bind_groups[tone];
        let timestamp = self.timestamps.as_ref().map(|t| (&t.set, SKY_TIMESTAMP));
        if placement == SkyPlacement::OwnPass {
            let compose_frame = &self.frame.sky_groups[tone];
            sky.encode(
                device,
                encoder,
                stars_frame,
                compose_frame,
                color_view,
                timestamp,
            );
            return wgpu::LoadOp::Load;
        }
        sky.encode_stars(encoder, stars_frame, timestamp);
        clear
    }

    /// Draws the sky's compose triangle into the object pass `pass` at `placement` (after
    /// [`Self::encode_background`] for the same placement), if the scene has a sky.
    pub(super) fn draw_sky(
        &self,
        device: &wgpu::Device,
        pass: &mut wgpu::RenderPass<'_>,
        tone: usize,
        placement: SkyPlacement,
    ) {
        if let Some(sky) = &self.sky {
            sky.draw_compose(device, pass, &self.frame.sky_groups[tone], placement);
        }
    }

    /// The visibility pass's draws: the objects `shown` drawn by their footprints, then those
    /// traced through their BVH, each by the visibility pipelines of its variant (`variants`);
    /// the depth test keeps the nearest hit across both.
    fn draw_visibility(
        &self,
        device: &wgpu::Device,
        pass: &mut wgpu::RenderPass<'_>,
        traced: &[Option<&ObjectRayTracing>],
        variants: &[ObjectVariant],
        shown: &[usize],
    ) {
        let visibility = |variant| self.pipelines.visibility(device, variant);
        let mut set = PipelineVariant::default();
        for &index in shown {
            if traced[index].is_some() {
                continue;
            }
            let object = &self.objects[index];
            let variant = variants[index].for_visibility();
            set.set(pass, variant, || &visibility(variant).visibility);
            pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
            for part in &object.parts {
                pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                self.draw_footprints(pass, part);
            }
        }
        let mut set = PipelineVariant::default();
        for &index in shown {
            if let Some(rt) = traced[index] {
                let object = &self.objects[index];
                let variant = variants[index].for_visibility();
                set.set(pass, variant, || &visibility(variant).rt_visibility);
                pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
                pass.set_bind_group(PART_GROUP.index, &rt.box_part_group, &[]);
                pass.set_bind_group(RT_INPUT_GROUP.index, &rt.visibility_group, &[]);
                self.draw_box_footprints(pass, &rt.box_draw_args);
            }
        }
    }

    /// The shading pass's draws: each part's screen bound (for a traced object its box's) of
    /// the objects `shown`, by the shading pipeline of the part's variant ([`variant_of_part`]).
    fn draw_shading(
        &self,
        device: &wgpu::Device,
        pass: &mut wgpu::RenderPass<'_>,
        traced: &[Option<&ObjectRayTracing>],
        variants: &[ObjectVariant],
        shown: &[usize],
    ) {
        let mut set = PipelineVariant::default();
        for &index in shown {
            let object = &self.objects[index];
            pass.set_bind_group(OBJECT_GROUP.index, &object.bind_group, &[]);
            for part in &object.parts {
                let variant = variant_of_part(variants[index], part);
                set.set(pass, variant, || self.pipelines.shade(device, variant));
                pass.set_bind_group(PART_GROUP.index, &part.bind_group, &[]);
                let (group, draw_args) = match traced[index] {
                    Some(rt) => (&rt.shade_group, &rt.box_draw_args),
                    None => (&part.lrt_bind_group, &part.draw_args),
                };
                pass.set_bind_group(LRT_INPUT_GROUP.index, group, &[]);
                self.draw_bound(pass, draw_args);
            }
        }
    }

    /// Begins a render pass into `target` (loaded as `load` says) and `depth`, writing
    /// timestamps at the indices `[beginning, end]` given.
    pub(super) fn begin_pass<'a>(
        &self,
        encoder: &'a mut wgpu::CommandEncoder,
        label: &str,
        target: &wgpu::TextureView,
        load: wgpu::LoadOp<wgpu::Color>,
        depth: Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
        [beginning, end]: [Option<u32>; 2],
    ) -> wgpu::RenderPass<'a> {
        let stamped = beginning.is_some() || end.is_some();
        let timestamps =
            self.timestamps
                .as_ref()
                .filter(|_| stamped)
                .map(|t| wgpu::RenderPassTimestampWrites {
                    query_set: &t.set,
                    beginning_of_pass_write_index: beginning,
                    end_of_pass_write_index: end,
                });
        crate::passes::begin_pass(encoder, label, target, load, depth, timestamps)
    }

    /// Draws a part's screen bound as two triangles (`part_bound_vertex`), if any footprint
    /// behind it is on screen: the proxy pass wrote the vertex count into `draw_args` where the
    /// device has indirect draws.
    pub(super) fn draw_bound(&self, pass: &mut wgpu::RenderPass<'_>, draw_args: &wgpu::Buffer) {
        if self.indirect_draws {
            pass.draw_indirect(draw_args, SHADE_DRAW_OFFSET);
        } else {
            pass.draw(0..6, 0..1);
        }
    }

    /// Draws the footprints of an object's box (group 3 bound by the caller), up to the last
    /// one on screen where the device has indirect draws.
    pub(super) fn draw_box_footprints(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        draw_args: &wgpu::Buffer,
    ) {
        if self.indirect_draws {
            pass.draw_indirect(draw_args, 0);
        } else {
            pass.draw(0..FOOTPRINT_VERTICES * BOX_TRIANGLES, 0..1);
        }
    }

    /// Draws the footprints of `part`, `FOOTPRINT_VERTICES` vertices per triangle in one draw
    /// (not instanced: a 12-vertex instance per triangle leaves most of a software rasteriser's
    /// vertex batch empty), up to the last triangle on screen where the device has indirect
    /// draws (the proxy pass wrote the count); group 3: footprints and counter.
    pub(super) fn draw_footprints(&self, pass: &mut wgpu::RenderPass<'_>, part: &PartResources) {
        pass.set_bind_group(LRT_INPUT_GROUP.index, &part.lrt_bind_group, &[]);
        if self.indirect_draws {
            pass.draw_indirect(&part.draw_args, 0);
        } else {
            // Checked at upload: FOOTPRINT_VERTICES × triangles fits in u32.
            pass.draw(0..FOOTPRINT_VERTICES * part.sizes.triangles, 0..1);
        }
    }
}

/// The background colour `display` (sRGB-encoded) as `output` holds it: itself, or its radiance
/// (decoded, as the CPU reference writes it), alpha 0 (no object seen: [`GpuImage::pixels`]);
/// for the seen-event outputs, what a pixel that sees no object holds (0, and −1 as the object
/// index).
fn background_as(output: OutputCode, display: DVec3) -> DVec4 {
    match output {
        OutputCode::RADIANCE => display.map(srgb_decode).extend(0.0),
        OutputCode::SEEN_EVENT => DVec4::ZERO,
        OutputCode::SEEN_OBJECT => DVec4::new(-1.0, 0.0, 0.0, 0.0),
        _ => display.extend(0.0),
    }
}

/// The variant a part of an object drawn as `object` is drawn as: the object's, textured where
/// the part has a texture.
pub(super) fn variant_of_part(object: ObjectVariant, part: &PartResources) -> ObjectVariant {
    ObjectVariant {
        textured: part.material.flags.contains(PartFlags::TEXTURED),
        ..object
    }
}

/// The pipeline variant a render pass has set, so that a run of draws of one variant sets its
/// pipeline once.
#[derive(Default)]
struct PipelineVariant(Option<ObjectVariant>);

impl PipelineVariant {
    /// Sets in `pass` the pipeline `pipeline` gives for `variant`, unless it is the one set.
    fn set<'p>(
        &mut self,
        pass: &mut wgpu::RenderPass<'_>,
        variant: ObjectVariant,
        pipeline: impl FnOnce() -> &'p wgpu::RenderPipeline,
    ) {
        if self.0 != Some(variant) {
            pass.set_pipeline(pipeline());
            self.0 = Some(variant);
        }
    }
}

/// The ball (centre and radius in S′) that holds `object` at every event a backward ray can meet
/// it: around its vertices at rest, or around the box its motion sweeps ([`sweep_bounds`]).
fn object_ball(
    object: &Object,
    resources: &ObjectResources,
    event: srt_physics::Event,
) -> (DVec3, f64) {
    sweep_bounds(object, &resources.extent, event).map_or(resources.extent.ball, |(lo, hi)| {
        ((lo + hi) / 2.0, (hi - lo).length() / 2.0)
    })
}

/// Writes each batch of `object`'s parts' material with its back-face culling for the
/// observation event `event`: the back faces of a batch of closed solids are hidden when the
/// observer is outside every one of them.
fn write_part_culling(
    ctx: &GpuContext,
    object: &Object,
    resources: &ObjectResources,
    event: srt_physics::Event,
) {
    // Whether each part's back faces may be culled, worked out once however many slices of it
    // the batches hold (a winding number costs a pass over the mesh).
    let mut part_culled: Vec<Option<bool>> = vec![None; object.parts.len()];
    for batch in &resources.parts {
        let cull = batch.members.iter().all(|slice| {
            *part_culled[slice.part].get_or_insert_with(|| {
                resources.culling[slice.part].applies(
                    &object.parts[slice.part].mesh,
                    &object.frame,
                    event,
                )
            })
        });
        let mut material = batch.material;
        material.flags = material.flags.with(PartFlags::CULL_BACK_FACES, cull);
        ctx.queue
            .write_buffer(&batch.uniforms, 0, bytemuck::bytes_of(&material));
    }
}
