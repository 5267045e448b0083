//! The paper's two tone maps from black-body tristimulus values to display sRGB (Fig. 6), and the
//! 2D colour tables of Fig. 6.
//!
//! Without tone mapping, Eq. 11–13 would send every temperature below about 1900 K to yellow and
//! the rest to white (§3.3). The paper therefore scales XYZ before Eq. 12, in one of two ways:
//!
//! - [`ToneMap::Luminance`] (Fig. 6 left, the `doppler` effect mode): XYZ / Y, so that only the
//!   chromaticity survives and the searchlight effect's brightness change is hidden;
//! - [`ToneMap::Searchlight`] (Fig. 6 right): XYZ / Y(1500 K), followed by the global logarithmic
//!   operator C → 0.6 · log₁₀(C + 1) on the encoded value, which keeps the brightness.

use std::sync::LazyLock;

use glam::DVec3;

use crate::cie::{ScaledXyz, blackbody_xyz_relative, blackbody_xyz_scaled};
use crate::error::{ColourError, positive_finite};
use crate::rgb::{srgb_encode, xyz_to_linear_rgb};

/// Reference temperature of the searchlight tone map, whose luminance Y scales all XYZ (§3.3).
pub const SEARCHLIGHT_REFERENCE_K: f64 = 1500.0;

/// ln Y(1500 K), the logarithm of the searchlight tone map's divisor.
static LN_SEARCHLIGHT_REFERENCE_Y: LazyLock<f64> = LazyLock::new(|| {
    let (relative, ln_scale) = blackbody_xyz_relative(SEARCHLIGHT_REFERENCE_K);
    relative.y.ln() + ln_scale
});

/// ln Y(1500 K), the logarithm (of Y in W·sr⁻¹·m⁻², Eq. 11) by which the searchlight tone map
/// divides XYZ, for mirrors of [`ToneMap::display_rgb_xyz`] (srt-gpu's spectral shading).
#[must_use]
pub fn searchlight_reference_ln_y() -> f64 {
    *LN_SEARCHLIGHT_REFERENCE_Y
}

/// Largest natural-log factor applied to relative XYZ (by either tone map, exposure included). Far
/// beyond it every channel saturates anyway; the cap keeps absurd temperatures and exposures from
/// producing ∞ − ∞ in Eq. 12.
const MAX_LN_SEARCHLIGHT_GAIN: f64 = 600.0;

/// A white of luminance 1 (only its Y is read): the reference of lights already divided by
/// their own whites ([`ToneMap::display_rgb_xyz_sum`]).
const UNIT_WHITE: ScaledXyz = ScaledXyz {
    relative: DVec3::Y,
    ln_scale: 0.0,
};

/// How black-body XYZ becomes display sRGB: the two colour tables of the paper's Fig. 6.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ToneMap {
    /// Fig. 6 left (the `doppler` effect mode): XYZ / Y → Eq. 12 → clamp negatives to 0 → Eq. 13
    /// → clamp to [0, 1]. Every temperature is fully bright; only its hue shows the Doppler shift.
    #[default]
    Luminance,
    /// Fig. 6 right (the `searchlight` effect mode): XYZ / Y(1500 K) → Eq. 12 → clamp negatives to
    /// 0 → Eq. 13 → C ↦ 0.6 · log₁₀(C + 1) → clamp to [0, 1]. About 1500 K is dark red, 3600 K and
    /// above are white, colder bodies fade to black.
    Searchlight,
}

impl ToneMap {
    /// Both tone maps, in the order of Fig. 6 (left, right).
    pub const ALL: [Self; 2] = [Self::Luminance, Self::Searchlight];

    /// Display sRGB, each component in [0, 1], of a black body at `temperature_k` seen with
    /// reflection factor f = 1 (the top row of Fig. 6), via Eq. 10–13 and this tone map.
    ///
    /// A non-finite or non-positive temperature gives black. [`ToneMap::Luminance`] is defined at
    /// every positive temperature (it needs only ratios of radiances); as T → 0 it tends to the
    /// colour of the 830 nm end of the table.
    #[must_use]
    pub fn display_rgb(self, temperature_k: f64) -> DVec3 {
        let light = blackbody_xyz_scaled(temperature_k);
        if light.relative.y <= 0.0 || !light.relative.is_finite() {
            return DVec3::ZERO;
        }
        self.map(light, light, 0.0)
    }

    /// [`ToneMap::display_rgb`] with an exposure: XYZ is multiplied by `exposure` before the tone
    /// map (so with [`ToneMap::Luminance`] an exposure above 1 saturates, below 1 darkens).
    ///
    /// Any positive finite exposure works, from far above 10⁶ to far below 10⁻²⁰, without
    /// overflow, NaN or ∞: the product is formed in the logarithmic domain.
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidTemperature`] unless the temperature is positive and finite,
    /// [`ColourError::InvalidExposure`] unless the exposure is.
    pub fn display_rgb_exposed(
        self,
        temperature_k: f64,
        exposure: f64,
    ) -> Result<DVec3, ColourError> {
        positive_finite(temperature_k, ColourError::InvalidTemperature)?;
        let light = blackbody_xyz_scaled(temperature_k);
        self.display_rgb_xyz(light, light, exposure)
    }

    /// Display sRGB in [0, 1] of arbitrary light `light`, given as [`ScaledXyz`], through this
    /// tone map with an exposure multiplier on XYZ.
    ///
    /// `white` is the light a perfect white reflector (or the emitter itself) would send: the
    /// luminance tone map divides by its Y, as Fig. 6 left divides a black body by its own Y; the
    /// searchlight tone map ignores it and divides by Y(1500 K), as Fig. 6 right. So
    /// `display_rgb_xyz(b, b, 1)` of a black body `b` is [`ToneMap::display_rgb`], and a grey
    /// reflector ρ under it gives linear RGB ρ times that black body's before Eq. 13.
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidExposure`] unless `exposure` is positive and finite. Black or
    /// invalid light (zero, negative or non-finite `white` luminance for the luminance map,
    /// non-finite `light`) gives black, not an error.
    pub fn display_rgb_xyz(
        self,
        light: ScaledXyz,
        white: ScaledXyz,
        exposure: f64,
    ) -> Result<DVec3, ColourError> {
        let ln_exposure = positive_finite(exposure, ColourError::InvalidExposure)?.ln();
        if !light.relative.is_finite() || light.ln_scale.is_nan() {
            return Ok(DVec3::ZERO);
        }
        let valid_white =
            white.relative.y > 0.0 && white.relative.is_finite() && !white.ln_scale.is_nan();
        if self == Self::Luminance && !valid_white {
            return Ok(DVec3::ZERO);
        }
        Ok(self.map(light, white, ln_exposure))
    }

    /// Display sRGB in [0, 1] of several lights falling on one place, each `(light, white,
    /// factor)` as [`ToneMap::display_rgb_xyz`] takes it with the exposure `exposure · factor`:
    /// they are summed as XYZ before the tone map (each divided by its own white's Y for the
    /// luminance map, each absolute for the searchlight map), so that light from several sources
    /// adds as light does. One term gives what [`ToneMap::display_rgb_xyz`] gives, up to
    /// rounding. Terms with a factor ≤ 0, invalid light or (luminance map) an invalid white are
    /// left out; none left is black.
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidExposure`] unless `exposure` is positive and finite.
    pub fn display_rgb_xyz_sum(
        self,
        terms: &[(ScaledXyz, ScaledXyz, f64)],
        exposure: f64,
    ) -> Result<DVec3, ColourError> {
        let ln_exposure = positive_finite(exposure, ColourError::InvalidExposure)?.ln();
        // Each term as relative XYZ times exp(ln): the light with its factor, over its white.
        let scaled = terms.iter().filter_map(|&(light, white, factor)| {
            let valid_light = light.relative.is_finite() && !light.ln_scale.is_nan();
            let valid_white =
                white.relative.y > 0.0 && white.relative.is_finite() && !white.ln_scale.is_nan();
            if !(valid_light && factor > 0.0 && factor.is_finite()) {
                return None;
            }
            let ln_white = match self {
                Self::Luminance if !valid_white => return None,
                Self::Luminance => white.ln_scale + white.relative.y.ln(),
                Self::Searchlight => 0.0,
            };
            Some((light.relative, light.ln_scale + factor.ln() - ln_white))
        });
        let ln_reference = scaled
            .clone()
            .map(|(_, ln)| ln)
            .fold(f64::NEG_INFINITY, f64::max);
        if !ln_reference.is_finite() {
            return Ok(DVec3::ZERO);
        }
        let sum = ScaledXyz {
            relative: scaled
                .map(|(relative, ln)| relative * (ln - ln_reference).exp())
                .sum(),
            ln_scale: ln_reference,
        };
        Ok(self.map(sum, UNIT_WHITE, ln_exposure))
    }

    /// The tone map proper: XYZ = `light` scaled (by the white's Y or by Y(1500 K)) and by
    /// exp(`ln_exposure`) → Eq. 12 → clamp negatives → Eq. 13 → (searchlight: 0.6 · log₁₀(C + 1))
    /// → clamp to [0, 1]. `light` must be finite; for the luminance map `white.relative.y > 0`.
    fn map(self, light: ScaledXyz, white: ScaledXyz, ln_exposure: f64) -> DVec3 {
        let xyz = match self {
            // With `light == white` and no exposure the factor is exp(0) = 1 exactly, so a black
            // body comes out as relative / Y, bit for bit.
            Self::Luminance => {
                let ln_gain =
                    (light.ln_scale - white.ln_scale + ln_exposure).min(MAX_LN_SEARCHLIGHT_GAIN);
                light.relative / white.relative.y * ln_gain.exp()
            }
            Self::Searchlight => {
                let ln_gain = (light.ln_scale - *LN_SEARCHLIGHT_REFERENCE_Y + ln_exposure)
                    .min(MAX_LN_SEARCHLIGHT_GAIN);
                light.relative * ln_gain.exp()
            }
        };
        let linear = xyz_to_linear_rgb(xyz).max(DVec3::ZERO);
        let encoded = linear.map(srgb_encode);
        let mapped = match self {
            Self::Luminance => encoded,
            Self::Searchlight => encoded.map(|c| 0.6 * (c + 1.0).log10()),
        };
        // NaN cannot arise (finite inputs, capped gain); `max`/`min` would map it to 0 anyway.
        mapped.clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// A short lower-case name: `"luminance"` or `"searchlight"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Luminance => "luminance",
            Self::Searchlight => "searchlight",
        }
    }
}

/// A 2D colour table as in Fig. 6: `width` × `height` display sRGB pixels,
/// row-major, row 0 at the top.
///
/// Column `i` shows temperature T = `t_min` + (`t_max` − `t_min`) · i / (width − 1) (linear in
/// T, as the paper's horizontal axis); row `j` scales by f = 1 − j / (height − 1), so the top row
/// is f = 1 and the bottom row f = 0. Pixel = f · `tone_map.display_rgb(T)` (the
/// `C_display` = `f_ar` · `C_sRGB` of §4.2). A single column shows `t_min`, a single row f = 1; a
/// zero width or height gives an empty table; invalid temperatures give black columns.
#[must_use]
pub fn colour_table(
    tone_map: ToneMap,
    t_min_k: f64,
    t_max_k: f64,
    width: usize,
    height: usize,
) -> Vec<[f32; 3]> {
    let fraction = |i: usize, n: usize| {
        if n > 1 {
            i as f64 / (n - 1) as f64
        } else {
            0.0
        }
    };
    let columns: Vec<DVec3> = (0..width)
        .map(|i| tone_map.display_rgb(t_min_k + (t_max_k - t_min_k) * fraction(i, width)))
        .collect();
    let mut table = Vec::with_capacity(width.saturating_mul(height));
    for j in 0..height {
        let f = 1.0 - fraction(j, height);
        table.extend(columns.iter().map(|&c| (f * c).as_vec3().to_array()));
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_temperatures_are_black() {
        for tone_map in ToneMap::ALL {
            for t in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                assert_eq!(tone_map.display_rgb(t), DVec3::ZERO, "{tone_map:?} at {t}");
            }
        }
    }

    #[test]
    fn absurd_temperatures_stay_in_range() {
        for tone_map in ToneMap::ALL {
            for t in [1e-3, 1.0, 1e9, 1e200, f64::MAX] {
                let c = tone_map.display_rgb(t);
                assert!(
                    c.cmpge(DVec3::ZERO).all() && c.cmple(DVec3::ONE).all(),
                    "{tone_map:?} {t}: {c}"
                );
            }
        }
        assert_eq!(ToneMap::Searchlight.display_rgb(1e200), DVec3::ONE);
    }

    #[test]
    fn lights_summed_before_the_tone_map_add_as_light() {
        let warm = crate::cie::blackbody_xyz_scaled(3000.0);
        let hot = crate::cie::blackbody_xyz_scaled(9000.0);
        for tone_map in ToneMap::ALL {
            // One term is the single light's display.
            let one = tone_map
                .display_rgb_xyz_sum(&[(warm, warm, 0.3)], 1.0)
                .unwrap();
            let single = tone_map.display_rgb_xyz(warm, warm, 0.3).unwrap();
            assert!((one - single).abs().max_element() < 1e-12, "{tone_map:?}");
            // Two halves are the whole; dark and invalid terms add nothing.
            let halves = [(hot, hot, 0.2), (hot, hot, 0.2), (warm, warm, 0.0)];
            let whole = tone_map.display_rgb_xyz(hot, hot, 0.4).unwrap();
            let summed = tone_map.display_rgb_xyz_sum(&halves, 1.0).unwrap();
            assert!((summed - whole).abs().max_element() < 1e-12, "{tone_map:?}");
            assert_eq!(tone_map.display_rgb_xyz_sum(&[], 1.0).unwrap(), DVec3::ZERO);
            // A warm and a hot light together are between each alone in hue: bluer than the
            // warm one, redder than the hot one (dim enough that no channel saturates).
            let dim = match tone_map {
                ToneMap::Luminance => 0.1,
                ToneMap::Searchlight => 1e-4,
            };
            let both = tone_map
                .display_rgb_xyz_sum(&[(warm, warm, dim), (hot, hot, dim)], 1.0)
                .unwrap();
            let ratio = |c: DVec3| c.z / c.x;
            let warm_alone = tone_map.display_rgb_xyz(warm, warm, dim).unwrap();
            let hot_alone = tone_map.display_rgb_xyz(hot, hot, dim).unwrap();
            assert!(
                ratio(warm_alone) < ratio(both) && ratio(both) < ratio(hot_alone),
                "{tone_map:?}: {warm_alone} {both} {hot_alone}"
            );
        }
    }
}
