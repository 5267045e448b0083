//! Moving lights on the CPU reference against independent computations in S alone (no Lorentz
//! transformation of the renderer's, no `RetardedLight`): the retarded event by bisection on the
//! light's worldline, D_in and r_L from their formulas, and shadows by sampling the null segment
//! through the occluder's contracted box as it moves (docs/physics.md, "Moving lights").

use glam::DVec3;
use srt_scene::{Effects, SceneDescription};
use srt_trace::{Arriving, Hit, Tracer};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 64;

/// A white ground at rest (top face z = 0) lit only by one moving light of 5000 K and strength
/// 10; Phong diffuse only. `occluder` adds a unit cube moving with β = (−0.5, 0, 0), at
/// (−4, 0, 1.2) at t = 0, between the light and the ground around ct = −8 (the events seen).
fn scene_file(light_beta: [f64; 3], effects: Effects, occluder: bool) -> String {
    let mut text = format!(
        r#"
name = "moving light"
[observer]
position = [0.0, -9.0, 7.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 50.0
ct = 6.0

[[light]]
position = [2.4, 0.5, 3.5]
beta = [{}, {}, {}]
temperature_k = 5000.0
strength = 10.0

[render]
effects = "{}"
ambient = 0.0
specular = 0.0
diffuse = 0.7

[[object]]
name = "ground"
shape = {{ type = "cube", size = 1.0 }}
scale = [40.0, 40.0, 0.02]
translate = [0.0, 0.0, -0.01]
"#,
        light_beta[0],
        light_beta[1],
        light_beta[2],
        effects.name()
    );
    if occluder {
        text.push_str(
            r#"
[[object]]
name = "occluder"
shape = { type = "cube", size = 1.0 }
beta = [-0.5, 0.0, 0.0]
offset = [-4.0, 0.0, 1.2]
"#,
        );
    }
    text
}

/// The retarded event (ct, x) of the light resting at `offset` + `beta`·ct that reaches the
/// event (`ct`, `at`): bisection on ct_E − ct = ‖x_E − x(ct)‖.
fn retarded(offset: DVec3, beta: DVec3, ct: f64, at: DVec3) -> (f64, DVec3) {
    let gap = |t: f64| (ct - t) - (at - offset - beta * t).length();
    let (mut lo, mut hi) = (ct - 1e4, ct);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    (t, offset + beta * t)
}

/// The colour-table terms (factor, temperature) with light in them.
fn lit_terms(light: Arriving) -> Vec<(f64, f64)> {
    let terms = match light {
        Arriving::Table {
            factor,
            temperature_k,
        } => vec![(factor, temperature_k)],
        Arriving::Tables(terms) => terms.iter().collect(),
        other => panic!("not a colour-table light: {other:?}"),
    };
    terms.into_iter().filter(|&(f, _)| f > 0.0).collect()
}

/// Every pixel's hit on the ground's top face.
fn ground_hits(tracer: &Tracer<'_>) -> Vec<Hit> {
    (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .filter_map(|(x, y)| tracer.hit_at_pixel(WIDTH, HEIGHT, x, y))
        .filter(|hit| hit.object == 0 && hit.emission.position.z.abs() < 1e-9)
        .collect()
}

#[test]
fn a_moving_light_shades_as_the_retarded_time_construction_says() {
    let offset = DVec3::new(2.4, 0.5, 3.5);
    for (beta, effects) in [
        (DVec3::new(0.8, 0.3, 0.0), Effects::Doppler),
        (DVec3::new(0.8, 0.3, 0.0), Effects::Searchlight),
        (DVec3::new(-0.6, 0.0, -0.2), Effects::Doppler),
        (DVec3::ZERO, Effects::Geometry),
    ] {
        let description =
            SceneDescription::from_toml_str(&scene_file(beta.to_array(), effects, false), "test")
                .unwrap();
        let (scene, _) = description.build(std::path::Path::new(".")).unwrap();
        let tracer = Tracer::new(&scene);
        let hits = ground_hits(&tracer);
        assert!(hits.len() > 3000, "{} ground pixels", hits.len());
        let mut worst = 0.0f64;
        for hit in &hits {
            let at = hit.emission.position;
            let (t, source) = retarded(offset, beta, hit.emission.ct, at);
            let tau = hit.emission.ct - t;
            let n = (at - source) / tau;
            let gamma = 1.0 / (1.0 - beta.length_squared()).sqrt();
            // The ground rests in S: D_in is the source's Doppler factor, r_L its distance.
            let relativistic = effects != Effects::Geometry;
            let d_in = if relativistic {
                1.0 / (gamma * (1.0 - beta.dot(n)))
            } else {
                1.0
            };
            let r_source = gamma * tau * (1.0 - beta.dot(n));
            let strength = if effects == Effects::Searchlight {
                10.0 / (r_source * r_source * d_in * d_in)
            } else {
                10.0 / (r_source * r_source)
            };
            // White (𝒢 = 1): ½(𝒢 + 1) = 1; the light comes from above: cos = −n_z.
            let expected = (0.7 * -n.z * strength, d_in * 5000.0);
            let terms = lit_terms(tracer.light(hit, [DVec3::X, DVec3::Y]));
            assert_eq!(terms.len(), 1, "{effects:?} at {at}: {terms:?}");
            let (factor, temperature) = terms[0];
            let error = ((factor - expected.0) / expected.0)
                .abs()
                .max(((temperature - expected.1) / expected.1).abs());
            worst = worst.max(error);
        }
        eprintln!(
            "{effects:?} β = {beta}: {} pixels, worst relative error {worst:e}",
            hits.len()
        );
        assert!(
            worst < 1e-6,
            "{effects:?} β = {beta}: worst relative error {worst:e}"
        );
    }
}

#[test]
fn a_moving_occluder_shadows_where_it_was_when_the_light_passed() {
    let offset = DVec3::new(2.4, 0.5, 3.5);
    let beta = DVec3::new(0.3, 0.0, 0.0);
    let description =
        SceneDescription::from_toml_str(&scene_file(beta.to_array(), Effects::Doppler, true), "t")
            .unwrap();
    let (scene, _) = description.build(std::path::Path::new(".")).unwrap();
    let tracer = Tracer::new(&scene);
    // The occluder's rest-frame coordinates of an event (ct, x) of S: boost along x by −0.5.
    let (occluder_offset, occluder_beta) = (DVec3::new(-4.0, 0.0, 1.2), -0.5f64);
    let occluder_gamma = 1.0 / (1.0 - occluder_beta * occluder_beta).sqrt();
    let depth_inside = |ct: f64, x: DVec3| {
        let d = x - occluder_offset;
        let rest = DVec3::new(occluder_gamma * (d.x - occluder_beta * ct), d.y, d.z);
        0.5 - rest.abs().max_element()
    };
    let (mut agree, mut shadowed, mut naive_disagrees) = (0, 0, 0);
    for hit in ground_hits(&tracer) {
        let at = hit.emission.position;
        let (t, source) = retarded(offset, beta, hit.emission.ct, at);
        // The deepest point of the null segment inside the occluder, and of the same segment
        // against the occluder frozen where it is at the surface event (the naive shadow).
        let samples = 4000;
        let (mut moving, mut frozen) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for k in 1..samples {
            let s = f64::from(k) / f64::from(samples);
            let (ct, x) = (t + s * (hit.emission.ct - t), source + s * (at - source));
            moving = moving.max(depth_inside(ct, x));
            frozen = frozen.max(depth_inside(hit.emission.ct, x));
        }
        if moving.abs() < 0.01 {
            continue; // too near the shadow's edge to classify by sampling
        }
        let expected_shadow = moving > 0.0;
        let rendered_shadow = lit_terms(tracer.light(&hit, [DVec3::X, DVec3::Y])).is_empty();
        assert_eq!(
            rendered_shadow, expected_shadow,
            "ground point {at} at ct {}: depth {moving}",
            hit.emission.ct
        );
        agree += 1;
        shadowed += usize::from(expected_shadow);
        naive_disagrees += usize::from((frozen > 0.0) != expected_shadow);
    }
    eprintln!(
        "{agree} ground pixels agree, {shadowed} in shadow, {naive_disagrees} not in the naive shadow's place"
    );
    assert!(
        agree > 3000 && shadowed > 100,
        "{agree} pixels, {shadowed} shadowed"
    );
    // The test tells the late shadow from the occluder's present one.
    assert!(
        naive_disagrees > 50,
        "{naive_disagrees} pixels differ from the naive shadow"
    );
}
