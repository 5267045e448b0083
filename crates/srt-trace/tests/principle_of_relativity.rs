//! The principle of relativity, pixel for pixel: a scene rendered with the observer moving
//! through it (`[observer] beta`) is the same picture as the scene written down in the
//! observer's own frame by hand — observer at rest, every worldline, the observation event and
//! the light mapped by the Lorentz transformation — rendered with the observer at rest.
//!
//! The hand-written counterpart does not use `MovingObserver`: worldlines are mapped event by
//! event with Λ (Eq. 2), velocities and offsets read off the mapped events, the coordinates of S
//! are chosen differently (S's origin at W's at t = 0, not at the observation event), and moving
//! objects are turned by the closed-form Thomas–Wigner rotation (Rhodes and Semon, Am. J. Phys.
//! 72, 943 (2004), Eq. 3), not by the matrix decomposition the scene builder uses.

use std::path::Path;

use glam::{DMat3, DMat4, DVec3};
use srt_physics::{Event, lorentz_factor, lorentz_matrix};
use srt_scene::{LightsDescription, Scene, SceneDescription};
use srt_trace::{RenderSettings, Tracer};

/// Objects at rest or moving in W, a light, an observer looking along +y; doppler colours, so
/// the Doppler factors of the moving frames show.
const WORLD: &str = r#"
name = "principle"
[observer]
position = [0.0, -2.0, 0.6]
direction = [0.1, 1.0, -0.05]
fov_y_deg = 70.0
ct = 1.5
[light]
position = [2.0, -3.0, 4.0]
temperature_k = 4000.0
[render]
effects = "doppler"
background = [0.1, 0.1, 0.2]
[[object]]
name = "cube"
shape = { type = "cube", size = 1.5, subdivisions = 2 }
texture = { type = "checker", squares = 4 }
offset = [-0.8, 4.0, 0.2]
rotate_deg = [10.0, 0.0, 25.0]
[[object]]
name = "sphere"
shape = { type = "sphere", radius = 0.7, segments = 24 }
texture = { type = "checker", squares = 6 }
offset = [1.5, 6.0, 0.0]
[[object]]
name = "floor"
shape = { type = "cube", size = 1.0 }
texture = { type = "checker", squares = 16 }
scale = [8.0, 30.0, 0.1]
offset = [0.0, 8.0, -1.2]
"#;

const SETTINGS: RenderSettings = RenderSettings {
    width: 80,
    height: 60,
    samples: 4,
};

fn world() -> SceneDescription {
    SceneDescription::from_toml_str(WORLD, "principle").expect("the test scene parses")
}

fn build(description: &SceneDescription) -> Scene {
    description
        .build(Path::new("."))
        .expect("the test scene builds")
        .0
}

fn render(scene: &Scene) -> Vec<[u8; 3]> {
    Tracer::new(scene).render(SETTINGS, &|_| {}).to_rgb8()
}

/// The Lorentz transformation W → S of the observer moving with `beta_o`, origins together at
/// t = 0: x_S = Λ_−β_o x_W (Eq. 1 with a = 0).
fn to_observer(beta_o: DVec3, event: Event) -> Event {
    Event::from_four_vector(lorentz_matrix(-beta_o) * event.to_four_vector())
}

/// The Thomas–Wigner rotation of Λ_a Λ_b in closed form: angle from Rhodes and Semon's Eq. 3,
/// about −(a × b) (the sense `srt-physics`' tests establish against the matrix product).
fn wigner_rotation(a: DVec3, b: DVec3) -> DMat3 {
    let normal = a.cross(b);
    if normal.length() < 1e-12 {
        return DMat3::IDENTITY;
    }
    let (ga, gb) = (lorentz_factor(a), lorentz_factor(b));
    let g = ga * gb * (1.0 + a.dot(b));
    let cos = (1.0 + g + ga + gb).powi(2) / ((1.0 + g) * (1.0 + ga) * (1.0 + gb)) - 1.0;
    DMat3::from_axis_angle(-normal.normalize(), cos.clamp(-1.0, 1.0).acos())
}

/// `world` (observer moving with `beta_o`) written in the observer's frame by hand.
fn in_observer_frame(world: &SceneDescription, beta_o: DVec3) -> Scene {
    let mut description = world.clone();
    let observer = &mut description.observer;
    let event = to_observer(
        beta_o,
        Event::new(observer.ct, DVec3::from_array(observer.position)),
    );
    observer.beta = [0.0; 3];
    observer.position = event.position.to_array();
    observer.ct = event.ct;
    if let Some(light) = description
        .light
        .as_mut()
        .and_then(LightsDescription::lamp_mut)
    {
        let lit = to_observer(
            beta_o,
            Event::new(world.observer.ct, DVec3::from_array(light.position)),
        );
        light.position = lit.position.to_array();
    }
    let mut rotations = Vec::new();
    for object in &mut description.objects {
        // Two events on the worldline of the object's origin, mapped to S.
        let beta = DVec3::from_array(object.beta);
        let offset = DVec3::from_array(object.offset);
        let first = to_observer(beta_o, Event::new(0.0, offset));
        let second = to_observer(beta_o, Event::new(1.0, offset + beta));
        let velocity = (second.position - first.position) / (second.ct - first.ct);
        object.beta = velocity.to_array();
        object.offset = (first.position - velocity * first.ct).to_array();
        rotations.push(wigner_rotation(-beta_o, beta));
    }
    let mut scene = build(&description);
    for (object, rotation) in scene.objects.iter_mut().zip(rotations) {
        for part in &mut object.parts {
            part.mesh = part
                .mesh
                .clone()
                .transformed(DMat4::from_mat3(rotation))
                .expect("a rotation keeps the mesh valid");
        }
    }
    scene
}

/// The pixels that differ, and the largest difference of a channel.
fn difference(a: &[[u8; 3]], b: &[[u8; 3]]) -> (usize, u8) {
    let mut count = 0;
    let mut largest = 0;
    for (p, q) in a.iter().zip(b) {
        let d = p
            .iter()
            .zip(q)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap_or(0);
        if d > 0 {
            count += 1;
            largest = largest.max(d);
        }
    }
    (count, largest)
}

/// Pixels showing an object rather than the background.
fn object_pixels(image: &[[u8; 3]], background: [u8; 3]) -> usize {
    image.iter().filter(|p| **p != background).count()
}

fn check(description: &SceneDescription, beta_o: DVec3) {
    let mut moving = description.clone();
    moving.observer.beta = beta_o.to_array();
    let seen_moving = render(&build(&moving));
    let seen_at_rest = render(&in_observer_frame(description, beta_o));
    let background = render(&build(&SceneDescription {
        objects: Vec::new(),
        ..description.clone()
    }))[0];
    let shown = object_pixels(&seen_moving, background);
    assert!(
        shown > seen_moving.len() / 10,
        "β_o = {beta_o}: only {shown} pixels show an object; the comparison would say little"
    );
    let (count, largest) = difference(&seen_moving, &seen_at_rest);
    assert_eq!(
        (count, largest),
        (0, 0),
        "β_o = {beta_o}: {count} pixels differ, by up to {largest}/255"
    );
    // The observer's motion is visible: the picture is not the one seen at rest in W.
    let (changed, _) = difference(&seen_moving, &render(&build(description)));
    assert!(
        changed > seen_moving.len() / 20,
        "β_o = {beta_o}: the moving observer sees almost what the resting one sees ({changed} pixels differ)"
    );
}

const OBSERVER_VELOCITIES: [DVec3; 4] = [
    DVec3::new(0.0, 0.9, 0.0),
    DVec3::new(0.3, 0.5, 0.2),
    DVec3::new(-0.6, 0.3, -0.1),
    DVec3::new(0.0, -0.7, 0.0),
];

/// Objects at rest in W: they move with −β_o relative to the observer.
#[test]
fn objects_at_rest_look_the_same_from_either_frame() {
    for beta_o in OBSERVER_VELOCITIES {
        check(&world(), beta_o);
    }
}

/// Objects moving in W, obliquely to the observer: their frames relative to the observer are
/// composed boosts with a Wigner rotation.
#[test]
fn moving_objects_look_the_same_from_either_frame() {
    let mut description = world();
    let velocities = [
        DVec3::new(0.5, 0.0, 0.0),
        DVec3::new(0.0, -0.6, 0.3),
        DVec3::new(0.0, 0.0, 0.0),
    ];
    for (object, beta) in description.objects.iter_mut().zip(velocities) {
        object.beta = beta.to_array();
    }
    for beta_o in OBSERVER_VELOCITIES {
        check(&description, beta_o);
    }
}

/// The Wigner rotation matters: without it a moving object is seen differently.
#[test]
fn the_wigner_rotation_is_visible() {
    let beta_o = DVec3::new(0.0, 0.6, 0.0);
    let mut description = world();
    description.objects[0].beta = [0.6, 0.0, 0.0];
    description.objects[0].offset = [-2.0, 4.0, 0.2];
    let mut moving = description.clone();
    moving.observer.beta = beta_o.to_array();
    let mut unrotated = in_observer_frame(&description, beta_o);
    // Undo the closed-form rotation of the cube only (12.68° for two perpendicular 0.6c).
    let rotation = wigner_rotation(-beta_o, DVec3::new(0.6, 0.0, 0.0));
    let angle = ((rotation.col(0).x + rotation.col(1).y + rotation.col(2).z - 1.0) / 2.0).acos();
    assert!(
        (angle.to_degrees() - 12.68).abs() < 0.01,
        "{}",
        angle.to_degrees()
    );
    for part in &mut unrotated.objects[0].parts {
        part.mesh = part
            .mesh
            .clone()
            .transformed(DMat4::from_mat3(rotation.transpose()))
            .expect("a rotation keeps the mesh valid");
    }
    let seen = render(&build(&moving));
    let (count, _) = difference(&seen, &render(&unrotated));
    assert!(count > 40, "only {count} pixels differ");
}

/// The hand-written counterpart uses other coordinates of S than the scene builder (which keeps
/// the observation event's): the image tests compare two different descriptions.
#[test]
fn the_counterpart_uses_other_coordinates() {
    let beta_o = DVec3::new(0.0, 0.9, 0.0);
    let description = world();
    let mut moving = description.clone();
    moving.observer.beta = beta_o.to_array();
    let built = build(&moving).observer;
    let counterpart = in_observer_frame(&description, beta_o).observer;
    assert!((built.time - counterpart.time).abs() > 1.0);
    assert!((built.position - counterpart.position).length() > 1.0);
}
