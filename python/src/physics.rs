//! srt's physics for numpy arrays, row by row through the very functions the renderers use
//! (srt-physics in f64, srt-color's tone maps); `srt.physics` (python/srt/physics.py) shapes the
//! arguments and documents them. Every velocity is checked as the scene file checks one
//! (finite, |β| < 1).

use glam::DVec3;
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray as _, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use srt_color::ToneMap;
use srt_physics::{Event, Frame, aberrate, doppler_factor, lorentz_matrix, validate_beta};

use crate::errors;

/// Adds the physics functions to the extension module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(lorentz_boost, m)?)?;
    m.add_function(wrap_pyfunction!(apparent_positions, m)?)?;
    m.add_function(wrap_pyfunction!(doppler_factors, m)?)?;
    m.add_function(wrap_pyfunction!(aberrate_directions, m)?)?;
    m.add_function(wrap_pyfunction!(blackbody_colours, m)?)?;
    Ok(())
}

/// `beta` if it is a velocity, else srt's message naming it `name`.
fn velocity(name: &str, beta: [f64; 3]) -> PyResult<DVec3> {
    validate_beta(DVec3::from_array(beta))
        .map_err(|error| errors::value(format!("{name} {beta:?} is not a valid velocity: {error}")))
}

/// The rows of an (N, 3) array as vectors.
fn rows(array: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<DVec3>> {
    let view = array.as_array();
    if view.ncols() != 3 {
        return Err(errors::value(format!(
            "expected an array of shape (N, 3), got (N, {})",
            view.ncols()
        )));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|row| DVec3::new(row[0], row[1], row[2]))
        .collect())
}

/// The rows of an (N, 3) array as unit directions: each must be finite and non-zero.
fn unit_directions(array: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<DVec3>> {
    rows(array)?
        .into_iter()
        .enumerate()
        .map(|(i, n)| {
            let unit = n.normalize_or_zero();
            if n.is_finite() && unit != DVec3::ZERO {
                Ok(unit)
            } else {
                Err(errors::value(format!(
                    "directions must be non-zero and finite, got {:?} in row {i}",
                    n.to_array()
                )))
            }
        })
        .collect()
}

/// Vectors as an (N, 3) array.
fn to_array<'py>(py: Python<'py>, vectors: &[DVec3]) -> Bound<'py, PyArray2<f64>> {
    let values: Vec<f64> = vectors.iter().flat_map(|v| v.to_array()).collect();
    Array2::from_shape_vec((vectors.len(), 3), values)
        .expect("three components per vector")
        .into_pyarray(py)
}

/// The Lorentz matrix Λ_β of Eq. 2 (S′ to S, Eq. 1) as a 4×4 array acting on (ct, x, y, z)
/// column vectors.
#[pyfunction]
fn lorentz_boost<'py>(py: Python<'py>, beta: [f64; 3]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let matrix = lorentz_matrix(velocity("beta", beta)?);
    let rows: Vec<f64> = (0..4).flat_map(|i| matrix.row(i).to_array()).collect();
    Ok(Array2::from_shape_vec((4, 4), rows)
        .expect("sixteen entries")
        .into_pyarray(py))
}

/// Apparent positions (Eqs. 5–8) of rest-frame points of a frame moving with `beta` whose
/// origin is at `offset` at t = t′ = 0, seen from `observer` at time `ct`.
#[pyfunction]
fn apparent_positions<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    beta: [f64; 3],
    offset: [f64; 3],
    observer: [f64; 3],
    ct: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let frame = Frame::new(velocity("beta", beta)?, DVec3::from_array(offset))
        .map_err(|e| errors::value(format!("beta {beta:?}, offset {offset:?}: {e}")))?;
    if !ct.is_finite() || !observer.iter().all(|c| c.is_finite()) {
        return Err(errors::value(format!(
            "the observer's event must be finite, got ct {ct:?} at {observer:?}"
        )));
    }
    let event = Event::new(ct, DVec3::from_array(observer));
    let points = rows(&points)?;
    let seen: Vec<DVec3> = points
        .iter()
        .map(|&p| frame.apparent_position(p, event))
        .collect();
    Ok(to_array(py, &seen))
}

/// Doppler factors D = 1 / (γ (1 − β·n)) (Eq. 4) of light reaching an observer at rest along
/// the unit propagation directions n from a source moving with `beta`.
#[pyfunction]
fn doppler_factors<'py>(
    py: Python<'py>,
    beta: [f64; 3],
    directions: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let beta = velocity("beta", beta)?;
    let factors: Vec<f64> = unit_directions(&directions)?
        .iter()
        .map(|&n| doppler_factor(beta, n))
        .collect();
    Ok(Array1::from(factors).into_pyarray(py))
}

/// Aberration (Eq. 4): propagation directions in S of light that propagates along
/// `directions` in S′, S′ moving with `beta`.
#[pyfunction]
fn aberrate_directions<'py>(
    py: Python<'py>,
    directions: PyReadonlyArray2<'py, f64>,
    beta: [f64; 3],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let beta = velocity("beta", beta)?;
    let seen: Vec<DVec3> = unit_directions(&directions)?
        .iter()
        .map(|&n| aberrate(beta, n))
        .collect();
    Ok(to_array(py, &seen))
}

/// The display colour (sRGB-encoded, [0, 1]) of black bodies at `temperatures` through the
/// tone map called `tone_map` (Fig. 6: "luminance" left, "searchlight" right, f = 1).
#[pyfunction]
fn blackbody_colours<'py>(
    py: Python<'py>,
    temperatures: PyReadonlyArray1<'py, f64>,
    tone_map: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let map = ToneMap::ALL
        .into_iter()
        .find(|m| m.name() == tone_map)
        .ok_or_else(|| {
            errors::value(format!(
                "tone_map {tone_map:?} is neither \"luminance\" nor \"searchlight\""
            ))
        })?;
    let colours: Vec<DVec3> = temperatures
        .as_array()
        .iter()
        .map(|&t| {
            if t > 0.0 && t.is_finite() {
                Ok(map.display_rgb(t))
            } else {
                Err(errors::value(format!(
                    "temperatures must be positive and finite, got {t:?} K"
                )))
            }
        })
        .collect::<PyResult<_>>()?;
    Ok(to_array(py, &colours))
}
