//! Relativistic Phong shading of one surface point (§4.2, Eq. 17–18, Fig. 9).
//!
//! All vectors handed in are unit vectors. The light and the observer rest in S; the surface
//! rests in S′ and moves with β. Directions are aberrated into S′ (Eq. 3–4) for the Phong terms.
//! Two ways to colour (docs/colour.md):
//! - the paper's (`SurfaceColour::Paper`): the combined Doppler factor (Eq. 17) shifts the
//!   light's Planck temperature, and C = f_ar · C_sRGB(D·T_light) with
//!   f_ar = ½(G + 1)(f_amb + f_diff + f_spec) (Eq. 18);
//! - spectral (`SurfaceColour::Spectral`): the surface colour becomes a reflectance spectrum
//!   (Jakob & Hanika 2019), lit by the black body at D_in·T the surface sees and shifted by D_out
//!   to the observer (Eq. 17 split into its two factors), with f_amb + f_diff + f_spec as the
//!   exposure of `srt_color::reflected_display_rgb`.
//!
//! An emitting surface shows the black body at D_out·T_e instead.

use glam::{DVec3, DVec4};
use srt_color::{
    RadianceScale, RadianceTable, Reflectance, ScaledXyz, TemperatureLut, emitted_light,
    reflected_light, srgb_coefficient_table, srgb_decode,
};
use srt_physics::{aberrate, doppler_factor, receiver_doppler};
use srt_scene::{Effects, Emission, Shading, SurfaceColour, SurfaceOptics};

/// What the shading of one point needs to know about the surface there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Velocity of the surface's rest frame.
    pub beta: DVec3,
    /// Interpolated unit normal in S′.
    pub normal_rest: DVec3,
    /// Apparent position of the point in S (Eq. 8).
    pub apparent_position: DVec3,
    /// Surface colour (texel × base colour × vertex colour), RGBA in [0, 1].
    pub albedo: DVec4,
    /// The object's ultraviolet and infrared reflectances and emission.
    pub optics: SurfaceOptics,
    /// The object's proper time ct′ at the point's emission event (a blinking emission's clock).
    pub proper_time: f64,
}

/// The light and observer side of shading, fixed per image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Illumination<'a> {
    /// Observer position in S.
    pub observer: DVec3,
    /// Light position in S.
    pub light_position: DVec3,
    /// Light Planck temperature in kelvin.
    pub light_temperature_k: f64,
    /// Phong parameters.
    pub shading: Shading,
    /// Effect mode (geometry forces D = 1).
    pub effects: Effects,
    /// Colour table C_sRGB(T) (already chosen for the tone map).
    pub lut: &'a TemperatureLut,
    /// How surfaces are coloured.
    pub colour: SurfaceColour,
    /// Multiplier on the light before the tone map (spectral colour).
    pub exposure: f64,
}

/// The weights (R, G, B) of the grey value 𝒢 of Eq. 18 (WGSL `GREY_WEIGHTS` in colour.wgsl,
/// checked by srt-gpu's `tests/reflect.rs`).
pub const GREY_WEIGHTS: [f64; 3] = [0.3, 0.59, 0.11];

/// Grey value 𝒢 = 0.3R + 0.59G + 0.11B of Eq. 18.
#[must_use]
pub fn grey_value(colour: DVec4) -> f64 {
    colour.truncate().dot(DVec3::from_array(GREY_WEIGHTS))
}

/// The light a renderer draws somewhere, before it is shown ([`Arriving::display`]) or
/// measured ([`Arriving::radiance`]): the two are computed from it, never one from the other
/// (srt-color's `radiance` module says why).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Arriving {
    /// The colour-table light `factor` · C(`temperature_k`): the paper's colour (f_ar of
    /// Eq. 18 at D·T), an emitter with the paper's colour, a star, a sky texel's grey value.
    Table {
        /// k.
        factor: f64,
        /// The apparent temperature T.
        temperature_k: f64,
    },
    /// A spectrum (spectral colour): its XYZ per unit `factor`, and the light the luminance
    /// tone map divides by (the white reflector in its place, or the emitter at brightness 1).
    Spectrum {
        /// XYZ of the light.
        light: ScaledXyz,
        /// The luminance reference.
        white: ScaledXyz,
        /// The geometric factor (f_amb + f_diff + f_spec, or a sky texel's brightness).
        factor: f64,
    },
    /// No light.
    Dark,
}

impl Arriving {
    /// Display colour (sRGB-encoded, not clamped) through the colour table `lut` and its tone
    /// map, spectra with `exposure`.
    #[must_use]
    pub fn display(&self, lut: &TemperatureLut, exposure: f64) -> DVec3 {
        match *self {
            Self::Table {
                factor,
                temperature_k,
            } => factor * lut_colour(lut, temperature_k),
            Self::Spectrum {
                light,
                white,
                factor,
            } => lut
                .tone_map()
                .display_rgb_xyz(light, white, exposure * factor)
                .unwrap_or(DVec3::ZERO),
            Self::Dark => DVec3::ZERO,
        }
    }

    /// Radiance (linear BT.709, the unit of srt-color's `radiance` module), exposure left out.
    #[must_use]
    pub fn radiance(&self, table: &RadianceTable, scale: &RadianceScale) -> DVec3 {
        match *self {
            Self::Table {
                factor,
                temperature_k,
            } => scale.of_table_light(table, factor, temperature_k),
            Self::Spectrum {
                light,
                white,
                factor,
            } => scale.of_spectrum(light, white, factor),
            Self::Dark => DVec3::ZERO,
        }
    }
}

/// The light a surface point sends to the observer.
#[must_use]
pub fn arriving(point: &SurfacePoint, light: &Illumination<'_>) -> Arriving {
    let incident = (point.apparent_position - light.light_position).normalize();
    let outgoing = (light.observer - point.apparent_position).normalize();
    // Eq. 17 in its two factors: light → surface and surface → observer.
    let (d_in, d_out) = match light.effects {
        Effects::Geometry => (1.0, 1.0),
        Effects::Doppler | Effects::Searchlight => (
            receiver_doppler(point.beta, incident),
            doppler_factor(point.beta, outgoing),
        ),
    };
    if let Some(emission) = point.optics.emission
        && emission.shines_at(point.proper_time)
    {
        return emitted(emission, d_out, light);
    }
    // Phong in S′: directions towards the light and towards the observer, aberrated (Eq. 4).
    let to_light = -aberrate(-point.beta, incident).normalize();
    let to_observer = aberrate(-point.beta, outgoing).normalize();
    // Two-sided surfaces: the normal facing the observer.
    let normal = if point.normal_rest.dot(to_observer) < 0.0 {
        -point.normal_rest
    } else {
        point.normal_rest
    };
    let cos_light = normal.dot(to_light);
    let (diffuse, specular) = if cos_light > 0.0 {
        let reflected = 2.0 * cos_light * normal - to_light;
        let cos_spec = reflected.dot(to_observer).max(0.0);
        (
            light.shading.diffuse * cos_light,
            light.shading.specular * cos_spec.powf(light.shading.shininess),
        )
    } else {
        (0.0, 0.0)
    };
    let geometry = light.shading.ambient + diffuse + specular;
    match light.colour {
        SurfaceColour::Paper => Arriving::Table {
            factor: 0.5 * (grey_value(point.albedo) + 1.0) * geometry,
            temperature_k: d_in * d_out * light.light_temperature_k,
        },
        SurfaceColour::Spectral => {
            let linear = point.albedo.truncate().map(srgb_decode);
            let reflectance = srgb_coefficient_table()
                .lookup(linear.clamp(DVec3::ZERO, DVec3::ONE))
                .and_then(|polynomial| {
                    Reflectance::with_bands(
                        polynomial,
                        point.optics.ultraviolet,
                        point.optics.infrared,
                    )
                });
            // A surface that reflects nothing (no light on it, a zero exposure), or a
            // temperature no table reaches, is black.
            reflectance
                .and_then(|r| reflected_light(&r, light.light_temperature_k, d_in, d_out))
                .map_or(Arriving::Dark, |reflected| Arriving::Spectrum {
                    light: reflected.light,
                    white: reflected.white,
                    factor: geometry,
                })
        }
    }
}

/// Display colour (sRGB-encoded RGB in [0, 1]) of a surface point.
#[must_use]
pub fn shade(point: &SurfacePoint, light: &Illumination<'_>) -> DVec3 {
    arriving(point, light)
        .display(light.lut, light.exposure)
        .clamp(DVec3::ZERO, DVec3::ONE)
}

/// The light of an emitting surface seen with Doppler factor `d_out`: the black body at
/// D_out·T_e, `brightness` times the luminance tone map's white — through the colour table with
/// the paper's colour, as a spectrum with spectral colour.
fn emitted(emission: Emission, d_out: f64, light: &Illumination<'_>) -> Arriving {
    let apparent = d_out * emission.temperature_k;
    match light.colour {
        SurfaceColour::Paper => Arriving::Table {
            factor: emission.brightness,
            temperature_k: apparent,
        },
        SurfaceColour::Spectral => {
            let seen = |brightness| emitted_light(emission.temperature_k, brightness, d_out);
            match (seen(emission.brightness), seen(1.0)) {
                (Ok(light), Ok(white)) => Arriving::Spectrum {
                    light,
                    white,
                    factor: 1.0,
                },
                _ => Arriving::Dark,
            }
        }
    }
}

/// The colour table's colour C_sRGB(T).
pub(crate) fn lut_colour(lut: &TemperatureLut, temperature_k: f64) -> DVec3 {
    let [r, g, b, _] = lut.sample(temperature_k);
    DVec3::new(f64::from(r), f64::from(g), f64::from(b))
}
