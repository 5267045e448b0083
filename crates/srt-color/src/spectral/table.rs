//! The coefficient table of Jakob & Hanika 2019 §5: the fit of [`super::fit_rgb`] precomputed
//! over the RGB cube, so that a texture texel costs a lookup and a trilinear interpolation.
//!
//! # Layout (what a GPU mirror needs)
//!
//! Three tables, one per largest channel m ∈ {R, G, B}, each `n × n × n` texels of three `f32`
//! coefficients (c₀, c₁, c₂) for λ in nm. Texel (m, k, j, i), stored at
//! `((m · n + k) · n + j) · n + i`, is the fit of the colour whose channel m is zₖ, channel
//! (m + 1) mod 3 is zₖ · i/(n − 1) and channel (m + 2) mod 3 is zₖ · j/(n − 1), with the
//! nonlinear brightness scale zₖ = smoothstep(smoothstep(k/(n − 1))), smoothstep(x) = x²(3 − 2x),
//! which spends texels on dark colours where CIELAB is most sensitive (as pbrt-v4 and
//! `rgb2spec_opt`).
//!
//! Lookup of linear rgb ([`CoefficientTable::lookup`]): if r = g = b, the exact constant; else m =
//! the largest channel, z = rgb\[m\], x = rgb\[(m+1) mod 3\]/z · (n − 1), y = rgb\[(m+2) mod 3\]/z ·
//! (n − 1), k the interval of the scale holding z; trilinear interpolation of the eight texels
//! with weights from x − ⌊x⌋, y − ⌊y⌋ and (z − zₖ)/(zₖ₊₁ − zₖ).

use std::sync::LazyLock;
use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;

use super::fit::{gauss_newton, target_lab};
use super::sigmoid::SigmoidPolynomial;
use crate::error::{ColourError, unit_interval};

/// Smallest and largest supported table resolution n.
const RESOLUTION_RANGE: std::ops::RangeInclusive<usize> = 3..=256;

/// Gauss–Newton iterations allowed per table entry (each starts from its neighbour's solution).
const ITERATIONS_PER_ENTRY: usize = 30;

/// The 3 × n³ table of Jakob–Hanika coefficients over linear sRGB (§5 of the paper).
#[derive(Clone, Debug, PartialEq)]
pub struct CoefficientTable {
    resolution: usize,
    scale: Vec<f64>,
    texels: Vec<[f32; 3]>,
}

/// x²(3 − 2x), the smoothstep of the brightness scale.
fn smoothstep(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

impl CoefficientTable {
    /// The resolution of [`srgb_coefficient_table`]: 32³ texels per table (1.2 MB of `f32`);
    /// `tests/spectral.rs` measures its interpolation error against fresh fits.
    pub const DEFAULT_RESOLUTION: usize = 32;

    /// Builds the table by fitting every texel, on all available cores.
    ///
    /// As in `rgb2spec_opt`, each (m, i, j) column is solved along the brightness scale by
    /// continuation: from k = n/5 upwards and from k = n/5 downwards, each entry starting from the
    /// previous one's coefficients (the first from zero, R = ½).
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidResolution`] unless 3 ≤ `resolution` ≤ 256.
    pub fn build(resolution: usize) -> Result<Self, ColourError> {
        if !RESOLUTION_RANGE.contains(&resolution) {
            return Err(ColourError::InvalidResolution(resolution));
        }
        let n = resolution;
        let scale = brightness_scale(n);
        // One task per (m, j) row; each returns its n × n (i, k) coefficients.
        let tasks = 3 * n;
        let next = AtomicUsize::new(0);
        let work = || {
            let mut done = Vec::new();
            loop {
                let task = next.fetch_add(1, Ordering::Relaxed);
                if task >= tasks {
                    break done;
                }
                done.push((task, fit_row(task / n, task % n, &scale)));
            }
        };
        // This thread works too; helpers are added where threads exist (not in a browser's
        // WebAssembly, where the build runs on this thread alone).
        let threads = std::thread::available_parallelism().map_or(1, usize::from);
        let mut rows: Vec<(usize, Vec<[f64; 3]>)> = std::thread::scope(|scope| {
            let helpers: Vec<_> = (1..threads.min(tasks))
                .map_while(|_| std::thread::Builder::new().spawn_scoped(scope, work).ok())
                .collect();
            let mut rows = work();
            for helper in helpers {
                rows.extend(
                    helper
                        .join()
                        .unwrap_or_else(|e| std::panic::resume_unwind(e)),
                );
            }
            rows
        });
        rows.sort_by_key(|&(task, _)| task);
        let mut texels = vec![[0.0_f32; 3]; 3 * n * n * n];
        for (task, row) in rows {
            let (m, j) = (task / n, task % n);
            for k in 0..n {
                for i in 0..n {
                    let p = SigmoidPolynomial::from_normalised(row[k * n + i]).coefficients();
                    texels[Self::index_of(n, m, k, j, i)] = p.map(|c| c as f32);
                }
            }
        }
        Ok(Self {
            resolution,
            scale,
            texels,
        })
    }

    /// The table of resolution `resolution` whose texels are `bytes`, as [`Self::texel_bytes`]
    /// wrote them; `None` unless the resolution is supported and `bytes` holds 3 · n³ texels.
    fn from_texel_bytes(resolution: usize, bytes: &[u8]) -> Option<Self> {
        let count = 3 * resolution.pow(3);
        if !RESOLUTION_RANGE.contains(&resolution) || bytes.len() != count * TEXEL_BYTES {
            return None;
        }
        let word = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        let texels = bytes
            .chunks_exact(TEXEL_BYTES)
            .map(|t| [word(&t[0..4]), word(&t[4..8]), word(&t[8..12])])
            .collect();
        Some(Self {
            resolution,
            scale: brightness_scale(resolution),
            texels,
        })
    }

    /// The texels as little-endian `f32` bytes, c₀, c₁, c₂ per texel in [`Self::texels`]' order:
    /// the form of the table embedded in the crate (`data/coefficients_32.bin`).
    #[must_use]
    pub fn texel_bytes(&self) -> Vec<u8> {
        self.texels
            .iter()
            .flatten()
            .flat_map(|c| c.to_le_bytes())
            .collect()
    }

    /// Index of texel (m, k, j, i) in a table of resolution `n`.
    fn index_of(n: usize, m: usize, k: usize, j: usize, i: usize) -> usize {
        ((m * n + k) * n + j) * n + i
    }

    /// The resolution n (texels per axis).
    #[must_use]
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The brightness scale z₀ = 0 < … < z_{n−1} = 1 along the largest channel.
    #[must_use]
    pub fn scale(&self) -> &[f64] {
        &self.scale
    }

    /// All 3 · n³ texels (c₀, c₁, c₂ for λ in nm) in the layout of the module documentation.
    #[must_use]
    pub fn texels(&self) -> &[[f32; 3]] {
        &self.texels
    }

    /// The texel of largest channel `m`, brightness index `k`, second-channel index `i` and
    /// third-channel index `j`; `None` outside the table.
    #[must_use]
    pub fn texel(&self, m: usize, k: usize, j: usize, i: usize) -> Option<[f32; 3]> {
        let n = self.resolution;
        (m < 3 && k < n && j < n && i < n).then(|| self.texels[Self::index_of(n, m, k, j, i)])
    }

    /// The linear sRGB colour that texel (m, k, j, i) was fitted to.
    #[must_use]
    pub fn texel_rgb(&self, m: usize, k: usize, j: usize, i: usize) -> DVec3 {
        texel_rgb(&self.scale, m, k, j, i)
    }

    /// Jakob–Hanika coefficients of linear sRGB `rgb` by table lookup and trilinear
    /// interpolation (module documentation); greys are exact constants.
    ///
    /// # Errors
    ///
    /// [`ColourError::InvalidRgb`] unless every component lies in [0, 1].
    pub fn lookup(&self, rgb: DVec3) -> Result<SigmoidPolynomial, ColourError> {
        for c in rgb.to_array() {
            unit_interval(c, ColourError::InvalidRgb)?;
        }
        if rgb.x == rgb.y && rgb.y == rgb.z {
            return SigmoidPolynomial::constant(rgb.x);
        }
        let c = rgb.to_array();
        let m = if c[0] > c[1] {
            if c[0] > c[2] { 0 } else { 2 }
        } else if c[1] > c[2] {
            1
        } else {
            2
        };
        let n = self.resolution;
        let z = c[m];
        // z > 0 here: the largest channel of a non-grey colour in [0, 1]³.
        let last = (n - 1) as f64;
        let x = c[(m + 1) % 3] / z * last;
        let y = c[(m + 2) % 3] / z * last;
        let cell = |v: f64| (v.floor() as usize).min(n - 2);
        let (i, j) = (cell(x), cell(y));
        let k = self
            .scale
            .partition_point(|&s| s <= z)
            .saturating_sub(1)
            .min(n - 2);
        let weights = [
            x - i as f64,
            y - j as f64,
            (z - self.scale[k]) / (self.scale[k + 1] - self.scale[k]),
        ];
        let mut sum = [0.0_f64; 3];
        for corner in 0..8 {
            let (di, dj, dk) = (corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            let w = [di, dj, dk]
                .iter()
                .zip(weights)
                .map(|(&d, t)| if d == 1 { t } else { 1.0 - t })
                .product::<f64>();
            let texel = self.texels[Self::index_of(n, m, k + dk, j + dj, i + di)];
            for (s, t) in sum.iter_mut().zip(texel) {
                *s += w * f64::from(t);
            }
        }
        SigmoidPolynomial::new(sum)
    }
}

/// Bytes of one texel in [`CoefficientTable::texel_bytes`]: three `f32`.
const TEXEL_BYTES: usize = 12;

/// The brightness scale zₖ = smoothstep(smoothstep(k/(n − 1))) of a table of resolution `n`.
fn brightness_scale(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| smoothstep(smoothstep(k as f64 / (n - 1) as f64)))
        .collect()
}

/// The linear sRGB colour of texel (m, k, j, i) on the brightness scale `scale`.
fn texel_rgb(scale: &[f64], m: usize, k: usize, j: usize, i: usize) -> DVec3 {
    let last = (scale.len() - 1) as f64;
    let z = scale[k];
    let mut rgb = [0.0; 3];
    rgb[m] = z;
    rgb[(m + 1) % 3] = z * i as f64 / last;
    rgb[(m + 2) % 3] = z * j as f64 / last;
    DVec3::from_array(rgb)
}

/// Fits row (m, j) of the table: for every i, the column over k by continuation from k = n/5.
/// Returns the normalised coefficients at `k * n + i`.
fn fit_row(m: usize, j: usize, scale: &[f64]) -> Vec<[f64; 3]> {
    let n = scale.len();
    let start = n / 5;
    let mut row = vec![[0.0; 3]; n * n];
    for i in 0..n {
        for ks in [
            (start..n).collect::<Vec<_>>(),
            (0..start).rev().collect::<Vec<_>>(),
        ] {
            let mut abc = [0.0; 3];
            for k in ks {
                let target = target_lab(texel_rgb(scale, m, k, j, i));
                abc = gauss_newton(target, abc, ITERATIONS_PER_ENTRY).0;
                row[k * n + i] = abc;
            }
        }
    }
    row
}

/// [`CoefficientTable::build`] at [`CoefficientTable::DEFAULT_RESOLUTION`], as
/// [`CoefficientTable::texel_bytes`] (`cargo xtask coefficient-table` writes it; a test checks
/// it against a fresh build).
const EMBEDDED_TABLE: &[u8] = include_bytes!("../../data/coefficients_32.bin");

/// The sRGB coefficient table at [`CoefficientTable::DEFAULT_RESOLUTION`]: the build embedded in
/// the crate, read on first use (fitting it takes about 0.36 s on two cores, which every
/// renderer paid at start-up; see docs/colour.md).
///
/// # Panics
///
/// Never: the embedded table has the default resolution's size (tested).
#[must_use]
pub fn srgb_coefficient_table() -> &'static CoefficientTable {
    static TABLE: LazyLock<CoefficientTable> = LazyLock::new(|| {
        CoefficientTable::from_texel_bytes(CoefficientTable::DEFAULT_RESOLUTION, EMBEDDED_TABLE)
            .expect("the embedded table has the default resolution's size")
    });
    &TABLE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_resolutions_and_rgb() {
        assert!(CoefficientTable::build(2).is_err());
        assert!(CoefficientTable::build(257).is_err());
        let table = CoefficientTable::build(4).unwrap();
        assert!(table.lookup(DVec3::new(0.2, 1.5, 0.1)).is_err());
        assert!(table.lookup(DVec3::new(0.2, f64::NAN, 0.1)).is_err());
    }

    #[test]
    fn texel_bytes_read_back_and_wrong_sizes_are_refused() {
        let table = CoefficientTable::build(4).unwrap();
        let bytes = table.texel_bytes();
        assert_eq!(CoefficientTable::from_texel_bytes(4, &bytes), Some(table));
        assert_eq!(CoefficientTable::from_texel_bytes(5, &bytes), None);
        assert_eq!(CoefficientTable::from_texel_bytes(4, &bytes[1..]), None);
        assert_eq!(CoefficientTable::from_texel_bytes(2, &[]), None);
    }

    #[test]
    fn the_embedded_table_is_a_fresh_build() {
        // Regenerate with `cargo xtask coefficient-table` after any change to the fit. The fit
        // runs on libm's functions, which may differ in their last bits between platforms, so
        // the coefficients are compared to a relative 10⁻⁵ (a changed fit moves them by far more).
        let fresh = CoefficientTable::build(CoefficientTable::DEFAULT_RESOLUTION).unwrap();
        let embedded = srgb_coefficient_table();
        assert_eq!(embedded.resolution(), fresh.resolution());
        assert_eq!(embedded.scale(), fresh.scale());
        for (index, (e, f)) in embedded.texels().iter().zip(fresh.texels()).enumerate() {
            for (a, b) in e.iter().zip(f) {
                assert!(
                    (a - b).abs() <= 1e-5 * b.abs().max(1.0),
                    "texel {index}: embedded {e:?}, fresh {f:?}"
                );
            }
        }
    }

    #[test]
    fn scale_runs_from_zero_to_one() {
        let table = CoefficientTable::build(5).unwrap();
        assert_eq!(table.scale().first(), Some(&0.0));
        assert_eq!(table.scale().last(), Some(&1.0));
        assert!(table.scale().windows(2).all(|w| w[0] < w[1]));
        assert_eq!(table.texels().len(), 3 * 125);
    }

    #[test]
    fn lookup_at_a_texel_returns_that_texel() {
        let table = CoefficientTable::build(6).unwrap();
        let (m, k, j, i) = (1, 3, 2, 4);
        let got = table
            .lookup(table.texel_rgb(m, k, j, i))
            .unwrap()
            .coefficients();
        let want = table.texel(m, k, j, i).unwrap();
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - f64::from(w)).abs() <= 1e-9 * f64::from(w).abs().max(1.0),
                "{got:?} vs {want:?}"
            );
        }
    }
}
