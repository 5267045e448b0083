//! What the page's JavaScript calls (wasm32 only, through wasm-bindgen): [`GpuPage`] draws on a
//! canvas with WebGPU — srt-gpu's passes, the same as on the desktop, shown by its display pass —
//! and [`CpuPage`] renders the exact CPU picture to bytes (in a Web Worker, where WebGPU is
//! missing). Both hold a [`Session`] set from the page's address ([`crate::query`]).

use std::cell::RefCell;
use std::rc::Rc;

use srt_gpu::display::DisplayPass;
use srt_gpu::exact_path::{DrawnBy, PaneTimes};
use srt_gpu::{FootprintShape, GpuContext, GpuRenderer, Method};
use srt_scene::{UploadKey, View};
use wasm_bindgen::prelude::*;
use web_time::Instant;

use crate::query::{PageQuery, parse_query};
use crate::session::{Session, SessionError, scene_names as builtin_names};

/// Installs the panic hook that sends Rust panics to the browser's console.
#[wasm_bindgen(start)]
pub fn start() {
    console_error_panic_hook::set_once();
}

/// The names of the built-in scenes, in `srt scenes` order.
#[wasm_bindgen]
#[must_use]
pub fn scene_names() -> Vec<String> {
    builtin_names().into_iter().map(str::to_owned).collect()
}

/// The page settings of the address `query` as JSON (`scene`, `width`, `height`, `embed`,
/// `backend`, `method`, `split`): what the page's script needs before it picks a renderer.
///
/// # Errors
/// The address's first unknown key or unreadable value, named.
#[wasm_bindgen]
pub fn page_settings(query: &str) -> Result<String, JsError> {
    let page = parse_query(query).map_err(js_error)?;
    let (width, height) = page.size.unzip();
    Ok(serde_json::json!({
        "scene": page.scene,
        "width": width,
        "height": height,
        "embed": page.embed,
        "backend": format!("{:?}", page.backend).to_lowercase(),
        "method": page.method.name(),
        "split": page.split,
    })
    .to_string())
}

fn js_error(error: impl std::fmt::Display) -> JsError {
    JsError::new(&error.to_string())
}

/// Sets `session` from the address `query` and returns the settings.
fn apply_query(session: &mut Session, query: &str) -> Result<PageQuery, JsError> {
    let page = parse_query(query).map_err(js_error)?;
    if let Some(scene) = &page.scene {
        session.set_builtin(scene).map_err(js_error)?;
    }
    session.set_overrides(page.overrides.clone());
    Ok(page)
}

/// The scene's own values as JSON (`name`, `ct`, `beta`, `observer_moves`, `effects`,
/// `colour`, `warnings`).
fn info_json(session: &Session) -> Result<String, JsError> {
    let info = session.info().map_err(js_error)?;
    Ok(serde_json::json!({
        "name": info.name,
        "time": info.time,
        "beta": info.beta.to_array(),
        "observer_moves": info.observer_moves,
        "effects": info.effects,
        "colour": info.colour,
        "warnings": info.warnings,
    })
    .to_string())
}

/// The exact CPU renderer of a page (run it in a Web Worker: a frame takes a while).
#[wasm_bindgen]
pub struct CpuPage {
    session: Session,
}

#[wasm_bindgen]
impl CpuPage {
    /// A page showing the teaser.
    ///
    /// # Errors
    /// Never in practice (the teaser is built in).
    #[wasm_bindgen(constructor)]
    pub fn new() -> Result<Self, JsError> {
        Ok(Self {
            session: Session::new(DEFAULT_SCENE).map_err(js_error)?,
        })
    }

    /// Takes the scene and values of the address `query` (what it leaves out stays).
    ///
    /// # Errors
    /// An unknown key or scene, an unreadable value.
    pub fn set_query(&mut self, query: &str) -> Result<(), JsError> {
        apply_query(&mut self.session, query).map(drop)
    }

    /// Shows the model file `name` made of `bytes`; returns its warnings, one per line.
    ///
    /// # Errors
    /// The file and the reason, as `srt render MODEL` gives them.
    pub fn load_model(&mut self, name: &str, bytes: Vec<u8>) -> Result<String, JsError> {
        load_model(&mut self.session, name, bytes)
    }

    /// The scene's own values as JSON.
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn info(&self) -> Result<String, JsError> {
        info_json(&self.session)
    }

    /// The exact picture, RGBA bytes, rows from the top.
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn render(&mut self, width: u32, height: u32) -> Result<Vec<u8>, JsError> {
        self.session.render_cpu(width, height).map_err(js_error)
    }

    /// The seconds an exact picture at `width`×`height` is estimated to take here: the tracer's
    /// build and the frame measured on a few rows (`srt_trace::measure_picture`).
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn measure(&mut self, width: u32, height: u32) -> Result<f64, JsError> {
        self.session.measure_cpu(width, height).map_err(js_error)
    }
}

/// The scene a page opens with.
const DEFAULT_SCENE: &str = "teaser";

fn load_model(session: &mut Session, name: &str, bytes: Vec<u8>) -> Result<String, JsError> {
    session
        .load_model(name, bytes)
        .map(|warnings| warnings.join("\n"))
        .map_err(|error: SessionError| js_error(error))
}

/// A renderer of one method with the key of the upload it holds.
struct Uploaded {
    key: UploadKey,
    method: Method,
    renderer: GpuRenderer,
}

/// A canvas drawn with WebGPU.
#[wasm_bindgen]
pub struct GpuPage {
    session: Session,
    context: GpuContext,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    display: DisplayPass,
    method: Method,
    split: bool,
    /// The exact (or the chosen) method's renderer, and the polygon method's in split view.
    renderers: Vec<Uploaded>,
    /// Both paths' frame times for the picture [`GpuPage::weighs`] weighs, and what they were
    /// timed on (upload version, size, method): a new picture starts them again.
    times: (PaneTimes, Option<(u64, u32, u32, Method)>),
    /// Whether the last [`GpuPage::draw`] made a renderer (the scene uploaded, its pipelines
    /// compiled): that frame's time is not a frame's of the picture and is not weighed.
    uploaded: bool,
}

#[wasm_bindgen]
impl GpuPage {
    /// Opens WebGPU on `canvas` (sized by the caller) and shows the teaser.
    ///
    /// # Errors
    /// No WebGPU adapter or device, or a canvas WebGPU cannot draw on.
    pub async fn create(canvas: web_sys::HtmlCanvasElement) -> Result<Self, JsError> {
        let (width, height) = (canvas.width().max(1), canvas.height().max(1));
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::BROWSER_WEBGPU,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Canvas(canvas))
            .map_err(|e| js_error(format!("WebGPU cannot draw on the canvas: {e}")))?;
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: Some(&surface),
                ..Default::default()
            })
            .await
            .map_err(|e| js_error(format!("this browser offers no WebGPU adapter: {e}")))?;
        let context = GpuContext::from_adapter(&adapter).await.map_err(js_error)?;
        let capabilities = surface.get_capabilities(&adapter);
        let format = capabilities
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .ok_or_else(|| js_error("the canvas offers no 8-bit colour format"))?;
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width,
            height,
            present_mode: wgpu::PresentMode::Fifo,
            desired_maximum_frame_latency: 1,
            alpha_mode: wgpu::CompositeAlphaMode::Opaque,
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Srgb,
        };
        surface.configure(&context.device, &config);
        let display = DisplayPass::new(&context.device, format);
        Ok(Self {
            session: Session::new(DEFAULT_SCENE).map_err(js_error)?,
            context,
            surface,
            config,
            display,
            method: Method::Auto,
            split: false,
            renderers: Vec::new(),
            times: (PaneTimes::default(), None),
            uploaded: false,
        })
    }

    /// The adapter, in words (browsers may keep its name to themselves).
    #[must_use]
    pub fn adapter(&self) -> String {
        let info = &self.context.adapter_info;
        let kind = match info.device_type {
            wgpu::DeviceType::Cpu => "a software adapter",
            wgpu::DeviceType::IntegratedGpu => "an integrated GPU",
            wgpu::DeviceType::DiscreteGpu => "a discrete GPU",
            wgpu::DeviceType::VirtualGpu => "a virtual GPU",
            wgpu::DeviceType::Other => "an adapter",
        };
        if info.name.is_empty() {
            kind.to_owned()
        } else {
            format!("{} ({kind})", info.name)
        }
    }

    /// Takes the scene, method, split view and values of the address `query`.
    ///
    /// # Errors
    /// An unknown key or scene, an unreadable value.
    pub fn set_query(&mut self, query: &str) -> Result<(), JsError> {
        let page = apply_query(&mut self.session, query)?;
        self.method = page.method;
        self.split = page.split;
        Ok(())
    }

    /// Shows the model file `name` made of `bytes`; returns its warnings, one per line.
    ///
    /// # Errors
    /// The file and the reason, as `srt render MODEL` gives them.
    pub fn load_model(&mut self, name: &str, bytes: Vec<u8>) -> Result<String, JsError> {
        load_model(&mut self.session, name, bytes)
    }

    /// The scene's own values as JSON.
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn info(&self) -> Result<String, JsError> {
        info_json(&self.session)
    }

    /// Draws at `width`×`height` pixels from now on (the canvas's own size).
    pub fn resize(&mut self, width: u32, height: u32) {
        let (width, height) = (width.max(1), height.max(1));
        if (width, height) != (self.config.width, self.config.height) {
            self.config.width = width;
            self.config.height = height;
            self.surface.configure(&self.context.device, &self.config);
        }
    }

    /// Draws the scene on the canvas. Returns why the GPU cannot draw this scene, if it cannot
    /// (then the page asks the CPU), or `undefined` once the frame is submitted.
    ///
    /// # Errors
    /// A scene that does not build, a value it refuses, or a WebGPU failure.
    pub fn draw(&mut self) -> Result<Option<String>, JsError> {
        let (width, height) = (self.config.width, self.config.height);
        let mut methods = vec![self.method];
        if self.split {
            methods.push(Method::Polygon);
        }
        // Built first (if needed), so that the version read next is the scene's.
        self.session.scene().map_err(js_error)?;
        let version = self.session.upload_version();
        let scene = self.session.scene().map_err(js_error)?;
        if let Some(reason) = methods.iter().find_map(|m| m.cannot_draw(scene)) {
            return Ok(Some(reason));
        }
        let key = UploadKey::new(View::Seen, scene, version);
        let context = &self.context;
        self.renderers.truncate(methods.len());
        self.uploaded = false;
        for (index, &method) in methods.iter().enumerate() {
            match self.renderers.get_mut(index) {
                Some(uploaded) if !uploaded.key.needs_upload(&key) => {
                    uploaded.method = method;
                    uploaded
                        .renderer
                        .resize(context, width, height)
                        .map_err(js_error)?;
                }
                _ => {
                    self.uploaded = true;
                    let renderer =
                        GpuRenderer::new(context, scene, width, height).map_err(js_error)?;
                    let uploaded = Uploaded {
                        key: key.clone(),
                        method,
                        renderer,
                    };
                    if index < self.renderers.len() {
                        self.renderers[index] = uploaded;
                    } else {
                        self.renderers.push(uploaded);
                    }
                }
            }
            let uploaded = &self.renderers[index];
            let mut encoder =
                context
                    .device
                    .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                        label: Some("srt-web frame"),
                    });
            uploaded
                .renderer
                .encode(context, &mut encoder, scene, method, FootprintShape::Hull)
                .map_err(js_error)?;
            context.queue.submit([encoder.finish()]);
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            other => {
                // Configured again for the next frame (the canvas changed or was lost).
                self.surface.configure(&context.device, &self.config);
                return Err(js_error(format!(
                    "the canvas gave no texture to draw into ({})",
                    surface_problem(&other)
                )));
            }
        };
        let target = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = context
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("srt-web display"),
            });
        let half = width / 2;
        for (index, uploaded) in self.renderers.iter().enumerate() {
            let columns = self
                .split
                .then(|| if index == 0 { 0..half } else { half..width });
            self.display.encode(
                &context.device,
                &mut encoder,
                uploaded.renderer.color_texture(),
                &target,
                columns,
                index == 0,
            );
        }
        context.queue.submit([encoder.finish()]);
        context.queue.present(frame);
        context.take_errors().map_err(js_error)?;
        Ok(None)
    }

    /// Whether the page weighs who draws its picture (under `backend=auto`): the adapter is a
    /// software one (the browser's fallback adapter, such as SwiftShader) and the picture is one
    /// exact method's (not the split view, not an approximate method, which only WebGPU draws).
    /// Both paths then draw at the canvas's size, and the faster draws ([`PaneTimes`], the rule
    /// of the viewer's panes).
    #[must_use]
    pub fn weighs(&self) -> bool {
        self.context.software_api().is_some() && !self.split && self.method.is_exact()
    }

    /// Whether the CPU's cost is to be measured (`CpuPage::measure`) before the next frame.
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn wants_cpu_measure(&mut self) -> Result<bool, JsError> {
        Ok(self.picture_times()?.wants_cpu_measure(Instant::now()))
    }

    /// The CPU's measured cost of the picture, in seconds, by a measure that took `took`
    /// seconds (the worker's reply awaited).
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn measured_cpu(&mut self, seconds: f64, took: f64) -> Result<(), JsError> {
        self.picture_times()?
            .measured_cpu(seconds, took, Instant::now());
        Ok(())
    }

    /// Who draws the next frame: `"webgpu"` or `"cpu"`.
    ///
    /// # Errors
    /// A scene that does not build, or a value it refuses.
    pub fn next_path(&mut self) -> Result<String, JsError> {
        Ok(path_name(self.picture_times()?.next(Instant::now())).to_owned())
    }

    /// A frame drawn by `path` (`"webgpu"` or `"cpu"`) took `seconds`, to its end. A WebGPU
    /// frame that made its renderer is not counted: the upload and the pipelines' compilation
    /// (seconds on a software adapter) are paid once, not by every frame that follows, as the
    /// viewer's renderers are made before its frames are timed.
    ///
    /// # Errors
    /// Another path's name, a scene that does not build, or a value it refuses.
    pub fn drawn(&mut self, path: &str, seconds: f64) -> Result<(), JsError> {
        let by = match path {
            "webgpu" if self.uploaded => return Ok(()),
            "webgpu" => DrawnBy::Gpu,
            "cpu" => DrawnBy::Cpu,
            other => return Err(js_error(format!("no path named {other:?}"))),
        };
        self.picture_times()?.drawn(by, seconds, Instant::now());
        Ok(())
    }

    /// The weighed picture's times as JSON: `drawn_by` (the last frame's path), `webgpu_ms`
    /// and `cpu_ms` (each path's running time, `null` where not yet timed).
    #[must_use]
    pub fn path_times(&self) -> String {
        let (last, gpu, cpu) = self.times.0.report();
        let ms = |seconds: Option<f64>| seconds.map(|s| s * 1e3);
        serde_json::json!({
            "drawn_by": last.map(path_name),
            "webgpu_ms": ms(gpu),
            "cpu_ms": ms(cpu),
        })
        .to_string()
    }

    /// The times of the picture the page shows now, started again when its meshes or sky, its
    /// size or its method changed.
    fn picture_times(&mut self) -> Result<&mut PaneTimes, JsError> {
        self.session.scene().map_err(js_error)?;
        let key = (
            self.session.upload_version(),
            self.config.width,
            self.config.height,
            self.method,
        );
        if self.times.1 != Some(key) {
            self.times = (PaneTimes::default(), Some(key));
        }
        Ok(&mut self.times.0)
    }

    /// The WebGPU errors reported since the last call (validation errors arrive after the
    /// frame that caused them), or `undefined`.
    #[must_use]
    pub fn errors(&self) -> Option<String> {
        self.context
            .take_errors()
            .err()
            .map(|error| error.to_string())
    }

    /// A promise that resolves once the GPU has finished the frames drawn so far (a pixel of
    /// the last picture is read back: the browser resolves the read after the work before it).
    #[must_use]
    pub fn finished(&self) -> js_sys::Promise {
        let Some(uploaded) = self.renderers.first() else {
            return js_sys::Promise::resolve(&JsValue::UNDEFINED);
        };
        let device = &self.context.device;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("srt-web frame done"),
            size: 16,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("srt-web frame done"),
        });
        encoder.copy_texture_to_buffer(
            uploaded.renderer.color_texture().as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout::default(),
            },
            wgpu::Extent3d::default(),
        );
        self.context.queue.submit([encoder.finish()]);
        // The buffer lives until its mapping settles (the callback holds it).
        let kept = Rc::new(buffer);
        js_sys::Promise::new(&mut move |resolve, reject| {
            let kept = Rc::clone(&kept);
            let settle = RefCell::new(Some((resolve, reject)));
            kept.clone()
                .map_async(wgpu::MapMode::Read, .., move |result| {
                    kept.unmap();
                    if let Some((resolve, reject)) = settle.borrow_mut().take() {
                        let _ = match result {
                            Ok(()) => resolve.call0(&JsValue::UNDEFINED),
                            Err(error) => reject
                                .call1(&JsValue::UNDEFINED, &JsValue::from_str(&error.to_string())),
                        };
                    }
                });
        })
    }
}

/// A path's name on the page.
const fn path_name(by: DrawnBy) -> &'static str {
    match by {
        DrawnBy::Gpu => "webgpu",
        DrawnBy::Cpu => "cpu",
    }
}

/// Why the canvas gave no texture, in words.
fn surface_problem(status: &wgpu::CurrentSurfaceTexture) -> &'static str {
    match status {
        wgpu::CurrentSurfaceTexture::Timeout => "timeout",
        wgpu::CurrentSurfaceTexture::Occluded => "occluded",
        wgpu::CurrentSurfaceTexture::Outdated => "outdated",
        wgpu::CurrentSurfaceTexture::Lost => "lost",
        _ => "validation",
    }
}
