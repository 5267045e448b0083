//! What each pixel sees of time (`SeenEvent`, the `--aov` channels) against an independent
//! light-cone solution: the event lies on the observer's backward light cone along the pixel's
//! ray, on the surface of the object's worldline, and its world time, proper time and Doppler
//! factor follow from Lorentz transformations written out here from Eq. 1–2, for cubes and
//! spheres moving in several directions, seen by observers at rest and moving.

use std::sync::atomic::AtomicBool;

use glam::{DMat4, DVec2, DVec3, DVec4};
use srt_scene::{Scene, SceneDescription};
use srt_trace::{SeenEvent, Tracer};

const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;
const HALF_SIZE: f64 = 1.0;

/// Λ_β of Eq. 2, written out here (not srt-physics'): S′ → S for S′ moving with `beta` (also
/// `moving_bodies`' independent rest-frame rays).
pub(crate) fn boost(beta: DVec3) -> DMat4 {
    let b2 = beta.length_squared();
    let gamma = 1.0 / (1.0 - b2).sqrt();
    let k = if b2 > 0.0 { (gamma - 1.0) / b2 } else { 0.0 };
    let column = |i: usize| -> DVec4 {
        // column i of Λ: row 0 is γβᵀ, the spatial block 1 + k ββᵀ.
        if i == 0 {
            DVec4::new(gamma, gamma * beta.x, gamma * beta.y, gamma * beta.z)
        } else {
            let b = beta[i - 1];
            let mut c = DVec4::new(gamma * b, k * b * beta.x, k * b * beta.y, k * b * beta.z);
            c[i] += 1.0;
            c
        }
    };
    DMat4::from_cols(column(0), column(1), column(2), column(3))
}

/// The shapes checked, each of half size [`HALF_SIZE`].
#[derive(Debug, Clone, Copy)]
enum Shape {
    Cube,
    /// A latitude–longitude sphere of [`SPHERE_SEGMENTS`] slices and half as many rings, both
    /// 2π / segments apart, its poles on ±z (`srt_scene::shapes::uv_sphere`): a convex
    /// polyhedron whose faces are the flat cells between neighbouring rings and slices.
    Sphere,
}

const SPHERE_SEGMENTS: u32 = 64;

/// The face planes (outward unit normal n, offset d: n·p ≤ d inside) of the tessellated
/// sphere of radius [`HALF_SIZE`], from its vertex grid written out here: the vertex of ring i
/// and slice j is r (sin θᵢ cos φⱼ, sin θᵢ sin φⱼ, cos θᵢ), θᵢ = π i / rings, φⱼ = 2π j /
/// slices. A cell's four corners are coplanar (an isosceles trapezoid, symmetric about the
/// meridian plane halfway between its slices); at a pole two of them coincide.
fn sphere_planes() -> Vec<(DVec3, f64)> {
    let (slices, rings) = (SPHERE_SEGMENTS, SPHERE_SEGMENTS / 2);
    let vertex = |i: u32, j: u32| {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        let phi = std::f64::consts::TAU * f64::from(j) / f64::from(slices);
        HALF_SIZE
            * DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            )
    };
    let mut planes = Vec::new();
    for i in 0..rings {
        for j in 0..slices {
            // Three distinct corners: at the north pole the ring-i corners coincide.
            let [a, b, c] = if i == 0 {
                [vertex(0, j), vertex(1, j), vertex(1, j + 1)]
            } else {
                [vertex(i, j), vertex(i + 1, j), vertex(i, j + 1)]
            };
            let mut normal = (b - a).cross(c - a).normalize();
            if normal.dot(a + b + c) < 0.0 {
                normal = -normal;
            }
            planes.push((normal, normal.dot(a)));
        }
    }
    planes
}

impl Shape {
    /// The scene file's `shape` table.
    fn table(self) -> String {
        match self {
            Self::Cube => format!("{{ type = \"cube\", size = {} }}", 2.0 * HALF_SIZE),
            Self::Sphere => format!(
                "{{ type = \"sphere\", radius = {HALF_SIZE}, segments = {SPHERE_SEGMENTS} }}"
            ),
        }
    }

    /// How far the rest point `p` lies off the shape's surface: |max over the face planes of
    /// n·p − d| for these convex solids, zero exactly on the surface, the distance to the
    /// surface for a point inside and at most that for one outside.
    fn distance_off_surface(self, p: DVec3) -> f64 {
        match self {
            Self::Cube => (p.abs().max_element() - HALF_SIZE).abs(),
            Self::Sphere => {
                static PLANES: std::sync::OnceLock<Vec<(DVec3, f64)>> = std::sync::OnceLock::new();
                PLANES
                    .get_or_init(sphere_planes)
                    .iter()
                    .map(|(normal, offset)| normal.dot(p) - offset)
                    .fold(f64::NEG_INFINITY, f64::max)
                    .abs()
            }
        }
    }
}

/// The measure off the surface is two-sided: zero on it (a vertex), the depth for a point inside,
/// and for a point outside at least the part of its height along the face's normal that the
/// tessellation leaves (a point 0.1 beyond the surface along an axis is 0.1 off the cube, and
/// over 0.05 off the sphere's facets, whose middles lie at most 2·10⁻³ inside the sphere).
#[test]
fn a_point_off_the_surface_on_either_side_is_off_it() {
    for shape in [Shape::Cube, Shape::Sphere] {
        let on = DVec3::new(0.0, 0.0, HALF_SIZE);
        assert!(shape.distance_off_surface(on) < 1e-12, "{shape:?} on");
        for direction in [DVec3::X, DVec3::NEG_Y, DVec3::Z] {
            let outside = shape.distance_off_surface((HALF_SIZE + 0.1) * direction);
            let inside = shape.distance_off_surface((HALF_SIZE - 0.1) * direction);
            assert!(
                outside > 0.05,
                "{shape:?} outside along {direction}: {outside}"
            );
            assert!(
                inside > 0.05,
                "{shape:?} inside along {direction}: {inside}"
            );
        }
    }
}

fn scene(shape: Shape, observer_beta: [f64; 3], beta: [f64; 3], offset: [f64; 3]) -> Scene {
    let text = format!(
        "[observer]\nposition = [0.0, -6.0, 0.5]\nlook_at = [0.0, 0.0, 0.0]\nct = 0.0\n\
         beta = {observer_beta:?}\nfov_y_deg = 60.0\n\
         [[object]]\nshape = {}\nbeta = {beta:?}\n\
         offset = {offset:?}\n",
        shape.table()
    );
    let description = SceneDescription::from_toml_str(&text, "test").unwrap();
    description.build(std::path::Path::new(".")).unwrap().0
}

/// Checks every pixel's event; returns how many pixels saw the object.
fn check(shape: Shape, observer_beta: [f64; 3], cube_beta: [f64; 3], offset: [f64; 3]) -> usize {
    let scene = scene(shape, observer_beta, cube_beta, offset);
    let events = Tracer::new(&scene)
        .render_seen_events(WIDTH, HEIGHT, &|_| {}, &AtomicBool::new(false))
        .unwrap();
    let observer = scene.observer;
    // The observation event in W and the map S → W: x_W = Λ_βo (x_S − E) + E (Eq. 1).
    let observation = DVec4::new(
        observer.time,
        observer.position.x,
        observer.position.y,
        observer.position.z,
    );
    let to_world = |event: DVec4| {
        boost(DVec3::from_array(observer_beta)) * (event - observation) + observation
    };
    let cube_beta = DVec3::from_array(cube_beta);
    let from_world = boost(-cube_beta);
    let a = DVec4::new(0.0, offset[0], offset[1], offset[2]);
    let mut seen = 0;
    for (index, event) in events.iter().enumerate() {
        let Some(SeenEvent {
            object,
            emission_ct,
            proper_time,
            distance,
            doppler,
        }) = *event
        else {
            continue;
        };
        seen += 1;
        assert_eq!(object, 0);
        let (x, y) = (index as u32 % WIDTH, index as u32 / WIDTH);
        let ndc = DVec2::new(
            2.0 * (f64::from(x) + 0.5) / f64::from(WIDTH) - 1.0,
            1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(HEIGHT),
        );
        let look = observer
            .view_direction(ndc, f64::from(WIDTH) / f64::from(HEIGHT))
            .normalize();
        // On the backward light cone in S: seen at `distance` along the ray, that long ago.
        let at = observer.position + distance * look;
        let in_s = DVec4::new(observer.time - distance, at.x, at.y, at.z);
        let in_w = to_world(in_s);
        let rest = from_world * (in_w - a);
        let context =
            format!("pixel ({x}, {y}) of {shape:?} {cube_beta} seen moving {observer_beta:?}");
        assert!(
            (emission_ct - in_w.x).abs() <= 1e-9 * (1.0 + in_w.x.abs()),
            "{context}: emission_ct {emission_ct} vs {}",
            in_w.x
        );
        assert!(
            (proper_time - rest.x).abs() <= 1e-9 * (1.0 + rest.x.abs()),
            "{context}: proper_time {proper_time} vs {}",
            rest.x
        );
        // On the object's surface, at rest in S′.
        let off = shape.distance_off_surface(DVec3::new(rest.y, rest.z, rest.w));
        assert!(off < 1e-6, "{context}: {rest} is {off} off the surface");
        // Doppler factor in S (Eq. 4): light leaves the surface towards the observer, along −look.
        let relative = velocity_in_s(cube_beta, DVec3::from_array(observer_beta));
        let expected =
            1.0 / ((1.0 / (1.0 - relative.length_squared()).sqrt()) * (1.0 + relative.dot(look)));
        assert!(
            (doppler - expected).abs() <= 1e-9 * expected,
            "{context}: D {doppler} vs {expected}"
        );
    }
    seen
}

/// The cube's velocity relative to the observer's frame S: the first column of
/// Λ_−βo Λ_β (its origin's four-velocity, γ (1, v)).
fn velocity_in_s(cube_beta: DVec3, observer_beta: DVec3) -> DVec3 {
    let u = boost(-observer_beta) * boost(cube_beta) * DVec4::X;
    DVec3::new(u.y, u.z, u.w) / u.x
}

#[test]
fn events_lie_on_the_light_cone_and_the_worldline_for_an_observer_at_rest() {
    for (beta, offset) in [
        ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        // approaching head-on: seen about 7 units away, though 0.7 away now
        ([0.0, -0.9, 0.0], [0.0, -5.3, 0.0]),
        ([0.6, 0.3, -0.2], [2.5, 1.0, 0.0]),
        ([-0.95, 0.0, 0.1], [-3.0, 0.0, 0.0]),
    ] {
        for shape in [Shape::Cube, Shape::Sphere] {
            assert!(
                check(shape, [0.0; 3], beta, offset) > 100,
                "{beta:?}: the {shape:?} is seen"
            );
        }
    }
}

#[test]
fn world_and_proper_times_hold_for_a_moving_observer() {
    for (observer_beta, cube_beta, offset) in [
        ([0.5, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ([0.0, -0.7, 0.2], [0.3, -0.4, 0.0], [0.0, 0.0, 0.0]),
    ] {
        for shape in [Shape::Cube, Shape::Sphere] {
            assert!(
                check(shape, observer_beta, cube_beta, offset) > 100,
                "{observer_beta:?}, {cube_beta:?}: the {shape:?} is seen"
            );
        }
    }
}
