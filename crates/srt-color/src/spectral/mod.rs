//! Spectral surface colour under the Doppler effect (issue 11): reflectance spectra upsampled
//! from RGB by Jakob & Hanika 2019, reflected black-body light shifted twice (the paper's Eq. 17
//! as a product of two Doppler factors), and the policy for the bands a shift brings into view.
//!
//! - [`mod@sigmoid`]: the model R(λ) = S(c₀λ² + c₁λ + c₂) ([`SigmoidPolynomial`]).
//! - [`mod@fit`]: linear sRGB → coefficients by Gauss–Newton in CIELAB under D65 ([`fit_rgb`]).
//! - [`mod@table`]: the 3 × n³ coefficient table for textures ([`CoefficientTable`]).
//! - [`mod@reflect`]: [`Reflectance`] with its out-of-domain policy and infrared/ultraviolet bands,
//!   [`reflected_light`] and [`emitted_light`] as XYZ, and the display colours a renderer calls
//!   per point ([`reflected_display_rgb`], [`emitted_display_rgb`]).

pub mod fit;
pub mod reflect;
pub mod sigmoid;
pub mod table;

pub use fit::{
    RgbFit, cie_d65, d65_white_xyz, fit_rgb, linear_rgb_to_xyz, reflectance_xyz_d65, xyz_to_lab,
};
pub use reflect::{
    INFRARED_ABOVE_NM, Reflectance, ReflectedLight, ULTRAVIOLET_BELOW_NM, emitted_display_rgb,
    emitted_light, reflected_display_rgb, reflected_light,
};
pub use sigmoid::{MODEL_MAX_NM, MODEL_MIN_NM, SigmoidPolynomial, sigmoid};
pub use table::{CoefficientTable, srgb_coefficient_table};
