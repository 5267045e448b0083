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
//!    ill-conditioned, the paper takes the whole screen. We split such a triangle in S′ instead
//!    ([`split_pieces`]), and bound each piece by the paper's footprint when it lies wholly in
//!    front of the camera, or else by a *swept prism* (below), clipped at the camera, taking the
//!    rectangle of what is left on the screen: a triangle beside or behind the camera draws
//!    only where it can be seen, and one wholly behind draws nothing. The whole screen remains
//!    only for a piece 8 halvings deep whose prism reaches the camera itself. A large footprint
//!    whose hull is loose (strongly curved edges: [`Footprint::worth_splitting`]) is split the
//!    same way.
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
mod nearest;

use glam::{DMat4, DVec2, DVec3, DVec4};
use srt_physics::{Event, Frame};

pub use hull::{contains as hull_contains, convex_hull};
pub use nearest::nearest_apparent_distance;

/// The paper's ε for the chord points Q_ij of Eq. 14.
pub const PAPER_EPSILON: f64 = 0.01;

/// How many chord lengths a tangent intersection may lie from its chord's midpoint before the
/// footprint is taken to be the whole screen. Such edges turn by almost 180°; their tangent
/// intersection is ill-conditioned (in f32 on the GPU especially), and their footprint is huge
/// anyway.
pub const MAX_TANGENT_REACH: f64 = 1000.0;

/// How far from the screen's centre, in screen sizes (the larger of width and height), the
/// points of the paper's footprint may lie; a triangle with one further out is split instead
/// ([`split_pieces`]). Points that far out come from corners just in front of the camera
/// plane; in f32 the hull of such points is numerically meaningless (seen in `cargo xtask
/// validate`: hull points at 2·10⁸ pixels that no longer held the triangle).
pub const MAX_SCREEN_REACH: f64 = 16.0;

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
    /// True when a piece of the triangle, split as deep as allowed, may reach the camera
    /// itself: the footprint is then the whole screen.
    pub whole_screen: bool,
    /// True when the footprint is the rectangle holding the pieces of a split triangle
    /// ([`split_pieces`]: one reaching beside or behind the camera, with an ill-conditioned
    /// tangent intersection, or loose and large) rather than the tangent construction: its hull
    /// is then its rectangle, clamped to the screen (or empty when nothing of it can be seen).
    pub split: bool,
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
            split: false,
        }
    }

    /// The footprint of a split triangle whose pieces lie in `rect` (clamped to the screen
    /// here); empty (zero rectangle, no hull) when `rect` misses the screen.
    fn split(
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
            split: true,
        }
    }

    /// Whether this footprint of the tangent construction is better split ([`split_pieces`]):
    /// it covers more than [`SPLIT_AREA_FRACTION`] of the screen and its hull is loose
    /// ([`LOOSE_HULL_FACTOR`]).
    #[must_use]
    pub fn worth_splitting(&self, viewport: Viewport) -> bool {
        !self.split
            && !self.whole_screen
            && self.rect.clamped(viewport).area()
                > SPLIT_AREA_FRACTION * viewport.width * viewport.height
            && polygon_area(self.hull_points()) > LOOSE_HULL_FACTOR * polygon_area(&self.corners)
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
/// zero-area footprint (nothing is drawn, and the exact tracer finds no hit either). A triangle
/// with any corner or tangent intersection at or behind the camera or more than
/// [`MAX_SCREEN_REACH`] screens away, or a tangent intersection more than
/// [`MAX_TANGENT_REACH`] chord lengths away, or whose footprint is
/// [worth splitting](Footprint::worth_splitting), is split ([`split_pieces`]); the footprint
/// returned is then the rectangle holding its pieces ([`split_footprint`]).
#[must_use]
pub fn footprint(
    frame: &Frame,
    triangle: [DVec3; 3],
    observer: Event,
    view_projection: DMat4,
    viewport: Viewport,
) -> Footprint {
    match tangent_footprint(frame, triangle, observer, view_projection, viewport) {
        Some(f) if !f.worth_splitting(viewport) => f,
        _ => split_footprint(frame, triangle, observer, view_projection, viewport),
    }
}

/// The paper's footprint (the six points P_i, G_ij, their rectangle and convex hull), or
/// `None` when one of the six points is at or behind the camera or more than
/// [`MAX_SCREEN_REACH`] screens away, or a tangent intersection is more than
/// [`MAX_TANGENT_REACH`] chord lengths away.
#[must_use]
pub fn tangent_footprint(
    frame: &Frame,
    triangle: [DVec3; 3],
    observer: Event,
    view_projection: DMat4,
    viewport: Viewport,
) -> Option<Footprint> {
    let (corners, tangent_points) = apparent_outline(frame, triangle, observer);
    let far = (0..3).any(|i| {
        let (a, b) = (corners[i], corners[(i + 1) % 3]);
        (tangent_points[i] - 0.5 * (a + b)).length() > MAX_TANGENT_REACH * (b - a).length()
    });
    if far {
        return None;
    }
    let centre = 0.5 * DVec2::new(viewport.width, viewport.height);
    let reach = MAX_SCREEN_REACH * viewport.width.max(viewport.height);
    let project = |p: DVec3| {
        project(view_projection, viewport, p)
            .filter(|pixel| (*pixel - centre).abs().max_element() <= reach)
    };
    let [p1, p2, p3] = corners.map(project);
    let [g1, g2, g3] = tangent_points.map(project);
    let (corners, tangent_points) = ([p1?, p2?, p3?], [g1?, g2?, g3?]);
    let six = [
        corners[0],
        tangent_points[0],
        corners[1],
        tangent_points[1],
        corners[2],
        tangent_points[2],
    ];
    let mut hull = [DVec2::ZERO; 6];
    let hull_len = convex_hull(&six, &mut hull);
    Some(Footprint {
        corners,
        tangent_points,
        rect: Rect::bounding(&six),
        hull,
        hull_len,
        whole_screen: false,
        split: false,
    })
}

/// How many times a split triangle may be halved ([`split_pieces`]): at most 2^depth pieces
/// (WGSL `MAX_SPLIT_DEPTH` in proxy.wgsl, whose stack holds depth + 1 pieces).
pub const MAX_SPLIT_DEPTH: u32 = 8;

/// A piece whose footprint covers more than this fraction of the screen is split again (until
/// [`MAX_SPLIT_DEPTH`]) when it reaches beside or behind the camera or its hull is loose
/// ([`LOOSE_HULL_FACTOR`]).
pub const SPLIT_AREA_FRACTION: f64 = 1.0 / 64.0;

/// A footprint of the tangent construction whose hull has more than this many times the area
/// of the triangle of its projected corners is loose: its edges are seen strongly curved, and
/// the tangent triangles P_i G_ij P_j hold much more than the arcs. (For straight edges the
/// hull is that triangle.)
pub const LOOSE_HULL_FACTOR: f64 = 2.0;

/// The fraction of [`near_bound`]'s bound at which a piece's swept prism is clipped (below 1
/// so that rounding cannot clip off what can be seen; the GPU's f32 mirror uses the same).
pub const NEAR_CLIP_FRACTION: f64 = 0.9;

/// The halves of `piece` across the midpoint of its longest edge (so that pieces of a long,
/// thin triangle become well shaped instead of thinner).
fn bisect(piece: [DVec3; 3]) -> [[DVec3; 3]; 2] {
    let length = |i: usize| (piece[(i + 1) % 3] - piece[i]).length_squared();
    let i = (0..3)
        .max_by(|&a, &b| length(a).total_cmp(&length(b)))
        .unwrap_or(0);
    let (a, b, c) = (piece[i], piece[(i + 1) % 3], piece[(i + 2) % 3]);
    let middle = 0.5 * (a + b);
    [[a, middle, c], [middle, b, c]]
}

/// The pieces of a triangle that one convex footprint cannot bound tightly: footprints that
/// together hold every on-screen point of its apparent image, none of them empty; `None` when
/// the whole screen is needed.
///
/// The triangle is split in S′ (halved across its longest edge) until every piece either has
/// the paper's footprint ([`tangent_footprint`]: wholly in front of the camera) and that is
/// not both loose and large ([`Footprint::worth_splitting`]), which it then keeps; or is proved
/// hidden ([`NearBound::Hidden`]: its swept prism misses the view pyramid); or is small on the
/// screen (its visible rectangle, [`visible_rect`] of its swept prism, under
/// [`SPLIT_AREA_FRACTION`] of the screen) or [`MAX_SPLIT_DEPTH`] halvings deep, and gets that
/// rectangle. One convex bound of a whole big triangle cannot be tight: an edge passing around
/// the camera is seen as an arc from one side of the picture, behind the observer, to the
/// other, and every convex set holding both ends crosses the screen between them. The pieces
/// follow the arc.
///
/// The whole screen is left only for a piece at the deepest level whose prism reaches the
/// camera itself.
#[must_use]
pub fn split_pieces(
    frame: &Frame,
    triangle: [DVec3; 3],
    observer: Event,
    view_projection: DMat4,
    viewport: Viewport,
) -> Option<Vec<Footprint>> {
    let split_area = SPLIT_AREA_FRACTION * viewport.width * viewport.height;
    let mut kept = Vec::new();
    let mut pieces = vec![(triangle, 0)];
    while let Some((piece, depth)) = pieces.pop() {
        let (footprint, worth_splitting) =
            match tangent_footprint(frame, piece, observer, view_projection, viewport) {
                Some(f) => {
                    let worth_splitting = f.worth_splitting(viewport);
                    (Some(f), worth_splitting)
                }
                None => {
                    let rect = swept_prism(frame, piece, observer)
                        .and_then(|prism| visible_rect(&prism, view_projection, viewport));
                    let large = rect.is_none_or(|r| r.clamped(viewport).area() > split_area);
                    let footprint = rect
                        .map(|r| Footprint::split(viewport, [DVec2::ZERO; 3], [DVec2::ZERO; 3], r));
                    (footprint, large)
                }
            };
        if depth < MAX_SPLIT_DEPTH && worth_splitting {
            pieces.extend(bisect(piece).map(|half| (half, depth + 1)));
            continue;
        }
        let footprint = footprint?;
        if !footprint.is_empty() && footprint.rect.clamped(viewport).area() > 0.0 {
            kept.push(footprint);
        }
    }
    Some(kept)
}

/// The footprint of a triangle the tangent construction cannot bound tightly: the rectangle
/// holding its [`split_pieces`] on the screen (what a renderer draws when it has no room for
/// the pieces themselves), or the whole screen.
#[must_use]
pub fn split_footprint(
    frame: &Frame,
    triangle: [DVec3; 3],
    observer: Event,
    view_projection: DMat4,
    viewport: Viewport,
) -> Footprint {
    let projected = |p: DVec3| project(view_projection, viewport, p).unwrap_or(DVec2::ZERO);
    let (corners, tangent_points) = apparent_outline(frame, triangle, observer);
    let (corners, tangent_points) = (corners.map(projected), tangent_points.map(projected));
    match split_pieces(frame, triangle, observer, view_projection, viewport) {
        Some(pieces) => {
            let ends: Vec<DVec2> = pieces
                .iter()
                .map(|f| f.rect.clamped(viewport))
                .flat_map(|r| [r.min, r.max])
                .collect();
            let union = if ends.is_empty() {
                Rect {
                    min: DVec2::ZERO,
                    max: DVec2::ZERO,
                }
            } else {
                Rect::bounding(&ends)
            };
            Footprint::split(viewport, corners, tangent_points, union)
        }
        None => Footprint::whole(viewport, corners, tangent_points),
    }
}

/// Area of the polygon `points` (either orientation), e.g. of a footprint's hull in square
/// pixels.
#[must_use]
pub fn polygon_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum::<f64>()
        .abs()
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
/// Work in the clip coordinates c = (x, y, w); the on-screen points form the cone
/// |x|, |y| ≤ w. Any direction n with m = min over the points of n·c > 0 bounds the hull by the
/// half-space n·c ≥ m; over the cone n·c ≤ w (|n_x| + |n_y| + n_w). So either that factor is
/// ≤ 0 and nothing of the hull is on screen, or every on-screen point of the hull has
/// w ≥ m / (|n_x| + |n_y| + n_w). [`near_bound`] takes the best such bound over the planes
/// through any three of the points (among them the hull's faces) and the cone's own axes; the
/// hull is clipped at w = near, [`NEAR_CLIP_FRACTION`] of that bound: the points with
/// w ≥ near and the crossings of w = near by the segments between points on either side (these
/// include every vertex of the clipped hull) are projected.
#[must_use]
pub fn visible_rect(points: &[DVec3], view_projection: DMat4, viewport: Viewport) -> Option<Rect> {
    let clip: Vec<DVec4> = points
        .iter()
        .map(|p| view_projection * DVec4::new(p.x, p.y, p.z, 1.0))
        .collect();
    let nothing = Rect {
        min: DVec2::INFINITY,
        max: DVec2::NEG_INFINITY,
    };
    let near = match near_bound(&clip)? {
        NearBound::Hidden => return Some(nothing),
        NearBound::At(bound) => NEAR_CLIP_FRACTION * bound,
    };
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

/// What [`near_bound`] proves about the convex hull of some clip-space points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NearBound {
    /// No point of the hull is on screen.
    Hidden,
    /// Every on-screen point of the hull has clip w at least this (> 0).
    At(f64),
}

/// Relative size below which a plane's distance from the camera is taken for rounding.
const PLANE_TOLERANCE: f64 = 1e-9;

/// The largest lower bound on clip w of the on-screen points of the convex hull of `clip`
/// (see [`visible_rect`]), from the planes through any three points, the planes x = 0, y = 0
/// and w = 0, and the cone's four faces; `None` when no plane keeps the hull off the camera.
#[must_use]
pub fn near_bound(clip: &[DVec4]) -> Option<NearBound> {
    let xyw = |c: DVec4| DVec3::new(c.x, c.y, c.w);
    let points: Vec<DVec3> = clip.iter().map(|&c| xyw(c)).collect();
    if !points.iter().all(|p| p.is_finite()) {
        return None;
    }
    let reach = points.iter().map(|p| p.length()).fold(0.0, f64::max);
    // The cone's axes, the camera plane and the cone's four faces (hull wholly beyond one).
    let mut normals = vec![
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
        DVec3::new(1.0, 0.0, -1.0),
        DVec3::new(-1.0, 0.0, -1.0),
        DVec3::new(0.0, 1.0, -1.0),
        DVec3::new(0.0, -1.0, -1.0),
    ];
    for a in 0..points.len() {
        for b in a + 1..points.len() {
            for c in b + 1..points.len() {
                let n = (points[b] - points[a]).cross(points[c] - points[a]);
                normals.extend([n, -n]);
            }
        }
    }
    let mut best: Option<f64> = None;
    for n in normals {
        let m = points
            .iter()
            .map(|p| n.dot(*p))
            .fold(f64::INFINITY, f64::min);
        if m <= PLANE_TOLERANCE * n.length() * reach {
            continue;
        }
        // The cone's extent along n, widened by the tolerance so that rounding can only lower
        // the bound.
        let widest = n.x.abs() + n.y.abs() + n.z + PLANE_TOLERANCE * n.length();
        if widest <= 0.0 {
            return Some(NearBound::Hidden);
        }
        best = Some(best.map_or(m / widest, |b: f64| b.max(m / widest)));
    }
    best.map(NearBound::At)
}

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
