//! `srt.render` and `srt.Renderer`: a scene rendered to numpy arrays, exactly as
//! `srt render … -o x.exr` writes it (the same loading, overrides, view and renderer: the `srt`
//! library's [`engine`](srt::engine)), with the GIL released and Ctrl-C honoured; a `Renderer`
//! keeps its engine for a loop of frames. And `srt.to_srgb8`.

use std::borrow::Cow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::Duration;

use glam::DVec3;
use numpy::ndarray::{Array2, Array3, ArrayD};
use numpy::{IntoPyArray as _, PyArray3, PyArrayDyn, PyReadonlyArrayDyn};
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use srt::empty::empty_picture_warning;
use srt::engine::{
    AOV_CHANNELS, Backend, Frame, KeptEngine, MAX_IMAGE_SIDE, MAX_SAMPLES, channel_f32,
    display_as_linear,
};
use srt::software::Job;
use srt_color::{quantize_8bit, srgb_encode};
use srt_gpu::Method;
use srt_scene::{Editor, OverrideNames, Overrides, SceneSource, Setting, UploadKey, View};
use srt_trace::{Output, RenderSettings};

use crate::errors;
use crate::scene::Scene;

/// How often the waiting Python thread looks for Ctrl-C while a render runs.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// The scene argument of `srt.render`: a name or path as `srt render` takes it, a path object,
/// or a Scene.
#[derive(FromPyObject)]
pub enum SceneArgument<'py> {
    /// A `srt.Scene`.
    Scene(Bound<'py, Scene>),
    /// A built-in scene's name, a scene file or a model file.
    Name(String),
    /// A scene file or model file as a path object (never a built-in scene).
    Path(std::path::PathBuf),
}

/// What one render produced.
struct Rendered {
    /// Radiance, row-major from the top.
    radiance: Vec<DVec3>,
    /// Display colours (sRGB-encoded, [0, 1]) when asked for.
    display: Option<Vec<DVec3>>,
    /// What each pixel sees of time, when asked for.
    seen: Option<Vec<[f32; 5]>>,
    /// Warnings met loading the scene, and the engine's note.
    warnings: Vec<String>,
}

/// Why a render stopped without an image.
enum Failure {
    /// A Python exception to raise.
    Raise(PyErr),
    /// Ctrl-C: the render was stopped.
    Stopped,
}

impl From<PyErr> for Failure {
    fn from(error: PyErr) -> Self {
        Self::Raise(error)
    }
}

/// Renders `scene` to a float32 array (height, width, 3) of linear radiance (the EXR's R, G, B);
/// with `aov=True`, a dict of layers: "radiance", "display" (the displayed image as linear
/// light, the EXR's display.R, display.G, display.B) and the (height, width) channels
/// `srt render --aov` writes (emission_ct, proper_time, distance, doppler, object). One frame of
/// a [`Renderer`] made for it: a loop of frames keeps one `srt.Renderer` instead.
#[pyfunction]
#[pyo3(signature = (
    scene, *, width=1280, height=720, time=None, beta=None, observer_beta=None, effects=None,
    colour=None, exposure=None, projection=None, set=None, samples=1, backend="auto",
    method="auto", view="seen", aov=false
))]
#[expect(
    clippy::too_many_arguments,
    reason = "Python keyword arguments, as the issue names them"
)]
pub fn render<'py>(
    py: Python<'py>,
    scene: SceneArgument<'py>,
    width: u32,
    height: u32,
    time: Option<f64>,
    beta: Option<[f64; 3]>,
    observer_beta: Option<[f64; 3]>,
    effects: Option<&str>,
    colour: Option<&str>,
    exposure: Option<f64>,
    projection: Option<&str>,
    set: Option<&Bound<'py, PyDict>>,
    samples: u32,
    backend: &str,
    method: &str,
    view: &str,
    aov: bool,
) -> PyResult<Bound<'py, PyAny>> {
    Renderer::new(width, height, samples, backend, method)?.render(
        py,
        scene,
        time,
        beta,
        observer_beta,
        effects,
        colour,
        exposure,
        projection,
        set,
        view,
        aov,
    )
}

/// A renderer kept for a loop of frames: the GPU's device is made once and a scene uploaded
/// again only when its structure or the GPU's ability to draw it changes (the `srt` library's
/// [`KeptEngine`]), as the viewer and the web page keep theirs. Each frame is exactly what
/// `srt.render` with the same arguments gives.
#[pyclass(module = "srt")]
pub struct Renderer {
    /// Size and samples per pixel of every frame.
    settings: RenderSettings,
    /// The engine and the last frame's scene, kept between frames (locked by the frame being
    /// drawn).
    engine: Mutex<Kept>,
}

/// What a [`Renderer`] keeps between frames.
struct Kept {
    /// The engine, holding the last frame's upload.
    engine: KeptEngine,
    /// The last frame's scene: each frame's scene replaces it ([`Editor::replace_with`]),
    /// whose structure version tells the engine whether to upload again ([`UploadKey`]).
    editor: Option<Editor>,
}

#[pymethods]
impl Renderer {
    /// A renderer of `width` × `height` frames at `samples` per pixel, drawn by `backend` with
    /// `method` (as `srt.render` takes them).
    #[new]
    #[pyo3(signature = (*, width=1280, height=720, samples=1, backend="auto", method="auto"))]
    fn new(width: u32, height: u32, samples: u32, backend: &str, method: &str) -> PyResult<Self> {
        let settings = settings(width, height, samples)?;
        let backend = errors::chosen(backend)?;
        let method: Method = errors::chosen(method)?;
        if backend == Backend::Cpu && !method.is_exact() {
            return Err(errors::value(format!(
                "the {} method runs on the GPU only; use backend=\"gpu\" or \"auto\"",
                method.name()
            )));
        }
        Ok(Self {
            settings,
            engine: Mutex::new(Kept {
                engine: KeptEngine::new(backend, method),
                editor: None,
            }),
        })
    }

    /// One frame of `scene`, with the same arguments and result as `srt.render`'s.
    #[pyo3(signature = (
        scene, *, time=None, beta=None, observer_beta=None, effects=None, colour=None,
        exposure=None, projection=None, set=None, view="seen", aov=false
    ))]
    #[expect(
        clippy::too_many_arguments,
        reason = "Python keyword arguments, as srt.render takes them"
    )]
    fn render<'py>(
        &self,
        py: Python<'py>,
        scene: SceneArgument<'py>,
        time: Option<f64>,
        beta: Option<[f64; 3]>,
        observer_beta: Option<[f64; 3]>,
        effects: Option<&str>,
        colour: Option<&str>,
        exposure: Option<f64>,
        projection: Option<&str>,
        set: Option<&Bound<'py, PyDict>>,
        view: &str,
        aov: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let overrides = Overrides {
            effects: effects.map(errors::chosen).transpose()?,
            colour: colour.map(errors::chosen).transpose()?,
            exposure,
            time,
            beta: beta.map(DVec3::from_array),
            observer_beta: observer_beta.map(DVec3::from_array),
            projection: projection
                .map(|text| text.parse().map_err(errors::value))
                .transpose()?,
            settings: set.map(scene_settings).transpose()?.unwrap_or_default(),
            names: OverrideNames::KEYS,
        };
        let (built, warnings) = match &scene {
            SceneArgument::Name(name) => SceneSource::resolve(name)
                .map_err(|e| errors::resolve(&e))
                .and_then(|source| load(py, &source, &overrides)),
            SceneArgument::Path(path) => {
                crate::scene::file_source(path).and_then(|source| load(py, &source, &overrides))
            }
            SceneArgument::Scene(scene) => Ok((scene.borrow().overridden(&overrides)?, Vec::new())),
        }?;
        let request = Request {
            settings: self.settings,
            view: errors::chosen(view)?,
            aov,
        };
        let rendered = match run_interruptible(py, |stop| {
            let mut engine = self.engine.lock().unwrap_or_else(PoisonError::into_inner);
            request.run(&mut engine, built, warnings, stop)
        }) {
            Ok(rendered) => rendered,
            Err(Failure::Raise(error)) => return Err(error),
            Err(Failure::Stopped) => {
                // check_signals raised KeyboardInterrupt and the render has stopped; raise it
                // again.
                return Err(py.check_signals().err().unwrap_or_else(|| {
                    pyo3::exceptions::PyKeyboardInterrupt::new_err("render stopped")
                }));
            }
        };
        rendered.into_python(py, self.settings)
    }

    /// How many GPU devices this renderer has opened (srt's count, where the device is
    /// opened): 1 after any number of GPU frames, 0 where no device was asked for.
    #[getter]
    fn devices_opened(&self, py: Python<'_>) -> u32 {
        self.read(py, KeptEngine::made).devices
    }

    /// How many times this renderer has uploaded a scene to the GPU (srt's count, where the
    /// upload is made): once, and again for each change of the scene's structure.
    #[getter]
    fn scene_uploads(&self, py: Python<'_>) -> u32 {
        self.read(py, KeptEngine::made).uploads
    }

    /// The GPU adapter the last frame was drawn on, as wgpu names it: a dict of "name",
    /// "backend" (as `WGPU_BACKEND` names it: "vulkan", "gl", …), "driver" and "driver_info";
    /// `None` before the first frame and when the CPU drew it.
    #[getter]
    fn adapter<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(info) = self.read(py, |engine| {
            engine.context().map(|context| context.adapter_info.clone())
        }) else {
            return Ok(None);
        };
        let adapter = PyDict::new(py);
        adapter.set_item("name", info.name)?;
        adapter.set_item("backend", info.backend.to_str())?;
        adapter.set_item("driver", info.driver)?;
        adapter.set_item("driver_info", info.driver_info)?;
        Ok(Some(adapter))
    }

    fn __repr__(&self) -> String {
        let RenderSettings {
            width,
            height,
            samples,
        } = self.settings;
        format!("Renderer(width={width}, height={height}, samples={samples})")
    }
}

impl Renderer {
    /// `read` of the kept engine, without the GIL (a frame being drawn holds the engine).
    fn read<T: Send>(&self, py: Python<'_>, read: impl FnOnce(&KeptEngine) -> T + Send) -> T {
        py.detach(|| {
            read(
                &self
                    .engine
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .engine,
            )
        })
    }
}

/// `set={"KEY": value, …}` as scene file settings: each value as TOML holds it (a `str` is a
/// string, a list an array, a dict a table).
fn scene_settings(set: &Bound<'_, PyDict>) -> PyResult<Vec<Setting>> {
    set.iter()
        .map(|(key, value)| {
            let key: String = key.extract()?;
            Setting::new(&key, toml_value(&value)?).map_err(errors::value)
        })
        .collect()
}

/// A Python value as TOML: bool, int, float, str, list or tuple, dict with str keys.
fn toml_value(value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(flag) = value.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(flag.is_true()));
    }
    if let Ok(whole) = value.extract::<i64>() {
        return Ok(toml::Value::Integer(whole));
    }
    if let Ok(number) = value.extract::<f64>() {
        return Ok(toml::Value::Float(number));
    }
    if let Ok(text) = value.extract::<String>() {
        return Ok(toml::Value::String(text));
    }
    if let Ok(table) = value.cast::<PyDict>() {
        return table
            .iter()
            .map(|(key, value)| Ok((key.extract::<String>()?, toml_value(&value)?)))
            .collect::<PyResult<toml::Table>>()
            .map(toml::Value::Table);
    }
    if let Ok(items) = value.try_iter() {
        return items
            .map(|item| toml_value(&item?))
            .collect::<PyResult<Vec<_>>>()
            .map(toml::Value::Array);
    }
    Err(errors::value(format!(
        "a scene setting's value must be a bool, number, str, list or dict, got {}",
        value.get_type().name()?
    )))
}

impl Rendered {
    /// The layers as `srt.render` returns them: the radiance array, or with the display layer
    /// the dict of layers and time channels; the warnings raised as Python warnings.
    fn into_python(self, py: Python<'_>, settings: RenderSettings) -> PyResult<Bound<'_, PyAny>> {
        for warning in &self.warnings {
            PyErr::warn(
                py,
                &py.get_type::<PyUserWarning>(),
                &std::ffi::CString::new(warning.as_str()).unwrap_or_default(),
                1,
            )?;
        }
        let shape = (settings.height as usize, settings.width as usize, 3);
        let radiance = image_array(py, shape, &self.radiance, channel_f32);
        let Some(display) = self.display else {
            return Ok(radiance.into_any());
        };
        let layers = PyDict::new(py);
        layers.set_item("radiance", radiance)?;
        layers.set_item(
            "display",
            image_array(py, shape, &display, display_as_linear),
        )?;
        let values = self.seen.unwrap_or_default();
        let grid = (shape.0, shape.1);
        for (index, name) in AOV_CHANNELS.into_iter().enumerate() {
            let channel = values.iter().map(|v| v[index]);
            if name == OBJECT_CHANNEL {
                // An object's index (−1: none), a whole number the f32 holds exactly.
                let ids: Vec<i32> = channel.map(|id| id as i32).collect();
                let array = Array2::from_shape_vec(grid, ids).expect("one value per pixel");
                layers.set_item(name, array.into_pyarray(py))?;
            } else {
                let array = Array2::from_shape_vec(grid, channel.collect::<Vec<f32>>())
                    .expect("one value per pixel");
                layers.set_item(name, array.into_pyarray(py))?;
            }
        }
        Ok(layers.into_any())
    }
}

/// The time channel holding each pixel's object index, returned as integers.
const OBJECT_CHANNEL: &str = "object";

/// The parts of a render request that do not name the scene.
struct Request {
    /// Size and samples per pixel.
    settings: RenderSettings,
    /// Which picture.
    view: View,
    /// Whether the display layer is asked for.
    aov: bool,
}

impl Request {
    /// Renders the scene of `next`, met with `warnings`, with the engine `kept` has for it (no
    /// GIL held), giving up once `stop` is set. `next` replaces the kept editor, so that its
    /// structure version says whether the engine uploads again.
    fn run(
        &self,
        kept: &mut Kept,
        next: Editor,
        mut warnings: Vec<String>,
        stop: &AtomicBool,
    ) -> Result<Rendered, Failure> {
        let editor = match kept.editor.take() {
            Some(mut editor) => {
                editor.replace_with(next);
                editor
            }
            None => next,
        };
        let editor = kept.editor.insert(editor);
        let built = editor.scene();
        let key = UploadKey::new(self.view, built, editor.structure_version());
        let scene = if self.view == View::Seen {
            Cow::Borrowed(built)
        } else {
            Cow::Owned(self.view.apply(built).map_err(|error| {
                Failure::Raise(errors::value(format!(
                    "cannot draw scene {} in the {} view: {error}",
                    built.name,
                    self.view.name()
                )))
            })?)
        };
        scene
            .check_picture_size(self.settings.width, self.settings.height)
            .map_err(|reason| Failure::Raise(errors::value(reason)))?;
        // One CPU tracer for every layer that needs it (the CPU engine's display and
        // radiance, the time channels); the engine `srt render` would choose draws the
        // radiance, and with `aov` the display colours too.
        let frame = Frame::new(&scene);
        let (engine, note) = kept
            .engine
            .engine_for(
                &frame,
                &Job {
                    settings: self.settings,
                    frames: 1,
                    // The radiance; with `aov` the display colours and the time channels too.
                    passes: 1 + 2 * u32::from(self.aov),
                },
                &key,
            )
            .map_err(|e| Failure::Raise(errors::gpu(&e)))?;
        warnings.extend(note.map(|note| format!("note: {note}")));
        let mut render = |output| {
            engine
                .draw(&frame, self.settings, output, &|_| {}, stop)
                .map_err(|e| Failure::Raise(errors::gpu(&e)))?
                .ok_or(Failure::Stopped)
        };
        let display = if self.aov {
            Some(render(Output::Display)?.pixels)
        } else {
            None
        };
        let drawn = render(Output::Radiance)?;
        warnings.extend(empty_picture_warning(&scene, &drawn.seen));
        let radiance = drawn.pixels;
        let seen = if self.aov {
            let values = engine
                .render_aov(&frame, self.settings, &|_| {}, stop)
                .map_err(|e| Failure::Raise(errors::gpu(&e)))?;
            Some(values.ok_or(Failure::Stopped)?)
        } else {
            None
        };
        Ok(Rendered {
            radiance,
            display,
            seen,
            warnings,
        })
    }
}

/// An editor of the scene `source` loads with `overrides` (no GIL held), and the warnings met.
fn load(
    py: Python<'_>,
    source: &SceneSource,
    overrides: &Overrides,
) -> PyResult<(Editor, Vec<String>)> {
    let loaded = py
        .detach(|| source.load_with(overrides))
        .map_err(|e| errors::scene(&e))?;
    Ok(Editor::new(loaded))
}

/// Runs `work` on another thread with the GIL released, looking for Ctrl-C meanwhile: on one,
/// sets the stop flag `work` watches and waits for it to give up.
fn run_interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&AtomicBool) -> Result<T, Failure> + Send,
) -> Result<T, Failure> {
    let stop = AtomicBool::new(false);
    std::thread::scope(|scope| {
        let worker = scope.spawn(|| work(&stop));
        loop {
            if worker.is_finished() {
                return worker
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            }
            py.detach(|| std::thread::sleep(SIGNAL_POLL));
            if let Err(interrupt) = py.check_signals() {
                stop.store(true, Ordering::Relaxed);
                let _ = worker.join();
                return Err(Failure::Raise(interrupt));
            }
        }
    })
}

/// `pixels` as a float32 array of `shape`, each channel converted by `channel`.
fn image_array<'py>(
    py: Python<'py>,
    shape: (usize, usize, usize),
    pixels: &[DVec3],
    channel: fn(f64) -> f32,
) -> Bound<'py, PyArray3<f32>> {
    let values: Vec<f32> = pixels
        .iter()
        .flat_map(|p| p.to_array().map(channel))
        .collect();
    Array3::from_shape_vec(shape, values)
        .expect("one colour per pixel")
        .into_pyarray(py)
}

/// Linear light (any shape, float64) as 8-bit sRGB: clamped to [0, 1], encoded (IEC
/// 61966-2-1) and quantised as srt's PNGs are.
#[pyfunction]
pub fn to_srgb8<'py>(
    py: Python<'py>,
    linear: PyReadonlyArrayDyn<'py, f64>,
) -> Bound<'py, PyArrayDyn<u8>> {
    let encoded: ArrayD<u8> = linear
        .as_array()
        .mapv(|c| quantize_8bit(srgb_encode(c.clamp(0.0, 1.0))));
    encoded.into_pyarray(py)
}

/// The size and samples, within `srt render`'s limits.
fn settings(width: u32, height: u32, samples: u32) -> PyResult<RenderSettings> {
    for (name, value) in [("width", width), ("height", height)] {
        if !(1..=MAX_IMAGE_SIDE).contains(&value) {
            return Err(errors::value(format!(
                "{name} must be 1 to {MAX_IMAGE_SIDE} pixels, got {value}"
            )));
        }
    }
    if !(1..=MAX_SAMPLES).contains(&samples) {
        return Err(errors::value(format!(
            "samples must be 1 to {MAX_SAMPLES}, got {samples}"
        )));
    }
    Ok(RenderSettings {
        width,
        height,
        samples,
    })
}
