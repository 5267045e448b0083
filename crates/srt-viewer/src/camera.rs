//! The fly camera: moving and turning the observer. Flying with the camera only changes where
//! the observation happens and where the camera looks, never the observer's velocity (the
//! throttle of [`crate::pilot`] does that).

use glam::{DQuat, DVec3};
use srt_scene::Observer;

/// Steepest pitch the camera turns to, in radians from the horizon (keeps `up` usable).
const MAX_PITCH: f64 = 1.55;

/// Keys held this frame, as a movement in the camera's own axes: `right` (D − A), `up` (E − Q)
/// and `forward` (W − S), each −1, 0 or 1.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Movement {
    /// D − A.
    pub right: f64,
    /// E − Q.
    pub up: f64,
    /// W − S.
    pub forward: f64,
}

impl Movement {
    /// Whether no movement key is held.
    #[must_use]
    pub fn is_zero(&self) -> bool {
        self.right == 0.0 && self.up == 0.0 && self.forward == 0.0
    }
}

/// The observer moved by `movement` at `speed` (S units per second) for `dt` seconds: forward
/// along the viewing direction, right along the image's right, up along the scene's up.
#[must_use]
pub fn fly(observer: &Observer, movement: Movement, speed: f64, dt: f64) -> Observer {
    let (forward, right, _) = observer.basis();
    let up = observer.up.normalize_or(DVec3::Z);
    let step =
        (forward * movement.forward + right * movement.right + up * movement.up) * speed * dt;
    Observer {
        position: observer.position + step,
        ..*observer
    }
}

/// The observer turned by `yaw` (about the scene's up; positive turns left) and `pitch`
/// (positive looks up) radians. The pitch stops short of straight up or down.
#[must_use]
pub fn turn(observer: &Observer, yaw: f64, pitch: f64) -> Observer {
    let up = observer.up.normalize_or(DVec3::Z);
    let direction = observer.direction.normalize_or(DVec3::Y);
    let current_pitch = direction.dot(up).clamp(-1.0, 1.0).asin();
    let target_pitch = (current_pitch + pitch).clamp(-MAX_PITCH, MAX_PITCH);
    let horizontal = (direction - up * direction.dot(up)).normalize_or(up.any_orthonormal_vector());
    let horizontal = DQuat::from_axis_angle(up, yaw) * horizontal;
    let direction = horizontal * target_pitch.cos() + up * target_pitch.sin();
    Observer {
        direction,
        ..*observer
    }
}

/// A flying speed suited to the scene, in S units per second: 30 % of the distance from the
/// observer to the farthest object's offset, at least 3.
#[must_use]
pub fn default_fly_speed(observer: &Observer, offsets: impl Iterator<Item = DVec3>) -> f64 {
    offsets
        .map(|o| (o - observer.position).length())
        .fold(10.0, f64::max)
        * 0.3
}

#[cfg(test)]
mod tests {
    use super::*;

    fn observer() -> Observer {
        Observer {
            projection: srt_scene::Projection::Perspective,
            stereo: None,
            position: DVec3::new(0.0, -10.0, 1.0),
            direction: DVec3::Y,
            up: DVec3::Z,
            fov_y_deg: 45.0,
            time: 0.0,
        }
    }

    #[test]
    fn flying_moves_in_camera_axes() {
        let o = observer();
        let moved = fly(
            &o,
            Movement {
                forward: 1.0,
                ..Movement::default()
            },
            2.0,
            0.5,
        );
        assert!((moved.position - DVec3::new(0.0, -9.0, 1.0)).length() < 1e-12);
        let moved = fly(
            &o,
            Movement {
                right: 1.0,
                up: -1.0,
                forward: 0.0,
            },
            1.0,
            1.0,
        );
        assert!((moved.position - DVec3::new(1.0, -10.0, 0.0)).length() < 1e-12);
        assert_eq!(moved.direction, o.direction);
    }

    #[test]
    fn turning_keeps_the_horizon_and_stops_before_the_pole() {
        let o = observer();
        let left = turn(&o, std::f64::consts::FRAC_PI_2, 0.0);
        assert!((left.direction - DVec3::NEG_X).length() < 1e-12);
        let up = turn(&o, 0.0, 10.0);
        assert!(up.direction.dot(DVec3::Z) < 1.0);
        assert!(up.direction.cross(up.up).length() > 1e-3);
        let back = turn(&turn(&o, 0.3, 0.2), 0.0, -0.2);
        assert!((back.direction.normalize().z).abs() < 1e-12);
    }
}
