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
}
