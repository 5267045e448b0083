//! `srt._srt`, the Rust half of the Python package `srt` (python/srt/): scenes (`scene.rs`),
//! rendering to numpy arrays (`render.rs`) and srt's physics, vectorised (`physics.rs`). The
//! Python half wraps these with argument handling, docstrings and the `srt.physics` namespace;
//! docs/python.md is the user's guide.

mod errors;
mod physics;
mod render;
mod scene;

use pyo3::prelude::*;

/// The extension module: every class, exception and function the Python package re-exports.
#[pymodule]
fn _srt(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("SceneFileError", py.get_type::<errors::SceneFileError>())?;
    m.add("GpuError", py.get_type::<errors::GpuError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::Observer>()?;
    m.add_class::<scene::SceneObject>()?;
    m.add_function(wrap_pyfunction!(scene::scenes, m)?)?;
    m.add_class::<render::Renderer>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::to_srgb8, m)?)?;
    physics::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
