//! Mip chains of textures: every level a 2×2 box filter of the one above, rounded to 8 bits.
//! The CPU reference and the GPU upload the very same levels, so their filtered texture lookups
//! can agree. A flipbook's frames are filtered each on its own and stacked again in every
//! level, padded to the height a GPU texture of the stacked size has at that level.

use crate::mesh::Texture;

/// One mip level: RGBA8 texels, row 0 at v = 0; for a flipbook its frames one below the other,
/// each `frame_height` rows, then rows of padding up to `height`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MipLevel {
    /// Width in texels.
    pub width: u32,
    /// Height in texels (all frames and the padding).
    pub height: u32,
    /// Height of one frame in texels (`height` for a still image).
    pub frame_height: u32,
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
            frame_height: height,
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
    /// Builds the chain from a texture (level 0 is the texture itself), down to 1×1 frames.
    ///
    /// # Panics
    /// If the texture's texel count does not match its size, it is empty, or its height is not
    /// a multiple of its frame count.
    #[must_use]
    pub fn new(texture: &Texture) -> Self {
        assert!(
            texture.width > 0 && texture.height > 0 && texture.frames > 0,
            "texture {} is empty",
            texture.source
        );
        assert_eq!(
            texture.texels.len(),
            (texture.width * texture.height) as usize
        );
        assert_eq!(texture.height % texture.frames, 0, "{}", texture.source);
        let frame_height = texture.height / texture.frames;
        let frame_texels = (texture.width * frame_height) as usize;
        let frames: Vec<Vec<MipLevel>> = texture
            .texels
            .chunks(frame_texels)
            .map(|texels| {
                let mut levels = vec![MipLevel {
                    width: texture.width,
                    height: frame_height,
                    frame_height,
                    texels: texels.to_vec(),
                }];
                while let Some(last) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
                    levels.push(last.downsample());
                }
                levels
            })
            .collect();
        let levels = (0..frames[0].len())
            .map(|level| {
                let first = &frames[0][level];
                // A GPU texture of the stacked size has at least the stacked rows at this level.
                let height = (texture.height >> level).max(1);
                let mut texels: Vec<[u8; 4]> = frames
                    .iter()
                    .flat_map(|f| f[level].texels.iter().copied())
                    .collect();
                texels.resize((first.width * height) as usize, [0; 4]);
                MipLevel {
                    width: first.width,
                    height,
                    frame_height: first.height,
                    texels,
                }
            })
            .collect();
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
        Texture::still(width, height, texels, "test".into())
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
    fn a_flipbook_filters_each_frame_alone_and_pads_to_the_stacked_size() {
        let first = texture(3, 3, |x, y| [(x * 10 + y) as u8, 0, 0, 255]);
        let second = texture(3, 3, |_, _| [200, 0, 0, 255]);
        let book = crate::textures::flipbook(&[first, second], 2.0, "book".into()).unwrap();
        let chain = MipChain::new(&book);
        let shape: Vec<_> = chain
            .levels()
            .iter()
            .map(|l| (l.width, l.height, l.frame_height))
            .collect();
        // Level 1: two 1×1 frames, padded to the 3 rows a 3×6 texture has there.
        assert_eq!(shape, vec![(3, 6, 3), (1, 3, 1)]);
        let reds: Vec<u8> = chain.levels()[1].texels.iter().map(|t| t[0]).collect();
        assert_eq!(reds, vec![11, 200, 0]);
        assert_eq!(book.frame_at(0.49), 0);
        assert_eq!(book.frame_at(0.5), 1);
        assert_eq!(book.frame_at(1.2), 0);
        assert_eq!(book.frame_at(-0.2), 1);
        assert_eq!(book.frame_at(f64::NAN), 0);
    }
}
