//! The three pictures (`srt_scene::View`): seen is the identity; the Newtonian picture is the rest
//! shape translated to where the object is at ct_obs; the measured picture puts every vertex where
//! that material point is at S time ct_obs (contracted by 1/γ along β), all at rest in S.

use glam::DVec3;
use proptest::prelude::*;
use srt_physics::Frame;
use srt_scene::builtin::find_builtin;
use srt_scene::{Scene, View};

fn cube() -> Scene {
    find_builtin("fig10-cube50").unwrap().build().unwrap().0
}

/// `scene` with every object given velocity `beta` and the observer at time `ct`.
fn moving(beta: DVec3, ct: f64) -> Scene {
    let mut scene = cube();
    for object in &mut scene.objects {
        object.frame = Frame::new(beta, object.frame.offset()).unwrap();
    }
    scene.observer.time = ct;
    scene
}

/// Every vertex of every part of every object, in S (mesh position plus the frame's offset;
/// only meaningful for objects at rest in S).
fn static_positions(scene: &Scene) -> Vec<DVec3> {
    scene
        .objects
        .iter()
        .flat_map(|o| {
            assert_eq!(
                o.frame.beta(),
                DVec3::ZERO,
                "the view's objects are at rest in S"
            );
            o.parts.iter().flat_map(move |p| {
                p.mesh
                    .positions()
                    .iter()
                    .map(move |&x| x + o.frame.offset())
            })
        })
        .collect()
}

fn rest_positions(scene: &Scene) -> Vec<(Frame, DVec3)> {
    scene
        .objects
        .iter()
        .flat_map(|o| {
            o.parts
                .iter()
                .flat_map(move |p| p.mesh.positions().iter().map(move |&x| (o.frame, x)))
        })
        .collect()
}

#[test]
fn seen_is_the_identity() {
    let scene = moving(DVec3::new(0.3, 0.8, 0.1), 7.5);
    assert_eq!(View::Seen.apply(&scene).unwrap(), scene);
    assert_eq!(View::default(), View::Seen);
}

#[test]
fn names_are_distinct() {
    let names: Vec<_> = View::ALL.iter().map(|v| v.name()).collect();
    assert_eq!(names, ["seen", "measured", "newtonian"]);
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)
    })]

    #[test]
    fn newtonian_is_the_rest_shape_where_the_origin_is_now(
        (bx, by, bz) in (-0.5..0.5f64, -0.5..0.5f64, -0.5..0.5f64), ct in -20.0..20.0f64) {
        let beta = DVec3::new(bx, by, bz);
        let scene = moving(beta, ct);
        let viewed = View::Newtonian.apply(&scene).unwrap();
        for ((frame, rest), now) in rest_positions(&scene).into_iter().zip(static_positions(&viewed)) {
            let expected = frame.offset() + beta * ct + rest;
            prop_assert!((now - expected).length() < 1e-9, "{now} vs {expected}");
        }
        for (a, b) in scene.objects.iter().zip(&viewed.objects) {
            for (pa, pb) in a.parts.iter().zip(&b.parts) {
                prop_assert_eq!(&pa.mesh, &pb.mesh, "shape unchanged");
            }
        }
    }

    #[test]
    fn measured_is_simultaneous_in_s_and_contracted_along_beta(
        (bx, by, bz) in (-0.55..0.55f64, -0.55..0.55f64, -0.55..0.55f64), ct in -20.0..20.0f64) {
        let beta = DVec3::new(bx, by, bz);
        let scene = moving(beta, ct);
        let viewed = View::Measured.apply(&scene).unwrap();
        let rest = rest_positions(&scene);
        let now = static_positions(&viewed);
        // Each vertex is where its material point is at S time ct_obs.
        for (&(frame, x), &p) in rest.iter().zip(&now) {
            let event = frame.event_at_time(x, ct);
            prop_assert!((event.ct - ct).abs() < 1e-9);
            prop_assert!((p - event.position).length() < 1e-9, "{p} vs {}", event.position);
        }
        // Separations shrink by 1/γ along β and keep their part across β.
        let speed = beta.length();
        prop_assume!(speed > 1e-3);
        let n = beta / speed;
        let gamma = 1.0 / (1.0 - speed * speed).sqrt();
        for i in (1..rest.len()).step_by(37) {
            let d_rest = rest[i].1 - rest[0].1;
            let d_now = now[i] - now[0];
            prop_assert!((d_now.dot(n) - d_rest.dot(n) / gamma).abs() < 1e-9);
            let across = |d: DVec3| d - d.dot(n) * n;
            prop_assert!((across(d_now) - across(d_rest)).length() < 1e-9);
        }
    }
}

#[test]
fn measured_normals_stay_perpendicular_to_the_contracted_faces() {
    let scene = moving(DVec3::new(0.6, 0.5, 0.0), 3.0);
    let viewed = View::Measured.apply(&scene).unwrap();
    let mesh = &viewed.objects[0].parts[0].mesh;
    let rest = &scene.objects[0].parts[0].mesh;
    let mut checked = 0;
    for (index, t) in mesh.triangles().iter().enumerate() {
        let [a, b, c] = mesh.triangle_positions(index);
        let face = (b - a).cross(c - a).normalize();
        let rest_normals = t.map(|i| rest.normals()[i as usize]);
        // Flat-shaded (cube face) vertices only: their normal is the face normal.
        if rest_normals
            .iter()
            .all(|&n| (n - rest_normals[0]).length() < 1e-12)
        {
            for i in t {
                let normal = mesh.normals()[*i as usize];
                assert!((normal.length() - 1.0).abs() < 1e-12);
                assert!((normal - face).length() < 1e-9, "{normal} vs face {face}");
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "the cube's faces are flat: {checked}");
}

#[test]
fn the_sky_is_at_rest_in_the_static_views_and_contracted_when_measured() {
    let flythrough = find_builtin("flythrough").unwrap().build().unwrap().0;
    let beta = flythrough.sky.beta;
    assert!(beta.length() > 0.8, "the observer flies through the stars");
    let gamma = 1.0 / (1.0 - beta.length_squared()).sqrt();
    let along = beta.normalize();
    assert_eq!(View::Seen.apply(&flythrough).unwrap().sky, flythrough.sky);
    let newtonian = View::Newtonian.apply(&flythrough).unwrap().sky;
    let measured = View::Measured.apply(&flythrough).unwrap().sky;
    assert_eq!((newtonian.beta, measured.beta), (DVec3::ZERO, DVec3::ZERO));
    assert_eq!(newtonian.stars, flythrough.sky.stars);
    assert_eq!(newtonian.direction_map, glam::DMat3::IDENTITY);
    assert_eq!(measured.stars, flythrough.sky.stars);
    for star in &flythrough.sky.stars {
        // Measured: the component along W's velocity shrinks by 1/γ, the rest stays.
        let contracted = star.direction - (1.0 - 1.0 / gamma) * star.direction.dot(along) * along;
        assert!((measured.direction_map * star.direction - contracted).length() < 1e-12);
    }
}
