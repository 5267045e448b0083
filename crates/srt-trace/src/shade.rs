//! Relativistic Phong shading of one surface point (§4.2, Eq. 17–18, Fig. 9).
//!
//! All vectors handed in are unit vectors. The light and the observer rest in S; the surface
//! rests in S′ and moves with β. Directions are aberrated into S′ (Eq. 3–4) for the Phong terms,
//! the combined Doppler factor (Eq. 17) shifts the light's Planck temperature, and the colour is
//! C = f_ar · C_sRGB(D·T_light) with f_ar = ½(G + 1)(f_amb + f_diff + f_spec) (Eq. 18).

use glam::{DVec3, DVec4};
use srt_color::TemperatureLut;
use srt_physics::{aberrate, reflection_doppler};
use srt_scene::{Effects, Shading};

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
}

/// Grey value 𝒢 = 0.3R + 0.59G + 0.11B of Eq. 18.
#[must_use]
pub fn grey_value(colour: DVec4) -> f64 {
    0.3 * colour.x + 0.59 * colour.y + 0.11 * colour.z
}

/// Display colour (sRGB-encoded RGB in [0, 1]) of a surface point.
#[must_use]
pub fn shade(point: &SurfacePoint, light: &Illumination<'_>) -> DVec3 {
    let incident = (point.apparent_position - light.light_position).normalize();
    let outgoing = (light.observer - point.apparent_position).normalize();
    let doppler = match light.effects {
        Effects::Geometry => 1.0,
        Effects::Doppler | Effects::Searchlight => {
            reflection_doppler(point.beta, incident, outgoing)
        }
    };
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
    let f_ar =
        0.5 * (grey_value(point.albedo) + 1.0) * (light.shading.ambient + diffuse + specular);
    let [r, g, b, _] = light.lut.sample(doppler * light.light_temperature_k);
    (f_ar * DVec3::new(f64::from(r), f64::from(g), f64::from(b))).clamp(DVec3::ZERO, DVec3::ONE)
}
