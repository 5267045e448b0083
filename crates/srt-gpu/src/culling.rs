//! The renderer's culling rules, in one place: back faces ([`BackFaceCulling`]; the renderer
//! sets [`PartFlags::CULL_BACK_FACES`](crate::types::PartFlags::CULL_BACK_FACES) by it every
//! frame, and `cargo xtask validate` checks every culled triangle against it), the ray tracer's
//! box faces ([`box_near_faces_cullable`]), and whole objects out of view
//! ([`ball_out_of_view`]) or between pixel centres ([`ball_between_pixel_centres`]; the
//! renderer then skips the object's footprints and draws, whatever the method); where an
//! object's image lies in a wide projection's picture ([`ball_wide_bound`], the rectangle its
//! box's footprint covers there); and the order objects are drawn in, nearest first
//! ([`ball_nearest_apparent_distance`]).
//!
//! In S′ every viewing ray starts at the observer's rest-frame position, so the rest-frame
//! picture is an ordinary pinhole view from there: for a closed solid with outward fronts and
//! the observer outside it, a triangle facing away from the observer is hidden. The proxy pass
//! (`proxy.wgsl`) then gives such a triangle an empty footprint.

use std::f64::consts::TAU;

use glam::DVec3;
use srt_physics::{Event, Frame, aberrate};
use srt_scene::{Mesh, Observer};

/// How far (radians, about) outside the field of view an object's image must lie to be culled:
/// room for the rounding of [`ball_out_of_view`]'s f64 arithmetic.
const VIEW_MARGIN: f64 = 1e-6;
/// The smallest angular radius (sine) a ball's cap is given in [`ball_out_of_view`], so that
/// the circle through three points of its rim stays well conditioned; a larger cap only culls
/// less.
const MIN_CAP_SINE: f64 = 1e-6;

/// A lower bound of the apparent distance of every point of the ball (`centre`, `radius`, in
/// S′) seen from the observation event `observer`, the key by which the renderer draws objects
/// nearest first (so that a GPU testing depth before a visibility fragment, `shaders::
/// ConservativeDepth`, skips more of those behind). As in `srt_proxy::nearest_apparent_distance`:
/// r(w′) = γ (|w′| − β·w′) ≥ γ (u − β)·w′ for a unit u, here the direction u to the centre
/// (offset c), and over the ball (u − β)·w′ ≥ (u − β)·c − |u − β|·radius. At least 0.
#[must_use]
pub fn ball_nearest_apparent_distance(
    centre: DVec3,
    radius: f64,
    frame: &Frame,
    observer: Event,
) -> f64 {
    let offset = centre - frame.to_rest(observer).position;
    let slope = offset.normalize_or_zero() - frame.beta();
    (frame.gamma() * (slope.dot(offset) - slope.length() * radius)).max(0.0)
}

/// Whether a mesh may have its back faces culled at all, and its box (computed once per upload).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BackFaceCulling {
    closed_outward: bool,
    /// The mesh's axis-aligned bounds at rest (min, max).
    bounds: (DVec3, DVec3),
}

impl BackFaceCulling {
    /// The rule for `mesh`: cullable when it is a closed solid with outward fronts.
    #[must_use]
    pub fn for_mesh(mesh: &Mesh) -> Self {
        Self {
            closed_outward: mesh.is_closed_outward(),
            bounds: mesh.bounds(),
        }
    }

    /// Whether the mesh is a closed solid with outward fronts (so that its back faces may be
    /// culled wherever the observer is outside it).
    #[must_use]
    pub fn closed_outward(self) -> bool {
        self.closed_outward
    }

    /// Whether back faces of `mesh` (the one this rule was made for), at rest in `frame`, may
    /// be culled for the observation event `observer`: the mesh is closed and the observer's
    /// rest-frame position lies outside it — outside its box (where the winding number is 0,
    /// decided without a pass over the mesh), or of winding number ≈ 0.
    #[must_use]
    pub fn applies(self, mesh: &Mesh, frame: &Frame, observer: Event) -> bool {
        if !self.closed_outward {
            return false;
        }
        let position = frame.to_rest(observer).position;
        let (lo, hi) = self.bounds;
        // Rounding room: a point this far outside the box is outside the mesh.
        let margin = 1e-9 * (hi - lo).max_element().max(position.abs().max_element());
        let outside_box = position.cmplt(lo - margin).any() || position.cmpgt(hi + margin).any();
        outside_box || mesh.winding_number(position).abs() < 0.5
    }
}

/// Whether the ray tracer may cull the faces of an object's box `min`–`max` (in S′) that are
/// turned towards an observer at `observer` (S′; the box is wound inward, so the proxy pass's
/// back-face test culls those): only when the observer is outside the box by more than f32
/// rounding can blur, on the outer side of some face plane and off every face plane. A ray from
/// outside that reaches into a box leaves it again through a face turned away from its origin,
/// so the footprints of those faces then hold every pixel that sees into the box; otherwise all
/// twelve triangles are drawn.
#[must_use]
pub fn box_near_faces_cullable(min: [f32; 3], max: [f32; 3], observer: glam::DVec3) -> bool {
    let size = (0..3)
        .map(|axis| f64::from(max[axis] - min[axis]).abs())
        .fold(0.0, f64::max);
    let reach = (0..3)
        .map(|axis| f64::from(min[axis].abs().max(max[axis].abs())).max(observer[axis].abs()))
        .fold(0.0, f64::max);
    let tolerance = 1e-4 * (size + reach);
    let mut outside = false;
    for axis in 0..3 {
        let below = f64::from(min[axis]) - observer[axis];
        let above = observer[axis] - f64::from(max[axis]);
        if below.abs() <= tolerance || above.abs() <= tolerance {
            return false;
        }
        outside |= below > 0.0 || above > 0.0;
    }
    outside
}

/// Whether no pixel of an image of `aspect` (width / height) taken by `observer` can see
/// anything inside the ball of `radius` around `centre`, at rest in `frame` (S′): the exact
/// methods' viewing rays and the polygon method's triangles alike miss the screen.
///
/// In S′ the backward viewing rays are straight lines from the observer's rest-frame position
/// P′ (Eq. 5), and the directions that reach the ball form a cap around the direction to its
/// centre, of angular radius asin(radius / distance). The viewing directions in S that map to
/// it (the inverse of Eq. 3, [`aberrate`] with β) form a cap again: the Lorentz transformation
/// acts on the sphere of directions as a Möbius transformation, which takes circles to
/// circles. The image cap is the side of the plane through three images of the rim that holds
/// the centre's image (`ImageCap`). The object is out of view when that cap lies wholly
/// outside one of the four side planes of the view pyramid. The polygon method's triangles are
/// the convex hulls (in homogeneous coordinates) of vertex images inside that cap, so they are
/// clipped away too. An observer inside the ball, or non-finite input, is never culled.
#[must_use]
pub fn ball_out_of_view(
    centre: DVec3,
    radius: f64,
    frame: &Frame,
    observer: &Observer,
    aspect: f64,
) -> bool {
    let Some(cap) = ImageCap::of_ball(centre, radius, frame, observer) else {
        return false;
    };
    if !aspect.is_finite() {
        return false;
    }
    let (forward, right, up) = observer.basis();
    let tan_y = (0.5 * observer.fov_y_deg.to_radians()).tan();
    let tan_x = tan_y * aspect;
    // The view pyramid: n·d ≥ 0 for each side plane's n.
    let sides = [
        tan_x * forward - right,
        tan_x * forward + right,
        tan_y * forward - up,
        tan_y * forward + up,
    ];
    sides.into_iter().any(|side| cap.below(side, VIEW_MARGIN))
}

/// Whether the ball of `radius` around `centre`, at rest in `frame`, is seen in an image of
/// `width` × `height` pixels taken by `observer` but covers no pixel's centre: its image cap
/// ([`ball_out_of_view`]) lies in front of the observer and strictly between two neighbouring
/// columns, or two neighbouring rows, of pixel centres. Every method samples a pixel at its
/// centre only (the exact methods' viewing ray, the rasteriser's coverage of the polygon
/// method's triangles, whose vertex images lie in the cap), so such an object adds nothing to
/// the image, however near its picture comes to a pixel. The planes through the observer and a
/// column (row) of centres are moved towards the cap by `PIXEL_CENTRE_MARGIN` of a pixel, so
/// that a rasteriser's sub-pixel snapping cannot bring a triangle over a centre.
#[must_use]
pub fn ball_between_pixel_centres(
    centre: DVec3,
    radius: f64,
    frame: &Frame,
    observer: &Observer,
    width: u32,
    height: u32,
) -> bool {
    let Some(cap) = ImageCap::of_ball(centre, radius, frame, observer) else {
        return false;
    };
    if width == 0 || height == 0 {
        return false;
    }
    let (forward, right, up) = observer.basis();
    if !cap.below(-forward, VIEW_MARGIN) {
        // Some of the cap is beside or behind the observer: the screen's tangents are unbounded.
        return false;
    }
    let tan_y = (0.5 * observer.fov_y_deg.to_radians()).tan();
    let tan_x = tan_y * f64::from(width) / f64::from(height);
    let seen = cap.centre_image;
    let depth = forward.dot(seen);
    // Between two neighbouring lines of centres along one screen axis: `axis` (right or up),
    // the half-extent `tan` of the field of view along it and `pixels` centres. A direction x
    // in front has the coordinate w(x) = axis·x / forward·x there; the lines are at
    // w = line(k) = −tan + (k + ½)·pitch, k = 0 … pixels − 1 (counted from the left, or from
    // the bottom: the rows' lines are the same set).
    let between = |axis: DVec3, tan: f64, pixels: u32| {
        let pitch = 2.0 * tan / f64::from(pixels);
        let line = |k: f64| -tan + (k + 0.5) * pitch;
        // The centre image's position on the lines' count.
        let at = (axis.dot(seen) / depth + tan) / pitch - 0.5;
        if !at.is_finite() {
            return false;
        }
        let before = at.floor();
        let margin = PIXEL_CENTRE_MARGIN * pitch;
        // line(before) + margin < w(x) < line(before + 1) − margin over the whole cap, i.e.
        // n·x < 0 for the two planes' n (forward·x > 0 there); a missing line bounds nothing.
        let after_before =
            before < 0.0 || cap.below((line(before) + margin) * forward - axis, VIEW_MARGIN);
        let before_after = before + 1.0 > f64::from(pixels - 1)
            || cap.below(axis - (line(before + 1.0) - margin) * forward, VIEW_MARGIN);
        after_before && before_after
    };
    between(right, tan_x, width) || between(up, tan_y, height)
}

/// Of a pixel's pitch, how far a ball's image must stay from a line of pixel centres to be
/// culled by [`ball_between_pixel_centres`]: 1/64, four times the 1/256 of a pixel to which
/// common rasterisers snap vertices.
const PIXEL_CENTRE_MARGIN: f64 = 1.0 / 64.0;

/// How far (radians) a wide projection's bound of an object's image reaches beyond its cap: room
/// for the GPU's f32 viewing directions.
const WIDE_ANGLE_MARGIN: f64 = 1e-4;
/// How many pixels a wide projection's bound reaches beyond the cap's image: room for the
/// rasteriser's coverage of the bound's edges.
const WIDE_PIXEL_MARGIN: f64 = 1.5;

/// The rectangle (pixels of a `width` × `height` picture: min x, min y, max x, max y, pixel
/// centres at half-integers) holding every pixel whose viewing ray in `observer`'s wide
/// projection (equirectangular or fisheye) may reach the ball of `radius` around `centre` at
/// rest in `frame`; empty (min ≥ max) when none does (outside a fisheye's field), and the whole
/// picture where the image may be anywhere (the observer inside the ball, a cap around a pole
/// of the projection, non-finite input) or for the pinhole.
///
/// The ball's image is a cap on the sphere of viewing directions ([`ball_out_of_view`] says
/// why), of axis m and angular radius r, which the projection bounds
/// ([`srt_scene::Projection::cap_bound`]).
#[must_use]
pub fn ball_wide_bound(
    centre: DVec3,
    radius: f64,
    frame: &Frame,
    observer: &Observer,
    width: u32,
    height: u32,
) -> [f64; 4] {
    let (width, height) = (f64::from(width), f64::from(height));
    let whole = [0.0, 0.0, width, height];
    let Some(cap) = ImageCap::of_ball(centre, radius, frame, observer) else {
        return whole;
    };
    let r = cap.height.clamp(-1.0, 1.0).acos() + WIDE_ANGLE_MARGIN;
    // Normalised device coordinates (x right, y up) of the bound, or None for the whole picture.
    let ndc = (observer.projection).cap_bound(cap.axis, r, observer.basis());
    let Some([x0, y0, x1, y1]) = ndc.filter(|b| b.iter().all(|v| v.is_finite())) else {
        return whole;
    };
    // Pixels: x = (ndc.x + 1) W / 2, y = (1 − ndc.y) H / 2 (y down).
    [
        ((x0 + 1.0) * 0.5 * width - WIDE_PIXEL_MARGIN).max(0.0),
        ((1.0 - y1) * 0.5 * height - WIDE_PIXEL_MARGIN).max(0.0),
        ((x1 + 1.0) * 0.5 * width + WIDE_PIXEL_MARGIN).min(width),
        ((1.0 - y0) * 0.5 * height + WIDE_PIXEL_MARGIN).min(height),
    ]
}

/// Samples a side of the grid of viewing directions [`ball_seen_pixels`] counts a ball's
/// image on (32 × 32 over the picture).
const SEEN_GRID: u32 = 32;
/// Fewer grid samples than this in a ball's image and [`ball_seen_pixels`] measures it from
/// its solid angle instead: a small image falls between the samples.
const SEEN_GRID_LEAST: u32 = 16;

/// About how many pixels of a `width` × `height` picture see the ball of `radius` around
/// `centre` at rest in `frame`: its image cap ([`ball_out_of_view`] says why it is a cap)
/// counted on a 32 × 32 grid of the picture's viewing directions, or, for an image of fewer
/// than 16 samples whose centre is in the picture, its solid angle 2π(1 − h) times the
/// picture's pixels per steradian at the centre's image; the whole picture for an observer
/// inside the ball. An estimate of an object's screen size for `auto`'s choice of method
/// ([`crate::auto`]), in any projection; no culling depends on it.
#[must_use]
pub fn ball_seen_pixels(
    centre: DVec3,
    radius: f64,
    frame: &Frame,
    observer: &Observer,
    width: u32,
    height: u32,
) -> f64 {
    let pixels = f64::from(width) * f64::from(height);
    let Some(cap) = ImageCap::of_ball(centre, radius, frame, observer) else {
        return pixels;
    };
    let rays = observer.view_rays(f64::from(width) / f64::from(height));
    let at = |k: u32| (f64::from(k) + 0.5) / f64::from(SEEN_GRID) * 2.0 - 1.0;
    let inside = (0..SEEN_GRID * SEEN_GRID)
        .filter(|k| {
            let ndc = glam::DVec2::new(at(k % SEEN_GRID), at(k / SEEN_GRID));
            rays.direction(ndc)
                .and_then(DVec3::try_normalize)
                .is_some_and(|d| cap.axis.dot(d) >= cap.height)
        })
        .count() as f64;
    let counted = inside / f64::from(SEEN_GRID * SEEN_GRID) * pixels;
    if inside >= f64::from(SEEN_GRID_LEAST) {
        return counted;
    }
    // Pixels per steradian at the centre's image: the picture's area over the solid angle of
    // a small square of directions around it, from the image points of its corners.
    let centre_image = cap.centre_image;
    let Some(middle) = rays
        .image_point(centre_image)
        .filter(|p| p.x.abs() <= 1.0 && p.y.abs() <= 1.0)
    else {
        // The centre's image is outside the picture: the samples' count, if any.
        return counted;
    };
    let step = 1e-4;
    let (e1, e2) = centre_image.any_orthonormal_pair();
    let image_of = |d: DVec3| rays.image_point(d).map(|p| p - middle);
    let (Some(a), Some(b)) = (
        image_of(centre_image + step * e1),
        image_of(centre_image + step * e2),
    ) else {
        return 0.0;
    };
    let ndc_per_steradian = a.perp_dot(b).abs() / (step * step);
    let solid_angle = TAU * (1.0 - cap.height);
    (solid_angle * ndc_per_steradian * pixels / 4.0).min(pixels)
}

/// The viewing directions in S (unit vectors x with m·x ≥ h) whose backward rays reach a ball
/// at rest in S′, as [`ball_out_of_view`] derives them.
struct ImageCap {
    /// The cap's axis m (unit).
    axis: DVec3,
    /// Its height h: the cosine of its angular radius.
    height: f64,
    /// The viewing direction (unit) of the ball's centre, a point of the cap.
    centre_image: DVec3,
}

impl ImageCap {
    /// The image cap of the ball of `radius` around `centre` at rest in `frame`, seen by
    /// `observer`, slightly enlarged for rounding; none for an observer inside the ball or
    /// non-finite input.
    fn of_ball(centre: DVec3, radius: f64, frame: &Frame, observer: &Observer) -> Option<Self> {
        let origin = frame.to_rest(observer.event()).position;
        let towards = centre - origin;
        let distance = towards.length();
        let radius = radius * (1.0 + 1e-6) + 1e-9 * (1.0 + centre.length() + origin.length());
        if !distance.is_finite() || !radius.is_finite() || distance <= radius {
            return None;
        }
        let axis = towards / distance;
        let sine = (radius / distance).max(MIN_CAP_SINE);
        let cosine = (1.0 - sine * sine).sqrt();
        // The viewing direction in S whose backward ray runs along `rest` in S′.
        let view_of = |rest: DVec3| -aberrate(frame.beta(), -rest).normalize();
        let (e1, e2) = axis.any_orthonormal_pair();
        let rim = [0.0, 1.0, 2.0].map(|k: f64| {
            let phi = k * TAU / 3.0;
            view_of(cosine * axis + sine * (phi.cos() * e1 + phi.sin() * e2))
        });
        let normal = (rim[1] - rim[0]).cross(rim[2] - rim[0]).try_normalize()?;
        let offset = normal.dot(rim[0]);
        let centre_image = view_of(axis);
        // The side of the rim's plane that holds the centre's image.
        let (axis, height) = if normal.dot(centre_image) >= offset {
            (normal, offset)
        } else {
            (-normal, -offset)
        };
        Some(Self {
            axis,
            height,
            centre_image,
        })
    }

    /// Whether n·x < −margin for every x of the cap (n normalised here; false for n = 0).
    fn below(&self, n: DVec3, margin: f64) -> bool {
        n.try_normalize()
            .is_some_and(|n| highest_on_cap(n, self.axis, self.height) < -margin)
    }
}

/// The largest n·x over the unit vectors x of the cap m·x ≥ h (n, m unit vectors).
fn highest_on_cap(n: DVec3, m: DVec3, h: f64) -> f64 {
    let c = n.dot(m);
    if c >= h {
        1.0
    } else {
        c * h + (1.0 - c * c).max(0.0).sqrt() * (1.0 - h * h).max(0.0).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::{
        BackFaceCulling, ball_between_pixel_centres, ball_nearest_apparent_distance,
        ball_out_of_view, ball_seen_pixels, ball_wide_bound, box_near_faces_cullable,
    };
    use glam::{DVec2, DVec3};
    use proptest::prelude::*;
    use srt_physics::{Event, Frame, aberrate};
    use srt_scene::{Observer, Projection};
    use std::f64::consts::TAU;

    proptest! {
        /// The box's shortcut decides as the winding number does: a moving closed sphere's back
        /// faces are culled exactly when the observer's rest-frame position is outside it, near
        /// its surface and its box's faces included; an open mesh's never.
        #[test]
        fn back_face_culling_follows_the_winding_number(
            x in -1.6f64..1.6, y in -1.6f64..1.6, z in -1.6f64..1.6, ct in -3.0f64..3.0,
        ) {
            let sphere = srt_scene::shapes::uv_sphere(1.0, 24);
            let frame = Frame::new(DVec3::new(0.3, -0.5, 0.2), DVec3::new(0.4, 0.1, -0.2)).unwrap();
            let rule = BackFaceCulling::for_mesh(&sphere);
            let observer = frame.to_observer(Event { ct, position: DVec3::new(x, y, z) });
            let rest = frame.to_rest(observer).position;
            let outside = sphere.winding_number(rest).abs() < 0.5;
            prop_assert_eq!(rule.applies(&sphere, &frame, observer), outside);
            let open = srt_scene::Mesh::new(
                vec![DVec3::ZERO, DVec3::X, DVec3::Y],
                vec![[0, 1, 2]],
            ).unwrap();
            prop_assert!(!BackFaceCulling::for_mesh(&open).applies(&open, &frame, observer));
        }
    }

    /// An observer at the origin looking along +z with a 60° vertical field of view.
    fn looking_along_z(ct: f64) -> Observer {
        Observer {
            projection: srt_scene::Projection::Perspective,
            stereo: None,
            position: DVec3::ZERO,
            direction: DVec3::Z,
            up: DVec3::Y,
            fov_y_deg: 60.0,
            time: ct,
        }
    }

    /// Whether some viewing ray through a grid of `n` × `n` points of the image (corners and
    /// edges included) hits the ball, traced exactly in S′ (Eq. 3 and 5 through
    /// `Frame::backward_ray`).
    fn some_ray_hits(
        centre: DVec3,
        radius: f64,
        frame: &Frame,
        observer: &Observer,
        aspect: f64,
        n: u32,
    ) -> bool {
        (0..n * n).any(|k| {
            let ndc = DVec2::new(
                -1.0 + 2.0 * f64::from(k % n) / f64::from(n - 1),
                -1.0 + 2.0 * f64::from(k / n) / f64::from(n - 1),
            );
            let ray = frame.backward_ray(observer.event(), observer.view_direction(ndc, aspect));
            let along = (centre - ray.origin).dot(ray.direction).max(0.0);
            (ray.origin + along * ray.direction - centre).length() <= radius
        })
    }

    /// The pixels of a `width` × `height` image whose viewing ray, through the pixel's centre
    /// (the one sample of every method) and traced exactly in S′, hits the ball.
    fn pixels_hit(
        centre: DVec3,
        radius: f64,
        frame: &Frame,
        observer: &Observer,
        (width, height): (u32, u32),
    ) -> usize {
        let aspect = f64::from(width) / f64::from(height);
        (0..width * height)
            .filter(|k| {
                let ndc = DVec2::new(
                    2.0 * (f64::from(k % width) + 0.5) / f64::from(width) - 1.0,
                    1.0 - 2.0 * (f64::from(k / width) + 0.5) / f64::from(height),
                );
                let direction = observer.view_direction(ndc, aspect);
                let ray = frame.backward_ray(observer.event(), direction);
                let along = (centre - ray.origin).dot(ray.direction).max(0.0);
                (ray.origin + along * ray.direction - centre).length() <= radius
            })
            .count()
    }

    #[test]
    fn a_ball_between_pixel_centres_is_culled_and_one_over_a_centre_is_kept() {
        // A 4 × 4 image with a 90° field of view: the centres' tangents are ±0.25 and ±0.75.
        let observer = Observer {
            fov_y_deg: 90.0,
            ..looking_along_z(0.0)
        };
        let at_rest = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
        let size = (4, 4);
        // At the image's centre, between the four middle pixels' centres, 0.05 across at 10.
        let middle = DVec3::new(0.0, 0.0, 10.0);
        assert_eq!(pixels_hit(middle, 0.05, &at_rest, &observer, size), 0);
        assert!(ball_between_pixel_centres(
            middle, 0.05, &at_rest, &observer, 4, 4
        ));
        // The same ball over the centre of pixel (2, 1), at tangents (0.25, 0.25).
        let over = DVec3::new(2.5, 2.5, 10.0);
        assert_eq!(pixels_hit(over, 0.05, &at_rest, &observer, size), 1);
        assert!(!ball_between_pixel_centres(
            over, 0.05, &at_rest, &observer, 4, 4
        ));
        // Between two columns but across a row of centres: culled; grown over a centre: kept.
        let across_row = DVec3::new(0.0, 2.5, 10.0);
        assert!(ball_between_pixel_centres(
            across_row, 0.3, &at_rest, &observer, 4, 4
        ));
        assert!(!ball_between_pixel_centres(
            across_row, 3.0, &at_rest, &observer, 4, 4
        ));
        // Beyond the last column's centres but still on the image: culled.
        let edge = DVec3::new(9.0, 0.0, 10.0);
        assert_eq!(pixels_hit(edge, 0.1, &at_rest, &observer, size), 0);
        assert!(ball_between_pixel_centres(
            edge, 0.1, &at_rest, &observer, 4, 4
        ));
        // Moving at 0.9c across the view, the same small ball's image is carried to another
        // place (aberration): where it lands over a centre it is kept, whatever its rest place.
        // Each ball is put on the rest-frame ray of a pixel's centre (Eq. 3 and 5 through
        // `Frame::backward_ray`), 5 to 20 units out; at rest in S the same place is seen
        // elsewhere.
        let crossing = Frame::new(DVec3::new(0.9, 0.0, 0.0), DVec3::ZERO).unwrap();
        let mut missed_at_rest = 0;
        for (x, y) in [(0, 0), (1, 2), (2, 1), (3, 3)] {
            let ndc = DVec2::new(
                2.0 * (f64::from(x) + 0.5) / 4.0 - 1.0,
                1.0 - 2.0 * (f64::from(y) + 0.5) / 4.0,
            );
            let ray = crossing.backward_ray(observer.event(), observer.view_direction(ndc, 1.0));
            for distance in [5.0, 10.0, 20.0] {
                let ball = ray.origin + distance * ray.direction;
                assert!(
                    pixels_hit(ball, 0.05, &crossing, &observer, size) > 0,
                    "{ball}"
                );
                assert!(
                    !ball_between_pixel_centres(ball, 0.05, &crossing, &observer, 4, 4),
                    "pixel ({x}, {y}): {ball} culled"
                );
                missed_at_rest +=
                    usize::from(pixels_hit(ball, 0.05, &at_rest, &observer, size) == 0);
            }
        }
        assert!(
            missed_at_rest > 0,
            "every ball is over a centre at rest too: aberration not exercised"
        );
    }

    #[test]
    fn a_ball_behind_the_camera_is_culled_unless_aberration_brings_it_into_view() {
        // At 120° from the viewing direction, 10 units away.
        let centre = 10.0 * DVec3::new(120f64.to_radians().sin(), 0.0, 120f64.to_radians().cos());
        let observer = looking_along_z(0.0);
        let at_rest = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
        assert!(!some_ray_hits(centre, 1.0, &at_rest, &observer, 1.5, 64));
        assert!(ball_out_of_view(centre, 1.0, &at_rest, &observer, 1.5));
        // Moving away along −z at 0.99c, the whole scene crowds towards +z: seen at about 14°.
        let receding = Frame::new(DVec3::new(0.0, 0.0, -0.99), DVec3::ZERO).unwrap();
        assert!(some_ray_hits(centre, 1.0, &receding, &observer, 1.5, 64));
        assert!(!ball_out_of_view(centre, 1.0, &receding, &observer, 1.5));
    }

    #[test]
    fn a_ball_in_view_or_around_the_observer_is_kept() {
        let observer = looking_along_z(0.0);
        let at_rest = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
        assert!(!ball_out_of_view(
            5.0 * DVec3::Z,
            1.0,
            &at_rest,
            &observer,
            1.0
        ));
        assert!(!ball_out_of_view(DVec3::X, 2.0, &at_rest, &observer, 1.0));
        assert!(!ball_out_of_view(DVec3::NAN, 1.0, &at_rest, &observer, 1.0));
        assert!(!ball_out_of_view(
            -5.0 * DVec3::Z,
            f64::NAN,
            &at_rest,
            &observer,
            1.0
        ));
        // Just beside the right edge of a square image, but overlapping it.
        let edge = DVec3::new(30f64.to_radians().tan() * 10.0 + 0.9, 0.0, 10.0);
        assert!(!ball_out_of_view(edge, 1.0, &at_rest, &observer, 1.0));
    }

    /// Culling does its job: of random balls that no viewing ray reaches, at speeds up to
    /// 0.87c, it culls at least 95 % (342 of 345 when written). The cap test is exact but at
    /// the pyramid's corners, where a cap outside two side planes together, but not outside
    /// either alone, is kept.
    #[test]
    fn most_balls_out_of_view_are_culled() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = |lo: f64, hi: f64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut unseen, mut culled) = (0, 0);
        for _ in 0..400 {
            let centre = DVec3::new(
                uniform(-20.0, 20.0),
                uniform(-20.0, 20.0),
                uniform(-20.0, 20.0),
            );
            let beta = DVec3::new(uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5));
            let frame = Frame::new(beta, DVec3::ZERO).unwrap();
            let observer = looking_along_z(uniform(-10.0, 10.0));
            let radius = uniform(0.1, 3.0);
            if !some_ray_hits(centre, radius, &frame, &observer, 1.5, 32) {
                unseen += 1;
                culled += usize::from(ball_out_of_view(centre, radius, &frame, &observer, 1.5));
            }
        }
        assert!(unseen > 200, "{unseen}");
        assert!(
            culled * 100 >= unseen * 95,
            "culled {culled} of {unseen} unseen balls"
        );
    }

    proptest! {
        /// No point of a ball is seen nearer than its bound, and a small far ball's bound is
        /// within its diameter (times γ(1 + |β|)) of its centre's apparent distance.
        #[test]
        fn no_point_of_a_ball_is_nearer_than_its_bound(
            centre in prop::array::uniform3(-20.0f64..20.0),
            radius in 0.0f64..5.0,
            beta in prop::array::uniform3(-0.57f64..0.57),
            offset in prop::array::uniform3(-10.0f64..10.0),
            ct in -20.0f64..20.0,
            points in prop::collection::vec(prop::array::uniform3(-1.0f64..1.0), 16),
        ) {
            let frame = Frame::new(DVec3::from_array(beta), DVec3::from_array(offset)).unwrap();
            let observer = Event::new(ct, DVec3::ZERO);
            let centre = DVec3::from_array(centre);
            let bound = ball_nearest_apparent_distance(centre, radius, &frame, observer);
            let rest = frame.to_rest(observer);
            let apparent = |p: DVec3| {
                let w = p - rest.position;
                frame.gamma() * (w.length() - frame.beta().dot(w))
            };
            prop_assert!(bound >= 0.0);
            for p in points {
                let p = centre + DVec3::from_array(p).clamp_length_max(1.0) * radius;
                prop_assert!(bound <= apparent(p) * (1.0 + 1e-12) + 1e-12);
            }
            let gap = frame.gamma() * (1.0 + frame.beta().length()) * 2.0 * radius;
            prop_assert!(apparent(centre) - bound <= gap * (1.0 + 1e-9) + 1e-12);
        }

        /// Culling is conservative: when a ball is culled out of view, no viewing ray of the
        /// image (traced exactly in S′, over a grid that includes its edges) reaches it; when
        /// it is culled between pixel centres, the ray through every pixel's centre misses it.
        /// The images are small, so that every centre is traced and the balls often fall
        /// between them.
        #[test]
        fn a_culled_ball_is_missed_by_every_viewing_ray(
            centre in prop::array::uniform3(-20.0f64..20.0),
            radius in 0.001f64..5.0,
            beta in prop::array::uniform3(-0.57f64..0.57),
            offset in prop::array::uniform3(-10.0f64..10.0),
            direction in prop::array::uniform3(-1.0f64..1.0),
            fov_y_deg in 20.0f64..120.0,
            width in 1u32..24,
            height in 1u32..24,
            ct in -20.0f64..20.0,
        ) {
            let direction = DVec3::from_array(direction);
            prop_assume!(direction.length() > 0.1 && direction.cross(DVec3::Y).length() > 0.1);
            let frame = Frame::new(DVec3::from_array(beta), DVec3::from_array(offset)).unwrap();
            let observer = Observer { direction, fov_y_deg, ..looking_along_z(ct) };
            let centre = DVec3::from_array(centre);
            let aspect = f64::from(width) / f64::from(height);
            if ball_out_of_view(centre, radius, &frame, &observer, aspect) {
                prop_assert!(!some_ray_hits(centre, radius, &frame, &observer, aspect, 48));
            }
            if ball_between_pixel_centres(centre, radius, &frame, &observer, width, height) {
                prop_assert_eq!(pixels_hit(centre, radius, &frame, &observer, (width, height)), 0);
            }
        }
    }

    proptest! {
        /// A wide projection's bound holds every pixel whose viewing ray (traced exactly in
        /// S′, through the pixel's centre on a 96 × 48 grid) hits the ball, for the full sphere
        /// and fisheyes of any field, at any velocity, for balls beside, behind and around the
        /// observer's poles; and it is tight: at most twice as wide and as high as the ball's
        /// exact image ([`wide_image_extent`]) plus its margins (4 pixels), for the full sphere
        /// (the whole width for an image within those 4 pixels of the seam behind or of a pole
        /// row) and for a fisheye whose field holds the whole image (one cut by the field's edge
        /// is bounded by a box of an annular sector, not checked here). Twice: the fisheye's
        /// sector box is up to twice the image's where the image is near the picture's centre.
        #[test]
        fn a_wide_bound_holds_every_pixel_that_sees_the_ball(
            centre in prop::array::uniform3(-20.0f64..20.0),
            radius in 0.001f64..5.0,
            beta in prop::array::uniform3(-0.57f64..0.57),
            offset in prop::array::uniform3(-10.0f64..10.0),
            direction in prop::array::uniform3(-1.0f64..1.0),
            fisheye_fov in prop::option::of(10.0f64..360.0),
            ct in -20.0f64..20.0,
        ) {
            let direction = DVec3::from_array(direction);
            prop_assume!(direction.length() > 0.1 && direction.cross(DVec3::Y).length() > 0.1);
            let frame = Frame::new(DVec3::from_array(beta), DVec3::from_array(offset)).unwrap();
            let projection = fisheye_fov.map_or(srt_scene::Projection::Equirectangular, |fov_deg| {
                srt_scene::Projection::Fisheye { fov_deg }
            });
            let observer = Observer { direction, projection, ..looking_along_z(ct) };
            let centre = DVec3::from_array(centre);
            let (width, height) = (96u32, 48u32);
            let [x0, y0, x1, y1] =
                ball_wide_bound(centre, radius, &frame, &observer, width, height);
            let rays = observer.view_rays(f64::from(width) / f64::from(height));
            for k in 0..width * height {
                let (x, y) = (f64::from(k % width) + 0.5, f64::from(k / width) + 0.5);
                let ndc = DVec2::new(
                    2.0 * x / f64::from(width) - 1.0,
                    1.0 - 2.0 * y / f64::from(height),
                );
                let Some(view) = rays.direction(ndc) else { continue };
                let ray = frame.backward_ray(observer.event(), view);
                let along = (centre - ray.origin).dot(ray.direction).max(0.0);
                if (ray.origin + along * ray.direction - centre).length() <= radius {
                    prop_assert!(
                        (x0..=x1).contains(&x) && (y0..=y1).contains(&y),
                        "pixel ({x}, {y}) sees the ball outside {:?}", [x0, y0, x1, y1]
                    );
                }
            }
            if let Some([ex0, ey0, ex1, ey1]) =
                wide_image_extent(centre, radius, &frame, &observer, (width, height))
            {
                let (wide, high) = ((x1 - x0).max(0.0), (y1 - y0).max(0.0));
                let (exact_wide, exact_high) = ((ex1 - ex0).max(0.0), (ey1 - ey0).max(0.0));
                // The full sphere's bound takes the whole width for an image at the seam behind
                // or near a pole, where its angular margin spans many longitudes
                // (`Projection::cap_bound`): within the margins' 4 pixels of either, the whole
                // width is as tight as a single box can be.
                let (w, h) = (f64::from(width), f64::from(height));
                let at_seam_or_pole = fisheye_fov.is_none()
                    && (ex0 <= 4.0 || ex1 >= w - 4.0 || ey0 <= 4.0 || ey1 >= h - 4.0);
                let exact_wide = if at_seam_or_pole { w } else { exact_wide };
                prop_assert!(
                    wide <= 2.0 * exact_wide + 4.0 && high <= 2.0 * exact_high + 4.0,
                    "bound {:?} around the image {:?}", [x0, y0, x1, y1], [ex0, ey0, ex1, ey1]
                );
            }
        }
    }

    /// Whether the viewing ray `view` (in S) of `observer` hits the ball, traced exactly in S′.
    fn sees_ball(
        centre: DVec3,
        radius: f64,
        frame: &Frame,
        observer: &Observer,
        view: DVec3,
    ) -> bool {
        let ray = frame.backward_ray(observer.event(), view);
        let along = (centre - ray.origin).dot(ray.direction).max(0.0);
        (ray.origin + along * ray.direction - centre).length() <= radius
    }

    /// The exact extent (pixels: min x, min y, max x, max y) of the ball's image in a
    /// `width` × `height` picture of `observer`'s wide projection, from 4096 points of its rim:
    /// the viewing directions in S of the rays from the observer's rest-frame position that
    /// graze the ball (the inverse of Eq. 3 through `aberrate`, checked against
    /// `Frame::rest_direction`), reaching the picture's top or bottom row where the image holds
    /// a pole. `None` where that is not the image's extent: the observer inside the ball, a
    /// fisheye whose field does not hold the whole image.
    fn wide_image_extent(
        centre: DVec3,
        radius: f64,
        frame: &Frame,
        observer: &Observer,
        (width, height): (u32, u32),
    ) -> Option<[f64; 4]> {
        let origin = frame.to_rest(observer.event()).position;
        let distance = (centre - origin).length();
        if distance <= radius {
            return None;
        }
        let axis = (centre - origin) / distance;
        let (e1, e2) = axis.any_orthonormal_pair();
        let sine = radius / distance;
        let cosine = (1.0 - sine * sine).sqrt();
        let rays = observer.view_rays(f64::from(width) / f64::from(height));
        let (forward, _, up) = observer.basis();
        let mut points = Vec::new();
        for k in 0..4096 {
            let phi = TAU * f64::from(k) / 4096.0;
            let rest = cosine * axis + sine * (phi.cos() * e1 + phi.sin() * e2);
            // The light runs along −rest in S′, along aberrate(β, −rest) in S.
            let view = -aberrate(frame.beta(), -rest).normalize();
            assert!((frame.rest_direction(view) - rest).length() < 1e-9);
            points.push(rays.image_point(view)?);
        }
        match observer.projection {
            Projection::Equirectangular => {
                // A pole the ball holds is the picture's whole top or bottom row: every
                // longitude meets there.
                for pole in [up, -up] {
                    if sees_ball(centre, radius, frame, observer, pole) {
                        let row = pole.dot(up);
                        points.extend([DVec2::new(-1.0, row), DVec2::new(1.0, row)]);
                    }
                }
            }
            // Not the whole image in the field where the image holds the direction behind.
            _ if sees_ball(centre, radius, frame, observer, -forward) => return None,
            _ => {}
        }
        let (lo, hi) = points.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let (width, height) = (f64::from(width), f64::from(height));
        Some([
            (lo.x + 1.0) * 0.5 * width,
            (1.0 - hi.y) * 0.5 * height,
            (hi.x + 1.0) * 0.5 * width,
            (1.0 - lo.y) * 0.5 * height,
        ])
    }

    /// A small ball ahead in the full sphere and in a fisheye is bounded by a small rectangle
    /// around its image; one behind a 180° fisheye has an empty bound.
    #[test]
    fn a_wide_bound_is_tight_around_a_small_ball() {
        let frame = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
        let ahead = DVec3::new(0.0, 0.0, 10.0);
        for projection in [
            srt_scene::Projection::Equirectangular,
            srt_scene::Projection::Fisheye { fov_deg: 180.0 },
        ] {
            let observer = Observer {
                projection,
                ..looking_along_z(0.0)
            };
            let [x0, y0, x1, y1] = ball_wide_bound(ahead, 0.1, &frame, &observer, 200, 200);
            // The ball subtends 0.01 rad: about 0.6 pixels of the equirectangular picture
            // (200 px / 2π rad across), 1.3 of the fisheye's (200 px / π rad), plus margins.
            assert!(
                x1 - x0 < 6.0 && y1 - y0 < 6.0,
                "{projection}: {x0} {y0} {x1} {y1}"
            );
            assert!((x0..=x1).contains(&100.0) && (y0..=y1).contains(&100.0));
            let behind = ball_wide_bound(-ahead, 0.1, &frame, &observer, 200, 200);
            if projection != srt_scene::Projection::Equirectangular {
                assert!(
                    behind[0] >= behind[2] || behind[1] >= behind[3],
                    "{behind:?}"
                );
            }
        }
    }

    #[test]
    fn box_faces_are_culled_only_from_clearly_outside() {
        let (min, max) = ([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]);
        assert!(box_near_faces_cullable(min, max, DVec3::new(5.0, 0.0, 0.0)));
        assert!(box_near_faces_cullable(
            min,
            max,
            DVec3::new(-3.0, 4.0, 2.0)
        ));
        assert!(!box_near_faces_cullable(min, max, DVec3::ZERO), "inside");
        assert!(
            !box_near_faces_cullable(min, max, DVec3::new(1.0 + 1e-7, 0.0, 0.0)),
            "on a face"
        );
        assert!(
            !box_near_faces_cullable(min, max, DVec3::new(5.0, 1.0, 0.0)),
            "in the plane of a face seen edge-on"
        );
    }

    /// A ball at rest straight ahead is seen as a disc of radius f·tan θ (f the focal length in
    /// pixels, sin θ = radius / distance): counted on the grid when large, from its solid
    /// angle when small; nothing behind the observer, everything from inside; a ball the
    /// observer approaches at 0.9c is seen smaller (aberration gathers its rays forward).
    #[test]
    fn a_balls_seen_pixels_are_its_discs_area() {
        let observer = looking_along_z(0.0);
        let (width, height) = (400, 300);
        let focal = 150.0 / 30f64.to_radians().tan();
        let at_rest = Frame::new(DVec3::ZERO, DVec3::ZERO).unwrap();
        let disc = |radius: f64, distance: f64| {
            let image = focal * (radius / distance).asin().tan();
            std::f64::consts::PI * image * image
        };
        let centre = DVec3::new(0.0, 0.0, 10.0);
        for radius in [3.0, 0.3] {
            let seen = ball_seen_pixels(centre, radius, &at_rest, &observer, width, height);
            let expected = disc(radius, 10.0);
            assert!(
                (seen / expected - 1.0).abs() < 0.06,
                "radius {radius}: {seen} pixels, the disc has {expected}"
            );
        }
        let behind = -centre;
        assert_eq!(
            ball_seen_pixels(behind, 3.0, &at_rest, &observer, width, height),
            0.0
        );
        let around = ball_seen_pixels(DVec3::ZERO, 3.0, &at_rest, &observer, width, height);
        assert_eq!(around, f64::from(width * height));
        // Approached at 0.9c: the ball's frame moves towards the observer (−z).
        let approaching = Frame::new(DVec3::new(0.0, 0.0, -0.9), DVec3::ZERO).unwrap();
        let fast = ball_seen_pixels(centre, 3.0, &approaching, &observer, width, height);
        let slow = ball_seen_pixels(centre, 3.0, &at_rest, &observer, width, height);
        assert!(
            0.0 < fast && fast < 0.5 * slow,
            "{fast} against {slow} at rest"
        );
    }
}
