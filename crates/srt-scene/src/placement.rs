//! Default placement of a bare model: a scene in which one object, scaled to a standard size,
//! flies with a given velocity and is seen in front of the camera at the observation time.
//!
//! The object is fitted (`fit = true`: centred at its S′ origin, bounding-sphere radius
//! [`FIT_RADIUS`]). The observer stands at a distance d from the S origin, seen from the front, a
//! little from the side and above ([`VIEW_FROM`]; so −y approaches it, +y recedes, +x crosses to
//! the right and +z rises), looks at the S origin and observes at ct = 0. The object moves, so
//! where it *is* at ct = 0 is not where it is *seen*: the light that reaches the observer at
//! ct = 0 from the S′ origin left it at ct = −d. Choosing `offset` = β·d puts the S′ origin at
//! the S origin at exactly that moment (x(t) = offset + β·ct), so its apparent position is the S
//! origin, straight ahead, whatever β is.
//!
//! The rest of the apparent object is stretched (approaching) or compressed (receding) along β
//! around that point, so d depends on β ([`framing_distance`]): [`VIEW_DISTANCE`] at rest, and
//! as far as it takes for the *seen* bounding sphere — every point's position when the light
//! that reaches the observer left it (Eq. 8) — to fill no more of the view than the resting one
//! does. A model approaching at 0.9c is so seen whole and in front of the camera instead of
//! reaching it (at d = 3.5 it would have passed the observer by ct = 0).

use std::path::Path;

use glam::DVec3;

use crate::description::{
    DEFAULT_LIGHT_TEMPERATURE_K, FIT_RADIUS, LightDescription, LightsDescription,
    ObjectDescription, ObserverDescription, RenderDescription, SceneDescription, ShapeDescription,
};
use crate::scene::SurfaceColour;

/// Distance from the observer to the apparent centre of a placed object, in S units (with
/// [`FIT_RADIUS`] = 1 and [`VIEW_FOV_Y_DEG`] the object at rest fills about 75 % of the image
/// height).
pub const VIEW_DISTANCE: f64 = 3.5;

/// Direction from the apparent centre of a placed object towards the observer (length 7, so
/// that the observer stands at (1, −3, 1.5)): in front (−y), a little to the right (+x) and
/// above (+z).
pub const VIEW_FROM: [f64; 3] = [2.0, -6.0, 3.0];

/// Vertical field of view of the observer of a placed object, in degrees.
pub const VIEW_FOV_Y_DEG: f64 = 45.0;

/// How much of the view's half-height (in normalised device coordinates) the seen bounding
/// sphere of a placed object may reach, in every direction: what the sphere at rest at
/// [`VIEW_DISTANCE`] reaches (tan(asin(1 / 3.5)) / tan(22.5°) = 0.7197).
pub const VIEW_FILL: f64 = 0.72;

/// Points on the bounding sphere whose seen positions [`framing_distance`] checks.
const FRAMING_SAMPLES: usize = 4096;

/// The distance from the observer at which an object fitted to [`FIT_RADIUS`] and moving with
/// `beta` is seen whole within [`VIEW_FILL`] of the view, placed as the
/// [module documentation](self) explains: [`VIEW_DISTANCE`] when that is enough (at rest, and
/// for slow or crossing motion), else the nearest distance that is, to 0.1 %. The seen sphere is
/// the apparent position (Eq. 8) of 4096 points (`FRAMING_SAMPLES`) of the sphere of radius
/// [`FIT_RADIUS`] (a fitted model lies inside it, and the seen image of the ball is bounded by
/// the seen image of its sphere); a point seen behind the observer (one that has passed it)
/// does not fit.
#[must_use]
pub fn framing_distance(beta: DVec3) -> f64 {
    if beta.length() >= 1.0 || !beta.is_finite() {
        return VIEW_DISTANCE;
    }
    let towards_observer = DVec3::from_array(VIEW_FROM).normalize();
    let (forward, up) = (-towards_observer, DVec3::Z);
    let right = forward.cross(up).normalize();
    let up = right.cross(forward);
    let tan_half = (0.5 * VIEW_FOV_Y_DEG.to_radians()).tan();
    let fits = |distance: f64| {
        let Ok(frame) = srt_physics::Frame::new(beta, beta * distance) else {
            return false;
        };
        let observer = towards_observer * distance;
        let event = srt_physics::Event::new(0.0, observer);
        fibonacci_sphere(FRAMING_SAMPLES).all(|point| {
            let seen = frame.apparent_position(point * FIT_RADIUS, event) - observer;
            let depth = seen.dot(forward);
            depth > 0.0
                && seen.dot(right).abs().max(seen.dot(up).abs()) <= VIEW_FILL * tan_half * depth
        })
    };
    if fits(VIEW_DISTANCE) {
        return VIEW_DISTANCE;
    }
    let (mut near, mut far) = (VIEW_DISTANCE, 2.0 * VIEW_DISTANCE);
    while !fits(far) {
        (near, far) = (far, 2.0 * far);
        if far > 1e6 {
            return far;
        }
    }
    while far - near > 1e-3 * near {
        let middle = 0.5 * (near + far);
        if fits(middle) {
            far = middle;
        } else {
            near = middle;
        }
    }
    far
}

/// `count` points spread evenly over the unit sphere (a Fibonacci lattice).
fn fibonacci_sphere(count: usize) -> impl Iterator<Item = DVec3> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    (0..count).map(move |k| {
        let z = 1.0 - (2.0 * k as f64 + 1.0) / count as f64;
        let ring = (1.0 - z * z).sqrt();
        let (sin, cos) = (golden_angle * k as f64).sin_cos();
        DVec3::new(ring * cos, ring * sin, z)
    })
}

/// Velocity of `speed` (units of c) straight towards the observer of a placed object: the
/// default motion of a bare model.
#[must_use]
pub fn approach_velocity(speed: f64) -> DVec3 {
    speed * DVec3::from_array(VIEW_FROM).normalize()
}

impl SceneDescription {
    /// A scene showing the model file `path` (stored as given: relative paths are resolved
    /// against the `base_dir` passed to [`SceneDescription::build`], usually the current
    /// folder) fitted to radius [`FIT_RADIUS`], moving with `beta` (units of c), placed as the
    /// [module documentation](self) explains, from [`framing_distance`] away, in spectral colour
    /// (the model keeps its own colours at rest and they shift as light does; the paper's grey
    /// reflectance would turn them grey). Named after the file stem (of a memory file,
    /// `memory:NAME`, NAME's).
    #[must_use]
    pub fn for_model(path: &Path, beta: DVec3) -> Self {
        let mut scene = Self::for_model_at(path, beta, framing_distance(beta));
        scene.render.colour = SurfaceColour::Spectral;
        scene
    }

    /// The scene of [`SceneDescription::for_model`] with the observer `distance` from the model's
    /// apparent centre and the default (the paper's) colour: the placement of the paper's
    /// comparisons (`distance` = [`VIEW_DISTANCE`]), which the benchmarks keep.
    #[must_use]
    pub fn for_model_at(path: &Path, beta: DVec3, distance: f64) -> Self {
        let mut object = ObjectDescription::new(ShapeDescription::Model {
            path: path.to_string_lossy().into_owned(),
        });
        object.name = path.file_stem().map(|s| {
            let stem = s.to_string_lossy();
            stem.strip_prefix(crate::assets::MEMORY_PREFIX)
                .unwrap_or(&stem)
                .to_owned()
        });
        object.fit = true;
        let mut scene = Self::for_object_at(object, beta, distance);
        scene.name.clone_from(&scene.objects[0].name);
        scene
    }

    /// A scene showing `object` moving with `beta`, its S′ origin seen at the S origin straight
    /// ahead of the observer at ct = 0, from [`framing_distance`] away (sets the object's `beta`
    /// and `offset`; the rest of the object is kept, so set `fit` for an object of unknown
    /// size).
    #[must_use]
    pub fn for_object(object: ObjectDescription, beta: DVec3) -> Self {
        Self::for_object_at(object, beta, framing_distance(beta))
    }

    /// [`SceneDescription::for_object`] with the observer `distance` from the object's apparent
    /// centre.
    #[must_use]
    pub fn for_object_at(mut object: ObjectDescription, beta: DVec3, distance: f64) -> Self {
        object.beta = beta.to_array();
        object.offset = (beta * distance).to_array();
        let from = DVec3::from_array(VIEW_FROM);
        let position = from * (distance / from.length());
        Self {
            name: None,
            description: None,
            observer: ObserverDescription {
                position: position.to_array(),
                look_at: Some([0.0; 3]),
                direction: None,
                beta: [0.0; 3],
                up: [0.0, 0.0, 1.0],
                fov_y_deg: VIEW_FOV_Y_DEG,
                ct: 0.0,
                time: None,
                projection: None,
                thrust: None,
                stereo: None,
            },
            light: Some(LightsDescription::Lamp(LightDescription::lamp(
                (position + DVec3::new(-1.0, 0.0, 2.0) * FIT_RADIUS * 2.0).to_array(),
                DEFAULT_LIGHT_TEMPERATURE_K,
            ))),
            render: RenderDescription::default(),
            objects: vec![object],
            sky: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use srt_physics::Frame;

    use super::*;

    #[test]
    fn the_placed_object_is_seen_straight_ahead() {
        for beta in [
            DVec3::ZERO,
            DVec3::new(0.0, -0.95, 0.0),
            DVec3::new(0.6, 0.5, -0.3),
        ] {
            let scene = SceneDescription::for_object(
                ObjectDescription::new(ShapeDescription::Sphere {
                    radius: 1.0,
                    segments: 8,
                }),
                beta,
            );
            let object = &scene.objects[0];
            let frame = Frame::new(
                DVec3::from_array(object.beta),
                DVec3::from_array(object.offset),
            )
            .unwrap();
            let observer = scene.observer.clone();
            let event = srt_physics::Event::new(observer.ct, DVec3::from_array(observer.position));
            let seen = frame.apparent_position(DVec3::ZERO, event);
            assert!(seen.length() < 1e-9, "{beta}: seen at {seen}");
            assert!(scene.validate().is_ok());
        }
    }

    /// At rest the observer stands at [`VIEW_DISTANCE`]; approaching head-on at 0.9c it stands
    /// back until the seen sphere fits (at 3.5 the object would have reached it), and that
    /// distance is the nearest that fits; receding needs no more room.
    #[test]
    fn the_seen_sphere_decides_the_distance() {
        assert!((framing_distance(DVec3::ZERO) - VIEW_DISTANCE).abs() < 1e-12);
        let approaching = approach_velocity(0.9);
        let far = framing_distance(approaching);
        assert!(far > VIEW_DISTANCE, "{far}");
        // The object's nearest point at ct = 0 is still in front of the observer.
        let towards_observer = DVec3::from_array(VIEW_FROM).normalize();
        let centre_gap = (towards_observer * far - approaching * far).length();
        let contracted_radius = FIT_RADIUS * (1.0 - 0.81_f64).sqrt();
        assert!(centre_gap > contracted_radius, "{centre_gap}");
        assert!(framing_distance(-approaching) <= VIEW_DISTANCE + 1e-12);
        assert!(framing_distance(DVec3::new(0.0, 0.0, 0.999)).is_finite());
    }

    #[test]
    fn for_model_fits_and_names() {
        let scene = SceneDescription::for_model(Path::new("models/ship.glb"), DVec3::X * 0.5);
        assert_eq!(scene.name.as_deref(), Some("ship"));
        assert!(scene.objects[0].fit);
        assert_eq!(
            scene.objects[0].shape,
            ShapeDescription::Model {
                path: "models/ship.glb".to_owned()
            }
        );
    }
}
