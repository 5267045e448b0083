//! Radiance: the light that reaches the observer, in linear BT.709 (Rec. 709 primaries), before
//! any tone map — what an EXR holds (docs/colour.md, "Radiance and display").
//!
//! Everything a renderer draws is one of two kinds of light:
//! - **a colour-table light** k · C(T): the paper's colour (k = f_ar of Eq. 18, T = D·T_light),
//!   an emitter with the paper's colour, a star, a sky image texel with the paper's colour. Its
//!   radiance is k · ℓ(T) / g;
//! - **a spectrum** (spectral colour): XYZ of the reflected or emitted light. Its radiance is
//!   linear BT.709 of that XYZ (Eq. 12, unclamped) times its geometric factor, over the same
//!   reference luminance, over g.
//!
//! ℓ(T) is the black body's linear BT.709 colour at T scaled to luminance 1 ([`RadianceTable`])
//! and, with the searchlight effect, times Y(T) / Y(T_lamp): brightness then follows the black
//! body's luminance, as the paper's searchlight does; without it (Doppler, geometry only) every
//! light keeps unit luminance and only its colour shifts. g = f_amb + f_diff + f_spec of a white
//! surface facing the lamp. So the unit is: **luminance 1 is what a white surface at rest shows
//! under the observer's lamp, facing it.**
//!
//! The display colour is not a function of this radiance: the paper's colour multiplies the
//! *tone-mapped* colour C(T) by k (its shortcut), so a renderer computes display and radiance from
//! the same (k, T) or XYZ, never one from the other.

use glam::DVec3;

use crate::cie::{ScaledXyz, blackbody_xyz_scaled};
use crate::lut::{LogTable, LutError, TemperatureLut};
use crate::rgb::xyz_to_linear_rgb;

/// ln Y stored for a temperature whose black body has no visible light left (instead of −∞,
/// which would make interpolation NaN).
const LN_Y_NONE: f32 = -1.0e4;

/// The black body's linear BT.709 colour at luminance 1 (RGB) and the natural log of its
/// luminance Y (alpha, absolute CIE Y in W·sr⁻¹·m⁻² up to the CIE table's constant), over log
/// temperature: the same range, size and sampling rule as the colour table
/// ([`TemperatureLut`], module `lut`), so the GPU can sample it the same way.
#[derive(Clone, Debug, PartialEq)]
pub struct RadianceTable {
    table: LogTable,
}

impl RadianceTable {
    /// The table over [`TemperatureLut::DEFAULT_RANGE_K`] with [`TemperatureLut::DEFAULT_SIZE`]
    /// texels.
    ///
    /// # Panics
    /// Never: the default parameters are valid (a test builds them).
    #[must_use]
    pub fn with_defaults() -> Self {
        let (t_min, t_max) = TemperatureLut::DEFAULT_RANGE_K;
        match Self::build(TemperatureLut::DEFAULT_SIZE, t_min, t_max) {
            Ok(table) => table,
            Err(e) => unreachable!("the default table parameters are valid: {e}"),
        }
    }

    /// The default table ([`Self::with_defaults`]), built once per process.
    #[must_use]
    pub fn shared() -> &'static Self {
        static TABLE: std::sync::OnceLock<RadianceTable> = std::sync::OnceLock::new();
        TABLE.get_or_init(Self::with_defaults)
    }

    /// The table over the temperatures of `lut` (its range and size), so that one index
    /// samples both: the [shared](Self::shared) one for the default table.
    ///
    /// # Panics
    /// Never: `lut`'s parameters were validated when it was built.
    #[must_use]
    pub fn for_lut(lut: &TemperatureLut) -> std::borrow::Cow<'static, Self> {
        let (t_min, t_max) = TemperatureLut::DEFAULT_RANGE_K;
        if (lut.size(), lut.t_min(), lut.t_max()) == (TemperatureLut::DEFAULT_SIZE, t_min, t_max) {
            return std::borrow::Cow::Borrowed(Self::shared());
        }
        match Self::build(lut.size(), lut.t_min(), lut.t_max()) {
            Ok(table) => std::borrow::Cow::Owned(table),
            Err(e) => unreachable!("a built colour table's parameters are valid: {e}"),
        }
    }

    /// The table with `size` texels from `t_min_k` to `t_max_k`, uniform in ln T.
    ///
    /// # Errors
    /// As [`TemperatureLut::build`].
    pub fn build(size: usize, t_min_k: f64, t_max_k: f64) -> Result<Self, LutError> {
        let table = LogTable::build(size, t_min_k, t_max_k, |t| {
            let body = blackbody_xyz_scaled(t);
            let y = body.relative.y;
            if !(y > 0.0 && body.relative.is_finite() && body.ln_scale.is_finite()) {
                return [0.0, 0.0, 0.0, LN_Y_NONE];
            }
            #[expect(clippy::cast_possible_truncation, reason = "f32 texels, as the GPU's")]
            let ln_y = (body.ln_scale + y.ln()).max(f64::from(LN_Y_NONE)) as f32;
            let [r, g, b] = xyz_to_linear_rgb(body.relative / y).as_vec3().to_array();
            [r, g, b, ln_y]
        })?;
        Ok(Self { table })
    }

    /// The RGBA texels (RGB: colour at luminance 1; alpha: ln Y), texel 0 at the lowest
    /// temperature.
    #[must_use]
    pub fn texels(&self) -> &[[f32; 4]] {
        self.table.texels()
    }

    /// The colour at luminance 1 and ln Y of a black body at `temperature_k`, interpolated as
    /// [`TemperatureLut::sample`] interpolates.
    #[must_use]
    pub fn sample(&self, temperature_k: f64) -> (DVec3, f64) {
        let [r, g, b, ln_y] = self.table.sample(temperature_k).map(f64::from);
        (DVec3::new(r, g, b), ln_y)
    }
}

/// What a renderer's pixels hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Output {
    /// Display colours through the tone map, in [0, 1].
    #[default]
    Display,
    /// Radiance (the `radiance` module's documentation), unclamped.
    Radiance,
}

/// What turns light into radiance in one image: the effect mode's brightness rule, the lamp's
/// luminance and the white surface's geometric factor g (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadianceScale {
    /// Brightness follows the black body's luminance (the searchlight effect).
    follows_luminance: bool,
    /// ln Y of the lamp's black body (from the table).
    ln_y_lamp: f64,
    /// 1 / g.
    inverse_white: f64,
}

impl RadianceScale {
    /// The scale for an image lit by a lamp at `lamp_temperature_k` whose white surface facing
    /// it has geometric factor `white_geometry` (f_amb + f_diff + f_spec); `follows_luminance`
    /// with the searchlight effect. A non-positive `white_geometry` counts as 1.
    #[must_use]
    pub fn new(
        table: &RadianceTable,
        follows_luminance: bool,
        lamp_temperature_k: f64,
        white_geometry: f64,
    ) -> Self {
        let g = if white_geometry > 0.0 && white_geometry.is_finite() {
            white_geometry
        } else {
            1.0
        };
        Self {
            follows_luminance,
            ln_y_lamp: table.sample(lamp_temperature_k).1,
            inverse_white: 1.0 / g,
        }
    }

    /// Whether brightness follows the black body's luminance (the searchlight effect).
    #[must_use]
    pub const fn follows_luminance(&self) -> bool {
        self.follows_luminance
    }

    /// ln Y of the lamp's black body, from the table.
    #[must_use]
    pub const fn ln_y_lamp(&self) -> f64 {
        self.ln_y_lamp
    }

    /// 1 / g, the white surface's geometric factor inverted.
    #[must_use]
    pub const fn inverse_white(&self) -> f64 {
        self.inverse_white
    }

    /// Radiance of the colour-table light `factor` · C(`temperature_k`).
    #[must_use]
    pub fn of_table_light(&self, table: &RadianceTable, factor: f64, temperature_k: f64) -> DVec3 {
        let (colour, ln_y) = table.sample(temperature_k);
        let brightness = if self.follows_luminance {
            (ln_y - self.ln_y_lamp).exp()
        } else {
            1.0
        };
        colour * (factor * brightness * self.inverse_white)
    }

    /// Radiance of the spectrum `light` times `factor` (its geometric factor, not the
    /// exposure); `white` is its luminance reference where brightness does not follow
    /// luminance (the perfect white reflector in its place, or the emitter at brightness 1).
    /// Black for light or a white that is not finite or has no luminance.
    #[must_use]
    pub fn of_spectrum(&self, light: ScaledXyz, white: ScaledXyz, factor: f64) -> DVec3 {
        let ln_reference = if self.follows_luminance {
            self.ln_y_lamp
        } else if white.relative.y > 0.0 {
            white.ln_scale + white.relative.y.ln()
        } else {
            return DVec3::ZERO;
        };
        let radiance = xyz_to_linear_rgb(light.relative)
            * ((light.ln_scale - ln_reference).exp() * factor * self.inverse_white);
        if radiance.is_finite() {
            radiance
        } else {
            DVec3::ZERO
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectral::{Reflectance, reflected_light, srgb_coefficient_table};
    use crate::tonemap::ToneMap;

    /// Y of linear BT.709 RGB (the middle row of Eq. 12's inverse).
    fn luminance(rgb: DVec3) -> f64 {
        crate::rgb::XYZ_TO_LINEAR_BT709.inverse().row(1).dot(rgb)
    }

    #[test]
    fn a_white_surface_at_rest_facing_the_lamp_has_luminance_one() {
        let table = RadianceTable::with_defaults();
        for follows in [false, true] {
            for lamp in [2800.0, 6500.0] {
                let scale = RadianceScale::new(&table, follows, lamp, 1.15);
                let white = scale.of_table_light(&table, 1.15, lamp);
                assert!(
                    (luminance(white) - 1.0).abs() < 1e-3,
                    "{follows} {lamp}: {white}"
                );
            }
        }
    }

    #[test]
    fn the_searchlight_brightens_what_approaches_and_the_doppler_mode_does_not() {
        let table = RadianceTable::with_defaults();
        let lamp = 5000.0;
        let searchlight = RadianceScale::new(&table, true, lamp, 1.0);
        let doppler = RadianceScale::new(&table, false, lamp, 1.0);
        // D = 2 (approaching) and D = 0.5 (receding).
        let (hot, cold) = (2.0 * lamp, 0.5 * lamp);
        assert!(luminance(searchlight.of_table_light(&table, 1.0, hot)) > 5.0);
        assert!(luminance(searchlight.of_table_light(&table, 1.0, cold)) < 0.2);
        for t in [hot, cold] {
            let y = luminance(doppler.of_table_light(&table, 1.0, t));
            assert!((y - 1.0).abs() < 1e-3, "{t}: {y}");
        }
        // The ratio is the black body's luminance ratio, against an integral computed here.
        // Tolerance 1e-4: the table's error is far smaller (linear in ln T over 4096 texels
        // across ln 10⁴, step h ≈ 2.2e-3, it errs by h²/8 · |d² ln Y / d(ln T)²| ≤ 3e-6 here,
        // the curvature being 4.9 at 5000 K; ln Y ≈ 14 stored in f32 rounds by 5e-7 twice;
        // Simpson's rule and the crate's 1 nm sum differ by 3e-8), while a table 0.1 % off in
        // temperature errs by 2.4e-3.
        let ratio = luminance(searchlight.of_table_light(&table, 1.0, hot));
        let expected = luminance_integral(hot) / luminance_integral(lamp);
        assert!(
            (expected / ratio - 1.0).abs() < 1e-4,
            "table ratio {ratio}, integral {expected}"
        );
    }

    /// The black body's luminance Y(T) up to a constant factor, independent of `cie`'s sums:
    /// Planck's law (Eq. 10) written out here, L ∝ λ⁻⁵ / (exp(c₂ / λT) − 1) (the factor 2hc²
    /// cancels in every ratio), times the CIE 1931 ȳ(λ) read here from the CSV the crate
    /// ships, integrated by the composite Simpson rule over its 471 samples (360–830 nm at
    /// 1 nm, 470 intervals).
    fn luminance_integral(temperature_k: f64) -> f64 {
        /// The second radiation constant c₂ = hc/k in m·K (CODATA 2018, exact).
        const C2: f64 = 1.438_776_877e-2;
        let samples: Vec<(f64, f64)> = include_str!("../data/cie1931_2deg_1nm.csv")
            .lines()
            .filter(|line| line.starts_with(|c: char| c.is_ascii_digit()))
            .map(|line| {
                let fields: Vec<f64> = line.split(',').map(|f| f.trim().parse().unwrap()).collect();
                (fields[0], fields[2])
            })
            .collect();
        assert!(
            samples.len() == 471
                && (samples.iter().enumerate()).all(|(k, s)| s.0 == 360.0 + k as f64),
            "360–830 nm at 1 nm"
        );
        let last = samples.len() - 1;
        let h = 1e-9;
        let sum: f64 = samples
            .iter()
            .enumerate()
            .map(|(k, &(nm, ybar))| {
                let weight = if k == 0 || k == last {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                let lambda = nm * 1e-9;
                weight * ybar / (lambda.powi(5) * (C2 / (lambda * temperature_k)).exp_m1())
            })
            .sum();
        sum * h / 3.0
    }

    #[test]
    fn a_grey_spectrum_has_the_radiance_of_the_table_light() {
        let table = RadianceTable::with_defaults();
        let grey = srgb_coefficient_table()
            .lookup(DVec3::splat(0.5))
            .map(Reflectance::new)
            .unwrap();
        let reflected = reflected_light(&grey, 4000.0, 1.3, 1.2).unwrap();
        for follows in [false, true] {
            let scale = RadianceScale::new(&table, follows, 4000.0, 1.0);
            let spectral = scale.of_spectrum(reflected.light, reflected.white, 1.0);
            let body = scale.of_table_light(&table, 1.0, 4000.0 * 1.3 * 1.2);
            // A grey reflector of albedo ½ sends half the white reflector's light, in its colour.
            let ratio = luminance(spectral) / luminance(body);
            assert!((ratio - 0.5).abs() < 0.02, "{follows}: {ratio}");
            assert!((spectral / luminance(spectral) - body / luminance(body)).length() < 0.02);
        }
        // The display of the same light is within [0, 1], its radiance is not bounded by 1.
        let bright = RadianceScale::new(&table, true, 4000.0, 1.0).of_spectrum(
            reflected.light,
            reflected.white,
            1.0,
        );
        assert!(luminance(bright) > 1.0);
        let shown = ToneMap::Searchlight
            .display_rgb_xyz(reflected.light, reflected.white, 1.0)
            .unwrap();
        assert!(shown.max_element() <= 1.0);
    }
}
