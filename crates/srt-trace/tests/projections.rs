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

/// The teaser's objects seen by an observer `shift` (in S) away from the scene's, with the
/// observer's other settings as `scene`'s and no stereo.
fn moved(scene: &srt_scene::Scene, shift: glam::DVec3) -> srt_scene::Scene {
    let mut moved = scene.clone();
    moved.observer.position += shift;
    moved.observer.stereo = None;
    moved
}

/// The image of `scene` at `width` × `height`, one sample per pixel.
fn pixels(scene: &srt_scene::Scene, width: u32, height: u32) -> Vec<glam::DVec3> {
    let settings = RenderSettings {
        width,
        height,
        samples: 1,
    };
    Tracer::new(scene).render(settings, &|_| {}).pixels
}

/// Whether two pixel values agree to rounding (the rays' points are computed in another order).
fn same(a: glam::DVec3, b: glam::DVec3) -> bool {
    (a - b).abs().max_element() <= 1e-9
}

/// A side-by-side stereo picture is two pictures of half the width: its left half is what an
/// observer d/2 to the left (along the camera's right axis) sees, its right half what one d/2
/// to the right sees — pixel for pixel, the stars included; the two halves differ (parallax).
#[test]
fn side_by_side_stereo_is_two_shifted_pinholes() {
    for name in ["teaser", "flythrough"] {
        let built = srt_scene::builtin::find_builtin(name).unwrap();
        let mut scene = built.build().unwrap().0;
        let separation = 2.0;
        scene.observer.stereo = Some(srt_scene::Stereo {
            eye_separation: separation,
        });
        let (width, height) = (96, 36);
        let both = pixels(&scene, width, height);
        let (_, right, _) = scene.observer.basis();
        let left_eye = pixels(&moved(&scene, -0.5 * separation * right), width / 2, height);
        let right_eye = pixels(&moved(&scene, 0.5 * separation * right), width / 2, height);
        let half = (width / 2) as usize;
        for y in 0..height as usize {
            for x in 0..half {
                let row = y * width as usize;
                assert!(
                    same(both[row + x], left_eye[y * half + x]),
                    "{name} left ({x}, {y})"
                );
                assert!(
                    same(both[row + half + x], right_eye[y * half + x]),
                    "{name} right ({x}, {y})"
                );
            }
        }
        assert_ne!(left_eye, right_eye, "{name}: the eyes see the same");
    }
}

/// Omni-directional stereo: the top half is the left eye's full sphere, the bottom the right
/// eye's, and each column's rays leave from ±d/2 perpendicular to its direction — so the centre
/// column (looking along f) of each half is what an observer d/2 along ∓r sees there, and the
/// column looking along −r (longitude −90°) what one d/2 along ±f sees.
#[test]
fn omni_directional_stereo_moves_each_column_sideways() {
    let built = srt_scene::builtin::find_builtin("flythrough").unwrap();
    let mut scene = built.build().unwrap().0;
    scene.observer.projection = Projection::Equirectangular;
    let separation = 4.0;
    scene.observer.stereo = Some(srt_scene::Stereo {
        eye_separation: separation,
    });
    let (width, height) = (64, 64);
    let both = pixels(&scene, width, height);
    let (forward, right, _) = scene.observer.basis();
    // Column 32 looks along f (longitude (32.5/64 − ½)·360° ≈ 0), column 16 along −r
    // (longitude ≈ −90°); a mono picture of half the height has the same longitudes.
    for (column, left_shift) in [
        (32u32, -0.5 * separation * right),
        (16, -0.5 * separation * forward),
    ] {
        let longitude =
            std::f64::consts::TAU * ((f64::from(column) + 0.5) / f64::from(width) - 0.5);
        let offset_right = longitude.cos() * right - longitude.sin() * forward;
        let left_eye = pixels(
            &moved(&scene, -0.5 * separation * offset_right),
            width,
            height / 2,
        );
        let right_eye = pixels(
            &moved(&scene, 0.5 * separation * offset_right),
            width,
            height / 2,
        );
        assert!((-0.5 * separation * offset_right - left_shift).length() < 0.1 * separation);
        for y in 0..(height / 2) as usize {
            let (top, bottom) = (
                both[y * width as usize + column as usize],
                both[(y + (height / 2) as usize) * width as usize + column as usize],
            );
            let index = y * width as usize + column as usize;
            assert!(same(top, left_eye[index]), "top ({column}, {y})");
            assert!(same(bottom, right_eye[index]), "bottom ({column}, {y})");
        }
    }
}

/// Bad stereo is named: a fisheye has no stereo layout, and the separation must be a finite
/// distance ≥ 0.
#[test]
fn bad_stereo_is_named() {
    for (projection, separation, reason) in [
        (
            "{ type = \"fisheye\" }",
            "0.1",
            "a fisheye has no stereo layout",
        ),
        (
            "{ type = \"equirectangular\" }",
            "-0.1",
            "finite distance ≥ 0",
        ),
        ("{ type = \"perspective\" }", "nan", "finite distance ≥ 0"),
    ] {
        let text = format!(
            "[observer]\nposition = [0.0, 0.0, 0.0]\ndirection = [0.0, 1.0, 0.0]\n\
             projection = {projection}\nstereo = {{ eye_separation = {separation} }}\n"
        );
        let error = SceneDescription::from_toml_str(&text, "stereo.toml")
            .unwrap()
            .validate()
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("observer.stereo") && error.contains(reason),
            "{error}"
        );
    }
}
