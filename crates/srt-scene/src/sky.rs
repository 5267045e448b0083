//! The sky: stars at infinity, at rest in the scene's world frame W, each a black body of a
//! given temperature and brightness (docs/physics.md, "The sky"). A built-in synthetic star field
//! or stars read from a CSV file of directions, temperatures and magnitudes; and an
//! equirectangular image of the sky (EXR or Radiance HDR, linear light).
//!
//! A star is drawn like a light source of the scene: seen in the direction and with the Doppler
//! factor of [`srt_physics::distant_source_image`], coloured as a black body at D·T, and (with
//! the searchlight effect) its flux scales as D² — the D⁴ of the black body's radiance at D·T
//! over the 1/D² by which aberration shrinks the solid angle it covers.

use std::path::{Path, PathBuf};

use std::sync::{Arc, Mutex, PoisonError};
use std::time::SystemTime;

use glam::{DMat3, DVec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::input_file::{self, FileKind, InputFileError};
use crate::limits::Budget;
use crate::textures::decode_checked;

/// The most stars a sky may hold (a built-in field or a CSV file).
pub const MAX_STARS: usize = 1_000_000;

/// Default magnitude at which a star's light fills one pixel's colour completely.
pub const DEFAULT_SATURATION_MAGNITUDE: f64 = 3.0;

/// Seed of the built-in star field: the same field on every machine and in every version.
pub const STAR_FIELD_SEED: u64 = 0x5eed_57a5;

/// One star: a black body at infinity, at rest in W.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Star {
    /// Unit direction from the observer to the star, in W.
    pub direction: DVec3,
    /// Black-body temperature in kelvin (> 0).
    pub temperature_k: f64,
    /// Apparent visual magnitude at rest (smaller is brighter; 5 magnitudes = a factor 100).
    pub magnitude: f64,
}

/// Colour temperature of the light a sky image shows (kelvin): its texels are the light of a
/// black body this hot — the correlated colour temperature of D65, the white of sRGB — filtered
/// by each texel's colour, so white texels stay white at rest (docs/colour.md).
pub const SKY_IMAGE_WHITE_K: f64 = 6504.0;

/// An equirectangular image of the sky, at rest in W: linear-light RGB radiance (any value ≥ 0),
/// row 0 at the zenith (+z), the middle row at the horizon, column 0 towards −x, the middle
/// column towards +x, longitude increasing towards +y.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyImage {
    /// Width in texels (360° of longitude).
    pub width: u32,
    /// Height in texels (180° of latitude).
    pub height: u32,
    /// Linear RGB, row-major from the zenith.
    pub texels: Arc<[[f32; 3]]>,
    /// The file it came from, for messages and provenance.
    pub source: String,
}

impl SkyImage {
    /// The image's texture coordinates (u, v) ∈ [0, 1)² × [0, 1] of the unit direction
    /// `direction` (in W): u = ½ + φ/2π with φ = atan2(y, x), v = ½ − asin(z)/π.
    #[must_use]
    pub fn uv(direction: DVec3) -> (f64, f64) {
        let u = 0.5 + direction.y.atan2(direction.x) / std::f64::consts::TAU;
        let v = 0.5 - direction.z.clamp(-1.0, 1.0).asin() / std::f64::consts::PI;
        (u.rem_euclid(1.0), v)
    }

    /// The radiance seen in the unit direction `direction` (in W): bilinear between the four
    /// texel centres around it, wrapping around in longitude and clamped at the poles.
    #[must_use]
    pub fn sample(&self, direction: DVec3) -> DVec3 {
        let (u, v) = Self::uv(direction);
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let x = u * w - 0.5;
        let y = (v * h - 0.5).clamp(0.0, h - 1.0);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // wrapped, clamped
        let texel = |i: f64, j: f64| {
            let column = i.rem_euclid(w) as usize;
            let row = j.min(h - 1.0) as usize;
            let [r, g, b] = self.texels[row * self.width as usize + column];
            DVec3::new(f64::from(r), f64::from(g), f64::from(b))
        };
        (1.0 - fy) * ((1.0 - fx) * texel(x0, y0) + fx * texel(x0 + 1.0, y0))
            + fy * ((1.0 - fx) * texel(x0, y0 + 1.0) + fx * texel(x0 + 1.0, y0 + 1.0))
    }
}

/// The sky of a scene, seen from the observer's frame S.
#[derive(Debug, Clone, PartialEq)]
pub struct Sky {
    /// Velocity of the sky's rest frame W relative to S (−β of a moving observer; zero for an
    /// observer at rest, and in the measured and Newtonian views).
    pub beta: DVec3,
    /// The stars (directions in W).
    pub stars: Vec<Star>,
    /// A star of this magnitude at rest fills one pixel with its full colour.
    pub saturation_magnitude: f64,
    /// The sky image, if any.
    pub image: Option<SkyImage>,
    /// Factor on the image's radiance.
    pub image_brightness: f64,
    /// Linear map of directions in W to directions in S, before aberration: the identity, except
    /// in the measured view (the contraction by 1/γ along W's velocity).
    pub direction_map: DMat3,
}

impl Default for Sky {
    fn default() -> Self {
        Self {
            beta: DVec3::ZERO,
            stars: Vec::new(),
            saturation_magnitude: DEFAULT_SATURATION_MAGNITUDE,
            image: None,
            image_brightness: 1.0,
            direction_map: DMat3::IDENTITY,
        }
    }
}

impl Sky {
    /// Whether there is nothing to draw.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.stars.is_empty() && self.image.is_none()
    }

    /// The colour weight of a star of `magnitude` at rest: 10^(−0.4 (m − m_sat)), so that a star
    /// of the saturation magnitude has weight 1 (Pogson's ratio: 5 magnitudes = 100×).
    #[must_use]
    pub fn weight(&self, magnitude: f64) -> f64 {
        10f64.powf(-0.4 * (magnitude - self.saturation_magnitude))
    }
}

/// Why a star file could not be used.
#[derive(Debug, thiserror::Error)]
pub enum SkyError {
    /// The file could not be read.
    #[error("sky file {}: {error}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        error: InputFileError,
    },
    /// A line is not a valid star.
    #[error("star file {}, line {line}: {reason}", path.display())]
    Line {
        /// The file.
        path: PathBuf,
        /// The line (from 1).
        line: u64,
        /// What is wrong.
        reason: String,
    },
    /// The header names no usable set of columns, the file has no stars or too many, or a sky
    /// image is not usable.
    #[error("sky file {}: {reason}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
}

/// A synthetic star field of `count` stars (at most [`MAX_STARS`]), the same on every machine:
/// directions uniform over the sphere, magnitudes from −1.5 to 6.5 with the number of stars
/// brighter than m growing as 10^(0.4 m) (faint stars are many), temperatures log-uniform from
/// 3 000 K to 30 000 K (red to blue-white).
#[must_use]
pub fn star_field(count: usize) -> Vec<Star> {
    let mut rng = ChaCha8Rng::seed_from_u64(STAR_FIELD_SEED);
    (0..count.min(MAX_STARS))
        .map(|_| {
            let z: f64 = rng.random_range(-1.0..=1.0);
            let phi: f64 = rng.random_range(0.0..std::f64::consts::TAU);
            let r = (1.0 - z * z).max(0.0).sqrt();
            let u: f64 = rng.random_range(f64::MIN_POSITIVE..=1.0);
            let magnitude = (6.5 + 2.5 * u.log10()).max(-1.5);
            let temperature_k = 10f64.powf(rng.random_range(3000f64.log10()..30000f64.log10()));
            Star {
                direction: DVec3::new(r * phi.cos(), r * phi.sin(), z),
                temperature_k,
                magnitude,
            }
        })
        .collect()
}

/// Reads the equirectangular sky image at `path` (OpenEXR or Radiance HDR, linear light; other
/// formats the texture loader reads are taken as sRGB-encoded and decoded), charging its texels
/// to `budget`.
///
/// # Errors
/// [`SkyError`] naming the file: it cannot be read or decoded, is too large, or has negative or
/// non-finite radiance.
pub fn read_sky_image(path: &Path, budget: &mut Budget) -> Result<SkyImage, SkyError> {
    let fail = |reason: String| SkyError::File {
        path: path.to_path_buf(),
        reason,
    };
    let bytes = input_file::read(path, FileKind::Image).map_err(|error| SkyError::Io {
        path: path.to_path_buf(),
        error,
    })?;
    let extension = path.extension().and_then(|e| e.to_str());
    let image = decode_checked(&bytes, extension, budget).map_err(fail)?;
    let linear_light = matches!(
        image,
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
    );
    let rgb = image.into_rgb32f();
    let mut texels = Vec::with_capacity(rgb.len() / 3);
    for pixel in rgb.pixels() {
        let c = pixel.0.map(|c| {
            if linear_light {
                c
            } else {
                srt_color::srgb_decode(f64::from(c)) as f32
            }
        });
        if c.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(fail(format!(
                "it has a texel of radiance {c:?}; a sky needs finite values ≥ 0"
            )));
        }
        texels.push(c);
    }
    Ok(SkyImage {
        width: rgb.width(),
        height: rgb.height(),
        texels: texels.into(),
        source: path.display().to_string(),
    })
}

/// A file as last read: its path, size and modification time, and what was made of it.
struct LastRead<T> {
    key: (PathBuf, u64, Option<SystemTime>),
    value: T,
}

/// `read()` of the file at `path`, or a copy of the value read last time if the file (path,
/// size, modification time) is unchanged: the viewer builds its scene again on every edit —
/// every frame of a flight — and a sky file is decoded once, not per frame.
fn read_cached<T: Clone, E>(
    cache: &Mutex<Option<LastRead<T>>>,
    path: &Path,
    read: impl FnOnce() -> Result<T, E>,
) -> Result<T, E> {
    let key = std::fs::metadata(path)
        .ok()
        .map(|m| (path.to_path_buf(), m.len(), m.modified().ok()));
    let mut last = cache.lock().unwrap_or_else(PoisonError::into_inner);
    if let (Some(key), Some(hit)) = (&key, last.as_ref())
        && hit.key == *key
    {
        return Ok(hit.value.clone());
    }
    let value = read()?;
    if let Some(key) = key {
        *last = Some(LastRead {
            key,
            value: value.clone(),
        });
    }
    Ok(value)
}

/// [`read_star_file`] through a cache of the last file read (unchanged files are not parsed
/// again).
///
/// # Errors
/// As [`read_star_file`].
pub fn read_star_file_cached(path: &Path) -> Result<Vec<Star>, SkyError> {
    static LAST: Mutex<Option<LastRead<Vec<Star>>>> = Mutex::new(None);
    read_cached(&LAST, path, || read_star_file(path))
}

/// [`read_sky_image`] through a cache of the last image read (an unchanged file is not decoded
/// again; its texels are charged to `budget` either way).
///
/// # Errors
/// As [`read_sky_image`].
pub fn read_sky_image_cached(path: &Path, budget: &mut Budget) -> Result<SkyImage, SkyError> {
    static LAST: Mutex<Option<LastRead<SkyImage>>> = Mutex::new(None);
    let mut fresh = false;
    let image = read_cached(&LAST, path, || {
        fresh = true;
        read_sky_image(path, budget)
    })?;
    if !fresh {
        budget
            .charge_texels(image.width, image.height)
            .map_err(|e| SkyError::File {
                path: path.to_path_buf(),
                reason: format!("the image is too large: {e}"),
            })?;
    }
    Ok(image)
}

/// The columns a star file may have: a direction as `x,y,z` (any length, in W) or as right
/// ascension and declination in degrees (`ra_deg,dec_deg`: +z is the pole, ra = 0 is +x), plus
/// `temperature_k` and `magnitude`. Other columns are ignored.
const DIRECTION_COLUMNS: [&[&str]; 2] = [&["x", "y", "z"], &["ra_deg", "dec_deg"]];

/// Reads stars from the CSV file at `path` (a header line naming the columns, see
/// docs/scene-format.md; `#` starts a comment line).
///
/// # Errors
/// [`SkyError`] naming the file (and line): it cannot be read, lacks a column, has a value that
/// is not a finite number, a zero direction, a non-positive temperature, no stars or more than
/// [`MAX_STARS`].
pub fn read_star_file(path: &Path) -> Result<Vec<Star>, SkyError> {
    let text = input_file::read_text(path, FileKind::Stars).map_err(|error| SkyError::Io {
        path: path.to_path_buf(),
        error,
    })?;
    parse_stars(&text, path)
}

/// Parses the text of a star file; `path` names it in messages.
///
/// # Errors
/// As [`read_star_file`].
pub fn parse_stars(text: &str, path: &Path) -> Result<Vec<Star>, SkyError> {
    let file_error = |reason: String| SkyError::File {
        path: path.to_path_buf(),
        reason,
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .flexible(false)
        .from_reader(text.as_bytes());
    let headers = reader
        .headers()
        .map_err(|e| file_error(format!("cannot read the header line: {e}")))?
        .clone();
    let column = |name: &str| headers.iter().position(|h| h.eq_ignore_ascii_case(name));
    let direction = DIRECTION_COLUMNS
        .iter()
        .find_map(|names| names.iter().map(|n| column(n)).collect::<Option<Vec<_>>>())
        .ok_or_else(|| {
            file_error(format!(
                "the header line needs the columns x,y,z or ra_deg,dec_deg (found {})",
                headers.iter().collect::<Vec<_>>().join(",")
            ))
        })?;
    let [temperature, magnitude] = ["temperature_k", "magnitude"].map(column);
    let (Some(temperature), Some(magnitude)) = (temperature, magnitude) else {
        return Err(file_error(
            "the header line needs the columns temperature_k and magnitude".to_owned(),
        ));
    };
    let mut stars = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, csv::Position::line);
            SkyError::Line {
                path: path.to_path_buf(),
                line,
                reason: e.to_string(),
            }
        })?;
        let line = record.position().map_or(0, csv::Position::line);
        let line_error = |reason: String| SkyError::Line {
            path: path.to_path_buf(),
            line,
            reason,
        };
        let number = |index: usize| -> Result<f64, SkyError> {
            let name = &headers[index];
            let text = &record[index];
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(line_error(format!(
                    "{name} = \"{text}\" is not a finite number"
                ))),
            }
        };
        if stars.len() == MAX_STARS {
            return Err(file_error(format!("more than {MAX_STARS} stars")));
        }
        let values = direction
            .iter()
            .map(|&i| number(i))
            .collect::<Result<Vec<_>, _>>()?;
        let direction = if let [x, y, z] = values[..] {
            let v = DVec3::new(x, y, z);
            let length = v.length();
            if !(length > 0.0 && length.is_finite()) {
                return Err(line_error(format!(
                    "the direction ({x}, {y}, {z}) has no length"
                )));
            }
            v / length
        } else {
            let (ra, dec) = (values[0].to_radians(), values[1].to_radians());
            DVec3::new(dec.cos() * ra.cos(), dec.cos() * ra.sin(), dec.sin())
        };
        let temperature_k = number(temperature)?;
        if temperature_k <= 0.0 {
            return Err(line_error(format!(
                "temperature_k = {temperature_k} must be positive (kelvin)"
            )));
        }
        stars.push(Star {
            direction,
            temperature_k,
            magnitude: number(magnitude)?,
        });
    }
    if stars.is_empty() {
        return Err(file_error("it holds no stars".to_owned()));
    }
    Ok(stars)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<Star>, String> {
        parse_stars(text, Path::new("stars.csv")).map_err(|e| e.to_string())
    }

    #[test]
    fn reads_both_direction_forms() {
        let stars =
            parse("# a comment\nx, y, z, temperature_k, magnitude\n0, 0, 2, 5800, 1.5\n").unwrap();
        assert_eq!(stars[0].direction, DVec3::Z);
        assert_eq!(stars[0].temperature_k, 5800.0);
        let stars = parse("name,ra_deg,dec_deg,temperature_k,magnitude\nA,90,0,9600,0\n").unwrap();
        assert!((stars[0].direction - DVec3::Y).length() < 1e-15);
    }

    #[test]
    fn bad_files_name_the_file_line_and_reason() {
        let e = parse("x,y,temperature_k,magnitude\n1,2,3,4\n").unwrap_err();
        assert!(
            e.contains("stars.csv") && e.contains("x,y,z or ra_deg,dec_deg"),
            "{e}"
        );
        let e = parse("x,y,z,temperature_k,magnitude\n1,0,0,5000,1\n1,0,0,-5,1\n").unwrap_err();
        assert!(
            e.contains("line 3") && e.contains("must be positive"),
            "{e}"
        );
        let e = parse("x,y,z,temperature_k,magnitude\n0,0,0,5000,1\n").unwrap_err();
        assert!(e.contains("line 2") && e.contains("no length"), "{e}");
        let e = parse("x,y,z,temperature_k,magnitude\n1,0,0,NaN,1\n").unwrap_err();
        assert!(e.contains("not a finite number"), "{e}");
        let e = parse("x,y,z,temperature_k,magnitude\n1,0,0,5000\n").unwrap_err();
        assert!(e.contains("line 2"), "{e}");
        let e = parse("x,y,z,temperature_k,magnitude\n").unwrap_err();
        assert!(e.contains("no stars"), "{e}");
    }

    proptest::proptest! {
        #[test]
        fn any_text_is_stars_or_a_message_never_a_panic(
            body in "[-0-9a-z.,#eE\n ]{0,200}",
            header in proptest::sample::select(vec![
                "x,y,z,temperature_k,magnitude",
                "ra_deg,dec_deg,temperature_k,magnitude",
                "name,x,y,z,temperature_k,magnitude,extra",
            ]),
        ) {
            match parse_stars(&format!("{header}\n{body}"), Path::new("s.csv")) {
                Ok(stars) => {
                    for star in stars {
                        proptest::prop_assert!((star.direction.length() - 1.0).abs() < 1e-9);
                        proptest::prop_assert!(star.temperature_k > 0.0);
                        proptest::prop_assert!(star.magnitude.is_finite());
                    }
                }
                Err(e) => proptest::prop_assert!(e.to_string().contains("s.csv")),
            }
        }
    }

    #[test]
    fn the_equirectangular_map_puts_the_axes_where_the_format_says() {
        let (u, v) = SkyImage::uv(DVec3::X);
        assert!((u - 0.5).abs() < 1e-15 && (v - 0.5).abs() < 1e-15);
        let (u, _) = SkyImage::uv(DVec3::Y);
        assert!((u - 0.75).abs() < 1e-15);
        let (u, _) = SkyImage::uv(DVec3::NEG_X);
        assert!(u.abs() < 1e-15 || (u - 1.0).abs() < 1e-15);
        assert!(SkyImage::uv(DVec3::Z).1.abs() < 1e-15);
        assert!((SkyImage::uv(DVec3::NEG_Z).1 - 1.0).abs() < 1e-15);
        // A 4 × 2 image: texel (2, 0) is centred at u = 5/8, v = 1/4.
        let mut texels = vec![[0.0f32; 3]; 8];
        texels[2] = [1.0, 2.0, 3.0];
        let image = SkyImage {
            width: 4,
            height: 2,
            texels: texels.into(),
            source: "test".into(),
        };
        let phi = (5.0 / 8.0 - 0.5) * std::f64::consts::TAU;
        let theta = std::f64::consts::FRAC_PI_4;
        let centre = DVec3::new(
            theta.cos() * phi.cos(),
            theta.cos() * phi.sin(),
            theta.sin(),
        );
        assert!((image.sample(centre) - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        // Half-way to the next column: half the value; the poles clamp, longitude wraps.
        let half = (6.0 / 8.0 - 0.5) * std::f64::consts::TAU;
        let between = DVec3::new(
            theta.cos() * half.cos(),
            theta.cos() * half.sin(),
            theta.sin(),
        );
        assert!((image.sample(between).x - 0.5).abs() < 1e-12);
        assert!(image.sample(DVec3::Z).is_finite());
        assert!(image.sample(DVec3::NEG_X).is_finite());
    }

    #[test]
    fn cached_reads_follow_the_file_and_charge_the_budget_every_time() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.csv");
        std::fs::write(&path, "x,y,z,temperature_k,magnitude\n1,0,0,5000,1\n").unwrap();
        assert_eq!(read_star_file_cached(&path).unwrap().len(), 1);
        assert_eq!(read_star_file_cached(&path).unwrap().len(), 1);
        // A changed file (another size) is read again.
        std::fs::write(
            &path,
            "x,y,z,temperature_k,magnitude\n1,0,0,5000,1\n0,1,0,7000,2\n",
        )
        .unwrap();
        assert_eq!(read_star_file_cached(&path).unwrap().len(), 2);
        std::fs::remove_file(&path).unwrap();
        assert!(
            read_star_file_cached(&path).is_err(),
            "a vanished file is an error"
        );

        let image_path = dir.path().join("sky.png");
        image::RgbImage::from_pixel(8, 4, image::Rgb([255, 0, 0]))
            .save(&image_path)
            .unwrap();
        let mut budget = Budget::new();
        let first = read_sky_image_cached(&image_path, &mut budget).unwrap();
        let after_one = budget.clone();
        let second = read_sky_image_cached(&image_path, &mut budget).unwrap();
        assert_eq!(first, second);
        assert_ne!(budget, after_one, "a cached image is charged again");
        // An sRGB image is decoded to linear light: 255 → 1.
        assert_eq!(first.texels[0], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn the_star_field_is_fixed_and_plausible() {
        let field = star_field(2000);
        assert_eq!(field, star_field(2000));
        assert_eq!(field.len(), 2000);
        for star in &field {
            assert!((star.direction.length() - 1.0).abs() < 1e-12);
            assert!((3000.0..=30000.0).contains(&star.temperature_k));
            assert!((-1.5..=6.5).contains(&star.magnitude));
        }
        // Uniform over the sphere: the mean direction is near zero.
        let mean = field.iter().map(|s| s.direction).sum::<DVec3>() / 2000.0;
        assert!(mean.length() < 0.1, "{mean}");
        // Faint stars outnumber bright ones.
        let faint = field.iter().filter(|s| s.magnitude > 5.0).count();
        assert!(faint > 1000, "{faint}");
    }
}
