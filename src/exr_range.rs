//! What `srt info` reports of an EXR's pixels: the range of its R, G, B values and of their
//! luminance, how many pixels are brighter than 1.0 and how many are not finite — what someone
//! who measures, re-exposes or tone maps the file needs to know first — and the range of each
//! per-pixel channel `--aov` wrote ([`aov_lines`]).

use std::path::Path;

use anyhow::anyhow;
use srt::engine::AOV_CHANNELS;
use srt_color::XYZ_TO_LINEAR_BT709;

/// Statistics of an EXR's first RGB layer.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelRange {
    /// Number of pixels.
    pub pixels: usize,
    /// Smallest finite R, G and B.
    pub min: [f32; 3],
    /// Largest finite R, G and B.
    pub max: [f32; 3],
    /// Smallest, mean and largest luminance Y of the finite pixels (BT.709 primaries).
    pub luminance: [f64; 3],
    /// Pixels whose luminance is above 1.0.
    pub above_one: usize,
    /// Pixels with a channel that is NaN or infinite.
    pub non_finite: usize,
}

impl PixelRange {
    /// The statistics of `pixels` (linear R, G, B).
    #[must_use]
    pub fn of(pixels: &[[f32; 3]]) -> Self {
        // Y is the middle row of the inverse of Eq. 12's XYZ → linear BT.709 matrix.
        let weights = XYZ_TO_LINEAR_BT709.inverse().row(1);
        let mut range = Self {
            pixels: pixels.len(),
            min: [f32::INFINITY; 3],
            max: [f32::NEG_INFINITY; 3],
            luminance: [f64::INFINITY, 0.0, f64::NEG_INFINITY],
            above_one: 0,
            non_finite: 0,
        };
        let mut sum = 0.0;
        for pixel in pixels {
            if !pixel.iter().all(|c| c.is_finite()) {
                range.non_finite += 1;
                continue;
            }
            for (channel, &value) in pixel.iter().enumerate() {
                range.min[channel] = range.min[channel].min(value);
                range.max[channel] = range.max[channel].max(value);
            }
            let y = weights.dot(glam::DVec3::from_array(pixel.map(f64::from)));
            range.luminance[0] = range.luminance[0].min(y);
            range.luminance[2] = range.luminance[2].max(y);
            sum += y;
            range.above_one += usize::from(y > 1.0);
        }
        let finite = pixels.len() - range.non_finite;
        #[expect(clippy::cast_precision_loss, reason = "a pixel count")]
        let mean = if finite > 0 { sum / finite as f64 } else { 0.0 };
        range.luminance[1] = mean;
        range
    }

    /// Reads the first RGB layer of the EXR at `path`.
    ///
    /// # Errors
    /// A message naming the file when it cannot be read or has no RGB layer.
    pub fn read(path: &Path) -> anyhow::Result<Self> {
        let image = exr::prelude::read_first_rgba_layer_from_file(
            path,
            |size, _| {
                (
                    size.width(),
                    vec![[0.0_f32; 3]; size.width() * size.height()],
                )
            },
            |(width, pixels): &mut (usize, Vec<[f32; 3]>),
             position,
             (r, g, b, _alpha): (f32, f32, f32, f32)| {
                pixels[position.y() * *width + position.x()] = [r, g, b];
            },
        )
        .map_err(|error| anyhow!("cannot read the pixels of {} ({error})", path.display()))?;
        Ok(Self::of(&image.layer_data.channel_data.pixels.1))
    }

    /// The lines `srt info` prints: `key  value` pairs.
    #[must_use]
    pub fn lines(&self) -> Vec<(&'static str, String)> {
        let [y_min, y_mean, y_max] = self.luminance;
        vec![
            (
                "pixel range",
                format!(
                    "R {} to {}, G {} to {}, B {} to {}",
                    self.min[0], self.max[0], self.min[1], self.max[1], self.min[2], self.max[2]
                ),
            ),
            (
                "luminance",
                format!(
                    "{y_min:.6} to {y_max:.6}, mean {y_mean:.6}; {} of {} pixels above 1.0",
                    self.above_one, self.pixels
                ),
            ),
            ("non-finite pixels", self.non_finite.to_string()),
        ]
    }
}

/// One line per [`AOV_CHANNELS`] channel the EXR at `path` holds: its range over the pixels
/// that see an object (`object` ≥ 0), and for `object` how many pixels see one. Empty for an
/// EXR written without `--aov`.
///
/// # Errors
/// A message naming the file when its channels cannot be read.
pub fn aov_lines(path: &Path) -> anyhow::Result<Vec<(String, String)>> {
    use exr::prelude::{FlatSamples, ReadChannels as _, ReadLayers as _};
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|error| anyhow!("cannot read the channels of {} ({error})", path.display()))?;
    let channels = &image.layer_data.channel_data.list;
    let values = |name: &str| -> Option<Vec<f32>> {
        channels
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| match &c.sample_data {
                FlatSamples::F32(v) => v.clone(),
                FlatSamples::F16(v) => v.iter().map(|h| h.to_f32()).collect(),
                #[expect(clippy::cast_precision_loss, reason = "reported, not computed with")]
                FlatSamples::U32(v) => v.iter().map(|&u| u as f32).collect(),
            })
    };
    let Some(object) = values("object") else {
        return Ok(Vec::new());
    };
    let seen: Vec<bool> = object.iter().map(|&o| o >= 0.0).collect();
    let count = seen.iter().filter(|&&s| s).count();
    let mut lines = Vec::new();
    for name in AOV_CHANNELS {
        let Some(channel) = values(name) else {
            continue;
        };
        let (low, high) = channel
            .iter()
            .zip(&seen)
            .filter(|&(_, &s)| s)
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), (&v, _)| {
                (lo.min(v), hi.max(v))
            });
        let value = if name == "object" {
            format!(
                "{low} to {high}; {count} of {} pixels see an object (-1 elsewhere)",
                object.len()
            )
        } else if count == 0 {
            "no pixel sees an object".to_owned()
        } else {
            format!("{low} to {high} where an object is seen")
        };
        lines.push((name.to_owned(), value));
    }
    Ok(lines)
}

#[cfg(test)]
mod tests {
    use super::PixelRange;

    #[test]
    fn ranges_count_bright_and_broken_pixels() {
        let range = PixelRange::of(&[
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [4.0, 2.0, 0.5],
            [f32::NAN, 0.0, 0.0],
        ]);
        assert_eq!(range.pixels, 4);
        assert_eq!(range.non_finite, 1);
        assert_eq!((range.min, range.max), ([0.0; 3], [4.0, 2.0, 1.0]));
        // White has luminance 1 (the weights sum to 1); the orange pixel is brighter.
        let orange = 0.2126 * 4.0 + 0.7152 * 2.0 + 0.0722 * 0.5;
        assert!((range.luminance[0]).abs() < 1e-12);
        // Eq. 12's matrix has four decimals, so its inverse's weights differ from 0.2126… in the fourth.
        assert!(
            (range.luminance[2] - orange).abs() < 1e-3,
            "{:?}",
            range.luminance
        );
        assert!((range.luminance[1] - (1.0 + orange) / 3.0).abs() < 1e-3);
        assert_eq!(range.above_one, 1, "white is not above 1.0, orange is");
    }
}
