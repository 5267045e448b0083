//! The 1D temperature → colour lookup table that the GPU samples, and its exact CPU mirror.
//!
//! # Layout (what the GPU must mirror)
//!
//! A [`TemperatureLut`] holds `N = size()` RGBA `f32` texels (alpha = 1). Texel `i` is
//! `tone_map.display_rgb(Tᵢ)` with Tᵢ uniform in ln T:
//! ln Tᵢ = ln `t_min` + i / (N − 1) · (ln `t_max` − ln `t_min`), so texel 0 is exactly `t_min`
//! and texel N − 1 exactly `t_max`. Upload it as a 1D `rgba32float` texture of width N
//! (WebGPU: `rgba32float` is filterable only with the `float32-filterable` feature; without it,
//! do the lerp below in the shader with two `textureLoad`s, which is what this mirror computes
//! anyway).
//!
//! # Sampling rule
//!
//! For a temperature T (the apparent temperature D · `T_light` of §4.2):
//!
//! 1. u = (ln T − ln `t_min`) / (ln `t_max` − ln `t_min`), clamped to [0, 1] (NaN → 0);
//! 2. texture coordinate s = (0.5 + u · (N − 1)) / N — the centre of texel 0 at u = 0, of
//!    texel N − 1 at u = 1 — sampled with linear filtering and clamp-to-edge addressing;
//! 3. equivalently x = u · (N − 1), i = ⌊x⌋, t = x − i, colour = (1 − t) · texel\[i\] +
//!    t · texel\[min(i + 1, N − 1)\], in `f32`.
//!
//! [`TemperatureLut::sample`] is step 3 and [`TemperatureLut::texture_coordinate`] is step 2. The
//! GPU computes u in `f32` and its filter hardware quantises t (commonly to 8 bits), so GPU and
//! CPU agree to a small fraction of the colour change between neighbouring texels, not bit for
//! bit. Temperatures outside `t_min ..= t_max` clamp to the end texels; a non-finite or
//! non-positive temperature gives the `t_min` texel.

use thiserror::Error;

use crate::tonemap::ToneMap;

/// Why a [`TemperatureLut`] could not be built.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum LutError {
    /// Fewer than two texels cannot span a range.
    #[error("a temperature LUT needs at least 2 texels, got {size}")]
    TooFewTexels {
        /// The requested size.
        size: usize,
    },
    /// More texels than a WebGPU 1D texture is guaranteed to hold.
    #[error(
        "a temperature LUT can have at most {max} texels, got {size}",
        max = TemperatureLut::MAX_SIZE
    )]
    TooManyTexels {
        /// The requested size.
        size: usize,
    },
    /// The range is not 0 < `t_min` < `t_max` with both finite.
    #[error(
        "invalid temperature range {t_min_k} K .. {t_max_k} K: need 0 < t_min < t_max, both finite"
    )]
    InvalidRange {
        /// The requested lower end in kelvin.
        t_min_k: f64,
        /// The requested upper end in kelvin.
        t_max_k: f64,
    },
}

/// A 1D lookup table of display colours over log temperature, for the GPU and the CPU renderer.
///
/// See the module documentation for the texel layout and the sampling rule the GPU mirrors.
#[derive(Clone, Debug, PartialEq)]
pub struct TemperatureLut {
    tone_map: ToneMap,
    table: LogTable,
}

/// Texels uniform in ln T over `t_min_k ..= t_max_k`, sampled by the module's rule: what the
/// colour table and the radiance table ([`crate::RadianceTable`]) share.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LogTable {
    t_min_k: f64,
    t_max_k: f64,
    texels: Vec<[f32; 4]>,
}

impl LogTable {
    /// `size` texels from `t_min_k` to `t_max_k`, texel i holding `texel(Tᵢ)`.
    ///
    /// # Errors
    /// As [`TemperatureLut::build`].
    pub(crate) fn build(
        size: usize,
        t_min_k: f64,
        t_max_k: f64,
        texel: impl Fn(f64) -> [f32; 4],
    ) -> Result<Self, LutError> {
        if size < 2 {
            return Err(LutError::TooFewTexels { size });
        }
        if size > TemperatureLut::MAX_SIZE {
            return Err(LutError::TooManyTexels { size });
        }
        let valid =
            t_min_k.is_finite() && t_max_k.is_finite() && t_min_k > 0.0 && t_min_k < t_max_k;
        if !valid {
            return Err(LutError::InvalidRange { t_min_k, t_max_k });
        }
        let texels = (0..size)
            .map(|i| texel(texel_temperature(t_min_k, t_max_k, size, i)))
            .collect();
        Ok(Self {
            t_min_k,
            t_max_k,
            texels,
        })
    }

    /// The texels, texel 0 at `t_min`.
    pub(crate) fn texels(&self) -> &[[f32; 4]] {
        &self.texels
    }

    /// Normalised position u ∈ [0, 1] of `temperature_k` in ln T (step 1 of the sampling rule).
    fn normalised(&self, temperature_k: f64) -> f64 {
        if !(temperature_k.is_finite() && temperature_k > 0.0) {
            return 0.0;
        }
        let u = (temperature_k / self.t_min_k).ln() / (self.t_max_k / self.t_min_k).ln();
        u.clamp(0.0, 1.0)
    }

    /// Step 3 of the sampling rule (see [`TemperatureLut::sample`]).
    pub(crate) fn sample(&self, temperature_k: f64) -> [f32; 4] {
        let last = self.texels.len() - 1;
        let mut x = self.normalised(temperature_k) * last as f64;
        // Snap to a texel centre what only rounding in ln/exp moved off it, so that sampling at
        // `texel_temperature(i)` returns texel i exactly (GPU filter weights are far coarser).
        let nearest = x.round();
        if (x - nearest).abs() < 1e-9 {
            x = nearest;
        }
        let i = (x.floor() as usize).min(last);
        let t = (x - i as f64) as f32;
        let a = self.texels[i];
        let b = self.texels[(i + 1).min(last)];
        std::array::from_fn(|k| (1.0 - t) * a[k] + t * b[k])
    }
}

impl TemperatureLut {
    /// Default temperature range in kelvin: 100 K to 10⁶ K, which covers what 0.999c (D up to
    /// about 45) does to lights between a few thousand and about 20 000 K, both ways.
    pub const DEFAULT_RANGE_K: (f64, f64) = (100.0, 1.0e6);

    /// Default number of texels: 4096 (64 KiB of `rgba32float`), Δ ln T ≈ 0.0022 over the default
    /// range.
    ///
    /// Chosen by the interpolation error against the exact [`ToneMap::display_rgb`] (a test
    /// checks each statement): with 4096 texels the linearly interpolated colour is within 1/255
    /// of the exact one in every channel except in the one texel interval where a channel leaves
    /// 0 (the green channel near 960 K, the blue one near 1900 K), and within 0.01 there. The
    /// sRGB curve rises like C^(1/2.4) from such a point, so the error there shrinks only as
    /// N^(−1/2.4): 1024 texels leave 0.028, 2048 leave 0.020, and 1/255 would need about 30 000,
    /// more than a WebGPU 1D texture holds ([`Self::MAX_SIZE`]).
    pub const DEFAULT_SIZE: usize = 4096;

    /// Largest accepted size: WebGPU's guaranteed `maxTextureDimension1D`.
    pub const MAX_SIZE: usize = 8192;

    /// Builds the table for `tone_map` with `size` texels from `t_min_k` to `t_max_k` inclusive,
    /// uniform in ln T.
    ///
    /// # Errors
    ///
    /// [`LutError::TooFewTexels`] if `size < 2`, [`LutError::TooManyTexels`] if
    /// `size > MAX_SIZE`, and [`LutError::InvalidRange`] unless 0 < `t_min_k` < `t_max_k` with
    /// both finite.
    pub fn build(
        tone_map: ToneMap,
        size: usize,
        t_min_k: f64,
        t_max_k: f64,
    ) -> Result<Self, LutError> {
        let table = LogTable::build(size, t_min_k, t_max_k, |t| {
            let [r, g, b] = tone_map.display_rgb(t).as_vec3().to_array();
            [r, g, b, 1.0]
        })?;
        Ok(Self { tone_map, table })
    }

    /// [`TemperatureLut::build`] with [`Self::DEFAULT_SIZE`] and [`Self::DEFAULT_RANGE_K`].
    ///
    /// # Panics
    ///
    /// Never: the default parameters are valid (a test builds them).
    #[must_use]
    pub fn with_defaults(tone_map: ToneMap) -> Self {
        let (t_min, t_max) = Self::DEFAULT_RANGE_K;
        match Self::build(tone_map, Self::DEFAULT_SIZE, t_min, t_max) {
            Ok(lut) => lut,
            Err(e) => unreachable!("the default LUT parameters are valid: {e}"),
        }
    }

    /// The default table of `tone_map` ([`Self::with_defaults`]), built once per process:
    /// about 7 ms each on the machine CI runs on, which the CPU tracer of every frame and every
    /// GPU renderer would otherwise pay again.
    #[must_use]
    pub fn shared(tone_map: ToneMap) -> &'static Self {
        static TABLES: [std::sync::OnceLock<TemperatureLut>; ToneMap::ALL.len()] =
            [const { std::sync::OnceLock::new() }; ToneMap::ALL.len()];
        let index = ToneMap::ALL
            .iter()
            .position(|&t| t == tone_map)
            .unwrap_or_else(|| unreachable!("ToneMap::ALL holds every tone map"));
        TABLES[index].get_or_init(|| Self::with_defaults(tone_map))
    }

    /// The RGBA texels, texel 0 at `t_min`; alpha is always 1.
    #[must_use]
    pub fn texels(&self) -> &[[f32; 4]] {
        self.table.texels()
    }

    /// The lower end of the range in kelvin (texel 0).
    #[must_use]
    pub fn t_min(&self) -> f64 {
        self.table.t_min_k
    }

    /// The upper end of the range in kelvin (texel N − 1).
    #[must_use]
    pub fn t_max(&self) -> f64 {
        self.table.t_max_k
    }

    /// The number of texels N.
    #[must_use]
    pub fn size(&self) -> usize {
        self.table.texels.len()
    }

    /// The tone map the texels were computed with.
    #[must_use]
    pub fn tone_map(&self) -> ToneMap {
        self.tone_map
    }

    /// The temperature in kelvin at the centre of texel `index` (clamped to N − 1):
    /// exp(ln `t_min` + index / (N − 1) · (ln `t_max` − ln `t_min`)), exactly `t_min` and `t_max`
    /// at the ends.
    #[must_use]
    pub fn texel_temperature(&self, index: usize) -> f64 {
        texel_temperature(self.t_min(), self.t_max(), self.size(), index)
    }

    /// The 1D texture coordinate s = (0.5 + u · (N − 1)) / N at which a linearly filtered GPU
    /// texture returns [`Self::sample`]`(temperature_k)`; in [0.5/N, 1 − 0.5/N].
    #[must_use]
    pub fn texture_coordinate(&self, temperature_k: f64) -> f32 {
        let n = self.size() as f64;
        ((0.5 + self.table.normalised(temperature_k) * (n - 1.0)) / n) as f32
    }

    /// The colour of `temperature_k` as a linearly filtered 1D texture returns it (see the module
    /// documentation): texels interpolated linearly in ln T, clamped beyond the range; a
    /// non-finite or non-positive temperature gives texel 0.
    #[must_use]
    pub fn sample(&self, temperature_k: f64) -> [f32; 4] {
        self.table.sample(temperature_k)
    }
}

/// Temperature of texel `index` (clamped to `size − 1`) of a `size`-texel table over
/// `t_min_k ..= t_max_k`, uniform in ln T with the ends exact. `size` is at least 2.
fn texel_temperature(t_min_k: f64, t_max_k: f64, size: usize, index: usize) -> f64 {
    let last = size - 1;
    let index = index.min(last);
    if index == 0 {
        t_min_k
    } else if index == last {
        t_max_k
    } else {
        let u = index as f64 / last as f64;
        (t_min_k.ln() + u * (t_max_k / t_min_k).ln()).exp()
    }
}
