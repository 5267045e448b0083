//! An empty picture, explained: when a rendered picture is one colour and no object is seen
//! in the view, where each object is seen instead — behind the observer, or how far off the view
//! and to which side — so that `srt render fig4 --view measured` (the cube has passed the
//! observer) says why its image is black instead of writing it without a word.
//!
//! Where an object is seen is the direction of the light from its centre (the middle of its
//! bounds in its rest frame) that reaches the observer at the observation event: the past light
//! cone's intersection with that point's worldline (Eq. 8 of Müller et al. 2010 for uniform
//! motion, found by bisection for every motion, spinning and thrusting bodies included).

use glam::{DVec2, DVec3};
use srt_physics::Event;
use srt_scene::{Object, Scene};

/// Where one object is seen, relative to the picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Seen {
    /// Its centre is in the picture.
    InView,
    /// Its centre is seen behind the observer: `angle_deg` (> 90) from the viewing direction.
    Behind {
        /// Angle between the viewing direction and the centre's direction, in degrees.
        angle_deg: f64,
    },
    /// Its centre is seen in front of the observer but outside the picture, towards `side`.
    Outside {
        /// Angle between the viewing direction and the centre's direction, in degrees.
        angle_deg: f64,
        /// "left", "right", "above" or "below": the way the picture would have to turn.
        side: &'static str,
    },
    /// Its light cannot be followed back (a centre the observer's past light cone does not
    /// cross within the bisection's reach).
    Unknown,
}

/// Why `display` (one frame's pixels) shows no object, if it is one colour and no object of
/// `scene` is seen in the view: one line naming where each object is seen. `None` when the
/// picture has any detail or some object's centre is in view (a picture that one object fills
/// is one colour too).
#[must_use]
pub fn empty_picture_warning(scene: &Scene, display: &[DVec3]) -> Option<String> {
    let mut colours = OneColour::default();
    colours.look_at(display);
    colours.empty_warning(scene)
}

/// Whether a picture seen a band of rows at a time is one colour (for
/// [`empty_picture_warning`]'s test on a picture never held whole).
#[derive(Debug, Clone, Copy, Default)]
pub struct OneColour {
    /// The first pixel seen.
    first: Option<DVec3>,
    /// Whether some pixel differed from it.
    varied: bool,
}

impl OneColour {
    /// Takes the next `pixels` of the picture into account.
    pub fn look_at(&mut self, pixels: &[DVec3]) {
        let Some(&head) = pixels.first() else {
            return;
        };
        let first = *self.first.get_or_insert(head);
        self.varied = self.varied || pixels.iter().any(|pixel| *pixel != first);
    }

    /// [`empty_picture_warning`] for the picture of `scene` seen so far.
    #[must_use]
    pub fn empty_warning(&self, scene: &Scene) -> Option<String> {
        if self.varied || self.first.is_none() {
            return None;
        }
        let seen: Vec<(String, Seen)> = (scene.objects.iter())
            .map(|object| (object.name.clone(), where_seen(scene, object)))
            .collect();
        if seen
            .iter()
            .any(|(_, where_seen)| *where_seen == Seen::InView)
        {
            return None;
        }
        let places: Vec<String> = seen
            .iter()
            .map(|(name, where_seen)| format!("{name} {}", describe(*where_seen)))
            .collect();
        Some(format!(
            "the picture is empty: no object is in the view at ct = {} ({})",
            scene.observer.time,
            places.join("; ")
        ))
    }
}

/// Words for where an object is seen.
fn describe(seen: Seen) -> String {
    match seen {
        Seen::InView => "is in the view".to_owned(),
        Seen::Behind { angle_deg } => {
            format!("is seen behind the observer, {angle_deg:.0}° from the viewing direction")
        }
        Seen::Outside { angle_deg, side } => format!(
            "is seen outside the view, {angle_deg:.0}° from the viewing direction, {side} of it"
        ),
        Seen::Unknown => "cannot be placed".to_owned(),
    }
}

/// Where `object`'s centre is seen in `scene`'s picture.
#[must_use]
pub fn where_seen(scene: &Scene, object: &Object) -> Seen {
    let observer = &scene.observer;
    let Some(direction) = seen_direction(object, observer.event()) else {
        return Seen::Unknown;
    };
    // The image's shape matters only for the perspective picture's sides; 16:9 as rendered
    // by default is close enough to say which way the object lies.
    let rays = observer.view_rays(16.0 / 9.0);
    if rays
        .image_point(direction)
        .is_some_and(|point| point.abs().max_element() <= 1.0)
    {
        return Seen::InView;
    }
    let (forward, right, up) = observer.basis();
    let angle_deg = direction.angle_between(forward).to_degrees();
    if angle_deg > 90.0 {
        return Seen::Behind { angle_deg };
    }
    let across = DVec2::new(direction.dot(right), direction.dot(up));
    let side = match (
        across.x.abs() >= across.y.abs(),
        across.x > 0.0,
        across.y > 0.0,
    ) {
        (true, true, _) => "right",
        (true, false, _) => "left",
        (false, _, true) => "above",
        (false, _, false) => "below",
    };
    Seen::Outside { angle_deg, side }
}

/// The direction (unit, in the observer's frame S) from which light from `object`'s centre
/// reaches the observation event `observer`; `None` when the bisection cannot bracket it.
fn seen_direction(object: &Object, observer: Event) -> Option<DVec3> {
    let (low, high) = object.parts.iter().map(|part| part.mesh.bounds()).fold(
        (DVec3::INFINITY, DVec3::NEG_INFINITY),
        |(low, high), (part_low, part_high)| (low.min(part_low), high.max(part_high)),
    );
    let centre = if low.is_finite() && high.is_finite() {
        0.5 * (low + high)
    } else {
        DVec3::ZERO
    };
    // The centre's event at rest-frame time ct′, in S, and how far inside the observer's past
    // light cone it is (> 0 inside, decreasing along the worldline).
    let event_at = |rest_ct: f64| {
        let place = object.motion.position(centre, rest_ct);
        object.frame.to_observer(Event::new(rest_ct, place))
    };
    let inside = |rest_ct: f64| {
        let event = event_at(rest_ct);
        (observer.ct - event.ct) - (observer.position - event.position).length()
    };
    let start = object.frame.to_rest(observer).ct;
    let (mut early, mut late) = (start - 1.0, start + 1.0);
    let mut step = 1.0;
    for _ in 0..200 {
        if inside(early) > 0.0 && inside(late) <= 0.0 {
            break;
        }
        step *= 2.0;
        if inside(early) <= 0.0 {
            early -= step;
        }
        if inside(late) > 0.0 {
            late += step;
        }
    }
    if !(inside(early) > 0.0 && inside(late) <= 0.0) {
        return None;
    }
    for _ in 0..200 {
        let middle = 0.5 * (early + late);
        if middle <= early || middle >= late {
            break;
        }
        if inside(middle) > 0.0 {
            early = middle;
        } else {
            late = middle;
        }
    }
    let emitted = event_at(late);
    (emitted.position - observer.position).try_normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use srt_scene::View;

    fn built(name: &str) -> Scene {
        srt_scene::builtin::find_builtin(name)
            .expect("a built-in scene")
            .build()
            .expect("builds")
            .0
    }

    /// The seen direction of a uniformly moving point is Eq. 8's apparent position.
    #[test]
    fn a_uniformly_moving_centre_is_seen_where_eq_8_puts_it() {
        let scene = built("fig4");
        let cube = &scene.objects[0];
        let event = scene.observer.event();
        let expected =
            (cube.frame.apparent_position(DVec3::ZERO, event) - event.position).normalize();
        let found = seen_direction(cube, event).expect("found");
        assert!(found.abs_diff_eq(expected, 1e-9), "{found} vs {expected}");
        assert_eq!(where_seen(&scene, cube), Seen::InView);
    }

    /// Fig. 4's measured view at ct = 5.12 has the cube beside the observer, out of the view:
    /// a black picture is explained; the seen picture is not warned about.
    #[test]
    fn an_empty_measured_fig4_is_explained() {
        let scene = built("fig4");
        let measured = View::Measured.apply(&scene).expect("a measured view");
        let black = vec![DVec3::ZERO; 16];
        let warning = empty_picture_warning(&measured, &black).expect("a warning");
        assert!(warning.contains("no object is in the view"), "{warning}");
        assert!(warning.contains("cube is seen"), "{warning}");
        assert_eq!(
            empty_picture_warning(&scene, &black),
            None,
            "the cube is in view"
        );
        let mut detailed = black;
        detailed[3] = DVec3::ONE;
        assert_eq!(empty_picture_warning(&measured, &detailed), None);
    }
}
