//! Stars seen by a moving observer, rendered by the reference: each star's image lies where the
//! closed-form aberration formula puts it (within 0.1 px) and has the colour of a black body at
//! D·T with D = γ(1 + β cos θ), computed here from the tone map directly, not from the colour
//! table the renderer samples.

use glam::{DVec2, DVec3};
use srt_color::ToneMap;
use srt_scene::sky::SkyImage;
use srt_scene::{Effects, Light, Observer, Scene, Shading, Sky, Star, SurfaceColour};
use srt_trace::{RenderSettings, Tracer};

const WIDTH: u32 = 640;
const HEIGHT: u32 = 480;
const FOV_Y_DEG: f64 = 60.0;

/// A scene of `stars` only, the observer moving along +y with `speed` and looking along +y.
fn sky_scene(stars: Vec<Star>, speed: f64, effects: Effects) -> Scene {
    Scene {
        name: "stars".into(),
        objects: Vec::new(),
        observer: Observer {
            projection: srt_scene::Projection::Perspective,
            stereo: None,
            position: DVec3::ZERO,
            direction: DVec3::Y,
            up: DVec3::Z,
            fov_y_deg: FOV_Y_DEG,
            time: 0.0,
        },
        light: Light {
            position: DVec3::ZERO,
            temperature_k: 6500.0,
            strength: 1.0,
        },
        lights: Vec::new(),
        shadows: true,
        shading: Shading::default(),
        effects,
        tone_map: effects.default_tone_map(),
        background: DVec3::ZERO,
        sky: Sky {
            beta: DVec3::new(0.0, -speed, 0.0),
            stars,
            // Faint enough that no channel clips.
            saturation_magnitude: -1.0,
            ..Sky::default()
        },
        colour: SurfaceColour::Paper,
        exposure: 1.0,
        cube_map_size: srt_scene::DEFAULT_CUBE_MAP_SIZE,
        world: srt_physics::Poincare::IDENTITY,
    }
}

/// The reference's picture of `scene`, one sample per pixel.
fn render(scene: &Scene) -> srt_trace::RenderedImage {
    Tracer::new(scene).render(
        RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            samples: 1,
        },
        &|_| {},
    )
}

/// A star in the x–y plane at angle `theta` from +y (towards +x), of magnitude 0.
fn star_at(theta: f64, temperature_k: f64) -> Star {
    Star {
        direction: DVec3::new(theta.sin(), theta.cos(), 0.0),
        temperature_k,
        magnitude: 0.0,
    }
}

/// The colour-weighted centroid (pixel centres at half-integers) and the summed colour of the
/// lit pixels within 3 px of `near`.
fn splat(image: &srt_trace::RenderedImage, near: DVec2) -> (DVec2, DVec3) {
    let mut weighted = DVec2::ZERO;
    let mut total = DVec3::ZERO;
    let mut weight = 0.0;
    for y in 0..image.height {
        for x in 0..image.width {
            let centre = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            if (centre - near).length() > 3.0 {
                continue;
            }
            let colour = image.pixels[(y * image.width + x) as usize];
            let w = colour.x + colour.y + colour.z;
            weighted += w * centre;
            weight += w;
            total += colour;
        }
    }
    (weighted / weight, total)
}

#[test]
fn stars_are_where_the_aberration_formula_puts_them_with_the_colour_of_d_t() {
    let speed = 0.8;
    let tan_half = (0.5 * FOV_Y_DEG.to_radians()).tan();
    let aspect = f64::from(WIDTH) / f64::from(HEIGHT);
    // Rest angles whose images stay inside the picture (|θ′| < the half field of view across).
    let cases = [(0.0, 6000.0), (0.9, 4000.0), (-1.3, 9000.0), (1.5, 3000.0)];
    let stars = cases.iter().map(|&(t, k)| star_at(t, k)).collect();
    let image = render(&sky_scene(stars, speed, Effects::Doppler));
    let gamma = 1.0 / (1.0 - speed * speed).sqrt();
    for (theta, temperature) in cases {
        // cos θ′ = (cos θ + β)/(1 + β cos θ), on the same side as θ.
        let cos_seen = (theta.cos() + speed) / (1.0 + speed * theta.cos());
        let seen = cos_seen.acos().copysign(theta);
        let expected = DVec2::new(
            0.5 * (1.0 + seen.tan() / (tan_half * aspect)) * f64::from(WIDTH),
            0.5 * f64::from(HEIGHT),
        );
        let (centroid, colour) = splat(&image, expected);
        assert!(
            (centroid - expected).length() < 0.1,
            "θ = {theta}: star seen at {centroid}, the formula says {expected}"
        );
        let doppler = gamma * (1.0 + speed * theta.cos());
        let planck = ToneMap::Luminance.display_rgb(doppler * temperature);
        // Magnitude 0 against a saturation magnitude of −1: weight 10^−0.4.
        let weight = 10f64.powf(-0.4);
        assert!(
            (colour - weight * planck).abs().max_element() < 3e-3,
            "θ = {theta}, D = {doppler}: colour {colour}, black body at D·T gives {}",
            weight * planck
        );
    }
}

#[test]
fn without_motion_the_sky_is_unshifted_and_the_searchlight_scales_flux_by_d_squared() {
    let star = star_at(0.0, 5000.0);
    let star_light = |speed, effects| {
        let image = render(&sky_scene(vec![star], speed, effects));
        splat(&image, DVec2::new(320.0, 240.0)).1
    };
    // At rest, geometry and Doppler modes agree: D = 1.
    let at_rest = star_light(0.0, Effects::Doppler);
    assert!((at_rest - star_light(0.0, Effects::Geometry)).length() < 1e-12);
    // Moving at 0.5c straight at it: D = √3; geometry ignores it.
    assert!((star_light(0.5, Effects::Geometry) - at_rest).length() < 1e-12);
    let doppler = 3f64.sqrt();
    let searchlight = star_light(0.5, Effects::Searchlight);
    let expected =
        ToneMap::Searchlight.display_rgb(doppler * 5000.0) * 10f64.powf(-0.4) / (doppler * doppler);
    assert!(
        (searchlight - expected).abs().max_element() < 3e-3,
        "{searchlight} against {expected}"
    );
}

/// An equirectangular image of `width` × `height` texels of colour `texel(longitude, latitude)`
/// (radians).
fn sky_image(width: u32, height: u32, texel: impl Fn(f64, f64) -> [f32; 3]) -> SkyImage {
    let texels: Vec<[f32; 3]> = (0..height)
        .flat_map(|row| (0..width).map(move |column| (row, column)))
        .map(|(row, column)| {
            let u = (f64::from(column) + 0.5) / f64::from(width);
            let v = (f64::from(row) + 0.5) / f64::from(height);
            texel(
                (u - 0.5) * std::f64::consts::TAU,
                (0.5 - v) * std::f64::consts::PI,
            )
        })
        .collect();
    SkyImage {
        width,
        height,
        texels: texels.into(),
        source: "test".into(),
    }
}

#[test]
fn a_sky_image_at_rest_shows_its_own_colours_in_spectral_colour() {
    let colour = [0.2f32, 0.5, 0.8];
    let mut scene = sky_scene(Vec::new(), 0.0, Effects::Doppler);
    scene.colour = SurfaceColour::Spectral;
    scene.sky.image = Some(sky_image(64, 32, |_, _| colour));
    let image = render(&scene);
    let expected = DVec3::from_array(colour.map(|c| srt_color::srgb_encode(f64::from(c))));
    for pixel in [0, 1000, 150_000, image.pixels.len() - 1] {
        // The texel is the light of a 6504 K black body filtered by its colour: at rest it is
        // the colour itself, up to the black body's white against D65's and the fit.
        let shown = image.pixels[pixel];
        assert!(
            (shown - expected).abs().max_element() < 0.03,
            "{shown} against {expected}"
        );
    }
}

#[test]
fn the_sky_image_is_aberrated_like_the_stars() {
    // A bright meridian at longitude 0 (+x, beside the observer's path along +y): moving at
    // 0.8c it is seen at cos θ′ = 0.8 from the direction of flight, 36.87° to the right.
    let speed = 0.8;
    let mut scene = sky_scene(Vec::new(), speed, Effects::Geometry);
    scene.sky.image = Some(sky_image(2048, 64, |longitude, _| {
        if longitude.abs() < 0.004 {
            [1.0; 3]
        } else {
            [0.0; 3]
        }
    }));
    let image = render(&scene);
    let row = (HEIGHT / 2) as usize * WIDTH as usize;
    let brightest = (0..WIDTH as usize)
        .max_by(|&a, &b| image.pixels[row + a].x.total_cmp(&image.pixels[row + b].x))
        .unwrap();
    let tan_half = (0.5 * FOV_Y_DEG.to_radians()).tan();
    let aspect = f64::from(WIDTH) / f64::from(HEIGHT);
    let seen = speed.acos();
    let expected = 0.5 * (1.0 + seen.tan() / (tan_half * aspect)) * f64::from(WIDTH);
    assert!(
        (brightest as f64 + 0.5 - expected).abs() < 1.5,
        "the meridian is seen at pixel {brightest}, the aberration formula says {expected}"
    );
    // At rest it is straight to the side, outside the picture: nothing lit in that row.
    let mut at_rest = sky_scene(Vec::new(), 0.0, Effects::Geometry);
    at_rest.sky.image = scene.sky.image.clone();
    let at_rest = render(&at_rest);
    assert!(
        at_rest.pixels[row..row + WIDTH as usize]
            .iter()
            .all(|p| p.x < 1e-3)
    );
}
