//! The renderer checked against what physics says: Penrose's circular outline of a moving
//! sphere, Terrell's apparent rotation of a passing cube, and agreement with an ordinary
//! (non-relativistic) ray tracer at β = 0.

use glam::{DVec2, DVec3};
use srt_color::ToneMap;
use srt_physics::{Event, Frame, Poincare, aberrate};
use srt_scene::shapes::{cube, uv_sphere};
use srt_scene::{
    Effects, Light, Material, Mesh, Object, Observer, Part, Scene, Shading, Sky, SurfaceColour,
    SurfaceOptics,
};
use srt_trace::{RenderSettings, Tracer, grey_value};

fn scene(objects: Vec<Object>, observer: Observer) -> Scene {
    Scene {
        name: "test".into(),
        objects,
        observer,
        light: Light {
            position: DVec3::new(3.0, 8.0, 10.0),
            temperature_k: 6500.0,
            strength: 1.0,
        },
        lights: Vec::new(),
        shadows: true,
        shading: Shading::default(),
        effects: Effects::Geometry,
        tone_map: ToneMap::Luminance,
        background: DVec3::ZERO,
        sky: Sky::default(),
        colour: SurfaceColour::Paper,
        exposure: 1.0,
        cube_map_size: srt_scene::DEFAULT_CUBE_MAP_SIZE,
        world: Poincare::IDENTITY,
    }
}

fn object(mesh: Mesh, beta: DVec3, offset: DVec3, base_color: [f32; 4]) -> Object {
    Object {
        name: "object".into(),
        parts: vec![Part {
            mesh,
            material: Material {
                base_color,
                ..Material::default()
            },
        }],
        frame: Frame::new(beta, offset).unwrap(),
        rest_time_shift: 0.0,
        wireframe: None,
        optics: SurfaceOptics::default(),
        clock: None,
        motion: Default::default(),
    }
}

/// Least-squares circle through `points` (Kåsa's algebraic fit), returning the centre, the
/// radius and the RMS of the geometric residuals.
fn fit_circle(points: &[DVec2]) -> (DVec2, f64, f64) {
    // Solve [x y 1]·(a, b, c) = x² + y² in the least-squares sense (3×3 normal equations).
    let mut normal = glam::DMat3::ZERO;
    let mut rhs = DVec3::ZERO;
    for p in points {
        let row = DVec3::new(p.x, p.y, 1.0);
        normal += glam::DMat3::from_cols(row * row.x, row * row.y, row * row.z);
        rhs += row * p.length_squared();
    }
    let DVec3 { x: a, y: b, z: c } = normal.inverse() * rhs;
    let centre = DVec2::new(a / 2.0, b / 2.0);
    let radius = (c + centre.length_squared()).sqrt();
    let rms = (points
        .iter()
        .map(|p| ((*p - centre).length() - radius).powi(2))
        .sum::<f64>()
        / points.len() as f64)
        .sqrt();
    (centre, radius, rms)
}

/// Silhouette points of the rendered coverage mask: for every row and column, the midpoints
/// between the pixel centres where coverage switches on or off.
fn mask_boundary(coverage: &[u32], width: u32, height: u32) -> Vec<DVec2> {
    let covered = |x: u32, y: u32| coverage[(y * width + x) as usize] != 0;
    let mut points = Vec::new();
    for y in 0..height {
        for x in 0..width - 1 {
            if covered(x, y) != covered(x + 1, y) {
                points.push(DVec2::new(f64::from(x) + 1.0, f64::from(y) + 0.5));
            }
        }
    }
    for x in 0..width {
        for y in 0..height - 1 {
            if covered(x, y) != covered(x, y + 1) {
                points.push(DVec2::new(f64::from(x) + 0.5, f64::from(y) + 1.0));
            }
        }
    }
    points
}

/// Renders the coverage mask of `scene` at `size`² and fits a circle to its silhouette.
fn outline_fit(scene: &Scene, size: u32) -> (DVec2, f64, f64, usize) {
    let image = Tracer::new(scene).render(
        RenderSettings {
            width: size,
            height: size,
            samples: 1,
        },
        &|_| {},
    );
    let boundary = mask_boundary(&image.coverage, size, size);
    let (centre, radius, rms) = fit_circle(&boundary);
    (centre, radius, rms, boundary.len())
}

/// The camera axis on which a sphere's circular outline cone is centred: the aberrated
/// direction towards its centre.
fn outline_axis(frame: &Frame, centre_rest: DVec3, observer: Event) -> DVec3 {
    let observer_rest = frame.to_rest(observer).position;
    let propagation_rest = (observer_rest - centre_rest).normalize();
    -aberrate(frame.beta(), propagation_rest)
}

#[test]
fn penrose_a_moving_sphere_has_a_circular_outline() {
    let cases = [
        (DVec3::new(0.9, 0.0, 0.0), DVec3::new(-4.0, 0.0, -6.0), 0.0),
        (DVec3::new(0.3, -0.5, 0.75), DVec3::new(1.0, 2.0, -5.0), 3.0),
        (DVec3::new(0.0, 0.0, 0.99), DVec3::new(0.5, 0.3, -40.0), 5.0),
    ];
    for (beta, offset, ct) in cases {
        let frame = Frame::new(beta, offset).unwrap();
        let observer_event = Event::new(ct, DVec3::ZERO);
        let axis = outline_axis(&frame, DVec3::ZERO, observer_event);
        let sphere = object(uv_sphere(1.0, 512), beta, offset, [1.0; 4]);
        // Field of view chosen so the outline fills about half the image.
        let apparent = frame
            .apparent_position(DVec3::ZERO, observer_event)
            .length();
        let observer = Observer {
            projection: srt_scene::Projection::Perspective,
            stereo: None,
            position: DVec3::ZERO,
            direction: axis,
            up: DVec3::new(0.1, 1.0, 0.05),
            fov_y_deg: 0.0,
            time: ct,
        };
        let half_angle = (1.0 / apparent).asin();
        let observer = Observer {
            fov_y_deg: (4.0 * half_angle).to_degrees().min(120.0),
            ..observer
        };
        let (centre, radius, rms, count) = outline_fit(&scene(vec![sphere], observer), 512);
        println!(
            "Penrose β = {beta}: {count} outline points, radius {radius:.1} px, RMS {rms:.3} px"
        );
        assert!(count > 200, "β = {beta}: only {count} silhouette points");
        assert!(
            radius > 40.0,
            "β = {beta}: outline radius {radius} px is too small to judge"
        );
        assert!(
            rms < 0.5,
            "β = {beta}: outline is not a circle: RMS residual {rms} px (centre {centre}, radius {radius})"
        );
    }
}

#[test]
fn penrose_check_detects_a_non_circular_outline() {
    // Control: an ellipsoid (a sphere squashed to 1/γ along x, γ for 0.9c) seen at rest has a
    // visibly non-circular outline, so the fit above can fail.
    let squash = glam::DMat4::from_scale(DVec3::new(1.0 / 2.294, 1.0, 1.0));
    let mesh = uv_sphere(1.0, 256).transformed(squash).unwrap();
    let ellipsoid = object(mesh, DVec3::ZERO, DVec3::new(0.0, 0.0, -6.0), [1.0; 4]);
    let observer = Observer {
        projection: srt_scene::Projection::Perspective,
        stereo: None,
        position: DVec3::ZERO,
        direction: -DVec3::Z,
        up: DVec3::Y,
        fov_y_deg: 30.0,
        time: 0.0,
    };
    let (_, _, rms, _) = outline_fit(&scene(vec![ellipsoid], observer), 512);
    println!("control ellipse: RMS {rms:.3} px");
    assert!(rms > 5.0, "the ellipse fitted a circle with RMS {rms} px");
}

/// Width in pixels of the front (+z) and trailing (−x) faces of a unit cube along the middle
/// row of a `size`-pixel image.
fn face_widths(scene: &Scene, size: u32) -> (f64, f64) {
    let tracer = Tracer::new(scene);
    let object = &scene.objects[0].parts[0].mesh;
    let (mut front, mut trailing) = (0.0, 0.0);
    let samples = 8;
    for x in 0..size * samples {
        let ndc = DVec2::new(
            2.0 * (f64::from(x) + 0.5) / f64::from(size * samples) - 1.0,
            0.0,
        );
        let Some(hit) = tracer.trace(scene.observer.view_direction(ndc, 1.0)) else {
            continue;
        };
        let normal = object.normals()[object.triangles()[hit.triangle][0] as usize];
        if normal.z > 0.99 {
            front += 1.0 / f64::from(samples);
        } else if normal.x < -0.99 {
            trailing += 1.0 / f64::from(samples);
        }
    }
    (front, trailing)
}

#[test]
fn terrell_a_passing_cube_appears_rotated_by_arcsin_beta() {
    // A unit cube moves along +x, far from the observer on the +z axis. The light that reaches
    // the observer along −z (perpendicular to the motion in S) left the cube when its centre
    // crossed x = 0 at t = 0; with ct_obs = D it arrives now. Terrell: the picture is the cube
    // rotated by θ = arcsin β, showing its trailing (−x) face with width sin θ and its front face
    // with width cos θ.
    let distance = 1000.0;
    for b in [0.5, 0.9] {
        let cube_object = object(cube(1.0, 1), DVec3::new(b, 0.0, 0.0), DVec3::ZERO, [1.0; 4]);
        let observer = Observer {
            projection: srt_scene::Projection::Perspective,
            stereo: None,
            position: DVec3::new(0.0, 0.0, distance),
            direction: -DVec3::Z,
            up: DVec3::Y,
            fov_y_deg: (2.0f64 / distance).atan().to_degrees(),
            time: distance,
        };
        let (front, trailing) = face_widths(&scene(vec![cube_object], observer), 800);
        let measured = trailing.atan2(front).to_degrees();
        let expected = b.asin().to_degrees();
        println!("Terrell β = {b}: measured rotation {measured:.3}°, arcsin β = {expected:.3}°");
        assert!(
            (measured - expected).abs() < 0.5,
            "β = {b}: rotation {measured}° vs arcsin β = {expected}°"
        );
    }
    // Control: at rest the trailing face is invisible.
    let at_rest = object(cube(1.0, 1), DVec3::ZERO, DVec3::ZERO, [1.0; 4]);
    let observer = Observer {
        projection: srt_scene::Projection::Perspective,
        stereo: None,
        position: DVec3::new(0.0, 0.0, distance),
        direction: -DVec3::Z,
        up: DVec3::Y,
        fov_y_deg: 0.1146,
        time: 0.0,
    };
    let (front, trailing) = face_widths(&scene(vec![at_rest], observer), 800);
    assert!(front > 300.0 && trailing == 0.0);
}

/// An ordinary ray tracer written independently of srt-trace: brute-force ray–triangle tests,
/// Phong shading with the same parameters, no relativity.
fn ordinary_ray_tracer(scene: &Scene, width: u32, height: u32) -> Vec<[u8; 3]> {
    let lut = srt_color::TemperatureLut::with_defaults(scene.tone_map);
    let [r, g, b, _] = lut.sample(scene.light.temperature_k);
    let light_colour = DVec3::new(f64::from(r), f64::from(g), f64::from(b));
    let aspect = f64::from(width) / f64::from(height);
    let mut out = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let ndc = DVec2::new(
                2.0 * (f64::from(x) + 0.5) / f64::from(width) - 1.0,
                1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(height),
            );
            let d = scene.observer.view_direction(ndc, aspect).normalize();
            let o = scene.observer.position;
            let mut best: Option<(f64, DVec3, f64)> = None;
            for obj in &scene.objects {
                let mesh = &obj.parts[0].mesh;
                let albedo = obj.parts[0].material.base_color.map(f64::from);
                for (i, tri) in mesh.triangles().iter().enumerate() {
                    let [a, bb, c] = mesh.triangle_positions(i).map(|p| p + obj.frame.offset());
                    // Solve o + t d = a + u (b − a) + v (c − a) with a 3×3 determinant.
                    let (e1, e2) = (bb - a, c - a);
                    let det = glam::DMat3::from_cols(e1, e2, -d).determinant();
                    if det == 0.0 {
                        continue;
                    }
                    let rhs = o - a;
                    let u = glam::DMat3::from_cols(rhs, e2, -d).determinant() / det;
                    let v = glam::DMat3::from_cols(e1, rhs, -d).determinant() / det;
                    let t = glam::DMat3::from_cols(e1, e2, rhs).determinant() / det;
                    if u < 0.0
                        || v < 0.0
                        || u + v > 1.0
                        || t <= 0.0
                        || best.is_some_and(|(bt, _, _)| bt <= t)
                    {
                        continue;
                    }
                    let n = mesh.normals();
                    let normal = ((1.0 - u - v) * n[tri[0] as usize]
                        + u * n[tri[1] as usize]
                        + v * n[tri[2] as usize])
                        .normalize();
                    let grey = grey_value(glam::DVec4::from_array(albedo));
                    best = Some((t, normal, grey));
                }
            }
            let colour = best.map_or(scene.background, |(t, mut normal, grey)| {
                let p = o + t * d;
                let to_light = (scene.light.position - p).normalize();
                let to_eye = -d;
                if normal.dot(to_eye) < 0.0 {
                    normal = -normal;
                }
                let cos = normal.dot(to_light);
                let s = scene.shading;
                let (diffuse, specular) = if cos > 0.0 {
                    let r = 2.0 * cos * normal - to_light;
                    (
                        s.diffuse * cos,
                        s.specular * r.dot(to_eye).max(0.0).powf(s.shininess),
                    )
                } else {
                    (0.0, 0.0)
                };
                (0.5 * (grey + 1.0) * (s.ambient + diffuse + specular) * light_colour)
                    .clamp(DVec3::ZERO, DVec3::ONE)
            });
            out.push(colour.to_array().map(|c| (c * 255.0).round() as u8));
        }
    }
    out
}

#[test]
fn at_rest_the_renderer_is_an_ordinary_ray_tracer() {
    let objects = vec![
        object(
            cube(1.5, 2),
            DVec3::ZERO,
            DVec3::new(-0.7, 0.1, -0.3),
            [0.9, 0.5, 0.2, 1.0],
        ),
        object(
            uv_sphere(0.8, 24),
            DVec3::ZERO,
            DVec3::new(0.9, 0.3, 0.4),
            [0.2, 0.6, 1.0, 1.0],
        ),
    ];
    let observer = Observer {
        projection: srt_scene::Projection::Perspective,
        stereo: None,
        position: DVec3::new(0.37, 1.21, 3.43),
        direction: DVec3::new(-0.05, -0.33, -1.0),
        up: DVec3::Y,
        fov_y_deg: 50.0,
        time: 17.0,
    };
    for effects in Effects::ALL {
        let mut s = scene(objects.clone(), observer);
        s.set_effects(effects);
        let (w, h) = (96, 64);
        let ours = Tracer::new(&s)
            .render(
                RenderSettings {
                    width: w,
                    height: h,
                    samples: 1,
                },
                &|_| {},
            )
            .to_rgb8();
        let reference = ordinary_ray_tracer(&s, w, h);
        let differing = ours.iter().zip(&reference).filter(|(a, b)| a != b).count();
        assert_eq!(
            differing,
            0,
            "{}: {differing} pixels differ from an ordinary ray tracer",
            effects.name()
        );
        let covered = ours.iter().filter(|p| **p != [0, 0, 0]).count();
        assert!(
            covered > 1000,
            "the objects are in view: only {covered} pixels"
        );
    }
}
