//! Trilinear filtering of mipmapped textures with explicit derivatives (repeat addressing, texel
//! centres at half-integers, LOD = log₂ of the longer footprint axis), the way a GPU's
//! `textureSampleGrad` is specified. The GPU mirrors it in `shaders/surface.wgsl`
//! (`sample_part_texture`) with `textureLoad` rather than the sampler hardware, whose level of
//! detail and weights are implementation-defined. The mip levels come from
//! [`srt_scene::mip::MipChain`], which the GPU uploads unchanged.

use glam::{DVec2, DVec4};
use srt_scene::mip::{MipChain, MipLevel};

/// Texel (`x`, `y`) of frame `frame` of `level`, wrapped within the frame (repeat addressing).
fn texel(level: &MipLevel, frame: u32, x: i64, y: i64) -> DVec4 {
    let xi = x.rem_euclid(i64::from(level.width)) as usize;
    let yi = y.rem_euclid(i64::from(level.frame_height)) as usize
        + (frame * level.frame_height) as usize;
    let t = level.texels[yi * level.width as usize + xi];
    DVec4::new(
        f64::from(t[0]),
        f64::from(t[1]),
        f64::from(t[2]),
        f64::from(t[3]),
    ) / 255.0
}

/// Bilinear sample of frame `frame` of one level with repeat addressing.
fn bilinear(level: &MipLevel, frame: u32, uv: DVec2) -> DVec4 {
    let x = uv.x * f64::from(level.width) - 0.5;
    let y = uv.y * f64::from(level.frame_height) - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (xi, yi) = (x0 as i64, y0 as i64);
    let at = |x, y| texel(level, frame, x, y);
    let top = at(xi, yi).lerp(at(xi + 1, yi), fx);
    let bottom = at(xi, yi + 1).lerp(at(xi + 1, yi + 1), fx);
    top.lerp(bottom, fy)
}

/// Trilinear sample of frame `frame` (0 for a still image) at `uv` with screen-space derivatives
/// `ddx`, `ddy` of the texture coordinates per pixel: LOD λ = log₂ max(‖ddx·size‖, ‖ddy·size‖)
/// (the frame's size), clamped to the chain; bilinear on levels ⌊λ⌋ and ⌊λ⌋+1, blended
/// linearly. RGBA in [0, 1].
#[must_use]
pub fn sample_trilinear(chain: &MipChain, frame: u32, uv: DVec2, ddx: DVec2, ddy: DVec2) -> DVec4 {
    let levels = chain.levels();
    let size = DVec2::new(
        f64::from(levels[0].width),
        f64::from(levels[0].frame_height),
    );
    let rho = (ddx * size).length().max((ddy * size).length());
    let max_level = (levels.len() - 1) as f64;
    let lod = if rho > 0.0 && rho.is_finite() {
        rho.log2().clamp(0.0, max_level)
    } else {
        0.0
    };
    let lower = lod.floor();
    let fraction = lod - lower;
    let a = bilinear(&levels[lower as usize], frame, uv);
    if fraction == 0.0 {
        return a;
    }
    a.lerp(bilinear(&levels[lower as usize + 1], frame, uv), fraction)
}

#[cfg(test)]
mod tests {
    use super::*;
    use srt_scene::Texture;

    #[test]
    fn texel_centres_are_exact_and_minification_blurs() {
        let texels = (0..16u32)
            .map(|i| {
                if (i % 4 + i / 4) % 2 == 0 {
                    [255; 4]
                } else {
                    [0, 0, 0, 255]
                }
            })
            .collect();
        let chain = MipChain::new(&Texture::still(4, 4, texels, "test".into()));
        let centre = DVec2::new(0.125, 0.125);
        let tiny = 1e-4;
        let sharp = sample_trilinear(
            &chain,
            0,
            centre,
            DVec2::new(tiny, 0.0),
            DVec2::new(0.0, tiny),
        );
        assert!((sharp.x - 1.0).abs() < 1e-12);
        // One pixel covering 4×4 texels: level 2 (1×1) is uniform grey.
        let blurred = sample_trilinear(&chain, 0, centre, DVec2::X, DVec2::Y);
        assert!((blurred.x - 128.0 / 255.0).abs() < 1e-12);
    }
}
