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
//!
//! Moving lights (docs/physics.md, "Moving lights") add their diffuse and specular terms: each
//! lights the point as it was at its retarded event ([`RetardedLight`]), from the direction its
//! light arrives in (aberrated into S′), at the temperature D_in·T it is seen with there, with
//! the strength s · D_in² / r_L² (the inverse square in its own frame, transformed as a plane
//! wave; the colour table's searchlight brightness already holds D_in⁴ of it, so there the factor
//! is s / r_L² · D_in⁻²). The lights of several sources add as light: colour-table lights as
//! their displays (the paper's colours are per light), spectra as XYZ before the tone map.

use glam::{DVec3, DVec4};
use srt_color::{
    RadianceScale, RadianceTable, Reflectance, ScaledXyz, TemperatureLut, ToneMap, emitted_light,
    reflected_light, srgb_coefficient_table, srgb_decode,
};
use srt_physics::{Event, FourVelocity, RetardedLight};
use srt_scene::{
    Effects, Emission, MAX_MOVING_LIGHTS, MovingLight, Shading, SurfaceColour, SurfaceOptics,
};

/// What the shading of one point needs to know about the surface there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Velocity of the surface's rest frame relative to S, as its four-velocity (finite where a
    /// point moving on a fast body has a β that rounds to |β| = 1).
    pub velocity: FourVelocity,
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
    /// The S time ct of the point's emission event (where the moving lights' light must arrive).
    pub emission_ct: f64,
}

impl SurfacePoint {
    /// The point's emission event in S (the event the observer sees).
    #[must_use]
    pub fn event(&self) -> Event {
        Event::new(self.emission_ct, self.apparent_position)
    }
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
    /// The lamp's strength (a multiplier on all its light; 0: no lamp).
    pub light_strength: f64,
    /// The lights moving on their own worldlines.
    pub moving_lights: &'a [MovingLight],
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
#[expect(
    clippy::large_enum_variant,
    reason = "the sums are fixed arrays so that shading a pixel allocates nothing"
)]
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
    /// Colour-table lights of several sources on one surface point (the lamp's and the moving
    /// lights'), each (factor, temperature): shown as the sum of their displays, measured as
    /// the sum of their radiances.
    Tables(Sources<(f64, f64)>),
    /// Spectra of several sources on one surface point, each (light, white, factor) as in
    /// [`Arriving::Spectrum`]: summed as XYZ before the tone map.
    Spectra(Sources<(ScaledXyz, ScaledXyz, f64)>),
}

/// Most light sources one surface point sums: the lamp and every moving light.
pub const MAX_SOURCES: usize = MAX_MOVING_LIGHTS + 1;

/// Up to [`MAX_SOURCES`] values, one per light source (a fixed array: [`Arriving`] stays
/// `Copy`, and shading allocates nothing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sources<T>([Option<T>; MAX_SOURCES]);

impl<T: Copy> Sources<T> {
    /// The values, from `values` (those beyond [`MAX_SOURCES`] are left out; scenes have fewer).
    fn collect(values: impl IntoIterator<Item = T>) -> Self {
        let mut sources = [None; MAX_SOURCES];
        for (slot, value) in sources.iter_mut().zip(values) {
            *slot = Some(value);
        }
        Self(sources)
    }

    /// The values, in order.
    pub fn iter(&self) -> impl Iterator<Item = T> + '_ {
        self.0.iter().flatten().copied()
    }
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
            Self::Tables(terms) => terms
                .iter()
                .map(|(factor, temperature_k)| factor * lut_colour(lut, temperature_k))
                .sum(),
            Self::Spectra(terms) => {
                let terms: Vec<_> = terms.iter().collect();
                lut.tone_map()
                    .display_rgb_xyz_sum(&terms, exposure)
                    .unwrap_or(DVec3::ZERO)
            }
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
            Self::Tables(terms) => terms
                .iter()
                .map(|(factor, temperature_k)| scale.of_table_light(table, factor, temperature_k))
                .sum(),
            Self::Spectra(terms) => terms
                .iter()
                .map(|(light, white, factor)| scale.of_spectrum(light, white, factor))
                .sum(),
            Self::Dark => DVec3::ZERO,
        }
    }
}

/// The light a surface point sends to the observer, every moving light reaching it (no
/// shadows: [`arriving_unless_shadowed`] takes them).
#[must_use]
pub fn arriving(point: &SurfacePoint, light: &Illumination<'_>) -> Arriving {
    arriving_unless_shadowed(point, light, &|_| false)
}

/// The light a surface point sends to the observer; `shadowed` says whether an object blocks
/// a moving light's light on its way to the point (asked only for lights the point faces).
#[must_use]
pub fn arriving_unless_shadowed(
    point: &SurfacePoint,
    light: &Illumination<'_>,
    shadowed: &dyn Fn(&RetardedLight) -> bool,
) -> Arriving {
    let incident = (point.apparent_position - light.light_position).normalize();
    let outgoing = (light.observer - point.apparent_position).normalize();
    let relativistic = light.effects != Effects::Geometry;
    // Eq. 17 in its two factors: light → surface and surface → observer.
    let (d_in, d_out) = if relativistic {
        (
            point.velocity.receiver_doppler(incident),
            point.velocity.doppler_factor(outgoing),
        )
    } else {
        (1.0, 1.0)
    };
    if let Some(emission) = point.optics.emission
        && emission.shines_at(point.proper_time)
    {
        return emitted(emission, d_out, light);
    }
    // Phong in S′: directions towards the light and towards the observer, aberrated (Eq. 4).
    let to_observer = point.velocity.reversed().aberrate(outgoing);
    // Two-sided surfaces: the normal facing the observer.
    let normal = if point.normal_rest.dot(to_observer) < 0.0 {
        -point.normal_rest
    } else {
        point.normal_rest
    };
    let phong = |propagation: DVec3| {
        let to_light = -point.velocity.reversed().aberrate(propagation);
        phong_terms(&light.shading, normal, to_light, to_observer)
    };
    let (diffuse, specular) = phong(incident);
    let geometry = light.light_strength * (light.shading.ambient + diffuse + specular);
    let lamp = Source {
        factor: geometry,
        temperature_k: light.light_temperature_k,
        d_in,
    };
    // The moving lights the point faces and no object shadows: their geometric factor with
    // the strength of their light (the module documentation).
    let follows_luminance = light.lut.tone_map() == ToneMap::Searchlight;
    let moving = light.moving_lights.iter().filter_map(|source| {
        let arriving = RetardedLight::reaching(&source.frame, point.event())?;
        let (diffuse, specular) = phong(arriving.direction);
        let terms = diffuse + specular;
        if terms <= 0.0 || source.strength <= 0.0 || shadowed(&arriving) {
            return None;
        }
        let d_in = if relativistic {
            arriving.doppler_to(point.velocity)
        } else {
            1.0
        };
        let r = arriving.source_distance;
        let strength = if follows_luminance && relativistic {
            source.strength / (r * r * d_in * d_in)
        } else {
            source.strength / (r * r)
        };
        Some(Source {
            factor: terms * strength,
            temperature_k: source.temperature_k,
            d_in,
        })
    });
    let mut sources = std::iter::once(lamp).chain(moving).peekable();
    match light.colour {
        SurfaceColour::Paper => {
            let grey = 0.5 * (grey_value(point.albedo) + 1.0);
            let table = |s: Source| (grey * s.factor, s.d_in * d_out * s.temperature_k);
            let first = table(sources.next().unwrap_or(lamp));
            if sources.peek().is_none() {
                return Arriving::Table {
                    factor: first.0,
                    temperature_k: first.1,
                };
            }
            Arriving::Tables(Sources::collect(
                std::iter::once(first).chain(sources.map(table)),
            ))
        }
        SurfaceColour::Spectral => spectral_arriving(point, d_out, sources),
    }
}

/// The light of `sources` reflected by the point's spectral reflectance (the Jakob–Hanika
/// spectrum of its albedo, with its bands) and shifted by `d_out` towards the observer.
fn spectral_arriving(
    point: &SurfacePoint,
    d_out: f64,
    sources: impl Iterator<Item = Source>,
) -> Arriving {
    let linear = point.albedo.truncate().map(srgb_decode);
    let Ok(reflectance) = srgb_coefficient_table()
        .lookup(linear.clamp(DVec3::ZERO, DVec3::ONE))
        .and_then(|polynomial| {
            Reflectance::with_bands(polynomial, point.optics.ultraviolet, point.optics.infrared)
        })
    else {
        // A surface that reflects nothing is black.
        return Arriving::Dark;
    };
    // A source at a temperature no table reaches gives no light.
    let spectrum = |s: Source| {
        reflected_light(&reflectance, s.temperature_k, s.d_in, d_out)
            .ok()
            .map(|reflected| (reflected.light, reflected.white, s.factor))
    };
    let mut sources = sources.peekable();
    let first = sources.next().and_then(spectrum);
    if sources.peek().is_none() {
        return first.map_or(Arriving::Dark, |(light, white, factor)| {
            Arriving::Spectrum {
                light,
                white,
                factor,
            }
        });
    }
    Arriving::Spectra(Sources::collect(
        first.into_iter().chain(sources.filter_map(spectrum)),
    ))
}

/// One source's light on a surface point before it is coloured: its geometric factor (with its
/// strength), its temperature and the Doppler factor it reaches the surface with.
#[derive(Debug, Clone, Copy)]
struct Source {
    factor: f64,
    temperature_k: f64,
    d_in: f64,
}

/// (f_diff, f_spec) of Eq. 18 for the unit directions (in S′) `to_light` and `to_observer` on
/// a surface with the unit normal `normal` (facing the observer); 0 where the light is behind it.
fn phong_terms(
    shading: &Shading,
    normal: DVec3,
    to_light: DVec3,
    to_observer: DVec3,
) -> (f64, f64) {
    let cos_light = normal.dot(to_light);
    if cos_light <= 0.0 {
        return (0.0, 0.0);
    }
    let reflected = 2.0 * cos_light * normal - to_light;
    let cos_spec = reflected.dot(to_observer).max(0.0);
    (
        shading.diffuse * cos_light,
        shading.specular * cos_spec.powf(shading.shininess),
    )
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
