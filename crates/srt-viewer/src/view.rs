//! Drawing the scene into textures the UI shows: the srt-gpu passes (the same ones `srt render`
//! uses) render into their `Rgba32Float` target, and srt-gpu's display pass copies that into an
//! `Rgba8Unorm` texture registered with egui. The values are already display-encoded (sRGB), and
//! egui expects exactly that of a non-sRGB texture.
//!
//! The screen is a row of [`Pane`]s: a view of the scene (seen, measured or Newtonian, made by
//! [`View::apply`] as `srt render --view` makes it) drawn with a method (local ray tracing or
//! polygons). Each pane is rendered into its own display texture, by a renderer holding the
//! meshes of its view — the seen and Newtonian pictures share the scene's meshes, the measured
//! one has contracted meshes of its own ([`UploadKey`]); a queue submission between panes keeps
//! their uniforms apart.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use eframe::egui;
use eframe::egui_wgpu;
use srt_gpu::display::DisplayPass;
use srt_gpu::{FootprintShape, GpuContext, GpuError, GpuRenderer, Method};
use srt_scene::{Scene, UploadKey, View};
use srt_trace::{MeasuredPicture, Output, RenderSettings, Tracer, measure_picture};

use crate::exact_path::{DrawnBy, ExactPath, PaneTimes};

/// Format of the textures egui shows.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Which method(s) the view shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ViewMethod {
    /// Exact: each object by whichever of LRT and the ray tracer is faster for it.
    #[default]
    Exact,
    /// Local ray tracing only (the paper's method).
    Lrt,
    /// The GPU ray tracer only (exact like LRT; a BVH per batch of parts).
    Rt,
    /// The polygon baseline only (§3.2).
    Polygon,
    /// The image-based method only (cube maps, the paper's Table 1 "IB").
    ImageBased,
    /// Both, side by side: the exact picture on the left, polygons on the right.
    Split,
}

impl ViewMethod {
    /// All choices, in the order the panel lists them.
    pub const ALL: [Self; 6] = [
        Self::Exact,
        Self::Lrt,
        Self::Rt,
        Self::Polygon,
        Self::ImageBased,
        Self::Split,
    ];

    /// The methods rendered, left to right.
    #[must_use]
    pub const fn methods(self) -> &'static [Method] {
        match self {
            Self::Exact => &[Method::Auto],
            Self::Lrt => &[Method::Lrt],
            Self::Rt => &[Method::Rt],
            Self::Polygon => &[Method::Polygon],
            Self::ImageBased => &[Method::ImageBased],
            Self::Split => &[Method::Auto, Method::Polygon],
        }
    }

    /// The label in the panel.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::Exact => "Exact (fastest method per object)",
            Self::Lrt => "Local ray tracing",
            Self::Rt => "Ray tracing (BVH)",
            Self::Polygon => "Polygon",
            Self::ImageBased => "Image-based (cube maps)",
            Self::Split => "Split screen (both)",
        }
    }
}

/// One picture on the screen: a view of the scene drawn with a method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pane {
    /// Which picture of the scene ([`View::apply`]).
    pub view: View,
    /// How it is drawn.
    pub method: Method,
}

impl Pane {
    /// The panes shown, left to right: each of `views` (one, or two side by side) with each of
    /// `method`'s methods.
    #[must_use]
    pub fn row(views: &[View], method: ViewMethod) -> Vec<Self> {
        views
            .iter()
            .flat_map(|&view| {
                method
                    .methods()
                    .iter()
                    .map(move |&method| Self { view, method })
            })
            .collect()
    }

    /// The label drawn on the pane; `None` for today's single picture (seen, one method).
    #[must_use]
    pub fn label(panes: &[Self], index: usize) -> Option<String> {
        let pane = panes.get(index)?;
        let several_views = panes.iter().any(|p| p.view != pane.view);
        let several_methods = panes.iter().any(|p| p.method != pane.method);
        let view = (several_views || pane.view != View::Seen).then(|| view_label(pane.view));
        let method = several_methods.then_some(match pane.method {
            Method::Auto => "exact",
            Method::Lrt => "local ray tracing",
            Method::Rt => "ray tracing (BVH)",
            Method::Polygon => "polygon",
            Method::ImageBased => "image-based",
        });
        match (view, method) {
            (Some(view), Some(method)) => Some(format!("{view} · {method}")),
            (Some(view), None) => Some(view.to_owned()),
            (None, Some(method)) => Some(method.to_owned()),
            (None, None) => None,
        }
    }
}

/// The name of a view in the panel and on its pane.
#[must_use]
pub const fn view_label(view: View) -> &'static str {
    match view {
        View::Seen => "seen (what a camera records)",
        View::Measured => "measured (where everything is now, contracted)",
        View::Newtonian => "Newtonian (rest shapes where they are now)",
    }
}

/// One pane to render: the scene of its view, the meshes that scene has, and the method.
#[derive(Debug, Clone, Copy)]
pub struct PaneScene<'a> {
    /// The scene as the pane's view shows it.
    pub scene: &'a Scene,
    /// Which meshes it has.
    pub key: &'a UploadKey,
    /// How it is drawn.
    pub method: Method,
}

/// One texture egui shows.
struct Display {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    size: (u32, u32),
    /// Its egui id once registered; `registered` is false when the texture changed since.
    id: Option<egui::TextureId>,
    registered: bool,
}

impl Display {
    fn new(device: &wgpu::Device, size: (u32, u32), id: Option<egui::TextureId>) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("srt-viewer display"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DISPLAY_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Self {
            texture,
            view,
            size,
            id,
            registered: false,
        }
    }
}

/// The uploaded scenes and the textures the UI shows.
pub struct SceneView {
    display_pass: DisplayPass,
    /// One renderer per set of meshes the panes need, with the key of those meshes.
    renderers: Vec<(UploadKey, GpuRenderer)>,
    displays: Vec<Display>,
    /// egui ids of displays no longer shown (a pane fewer), reused before new ones are
    /// registered.
    spare_ids: Vec<egui::TextureId>,
    triangles: usize,
    /// Who draws the exact panes.
    exact_path: ExactPath,
    /// Whether the adapter is a software rasteriser, where [`ExactPath::Auto`] weighs the CPU.
    software: bool,
    /// Per pane, what its frame times were measured for (its size, meshes and method) and the
    /// times ([`crate::exact_path`]).
    times: Vec<(PaneKey, PaneTimes)>,
}

/// What a pane's frame times hold for: a pane of another size, meshes or method starts again.
#[derive(Debug, Clone, PartialEq)]
struct PaneKey {
    size: (u32, u32),
    key: UploadKey,
    method: Method,
}

impl SceneView {
    /// Creates the display pipeline; nothing is uploaded yet.
    #[must_use]
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            display_pass: DisplayPass::new(&ctx.device, DISPLAY_FORMAT),
            renderers: Vec::new(),
            displays: Vec::new(),
            spare_ids: Vec::new(),
            triangles: 0,
            exact_path: ExactPath::default(),
            software: ctx.software_api().is_some(),
            times: Vec::new(),
        }
    }

    /// Who draws the exact panes from the next frame on.
    pub fn set_exact_path(&mut self, path: ExactPath) {
        self.exact_path = path;
    }

    /// Who draws the exact panes.
    #[must_use]
    pub const fn exact_path(&self) -> ExactPath {
        self.exact_path
    }

    /// Where [`ExactPath::Auto`] weighs the CPU against a software adapter: which path drew the
    /// first exact pane's last frame, and both paths' running frame times in seconds where
    /// known; `None` where it does not weigh (a hardware GPU, or a path chosen in the panel).
    #[must_use]
    pub fn exact_report(&self) -> Option<(DrawnBy, Option<f64>, Option<f64>)> {
        (self.exact_path == ExactPath::Auto && self.software).then_some(())?;
        self.times.iter().find_map(|(key, times)| {
            let (last, gpu, cpu) = times.report();
            (key.method == Method::Auto).then_some((last?, gpu, cpu))
        })
    }

    /// Uploads `scene` (the seen view) unless the scene of structure `version` is already
    /// uploaded.
    ///
    /// # Errors
    /// [`GpuError`] when the upload fails (a model too large for the device…); the previously
    /// uploaded scenes are then dropped.
    pub fn upload(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        version: u64,
    ) -> Result<(), GpuError> {
        let key = UploadKey::new(View::Seen, scene, version);
        self.ensure(ctx, scene, &key).map(|_| ())
    }

    /// The index of the renderer holding `key`'s meshes, uploading `scene` (which has them) if
    /// there is none; renderers of older structure versions are dropped first.
    fn ensure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        key: &UploadKey,
    ) -> Result<usize, GpuError> {
        if let Some(index) = (self.renderers.iter()).position(|(k, _)| !k.needs_upload(key)) {
            return Ok(index);
        }
        let size = self.renderers.first().map_or((64, 64), |(_, r)| r.size());
        self.renderers
            .retain(|(k, _)| k.structure_version() == key.structure_version());
        if key.is_contracted() {
            // One set of contracted meshes at a time: the velocities changed.
            self.renderers.retain(|(k, _)| !k.is_contracted());
        }
        let renderer = GpuRenderer::new(ctx, scene, size.0, size.1).inspect_err(|_| {
            self.renderers.clear();
        })?;
        if !key.is_contracted() {
            self.triangles = scene.triangle_count();
        }
        self.renderers.push((key.clone(), renderer));
        Ok(self.renderers.len() - 1)
    }

    /// Triangles in the uploaded scene.
    #[must_use]
    pub const fn triangles(&self) -> usize {
        self.triangles
    }

    /// Renders `panes` side by side into display textures filling `size` pixels in all (each
    /// pane an equal share of the width), uploading the meshes a pane's view needs when no
    /// renderer holds them; with `egui_renderer`, (re-)registers the textures with egui.
    ///
    /// # Errors
    /// [`GpuError`] when an upload fails, a scene's structure differs from its key's, or wgpu
    /// reports an error.
    pub fn render(
        &mut self,
        ctx: &GpuContext,
        egui_renderer: Option<&mut egui_wgpu::Renderer>,
        panes: &[PaneScene<'_>],
        size: (u32, u32),
    ) -> Result<(), GpuError> {
        if panes.is_empty() {
            return Err(GpuError::NotReady("no view to render"));
        }
        let count = u32::try_from(panes.len()).unwrap_or(1);
        let limit = ctx.device.limits().max_texture_dimension_2d;
        let each = ((size.0 / count).clamp(1, limit), size.1.clamp(1, limit));
        // Renderers no pane needs any more are dropped (their meshes are stale or unused).
        self.renderers
            .retain(|(key, _)| panes.iter().any(|pane| !key.needs_upload(pane.key)));
        // Displays no longer needed keep their egui ids for later reuse.
        while self.displays.len() > panes.len() {
            if let Some(display) = self.displays.pop() {
                self.spare_ids.extend(display.id);
            }
        }
        for (index, pane) in panes.iter().enumerate() {
            match self.displays.get(index) {
                Some(display) if display.size == each => {}
                Some(display) => {
                    let id = display.id;
                    self.displays[index] = Display::new(&ctx.device, each, id);
                }
                None => {
                    let id = self.spare_ids.pop();
                    self.displays.push(Display::new(&ctx.device, each, id));
                }
            }
            let renderer_index = self.ensure(ctx, pane.scene, pane.key)?;
            self.draw_pane(ctx, index, pane, each, renderer_index)?;
        }
        self.times.truncate(panes.len());
        if let Some(egui_renderer) = egui_renderer {
            for display in &mut self.displays {
                match display.id {
                    Some(id) if !display.registered => egui_renderer
                        .update_egui_texture_from_wgpu_texture(
                            &ctx.device,
                            &display.view,
                            wgpu::FilterMode::Linear,
                            id,
                        ),
                    None => {
                        display.id = Some(egui_renderer.register_native_texture(
                            &ctx.device,
                            &display.view,
                            wgpu::FilterMode::Linear,
                        ));
                    }
                    Some(_) => {}
                }
                display.registered = true;
            }
        }
        ctx.take_errors()
    }

    /// Draws pane `index`, `pane` at `each` pixels, into its display: by the GPU renderer of
    /// index `renderer_index`, or by the CPU tracer where [`ExactPath`] says so (on a software
    /// adapter under [`ExactPath::Auto`], the faster of the two by the pane's [`PaneTimes`]).
    ///
    /// # Errors
    /// [`GpuError`] when the GPU's frame fails.
    fn draw_pane(
        &mut self,
        ctx: &GpuContext,
        index: usize,
        pane: &PaneScene<'_>,
        each: (u32, u32),
        renderer_index: usize,
    ) -> Result<(), GpuError> {
        let exact = pane.method == Method::Auto;
        let weighing = exact && self.exact_path == ExactPath::Auto && self.software;
        let forced_cpu = exact && self.exact_path == ExactPath::Cpu;
        let pane_key = PaneKey {
            size: each,
            key: pane.key.clone(),
            method: pane.method,
        };
        if self
            .times
            .get(index)
            .is_none_or(|(key, _)| *key != pane_key)
        {
            self.times.truncate(index);
            self.times.push((pane_key, PaneTimes::default()));
        }
        let times = &mut self.times[index].1;
        let settings = RenderSettings {
            width: each.0,
            height: each.1,
            samples: 1,
        };
        let now = Instant::now();
        let measured = (weighing && times.wants_cpu_measure(now)).then(|| {
            let measured = measure_picture(pane.scene, settings);
            let took = now.elapsed().as_secs_f64();
            times.measured_cpu(measured.seconds, took, Instant::now());
            measured
        });
        let by = if forced_cpu || (weighing && times.next(Instant::now()) == DrawnBy::Cpu) {
            DrawnBy::Cpu
        } else {
            DrawnBy::Gpu
        };
        // A CPU frame after a measure counts it: the frame took the measure's tracer and rows.
        let start = if by == DrawnBy::Cpu && measured.is_some() {
            now
        } else {
            Instant::now()
        };
        match by {
            DrawnBy::Cpu => {
                let display = &self.displays[index];
                draw_on_cpu(ctx, pane.scene, settings, measured, &display.texture);
            }
            DrawnBy::Gpu => {
                let renderer = &mut self.renderers[renderer_index].1;
                renderer.resize(ctx, each.0, each.1)?;
                let mut encoder =
                    ctx.device
                        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                            label: Some("srt-viewer frame"),
                        });
                renderer.encode(
                    ctx,
                    &mut encoder,
                    pane.scene,
                    pane.method,
                    FootprintShape::Hull,
                )?;
                self.display_pass.encode(
                    &ctx.device,
                    &mut encoder,
                    renderer.color_texture(),
                    &self.displays[index].view,
                    None,
                    true,
                );
                ctx.queue.submit([encoder.finish()]);
                if weighing {
                    // Timed to its end, as a CPU frame is.
                    ctx.wait()?;
                }
            }
        }
        if weighing {
            let times = &mut self.times[index].1;
            times.drawn(by, start.elapsed().as_secs_f64(), Instant::now());
        }
        Ok(())
    }

    /// The registered textures with their sizes in pixels, left to right.
    pub fn textures(&self) -> impl Iterator<Item = (egui::TextureId, [u32; 2])> + '_ {
        self.displays
            .iter()
            .filter_map(|d| d.id.map(|id| (id, [d.size.0, d.size.1])))
    }

    /// Reads the shown image(s) back, side by side, as 8-bit RGBA.
    ///
    /// # Errors
    /// [`GpuError`] when nothing was rendered yet or the readback fails.
    pub fn read_image(&self, ctx: &GpuContext) -> Result<image::RgbaImage, GpuError> {
        if self.displays.is_empty() {
            return Err(GpuError::NotReady("nothing has been rendered yet"));
        }
        let width: u32 = self.displays.iter().map(|d| d.size.0).sum();
        let height = self.displays.iter().map(|d| d.size.1).max().unwrap_or(1);
        let mut image = image::RgbaImage::new(width, height);
        let mut x0 = 0;
        for display in &self.displays {
            let w = display.size.0;
            let bytes = srt_gpu::read_texture(ctx, &display.texture)?;
            for (y, line) in bytes.chunks_exact(w as usize * 4).enumerate() {
                for (x, texel) in line.chunks_exact(4).enumerate() {
                    #[expect(
                        clippy::cast_possible_truncation,
                        reason = "texture sizes fit in u32"
                    )]
                    image.put_pixel(
                        x0 + x as u32,
                        y as u32,
                        image::Rgba([texel[0], texel[1], texel[2], texel[3]]),
                    );
                }
            }
            x0 += w;
        }
        ctx.take_errors()?;
        Ok(image)
    }
}

/// Draws `scene` at `settings` with srt's CPU tracer into the display `texture` (its 8-bit
/// display colours, as `srt render --backend cpu` writes them), taking the rows of `measured`
/// (a tracer of this scene and its measure of this picture) where given.
fn draw_on_cpu(
    ctx: &GpuContext,
    scene: &Scene,
    settings: RenderSettings,
    measured: Option<MeasuredPicture<'_>>,
    texture: &wgpu::Texture,
) {
    let (tracer, measure) = match measured {
        Some(MeasuredPicture {
            tracer, measure, ..
        }) => (tracer, Some(measure)),
        None => (Tracer::new(scene), None),
    };
    let never = AtomicBool::new(false);
    let image = tracer
        .render_band_reusing(
            settings,
            0..settings.height,
            Output::Display,
            &|_| {},
            &never,
            measure.as_ref(),
        )
        .unwrap_or_else(|| unreachable!("a render that is never stopped finishes"));
    let bytes: Vec<u8> = (image.to_rgb8().into_iter())
        .flat_map(|[r, g, b]| [r, g, b, u8::MAX])
        .collect();
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        &bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * settings.width),
            rows_per_image: Some(settings.height),
        },
        wgpu::Extent3d {
            width: settings.width,
            height: settings.height,
            depth_or_array_layers: 1,
        },
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panes_are_each_view_with_each_method() {
        let lrt = |view| Pane {
            view,
            method: Method::Lrt,
        };
        assert_eq!(
            Pane::row(&[View::Seen], ViewMethod::Lrt),
            vec![lrt(View::Seen)]
        );
        let split = Pane::row(&[View::Seen, View::Measured], ViewMethod::Lrt);
        assert_eq!(split, vec![lrt(View::Seen), lrt(View::Measured)]);
        assert_eq!(
            Pane::label(&Pane::row(&[View::Seen], ViewMethod::Lrt), 0),
            None
        );
        assert_eq!(
            Pane::label(&split, 1).as_deref(),
            Some(view_label(View::Measured))
        );
        let both = Pane::row(&[View::Newtonian], ViewMethod::Split);
        assert_eq!(both.len(), 2);
        assert_eq!(
            Pane::label(&both, 1),
            Some(format!("{} · polygon", view_label(View::Newtonian)))
        );
        assert_eq!(Pane::label(&both, 2), None);
    }
}
