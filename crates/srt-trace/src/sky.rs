//! The sky in the reference renderer: each star is seen in its aberrated direction with its
//! Doppler factor ([`srt_physics::distant_source_image`]), coloured like a light of the scene,
//! and splatted into the image with a tent filter over the four pixels around its exact
//! position, so that its light never falls between pixels and the weighted centroid of its
//! splat is its position. The sky image is looked up per viewing ray: the ray's direction is
//! taken back into the sky's frame (the inverse aberration) and the light found there is
//! Doppler-shifted like a surface's. The sky shows where no object is hit.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use srt_color::{Reflectance, TemperatureLut, reflected_light, srgb_coefficient_table};
use srt_physics::distant_source_image;
use srt_scene::sky::SKY_IMAGE_WHITE_K;
use srt_scene::{Effects, Observer, Scene, Sky, Star, SurfaceColour};

use crate::shade::{Arriving, grey_value};

/// Where one star lands in an image and with what colour.
#[derive(Debug, Clone, PartialEq)]
pub struct StarImage {
    /// Its positions in pixels (x right, y down; pixel centres at half-integers): one, or one
    /// in each eye's half of a stereo picture.
    pub pixels: Vec<DVec2>,
    /// The light the star adds at each position, spread over the four pixels around it
    /// ([`star_light`]).
    pub light: Arriving,
    /// Doppler factor of its light.
    pub doppler: f64,
}

/// The light a star adds to the image: its colour weight ([`Sky::weight`]) times the colour
/// table at D·T, the colour a surface lit by a black body at D·T gets (§4.2). With
/// [`Effects::Geometry`] D is 1; with [`Effects::Searchlight`] the weight is divided by D², the
/// factor by which aberration shrinks the solid angle of the star, so that its flux grows as
/// D⁴/D² = D² (the table's brightness carries the D⁴ of the radiance at D·T).
#[must_use]
pub fn star_light(star: &Star, doppler: f64, sky: &Sky, effects: Effects) -> Arriving {
    let (doppler, solid_angle) = match effects {
        Effects::Geometry => (1.0, 1.0),
        Effects::Doppler => (doppler, 1.0),
        Effects::Searchlight => (doppler, 1.0 / (doppler * doppler)),
    };
    Arriving::Table {
        factor: sky.weight(star.magnitude) * solid_angle,
        temperature_k: doppler * star.temperature_k,
    }
}

/// The display colour a star adds to the image: [`star_light`] through the colour table.
#[must_use]
pub fn star_colour(
    star: &Star,
    doppler: f64,
    sky: &Sky,
    effects: Effects,
    lut: &TemperatureLut,
) -> DVec3 {
    star_light(star, doppler, sky, effects).display(lut, 1.0)
}

/// Where `star` is seen from `observer` in an image of `width` × `height` pixels (`None` when it
/// is not in the picture: behind the camera, outside a fisheye), with its light.
#[must_use]
pub fn star_image(star: &Star, scene: &Scene, width: u32, height: u32) -> Option<StarImage> {
    let (direction, doppler) = star_seen(star, scene);
    let pixels: Vec<DVec2> = project(&scene.observer, direction, width, height)
        .into_iter()
        .flatten()
        .collect();
    (!pixels.is_empty()).then(|| StarImage {
        pixels,
        light: star_light(star, doppler, &scene.sky, scene.effects),
        doppler,
    })
}

/// The direction (in S) `star` is seen in and the Doppler factor of its light.
fn star_seen(star: &Star, scene: &Scene) -> (DVec3, f64) {
    let rest_direction = (scene.sky.direction_map * star.direction).normalize();
    distant_source_image(scene.sky.beta, rest_direction)
}

/// The light the sky image shows in the viewing direction `direction` (in S; any length);
/// none without an image.
///
/// The direction is taken back into the sky's frame (`distant_source_image` with −β gives the
/// direction there and the reciprocal Doppler factor) and through the inverse of the sky's
/// `direction_map`, the image is sampled there ([`srt_scene::sky::SkyImage::sample`]) and
/// scaled by `image_brightness`. The texel's light is that of a black body at
/// [`SKY_IMAGE_WHITE_K`] filtered by the texel's colour, seen with the Doppler factor D (1 for
/// geometry only): with the paper's colour, its grey value 𝒢 (Eq. 18) times the colour table at
/// D·T; with spectral colour, the texel's reflectance spectrum (Jakob & Hanika) under that black
/// body, shifted by D, its brightness s = the largest channel as its factor.
#[must_use]
pub fn sky_image_light(scene: &Scene, direction: DVec3) -> Arriving {
    let sky = &scene.sky;
    let Some(image) = &sky.image else {
        return Arriving::Dark;
    };
    let (rest_direction, inverse_doppler) = distant_source_image(-sky.beta, direction.normalize());
    let world = (sky.direction_map.inverse() * rest_direction).normalize();
    let radiance = image.sample(world) * sky.image_brightness;
    let doppler = match scene.effects {
        Effects::Geometry => 1.0,
        Effects::Doppler | Effects::Searchlight => 1.0 / inverse_doppler,
    };
    match scene.colour {
        SurfaceColour::Paper => Arriving::Table {
            factor: grey_value(radiance.extend(1.0)),
            temperature_k: doppler * SKY_IMAGE_WHITE_K,
        },
        SurfaceColour::Spectral => {
            let brightness = radiance.max_element();
            // Black (and a NaN, which the image loader refuses anyway) shows nothing.
            if brightness.is_nan() || brightness <= 0.0 {
                return Arriving::Dark;
            }
            srgb_coefficient_table()
                .lookup((radiance / brightness).clamp(DVec3::ZERO, DVec3::ONE))
                .and_then(|polynomial| {
                    reflected_light(
                        &Reflectance::new(polynomial),
                        SKY_IMAGE_WHITE_K,
                        1.0,
                        doppler,
                    )
                })
                .map_or(Arriving::Dark, |reflected| Arriving::Spectrum {
                    light: reflected.light,
                    white: reflected.white,
                    factor: brightness,
                })
        }
    }
}

/// The display colour (sRGB-encoded, not clamped) the sky image shows in the viewing direction
/// `direction`: [`sky_image_light`] through the colour table, spectra with the scene's exposure.
#[must_use]
pub fn sky_image_colour(scene: &Scene, lut: &TemperatureLut, direction: DVec3) -> DVec3 {
    sky_image_light(scene, direction).display(lut, scene.exposure)
}

/// The pixel positions of a direction far away, `direction` (in S), in the image of `observer`,
/// in its projection: the inverse of the pixel's viewing ray
/// ([`srt_scene::ViewRays::image_points`]), one position, or one in each eye's half of a
/// stereo picture; `None` where the direction is not in the picture (behind a pinhole, outside
/// a fisheye).
#[must_use]
pub fn project(
    observer: &Observer,
    direction: DVec3,
    width: u32,
    height: u32,
) -> [Option<DVec2>; 2] {
    let aspect = f64::from(width) / f64::from(height);
    observer
        .view_rays(aspect)
        .image_points(direction)
        .map(|point| {
            point.map(|ndc| {
                DVec2::new(
                    0.5 * (ndc.x + 1.0) * f64::from(width),
                    0.5 * (1.0 - ndc.y) * f64::from(height),
                )
            })
        })
}

/// The four pixels around `pixel` (centres at half-integers) and their tent weights, which sum
/// to 1 and whose weighted mean of pixel centres is `pixel`; pixels outside the image are left
/// out.
pub fn tent_splat(pixel: DVec2, width: u32, height: u32) -> impl Iterator<Item = (usize, f64)> {
    let corner = pixel - DVec2::splat(0.5);
    let base = corner.floor();
    let fraction = corner - base;
    [(0, 0), (1, 0), (0, 1), (1, 1)]
        .into_iter()
        .filter_map(move |(dx, dy)| {
            let x = base.x + f64::from(dx);
            let y = base.y + f64::from(dy);
            let inside = x >= 0.0 && y >= 0.0 && x < f64::from(width) && y < f64::from(height);
            let weight = (if dx == 0 {
                1.0 - fraction.x
            } else {
                fraction.x
            }) * (if dy == 0 {
                1.0 - fraction.y
            } else {
                fraction.y
            });
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // inside
            inside.then(|| ((y as usize) * width as usize + x as usize, weight))
        })
}

/// The light the stars add to the pixels they land on, each star's [`Arriving`] light turned
/// into a pixel value by `value` (display colour or radiance; not clamped): sparse, so that it
/// costs memory per star, not per pixel, at any image size.
#[must_use]
pub fn star_layer(
    scene: &Scene,
    width: u32,
    height: u32,
    value: &dyn Fn(&Arriving) -> DVec3,
) -> StarLayer {
    let mut lit = BTreeMap::new();
    let aspect = f64::from(width) / f64::from(height);
    // Each eye's half of a stereo picture is a picture of its own: a star's splat stays in it.
    let pictures = scene.observer.view_rays(aspect).eye_pictures(width, height);
    for star in &scene.sky.stars {
        let (direction, doppler) = star_seen(star, scene);
        let colour = value(&star_light(star, doppler, &scene.sky, scene.effects));
        for ([left, top, picture_width, picture_height], rays) in &pictures {
            let Some(ndc) = rays.image_point(direction) else {
                continue;
            };
            let pixel = DVec2::new(
                0.5 * (ndc.x + 1.0) * f64::from(*picture_width),
                0.5 * (1.0 - ndc.y) * f64::from(*picture_height),
            );
            for (index, weight) in tent_splat(pixel, *picture_width, *picture_height) {
                let (x, y) = (
                    index % *picture_width as usize,
                    index / *picture_width as usize,
                );
                let whole = (y + *top as usize) * width as usize + x + *left as usize;
                *lit.entry(whole).or_insert(DVec3::ZERO) += weight * colour;
            }
        }
    }
    StarLayer { lit }
}

/// The stars' light on an image ([`star_layer`]): the pixels some star lands on, by row-major
/// index from the top; every other pixel gets none.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StarLayer {
    /// The light of each lit pixel, by row-major index.
    lit: BTreeMap<usize, DVec3>,
}

impl StarLayer {
    /// The stars' light on the pixel of row-major index `index` (zero where no star lands).
    #[must_use]
    pub fn at(&self, index: usize) -> DVec3 {
        self.lit.get(&index).copied().unwrap_or(DVec3::ZERO)
    }

    /// How many pixels some star lands on.
    #[must_use]
    pub fn len(&self) -> usize {
        self.lit.len()
    }

    /// Whether no star lands on the image.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.lit.is_empty()
    }
}
