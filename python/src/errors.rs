//! srt's errors as Python exceptions carrying srt's one-line message: bad values and scenes
//! raise [`SceneError`] (a `ValueError`), files that cannot be found or read raise
//! [`SceneFileError`] (an `OSError`), a GPU that is missing or fails raises [`GpuError`] (a
//! `RuntimeError`).

use pyo3::PyErr;
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use srt_scene::{Choice, ResolveError, SceneErrorKind};

create_exception!(
    srt,
    SceneError,
    PyValueError,
    "A scene or a value srt refuses: an unknown name, invalid scene text, a value out of its range (|beta| >= 1, NaN, ...). The message is srt's own."
);
create_exception!(
    srt,
    SceneFileError,
    PyOSError,
    "A scene, model, texture or star file that cannot be found, read or imported; the message names the file."
);
create_exception!(
    srt,
    GpuError,
    PyRuntimeError,
    "No GPU adapter where one was asked for (backend='gpu'), or the GPU failed."
);

/// A value refused, with srt's message.
pub fn value(message: impl Into<String>) -> PyErr {
    SceneError::new_err(message.into())
}

/// A scene that does not load: file problems as [`SceneFileError`], the rest as [`SceneError`].
pub fn scene(error: &srt_scene::SceneError) -> PyErr {
    let message = error.to_string();
    match error.kind() {
        SceneErrorKind::Io(_) | SceneErrorKind::Model { .. } | SceneErrorKind::Sky(_) => {
            SceneFileError::new_err(message)
        }
        _ => SceneError::new_err(message),
    }
}

/// An edit refused: the scene's rules as [`scene`] raises them, the rest as [`SceneError`].
pub fn edit(error: &srt_scene::EditError) -> PyErr {
    match error {
        srt_scene::EditError::Scene(error) => scene(error),
        srt_scene::EditError::Source(error) => resolve(error),
        other => value(other.to_string()),
    }
}

/// A scene argument that names no scene.
pub fn resolve(error: &ResolveError) -> PyErr {
    match error {
        ResolveError::NotFound(_) | ResolveError::NoSuchFile(_) => {
            SceneFileError::new_err(error.to_string())
        }
        ResolveError::Unsupported(_) => SceneError::new_err(error.to_string()),
        ResolveError::Scene(error) => scene(error),
    }
}

/// A GPU problem (no adapter, a target beyond its limits, device lost), with its causes in one
/// line as `srt` prints them.
pub fn gpu(error: &anyhow::Error) -> PyErr {
    GpuError::new_err(format!("{error:#}"))
}

/// The choice called `name` (a method, an effect mode, a view, …), or [`SceneError`] with the
/// library's message naming the choices there are (the command line's and the page's).
pub fn chosen<T: Choice>(name: &str) -> Result<T, PyErr> {
    T::parse(name).map_err(|unknown| value(unknown.to_string()))
}
