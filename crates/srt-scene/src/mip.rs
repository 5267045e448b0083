//! Mip chains of textures: every level a 2×2 box filter of the one above, rounded to 8 bits.
//! The CPU reference and the GPU upload the very same levels, so their filtered texture lookups
//! can agree.

use crate::mesh::Texture;

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
                        for (s, v) in sum.iter_mut().zip(t) {
                            *s += u32::from(v);
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
}
