//! Bodies that spin or thrust on a frame at the fastest speeds `f64` can write,
//! |β| = 1 − 1.1·10⁻¹⁶ (`--beta=0.9999999999999999,0,0`) and |β| = 1 − 3·10⁻¹⁶ (`--beta` with
//! three components 0.5773502691896256): a point moving forward on such a body moves faster
//! still, and its β rounds to |β| = 1. Every built-in scene with a spinning or thrusting object
//! is traced there, and every pixel's radiance and every per-pixel channel `--aov` writes
//! (srt-trace's `SeenEvent`) must be a finite number.

use glam::DVec3;
use srt_physics::motion::Motion;
use srt_scene::{Overrides, SceneSource, builtin_scenes};
use srt_trace::{RenderSettings, Tracer};

const SETTINGS: RenderSettings = RenderSettings {
    width: 160,
    height: 90,
    samples: 1,
};

/// The velocities given to every object: the largest f64 below 1 along an axis (both ways), and
/// the largest diagonal whose length validates below 1.
fn fastest() -> [DVec3; 4] {
    let edge = 0.999_999_999_999_999_9;
    let diagonal = 0.577_350_269_189_625_6;
    [
        DVec3::new(edge, 0.0, 0.0),
        DVec3::new(-edge, 0.0, 0.0),
        DVec3::new(0.0, edge, 0.0),
        DVec3::splat(diagonal),
    ]
}

/// The built-in scenes with an object that spins or thrusts, as `srt render NAME --beta=β`
/// loads them (those that take `--beta`).
fn moving_scenes(beta: DVec3) -> Vec<(&'static str, srt_scene::Scene)> {
    let overrides = Overrides {
        beta: Some(beta),
        ..Overrides::default()
    };
    builtin_scenes()
        .iter()
        .filter_map(|builtin| {
            // A scene with a moving observer refuses `--beta` (the test names the scenes it
            // must see).
            let loaded = (SceneSource::resolve(builtin.name).unwrap())
                .load_with(&overrides)
                .ok()?;
            let moves = (loaded.scene.objects.iter()).any(|object| object.motion != Motion::Rest);
            moves.then_some((builtin.name, loaded.scene))
        })
        .collect()
}

#[test]
fn spinning_and_thrusting_bodies_at_the_fastest_f64_speeds_give_finite_pixels() {
    // Per scene, the pixels that see a spinning or thrusting body, at any of the velocities.
    let mut seen_moving = std::collections::BTreeMap::<&str, usize>::new();
    let mut bad = Vec::new();
    for beta in fastest() {
        for (name, scene) in moving_scenes(beta) {
            let moving = seen_moving.entry(name).or_default();
            let tracer = Tracer::new(&scene);
            let picture = tracer.render_radiance(SETTINGS, &|_| {});
            for (index, pixel) in picture.pixels.iter().enumerate() {
                if !pixel.is_finite() {
                    bad.push(format!("{name} at {beta}: pixel {index} radiance {pixel}"));
                }
            }
            for y in 0..SETTINGS.height {
                for x in 0..SETTINGS.width {
                    let Some(hit) = tracer.hit_at_pixel(SETTINGS.width, SETTINGS.height, x, y)
                    else {
                        continue;
                    };
                    if scene.objects[hit.object].motion != Motion::Rest {
                        *moving += 1;
                    }
                    let seen = tracer.seen_event(&hit);
                    let channels = [
                        seen.emission_ct,
                        seen.proper_time,
                        seen.distance,
                        seen.doppler,
                    ];
                    if !channels.iter().all(|c| c.is_finite()) {
                        bad.push(format!("{name} at {beta}: ({x}, {y}) channels {seen:?}"));
                    }
                }
            }
        }
    }
    // The rolling wheel spins, the rocket and Bell's ships thrust.
    for name in ["rolling-wheel", "rocket", "bell"] {
        let pixels = seen_moving.get(name).copied().unwrap_or(0);
        assert!(
            pixels > 0,
            "{name}'s moving bodies are not seen: {seen_moving:?}"
        );
    }
    assert_all_finite(&bad);
}

/// The built-in scene `name` as `srt render NAME --set KEY=VALUE …` loads it.
fn with_settings(name: &str, settings: &[String]) -> srt_scene::Scene {
    let overrides = Overrides {
        settings: (settings.iter())
            .map(|text| text.parse().unwrap())
            .collect(),
        ..Overrides::default()
    };
    (SceneSource::resolve(name).unwrap().load_with(&overrides))
        .unwrap_or_else(|e| panic!("{name} with {settings:?}: {e}"))
        .scene
}

/// Fails listing every non-finite value `non_finite` found.
fn assert_all_finite(bad: &[String]) {
    assert!(
        bad.is_empty(),
        "{} non-finite:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// Every pixel's radiance and every channel `--aov` writes, for a scene, in `bad` where not
/// finite; the number of pixels that see an object.
fn non_finite(label: &str, scene: &srt_scene::Scene, bad: &mut Vec<String>) -> usize {
    let tracer = Tracer::new(scene);
    let picture = tracer.render_radiance(SETTINGS, &|_| {});
    for (index, pixel) in picture.pixels.iter().enumerate() {
        if !pixel.is_finite() {
            bad.push(format!("{label}: pixel {index} radiance {pixel}"));
        }
    }
    let mut seen = 0;
    for y in 0..SETTINGS.height {
        for x in 0..SETTINGS.width {
            let Some(hit) = tracer.hit_at_pixel(SETTINGS.width, SETTINGS.height, x, y) else {
                continue;
            };
            seen += 1;
            let event = tracer.seen_event(&hit);
            let channels = [
                event.emission_ct,
                event.proper_time,
                event.distance,
                event.doppler,
            ];
            if !channels.iter().all(|c| c.is_finite()) {
                bad.push(format!("{label}: ({x}, {y}) channels {event:?}"));
            }
        }
    }
    seen
}

/// The lamp of `shadows` (a moving `[[light]]` and its glowing bulb) flying at the fastest
/// speeds, with each effect: its light, D_in, flux and late shadows give finite pixels, and the
/// plain moving objects of fig10-cube50 and teaser (`--beta`) give finite pixels too.
#[test]
fn moving_lights_and_uniform_motion_at_the_fastest_f64_speeds_give_finite_pixels() {
    let mut bad = Vec::new();
    for beta in fastest() {
        let value = format!("[{}, {}, {}]", beta.x, beta.y, beta.z);
        for effects in ["geometry", "doppler", "searchlight"] {
            let settings = [
                format!("light.1.beta={value}"),
                format!("object.lamp.beta={value}"),
                format!("render.effects={effects}"),
            ];
            let scene = with_settings("shadows", &settings);
            let seen = non_finite(&format!("shadows {settings:?}"), &scene, &mut bad);
            assert!(seen > 0, "shadows with {settings:?} sees nothing");
        }
        let overrides = Overrides {
            beta: Some(beta),
            ..Overrides::default()
        };
        for name in ["fig10-cube50", "teaser"] {
            let loaded = SceneSource::resolve(name).unwrap().load_with(&overrides);
            let scene = loaded.unwrap().scene;
            non_finite(&format!("{name} at {beta}"), &scene, &mut bad);
        }
    }
    assert_all_finite(&bad);
}

/// The ride (`observer.thrust`) of flythrough's observer at the fastest speeds: coasting at
/// |β| = 1 − 1.1·10⁻¹⁶ and braking from it, and accelerating from rest to rapidity 18
/// (|β| = 1 − 4.4·10⁻¹⁶): finite pixels.
#[test]
fn an_accelerating_observer_at_the_fastest_f64_speeds_gives_finite_pixels() {
    let edge = "0.9999999999999999";
    let lamp = "light.position=[0, 0, 1.6]".to_string();
    let rides = [
        vec![format!("observer.beta=[0, {edge}, 0]"), lamp.clone()],
        vec![
            format!("observer.beta=[0, {edge}, 0]"),
            "observer.thrust={ proper_acceleration = [0, -0.1, 0] }".into(),
            "observer.ct=20".into(),
            lamp.clone(),
        ],
        vec![
            "observer.beta=[0, 0, 0]".into(),
            "observer.thrust={ proper_acceleration = [0, 0.1, 0] }".into(),
            "observer.ct=180".into(),
            lamp,
        ],
    ];
    let mut bad = Vec::new();
    for settings in rides {
        for effects in ["doppler", "searchlight"] {
            let mut settings = settings.clone();
            settings.push(format!("render.effects={effects}"));
            let scene = with_settings("flythrough", &settings);
            non_finite(&format!("flythrough {settings:?}"), &scene, &mut bad);
        }
    }
    assert_all_finite(&bad);
}

/// A ride that carries the observer past the fastest speed `f64` writes (rapidity 40 from
/// rest, tanh 40 = 1 in f64) is refused with a reason that names `observer.thrust`.
#[test]
fn a_ride_past_the_fastest_f64_speed_is_refused_by_its_thrust() {
    let settings = [
        "observer.thrust={ proper_acceleration = [0, 0.1, 0] }",
        "observer.ct=400",
        "light.position=[0, 0, 1.6]",
    ];
    let overrides = Overrides {
        settings: settings.iter().map(|text| text.parse().unwrap()).collect(),
        ..Overrides::default()
    };
    let loaded = SceneSource::resolve("flythrough")
        .unwrap()
        .load_with(&overrides);
    let Err(error) = loaded else {
        panic!("a ride to rapidity 40 loads");
    };
    let message = error.to_string();
    assert!(
        message.contains("observer.thrust") && message.contains("rounds to 1"),
        "{message}"
    );
}
