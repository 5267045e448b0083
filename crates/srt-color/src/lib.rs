//! Black-body colour for special relativistic rendering, in `f64` on the CPU.
//!
//! This crate implements §3.3 of Müller, Grottel and Weiskopf, *Special Relativistic
//! Visualization by Local Ray Tracing* (IEEE TVCG 2010); equation and figure numbers in the
//! documentation are the paper's. The pipeline, one function per step:
//!
//! 1. [`planck_radiance`] — the Planck spectrum L(λ, T), Eq. 10. A Doppler factor D (received
//!    over emitted frequency, D > 1 a blue shift) turns a black body of temperature T into one of
//!    temperature D · T, radiance included (Eq. 9: L(λ, D·T) = D⁵ · L(D·λ, T)).
//! 2. [`blackbody_xyz`] — CIE 1931 XYZ by summing L against the colour-matching functions
//!    ([`cie_1931`]) at 1 nm, Eq. 11; [`chromaticity`] gives (x, y).
//! 3. [`xyz_to_linear_rgb`] — the BT.709 matrix [`XYZ_TO_LINEAR_BT709`], Eq. 12.
//! 4. [`srgb_encode`] — the sRGB transfer curve, Eq. 13.
//! 5. [`ToneMap`] — the paper's two tone maps (Fig. 6), [`ToneMap::display_rgb`] running the
//!    whole pipeline; [`colour_table`] draws Fig. 6.
//! 6. [`TemperatureLut`] — the 1D table over ln T that the GPU samples, with its exact CPU mirror.
//! 7. [`spectral`] — surface colour from spectra instead of the paper's grey-value shortcut:
//!    RGB → reflectance spectra (Jakob & Hanika 2019), light reflected under two Doppler factors
//!    ([`reflected_display_rgb`]), emitters ([`emitted_display_rgb`]); [`ToneMap::display_rgb_xyz`]
//!    tone-maps any light with an exposure.
//! 8. [`RadianceTable`] and [`RadianceScale`] — the same light as radiance (linear BT.709,
//!    unclamped, luminance 1 = a white surface at rest facing the lamp), what an EXR holds
//!    beside the displayed image (docs/colour.md, "Radiance and display").
//!
//! ```
//! use srt_color::{TemperatureLut, ToneMap};
//!
//! // A 6000 K light seen by an observer approaching it head-on at 0.2c: D = √(3/2).
//! let apparent_k = 6000.0 * 1.5_f64.sqrt();
//! assert!((apparent_k - 7348.0).abs() < 1.0);
//!
//! let lut = TemperatureLut::with_defaults(ToneMap::Luminance);
//! let [r, g, b, a] = lut.sample(apparent_k);
//! assert!(b > r && a == 1.0); // hotter than the Sun: slightly bluish white
//! let exact = ToneMap::Luminance.display_rgb(apparent_k);
//! assert!((f64::from(g) - exact.y).abs() < 1.0 / 255.0);
//! ```

mod cie;
mod error;
mod lut;
mod planck;
mod radiance;
mod rgb;
pub mod spectral;
mod tonemap;

pub use cie::{
    CIE_1931_MAX_NM, CIE_1931_MIN_NM, CIE_1931_STEP_M, CmfSample, ScaledXyz, blackbody_xyz,
    blackbody_xyz_scaled, chromaticity, cie_1931,
};
pub use error::ColourError;
pub use lut::{LutError, TemperatureLut};
pub use planck::{
    BOLTZMANN_CONSTANT, PLANCK_CONSTANT, SECOND_RADIATION_CONSTANT, SPEED_OF_LIGHT, WIEN_X,
    planck_radiance,
};
pub use radiance::{Output, RadianceScale, RadianceTable};
pub use rgb::{
    SRGB_LINEAR_THRESHOLD, SRGB_OFFSET, XYZ_TO_LINEAR_BT709, quantize_8bit, srgb_decode,
    srgb_encode, xyz_to_linear_rgb,
};
pub use spectral::{
    CoefficientTable, Reflectance, ReflectedLight, SigmoidPolynomial, emitted_display_rgb,
    emitted_light, fit_rgb, reflected_display_rgb, reflected_light, srgb_coefficient_table,
};
pub use tonemap::{SEARCHLIGHT_REFERENCE_K, ToneMap, colour_table, searchlight_reference_ln_y};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
