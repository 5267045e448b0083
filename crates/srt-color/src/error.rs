//! The one error type of the colour pipeline's checked entry points: bad input is reported,
//! never turned into a panic or a NaN.

use thiserror::Error;

/// Why a colour could not be computed: an input outside its domain.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum ColourError {
    /// A temperature that is not positive and finite (kelvin).
    #[error("invalid temperature {0} K: need a positive finite value")]
    InvalidTemperature(f64),
    /// A Doppler factor D = ω_received/ω_emitted that is not positive and finite.
    #[error("invalid Doppler factor {0}: need a positive finite value")]
    InvalidDoppler(f64),
    /// The apparent temperature D_in · D_out · T left `f64`'s positive finite range.
    #[error("apparent temperature {0} K is out of range (the Doppler factors are too extreme)")]
    ApparentTemperatureOutOfRange(f64),
    /// A tone-map exposure that is not positive and finite.
    #[error("invalid exposure {0}: need a positive finite multiplier")]
    InvalidExposure(f64),
    /// An emitter brightness that is not finite and ≥ 0.
    #[error("invalid brightness {0}: need a finite value ≥ 0")]
    InvalidBrightness(f64),
    /// A reflectance that is not in [0, 1].
    #[error("invalid reflectance {0}: need a value in [0, 1]")]
    InvalidReflectance(f64),
    /// A linear RGB component that is not in [0, 1].
    #[error("invalid linear RGB component {0}: need a value in [0, 1]")]
    InvalidRgb(f64),
    /// Sigmoid-polynomial coefficients that are NaN, or infinite other than a constant's.
    #[error("invalid sigmoid coefficients ({0}, {1}, {2})")]
    InvalidCoefficients(f64, f64, f64),
    /// A coefficient table resolution outside the supported range.
    #[error("invalid coefficient table resolution {0}: need 3 ..= 256")]
    InvalidResolution(usize),
}

/// `Ok(value)` if `value` is positive and finite, otherwise `Err(error(value))`.
pub(crate) fn positive_finite(
    value: f64,
    error: impl FnOnce(f64) -> ColourError,
) -> Result<f64, ColourError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(error(value))
    }
}

/// `Ok(value)` if `value` lies in [0, 1] (so not NaN), otherwise `Err(error(value))`.
pub(crate) fn unit_interval(
    value: f64,
    error: impl FnOnce(f64) -> ColourError,
) -> Result<f64, ColourError> {
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(error(value))
    }
}
