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
//! 5. if any of the six points is at or behind the camera, or a tangent intersection is
//!    ill-conditioned, the paper takes the whole screen. We bound such a triangle instead by a
//!    *swept prism* (below), clip it at the camera and take the rectangle of what is left on the
//!    screen: a triangle beside or behind the camera draws only where it can be seen, and one
//!    wholly behind draws nothing. The whole screen remains only for a triangle whose prism
//!    reaches the camera itself.
//!
//! **The swept prism.** A point of the object that is at x₀ in S at ct = 0 moves along
//! x₀ + β·ct; it is seen where that worldline meets the observer's backward light cone, at the
//! emission time u(x₀), solving ct_obs − u = ‖x₀ + βu − o‖. Solved for u, this is a linear
//! function minus a norm of x₀, so u is *concave* over the (flat) triangle of x₀ points, with
//! gradient ∇u = −n/(1 + n·β), n the unit direction from the observer to the apparent point
//! (differentiate the light-cone condition). Hence over the triangle u lies above the plane
//! through its corner values and below each corner's tangent plane; the apparent triangle
//! {x₀ + β u(x₀)} lies in the convex hull of the three apparent corners P_i = x₀ᵢ + β uᵢ and
//! the three points x₀ᵢ + β u_max, where u_max = min over corners i of the largest value of
//! corner i's tangent plane over the triangle (at one of its corners). Clipping this convex
//! set at a plane w = ε in front of the camera, chosen from the six points' clip-space bounds
//! so that no part of the set between the camera and that plane is on screen, keeps every point
//! that can be seen; its projection is bounded.
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

    /// The four corners, counter-clockwise in pixel coordinates from `min`.
    #[must_use]
    pub fn corners(self) -> [DVec2; 4] {
        [
            self.min,
            DVec2::new(self.max.x, self.min.y),
            self.max,
            DVec2::new(self.min.x, self.max.y),
        ]
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
    /// True when the triangle's swept prism reaches the camera itself: the footprint is then
    /// the whole screen.
    pub whole_screen: bool,
    /// True when the footprint bounds the clipped swept prism (a triangle reaching beside or
    /// behind the camera, or with an ill-conditioned tangent intersection) rather than the
    /// tangent construction: its hull is then its rectangle, clamped to the screen (or empty when
    /// nothing of it can be seen).
    pub swept: bool,
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
        hull[..4].copy_from_slice(&rect.corners());
        Self {
            corners,
            tangent_points,
            rect,
            hull,
            hull_len: 4,
            whole_screen: true,
            swept: false,
        }
    }

    /// The footprint of a swept prism whose visible part projects into `rect` (clamped to the
    /// screen here); empty (zero rectangle, no hull) when `rect` misses the screen.
    fn swept(
        viewport: Viewport,
        corners: [DVec2; 3],
        tangent_points: [DVec2; 3],
        rect: Rect,
    ) -> Self {
        let rect = rect.clamped(viewport);
        let visible = rect.min.cmplt(rect.max).all();
        let mut hull = [DVec2::ZERO; 6];
        if visible {
            hull[..4].copy_from_slice(&rect.corners());
        }
        Self {
            corners,
            tangent_points,
            rect: if visible {
                rect
            } else {
                Rect {
                    min: DVec2::ZERO,
                    max: DVec2::ZERO,
                }
            },
            hull,
            hull_len: if visible { 4 } else { 0 },
            whole_screen: false,
            swept: true,
        }
    }

    /// Whether nothing is drawn for it (an empty rectangle).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !self.whole_screen && self.rect.area() <= 0.0 && self.hull_len == 0
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
                swept: false,
            }
        }
        (c, g) => {
            let or_zero = |p: Option<DVec2>| p.unwrap_or(DVec2::ZERO);
            let (c, g) = (c.map(or_zero), g.map(or_zero));
            match swept_prism(frame, triangle, observer)
                .and_then(|prism| visible_rect(&prism, view_projection, viewport))
            {
                Some(rect) => Footprint::swept(viewport, c, g, rect),
                None => Footprint::whole(viewport, c, g),
            }
        }
    }
}

/// The six points whose convex hull holds the apparent image of `triangle` (see the crate
/// documentation): the apparent corners P_i, then x₀ᵢ + β u_max. `None` when the observer's
/// own position is a corner's apparent position (no direction to it).
#[must_use]
pub fn swept_prism(frame: &Frame, triangle: [DVec3; 3], observer: Event) -> Option<[DVec3; 6]> {
    let beta = frame.beta();
    let emissions = triangle.map(|p| frame.to_observer(frame.emission_event(p, observer)));
    let mut start = [DVec3::ZERO; 3];
    let mut slope = [DVec3::ZERO; 3];
    for (i, emission) in emissions.iter().enumerate() {
        // Where the corner is at ct = 0, and the gradient −n/(1 + n·β) of u at it.
        start[i] = emission.position - beta * emission.ct;
        let n = (emission.position - observer.position).try_normalize()?;
        slope[i] = -n / (1.0 + n.dot(beta));
    }
    let latest = (0..3)
        .map(|i| {
            (0..3)
                .map(|j| emissions[i].ct + slope[i].dot(start[j] - start[i]))
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .fold(f64::INFINITY, f64::min);
    let latest = latest.max(
        emissions
            .iter()
            .map(|e| e.ct)
            .fold(f64::NEG_INFINITY, f64::max),
    );
    let points = [
        emissions[0].position,
        emissions[1].position,
        emissions[2].position,
        start[0] + beta * latest,
        start[1] + beta * latest,
        start[2] + beta * latest,
    ];
    points.iter().all(|p| p.is_finite()).then_some(points)
}

/// The rectangle (pixels, not yet clamped to the screen) holding every on-screen point of the
/// convex hull of `points` (in S), or `None` when that hull may reach the camera itself.
///
/// In clip space the on-screen points with 0 < w ≤ ε lie in the box |x|, |y| ≤ ε, 0 ≤ w ≤ ε.
/// With ε half the distance by which the points' bounding box misses that box at ε = its
/// largest possible value, nothing of the hull is on screen before w = ε, so the hull is
/// clipped there: the points with w ≥ ε and the crossings of w = ε by the segments between
/// points on either side (these include every vertex of the clipped hull) are projected.
#[must_use]
pub fn visible_rect(points: &[DVec3], view_projection: DMat4, viewport: Viewport) -> Option<Rect> {
    let clip: Vec<DVec4> = points
        .iter()
        .map(|p| view_projection * DVec4::new(p.x, p.y, p.z, 1.0))
        .collect();
    let lo = clip.iter().fold(DVec4::INFINITY, |a, &c| a.min(c));
    let hi = clip.iter().fold(DVec4::NEG_INFINITY, |a, &c| a.max(c));
    let nothing = Rect {
        min: DVec2::INFINITY,
        max: DVec2::NEG_INFINITY,
    };
    // Wholly behind the camera, or wholly beyond one side plane of the view pyramid.
    let beyond = |f: &dyn Fn(DVec4) -> f64| clip.iter().all(|&c| f(c) < 0.0);
    if beyond(&|c| c.w)
        || beyond(&|c| c.w - c.x)
        || beyond(&|c| c.w + c.x)
        || beyond(&|c| c.w - c.y)
        || beyond(&|c| c.w + c.y)
    {
        return Some(nothing);
    }
    let clearance = lo.x.max(-hi.x).max(lo.y).max(-hi.y).max(lo.w);
    if !(clearance > 0.0 && clearance.is_finite()) {
        return None;
    }
    let near = 0.5 * clearance;
    let mut kept: Vec<DVec4> = clip.iter().copied().filter(|c| c.w >= near).collect();
    for a in &clip {
        for b in &clip {
            if a.w >= near && b.w < near {
                kept.push(*a + (*b - *a) * ((near - a.w) / (b.w - a.w)));
            }
        }
    }
    let pixels: Vec<DVec2> = kept
        .iter()
        .map(|c| {
            DVec2::new(
                (c.x / c.w + 1.0) * 0.5 * viewport.width,
                (1.0 - c.y / c.w) * 0.5 * viewport.height,
            )
        })
        .collect();
    Some(if pixels.is_empty() {
        nothing
    } else {
        Rect::bounding(&pixels)
    })
}
