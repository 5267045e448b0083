//! The whole sky through the exact tracer: every pixel of an equirectangular or fisheye image
//! traces its own ray (srt_scene::projection's conventions), so what a pinhole cannot show —
//! the sky folded forward by aberration, an object beside or behind the observer — is drawn
//! where the closed-form formulas put it.

use srt_scene::{Projection, SceneDescription};
use srt_trace::{RenderSettings, Tracer};

/// The sphere's radius and its distance from the observer.
const RADIUS: f64 = 5.0;
const DISTANCE: f64 = 100.0;

/// A sphere at rest in W, [`DISTANCE`] to the observer's right (+x), seen by an observer flying
/// along +y with `speed` and looking along +y through `projection`.
fn beside(speed: f64, projection: &str) -> srt_scene::Scene {
    let text = format!(
        "[observer]\nposition = [0.0, 0.0, 0.0]\ndirection = [0.0, 1.0, 0.0]\n\
         beta = [0.0, {speed}, 0.0]\nprojection = {projection}\n\
         [[object]]\nshape = {{ type = \"sphere\", radius = {RADIUS}, segments = 96 }}\n\
         offset = [{DISTANCE}, 0.0, 0.0]\n"
    );
    let description = SceneDescription::from_toml_str(&text, "test scene").unwrap();
    description.build(std::path::Path::new(".")).unwrap().0
}

/// The mean pixel position (x, y; centres at +0.5) of the pixels covered by an object.
fn covered_centroid(scene: &srt_scene::Scene, width: u32, height: u32) -> (f64, f64, u32) {
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    let image = Tracer::new(scene).render(settings, &|_| {});
    let (mut sx, mut sy, mut count) = (0.0, 0.0, 0);
    for (index, &covered) in image.coverage.iter().enumerate() {
        if covered > 0 {
            let index = u32::try_from(index).unwrap();
            sx += f64::from(index % width) + 0.5;
            sy += f64::from(index / width) + 0.5;
            count += 1;
        }
    }
    assert!(count > 0, "the sphere is seen");
    (sx / f64::from(count), sy / f64::from(count), count)
}

/// The angle from the direction of flight at which an observer moving with `speed` sees light
/// that arrives, in W, at the angle `theta` from it: cos θ′ = (cos θ + β) / (1 + β cos θ), the
/// aberration formula (the paper's Eq. 3 for the direction).
fn aberrated(theta: f64, speed: f64) -> f64 {
    ((theta.cos() + speed) / (1.0 + speed * theta.cos())).acos()
}

/// At rest the sphere is seen 90° to the right: a quarter of the way from the centre column to
/// the right edge of an equirectangular image, on the horizon. At 0.9c aberration moves it to
/// about arccos β = 25.84° from the direction of flight (the forward cone): exactly,
/// midway between the images of its two limbs (aberration maps circles on the sky to circles).
/// A pinhole looking forward with a 45° field cannot show it at rest at all.
#[test]
fn an_object_beside_the_observer_is_seen_where_aberration_puts_it() {
    let (width, height) = (2048, 1024);
    let equirectangular = "{ type = \"equirectangular\" }";
    let degrees_per_pixel = 360.0 / f64::from(width);
    let limb = (RADIUS / DISTANCE).asin();
    for speed in [0.0, 0.9] {
        let (near, far) = (
            aberrated(std::f64::consts::FRAC_PI_2 - limb, speed),
            aberrated(std::f64::consts::FRAC_PI_2 + limb, speed),
        );
        let expected_deg = (0.5 * (near + far)).to_degrees();
        if speed > 0.0 {
            assert!((expected_deg - 0.9_f64.acos().to_degrees()).abs() < 0.1);
        }
        let scene = beside(speed, equirectangular);
        assert_eq!(scene.observer.projection, Projection::Equirectangular);
        let (x, y, _) = covered_centroid(&scene, width, height);
        let longitude = (x / f64::from(width) - 0.5) * 360.0;
        let latitude = (0.5 - y / f64::from(height)) * 180.0;
        assert!(
            (longitude - expected_deg).abs() < 0.25 * degrees_per_pixel,
            "β = {speed}: seen at {longitude}°, expected {expected_deg}°"
        );
        assert!(
            latitude.abs() < 0.25 * degrees_per_pixel,
            "β = {speed}: {latitude}°"
        );
    }
    let pinhole = beside(0.0, "{ type = \"perspective\" }");
    let image = Tracer::new(&pinhole).render(
        RenderSettings {
            width: 64,
            height: 64,
            samples: 1,
        },
        &|_| {},
    );
    assert!(
        image.coverage.iter().all(|&c| c == 0),
        "a pinhole does not see it"
    );
}

/// A fisheye of 360° sees the whole sphere: the sphere at 90° to the right lies halfway from the
/// centre to the rim along the horizontal; outside the circle nothing is seen (the corners are
/// background).
#[test]
fn a_full_fisheye_puts_the_side_halfway_to_the_rim() {
    let size = 512;
    let scene = beside(0.0, "{ type = \"fisheye\", fov_deg = 360.0 }");
    let (x, y, _) = covered_centroid(&scene, size, size);
    let half = f64::from(size) / 2.0;
    assert!(((x - half) / half - 0.5).abs() < 0.5 / half, "x = {x}");
    assert!((y - half).abs() < 0.5, "y = {y}");
    let tracer = Tracer::new(&scene);
    assert!(tracer.hit_at_pixel(size, size, 0, 0).is_none());
}
