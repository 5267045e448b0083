//! The reference renderer: for every pixel sample, the backward viewing ray from the observation
//! event is transformed into each object's rest frame S′ (Eq. 3, 5), intersected there with the
//! static mesh through a BVH (Eq. 15–16), mapped back to S (Eq. 7–8), and the smallest apparent
//! distance over all objects wins; the winner is shaded (Eq. 17–18).
//!
//! Each object has one BVH over all its parts' triangles. A ray is taken into S′ once per group
//! of objects sharing a velocity, and an object's BVH is walked only if the ray meets its box
//! before the nearest hit so far (apparent distance grows linearly along each object's ray), so
//! that a ray costs about one box test per object it misses. None of this changes a result:
//! ties go to the lowest (object, part, triangle) whatever the order of the search.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use glam::{DVec2, DVec3, DVec4};
use rayon::prelude::*;
use srt_color::{RadianceScale, RadianceTable, TemperatureLut, quantize_8bit, srgb_decode};
use srt_physics::{Event, FourVelocity, RetardedLight};
use srt_scene::{Scene, ViewRays};
use web_time::Instant;

use crate::clock::clock_albedo;
use crate::group::{RestDirection, VelocityGroup};
use crate::intersect::plane_hit;
use crate::moving::{local_rest_frame, moving_normal};
pub use crate::prepared::Hit;
use crate::prepared::{MipChains, PreparedObject};
use crate::seen::SeenEvent;
use crate::shade::{Arriving, Illumination, SurfacePoint, arriving_unless_shadowed};
use crate::shared::SharedBvhs;
use crate::sky::{StarLayer, sky_image_light, star_layer};
use crate::texture::sample_trilinear;

/// Image size and sampling.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderSettings {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Samples per pixel (1 = the pixel centre only).
    pub samples: u32,
}

/// A rendered picture.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Display colours (sRGB-encoded, [0, 1]), row-major from the top.
    pub pixels: Vec<DVec3>,
    /// Per pixel, 1 + the index of the object hit by the first sample (the pixel centre), or 0
    /// for the background: for silhouette masks in tests and validation.
    pub coverage: Vec<u32>,
}

impl RenderedImage {
    /// 8-bit sRGB pixels, rounded.
    #[must_use]
    pub fn to_rgb8(&self) -> Vec<[u8; 3]> {
        self.pixels
            .iter()
            .map(|p| p.to_array().map(quantize_8bit))
            .collect()
    }
}

pub use srt_color::Output;

/// The surface point a [`Hit`] sees, in the local rest frame it is shaded in
/// ([`Tracer::surface_at`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceState {
    /// The body point (its place in the object's rest coordinates at S′ time 0).
    pub body: DVec3,
    /// The object's S′ time ct′ at the emission event.
    pub ct: f64,
    /// The proper time a clock riding on the point shows there (ct′ for a body at rest in S′).
    pub proper_time: f64,
    /// The velocity of the point's local rest frame relative to S (its four-velocity: finite
    /// where β rounds to |β| = 1).
    pub velocity: FourVelocity,
    /// The unit surface normal in that frame (a pure boost from S).
    pub normal: DVec3,
}

/// A scene prepared for tracing: BVHs built, textures mipmapped, colour table built.
pub struct Tracer<'a> {
    scene: &'a Scene,
    objects: Vec<PreparedObject<'a>>,
    /// The objects grouped by velocity: a ray's direction in S′ is computed once per group,
    /// and a group's resting objects are searched through one BVH over their boxes (the
    /// flythrough's columns and slabs all rest in the world frame).
    velocity_groups: Vec<VelocityGroup>,
    lut: &'static TemperatureLut,
    /// The stars' light on the last picture's size and output ([`star_layer`]): the same for
    /// every band and every measure of a picture, and a few milliseconds for a sky of
    /// thousands of stars.
    stars: Mutex<Option<(StarsKey, Arc<StarLayer>)>>,
}

/// What a picture's star layer depends on besides the scene: its size and output.
type StarsKey = (u32, u32, Output);

impl<'a> Tracer<'a> {
    /// Prepares `scene` (builds one BVH per part, the mip chains and the colour table).
    #[must_use]
    pub fn new(scene: &'a Scene) -> Self {
        let observer = scene.observer.event();
        let mut chains = MipChains::default();
        let mut bvhs = SharedBvhs::begin();
        let objects: Vec<PreparedObject<'a>> = (scene.objects.iter())
            .map(|object| PreparedObject::new(object, observer, &mut chains, &mut bvhs))
            .collect();
        bvhs.finish();
        let velocity_groups = VelocityGroup::of_objects(&objects);
        Self {
            scene,
            objects,
            velocity_groups,
            lut: TemperatureLut::shared(scene.tone_map),
            stars: Mutex::new(None),
        }
    }

    /// The scene being traced.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        self.scene
    }

    /// The colour table used for shading.
    #[must_use]
    pub const fn lut(&self) -> &TemperatureLut {
        self.lut
    }

    /// The closest surface seen along `view_direction` (in S) from the observation event.
    #[must_use]
    pub fn trace(&self, view_direction: DVec3) -> Option<Hit> {
        self.trace_from(DVec3::ZERO, view_direction)
    }

    /// The closest surface seen along `view_direction` (in S) from the eye `eye` away from the
    /// observer (in S, at the observation time: a stereo pair's, [`srt_scene::ViewRays::ray`];
    /// zero for the observer itself).
    #[must_use]
    pub fn trace_from(&self, eye: DVec3, view_direction: DVec3) -> Option<Hit> {
        self.trace_with(eye, |_, group| {
            group.rest_direction(&self.objects, view_direction)
        })
    }

    /// [`Tracer::trace_from`] with the ray's direction in the rest frames of the `g`-th
    /// velocity group given by `direction_in(g, group)`.
    fn trace_with(
        &self,
        eye: DVec3,
        direction_in: impl Fn(usize, &VelocityGroup) -> RestDirection,
    ) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let origin_of = |object: &PreparedObject<'_>| {
            if eye == DVec3::ZERO {
                object.observer_rest
            } else {
                object.frame.to_rest(self.eye_event(eye))
            }
        };
        for (index, group) in self.velocity_groups.iter().enumerate() {
            group.search(
                &self.objects,
                direction_in(index, group),
                &origin_of,
                &mut best,
            );
        }
        best.map(|hit| Hit { eye, ..hit })
    }

    /// The rest-frame directions of the viewing directions of `rays` (`None`: no ray; at most
    /// [`RAY_BATCH`]) in every velocity group, ray by ray, `groups` entries each (a missing
    /// ray's are left at their default), written over `directions`. Computed side by side
    /// ([`srt_physics::Frame::rest_directions`]): the square roots and divisions of two rays
    /// share a vector instruction, and a ray's chain of them overlaps the next ray's, where ray
    /// by ray in the search each would wait for the last.
    fn rest_directions(
        &self,
        rays: &[Option<(DVec3, DVec3)>],
        directions: &mut Vec<RestDirection>,
    ) {
        let groups = self.velocity_groups.len();
        directions.clear();
        directions.resize(rays.len() * groups, RestDirection::default());
        // A ray the picture does not cast (outside a fisheye's circle) stands in as +x; its
        // directions are then the default.
        let count = rays.len();
        let mut views = [DVec3::X; RAY_BATCH];
        for (view, ray) in views.iter_mut().zip(rays) {
            if let Some((_, direction)) = ray {
                *view = *direction;
            }
        }
        let mut rest = [DVec3::ZERO; RAY_BATCH];
        for (g, group) in self.velocity_groups.iter().enumerate() {
            (group.frame(&self.objects)).rest_directions(&views[..count], &mut rest[..count]);
            for (i, (ray, &direction)) in rays.iter().zip(&rest).enumerate() {
                if ray.is_some() {
                    directions[i * groups + g] = RestDirection::new(direction);
                }
            }
        }
    }

    /// The observation event of the eye `eye` away from the observer (in S).
    fn eye_event(&self, eye: DVec3) -> Event {
        let observer = self.scene.observer.event();
        Event::new(observer.ct, observer.position + eye)
    }

    /// The closest surface seen through the centre of pixel (`x`, `y`) (0-based, from the
    /// top-left corner) of a `width` × `height` image: the viewing ray [`Tracer::render`] casts
    /// for the pixel's first sample. `None` for the background or a pixel outside the image.
    #[must_use]
    pub fn hit_at_pixel(&self, width: u32, height: u32, x: u32, y: u32) -> Option<Hit> {
        if x >= width || y >= height {
            return None;
        }
        let centre = sample_offsets(1)[0];
        self.hit_at(
            width,
            height,
            DVec2::new(f64::from(x), f64::from(y)) + centre,
        )
    }

    /// The closest surface seen through the point `point` of a `width` × `height` image, in
    /// pixels from its top-left corner (pixel (x, y)'s centre is (x + ½, y + ½)): the ray
    /// [`Tracer::hit_at_pixel`] casts, anywhere in the picture.
    #[must_use]
    pub fn hit_at(&self, width: u32, height: u32, point: DVec2) -> Option<Hit> {
        let (eye, direction) = ImageRays::new(self.scene, width, height).ray(point.x, point.y)?;
        self.trace_from(eye, direction)
    }

    /// Display colour of a hit. `neighbour_directions` are the viewing directions one pixel to
    /// the right and one pixel down, for texture filtering (ray differentials).
    #[must_use]
    pub fn shade(&self, hit: &Hit, neighbour_directions: [DVec3; 2]) -> DVec3 {
        (self.light(hit, neighbour_directions))
            .display(self.lut, self.scene.exposure)
            .clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// The surface point a hit sees, in the frame it is shaded in: its body point, the
    /// object's S′ time ct′ at the event, the proper time a clock riding on the point shows
    /// there, the velocity of the point's local rest frame relative to S and the unit normal in
    /// that frame (for a body at rest in S′: the object frame's velocity and the interpolated
    /// normal).
    #[must_use]
    pub fn surface_at(&self, hit: &Hit) -> SurfaceState {
        let object = &self.objects[hit.object];
        let ct = self.scene.objects[hit.object].proper_time(hit.emission_rest.ct);
        let mesh = &object.parts[hit.part].part.mesh;
        let indices = mesh.triangles()[hit.triangle].map(|i| i as usize);
        let weights = hit.rest_hit.weights();
        let interpolate =
            |values: &[DVec3]| -> DVec3 { (0..3).map(|k| weights[k] * values[indices[k]]).sum() };
        let normal = interpolate(mesh.normals()).normalize();
        let body = interpolate(mesh.positions());
        if object.motion.is_rest() {
            return SurfaceState {
                body,
                ct,
                proper_time: ct,
                velocity: FourVelocity::from_beta(object.frame.beta()),
                normal,
            };
        }
        let velocity = object.motion.four_velocity(body, ct);
        let four_normal = moving_normal(&object.motion, body, ct, normal);
        let (velocity, normal) = local_rest_frame(object.frame.beta(), velocity, four_normal);
        SurfaceState {
            body,
            ct,
            proper_time: object.motion.proper_time(body, ct),
            velocity,
            normal,
        }
    }

    /// The light a hit sends to the observer ([`Tracer::shade`] shows it).
    #[must_use]
    pub fn light(&self, hit: &Hit, neighbour_directions: [DVec3; 2]) -> Arriving {
        let object = &self.objects[hit.object];
        let seen_object = &self.scene.objects[hit.object];
        let surface = self.surface_at(hit);
        let proper_time = surface.proper_time;
        let part = &object.parts[hit.part];
        let mesh = &part.part.mesh;
        let indices = mesh.triangles()[hit.triangle].map(|i| i as usize);
        let weights = hit.rest_hit.weights();
        let mut albedo = part.base_color;
        if let Some(colors) = mesh.colors() {
            let c: DVec4 = (0..3)
                .map(|k| weights[k] * DVec4::from_array(colors[indices[k]].map(f64::from)))
                .sum();
            albedo *= c;
        }
        let corners = mesh.triangle_positions(hit.triangle);
        // Where the triangle is at the event (a moving body's; texture differentials).
        let placed = corners.map(|c| object.motion.position(c, surface.ct));
        if let Some(width) = object.wireframe {
            // Distance (in S′) to the nearest edge: weight × the height over that edge.
            let twice_area = (corners[1] - corners[0])
                .cross(corners[2] - corners[0])
                .length();
            let near_edge = (0..3).any(|k| {
                let edge = (corners[(k + 2) % 3] - corners[(k + 1) % 3]).length();
                weights[k] * twice_area / edge < width
            });
            albedo = if near_edge {
                DVec4::new(0.0, 0.0, 0.0, 1.0)
            } else {
                DVec4::ONE
            };
        } else if seen_object.clock.is_some() || part.texture.is_some() {
            let uvs = mesh.uvs();
            let uv_at = |(zeta, xi): (f64, f64)| {
                (1.0 - zeta - xi) * uvs[indices[0]] + zeta * uvs[indices[1]] + xi * uvs[indices[2]]
            };
            let uv = uv_at((hit.rest_hit.zeta, hit.rest_hit.xi));
            let observer = self.eye_event(hit.eye);
            let differential = |direction: DVec3| -> DVec2 {
                let ray = object.frame.backward_ray(observer, direction);
                plane_hit(ray.origin, ray.direction, placed)
                    .map_or(DVec2::ZERO, |h| uv_at((h.zeta, h.xi)) - uv)
            };
            let (ddx, ddy) = (
                differential(neighbour_directions[0]),
                differential(neighbour_directions[1]),
            );
            if let Some(clock) = &seen_object.clock {
                albedo *= clock_albedo(clock, uv, ddx, ddy, proper_time);
            } else if let Some(texture) = &part.texture {
                // A flipbook shows the frame of the proper time at the emission event.
                let frame = part
                    .part
                    .material
                    .texture
                    .as_ref()
                    .map_or(0, |t| t.frame_at(proper_time));
                albedo *= sample_trilinear(texture, frame, uv, ddx, ddy);
            }
        }
        let illumination = Illumination {
            observer: self.scene.observer.position + hit.eye,
            light_position: self.scene.light.position,
            light_temperature_k: self.scene.light.temperature_k,
            light_strength: self.scene.light.strength,
            moving_lights: &self.scene.lights,
            shading: self.scene.shading,
            effects: self.scene.effects,
            lut: self.lut,
            colour: self.scene.colour,
            exposure: self.scene.exposure,
        };
        let point = SurfacePoint {
            velocity: surface.velocity,
            normal_rest: surface.normal,
            apparent_position: hit.emission.position,
            albedo,
            optics: seen_object.optics,
            proper_time,
            emission_ct: hit.emission.ct,
        };
        arriving_unless_shadowed(&point, &illumination, &|light| {
            self.scene.shadows && self.shadowed(light, hit.emission)
        })
    }

    /// Whether `light`, on its null ray from its retarded event to the event `at` (both in S),
    /// is blocked on the way: the segment is taken into each object's rest frame, where the
    /// object is static and the segment a straight piece of a ray (a null line stays null), and
    /// tested against its triangles, as a viewing ray is. Emitting objects (the lamps' visible
    /// bulbs) cast no shadow.
    fn shadowed(&self, light: &RetardedLight, at: Event) -> bool {
        (self.objects.iter().zip(&self.scene.objects))
            .filter(|(_, object)| object.optics.emission.is_none())
            .any(|(prepared, _)| {
                prepared.blocks(
                    prepared.frame.to_rest(at),
                    prepared.frame.to_rest(light.source_event),
                )
            })
    }

    /// Renders the image as it is shown (display colours, the tone map's, in [0, 1]); `progress`
    /// is called with the number of finished rows (from worker threads, in no particular order).
    /// Deterministic: the result does not depend on the number of threads.
    #[must_use]
    pub fn render(
        &self,
        settings: RenderSettings,
        progress: &(dyn Fn(u32) + Sync),
    ) -> RenderedImage {
        self.render_as(settings, progress, Output::Display, None)
            .unwrap_or_else(|| unreachable!("a render without a stop flag finishes"))
    }

    /// Renders the image's radiance: linear BT.709, unclamped, luminance 1 for a white surface
    /// at rest facing the lamp (srt-color's `radiance` module); the background's display colour
    /// counts as its linear light. As [`Tracer::render`] otherwise.
    #[must_use]
    pub fn render_radiance(
        &self,
        settings: RenderSettings,
        progress: &(dyn Fn(u32) + Sync),
    ) -> RenderedImage {
        self.render_as(settings, progress, Output::Radiance, None)
            .unwrap_or_else(|| unreachable!("a render without a stop flag finishes"))
    }

    /// [`Tracer::render`] or [`Tracer::render_radiance`], as `output` says, that gives up when
    /// `stop` is set (checked before each row: a caller's Ctrl-C). `None` if it gave up; the
    /// image otherwise, the same as theirs.
    #[must_use]
    pub fn render_stoppable(
        &self,
        settings: RenderSettings,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> Option<RenderedImage> {
        self.render_as(settings, progress, output, Some(stop))
    }

    /// The rows `rows` of the image [`Tracer::render_stoppable`] renders (a band, for writing
    /// an image of any size a band at a time): the same pixels, bit for bit, as those rows of
    /// the whole image; the result's `height` is the band's. `progress` hears the number of
    /// finished rows of the band.
    ///
    /// # Panics
    /// If `rows` reaches past the image's height.
    #[must_use]
    pub fn render_band(
        &self,
        settings: RenderSettings,
        rows: Range<u32>,
        output: Output,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> Option<RenderedImage> {
        self.render_band_reusing(settings, rows, output, progress, stop, None)
    }

    /// The stars' light on a picture of `key`'s size and output, each star's light made a
    /// pixel value by `value` ([`star_layer`]), made once for successive calls of the same key.
    fn stars_of(&self, key: StarsKey, value: &dyn Fn(&Arriving) -> DVec3) -> Arc<StarLayer> {
        let mut kept = self.stars.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((kept_key, stars)) = kept.as_ref()
            && *kept_key == key
        {
            return Arc::clone(stars);
        }
        let stars = Arc::new(star_layer(self.scene, key.0, key.1, value));
        *kept = Some((key, Arc::clone(&stars)));
        stars
    }

    /// [`Tracer::render`] or [`Tracer::render_radiance`], as `output` says; `None` if `stop` was
    /// set before some row began.
    fn render_as(
        &self,
        settings: RenderSettings,
        progress: &(dyn Fn(u32) + Sync),
        output: Output,
        stop: Option<&AtomicBool>,
    ) -> Option<RenderedImage> {
        let rows: Vec<u32> = (0..settings.height).collect();
        self.render_listed_rows(settings, &rows, progress, output, stop, Rows::Traced)
    }

    /// The rows `rows` (in the order given) of [`Tracer::render_as`]'s image, traced or taken
    /// as `how` says.
    pub(crate) fn render_listed_rows(
        &self,
        settings: RenderSettings,
        rows: &[u32],
        progress: &(dyn Fn(u32) + Sync),
        output: Output,
        stop: Option<&AtomicBool>,
        how: Rows<'_>,
    ) -> Option<RenderedImage> {
        let RenderSettings {
            width,
            height,
            samples,
        } = settings;
        assert!(
            rows.iter().all(|&y| y < height),
            "rows {rows:?} of a {height}-row image"
        );
        let image_rays = ImageRays::new(self.scene, width, height);
        let offsets = sample_offsets(samples.max(1));
        let colouring = Colouring::new(self, (width, height), output);
        let band_height = rows.len() as u32;
        let work = match how {
            Rows::Timed(work) => Some(work),
            Rows::Traced | Rows::Reusing(_) => None,
        };
        let known = match how {
            Rows::Reusing(known) => Some(known),
            Rows::Traced | Rows::Timed(_) => None,
        };
        let count = width as usize * rows.len();
        // Filled on the workers, so that the first touch of the picture's pages (the kernel
        // clears each) is shared among them, not left to this thread.
        let mut pixels = Vec::with_capacity(count);
        pixels.par_extend(rayon::iter::repeat_n(DVec3::ZERO, count));
        let mut coverage = vec![0_u32; count];
        let finished = rows_in_parallel_into(
            rows,
            (&mut pixels, &mut coverage),
            width as usize,
            progress,
            stop,
            work,
            |y, (colours, coverage)| {
                if let Some((pixels, known_coverage)) = known.and_then(|known| known.row(y)) {
                    colours.copy_from_slice(pixels);
                    coverage.copy_from_slice(known_coverage);
                    return;
                }
                let samples = offsets.len();
                let (mut sum, mut first_object) = (DVec3::ZERO, 0);
                self.trace_row(&image_rays, y, width, &offsets, |sample, traced| {
                    let Sample {
                        x,
                        k,
                        point: (sx, sy),
                    } = sample;
                    if k == 0 {
                        first_object =
                            (traced.and_then(|(_, hit)| hit)).map_or(0, |h| h.object as u32 + 1);
                    }
                    let pixel = y as usize * width as usize + x;
                    sum += colouring.sample(traced, &image_rays, (sx, sy), pixel);
                    if k + 1 == samples {
                        // A pixel of one sample is that sample (x / 1 = x, bit for bit).
                        colours[x] = if samples == 1 {
                            sum
                        } else {
                            sum / samples as f64
                        };
                        coverage[x] = first_object;
                        (sum, first_object) = (DVec3::ZERO, 0);
                    }
                });
            },
        );
        if !finished {
            return None;
        }
        Some(RenderedImage {
            width,
            height: band_height,
            pixels,
            coverage,
        })
    }
}

/// How a picture's traced samples become its values: the output's map from light to value,
/// its background, the stars' light on its pixels, and the one colour a ray that meets nothing
/// shows where there is one (no sky image, no stars).
struct Colouring<'t, 'a> {
    tracer: &'t Tracer<'a>,
    output: Output,
    /// The radiance table and the scene's scale on it, for radiance output.
    radiance: Option<(&'static RadianceTable, RadianceScale)>,
    background: DVec3,
    stars: Arc<StarLayer>,
    missed: Option<DVec3>,
}

impl<'t, 'a> Colouring<'t, 'a> {
    /// The colouring of `tracer`'s pictures of `size` for `output`.
    fn new(tracer: &'t Tracer<'a>, size: (u32, u32), output: Output) -> Self {
        let scene = tracer.scene;
        // The radiance table (built once per process, as long as the colour table) only for
        // radiance: a display picture need not wait for it.
        let radiance = (output == Output::Radiance).then(|| {
            let table = RadianceTable::shared();
            (table, scene.radiance_scale(table))
        });
        let background = match output {
            Output::Display => scene.background,
            Output::Radiance => scene.background.map(srgb_decode),
        };
        let mut colouring = Self {
            tracer,
            output,
            radiance,
            background,
            stars: Arc::default(),
            missed: None,
        };
        colouring.stars = tracer.stars_of((size.0, size.1, output), &|l| colouring.value(l));
        // Without a sky image or stars, what a ray that meets nothing sees is one colour, the
        // same whatever its direction (the sum `sample` makes, made once).
        colouring.missed = (scene.sky.image.is_none() && colouring.stars.is_empty())
            .then(|| colouring.finish(background + colouring.value(&Arriving::Dark) + DVec3::ZERO));
        colouring
    }

    /// The value of `light` in the output: display colour or radiance.
    fn value(&self, light: &Arriving) -> DVec3 {
        match &self.radiance {
            None => light.display(self.tracer.lut, self.tracer.scene.exposure),
            Some((table, scale)) => light.radiance(table, scale),
        }
    }

    /// A sample's value as it is summed into its pixel: clamped to [0, 1] for display.
    fn finish(&self, colour: DVec3) -> DVec3 {
        match self.output {
            Output::Display => colour.clamp(DVec3::ZERO, DVec3::ONE),
            Output::Radiance => colour,
        }
    }

    /// The value of a sample at `point` of pixel number `pixel` (row-major), traced as
    /// [`Tracer::trace_row`] gives it (`None`: the picture sees nothing there).
    fn sample(
        &self,
        traced: Option<(DVec3, Option<Hit>)>,
        image_rays: &ImageRays,
        (sx, sy): (f64, f64),
        pixel: usize,
    ) -> DVec3 {
        let Some((direction, hit)) = traced else {
            // Outside a fisheye's circle the image sees nothing: the background.
            return self.finish(self.background);
        };
        match (hit, self.missed) {
            (None, Some(missed)) => missed,
            (None, None) => {
                let sky = self.value(&sky_image_light(self.tracer.scene, direction));
                self.finish(self.background + sky + self.stars.at(pixel))
            }
            (Some(hit), _) => {
                // A neighbour beyond the fisheye's rim: no footprint that way.
                let neighbours = [(1.0, 0.0), (0.0, 1.0)]
                    .map(|step| image_rays.neighbour(sx, sy, step).unwrap_or(direction));
                self.finish(self.value(&self.tracer.light(&hit, neighbours)))
            }
        }
    }
}

impl Tracer<'_> {
    /// Traces every sample of row `y` of a `width`-pixel picture (`offsets` within each pixel,
    /// the pixel's samples in turn, pixels from the left) and gives each to `each` with its
    /// viewing direction and hit (`None` where the picture sees nothing, outside a fisheye's
    /// circle). The samples' rest-frame directions are computed [`RAY_BATCH`] at a time
    /// ([`Tracer::rest_directions`]).
    fn trace_row(
        &self,
        image_rays: &ImageRays,
        y: u32,
        width: u32,
        offsets: &[DVec2],
        mut each: impl FnMut(Sample, Option<(DVec3, Option<Hit>)>),
    ) {
        let samples = offsets.len();
        let groups = self.velocity_groups.len();
        let sample_at = |slot: usize| {
            let (x, k) = (slot / samples, slot % samples);
            let offset = offsets[k];
            let point = (f64::from(x as u32) + offset.x, f64::from(y) + offset.y);
            Sample { x, k, point }
        };
        let (mut rays, mut directions) = (Vec::new(), Vec::new());
        let slots = width as usize * samples;
        for start in (0..slots).step_by(RAY_BATCH) {
            let batch = start..(start + RAY_BATCH).min(slots);
            rays.clear();
            rays.extend(batch.clone().map(|slot| {
                let (sx, sy) = sample_at(slot).point;
                image_rays.ray(sx, sy)
            }));
            self.rest_directions(&rays, &mut directions);
            for (i, (slot, ray)) in batch.zip(&rays).enumerate() {
                let directions = &directions[i * groups..][..groups];
                let traced = ray.map(|(eye, direction)| {
                    (
                        direction,
                        self.trace_with(eye, |group, _| directions[group]),
                    )
                });
                each(sample_at(slot), traced);
            }
        }
    }

    /// What [`Tracer::render`] covers each pixel with (1 + the index of the object the pixel's
    /// first sample hits, 0 for the background, [`RenderedImage::coverage`]), found by tracing
    /// alone, nothing shaded: what tracing costs of a picture.
    #[must_use]
    pub fn coverage(&self, settings: RenderSettings) -> Vec<u32> {
        let RenderSettings {
            width,
            height,
            samples,
        } = settings;
        let image_rays = ImageRays::new(self.scene, width, height);
        let offsets = sample_offsets(samples.max(1));
        let rows: Vec<u32> = (0..height).collect();
        let count = width as usize * height as usize;
        let (mut coverage, mut unused) = (vec![0_u32; count], vec![(); count]);
        rows_in_parallel_into(
            &rows,
            (&mut coverage, &mut unused),
            width as usize,
            &|_| {},
            None,
            None,
            |y, (coverage, _)| {
                self.trace_row(&image_rays, y, width, &offsets, |sample, traced| {
                    if sample.k == 0 {
                        coverage[sample.x] = traced
                            .and_then(|(_, hit)| hit)
                            .map_or(0, |hit| hit.object as u32 + 1);
                    }
                });
            },
        );
        coverage
    }
}

/// A sample of a row ([`Tracer::trace_row`]): its pixel, its number within the pixel and its
/// point in the picture, in pixels from the top-left corner.
struct Sample {
    x: usize,
    k: usize,
    point: (f64, f64),
}

impl Tracer<'_> {
    /// The emission event of `hit` in the scene's terms ([`SeenEvent`]).
    #[must_use]
    pub fn seen_event(&self, hit: &Hit) -> SeenEvent {
        let scene = self.scene();
        let surface = self.surface_at(hit);
        let towards_observer =
            (scene.observer.position + hit.eye - hit.emission.position).normalize();
        SeenEvent {
            object: hit.object,
            emission_ct: scene.world.apply(hit.emission).ct,
            proper_time: surface.proper_time,
            distance: hit.apparent_distance,
            doppler: surface.velocity.doppler_factor(towards_observer),
        }
    }

    /// What the centre of each pixel of a `width` × `height` image sees of time
    /// ([`SeenEvent`]), row-major from the top; `None` for a pixel that sees no object. Gives
    /// up (`None`) once `stop` is set, as [`Tracer::render_stoppable`].
    #[must_use]
    pub fn render_seen_events(
        &self,
        width: u32,
        height: u32,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> Option<Vec<Option<SeenEvent>>> {
        self.render_seen_events_band(width, height, 0..height, progress, stop)
    }

    /// The rows `rows` of [`Tracer::render_seen_events`]'s picture (a band, as
    /// [`Tracer::render_band`]).
    ///
    /// # Panics
    /// If `rows` reaches past `height`.
    #[must_use]
    pub fn render_seen_events_band(
        &self,
        width: u32,
        height: u32,
        rows: Range<u32>,
        progress: &(dyn Fn(u32) + Sync),
        stop: &AtomicBool,
    ) -> Option<Vec<Option<SeenEvent>>> {
        assert!(rows.end <= height, "rows {rows:?} of a {height}-row image");
        let rows: Vec<u32> = rows.collect();
        let rows = rows_in_parallel(&rows, progress, Some(stop), None, |y| {
            (0..width)
                .map(|x| {
                    self.hit_at_pixel(width, height, x, y)
                        .map(|hit| self.seen_event(&hit))
                })
                .collect::<Vec<_>>()
        })?;
        Some(rows.into_iter().flatten().collect())
    }
}

/// What a frame of the CPU tracer costs ([`Tracer::measure_frame`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameCost {
    /// Seconds a frame takes whatever its rows (the rays' basis; the stars' light is made once
    /// per picture size and kept by the tracer).
    pub setup_seconds: f64,
    /// Seconds a row takes on average, every thread at work.
    pub row_seconds: f64,
    /// The frame's rows.
    pub rows: u32,
}

impl FrameCost {
    /// The frame's estimated seconds: its setup and every row.
    #[must_use]
    pub fn seconds(&self) -> f64 {
        self.setup_seconds + self.row_seconds * f64::from(self.rows)
    }
}

/// `count` rows of a `height`-row image spread evenly over it (the middle row of each of
/// `count` equal bands, all of them when `count` ≥ `height`), in order.
#[must_use]
pub fn spread_rows(height: u32, count: u32) -> Vec<u32> {
    let count = count.clamp(1, height.max(1));
    (0..count)
        .map(|band| ((2 * u64::from(band) + 1) * u64::from(height) / (2 * u64::from(count))) as u32)
        .filter(|&row| row < height)
        .collect()
}

/// Runs `row` for every row of `rows` on rayon's threads and returns them in order; `progress`
/// hears the number of finished rows, and `work[i]` (when given) gains the `i`-th row's
/// nanoseconds of work ([`WorkClock`]). `None` once `stop` is set: rows not yet begun are
/// skipped.
fn rows_in_parallel<T: Send>(
    rows: &[u32],
    progress: &(dyn Fn(u32) + Sync),
    stop: Option<&AtomicBool>,
    work: Option<&[AtomicU64]>,
    row: impl Fn(u32) -> T + Sync,
) -> Option<Vec<T>> {
    let finished = AtomicU32::new(0);
    let rows: Vec<Option<T>> = rows
        .par_iter()
        .enumerate()
        .map(|(index, &y)| {
            if stop.is_some_and(|stop| stop.load(Ordering::Relaxed)) {
                return None;
            }
            let start = work.map(|_| WorkClock::start());
            let done = row(y);
            if let (Some(work), Some(start)) = (work, start) {
                work[index].fetch_add(start.nanoseconds(), Ordering::Relaxed);
            }
            progress(finished.fetch_add(1, Ordering::Relaxed) + 1);
            Some(done)
        })
        .collect();
    rows.into_iter().collect()
}

/// Runs `row(y, (pixels, coverage))` for every row `y` of `rows` on rayon's threads, each
/// writing its own `width`-long stretch of `outputs` (row `i` of `rows` at `i × width`), so that
/// a picture is written where it is kept, not gathered from rows; `progress` and `work` as
/// [`rows_in_parallel`]. `false` once `stop` is set (rows not yet begun are skipped and left
/// as they were).
fn rows_in_parallel_into<A: Send, B: Send>(
    rows: &[u32],
    (first, second): (&mut [A], &mut [B]),
    width: usize,
    progress: &(dyn Fn(u32) + Sync),
    stop: Option<&AtomicBool>,
    work: Option<&[AtomicU64]>,
    row: impl Fn(u32, (&mut [A], &mut [B])) + Sync,
) -> bool {
    let finished = AtomicU32::new(0);
    let stopped = || stop.is_some_and(|stop| stop.load(Ordering::Relaxed));
    if width == 0 {
        // Rows without pixels: nothing to write, nothing to chunk.
        return !stopped();
    }
    (rows.par_iter().enumerate())
        .zip(first.par_chunks_mut(width))
        .zip(second.par_chunks_mut(width))
        .for_each(|(((index, &y), first), second)| {
            if stopped() {
                return;
            }
            let start = work.map(|_| WorkClock::start());
            row(y, (first, second));
            if let (Some(work), Some(start)) = (work, start) {
                work[index].fetch_add(start.nanoseconds(), Ordering::Relaxed);
            }
            progress(finished.fetch_add(1, Ordering::Relaxed) + 1);
        });
    finished.load(Ordering::Relaxed) as usize == rows.len()
}

/// How [`Tracer::render_listed_rows`] comes by its rows.
#[derive(Clone, Copy)]
pub(crate) enum Rows<'r> {
    /// Every row traced.
    Traced,
    /// Every row traced, the nanoseconds of work of the `i`-th row added to the `i`-th counter
    /// ([`WorkClock`]).
    Timed(&'r [AtomicU64]),
    /// The rows already traced taken from them (the same pixels, bit for bit, as every row is
    /// traced alike), the others traced.
    Reusing(KnownRows<'r>),
}

/// Rows of a picture already traced (a measure's, [`crate::FrameMeasure`]): their indices,
/// ascending, and their pixels in that order.
#[derive(Clone, Copy)]
pub(crate) struct KnownRows<'r> {
    /// The rows, ascending, without repeats.
    pub(crate) rows: &'r [u32],
    /// Their pixels and coverage, a row of the picture each.
    pub(crate) image: &'r RenderedImage,
}

impl<'r> KnownRows<'r> {
    /// The pixels and coverage of row `row` of the picture, if it is known.
    pub(crate) fn row(self, row: u32) -> Option<(&'r [DVec3], &'r [u32])> {
        let index = self.rows.binary_search(&row).ok()?;
        let width = self.image.width as usize;
        Some((
            &self.image.pixels[index * width..][..width],
            &self.image.coverage[index * width..][..width],
        ))
    }
}

/// The work a thread has done since [`WorkClock::start`]: its CPU time where the system keeps
/// one (a moment in which another process held the core is not counted, a scheduler's tick of
/// 4 ms that would add half as much again to a measured picture of 0.2 s), its wall time
/// elsewhere.
enum WorkClock {
    /// The thread's CPU time at the start.
    #[cfg(not(target_arch = "wasm32"))]
    Cpu(cpu_time::ThreadTime),
    /// The wall time at the start.
    Wall(Instant),
}

impl WorkClock {
    /// Starts counting the current thread's work.
    fn start() -> Self {
        #[cfg(not(target_arch = "wasm32"))]
        if let Ok(time) = cpu_time::ThreadTime::try_now() {
            return Self::Cpu(time);
        }
        Self::Wall(Instant::now())
    }

    /// Nanoseconds of work since the start (on the thread that started it).
    fn nanoseconds(&self) -> u64 {
        let elapsed = match self {
            #[cfg(not(target_arch = "wasm32"))]
            Self::Cpu(time) => time.try_elapsed().unwrap_or_default(),
            Self::Wall(start) => start.elapsed(),
        };
        u64::try_from(elapsed.as_nanos()).unwrap_or(u64::MAX)
    }
}

/// How many ray samples of a row are taken into the rest frames together
/// ([`Tracer::rest_directions`]).
const RAY_BATCH: usize = 64;

/// The viewing directions (in S, unnormalised) through the points of a `width` × `height`
/// image of a scene, the observer's basis and field of view computed once.
struct ImageRays {
    /// The observer's rays for the image's aspect.
    rays: ViewRays,
    /// The image's size in pixels.
    width: f64,
    height: f64,
}

impl ImageRays {
    /// The rays of a `width` × `height` image of `scene`.
    fn new(scene: &Scene, width: u32, height: u32) -> Self {
        let (width, height) = (f64::from(width), f64::from(height));
        Self {
            rays: scene.observer.view_rays(width / height),
            width,
            height,
        }
    }

    /// The ray through the point (`x`, `y`), in pixels from the top-left corner (pixel centres
    /// at +0.5), in the observer's projection: its eye's offset from the observer (zero but
    /// for stereo) and its direction; `None` where the image sees nothing (outside a fisheye's
    /// circle).
    fn ray(&self, x: f64, y: f64) -> Option<(DVec3, DVec3)> {
        self.rays.ray(self.ndc(x, y))
    }

    /// The direction through the point `step` (pixels, y down) beyond (`x`, `y`), from the same
    /// eye ([`ViewRays::neighbour`]); `None` where the image sees nothing there.
    fn neighbour(&self, x: f64, y: f64, (dx, dy): (f64, f64)) -> Option<DVec3> {
        if !self.rays.is_stereo() {
            return self.rays.direction(self.ndc(x + dx, y + dy));
        }
        let step = DVec2::new(2.0 * dx / self.width, -2.0 * dy / self.height);
        self.rays.neighbour(self.ndc(x, y), step)
    }

    /// The normalised device coordinates of the point (`x`, `y`) in pixels.
    fn ndc(&self, x: f64, y: f64) -> DVec2 {
        pixel_ndc((self.width, self.height), DVec2::new(x, y))
    }
}

/// The normalised device coordinates (x right, y up, both in [−1, 1]) of the point `point` of a
/// `width` × `height` picture, in pixels from its top-left corner: where the tracer's rays pass.
#[must_use]
pub fn pixel_ndc((width, height): (f64, f64), point: DVec2) -> DVec2 {
    DVec2::new(2.0 * point.x / width - 1.0, 1.0 - 2.0 * point.y / height)
}

/// Sub-pixel sample positions in [0, 1)²: the pixel centre first, then the R2 low-discrepancy
/// sequence (Roberts 2018), which is deterministic and well spread for any count.
#[must_use]
pub fn sample_offsets(count: u32) -> Vec<DVec2> {
    // 1/φ₂ and 1/φ₂² with φ₂ the plastic number.
    const A: DVec2 = DVec2::new(0.754_877_666_246_692_8, 0.569_840_290_998_053_2);
    (0..count)
        .map(|k| (DVec2::splat(0.5) + f64::from(k) * A).fract())
        .collect()
}

#[cfg(test)]
mod tests {
    use srt_scene::Part;

    use super::*;
    use crate::intersect::intersect_triangle;

    /// The probe's ray is the render's: every pixel's hit is the object the render covers it
    /// with (its first sample is the pixel centre), and pixels outside the image hit nothing.
    #[test]
    fn a_pixel_hits_what_the_render_shows_there() {
        let (scene, _) = srt_scene::builtin::find_builtin("fig7")
            .unwrap()
            .build()
            .unwrap();
        let tracer = Tracer::new(&scene);
        let (width, height) = (24, 16);
        let image = tracer.render(
            RenderSettings {
                width,
                height,
                samples: 1,
            },
            &|_| {},
        );
        let mut hits = 0;
        for y in 0..height {
            for x in 0..width {
                let hit = tracer.hit_at_pixel(width, height, x, y);
                let covered = image.coverage[(y * width + x) as usize];
                assert_eq!(
                    hit.map_or(0, |h| h.object as u32 + 1),
                    covered,
                    "({x}, {y})"
                );
                hits += u32::from(hit.is_some());
            }
        }
        assert!(hits > 0 && hits < width * height, "{hits} pixels hit");
        // Tracing alone covers the picture as the render does, with any sampling.
        for samples in [1, 3] {
            let settings = RenderSettings {
                width,
                height,
                samples,
            };
            let rendered = tracer.render(settings, &|_| {}).coverage;
            assert_eq!(tracer.coverage(settings), rendered, "{samples} samples");
        }
        assert!(tracer.hit_at_pixel(width, height, width, 0).is_none());
        assert!(tracer.hit_at_pixel(0, 0, 0, 0).is_none());
    }

    /// The probe's rows are distinct, in order, inside the image, and as many as asked for
    /// (all of them when more are asked for than there are), one in each equal band.
    #[test]
    fn spread_rows_take_one_row_of_each_band() {
        for height in [1, 2, 7, 24, 720, 1081] {
            for count in [1, 3, 16, 30, 2000] {
                let rows = spread_rows(height, count);
                assert_eq!(rows.len() as u32, count.min(height), "{height} {count}");
                assert!(rows.windows(2).all(|w| w[0] < w[1]), "{rows:?}");
                for (band, &row) in rows.iter().enumerate() {
                    let band = band as u64;
                    let bands = rows.len() as u64;
                    let (top, bottom) = (band * u64::from(height), (band + 1) * u64::from(height));
                    assert!(
                        (top..bottom).contains(&(u64::from(row) * bands)),
                        "row {row} is not in band {band} of {bands} ({height} rows)"
                    );
                }
            }
        }
    }

    /// The BVHs, the box pre-test and the pruning find what a search of every triangle of every
    /// part of every object finds: the teaser, whose first object (the spider) is given the
    /// other objects' parts as parts of its own, seen along a grid of directions.
    #[test]
    fn the_object_bvh_finds_the_closest_triangle_of_any_part() {
        let (mut scene, _) = srt_scene::builtin::find_builtin("teaser")
            .unwrap()
            .build()
            .unwrap();
        let others: Vec<Part> = (scene.objects[1..].iter())
            .flat_map(|o| o.parts.clone())
            .collect();
        scene.objects[0].parts.extend(others);
        assert!(scene.objects[0].parts.len() >= 3 && scene.objects.len() >= 3);
        assert_trace_is_a_search_of_every_triangle(&scene);
    }

    /// The same for the flythrough: 45 objects sharing one velocity relative to a moving
    /// observer, many behind each other.
    #[test]
    fn objects_behind_each_other_are_pruned_exactly() {
        let (scene, _) = srt_scene::builtin::find_builtin("flythrough")
            .unwrap()
            .build()
            .unwrap();
        assert!(scene.objects.len() > 40);
        assert_trace_is_a_search_of_every_triangle(&scene);
    }

    /// Objects holding the same triangles (one model placed twice by its frame's offset, and
    /// once more moving) share one BVH, an object with other triangles has its own, and the
    /// shared BVH finds what a search of every triangle finds for each of them.
    #[test]
    fn instances_of_one_model_share_a_bvh_and_trace_exactly() {
        let (mut scene, _) = srt_scene::builtin::find_builtin("teaser")
            .unwrap()
            .build()
            .unwrap();
        let mut copy = scene.objects[0].clone();
        copy.frame =
            srt_physics::Frame::new(scene.objects[0].frame.beta(), DVec3::new(0.5, 2.0, -0.3))
                .unwrap();
        let mut moving = scene.objects[0].clone();
        moving.frame = srt_physics::Frame::new(DVec3::new(0.0, 0.3, 0.0), DVec3::ZERO).unwrap();
        scene.objects.extend([copy, moving]);
        let tracer = Tracer::new(&scene);
        let bvh = |index: usize| tracer.objects[index].bvh.as_ref().unwrap();
        let last = scene.objects.len() - 1;
        assert!(Arc::ptr_eq(bvh(0), bvh(last - 1)) && Arc::ptr_eq(bvh(0), bvh(last)));
        assert!(!Arc::ptr_eq(bvh(0), bvh(1)));
        assert_trace_is_a_search_of_every_triangle(&scene);
    }

    /// A tracer made after another of the same scene (the next frame) takes its BVHs, not
    /// new ones; a scene whose model is scaled (other triangles) gets its own, and traces
    /// exactly.
    #[test]
    fn the_next_tracer_of_a_scene_takes_the_last_ones_bvhs() {
        let (scene, _) = srt_scene::builtin::find_builtin("teaser")
            .unwrap()
            .build()
            .unwrap();
        let first = Tracer::new(&scene);
        let next = Tracer::new(&scene);
        for (a, b) in first.objects.iter().zip(&next.objects) {
            assert!(Arc::ptr_eq(
                a.bvh.as_ref().unwrap(),
                b.bvh.as_ref().unwrap()
            ));
        }
        let mut scaled = scene.clone();
        for part in &mut scaled.objects[0].parts {
            let mesh = part.mesh.clone();
            part.mesh = mesh
                .transformed(glam::DMat4::from_scale(DVec3::splat(1.25)))
                .unwrap();
        }
        let other = Tracer::new(&scaled);
        let (a, b) = (&first.objects[0].bvh, &other.objects[0].bvh);
        assert!(!Arc::ptr_eq(a.as_ref().unwrap(), b.as_ref().unwrap()));
        assert_trace_is_a_search_of_every_triangle(&scaled);
    }

    /// [`Tracer::trace`] of `scene` through a grid of pixel centres equals the closest hit of a
    /// search of every triangle (ties to the lowest object, part and triangle).
    fn assert_trace_is_a_search_of_every_triangle(scene: &Scene) {
        let tracer = Tracer::new(scene);
        let observer = scene.observer.event();
        let (width, height) = (48, 27);
        let mut hits = 0;
        for y in 0..height {
            for x in 0..width {
                let (_, direction) = ImageRays::new(scene, width, height)
                    .ray(f64::from(x) + 0.5, f64::from(y) + 0.5)
                    .expect("a pinhole sees through every pixel");
                // Every triangle of every part of every object, in its own rest frame.
                let brute = (scene.objects.iter().enumerate())
                    .filter_map(|(object, o)| {
                        let ray = o.frame.backward_ray(observer, direction);
                        let closest = (o.parts.iter().enumerate())
                            .flat_map(|(part, p)| {
                                (0..p.mesh.triangles().len()).filter_map(move |t| {
                                    let corners = p.mesh.triangle_positions(t);
                                    intersect_triangle(ray.origin, ray.direction, corners)
                                        .map(|hit| (hit.distance, part, t))
                                })
                            })
                            .min_by(|a, b| a.partial_cmp(b).unwrap())?;
                        let apparent = o.frame.apparent_distance(&ray, closest.0);
                        Some((apparent, object, closest.1, closest.2))
                    })
                    .min_by(|a, b| a.partial_cmp(b).unwrap());
                let traced = tracer
                    .trace(direction)
                    .map(|h| (h.apparent_distance, h.object, h.part, h.triangle));
                assert_eq!(traced, brute, "pixel ({x}, {y})");
                hits += usize::from(traced.is_some());
            }
        }
        assert!(hits > 100, "only {hits} pixels hit something");
    }
}
