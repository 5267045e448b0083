//! An empty picture, explained: when no object covers any pixel of a rendered picture, where
//! each object is seen instead — behind the observer, how far off the view and to which side, or
//! in the view but covering no pixel (smaller than one, between pixel centres) — so that `srt
//! render fig4 --view measured` (the cube has passed the observer) says why its picture shows no
//! object instead of writing it without a word. Whether a pixel shows an object is what the
//! renderer knows of it ([`crate::engine::Drawn`]), not its colour: a starry sky varies an empty
//! picture's colours, and an object may be the colour of the background.
//!
//! Where an object is seen is the direction of the light from its centre (the middle of its
//! bounds in its rest frame) that reaches the observer at the observation event: the past light
//! cone's intersection with that point's worldline (Eq. 8 of Müller et al. 2010 for uniform
//! motion, found by bisection for every motion, spinning and thrusting bodies included).
//!
//! No picture is empty for light not yet emitted: every object's worldline reaches back to the
//! infinite past (uniform motion, spin, and a thrust at rest before it starts: srt-physics
//! `motion.rs`), so the observer's past light cone always meets it.

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

/// Why a picture of `scene` shows no object, if none of its pixels does (`seen`: per pixel,
/// whether it shows an object): one line naming where each object is seen. `None` when some
/// pixel shows an object, or the picture has no pixel.
#[must_use]
pub fn empty_picture_warning(scene: &Scene, seen: &[bool]) -> Option<String> {
    let mut objects = ObjectsSeen::default();
    objects.look_at(seen);
    objects.empty_warning(scene)
}

/// Whether any pixel of a picture seen a band of rows at a time shows an object (for
/// [`empty_picture_warning`]'s test on a picture never held whole).
#[derive(Debug, Clone, Copy, Default)]
pub struct ObjectsSeen {
    /// Whether any pixel was looked at.
    looked: bool,
    /// Whether some pixel showed an object.
    some: bool,
}

impl ObjectsSeen {
    /// Takes the next pixels of the picture into account: `seen` says, per pixel, whether it
    /// shows an object.
    pub fn look_at(&mut self, seen: &[bool]) {
        self.looked |= !seen.is_empty();
        self.some = self.some || seen.contains(&true);
    }

    /// [`empty_picture_warning`] for the picture of `scene` seen so far.
    #[must_use]
    pub fn empty_warning(&self, scene: &Scene) -> Option<String> {
        if self.some || !self.looked {
            return None;
        }
        let places: Vec<String> = (scene.objects.iter())
            .map(|object| format!("{} {}", object.name, describe(where_seen(scene, object))))
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
        Seen::InView => {
            "is in the view but covers no pixel (smaller than a pixel, or between pixel centres)"
                .to_owned()
        }
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

    /// Fig. 4's measured view at ct = 5.12 has the cube beside the observer, out of the view: a
    /// picture none of whose pixels shows an object is explained, band by band too; one pixel
    /// showing an object, in any band, silences it.
    #[test]
    fn an_empty_measured_fig4_is_explained() {
        let scene = built("fig4");
        let measured = View::Measured.apply(&scene).expect("a measured view");
        let none = vec![false; 16];
        let warning = empty_picture_warning(&measured, &none).expect("a warning");
        assert!(warning.contains("no object is in the view"), "{warning}");
        assert!(
            warning.contains("cube is seen outside the view"),
            "{warning}"
        );
        let mut one = none.clone();
        one[3] = true;
        assert_eq!(empty_picture_warning(&measured, &one), None);
        let mut bands = ObjectsSeen::default();
        bands.look_at(&none);
        bands.look_at(&one);
        bands.look_at(&none);
        assert_eq!(bands.empty_warning(&measured), None);
        assert_eq!(empty_picture_warning(&measured, &[]), None, "no picture");
    }

    /// An object whose centre is in the view but which covers no pixel is named as such.
    #[test]
    fn an_object_in_view_that_covers_no_pixel_is_explained() {
        let scene = built("fig4");
        let warning = empty_picture_warning(&scene, &[false; 16]).expect("a warning");
        assert!(
            warning.contains("cube is in the view but covers no pixel"),
            "{warning}"
        );
    }

    /// Fig. 4 under the built-in star field, drawn by the CPU engine: the measured view (the
    /// cube out of it) is warned about though the stars vary its colours; the seen view (the
    /// cube in it) is not.
    #[test]
    fn a_starry_picture_is_judged_by_the_objects_the_engine_sees() {
        let fig4 = srt_scene::builtin::find_builtin("fig4").expect("fig4");
        let mut description = fig4.description();
        description.sky = Some(srt_scene::description::SkyDescription {
            star_field: 4000,
            stars: None,
            saturation_magnitude: srt_scene::sky::DEFAULT_SATURATION_MAGNITUDE,
            image: None,
            image_brightness: 1.0,
        });
        let scene = fig4.build_description(&description).expect("builds").0;
        let measured = View::Measured.apply(&scene).expect("a measured view");
        let settings = srt_trace::RenderSettings {
            width: 32,
            height: 18,
            samples: 1,
        };
        let drawn = |scene: &Scene| {
            crate::engine::Engine::Cpu
                .draw(
                    &crate::engine::Frame::new(scene),
                    settings,
                    srt_trace::Output::Display,
                    &|_| {},
                    &std::sync::atomic::AtomicBool::new(false),
                )
                .expect("drawn")
                .expect("not stopped")
        };
        let empty = drawn(&measured);
        assert!(
            empty.pixels.iter().any(|pixel| *pixel != empty.pixels[0]),
            "the stars vary the picture"
        );
        let warning = empty_picture_warning(&measured, &empty.seen).expect("a warning");
        assert!(
            warning.contains("cube is seen outside the view"),
            "{warning}"
        );
        assert_eq!(empty_picture_warning(&scene, &drawn(&scene).seen), None);
    }
}
