//! How an observer's image maps pixels to viewing directions (`[observer] projection`): the
//! pinhole (perspective), the full sphere (equirectangular, as 360° players show it) and the
//! azimuthal equidistant fisheye (a planetarium's dome master). Every renderer that follows a
//! pixel takes its ray from [`crate::ViewRays`], which applies the projection; the inverse
//! ([`crate::ViewRays::image_point`]) places what is seen in a direction (the stars).
//!
//! Conventions (docs/scene-format.md, "Projections"), for normalised device coordinates
//! (x, y) ∈ [−1, 1]² of a point of the image (x right, y up; a pixel's centre (i + ½, j + ½)
//! of a W × H image has x = 2(i + ½)/W − 1, y = 1 − 2(j + ½)/H), and the observer's forward f,
//! right r and up u:
//! - equirectangular: longitude φ = π x (0 at the centre column, which looks along f, growing to
//!   the right), latitude θ = π y / 2 (+90° at the top, along u); the direction is
//!   cos θ (cos φ f + sin φ r) + sin θ u;
//! - fisheye of field `fov_deg`: ρ = √(x² + y²); ρ > 1 sees nothing; otherwise the direction
//!   makes the angle ρ · fov / 2 with f, at the azimuth atan2(y, x) measured from r towards u.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;
use std::str::FromStr;

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// The fisheye's field of view when none is given: a hemisphere, as a dome master has.
pub const DEFAULT_FISHEYE_FOV_DEG: f64 = 180.0;

/// The widest fisheye: the whole sphere.
pub const MAX_FISHEYE_FOV_DEG: f64 = 360.0;

/// How the image maps its points to viewing directions.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum Projection {
    /// The pinhole camera of `fov_y_deg` (the paper's).
    #[default]
    Perspective,
    /// The full sphere: longitude across, latitude up (W = 2H is the usual shape).
    Equirectangular,
    /// Azimuthal equidistant in the circle inscribed in the image.
    Fisheye {
        /// The field of view across the circle, in degrees, in (0, 360].
        #[serde(default = "default_fisheye_fov")]
        fov_deg: f64,
    },
}

/// Two eyes in one picture (`[observer] stereo = { eye_separation = d }`): top (left eye) over
/// bottom (right eye) for the equirectangular projection — omni-directional stereo, each
/// column's rays leaving from the point ±d/2 along the horizontal direction perpendicular to
/// the column's, as 360° players expect — and side by side (left eye on the left) for the
/// pinhole, whose eyes sit ±d/2 along the observer's right axis and look parallel. Each eye's
/// half is a picture of its own in the projection ([`Stereo::eye_at`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stereo {
    /// The distance between the eyes (scene units, ≥ 0).
    pub eye_separation: f64,
}

/// Which eye sees a point of a stereo picture, and where in that eye's own picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EyePoint {
    /// −1 for the left eye, +1 for the right.
    pub eye: f64,
    /// The point in the eye's picture (normalised device coordinates).
    pub ndc: DVec2,
}

impl Stereo {
    /// Why the stereo pair is not usable with `projection`, if it is not: a separation that is
    /// negative or not finite, or a fisheye (a dome has no stereo layout).
    ///
    /// # Errors
    /// The reason, naming the value.
    pub fn check(self, projection: Projection) -> Result<Self, String> {
        if !(self.eye_separation.is_finite() && self.eye_separation >= 0.0) {
            return Err(format!(
                "eye_separation must be a finite distance ≥ 0, got {:?}",
                self.eye_separation
            ));
        }
        if matches!(projection, Projection::Fisheye { .. }) {
            return Err(
                "a fisheye has no stereo layout; use the equirectangular projection \
                 (top-bottom) or the pinhole (side by side)"
                    .to_owned(),
            );
        }
        Ok(self)
    }

    /// Why a `width` × `height` picture cannot hold the pair in `projection`, if it cannot:
    /// the side the eyes share (the height top-bottom, the width side by side) must be even,
    /// so that each eye's half is a whole number of pixels.
    ///
    /// # Errors
    /// The reason, naming the size.
    pub fn check_size(projection: Projection, width: u32, height: u32) -> Result<(), String> {
        let (side, value) = if projection == Projection::Equirectangular {
            ("height", height)
        } else {
            ("width", width)
        };
        if value % 2 == 0 {
            Ok(())
        } else {
            Err(format!(
                "a stereo picture's {side} is split between the eyes and must be even, got \
                 {width}x{height}"
            ))
        }
    }

    /// The eye seeing the point `ndc` of the whole picture in `projection`, and the point in
    /// that eye's half: the top half (y > 0) is the left eye's for the equirectangular
    /// projection, the left half (x < 0) for the pinhole; each half is stretched over [−1, 1]².
    #[must_use]
    pub fn eye_at(projection: Projection, ndc: DVec2) -> EyePoint {
        if projection == Projection::Equirectangular {
            if ndc.y > 0.0 {
                EyePoint {
                    eye: -1.0,
                    ndc: DVec2::new(ndc.x, 2.0 * ndc.y - 1.0),
                }
            } else {
                EyePoint {
                    eye: 1.0,
                    ndc: DVec2::new(ndc.x, 2.0 * ndc.y + 1.0),
                }
            }
        } else if ndc.x < 0.0 {
            EyePoint {
                eye: -1.0,
                ndc: DVec2::new(2.0 * ndc.x + 1.0, ndc.y),
            }
        } else {
            EyePoint {
                eye: 1.0,
                ndc: DVec2::new(2.0 * ndc.x - 1.0, ndc.y),
            }
        }
    }

    /// The point of the whole picture where `eye` (−1 left, +1 right) sees the point `ndc` of
    /// its own half: the inverse of [`Stereo::eye_at`].
    #[must_use]
    pub fn picture_point(projection: Projection, eye: f64, ndc: DVec2) -> DVec2 {
        if projection == Projection::Equirectangular {
            DVec2::new(ndc.x, 0.5 * (ndc.y - eye))
        } else {
            DVec2::new(0.5 * (ndc.x + eye), ndc.y)
        }
    }

    /// The offset from the observer (in S) of the eye that sees `point`, for the basis
    /// (`forward`, `right`, `up`): ±d/2 along `right` for the pinhole; for the
    /// equirectangular projection ±d/2 along the horizontal direction perpendicular to the
    /// point's column, to its right (omni-directional stereo): the column at longitude φ looks
    /// along cos φ f + sin φ r, so the offset is ±d/2 (cos φ r − sin φ f).
    #[must_use]
    pub fn eye_offset(
        self,
        projection: Projection,
        point: EyePoint,
        [forward, right, _up]: [DVec3; 3],
    ) -> DVec3 {
        let half = 0.5 * self.eye_separation * point.eye;
        if projection != Projection::Equirectangular {
            return half * right;
        }
        let longitude = PI * point.ndc.x;
        half * (longitude.cos() * right - longitude.sin() * forward)
    }
}

/// [`DEFAULT_FISHEYE_FOV_DEG`], for serde.
const fn default_fisheye_fov() -> f64 {
    DEFAULT_FISHEYE_FOV_DEG
}

/// The projections' names, as the command line, Python and the page take them.
pub const PROJECTION_NAMES: [&str; 3] = ["perspective", "equirectangular", "fisheye"];

impl Projection {
    /// Every projection, each with its default parameters, in the order a menu lists them.
    pub const ALL: [Self; 3] = [
        Self::Perspective,
        Self::Equirectangular,
        Self::Fisheye {
            fov_deg: DEFAULT_FISHEYE_FOV_DEG,
        },
    ];

    /// What a menu calls the projection with its parameters as [`Projection::ALL`] has them
    /// (the viewer's): "full sky (equirectangular)".
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::Perspective => "perspective",
            Self::Equirectangular => "full sky (equirectangular)",
            Self::Fisheye { .. } => "dome (180° fisheye)",
        }
    }

    /// Whether the projection is the pinhole: the one picture whose every pixel's ray follows
    /// from one camera over the whole image, which the footprint methods (local ray tracing,
    /// the polygon method) draw; every other is traced ([`crate::Observer::picture_decides`]).
    #[must_use]
    pub const fn is_pinhole(self) -> bool {
        matches!(self, Self::Perspective)
    }

    /// The bound, in normalised device coordinates (min x, min y, max x, max y; module doc),
    /// of the image of a cap of viewing directions around the unit `axis` of angular radius
    /// `radius` (radians), for the observer's unit `basis` (forward, right, up); `None` where
    /// the projection cannot bound it (the pinhole, whose images the footprints bound) or the
    /// image may be anywhere, and an empty bound (min > max) where no point of the image sees
    /// the cap (outside a fisheye's field).
    ///
    /// In the equirectangular picture a cap around latitude θ_c that holds no pole spans
    /// latitudes θ_c ± r and longitudes φ_c ± asin(sin r / cos θ_c) (the tangent great
    /// circles through the poles); in a fisheye, where the angle from the viewing direction
    /// plays the colatitude, it spans angles θ_c ± r and azimuths ± asin(sin r / sin θ_c)
    /// around its own, a sector of an annulus whose box is taken. A range of longitudes
    /// across ±180° takes the whole width.
    #[must_use]
    pub fn cap_bound(
        self,
        axis: DVec3,
        radius: f64,
        basis: (DVec3, DVec3, DVec3),
    ) -> Option<[f64; 4]> {
        // An empty bound.
        const NOTHING: [f64; 4] = [2.0, 2.0, -2.0, -2.0];
        let (forward, right, up) = basis;
        let (m, r) = (axis, radius);
        match self {
            Self::Perspective => None,
            Self::Equirectangular => {
                let latitude = m.dot(up).clamp(-1.0, 1.0).asin();
                let longitude = m.dot(right).atan2(m.dot(forward));
                let (low, high) = (latitude - r, latitude + r);
                let half_width = (r.sin() / latitude.cos()).min(1.0).asin();
                let (west, east) = (longitude - half_width, longitude + half_width);
                let around = high >= FRAC_PI_2 || low <= -FRAC_PI_2 || west <= -PI || east >= PI;
                let (west, east) = if around { (-PI, PI) } else { (west, east) };
                Some([
                    west / PI,
                    low.max(-FRAC_PI_2) / FRAC_PI_2,
                    east / PI,
                    high.min(FRAC_PI_2) / FRAC_PI_2,
                ])
            }
            Self::Fisheye { fov_deg } => {
                let half_fov = 0.5 * fov_deg.to_radians();
                let polar = m.dot(forward).clamp(-1.0, 1.0).acos();
                let azimuth = m.dot(up).atan2(m.dot(right));
                let (inner, outer) = ((polar - r) / half_fov, (polar + r) / half_fov);
                if polar + r >= PI {
                    // Around the direction behind: every azimuth, from the inner angle on;
                    // beyond the field, nothing.
                    return (inner <= 1.0)
                        .then_some([-1.0, -1.0, 1.0, 1.0])
                        .or(Some(NOTHING));
                }
                if polar <= r {
                    return Some([-outer, -outer, outer, outer]);
                }
                let spread = (r.sin() / polar.sin()).min(1.0).asin();
                let (from, to) = (azimuth - spread, azimuth + spread);
                let at = |rho: f64, angle: f64| [rho * angle.cos(), rho * angle.sin()];
                let mut points = vec![
                    at(inner, from),
                    at(inner, to),
                    at(outer, from),
                    at(outer, to),
                ];
                // The outer arc's extremes along the axes that fall within the sector.
                for quarter in -4..=4 {
                    let angle = f64::from(quarter) * FRAC_PI_2;
                    if (from..=to).contains(&angle) {
                        points.push(at(outer, angle));
                    }
                }
                let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                for p in points {
                    for k in 0..2 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                Some([lo[0], lo[1], hi[0], hi[1]])
            }
        }
    }

    /// The projection's name (`"fisheye"` whatever its field).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Perspective => PROJECTION_NAMES[0],
            Self::Equirectangular => PROJECTION_NAMES[1],
            Self::Fisheye { .. } => PROJECTION_NAMES[2],
        }
    }

    /// Why the projection is not usable, if it is not: a fisheye's field outside (0°, 360°].
    ///
    /// # Errors
    /// The reason, naming the field and its value.
    pub fn check(self) -> Result<Self, String> {
        match self {
            Self::Fisheye { fov_deg } if !(fov_deg > 0.0 && fov_deg <= MAX_FISHEYE_FOV_DEG) => {
                Err(format!(
                    "a fisheye's fov_deg must be in (0, {MAX_FISHEYE_FOV_DEG}], got {fov_deg:?}"
                ))
            }
            other => Ok(other),
        }
    }

    /// The unit direction through the point `ndc` for the basis (`forward`, `right`, `up`);
    /// `None` where the image sees nothing (outside a fisheye's circle). Not for the pinhole,
    /// whose direction depends on the field of view ([`crate::ViewRays::direction`]).
    #[must_use]
    pub fn wide_direction(self, ndc: DVec2, [forward, right, up]: [DVec3; 3]) -> Option<DVec3> {
        match self {
            Self::Perspective => None,
            Self::Equirectangular => {
                let (longitude, latitude) = (PI * ndc.x, FRAC_PI_2 * ndc.y);
                let horizontal = longitude.cos() * forward + longitude.sin() * right;
                Some(latitude.cos() * horizontal + latitude.sin() * up)
            }
            Self::Fisheye { fov_deg } => {
                let rho = ndc.length();
                if rho > 1.0 {
                    return None;
                }
                let angle = rho * 0.5 * fov_deg.to_radians();
                let across = if rho > 0.0 {
                    (ndc.x * right + ndc.y * up) / rho
                } else {
                    DVec3::ZERO
                };
                Some(angle.cos() * forward + angle.sin() * across)
            }
        }
    }

    /// The point (normalised device coordinates) where the direction `direction` (need not be
    /// normalised) is seen, the inverse of [`Projection::wide_direction`]; `None` outside a
    /// fisheye's field or for the pinhole.
    #[must_use]
    pub fn wide_image_point(
        self,
        direction: DVec3,
        [forward, right, up]: [DVec3; 3],
    ) -> Option<DVec2> {
        let d = direction.try_normalize()?;
        let (along, across, above) = (d.dot(forward), d.dot(right), d.dot(up));
        match self {
            Self::Perspective => None,
            Self::Equirectangular => Some(DVec2::new(
                across.atan2(along) / PI,
                above.clamp(-1.0, 1.0).asin() / FRAC_PI_2,
            )),
            Self::Fisheye { fov_deg } => {
                let angle = along.clamp(-1.0, 1.0).acos();
                let rho = angle / (0.5 * fov_deg.to_radians());
                if rho > 1.0 {
                    return None;
                }
                let azimuth = DVec2::new(across, above)
                    .try_normalize()
                    .unwrap_or(DVec2::X);
                Some(rho * azimuth)
            }
        }
    }
}

impl fmt::Display for Projection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Fisheye { fov_deg } if *fov_deg != DEFAULT_FISHEYE_FOV_DEG => {
                write!(f, "fisheye:{fov_deg}")
            }
            other => f.write_str(other.name()),
        }
    }
}

impl FromStr for Projection {
    type Err = String;

    /// `perspective`, `equirectangular`, `fisheye` (180°) or `fisheye:FOV` (degrees).
    fn from_str(text: &str) -> Result<Self, String> {
        let (name, field) = match text.split_once(':') {
            Some((name, field)) => (name.trim(), Some(field.trim())),
            None => (text.trim(), None),
        };
        let projection = match (name, field) {
            ("perspective", None) => Self::Perspective,
            ("equirectangular", None) => Self::Equirectangular,
            ("fisheye", None) => Self::Fisheye {
                fov_deg: DEFAULT_FISHEYE_FOV_DEG,
            },
            ("fisheye", Some(field)) => Self::Fisheye {
                fov_deg: field.parse().map_err(|_| {
                    format!("{field:?} is not a fisheye's field of view in degrees")
                })?,
            },
            _ => {
                return Err(format!(
                    "unknown projection {text:?}; expected \"perspective\", \"equirectangular\", \
                     \"fisheye\" or \"fisheye:FOV\" (degrees)"
                ));
            }
        };
        projection.check()
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    const BASIS: [DVec3; 3] = [DVec3::Y, DVec3::X, DVec3::Z];

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    /// The centre looks forward; the equirectangular image's edges look back, its top up and its
    /// quarter columns right and left; the fisheye's rim is at half its field.
    #[test]
    fn the_conventions_hold_at_the_landmarks() {
        let equi = Projection::Equirectangular;
        let look = |p: Projection, x, y| p.wide_direction(DVec2::new(x, y), BASIS).unwrap();
        assert!(close(look(equi, 0.0, 0.0), DVec3::Y));
        assert!(close(look(equi, 0.5, 0.0), DVec3::X));
        assert!(close(look(equi, -0.5, 0.0), -DVec3::X));
        assert!(close(look(equi, 1.0, 0.0), -DVec3::Y));
        assert!(close(look(equi, 0.3, 1.0), DVec3::Z));
        let fisheye = Projection::Fisheye { fov_deg: 180.0 };
        assert!(close(look(fisheye, 0.0, 0.0), DVec3::Y));
        assert!(close(look(fisheye, 1.0, 0.0), DVec3::X));
        assert!(close(look(fisheye, 0.0, 1.0), DVec3::Z));
        assert!(
            fisheye
                .wide_direction(DVec2::new(0.8, 0.8), BASIS)
                .is_none()
        );
        let sphere = Projection::Fisheye { fov_deg: 360.0 };
        assert!(close(look(sphere, 1.0, 0.0), -DVec3::Y));
    }

    #[test]
    fn names_read_back_and_bad_ones_are_refused() {
        for text in ["perspective", "equirectangular", "fisheye", "fisheye:220"] {
            let projection: Projection = text.parse().unwrap();
            assert_eq!(projection.to_string(), text);
        }
        assert!(
            "fisheye:0"
                .parse::<Projection>()
                .unwrap_err()
                .contains("(0, 360]")
        );
        assert!("fisheye:400".parse::<Projection>().is_err());
        assert!(
            "cube"
                .parse::<Projection>()
                .unwrap_err()
                .contains("equirectangular")
        );
    }

    proptest! {
        /// Every point of the image that sees something is where its direction is seen.
        #[test]
        fn image_points_invert_directions(
            x in -0.999_f64..0.999,
            y in -0.999_f64..0.999,
            fov in 1.0_f64..359.0,
        ) {
            let ndc = DVec2::new(x, y);
            for projection in [Projection::Equirectangular, Projection::Fisheye { fov_deg: fov }] {
                if let Some(direction) = projection.wide_direction(ndc, BASIS) {
                    prop_assert!((direction.length() - 1.0).abs() < 1e-12);
                    let back = projection.wide_image_point(direction, BASIS).unwrap();
                    prop_assert!((back - ndc).length() < 1e-9, "{projection:?} {ndc} {back}");
                }
            }
        }
    }

    /// `ALL` lists every projection once, in `PROJECTION_NAMES`' order, each with a label of
    /// its own; only the pinhole is one; and a picture is decided by its place in the whole
    /// picture exactly where the projection is wide or the observer has two eyes.
    #[test]
    fn every_projection_is_listed_once_and_only_the_pinhole_is_one() {
        let names: Vec<&str> = Projection::ALL.iter().map(|p| p.name()).collect();
        assert_eq!(names, PROJECTION_NAMES);
        let mut labels: Vec<&str> = Projection::ALL.iter().map(|p| p.label()).collect();
        labels.sort_unstable();
        labels.dedup();
        assert_eq!(labels.len(), Projection::ALL.len());
        let pinholes: Vec<Projection> = (Projection::ALL.into_iter())
            .filter(|p| p.is_pinhole())
            .collect();
        assert_eq!(pinholes, [Projection::Perspective]);
        for projection in Projection::ALL {
            assert_eq!(projection.check(), Ok(projection));
            for stereo in [
                None,
                Some(crate::Stereo {
                    eye_separation: 0.065,
                }),
            ] {
                let observer = crate::Observer {
                    projection,
                    stereo,
                    ..crate::builtin::find_builtin("fig7")
                        .unwrap()
                        .build()
                        .unwrap()
                        .0
                        .observer
                };
                assert_eq!(
                    observer.picture_decides(),
                    projection != Projection::Perspective || stereo.is_some(),
                    "{projection} {stereo:?}"
                );
            }
        }
    }

    /// A cap's bound: none for the pinhole; in the equirectangular picture a small cap straight
    /// ahead spans its angular radius around the centre (longitude over π, latitude over π/2);
    /// in a fisheye of 180° a cap behind is outside the field (empty).
    #[test]
    fn a_cap_is_bounded_where_the_projection_draws_it() {
        let basis = (BASIS[0], BASIS[1], BASIS[2]);
        let r = 0.1;
        assert_eq!(Projection::Perspective.cap_bound(BASIS[0], r, basis), None);
        let [x0, y0, x1, y1] = Projection::Equirectangular
            .cap_bound(BASIS[0], r, basis)
            .unwrap();
        let half_width = r.sin().asin() / PI;
        assert!((x0 + half_width).abs() < 1e-12 && (x1 - half_width).abs() < 1e-12);
        assert!((y0 + r / FRAC_PI_2).abs() < 1e-12 && (y1 - r / FRAC_PI_2).abs() < 1e-12);
        let dome = Projection::Fisheye {
            fov_deg: DEFAULT_FISHEYE_FOV_DEG,
        };
        let [x0, _, x1, _] = dome.cap_bound(-BASIS[0], r, basis).unwrap();
        assert!(x0 > x1, "behind a hemisphere's dome: nothing");
    }
}
