//! Default placement of a bare model: a scene in which one object, scaled to a standard size,
//! flies with a given velocity and is seen in front of the camera at the observation time.
//!
//! The object is fitted (`fit = true`: centred at its S′ origin, bounding-sphere radius
//! [`FIT_RADIUS`]). The observer stands at distance [`VIEW_DISTANCE`] from the S origin, seen
//! from the front, a little from the side and above ([`VIEW_FROM`]), looks at the S origin and
//! observes at ct = 0. The object moves, so where it *is* at ct = 0 is not where it is *seen*:
//! the light that reaches the observer at ct = 0 from the S′ origin left it at ct = −d, d being the
//! distance travelled. Choosing `offset` = β·d puts the S′ origin at the S origin at exactly that
//! moment (x(t) = offset + β·ct), so its apparent position is the S origin, straight ahead,
//! whatever β is. The rest of the apparent object is stretched (approaching) or compressed
//! (receding) along β around that point, but stays in front of the camera.

use std::path::Path;

use glam::DVec3;

use crate::description::{
    DEFAULT_LIGHT_TEMPERATURE_K, FIT_RADIUS, LightDescription, LightsDescription,
    ObjectDescription, ObserverDescription, RenderDescription, SceneDescription, ShapeDescription,
};

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
    /// [module documentation](self) explains. Named after the file stem (of a memory file,
    /// `memory:NAME`, NAME's).
    #[must_use]
    pub fn for_model(path: &Path, beta: DVec3) -> Self {
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
        let mut scene = Self::for_object(object, beta);
        scene.name.clone_from(&scene.objects[0].name);
        scene
    }

    /// A scene showing `object` moving with `beta`, its S′ origin seen at the S origin straight
    /// ahead of the observer at ct = 0 (sets the object's `beta` and `offset`; the rest of the
    /// object is kept, so set `fit` for an object of unknown size).
    #[must_use]
    pub fn for_object(mut object: ObjectDescription, beta: DVec3) -> Self {
        object.beta = beta.to_array();
        object.offset = (beta * VIEW_DISTANCE).to_array();
        let from = DVec3::from_array(VIEW_FROM);
        let position = from * (VIEW_DISTANCE / from.length());
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
