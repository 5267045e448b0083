//! Comparing another renderer's image with the reference: the fraction of pixels that differ by
//! more than a tolerance in any channel, not counting pixels near a silhouette edge of the
//! reference (where a pixel-centre sample may legitimately fall on either side of an edge).
//! Display colours are compared in 8-bit steps ([`compare`]), radiance relative to the
//! reference's brightness ([`compare_radiance`]), what pixels see of time channel by channel
//! ([`compare_seen`]).

use glam::DVec3;

use crate::render::RenderedImage;
use crate::seen::SeenEvent;

/// Result of [`compare`] (differences in 1/255 steps) or [`compare_radiance`] (relative
/// differences).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mismatch<D = u8> {
    /// Pixels compared (all minus those near silhouettes).
    pub compared: usize,
    /// Compared pixels differing by more than the tolerance.
    pub differing: usize,
    /// Largest difference seen among compared pixels, in the comparison's unit.
    pub max_difference: D,
}

impl<D> Mismatch<D> {
    /// `differing / compared` (0 when nothing was compared).
    #[must_use]
    pub fn fraction(&self) -> f64 {
        if self.compared == 0 {
            0.0
        } else {
            self.differing as f64 / self.compared as f64
        }
    }
}

/// Whether pixel (x, y) lies within `margin` pixels (Chebyshev distance) of a pixel whose
/// coverage differs from its own, i.e. near a silhouette edge of the reference.
#[must_use]
pub fn near_silhouette(reference: &RenderedImage, x: u32, y: u32, margin: u32) -> bool {
    let (w, h) = (reference.width, reference.height);
    let own = reference.coverage[(y * w + x) as usize];
    let (x0, x1) = (x.saturating_sub(margin), (x + margin).min(w - 1));
    let (y0, y1) = (y.saturating_sub(margin), (y + margin).min(h - 1));
    (y0..=y1).any(|yy| (x0..=x1).any(|xx| reference.coverage[(yy * w + xx) as usize] != own))
}

/// Compares `candidate` (8-bit RGB, same size, row-major) with the reference image: a pixel
/// differs when any channel is more than `tolerance` steps of 1/255 away; pixels within
/// `edge_margin` pixels of a silhouette of the reference are skipped.
///
/// # Panics
/// If the sizes differ.
#[must_use]
pub fn compare(
    reference: &RenderedImage,
    candidate: &[[u8; 3]],
    tolerance: u8,
    edge_margin: u32,
) -> Mismatch {
    assert_eq!(
        candidate.len(),
        reference.pixels.len(),
        "images of different sizes"
    );
    let reference_rgb = reference.to_rgb8();
    count_differing(reference, edge_margin, tolerance, |i| {
        (0..3)
            .map(|c| reference_rgb[i][c].abs_diff(candidate[i][c]))
            .max()
            .unwrap_or(0)
    })
}

/// Compares the radiance `candidate` (same size, row-major) with the reference's radiance
/// ([`crate::Tracer::render_radiance`]): a pixel's difference is its largest channel difference
/// over the reference pixel's largest channel magnitude, at least `floor` (so that near-black
/// pixels are compared absolutely); it differs above `tolerance`. Pixels within `edge_margin`
/// pixels of a silhouette of the reference are skipped.
///
/// # Panics
/// If the sizes differ.
#[must_use]
pub fn compare_radiance(
    reference: &RenderedImage,
    candidate: &[DVec3],
    tolerance: f64,
    floor: f64,
    edge_margin: u32,
) -> Mismatch<f64> {
    assert_eq!(
        candidate.len(),
        reference.pixels.len(),
        "images of different sizes"
    );
    count_differing(reference, edge_margin, tolerance, |i| {
        let (expected, actual) = (reference.pixels[i], candidate[i]);
        // A non-finite value is as far off as can be.
        if actual.is_finite() {
            (actual - expected).abs().max_element() / expected.abs().max_element().max(floor)
        } else {
            f64::INFINITY
        }
    })
}

/// Compares what each pixel sees of time, `candidate` (per pixel emission ct, proper time,
/// distance, Doppler factor and object index, −1 for none, as srt's `--aov` channels), with the
/// reference's [`SeenEvent`]s (`events`, row-major, of the image `reference`): a pixel's
/// difference is infinite where the object differs, else its largest channel difference over
/// the channel's magnitude, at least 1; it differs above `tolerance`. Pixels within
/// `edge_margin` of a silhouette of `reference` are skipped.
///
/// # Panics
/// If the sizes differ.
#[must_use]
pub fn compare_seen(
    reference: &RenderedImage,
    events: &[Option<SeenEvent>],
    candidate: &[[f32; 5]],
    tolerance: f64,
    edge_margin: u32,
) -> Mismatch<f64> {
    assert!(
        events.len() == reference.pixels.len() && candidate.len() == events.len(),
        "images of different sizes"
    );
    count_differing(reference, edge_margin, tolerance, |i| {
        let actual = candidate[i].map(f64::from);
        match events[i] {
            None if actual[4] < 0.0 => 0.0,
            Some(event) if actual[4] == event.object as f64 => [
                event.emission_ct,
                event.proper_time,
                event.distance,
                event.doppler,
            ]
            .iter()
            .zip(actual)
            .map(|(expected, value)| (value - expected).abs() / expected.abs().max(1.0))
            .fold(0.0, f64::max),
            _ => f64::INFINITY,
        }
    })
}

/// The pixels of `reference` not within `edge_margin` of a silhouette, compared by
/// `difference` (of pixel index) against `tolerance`.
fn count_differing<D: PartialOrd + Default + Copy>(
    reference: &RenderedImage,
    edge_margin: u32,
    tolerance: D,
    difference: impl Fn(usize) -> D,
) -> Mismatch<D> {
    let mut result = Mismatch {
        compared: 0,
        differing: 0,
        max_difference: D::default(),
    };
    for y in 0..reference.height {
        for x in 0..reference.width {
            if near_silhouette(reference, x, y, edge_margin) {
                continue;
            }
            let d = difference((y * reference.width + x) as usize);
            result.compared += 1;
            if d > result.max_difference {
                result.max_difference = d;
            }
            if d > tolerance {
                result.differing += 1;
            }
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn image(coverage: Vec<u32>, width: u32) -> RenderedImage {
        let height = coverage.len() as u32 / width;
        let pixels = coverage
            .iter()
            .map(|&c| DVec3::splat(f64::from(c) * 0.5))
            .collect();
        RenderedImage {
            width,
            height,
            pixels,
            coverage,
        }
    }

    #[test]
    fn radiance_differs_relative_to_the_reference_above_its_floor() {
        // 4×1: background, background, object, object; radiance 0, 0, 0.5, 0.5.
        let reference = image(vec![0, 0, 1, 1], 4);
        let mut candidate = reference.pixels.clone();
        // 1 % of a bright pixel is within 2 %; 3 % is not.
        candidate[3] = DVec3::splat(0.5 * 1.01);
        let close = compare_radiance(&reference, &candidate, 0.02, 0.01, 0);
        assert_eq!((close.compared, close.differing), (4, 0));
        assert!((close.max_difference - 0.01).abs() < 1e-12);
        candidate[3] = DVec3::new(0.5, 0.5 * 1.03, 0.5);
        assert_eq!(
            compare_radiance(&reference, &candidate, 0.02, 0.01, 0).differing,
            1
        );
        // On black, the floor makes it absolute: 1e-4 is 1 % of the floor 0.01.
        candidate[3] = reference.pixels[3];
        candidate[0] = DVec3::splat(1e-4);
        assert_eq!(
            compare_radiance(&reference, &candidate, 0.02, 0.01, 0).differing,
            0
        );
        candidate[0] = DVec3::new(f64::NAN, 0.0, 0.0);
        let nan = compare_radiance(&reference, &candidate, 0.02, 0.01, 0);
        assert_eq!(nan.differing, 1);
        assert!(nan.max_difference.is_infinite());
        // Pixels beside the silhouette are skipped.
        assert_eq!(
            compare_radiance(&reference, &candidate, 0.02, 0.01, 1).compared,
            2
        );
    }

    #[test]
    fn skips_silhouette_pixels_and_counts_differences() {
        // 4×1: background, background, object, object.
        let reference = image(vec![0, 0, 1, 1], 4);
        let mut candidate = reference.to_rgb8();
        candidate[0] = [200, 0, 0];
        let result = compare(&reference, &candidate, 2, 1);
        // Pixels 1 and 2 touch the edge; 0 and 3 are compared; 0 differs.
        assert_eq!(result.compared, 2);
        assert_eq!(result.differing, 1);
        assert_eq!(result.max_difference, 200);
        assert!((result.fraction() - 0.5).abs() < 1e-12);
        // Within tolerance is not a difference.
        candidate[0] = [2, 0, 0];
        assert_eq!(compare(&reference, &candidate, 2, 1).differing, 0);
    }
}
