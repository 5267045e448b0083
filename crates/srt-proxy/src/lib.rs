//! Conservative image-space footprints of relativistically moving triangles (§4.1, Fig. 8 of
//! Müller, Grottel and Weiskopf 2010).
//!
//! A triangle at rest in a frame S′ appears to the observer as a *curved* triangle: each straight
//! edge becomes a hyperbola arc (the photo-object, Eq. 8). Local ray tracing needs a polygon that
//! is guaranteed to contain the curved triangle's image; the fragment stage then finds the exact
//! surface per pixel. This crate computes that polygon for one triangle:
//!
//! 1. the apparent corners P_i = R(P′_i) (Eq. 5–8) and, per edge end, the apparent *tangent*
//!    of the edge arc;
//! 2. the tangent intersection G_ij of each edge (the corner of the triangle P_i G_ij P_j that
//!    encloses the arc);
//! 3. projection with the view-projection matrix and viewport;
//! 4. the window-aligned rectangle (min–max of P̄_i, Ḡ_ij) and the tighter convex hull (3–6
//!    points) of the same six points;
//! 5. if any of the six points is at or behind the camera, the whole screen.
//!
//! **Where this differs from the paper.** The paper approximates the tangent at P_i by the chord
//! to Q_ij = R(P′_i + ε(P′_j − P′_i)) with ε = 0.01 (Eq. 14). A chord lies *inside* a convex arc,
//! so the enclosing triangle built from chords misses a sliver of the arc near each corner (of
//! order ε² times the edge's curvature). We use the exact tangent, the derivative of R along the
//! edge ([`srt_physics::Frame::apparent_tangent`]), which is the ε → 0 limit, costs the same
//! and makes the footprint provably conservative. [`chord_point`] still gives the paper's Q_ij
//! for illustration (Fig. 8).
//!
//! Everything is plain data in, plain data out; `shaders/proxy.wgsl` mirrors it in f32.
//!
//! Pixel coordinates: x to the right in [0, width], y *down* in [0, height] (the framebuffer
//! convention of wgpu), pixel centres at half-integers. NDC → pixel: x = (x_ndc + 1)/2 · width,
//! y = (1 − y_ndc)/2 · height.

mod hull;

use glam::{DMat4, DVec2, DVec3, DVec4};
use srt_physics::{Event, Frame};

pub use hull::{contains as hull_contains, convex_hull};

/// The paper's ε for the chord points Q_ij of Eq. 14.
pub const PAPER_EPSILON: f64 = 0.01;

/// How many chord lengths a tangent intersection may lie from its chord's midpoint before the
/// footprint is taken to be the whole screen. Such edges turn by almost 180°; their tangent
/// intersection is ill-conditioned (in f32 on the GPU especially), and their footprint is huge
/// anyway.
pub const MAX_TANGENT_REACH: f64 = 1000.0;

/// Clip-space w at or below which a point counts as at or behind the camera.
pub const MIN_CLIP_W: f64 = 1e-9;

/// Size of the render target in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewport {
    /// Width in pixels.
    pub width: f64,
    /// Height in pixels.
    pub height: f64,
}

/// A window-aligned rectangle in pixel coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Smallest x and y.
    pub min: DVec2,
    /// Largest x and y.
    pub max: DVec2,
}

impl Rect {
    /// The whole viewport.
    #[must_use]
    pub fn screen(viewport: Viewport) -> Self {
        Self {
            min: DVec2::ZERO,
            max: DVec2::new(viewport.width, viewport.height),
        }
    }

    /// The smallest rectangle containing `points`.
    #[must_use]
    pub fn bounding(points: &[DVec2]) -> Self {
        let init = Self {
            min: DVec2::splat(f64::INFINITY),
            max: DVec2::splat(f64::NEG_INFINITY),
        };
        points.iter().fold(init, |r, &p| Self {
            min: r.min.min(p),
            max: r.max.max(p),
        })
    }

    /// The part of the rectangle inside the viewport (may be empty: `min` > `max`).
    #[must_use]
    pub fn clamped(self, viewport: Viewport) -> Self {
        let screen = Self::screen(viewport);
        Self {
            min: self.min.max(screen.min),
            max: self.max.min(screen.max),
        }
    }

    /// Area in square pixels (0 when empty).
    #[must_use]
    pub fn area(self) -> f64 {
        let size = (self.max - self.min).max(DVec2::ZERO);
        size.x * size.y
    }

    /// Whether `p` lies inside or on the border, with tolerance `tolerance` pixels.
    #[must_use]
    pub fn contains(self, p: DVec2, tolerance: f64) -> bool {
        p.cmpge(self.min - tolerance).all() && p.cmple(self.max + tolerance).all()
    }
}

/// The image-space footprint of one apparent triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// Projected apparent corners P̄_1, P̄_2, P̄_3 (pixels).
    pub corners: [DVec2; 3],
    /// Projected tangent intersections Ḡ_12, Ḡ_23, Ḡ_31 (pixels).
    pub tangent_points: [DVec2; 3],
    /// Window-aligned rectangle: min–max of the six points, or the whole screen.
    pub rect: Rect,
    /// Convex hull of the six points, counter-clockwise in pixel coordinates; the first
    /// `hull_len` entries are valid (3–6; fewer only for degenerate, zero-area footprints).
    pub hull: [DVec2; 6],
    /// Number of valid points in `hull`.
    pub hull_len: usize,
    /// True when a point lies at or behind the camera: the footprint is then the whole screen.
    pub whole_screen: bool,
}

impl Footprint {
    /// The valid hull points.
    #[must_use]
    pub fn hull_points(&self) -> &[DVec2] {
        &self.hull[..self.hull_len]
    }

    /// Whether pixel position `p` is inside the convex hull (or anywhere, for a whole-screen
    /// footprint), allowing `tolerance` pixels outside.
    #[must_use]
    pub fn hull_contains(&self, p: DVec2, tolerance: f64) -> bool {
        self.whole_screen || hull::contains(self.hull_points(), p, tolerance)
    }

    fn whole(viewport: Viewport, corners: [DVec2; 3], tangent_points: [DVec2; 3]) -> Self {
        let rect = Rect::screen(viewport);
        let mut hull = [DVec2::ZERO; 6];
        hull[..4].copy_from_slice(&[
            rect.min,
            DVec2::new(rect.max.x, rect.min.y),
            rect.max,
            DVec2::new(rect.min.x, rect.max.y),
        ]);
        Self {
            corners,
            tangent_points,
            rect,
            hull,
            hull_len: 4,
            whole_screen: true,
        }
    }
}

/// Projects a point to pixel coordinates; `None` when it is at or behind the camera
/// (clip w ≤ [`MIN_CLIP_W`]) or the result is not finite.
#[must_use]
pub fn project(view_projection: DMat4, viewport: Viewport, point: DVec3) -> Option<DVec2> {
    let clip = view_projection * DVec4::new(point.x, point.y, point.z, 1.0);
    if clip.w.is_nan() || clip.w <= MIN_CLIP_W {
        return None;
    }
    let ndc = DVec2::new(clip.x, clip.y) / clip.w;
    let pixel = DVec2::new(
        (ndc.x + 1.0) * 0.5 * viewport.width,
        (1.0 - ndc.y) * 0.5 * viewport.height,
    );
    pixel.is_finite().then_some(pixel)
}

/// The paper's chord point Q_ij = R(P′_i + ε(P′_j − P′_i)) of Eq. 14, in S.
#[must_use]
pub fn chord_point(frame: &Frame, from: DVec3, to: DVec3, epsilon: f64, observer: Event) -> DVec3 {
    frame.apparent_position(from + epsilon * (to - from), observer)
}

/// Intersection of the lines `a + s·ta` and `b + t·tb` (coplanar), or the midpoint of `a` and
/// `b` when the lines are parallel (then the arc between them is a straight segment).
fn tangent_intersection(a: DVec3, ta: DVec3, b: DVec3, tb: DVec3) -> DVec3 {
    let normal = ta.cross(tb);
    let n2 = normal.length_squared();
    if n2 <= 1e-24 * ta.length_squared() * tb.length_squared() {
        return 0.5 * (a + b);
    }
    let s = (b - a).cross(tb).dot(normal) / n2;
    a + s * ta
}

/// The apparent corners P_i and tangent intersections G_ij in S (not yet projected), for the
/// rest-frame triangle `triangle` of an object in `frame`, seen at the observation event
/// `observer`.
#[must_use]
pub fn apparent_outline(
    frame: &Frame,
    triangle: [DVec3; 3],
    observer: Event,
) -> ([DVec3; 3], [DVec3; 3]) {
    let corners = triangle.map(|p| frame.apparent_position(p, observer));
    let mut tangent_points = [DVec3::ZERO; 3];
    for (i, g) in tangent_points.iter_mut().enumerate() {
        let j = (i + 1) % 3;
        let edge = triangle[j] - triangle[i];
        let ti = frame.apparent_tangent(triangle[i], edge, observer);
        let tj = frame.apparent_tangent(triangle[j], -edge, observer);
        *g = tangent_intersection(corners[i], ti, corners[j], tj);
    }
    (corners, tangent_points)
}

/// The conservative footprint of the apparent image of `triangle` (corners in S′) of an object in
/// `frame`, seen at the observation event `observer` through `view_projection` (world = S
/// coordinates → clip space) onto `viewport` (§4.1, Fig. 8).
///
/// Degenerate input has a documented result rather than an error: a zero-area triangle yields a
/// zero-area footprint (nothing is drawn, and the exact tracer finds no hit either); a triangle
/// touching the observer's own position, any corner or tangent intersection at or behind the
/// camera, or a tangent intersection more than [`MAX_TANGENT_REACH`] chord lengths away, yields
/// the whole screen.
#[must_use]
pub fn footprint(
    frame: &Frame,
    triangle: [DVec3; 3],
    observer: Event,
    view_projection: DMat4,
    viewport: Viewport,
) -> Footprint {
    let (corners, tangent_points) = apparent_outline(frame, triangle, observer);
    let far = (0..3).any(|i| {
        let (a, b) = (corners[i], corners[(i + 1) % 3]);
        (tangent_points[i] - 0.5 * (a + b)).length() > MAX_TANGENT_REACH * (b - a).length()
    });
    let project = |p: DVec3| {
        if far {
            None
        } else {
            project(view_projection, viewport, p)
        }
    };
    match (corners.map(project), tangent_points.map(project)) {
        ([Some(p1), Some(p2), Some(p3)], [Some(g1), Some(g2), Some(g3)]) => {
            let corners = [p1, p2, p3];
            let tangent_points = [g1, g2, g3];
            let six = [p1, g1, p2, g2, p3, g3];
            let mut hull = [DVec2::ZERO; 6];
            let hull_len = convex_hull(&six, &mut hull);
            Footprint {
                corners,
                tangent_points,
                rect: Rect::bounding(&six),
                hull,
                hull_len,
                whole_screen: false,
            }
        }
        (c, g) => {
            let or_zero = |p: Option<DVec2>| p.unwrap_or(DVec2::ZERO);
            Footprint::whole(viewport, c.map(or_zero), g.map(or_zero))
        }
    }
}
