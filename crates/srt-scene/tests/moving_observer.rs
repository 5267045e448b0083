//! `[observer] beta`: parsing, saving, refusing bad velocities with the key named, and what
//! building a scene with a moving observer gives the renderers (everything in the observer's
//! rest frame; the physics itself is tested in srt-physics and, image against image, in
//! srt-trace).

use std::path::Path;

use glam::{DMat3, DVec3};
use srt_physics::{Event, lorentz_matrix};
use srt_scene::{SceneDescription, SceneErrorKind};

/// A scene with the observer moving with `beta` (TOML text of the vector), a light, a cube at
/// rest in W and a sphere moving along x.
fn scene(beta: &str) -> String {
    format!(
        r#"
[observer]
position = [0.0, -5.0, 1.0]
direction = [0.0, 1.0, 0.0]
beta = {beta}
ct = 2.0
[light]
position = [1.0, -6.0, 4.0]
[[object]]
name = "cube"
shape = {{ type = "cube" }}
offset = [0.0, 3.0, 0.0]
[[object]]
name = "sphere"
shape = {{ type = "sphere" }}
beta = [0.6, 0.0, 0.0]
offset = [-2.0, 1.0, 0.0]
"#
    )
}

fn parse(text: &str) -> SceneDescription {
    SceneDescription::from_toml_str(text, "moving.toml").expect("parses")
}

#[test]
fn observer_beta_is_read_written_and_defaults_to_rest() {
    let description = parse(&scene("[0.0, 0.8, 0.1]"));
    assert_eq!(description.observer.beta, [0.0, 0.8, 0.1]);
    let text = description.to_toml_string();
    assert!(text.contains("beta = [0.0, 0.8, 0.1]"), "{text}");
    assert_eq!(parse(&text), description);
    let at_rest = parse(&scene("[0.0, 0.0, 0.0]"));
    assert!(
        !at_rest
            .to_toml_string()
            .contains("[observer]\nposition = [0.0, -5.0, 1.0]\ndirection = [0.0, 1.0, 0.0]\nbeta"),
        "a resting observer's beta is not written"
    );
    let without = scene("[0.0, 0.0, 0.0]").replace("beta = [0.0, 0.0, 0.0]\nct", "ct");
    assert_eq!(parse(&without).observer.beta, [0.0; 3]);
}

#[test]
fn bad_observer_velocities_name_the_file_and_the_key() {
    for (beta, reason) in [
        ("[0.0, 1.0, 0.0]", "speed of light"),
        ("[0.8, 0.7, 0.0]", "speed of light"),
        ("[nan, 0.0, 0.0]", "not a finite number"),
        ("[0.0, inf, 0.0]", "not a finite number"),
    ] {
        let description = parse(&scene(beta));
        let error = description.validate().expect_err(beta);
        let built = description
            .build(Path::new("."))
            .expect_err(beta)
            .with_origin("moving.toml");
        for message in [error.to_string(), built.to_string()] {
            assert!(message.contains("observer.beta"), "{message}");
            assert!(message.contains(reason), "{message}");
        }
        assert!(built.to_string().starts_with("moving.toml: "), "{built}");
        assert!(matches!(built.kind(), SceneErrorKind::Value { .. }));
    }
}

#[test]
fn unknown_observer_keys_are_errors() {
    let text = scene("[0.0, 0.5, 0.0]").replace("beta =", "velocity =");
    let error = SceneDescription::from_toml_str(&text, "moving.toml").unwrap_err();
    let message = error.to_string();
    assert!(
        message.starts_with("moving.toml: line") && message.contains("velocity"),
        "{message}"
    );
}

#[test]
fn a_moving_observer_gets_the_scene_in_its_rest_frame() {
    let beta_o = DVec3::new(0.0, 0.8, 0.1);
    let description = parse(&scene("[0.0, 0.8, 0.1]"));
    let (moving, warnings) = description.build(Path::new(".")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let (resting, _) = parse(&scene("[0.0, 0.0, 0.0]"))
        .build(Path::new("."))
        .unwrap();
    // The observation event keeps its coordinates, the camera its orientation.
    assert_eq!(moving.observer, resting.observer);
    // The cube rests in W: it moves with −β_o; its geometry is not turned.
    let cube = &moving.objects[0];
    assert!((cube.frame.beta() + beta_o).length() < 1e-15);
    let cube_positions = cube.parts[0].mesh.positions();
    let rest_positions = resting.objects[0].parts[0].mesh.positions();
    for (a, b) in cube_positions.iter().zip(rest_positions) {
        assert!((*a - *b).length() < 1e-15);
    }
    // The sphere moves obliquely to the observer: composed velocity, geometry turned by the
    // Wigner rotation (rotations keep lengths, and it is not the identity).
    let sphere = &moving.objects[1];
    let relative = description.relative_frames().unwrap()[1];
    assert_eq!(sphere.frame, relative.frame);
    assert!(!(relative.rotation - DMat3::IDENTITY).abs_diff_eq(DMat3::ZERO, 1e-3));
    let turned = sphere.parts[0].mesh.positions();
    let original = resting.objects[1].parts[0].mesh.positions();
    for (a, b) in turned.iter().zip(original) {
        assert!((*a - relative.rotation * *b).length() < 1e-12);
    }
    // The light rests relative to the observer, at the S position of the W event (ct, x_light).
    let light_event = Event::new(2.0, DVec3::new(1.0, -6.0, 4.0));
    let e = Event::new(2.0, DVec3::new(0.0, -5.0, 1.0));
    let expected = Event::from_four_vector(
        lorentz_matrix(-beta_o) * (light_event.to_four_vector() - e.to_four_vector())
            + e.to_four_vector(),
    );
    assert!((moving.light.position - expected.position).length() < 1e-12);
    assert!((moving.light.position - resting.light.position).length() > 0.1);
}

#[test]
fn a_resting_observer_changes_nothing() {
    let explicit = parse(&scene("[0.0, 0.0, 0.0]"));
    let mut plain = explicit.clone();
    plain.observer.beta = [0.0; 3];
    assert_eq!(
        explicit.build(Path::new(".")).unwrap().0,
        plain.build(Path::new(".")).unwrap().0
    );
    let (scene, _) = explicit.build(Path::new(".")).unwrap();
    assert_eq!(scene.objects[1].frame.beta(), DVec3::new(0.6, 0.0, 0.0));
    assert_eq!(scene.objects[1].frame.offset(), DVec3::new(-2.0, 1.0, 0.0));
    assert_eq!(scene.light.position, DVec3::new(1.0, -6.0, 4.0));
}

/// The scene text with a star field, so that the sky's velocity follows the observer too.
fn scene_with_sky(beta: &str) -> String {
    format!("{}\n[sky]\nstar_field = 50\n", scene(beta))
}

#[test]
fn a_built_scene_follows_an_observer_edit_as_a_fresh_build_would_give_it() {
    let mut description = parse(&scene_with_sky("[0.0, 0.5, 0.0]"));
    let (mut built, _) = description.build(Path::new(".")).unwrap();
    let rotations_before: Vec<DMat3> = description
        .kinematics()
        .unwrap()
        .frames
        .iter()
        .map(|f| f.rotation)
        .collect();
    // One step of an observer's flight at constant velocity: along its worldline, turned.
    let observer = &mut description.observer;
    observer.ct += 3.0;
    observer.position[1] += 0.5 * 3.0;
    observer.direction = Some([0.3, 1.0, 0.1]);
    let kinematics = description.kinematics().unwrap();
    let (fresh, _) = description.build(Path::new(".")).unwrap();
    assert_ne!(built, fresh, "the edit moves the scene");
    // The moving sphere's geometry is turned by a Wigner rotation, the same after the step.
    let rotations: Vec<DMat3> = kinematics.frames.iter().map(|f| f.rotation).collect();
    assert!(rotations[1] != DMat3::IDENTITY);
    assert_eq!(rotations, rotations_before);
    built.follow(&kinematics);
    assert_eq!(built, fresh);
}

#[test]
fn kinematics_are_what_the_build_places_the_scene_with() {
    let description = parse(&scene_with_sky("[0.3, 0.4, 0.0]"));
    let (built, _) = description.build(Path::new(".")).unwrap();
    let kinematics = description.kinematics().unwrap();
    assert_eq!(kinematics.observer, built.observer);
    assert_eq!(kinematics.light, built.light);
    assert_eq!(kinematics.sky_beta, Some(built.sky.beta));
    assert!((built.sky.beta + DVec3::new(0.3, 0.4, 0.0)).length() < 1e-15);
    for (relative, object) in kinematics.frames.iter().zip(&built.objects) {
        assert_eq!(relative.frame, object.frame);
    }
    let without_sky = parse(&scene("[0.3, 0.4, 0.0]"));
    assert_eq!(without_sky.kinematics().unwrap().sky_beta, None);
}

/// The scene with a riding observer: starting at rest (or with `beta`), thrusting along +y with
/// proper acceleration 0.5 from its clock's `start` for `duration`, looking when its clock reads
/// `time`.
fn ride(beta: &str, start: f64, duration: f64, time: f64) -> SceneDescription {
    let text = scene_with_sky(beta).replace(
        "ct = 2.0\n",
        &format!(
            "ct = 2.0\ntime = {time:?}\nthrust = {{ proper_acceleration = [0.0, 0.5, 0.0], start = {start:?}, duration = {duration:?} }}\n"
        ),
    );
    parse(&text)
}

/// Whether two built scenes agree to rounding: the observer, the lamp, every object's frame
/// and the sky's velocity.
fn assert_close(a: &srt_scene::Scene, b: &srt_scene::Scene) {
    let close = |x: DVec3, y: DVec3| (x - y).length() <= 1e-9 * (1.0 + x.length());
    assert!(
        close(a.observer.position, b.observer.position),
        "{:?} {:?}",
        a.observer,
        b.observer
    );
    assert!((a.observer.time - b.observer.time).abs() <= 1e-9 * (1.0 + a.observer.time.abs()));
    assert_eq!(a.observer.direction, b.observer.direction);
    assert!(
        close(a.light.position, b.light.position),
        "{:?} {:?}",
        a.light,
        b.light
    );
    assert!(
        close(a.sky.beta, b.sky.beta),
        "{} {}",
        a.sky.beta,
        b.sky.beta
    );
    for (x, y) in a.objects.iter().zip(&b.objects) {
        assert!(close(x.frame.beta(), y.frame.beta()), "{}", x.name);
        assert!(close(x.frame.offset(), y.frame.offset()), "{}", x.name);
    }
}

/// A riding observer is drawn from its event and velocity alone: at each clock reading its
/// scene is the scene of the inertial observer on the closed-form hyperbolic worldline —
/// event (start + sinh(ατ)/α, (cosh(ατ) − 1)/α ŷ) and velocity tanh(ατ) ŷ, τ the clock since the
/// start — before the thrust, during it and coasting after it; the lamp rides along at its
/// offset in the ship's frame.
#[test]
fn a_riding_observer_sees_from_its_hyperbolic_worldline() {
    let (alpha, start, duration) = (0.5, 3.0, 4.0);
    for time in [1.0, 3.0, 4.5, 7.0, 9.5] {
        let riding = ride("[0.0, 0.0, 0.0]", start, duration, time);
        let (ridden, _) = riding.build(Path::new(".")).unwrap();
        // The closed form, in W (the ship starts at rest at (ct 2, (0, −5, 1)), its clock
        // reading W's time until the start).
        let tau = (time - start).clamp(0.0, duration);
        let eta = alpha * tau;
        let coasting = (time - start - duration).max(0.0);
        let ct = start.min(time) + eta.sinh() / alpha + eta.cosh() * coasting;
        let y = -5.0 + (eta.cosh() - 1.0) / alpha + eta.sinh() * coasting;
        let beta = eta.tanh();
        let inertial = parse(
            &scene_with_sky(&format!("[0.0, {beta:?}, 0.0]"))
                .replace(
                    "position = [0.0, -5.0, 1.0]\ndirection = [0.0, 1.0, 0.0]",
                    &format!("position = [0.0, {y:?}, 1.0]\ndirection = [0.0, 1.0, 0.0]"),
                )
                .replace("ct = 2.0\n", &format!("ct = {ct:?}\n"))
                // The lamp, 1 to the side, 1 behind and 3 above the ship in its frame: in W at ct,
                // its offset along the motion is shorter by γ.
                .replace(
                    "[light]\nposition = [1.0, -6.0, 4.0]",
                    &format!("[light]\nposition = [1.0, {:?}, 4.0]", y - 1.0 / eta.cosh()),
                ),
        );
        let (expected, _) = inertial.build(Path::new(".")).unwrap();
        assert_close(&ridden, &expected);
        let event = riding.observation_event().unwrap();
        assert!(
            (event.ct - ct).abs() < 1e-9 && (event.position.y - y).abs() < 1e-9,
            "{event:?}"
        );
    }
}

/// A ride's bad input is named: a zero or non-finite acceleration, a negative duration, a
/// thrust across a moving observer's velocity, a lamp beyond the ship's Rindler horizon.
#[test]
fn bad_rides_are_named() {
    let cases = [
        (
            ride("[0.0, 0.0, 0.0]", 0.0, 1.0, 1.0)
                .to_toml_string()
                .replace("0.5, 0.0]", "0.0, 0.0]"),
            "zero vector",
        ),
        (
            ride("[0.0, 0.0, 0.0]", 0.0, -1.0, 1.0).to_toml_string(),
            "must be ≥ 0",
        ),
        (
            ride("[0.3, 0.0, 0.0]", 0.0, 1.0, 1.0).to_toml_string(),
            "must be along observer.beta",
        ),
        (
            ride("[0.0, 0.0, 0.0]", 0.0, 1.0, 1.0)
                .to_toml_string()
                .replace("position = [1.0, -6.0, 4.0]", "position = [1.0, -8.0, 4.0]"),
            "Rindler horizon",
        ),
    ];
    for (text, reason) in cases {
        let description = parse(&text);
        let error = description.validate().expect_err(reason).to_string();
        assert!(
            error.contains("observer.thrust") && error.contains(reason),
            "{error}"
        );
        let built = description
            .build(Path::new("."))
            .expect_err(reason)
            .to_string();
        assert!(built.contains("observer.thrust"), "{built}");
    }
}
