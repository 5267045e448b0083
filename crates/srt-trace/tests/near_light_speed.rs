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
    assert!(
        bad.is_empty(),
        "{} non-finite:\n{}",
        bad.len(),
        bad.join("\n")
    );
}
