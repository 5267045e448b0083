//! Spectral surface colour in the reference shading (`SurfaceColour::Spectral`): a grey surface
//! under a black body is exactly the black body at D_in·D_out·T (the paper's result, now through
//! the spectrum), coloured surfaces keep their colour at rest and shift *differently* when they
//! move (the paper's shortcut shifts them alike), and emitters show the black body at D·T_e.

use glam::{DVec3, DVec4};
use srt_color::{TemperatureLut, ToneMap};
use srt_physics::{FourVelocity, doppler_factor, receiver_doppler};
use srt_scene::{Effects, Emission, Shading, SurfaceColour, SurfaceOptics};
use srt_trace::{Illumination, SurfacePoint, shade};

/// Shading with only the ambient term (1), so the geometric factor is exactly 1.
fn flat() -> Shading {
    Shading {
        ambient: 1.0,
        diffuse: 0.0,
        specular: 0.0,
        shininess: 1.0,
    }
}

fn colour_of(albedo: [f64; 3], beta: DVec3, colour: SurfaceColour, optics: SurfaceOptics) -> DVec3 {
    let lut = TemperatureLut::with_defaults(ToneMap::Luminance);
    let light = Illumination {
        observer: DVec3::ZERO,
        light_position: DVec3::new(0.0, 0.0, 0.0),
        light_temperature_k: 6504.0,
        light_strength: 1.0,
        moving_lights: &[],
        shading: flat(),
        effects: Effects::Doppler,
        lut: &lut,
        colour,
        exposure: 1.0,
    };
    // A point straight ahead, moving with `beta`, lit from the observer's position.
    let point = SurfacePoint {
        velocity: FourVelocity::from_beta(beta),
        normal_rest: DVec3::NEG_Y,
        apparent_position: DVec3::new(0.0, 10.0, 0.0),
        albedo: DVec4::new(albedo[0], albedo[1], albedo[2], 1.0),
        optics,
        proper_time: 0.0,
        emission_ct: -10.0,
    };
    shade(&point, &light)
}

/// Hue angle in degrees of a display colour (HSV hue).
fn hue(c: DVec3) -> f64 {
    let max = c.max_element();
    let min = c.min_element();
    let d = max - min;
    let h = if max == c.x {
        60.0 * ((c.y - c.z) / d).rem_euclid(6.0)
    } else if max == c.y {
        60.0 * ((c.z - c.x) / d + 2.0)
    } else {
        60.0 * ((c.x - c.y) / d + 4.0)
    };
    h.rem_euclid(360.0)
}

#[test]
fn a_grey_surface_is_the_black_body_at_d_t() {
    for (grey, speed) in [(1.0, 0.0), (1.0, 0.3), (0.5, -0.4), (0.2, 0.6)] {
        let beta = DVec3::new(0.0, -speed, 0.0);
        let shown = colour_of(
            [grey; 3],
            beta,
            SurfaceColour::Spectral,
            SurfaceOptics::default(),
        );
        // Light from the observer's position to the point, and back.
        let d = receiver_doppler(beta, DVec3::Y) * doppler_factor(beta, DVec3::NEG_Y);
        // ρ in linear light: the sRGB-encoded albedo decodes to ρ_lin.
        let rho = srt_color::srgb_decode(grey);
        let expected = ToneMap::Luminance
            .display_rgb_exposed(d * 6504.0, rho)
            .unwrap();
        assert!(
            (shown - expected).abs().max_element() < 1e-9,
            "grey {grey} at {speed}c (D = {d}): {shown} against the black body at D·T {expected}"
        );
    }
}

#[test]
fn colours_keep_their_hue_at_rest_and_shift_differently_in_motion() {
    let red = [0.8, 0.1, 0.1];
    let blue = [0.1, 0.2, 0.8];
    let none = SurfaceOptics::default();
    let spectral = |albedo, speed: f64| {
        colour_of(
            albedo,
            DVec3::new(0.0, -speed, 0.0),
            SurfaceColour::Spectral,
            none,
        )
    };
    let paper = |albedo, speed: f64| {
        colour_of(
            albedo,
            DVec3::new(0.0, -speed, 0.0),
            SurfaceColour::Paper,
            none,
        )
    };
    // At rest under a white (6504 K) light, red is red and blue is blue.
    assert!(hue(spectral(red, 0.0)) < 15.0 || hue(spectral(red, 0.0)) > 345.0);
    assert!((200.0..250.0).contains(&hue(spectral(blue, 0.0))));
    // Approaching at 0.1c (D = 1.22 both ways): red moves towards yellow, blue towards violet
    // or out of the visible — each its own way; the paper's shortcut gives both the same hue.
    let (red_moving, blue_moving) = (spectral(red, 0.1), spectral(blue, 0.1));
    assert!(
        (15.0..90.0).contains(&hue(red_moving)),
        "red approaching: {red_moving}, hue {}",
        hue(red_moving)
    );
    assert!((hue(blue_moving) - hue(red_moving)).abs() > 60.0);
    let (red_paper, blue_paper) = (paper(red, 0.1), paper(blue, 0.1));
    assert!(
        (hue(red_paper) - hue(blue_paper)).abs() < 1e-6,
        "the shortcut colours by the light alone: {red_paper} {blue_paper}"
    );
}

#[test]
fn the_infrared_reflectance_is_what_a_fast_approach_shows() {
    // Approaching at 0.9c the observer sees the surface's reflectance at D_out·λ, far in the
    // infrared: a red paint that is black in the infrared looks black, one that reflects there
    // looks bright.
    let approach = DVec3::new(0.0, -0.9, 0.0);
    let optics = |infrared| SurfaceOptics {
        infrared: Some(infrared),
        ..SurfaceOptics::default()
    };
    let dark = colour_of(
        [0.8, 0.1, 0.1],
        approach,
        SurfaceColour::Spectral,
        optics(0.0),
    );
    let bright = colour_of(
        [0.8, 0.1, 0.1],
        approach,
        SurfaceColour::Spectral,
        optics(0.9),
    );
    assert!(dark.max_element() < 0.02, "{dark}");
    assert!(bright.max_element() > 0.5, "{bright}");
}

#[test]
fn emitters_show_the_black_body_at_d_t_in_both_colour_modes() {
    let optics = SurfaceOptics {
        emission: Some(Emission {
            temperature_k: 2000.0,
            brightness: 1.0,
            blink: None,
        }),
        ..SurfaceOptics::default()
    };
    let beta = DVec3::new(0.0, -0.5, 0.0);
    let d = doppler_factor(beta, DVec3::NEG_Y);
    let expected = ToneMap::Luminance.display_rgb(d * 2000.0);
    for colour in SurfaceColour::ALL {
        // The albedo and the light do not matter for an emitter.
        let shown = colour_of([0.3, 0.9, 0.1], beta, colour, optics);
        assert!(
            (shown - expected).abs().max_element() < 2e-3,
            "{colour:?}: {shown} against {expected}"
        );
    }
}
