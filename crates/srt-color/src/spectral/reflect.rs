//! Light reflected by a spectral surface under a Doppler-shifted black body, and the out-of-domain
//! policy for the wavelengths a shift brings into view.
//!
//! # Physics
//!
//! A black-body light of temperature T illuminates a surface; the surface sees it with Doppler
//! factor `D_in`, the observer sees the surface with `D_out` (D = ω_received/ω_emitted; the
//! paper's Eq. 17 is the product D_in · D_out). In the surface's frame the illuminant is a black
//! body at D_in · T, radiance included (Eq. 9), and the surface sends L_s(λ_s) = R(λ_s) ·
//! B(λ_s, D_in · T) (times the geometric factor the renderer applies, f_ar of Eq. 18, which is the
//! same at every λ). The observer receives at λ the light the surface sent at λ_s = D_out · λ,
//! with L_obs(λ) = D_out⁵ · L_s(D_out · λ) (Eq. 9's transformation of spectral radiance), so by
//! Eq. 9 once more
//!
//! L_obs(λ) = R(D_out · λ) · B(λ, D_in · D_out · T).
//!
//! A grey surface R = ρ therefore gives exactly ρ times the black body at D_in · D_out · T — the
//! paper's shortcut — while a coloured one shows its reflectance shifted by D_out.
//!
//! # What the shift shows, and the policy outside the model
//!
//! The observer's window 360–830 nm shows the surface's reflectance at D_out · 360 … D_out ·
//! 830 nm: at D_out = 4.36 the visible 380–780 nm come from 1.66–3.40 µm. The Jakob–Hanika model
//! is only fitted on 360–830 nm, where the CIELAB objective constrains it. Its quadratic keeps
//! growing outside, so the sigmoid saturates to 0 or 1 according to the sign of c₀ alone — an
//! artefact of the model, not a property of the material. [`Reflectance::evaluate`] therefore
//! **holds the edge value**: R(λ) = R(360 nm) below and R(830 nm) above the fitted domain
//! (continuous, bounded, and what pbrt-v4 effectively does by never evaluating outside it).
//! Where the material's ultraviolet (λ < 380 nm) or infrared (λ > 780 nm) reflectance is known,
//! a constant per band overrides the model there.

use glam::DVec3;

use super::sigmoid::{MODEL_MAX_NM, MODEL_MIN_NM, SigmoidPolynomial};
use crate::cie::{CIE_1931_STEP_M, PlanckWeights, ScaledXyz, blackbody_xyz_scaled, planck_sums};
use crate::error::{ColourError, positive_finite, unit_interval};
use crate::tonemap::ToneMap;

/// Wavelengths below this (nm) take a material's ultraviolet reflectance, where it has one.
pub const ULTRAVIOLET_BELOW_NM: f64 = 380.0;
/// Wavelengths above this (nm) take a material's infrared reflectance, where it has one.
pub const INFRARED_ABOVE_NM: f64 = 780.0;

/// A surface's reflectance spectrum: a Jakob–Hanika sigmoid polynomial, held at its edge values
/// outside 360–830 nm, with optional constant ultraviolet and infrared reflectances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reflectance {
    polynomial: SigmoidPolynomial,
    ultraviolet: Option<f64>,
    infrared: Option<f64>,
}

impl Reflectance {
    /// The reflectance `polynomial`, held at its edge values outside the fitted domain.
    #[must_use]
    pub fn new(polynomial: SigmoidPolynomial) -> Self {
        Self {
            polynomial,
            ultraviolet: None,
            infrared: None,
        }
    }

    /// [`Reflectance::new`] with constant reflectances that replace the model below
    /// [`ULTRAVIOLET_BELOW_NM`] (`ultraviolet`) and above [`INFRARED_ABOVE_NM`] (`infrared`).
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidReflectance`] unless each given value lies in [0, 1].
    pub fn with_bands(
        polynomial: SigmoidPolynomial,
        ultraviolet: Option<f64>,
        infrared: Option<f64>,
    ) -> Result<Self, ColourError> {
        for value in [ultraviolet, infrared].into_iter().flatten() {
            unit_interval(value, ColourError::InvalidReflectance)?;
        }
        Ok(Self {
            polynomial,
            ultraviolet,
            infrared,
        })
    }

    /// A constant (grey) reflectance ρ at every wavelength.
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidReflectance`] unless ρ ∈ [0, 1].
    pub fn grey(reflectance: f64) -> Result<Self, ColourError> {
        Ok(Self::new(SigmoidPolynomial::constant(reflectance)?))
    }

    /// The sigmoid polynomial.
    #[must_use]
    pub fn polynomial(&self) -> SigmoidPolynomial {
        self.polynomial
    }

    /// The ultraviolet override, if any.
    #[must_use]
    pub fn ultraviolet(&self) -> Option<f64> {
        self.ultraviolet
    }

    /// The infrared override, if any.
    #[must_use]
    pub fn infrared(&self) -> Option<f64> {
        self.infrared
    }

    /// R(λ) ∈ [0, 1] at `wavelength_nm` under the policy of the module documentation: the band
    /// override where one applies, else the model at λ clamped to 360–830 nm.
    #[must_use]
    pub fn evaluate(&self, wavelength_nm: f64) -> f64 {
        let (numerator, denominator) = self.evaluate_fraction(wavelength_nm);
        numerator / denominator
    }

    /// [`Reflectance::evaluate`] as a fraction (numerator, denominator), for a sum that divides
    /// once per wavelength; selects rather than branches, so that a loop over wavelengths
    /// vectorises.
    #[inline(always)]
    fn evaluate_fraction(&self, wavelength_nm: f64) -> (f64, f64) {
        let (ultraviolet_below, ultraviolet) = self
            .ultraviolet
            .map_or((f64::NEG_INFINITY, 0.0), |uv| (ULTRAVIOLET_BELOW_NM, uv));
        let (infrared_above, infrared) = self
            .infrared
            .map_or((f64::INFINITY, 0.0), |ir| (INFRARED_ABOVE_NM, ir));
        let model = self
            .polynomial
            .evaluate_fraction(wavelength_nm.clamp(MODEL_MIN_NM, MODEL_MAX_NM));
        if wavelength_nm < ultraviolet_below {
            (ultraviolet, 1.0)
        } else if wavelength_nm > infrared_above {
            (infrared, 1.0)
        } else {
            model
        }
    }
}

/// Light reflected towards the observer, with the light a perfect white reflector would send in
/// its place (the luminance tone map's reference).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReflectedLight {
    /// XYZ of the reflected light, per unit geometric factor.
    pub light: ScaledXyz,
    /// XYZ of a perfect white reflector in the same place: the black body at D_in · D_out · T.
    pub white: ScaledXyz,
}

/// D_in · D_out · T, checked: every factor positive and finite, and so the product.
fn apparent_temperature(temperature_k: f64, dopplers: &[f64]) -> Result<f64, ColourError> {
    let mut apparent = positive_finite(temperature_k, ColourError::InvalidTemperature)?;
    for &d in dopplers {
        apparent *= positive_finite(d, ColourError::InvalidDoppler)?;
    }
    positive_finite(apparent, ColourError::ApparentTemperatureOutOfRange)
}

/// CIE 1931 XYZ of black-body light of temperature `light_temperature_k` reflected by
/// `reflectance`, the surface seeing the light with Doppler factor `d_in` and the observer seeing
/// the surface with `d_out`: Σ R(D_out · λ) · B(λ, D_in · D_out · T) · σⱼ(λ) · Δλ over the CIE
/// table at 1 nm (Eq. 9–11 and 17; module documentation), in `f64`.
///
/// # Errors
///
/// [`ColourError::InvalidTemperature`] or [`ColourError::InvalidDoppler`] unless each input is
/// positive and finite; [`ColourError::ApparentTemperatureOutOfRange`] if D_in · D_out · T is not
/// (or underflows so far that no visible radiance is left).
pub fn reflected_light(
    reflectance: &Reflectance,
    light_temperature_k: f64,
    d_in: f64,
    d_out: f64,
) -> Result<ReflectedLight, ColourError> {
    let apparent = apparent_temperature(light_temperature_k, &[d_in, d_out])?;
    let weights =
        PlanckWeights::new(apparent).ok_or(ColourError::ApparentTemperatureOutOfRange(apparent))?;
    let (light, white) = planck_sums(
        &weights,
        #[inline(always)]
        |wavelengths_nm, numerators, denominators| {
            let rows = numerators.iter_mut().zip(denominators).zip(wavelengths_nm);
            for ((numerator, denominator), &wavelength_nm) in rows {
                (*numerator, *denominator) = reflectance.evaluate_fraction(d_out * wavelength_nm);
            }
        },
    );
    let ln_scale = weights.ln_max() + CIE_1931_STEP_M.ln();
    Ok(ReflectedLight {
        light: ScaledXyz {
            relative: light,
            ln_scale,
        },
        white: ScaledXyz {
            relative: white,
            ln_scale,
        },
    })
}

/// Display sRGB in [0, 1] of a surface point: [`reflected_light`] through `tone_map` with
/// `exposure` — the per-point function a renderer calls.
///
/// `exposure` multiplies XYZ before the tone map; a renderer passes its exposure times the
/// geometric factor (f_amb + f_diff + f_spec of Eq. 18), which replaces the shortcut's
/// f_ar = ½(𝒢 + 1)(…): the colour now comes from the spectrum, not from a grey value.
///
/// # Errors
///
/// As [`reflected_light`], and [`ColourError::InvalidExposure`] unless `exposure` is positive and
/// finite.
pub fn reflected_display_rgb(
    tone_map: ToneMap,
    reflectance: &Reflectance,
    light_temperature_k: f64,
    d_in: f64,
    d_out: f64,
    exposure: f64,
) -> Result<DVec3, ColourError> {
    let reflected = reflected_light(reflectance, light_temperature_k, d_in, d_out)?;
    tone_map.display_rgb_xyz(reflected.light, reflected.white, exposure)
}

/// XYZ of a black-body emitter of temperature `temperature_k` and brightness scale `brightness`
/// seen with Doppler factor `doppler`: `brightness` times the black body at D · T_e (Eq. 9).
///
/// # Errors
///
/// [`ColourError::InvalidTemperature`], [`ColourError::InvalidDoppler`],
/// [`ColourError::ApparentTemperatureOutOfRange`] as for [`reflected_light`];
/// [`ColourError::InvalidBrightness`] unless `brightness` is finite and ≥ 0.
pub fn emitted_light(
    temperature_k: f64,
    brightness: f64,
    doppler: f64,
) -> Result<ScaledXyz, ColourError> {
    Ok(emitter(temperature_k, brightness, doppler)?.0)
}

/// The emitter's light and the same emitter at brightness 1 (the luminance tone map's white).
fn emitter(
    temperature_k: f64,
    brightness: f64,
    doppler: f64,
) -> Result<(ScaledXyz, ScaledXyz), ColourError> {
    if !(brightness.is_finite() && brightness >= 0.0) {
        return Err(ColourError::InvalidBrightness(brightness));
    }
    let apparent = apparent_temperature(temperature_k, &[doppler])?;
    let body = blackbody_xyz_scaled(apparent);
    if body.relative.y <= 0.0 {
        return Err(ColourError::ApparentTemperatureOutOfRange(apparent));
    }
    let light = if brightness > 0.0 {
        ScaledXyz {
            ln_scale: body.ln_scale + brightness.ln(),
            ..body
        }
    } else {
        ScaledXyz::BLACK
    };
    Ok((light, body))
}

/// Display sRGB in [0, 1] of a black-body emitter ([`emitted_light`]) through `tone_map`: the
/// luminance tone map divides by the emitter's own Y at brightness 1, so `brightness` and
/// `exposure` both brighten it.
///
/// # Errors
///
/// As [`emitted_light`], and [`ColourError::InvalidExposure`].
pub fn emitted_display_rgb(
    tone_map: ToneMap,
    temperature_k: f64,
    brightness: f64,
    doppler: f64,
    exposure: f64,
) -> Result<DVec3, ColourError> {
    let (light, white) = emitter(temperature_k, brightness, doppler)?;
    tone_map.display_rgb_xyz(light, white, exposure)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cie::cie_1931;
    use crate::planck::ln_planck_radiance;
    use crate::spectral::srgb_coefficient_table;

    /// The sums of [`reflected_light`] by their definition, one row at a time: R(D_out · λ) ·
    /// L(λ, D_in · D_out · T) · σ(λ) with L from Planck's law in logarithms, relative to the
    /// largest L over the table; `(light, white, ln L_max)`.
    fn by_definition(
        reflectance: &Reflectance,
        temperature_k: f64,
        d_out: f64,
    ) -> (DVec3, DVec3, f64) {
        let ln: Vec<f64> = cie_1931()
            .iter()
            .map(|s| ln_planck_radiance(s.wavelength_m(), temperature_k))
            .collect();
        let ln_max = ln.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (mut light, mut white) = (DVec3::ZERO, DVec3::ZERO);
        for (sample, ln) in cie_1931().iter().zip(ln) {
            let radiance = (ln - ln_max).exp() * sample.tristimulus();
            light += reflectance.evaluate(d_out * sample.wavelength_nm) * radiance;
            white += radiance;
        }
        (light, white, ln_max)
    }

    proptest::proptest! {
        #[test]
        fn the_lane_wise_sum_is_the_sum_by_definition(
            rgb in proptest::array::uniform3(0.0_f64..=1.0),
            temperature_k in 500.0_f64..40_000.0,
            ln_d_in in -2.65_f64..2.65,
            ln_d_out in -2.65_f64..2.65,
            ultraviolet in proptest::option::of(0.0_f64..=1.0),
            infrared in proptest::option::of(0.0_f64..=1.0),
        ) {
            // Every colour of the table, 500–40 000 K, |β| up to 0.99 each way (D within 1/14 …
            // 14, so apparent temperatures from 2.5 K to 8 · 10⁶ K: both forms of g), with and
            // without band constants.
            let polynomial = srgb_coefficient_table().lookup(DVec3::from_array(rgb)).expect("rgb in [0, 1]");
            let reflectance = Reflectance::with_bands(polynomial, ultraviolet, infrared).expect("bands in [0, 1]");
            let (d_in, d_out) = (ln_d_in.exp(), ln_d_out.exp());
            let got = reflected_light(&reflectance, temperature_k, d_in, d_out).expect("valid input");
            let (light, white, ln_max) = by_definition(&reflectance, temperature_k * d_in * d_out, d_out);
            let scale = (got.light.ln_scale - ln_max - CIE_1931_STEP_M.ln()).exp();
            let tolerance = 1e-12 * white.y;
            proptest::prop_assert!((got.white.relative * scale - white).abs().max_element() <= tolerance,
                "white {:?} vs {:?}", got.white.relative * scale, white);
            proptest::prop_assert!((got.light.relative * scale - light).abs().max_element() <= tolerance,
                "light {:?} vs {:?}", got.light.relative * scale, light);
        }
    }
}
