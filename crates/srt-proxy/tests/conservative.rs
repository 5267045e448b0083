//! The footprint is conservative: every point of the curved apparent triangle projects inside
//! the rectangle and inside the convex hull (property test over random triangles, velocities up
//! to 0.99c, observers and cameras).

use glam::dcamera::rh::proj::directx::perspective;
use glam::dcamera::rh::view::look_at_mat4 as look_at;
use glam::{DMat4, DVec2, DVec3};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use srt_physics::{Event, Frame};
use srt_proxy::{Footprint, Rect, Viewport, footprint, polygon_area, project, split_pieces};

/// Where this binary's property tests keep a failing case, which proptest runs again before
/// any new one: beside the test's file, as `NAME.proptest-regressions`, committed with it
/// (docs/ARCHITECTURE.md, "Failing cases are kept"; tests/architecture.rs checks every test).
const KEEP_FAILURES: FileFailurePersistence =
    FileFailurePersistence::WithSource("proptest-regressions");

const VIEWPORT: Viewport = Viewport {
    width: 640.0,
    height: 480.0,
};

fn vec3(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn velocity() -> impl Strategy<Value = DVec3> {
    (vec3(1.0), 0.0..0.99f64)
        .prop_filter("direction", |(d, _)| d.length() > 0.1)
        .prop_map(|(d, s)| d.normalize() * s)
}

/// A scene: frame, rest triangle, observer event, camera looking near the triangle.
#[derive(Debug, Clone)]
struct Setup {
    frame: Frame,
    triangle: [DVec3; 3],
    observer: Event,
    view_projection: DMat4,
}

fn setup() -> impl Strategy<Value = Setup> {
    (
        velocity(),
        vec3(5.0),
        [vec3(3.0), vec3(3.0), vec3(3.0)],
        (-10.0..10.0f64, vec3(8.0)),
        vec3(0.5),
        vec3(1.0),
        20.0..120.0f64,
    )
        .prop_filter_map(
            "valid camera",
            |(beta, offset, triangle, (ct, position), aim_jitter, up, fov)| {
                let frame = Frame::new(beta, offset).ok()?;
                let observer = Event::new(ct, position);
                let centroid = (triangle[0] + triangle[1] + triangle[2]) / 3.0;
                let target = frame.apparent_position(centroid, observer) + aim_jitter;
                let forward = target - position;
                if forward.length() < 1e-3
                    || up.cross(forward).length() < 1e-3 * up.length() * forward.length()
                {
                    return None;
                }
                let view = look_at(position, target, up.normalize());
                let projection = perspective(
                    fov.to_radians(),
                    VIEWPORT.width / VIEWPORT.height,
                    0.01,
                    1000.0,
                );
                Some(Setup {
                    frame,
                    triangle,
                    observer,
                    view_projection: projection * view,
                })
            },
        )
}

/// Points of the rest triangle: a barycentric grid plus dense samples along the edges.
fn rest_samples(t: [DVec3; 3]) -> Vec<DVec3> {
    let mut out = Vec::new();
    let n = 24;
    for i in 0..=n {
        for j in 0..=n - i {
            let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            out.push(t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]));
        }
    }
    for k in 0..3 {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        for s in 0..=400 {
            out.push(a + f64::from(s) / 400.0 * (b - a));
        }
    }
    out
}

impl Setup {
    /// The footprint of the setup's triangle.
    fn footprint(&self) -> Footprint {
        footprint(
            &self.frame,
            self.triangle,
            self.observer,
            self.view_projection,
            VIEWPORT,
        )
    }
}

/// A setup whose camera looks anywhere (not at the triangle), from closer: triangles beside,
/// behind and around the camera, as when objects pass it.
fn passing_setup() -> impl Strategy<Value = Setup> {
    (setup(), vec3(1.0), vec3(1.0), 0.0..1.0f64).prop_filter_map(
        "valid camera",
        |(s, look, up, closeness)| {
            let position = s.observer.position;
            // Pull the observer towards the triangle's apparent centroid, often into it.
            let centroid = (s.triangle[0] + s.triangle[1] + s.triangle[2]) / 3.0;
            let seen = s.frame.apparent_position(centroid, s.observer);
            let observer = Event::new(s.observer.ct, position + closeness * (seen - position));
            if look.length() < 1e-3 || up.cross(look).length() < 1e-3 * up.length() * look.length()
            {
                return None;
            }
            let view = look_at(observer.position, observer.position + look, up.normalize());
            let projection = perspective(1.2, VIEWPORT.width / VIEWPORT.height, 0.01, 1000.0);
            Some(Setup {
                observer,
                view_projection: projection * view,
                ..s
            })
        },
    )
}

/// Every sample of the apparent triangle that lands on the screen lies in the footprint's
/// rectangle and hull, and for a split triangle in one of its pieces (samples behind the camera,
/// or off screen for a footprint clamped to it, are never seen).
fn assert_conservative(s: &Setup) -> Result<(), TestCaseError> {
    let fp = s.footprint();
    let pieces = if fp.split {
        split_pieces(
            &s.frame,
            s.triangle,
            s.observer,
            s.view_projection,
            VIEWPORT,
        )
    } else {
        None
    };
    let extent = if fp.whole_screen {
        1.0
    } else {
        (fp.rect.max - fp.rect.min).length()
    };
    let tolerance = 1e-7 * (1.0 + extent.max(VIEWPORT.width));
    for p in rest_samples(s.triangle) {
        let seen = s.frame.apparent_position(p, s.observer);
        match project(s.view_projection, VIEWPORT, seen) {
            None => {}
            // The whole screen covers every pixel that can show the point.
            Some(_) if fp.whole_screen => {}
            Some(px) if fp.split && !Rect::screen(VIEWPORT).contains(px, 0.0) => {}
            Some(px) => {
                prop_assert!(
                    fp.rect.contains(px, tolerance),
                    "{px} outside rect {:?}",
                    fp.rect
                );
                prop_assert!(
                    fp.hull_contains(px, tolerance),
                    "{px} outside hull {:?}",
                    fp.hull_points()
                );
                if let Some(pieces) = &pieces {
                    prop_assert!(
                        pieces
                            .iter()
                            .any(|f| f.rect.contains(px, tolerance)
                                && f.hull_contains(px, tolerance)),
                        "{px} outside every piece {pieces:?}"
                    );
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)
    })]

    #[test]
    fn apparent_triangle_lies_inside_rectangle_and_hull(s in setup()) {
        assert_conservative(&s)?;
    }

    #[test]
    fn triangles_passing_the_camera_stay_inside_their_footprints(s in passing_setup()) {
        assert_conservative(&s)?;
    }
}

#[test]
fn few_passing_triangles_need_the_whole_screen() {
    // Guards the second property test against passing through the whole-screen case, and
    // measures what splitting saves: the whole screen is left only for pieces whose
    // prism reaches the camera.
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = passing_setup();
    let total = 400;
    let (mut whole, mut split, mut empty) = (0, 0, 0);
    for _ in 0..total {
        let fp = strategy
            .new_tree(&mut runner)
            .unwrap()
            .current()
            .footprint();
        whole += usize::from(fp.whole_screen);
        split += usize::from(fp.split);
        empty += usize::from(fp.is_empty());
    }
    eprintln!("passing footprints: {whole} whole screen, {split} split, {empty} empty of {total}");
    assert!(
        whole * 10 < total,
        "{whole} of {total} passing footprints were the whole screen"
    );
    assert!(
        split * 5 > total,
        "only {split} of {total} passing footprints were split"
    );
    assert!(
        empty * 10 > total,
        "only {empty} of {total} passing footprints were empty"
    );
}

/// How many samples of the rest triangle's dense barycentric grid land on the screen.
fn samples_on_screen(s: &Setup) -> usize {
    let n = 400;
    let t = s.triangle;
    (0..=n)
        .flat_map(|i| (0..=n - i).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            let seen = s
                .frame
                .apparent_position(t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]), s.observer);
            project(s.view_projection, VIEWPORT, seen)
                .is_some_and(|q| Rect::screen(VIEWPORT).contains(q, 0.0))
        })
        .count()
}

#[test]
fn a_triangle_beside_and_behind_the_camera_draws_only_where_it_is_seen() {
    // The observer at the origin looks along −z; a long triangle moving at 0.9c along −z
    // passes beside the camera, seen partly in front of it and partly behind it.
    let frame = Frame::new(DVec3::new(0.0, 0.0, -0.9), DVec3::new(0.0, 0.0, 0.0)).unwrap();
    let observer = Event::new(0.0, DVec3::ZERO);
    let view = look_at(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), DVec3::Y);
    let setup = |triangle| Setup {
        frame,
        triangle,
        observer,
        view_projection: perspective(1.0, 4.0 / 3.0, 0.1, 100.0) * view,
    };
    let beside = setup([
        DVec3::new(1.0, -0.5, -12.0),
        DVec3::new(1.5, 0.5, 1.0),
        DVec3::new(2.0, 0.0, -4.0),
    ]);
    let seen_z = beside
        .triangle
        .map(|p| frame.apparent_position(p, observer).z);
    assert!(seen_z[0] < 0.0 && seen_z[1] > 0.0, "{seen_z:?}");
    let fp = beside.footprint();
    assert!(!fp.whole_screen && fp.split, "{fp:?}");
    assert!(samples_on_screen(&beside) > 0);
    assert_conservative(&beside).unwrap();
    assert!(
        fp.rect.area() < 0.1 * VIEWPORT.width * VIEWPORT.height,
        "{fp:?}"
    );
    assert!(
        fp.rect.max.x == VIEWPORT.width,
        "the part in front reaches the right edge: {fp:?}"
    );
    // Further out, its corner ahead is seen just beyond the right edge and the rest of it
    // passes behind the camera: nothing of it is on screen, and its pieces draw next to
    // nothing (a convex bound of the whole triangle reaches into the picture).
    let further = setup(beside.triangle.map(|p| p + DVec3::X));
    assert_eq!(samples_on_screen(&further), 0);
    let area = further.footprint().rect.area();
    assert!(area < 0.005 * VIEWPORT.width * VIEWPORT.height, "{area}");
    // Wholly behind the camera: nothing.
    let behind = setup(beside.triangle.map(|p| p + DVec3::new(-1.0, 0.0, 40.0)));
    assert!(behind.footprint().is_empty(), "{:?}", behind.footprint());
}

#[test]
fn most_random_setups_are_not_whole_screen() {
    // Guards the property test against passing vacuously through the whole-screen case.
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = setup();
    let total = 300;
    let whole = (0..total)
        .filter(|_| {
            strategy
                .new_tree(&mut runner)
                .unwrap()
                .current()
                .footprint()
                .whole_screen
        })
        .count();
    assert!(
        whole * 4 < total,
        "{whole} of {total} footprints were the whole screen"
    );
}

#[test]
fn hull_is_tighter_than_rectangle_and_has_three_to_six_points() {
    let frame = Frame::new(DVec3::new(0.0, 0.9, 0.0), DVec3::ZERO).unwrap();
    let observer = Event::new(0.0, DVec3::new(0.0, 0.0, 6.0));
    let view = look_at(observer.position, DVec3::ZERO, DVec3::Y);
    let vp = perspective(60f64.to_radians(), 4.0 / 3.0, 0.1, 100.0) * view;
    let tri = [
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.5, -0.5, 0.0),
        DVec3::new(0.0, 1.0, 0.5),
    ];
    let fp = footprint(&frame, tri, observer, vp, VIEWPORT);
    assert!(!fp.whole_screen);
    assert!((3..=6).contains(&fp.hull_len));
    // Signed: positive for the documented counter-clockwise order.
    let hull_area: f64 = (0..fp.hull_len)
        .map(|i| fp.hull[i].perp_dot(fp.hull[(i + 1) % fp.hull_len]))
        .sum::<f64>()
        / 2.0;
    assert!(hull_area > 0.0 && hull_area < fp.rect.area());
}

#[test]
fn a_big_triangle_around_the_observer_draws_its_visible_part() {
    let frame = Frame::new(DVec3::new(0.5, 0.0, 0.0), DVec3::ZERO).unwrap();
    let observer = Event::new(0.0, DVec3::ZERO);
    let view = look_at(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), DVec3::Y);
    let vp = perspective(1.0, 4.0 / 3.0, 0.1, 100.0) * view;
    // A big triangle 1.7 from the observer, reaching from in front of it to behind it.
    let around = Setup {
        frame,
        triangle: [
            DVec3::new(-5.0, -5.0, 5.0),
            DVec3::new(5.0, -5.0, -5.0),
            DVec3::new(0.0, 5.0, -5.0),
        ],
        observer,
        view_projection: vp,
    };
    let fp = around.footprint();
    assert!(fp.split && !fp.whole_screen, "{fp:?}");
    assert!(samples_on_screen(&around) > 0);
    assert_conservative(&around).unwrap();
    assert!(
        fp.rect.area() < 0.7 * VIEWPORT.width * VIEWPORT.height,
        "{fp:?}"
    );
    // The observer on the triangle itself: the whole screen, no NaN.
    let touching = [
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, -1.0),
        DVec3::new(0.0, 1.0, -1.0),
    ];
    let frame_at_rest = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
    let fp = footprint(&frame_at_rest, touching, observer, vp, VIEWPORT);
    assert!(fp.whole_screen);
    assert_eq!(fp.rect.min, DVec2::ZERO);
    assert_eq!(fp.rect.max, DVec2::new(640.0, 480.0));
}

#[test]
fn zero_area_triangle_has_a_zero_area_footprint() {
    let frame = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
    let observer = Event::new(0.0, DVec3::new(0.0, 0.0, 5.0));
    let view = look_at(observer.position, DVec3::ZERO, DVec3::Y);
    let vp = perspective(1.0, 4.0 / 3.0, 0.1, 100.0) * view;
    let tri = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
    let fp = footprint(&frame, tri, observer, vp, VIEWPORT);
    assert!(!fp.whole_screen);
    assert!(fp.hull_len < 3);
    assert!(fp.rect.area() < 1e-9);
}

#[test]
fn a_large_strongly_curved_footprint_is_split_into_tighter_pieces() {
    // A wall close beside the camera, rushing away from it at 0.9c along the view direction:
    // all of it is seen in front of the camera, but its edges are seen strongly curved.
    let frame = Frame::new(DVec3::new(0.0, 0.0, 0.9), DVec3::ZERO).unwrap();
    let observer = Event::new(0.0, DVec3::ZERO);
    let view = look_at(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), DVec3::Y);
    let wall = Setup {
        frame,
        triangle: [
            DVec3::new(0.5, -2.0, -1.0),
            DVec3::new(0.5, 2.0, -1.0),
            DVec3::new(0.5, -2.0, -5.0),
        ],
        observer,
        view_projection: perspective(1.2, 4.0 / 3.0, 0.1, 100.0) * view,
    };
    let tangent = srt_proxy::tangent_footprint(
        &wall.frame,
        wall.triangle,
        observer,
        wall.view_projection,
        VIEWPORT,
    )
    .expect("wholly in front of the camera");
    assert!(tangent.worth_splitting(VIEWPORT), "{tangent:?}");
    let fp = wall.footprint();
    assert!(fp.split && !fp.whole_screen, "{fp:?}");
    assert_conservative(&wall).unwrap();
    let pieces = split_pieces(
        &wall.frame,
        wall.triangle,
        observer,
        wall.view_projection,
        VIEWPORT,
    )
    .unwrap();
    let pieces_area: f64 = pieces.iter().map(|f| polygon_area(f.hull_points())).sum();
    let hull_area = polygon_area(tangent.hull_points());
    assert!(
        pieces.len() > 1 && pieces_area < 0.9 * hull_area,
        "{} pieces of {pieces_area} px² against a hull of {hull_area} px²",
        pieces.len()
    );
}
