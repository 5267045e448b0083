//! Spinning and thrusting bodies on the CPU reference against independent light-cone
//! solutions, everything but the renderer's hits written out here: each pixel's backward ray
//! from the pinhole camera of the scene file's values and the Lorentz transformation of `seen`;
//! the body's worldlines in closed form from the scene file's values (a spin's rotation by
//! Rodrigues' formula, a thrust's Rindler hyperbolas as motion.rs documents them, inverted by
//! bisection over the body point's height) — not srt-physics' `Spin` or `Thrust`, nor the
//! renderer's rays, BVH, triangles, curve pieces or inverse maps; the body's analytic shape (a
//! cube's max-norm, a sphere's radius, the rolling wheel's 33 boxes through their scene-file
//! placements) met along the ray by dense sampling and bisection. Every hit's emission event is
//! checked to lie on the observer's past light cone along the pixel's ray and on the body's
//! surface at that time, where the solver meets it.

use glam::{DVec3, DVec4};
use srt_physics::RestRay;

use srt_scene::SceneDescription;
use srt_trace::{Hit, Tracer};

const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;

fn build(text: &str) -> srt_scene::Scene {
    let description = SceneDescription::from_toml_str(text, "test").unwrap();
    description.build(std::path::Path::new(".")).unwrap().0
}

/// The first ray parameter s in [0, `far`] where `inside(s)` (a signed depth: > 0 inside)
/// turns positive: sampled every `step`, then bisected to the f64 limit.
fn first_entry(inside: &dyn Fn(f64) -> f64, far: f64, step: f64) -> Option<f64> {
    let mut previous = 0.0;
    if inside(0.0) > 0.0 {
        return Some(0.0);
    }
    let mut s = step;
    while s <= far {
        if inside(s) > 0.0 {
            let (mut lo, mut hi) = (previous, s);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if inside(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Some(hi);
        }
        previous = s;
        s += step;
    }
    None
}

/// The pinhole camera of a scene file's `[observer]` at rest, from its values alone: where it
/// stands, the point it looks at, its vertical field of view and observation time; up is +z.
#[derive(Debug, Clone, Copy)]
struct Camera {
    position: DVec3,
    look_at: DVec3,
    fov_y_deg: f64,
    ct: f64,
}

impl Camera {
    /// The camera of a scene description's observer (at rest, up +z, looking at a point).
    fn of(observer: &srt_scene::ObserverDescription) -> Self {
        assert_eq!(observer.beta, [0.0; 3], "an observer at rest");
        assert_eq!(observer.up, [0.0, 0.0, 1.0], "up +z");
        Self {
            position: DVec3::from_array(observer.position),
            look_at: DVec3::from_array(observer.look_at.expect("a look_at")),
            fov_y_deg: observer.fov_y_deg,
            ct: observer.time.unwrap_or(observer.ct),
        }
    }

    /// The scene file's `[observer]` table of this camera.
    fn table(&self) -> String {
        format!(
            "[observer]\nposition = {:?}\nlook_at = {:?}\nup = [0.0, 0.0, 1.0]\n\
             fov_y_deg = {:?}\nct = {:?}\n",
            self.position.to_array(),
            self.look_at.to_array(),
            self.fov_y_deg,
            self.ct
        )
    }

    /// The unit viewing direction in S through the centre of pixel (`x`, `y`) of a `width` ×
    /// `height` picture: forward towards `look_at`, right = forward × up and up′ = right ×
    /// forward span the screen, tan(fov/2) its half height, y counted down from the top row.
    fn pixel_view(&self, (width, height): (u32, u32), x: u32, y: u32) -> DVec3 {
        let forward = (self.look_at - self.position).normalize();
        let right = forward.cross(DVec3::Z).normalize();
        let up = right.cross(forward);
        let tan = (self.fov_y_deg.to_radians() * 0.5).tan();
        let aspect = f64::from(width) / f64::from(height);
        let px = (2.0 * (f64::from(x) + 0.5) / f64::from(width) - 1.0) * tan * aspect;
        let py = (1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(height)) * tan;
        (forward + px * right + py * up).normalize()
    }
}

/// A pixel's backward ray built here, independently of the renderer's: the viewing direction
/// `view` in S ([`Camera::pixel_view`]) from the observation event, and the same light's path
/// in the object's rest frame S′ through the Lorentz transformation written out in `seen`
/// (Eq. 1–2: x′ = Λ_−β (x − a), a = (0, offset)).
struct PixelRay {
    /// The observation event in S: (ct, position).
    observer: DVec4,
    /// The unit viewing direction in S.
    view: DVec3,
    /// The object frame's velocity β relative to S.
    beta: DVec3,
    /// The object frame's origin at ct = 0, in S.
    offset: DVec3,
    /// The light's path in S′: `origin + s·direction` at ct′ = `ct_origin − s`.
    rest: RestRay,
    /// How far the light runs in S′ per unit of its travel time in S (ds′ / d(ct_obs − ct)).
    rest_per_apparent: f64,
}

impl PixelRay {
    /// The ray of pixel (`x`, `y`) of a `size` picture towards an object at rest in the frame
    /// of velocity `beta` and offset `offset` (the scene file's values).
    fn new(
        camera: &Camera,
        (beta, offset): (DVec3, DVec3),
        size: (u32, u32),
        x: u32,
        y: u32,
    ) -> Self {
        let view = camera.pixel_view(size, x, y);
        let to_rest = crate::seen::boost(-beta);
        let observer = DVec4::new(
            camera.ct,
            camera.position.x,
            camera.position.y,
            camera.position.z,
        );
        let origin = to_rest * (observer - DVec4::new(0.0, offset.x, offset.y, offset.z));
        // The light's path in S is (ct_obs − s, x_obs + s·view): in S′ it moves by
        // Λ_−β (−1, view) per unit of s, a null vector whose spatial part has length L.
        let along = to_rest * DVec4::new(-1.0, view.x, view.y, view.z);
        let spatial = DVec3::new(along.y, along.z, along.w);
        let length = spatial.length();
        Self {
            observer,
            view,
            beta,
            offset,
            rest: RestRay {
                origin: DVec3::new(origin.y, origin.z, origin.w),
                direction: spatial / length,
                ct_origin: origin.x,
            },
            rest_per_apparent: length,
        }
    }

    /// The renderer's hit checked against this ray: its emission event in S lies on the
    /// observer's past light cone (ct_obs − ct = |x − x_obs|) and along the pixel's viewing
    /// direction; returns how far along [`Self::rest`] that event lies in S′.
    fn distance_of(&self, hit: &Hit, context: &str) -> f64 {
        let dt = self.observer.x - hit.emission.ct;
        let dx =
            hit.emission.position - DVec3::new(self.observer.y, self.observer.z, self.observer.w);
        assert!(
            (dt - dx.length()).abs() <= 1e-9 * (1.0 + dt),
            "{context}: ct_obs − ct = {dt}, |Δx| = {}: not on the light cone",
            dx.length()
        );
        assert!(
            (dx - dt * self.view).length() <= 1e-9 * (1.0 + dt),
            "{context}: the event {dx} from the observer is off the viewing ray {}",
            self.view
        );
        let rest = crate::seen::boost(-self.beta)
            * DVec4::new(
                hit.emission.ct,
                hit.emission.position.x - self.offset.x,
                hit.emission.position.y - self.offset.y,
                hit.emission.position.z - self.offset.z,
            );
        self.rest.ct_origin - rest.x
    }
}

/// `v` turned by `angle` radians about the unit `axis`, right-handed (Rodrigues' formula).
fn rotate(axis: DVec3, angle: f64, v: DVec3) -> DVec3 {
    let (sin, cos) = angle.sin_cos();
    v * cos + axis.cross(v) * sin + axis * axis.dot(v) * (1.0 - cos)
}

/// A scene file's `spin`, its worldlines in closed form: the body point b is at
/// centre + R(axis, ω·ct′)(b − centre) at S′ time ct′.
#[derive(Debug, Clone, Copy)]
struct Spinning {
    /// The unit axis.
    axis: DVec3,
    /// ω, radians per unit of ct′.
    rate: f64,
    /// A point of the axis.
    centre: DVec3,
}

impl Spinning {
    /// The spin of the scene file's values.
    fn new(axis: [f64; 3], rate: f64, centre: [f64; 3]) -> Self {
        Self {
            axis: DVec3::from_array(axis).normalize(),
            rate,
            centre: DVec3::from_array(centre),
        }
    }

    /// The scene file's `spin` table of this spin.
    fn table(&self) -> String {
        format!(
            "spin = {{ axis = {:?}, rate = {:?}, centre = {:?} }}",
            self.axis.to_array(),
            self.rate,
            self.centre.to_array()
        )
    }

    /// The body point whose worldline passes through `x` at S′ time `ct`: the rotation by
    /// ω·ct′ undone.
    fn body_at(&self, x: DVec3, ct: f64) -> DVec3 {
        self.centre + rotate(self.axis, -self.rate * ct, x - self.centre)
    }
}

/// A scene file's `thrust`, its worldlines in closed form (motion.rs's documentation): the body
/// point at height ξ = b·â, X = 1/α + ξ, rests until ct₀, then x∥ + 1/α = X cosh η,
/// ct′ − ct₀ = X sinh η for η ≤ α·τ (for the origin x = (cosh(α τ₀) − 1)/α at proper time τ₀),
/// then coasts at tanh(α·τ) along â.
#[derive(Debug, Clone, Copy)]
struct Thrusting {
    /// The scene file's proper acceleration a of the origin.
    acceleration: DVec3,
    /// ct₀.
    start: f64,
    /// τ, the origin's proper time of thrust.
    duration: f64,
}

impl Thrusting {
    /// The scene file's `thrust` table of this thrust.
    fn table(&self) -> String {
        format!(
            "thrust = {{ proper_acceleration = {:?}, start = {:?}, duration = {:?} }}",
            self.acceleration.to_array(),
            self.start,
            self.duration
        )
    }

    /// x∥ at S′ time `ct` of the body point at height `xi`.
    fn height_at(&self, xi: f64, ct: f64) -> f64 {
        let alpha = self.acceleration.length();
        let big_x = 1.0 / alpha + xi;
        let elapsed = ct - self.start;
        if elapsed <= 0.0 {
            return xi;
        }
        let eta_end = alpha * self.duration;
        let eta = (elapsed / big_x).asinh();
        if eta <= eta_end {
            big_x * eta.cosh() - 1.0 / alpha
        } else {
            let coasting = elapsed - big_x * eta_end.sinh();
            big_x * eta_end.cosh() - 1.0 / alpha + coasting * eta_end.tanh()
        }
    }

    /// The body point whose worldline passes through `x` at S′ time `ct`, if any: its part
    /// across â kept, its height found by bisection of [`Self::height_at`] (which grows with ξ
    /// at any time) above the Rindler horizon ξ = −1/α.
    fn body_at(&self, x: DVec3, ct: f64) -> Option<DVec3> {
        let along = self.acceleration.normalize();
        let across = x - x.dot(along) * along;
        let target = x.dot(along);
        let (mut lo, mut hi) = (-0.999_999 / self.acceleration.length(), 1e3);
        if self.height_at(lo, ct) > target || self.height_at(hi, ct) < target {
            return None;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.height_at(mid, ct) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(across + 0.5 * (lo + hi) * along)
    }
}

/// Every pixel's backward ray ([`PixelRay`]) towards the (only) object moving with `frame`
/// (β, offset), with where the renderer's hit lies along it in the object's rest coordinates
/// and the body point the renderer shades there (`None`: background).
fn rays_and_hits(
    tracer: &Tracer<'_>,
    camera: &Camera,
    frame: (DVec3, DVec3),
) -> Vec<(RestRay, Option<(f64, DVec3)>)> {
    let mut out = Vec::new();
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let ray = PixelRay::new(camera, frame, (WIDTH, HEIGHT), x, y);
            let seen = tracer.hit_at_pixel(WIDTH, HEIGHT, x, y).map(|h| {
                let s = ray.distance_of(&h, &format!("pixel ({x}, {y})"));
                (s, tracer.surface_at(&h).body)
            });
            out.push((ray.rest, seen));
        }
    }
    out
}

#[test]
fn a_spinning_cube_is_where_the_light_cone_meets_it() {
    let camera = Camera {
        position: DVec3::new(0.3, -6.0, 1.2),
        look_at: DVec3::ZERO,
        fov_y_deg: 36.0,
        ct: 2.0,
    };
    let spin = Spinning::new([0.2, 0.1, 1.0], 0.7, [0.1, 0.0, 0.0]);
    let frame = (DVec3::new(0.3, 0.0, 0.0), DVec3::new(-0.6, 0.0, 0.0));
    let scene = build(&format!(
        "{}[[object]]\nshape = {{ type = \"cube\", size = 1.6, subdivisions = 2 }}\n{}\n\
         beta = {:?}\noffset = {:?}\n",
        camera.table(),
        spin.table(),
        frame.0.to_array(),
        frame.1.to_array()
    ));
    let tracer = Tracer::new(&scene);
    let (mut hits, mut worst_s, mut worst_body, mut worst_off) = (0, 0.0f64, 0.0f64, 0.0f64);
    for (ray, seen) in rays_and_hits(&tracer, &camera, frame) {
        // Depth inside the cube |b|∞ ≤ 0.8 of the body point at the ray's event (the observer
        // rests, so S′ time is the object's proper time).
        let body_at = |s: f64| spin.body_at(ray.origin + s * ray.direction, ray.ct_origin - s);
        let depth = |s: f64| 0.8 - body_at(s).abs().max_element();
        // Every body point is within 0.8·√3 + 0.1 < 1.6 of the spin centre: sample finely only
        // where the ray is that near it.
        let to_centre = spin.centre - ray.origin;
        let nearest = to_centre.dot(ray.direction);
        let miss = (to_centre - nearest * ray.direction).length();
        let expected = if miss > 1.6 {
            None
        } else {
            let half = (1.6f64 * 1.6 - miss * miss).sqrt();
            let from = (nearest - half).max(0.0);
            let shifted = |s: f64| depth(from + s);
            first_entry(&shifted, 2.0 * half, 0.001).map(|s| s + from)
        };
        match (seen, expected) {
            (Some((s, body)), Some(e)) => {
                hits += 1;
                worst_s = worst_s.max((s - e).abs() / e);
                worst_body = worst_body.max((body - body_at(e)).length());
                // The renderer's event on the cube's surface at its time.
                worst_off = worst_off.max(depth(s).abs());
            }
            (None, None) => {}
            (seen, expected) => {
                // A grazing ray may differ by a sample step at the silhouette: allow only
                // those, where the solver's entry depth stays within the sampling's reach.
                let s = seen.map_or_else(|| expected.unwrap(), |(s, _)| s);
                let graze = (0..=20)
                    .map(|k| depth(s - 0.001 + 0.0001 * f64::from(k)))
                    .fold(f64::MIN, f64::max);
                assert!(
                    graze < 1e-4,
                    "pixel disagrees: renderer {seen:?}, solver {expected:?}"
                );
            }
        }
    }
    eprintln!(
        "{hits} hits; worst relative s error {worst_s:e}, worst body point error \
         {worst_body:e}, worst distance off the surface {worst_off:e}"
    );
    assert!(hits > 300, "{hits} hits");
    assert!(worst_s < 1e-9, "relative s error {worst_s:e}");
    assert!(worst_body < 1e-8, "body point error {worst_body:e}");
    assert!(worst_off < 1e-8, "off the surface by {worst_off:e}");
}

/// A thrusting body of shape `shape` with the signed depth `inside(body point)` (> 0 inside):
/// every pixel's renderer hit against the solver's; returns the hits, the worst relative
/// error of the hit distance and the worst |depth| of the renderer's events.
fn thrusting(shape: &str, inside: &dyn Fn(DVec3) -> f64) -> (usize, f64, f64) {
    let camera = Camera {
        position: DVec3::new(0.0, -5.0, 0.5),
        look_at: DVec3::ZERO,
        fov_y_deg: 50.0,
        ct: 3.0,
    };
    let thrust = Thrusting {
        acceleration: DVec3::new(0.5, 0.0, 0.2),
        start: -2.0,
        duration: 3.0,
    };
    let scene = build(&format!(
        "{}[[object]]\nshape = {shape}\n{}\n",
        camera.table(),
        thrust.table()
    ));
    let tracer = Tracer::new(&scene);
    let (mut hits, mut worst_s, mut worst_off) = (0, 0.0f64, 0.0f64);
    for (ray, seen) in rays_and_hits(&tracer, &camera, (DVec3::ZERO, DVec3::ZERO)) {
        let body_at = |s: f64| thrust.body_at(ray.origin + s * ray.direction, ray.ct_origin - s);
        let depth = |s: f64| body_at(s).map_or(-1.0, inside);
        let expected = first_entry(&depth, 40.0, 0.01);
        match (seen, expected) {
            (Some((s, _)), Some(e)) => {
                hits += 1;
                worst_s = worst_s.max((s - e).abs() / e);
                worst_off = worst_off.max(depth(s).abs());
            }
            (None, None) => {}
            (seen, expected) => {
                let s = seen.map_or_else(|| expected.unwrap(), |(s, _)| s);
                let graze = (0..=20)
                    .map(|k| depth(s - 0.01 + 0.001 * f64::from(k)))
                    .fold(f64::MIN, f64::max);
                assert!(
                    graze < 2e-3,
                    "pixel disagrees: renderer {seen:?}, solver {expected:?}"
                );
            }
        }
    }
    (hits, worst_s, worst_off)
}

#[test]
fn a_thrusting_cube_and_sphere_are_where_the_light_cone_meets_them() {
    let (hits, worst, off) = thrusting(
        r#"{ type = "cube", size = 1.6, subdivisions = 2 }"#,
        &|b: DVec3| 0.8 - b.abs().max_element(),
    );
    eprintln!("cube: {hits} hits; worst relative s error {worst:e}, off the surface {off:e}");
    assert!(
        hits > 300 && worst < 1e-9 && off < 1e-8,
        "cube: {hits} hits, error {worst:e}, off the surface by {off:e}"
    );
    let (hits, worst, off) = thrusting(
        r#"{ type = "sphere", radius = 1.0, segments = 96 }"#,
        &|b: DVec3| 1.0 - b.length(),
    );
    eprintln!("sphere: {hits} hits; worst relative s error {worst:e}, off the surface {off:e}");
    // The sphere is a mesh of 96 segments and 48 rings, π/48 apart both ways: the solver's exact
    // sphere differs from it by the facets' sagitta along the ray, and a facet's middle lies
    // 1 − cos²(π/96) ≈ 1.07e-3 of the radius inside it (half a cell off both its rings and its
    // slices).
    assert!(
        hits > 300 && worst < 2e-3 && off < 1.1e-3,
        "sphere: {hits} hits, error {worst:e}, off the surface by {off:e}"
    );
}

#[test]
fn thrust_start_and_spin_keep_the_static_picture_before_they_act() {
    let text = |motion: &str| {
        format!(
            r#"
            [observer]
            position = [0.0, -6.0, 0.5]
            look_at = [0.0, 0.0, 0.0]
            ct = 0.0
            [[object]]
            shape = {{ type = "cube", size = 1.0 }}
            texture = "checker"
            {motion}
            "#
        )
    };
    let settings = srt_trace::RenderSettings {
        width: 80,
        height: 60,
        samples: 1,
    };
    let picture = |motion: &str| {
        let scene = build(&text(motion));
        Tracer::new(&scene).render(settings, &|_| {}).to_rgb8()
    };
    let still = picture("");
    // The light seen at ct = 0 left the cube about 6 units earlier, before ct′ = 1.
    let thrust_later = "thrust = { proper_acceleration = [0.0, 1.0, 0.0], start = 1.0 }";
    let spin_still = "spin = { axis = [0.2, 0.1, 1.0], rate = 0.0 }";
    for motion in [thrust_later, spin_still] {
        assert!(still == picture(motion), "{motion}: not the static picture");
    }
    // A thrust since ct′ = −10 has carried the cube away by then; a spin at 0.3 turned it.
    let thrust_earlier = "thrust = { proper_acceleration = [0.0, 1.0, 0.0], start = -10.0 }";
    let spin_turning = "spin = { axis = [0.2, 0.1, 1.0], rate = 0.3 }";
    for motion in [thrust_earlier, spin_turning] {
        assert!(still != picture(motion), "{motion}: the static picture");
    }
}

#[test]
fn the_built_in_moving_scenes_show_their_objects() {
    for (name, width, height) in [
        ("rocket", 160, 90),
        ("bell", 320, 180),
        ("rolling-wheel", 320, 180),
    ] {
        let (scene, _) = srt_scene::builtin::find_builtin(name)
            .unwrap()
            .build()
            .unwrap();
        let tracer = Tracer::new(&scene);
        let mut seen = vec![false; scene.objects.len()];
        for y in 0..height {
            for x in 0..width {
                if let Some(hit) = tracer.hit_at_pixel(width, height, x, y) {
                    seen[hit.object] = true;
                }
            }
        }
        let missing: Vec<_> = (scene.objects.iter().zip(&seen))
            .filter(|(_, seen)| !**seen)
            .map(|(o, _)| o.name.clone())
            .collect();
        assert!(missing.is_empty(), "{name}: not seen: {missing:?}");
    }
}

#[test]
fn the_rolling_wheel_is_where_the_light_cone_meets_it() {
    // The wheel's 33 parts as boxes: a body point b is inside part k when P_k⁻¹ b lies in the
    // unit cube its placement P_k (scale, rotation, translation of the scene file) maps from.
    let builtin = srt_scene::builtin::find_builtin("rolling-wheel").unwrap();
    let description = builtin.description();
    let (scene, _) = builtin.build().unwrap();
    let parts: Vec<glam::DMat4> = description.objects[1..]
        .iter()
        .map(|o| {
            let size = match o.shape {
                srt_scene::ShapeDescription::Cube { size, .. } => size,
                _ => panic!("the wheel is made of cubes"),
            };
            (o.placement() * glam::DMat4::from_scale(DVec3::splat(size))).inverse()
        })
        .collect();
    // The camera, the wheel's frame and its spin from the scene file's values (every part
    // has the same ones).
    let camera = Camera::of(&description.observer);
    let wheel = &description.objects[1];
    assert!(
        description.objects[1..]
            .iter()
            .all(|o| (o.beta, o.offset, o.spin) == (wheel.beta, wheel.offset, wheel.spin))
    );
    let frame = (
        DVec3::from_array(wheel.beta),
        DVec3::from_array(wheel.offset),
    );
    let spin = wheel.spin.expect("the wheel spins");
    let spin = Spinning::new(spin.axis, spin.rate, spin.centre);
    let tracer = Tracer::new(&scene);
    let (width, height) = (96u32, 54u32);
    let (mut hits, mut worst, mut worst_off) = (0, 0.0f64, 0.0f64);
    for y in 0..height {
        for x in 0..width {
            let hit = tracer.hit_at_pixel(width, height, x, y);
            let pixel = PixelRay::new(&camera, frame, (width, height), x, y);
            let ray = pixel.rest;
            let depth = |s: f64| {
                let b = spin.body_at(ray.origin + s * ray.direction, ray.ct_origin - s);
                parts
                    .iter()
                    .map(|inverse| 0.5 - inverse.transform_point3(b).abs().max_element())
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            // Within the ball of radius 1.1 around the axle only.
            let to_centre = spin.centre - ray.origin;
            let nearest = to_centre.dot(ray.direction);
            let miss = (to_centre - nearest * ray.direction).length();
            let expected = (miss < 1.1).then(|| {
                let half = (1.1f64 * 1.1 - miss * miss).sqrt();
                let from = (nearest - half).max(0.0);
                first_entry(&|s| depth(from + s), 2.0 * half, 0.002).map(|s| s + from)
            });
            match (hit.filter(|h| h.object >= 1), expected.flatten()) {
                (Some(h), Some(e)) => {
                    hits += 1;
                    let s = pixel.distance_of(&h, &format!("pixel ({x}, {y})"));
                    worst = worst.max((s - e).abs() / e);
                    worst_off = worst_off.max(depth(s).abs());
                }
                (None, None) => {}
                (None, Some(e)) => {
                    // The ground may hide it; otherwise only a graze thinner than the sampling.
                    let ground = tracer
                        .hit_at_pixel(width, height, x, y)
                        .filter(|h| h.object == 0)
                        .map(|h| h.apparent_distance);
                    let behind = ground.is_some_and(|g| e / pixel.rest_per_apparent > g - 1e-6);
                    let graze = (0..=20)
                        .map(|k| depth(e - 0.002 + 0.0002 * f64::from(k)))
                        .fold(f64::MIN, f64::max);
                    assert!(
                        behind || graze < 1e-3,
                        "pixel ({x}, {y}): solver {e}, renderer none"
                    );
                }
                (Some(h), None) => {
                    let s = pixel.distance_of(&h, &format!("pixel ({x}, {y})"));
                    let graze = (0..=20)
                        .map(|k| depth(s - 0.002 + 0.0002 * f64::from(k)))
                        .fold(f64::MIN, f64::max);
                    assert!(graze < 1e-3, "pixel ({x}, {y}): renderer {s}, solver none");
                }
            }
        }
    }
    eprintln!(
        "wheel: {hits} hits; worst relative s error {worst:e}, off the surface {worst_off:e}"
    );
    assert!(hits > 200, "{hits} hits");
    assert!(worst < 1e-9, "relative s error {worst:e}");
    assert!(worst_off < 1e-8, "off the surface by {worst_off:e}");
}
