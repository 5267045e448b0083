//! Mipmapped textures and trilinear filtering with explicit derivatives, defined the way GPU
//! hardware filters an `Rgba8Unorm` texture with `textureSampleGrad` (repeat addressing, texel
//! centres at half-integers, LOD = log₂ of the longer footprint axis), so that the GPU renderer
//! can upload these very mip levels and agree with the CPU reference.

use glam::{DVec2, DVec4};
use srt_scene::Texture;

/// One mip level: RGBA8 texels, row 0 at v = 0.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MipLevel {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Row-major texels.
    pub texels: Vec<[u8; 4]>,
}

impl MipLevel {
    fn texel(&self, x: i64, y: i64) -> DVec4 {
        let xi = x.rem_euclid(i64::from(self.width)) as usize;
        let yi = y.rem_euclid(i64::from(self.height)) as usize;
        let t = self.texels[yi * self.width as usize + xi];
        DVec4::new(
            f64::from(t[0]),
            f64::from(t[1]),
            f64::from(t[2]),
            f64::from(t[3]),
        ) / 255.0
    }

    /// Bilinear sample with repeat addressing.
    fn bilinear(&self, uv: DVec2) -> DVec4 {
        let x = uv.x * f64::from(self.width) - 0.5;
        let y = uv.y * f64::from(self.height) - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (xi, yi) = (x0 as i64, y0 as i64);
        let top = self.texel(xi, yi).lerp(self.texel(xi + 1, yi), fx);
        let bottom = self.texel(xi, yi + 1).lerp(self.texel(xi + 1, yi + 1), fx);
        top.lerp(bottom, fy)
    }

    /// The next smaller level: 2×2 box filter (a lone odd row or column is folded into the
    /// last output texel's average), rounded to 8 bits.
    fn downsample(&self) -> Self {
        let width = (self.width / 2).max(1);
        let height = (self.height / 2).max(1);
        let mut texels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                let xs = source_span(x, width, self.width);
                let ys = source_span(y, height, self.height);
                let mut sum = [0u32; 4];
                let mut count = 0;
                for sy in ys.clone() {
                    for sx in xs.clone() {
                        let t = self.texels[(sy * self.width + sx) as usize];
                        for c in 0..4 {
                            sum[c] += u32::from(t[c]);
                        }
                        count += 1;
                    }
                }
                texels.push(sum.map(|s| ((s + count / 2) / count) as u8));
            }
        }
        Self {
            width,
            height,
            texels,
        }
    }
}

/// Source texels that fold into output texel `i` of `out` when halving `size`.
fn source_span(i: u32, out: u32, size: u32) -> std::ops::Range<u32> {
    let start = (2 * i).min(size - 1);
    let end = if i + 1 == out {
        size
    } else {
        (2 * i + 2).min(size)
    };
    start..end.max(start + 1)
}

/// A texture with its full mip chain down to 1×1.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MipChain {
    levels: Vec<MipLevel>,
}

impl MipChain {
    /// Builds the chain from a texture (level 0 is the texture itself).
    ///
    /// # Panics
    /// If the texture's texel count does not match its size or it is empty.
    #[must_use]
    pub fn new(texture: &Texture) -> Self {
        assert!(
            texture.width > 0 && texture.height > 0,
            "texture {} is empty",
            texture.source
        );
        assert_eq!(
            texture.texels.len(),
            (texture.width * texture.height) as usize
        );
        let mut levels = vec![MipLevel {
            width: texture.width,
            height: texture.height,
            texels: texture.texels.clone(),
        }];
        while let Some(last) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
            levels.push(last.downsample());
        }
        Self { levels }
    }

    /// The mip levels, largest first.
    #[must_use]
    pub fn levels(&self) -> &[MipLevel] {
        &self.levels
    }

    /// Trilinear sample at `uv` with screen-space derivatives `ddx`, `ddy` of the texture
    /// coordinates per pixel: LOD λ = log₂ max(‖ddx·size‖, ‖ddy·size‖), clamped to the chain;
    /// bilinear on levels ⌊λ⌋ and ⌊λ⌋+1, blended linearly. RGBA in [0, 1].
    #[must_use]
    pub fn sample(&self, uv: DVec2, ddx: DVec2, ddy: DVec2) -> DVec4 {
        let base = &self.levels[0];
        let size = DVec2::new(f64::from(base.width), f64::from(base.height));
        let rho = (ddx * size).length().max((ddy * size).length());
        let max_level = (self.levels.len() - 1) as f64;
        let lod = if rho > 0.0 && rho.is_finite() {
            rho.log2().clamp(0.0, max_level)
        } else {
            0.0
        };
        let lower = lod.floor();
        let fraction = lod - lower;
        let a = self.levels[lower as usize].bilinear(uv);
        if fraction == 0.0 {
            return a;
        }
        a.lerp(self.levels[lower as usize + 1].bilinear(uv), fraction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texture(width: u32, height: u32, f: impl Fn(u32, u32) -> [u8; 4]) -> Texture {
        let texels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Texture {
            width,
            height,
            texels,
            source: "test".into(),
        }
    }

    #[test]
    fn chain_goes_down_to_one_texel_and_averages() {
        let chain = MipChain::new(&texture(8, 4, |x, _| {
            if x % 2 == 0 { [0, 0, 0, 255] } else { [255; 4] }
        }));
        let sizes: Vec<_> = chain.levels().iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, vec![(8, 4), (4, 2), (2, 1), (1, 1)]);
        assert_eq!(chain.levels()[1].texels[0], [128, 128, 128, 255]);
    }

    #[test]
    fn odd_sizes_fold_the_last_row() {
        let chain = MipChain::new(&texture(3, 3, |x, y| [(x * 10 + y) as u8, 0, 0, 255]));
        assert_eq!((chain.levels()[1].width, chain.levels()[1].height), (1, 1));
        // Average of all nine values 0,1,2,10,11,12,20,21,22 = 11.
        assert_eq!(chain.levels()[1].texels[0][0], 11);
    }

    #[test]
    fn texel_centres_are_exact_and_minification_blurs() {
        let chain = MipChain::new(&texture(4, 4, |x, y| {
            if (x + y) % 2 == 0 {
                [255; 4]
            } else {
                [0, 0, 0, 255]
            }
        }));
        let centre = DVec2::new(0.125, 0.125);
        let tiny = DVec2::new(1e-4, 0.0);
        assert!((chain.sample(centre, tiny, DVec2::new(0.0, 1e-4)).x - 1.0).abs() < 1e-12);
        // One pixel covering 4 texels: level 2 (1×1) is uniform grey.
        let big = DVec2::new(1.0, 0.0);
        assert!((chain.sample(centre, big, DVec2::new(0.0, 1.0)).x - 128.0 / 255.0).abs() < 1e-12);
    }
}
