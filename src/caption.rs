//! `srt render --caption`: one line burnt into the bottom of the picture saying what it shows —
//! the scene, the observer's time, each object's velocity (or their range of speeds), the
//! picture (`seen`, `measured`, `newtonian`), the effects and the renderer — for a slide or a
//! video. It is drawn into the display colours (the PNG, the video's frames, an EXR's display
//! layer); an EXR's radiance and time channels stay the data they are.

use ab_glyph::{FontRef, PxScale};
use glam::DVec3;
use image::{GrayImage, Luma};
use imageproc::drawing::{draw_text_mut, text_size};
use srt_scene::{Scene, View};

/// How much the band behind the caption darkens the picture (the fraction kept).
const BAND_KEEPS: f64 = 0.35;

/// What a caption says besides the frame's scene: the observer's motion through the world, the
/// picture and the renderer.
pub struct Captioner {
    /// The observer's velocity through the scene's world frame.
    pub observer_beta: DVec3,
    /// The picture drawn.
    pub view: View,
    /// Who drew it, in a word or two ("cpu", "gpu lrt").
    pub renderer: String,
}

impl Captioner {
    /// The caption of `scene` (the frame's scene before its view is applied: its velocities are
    /// the objects') for a `width` × `height` picture, to burn into it a band of rows at a time
    /// ([`Ink::burn_into_rows`]).
    #[must_use]
    pub fn ink_for(&self, scene: &Scene, width: u32, height: u32) -> Ink {
        let text = caption_text(scene, self.observer_beta, self.view, &self.renderer);
        Ink::new(width, height, &text)
    }
}

/// The caption of one frame: `scene` (built, at the frame's time) drawn in `view` by `renderer`
/// ("cpu", "gpu lrt", …), the observer moving with `observer_beta` through the world.
#[must_use]
pub fn caption_text(scene: &Scene, observer_beta: DVec3, view: View, renderer: &str) -> String {
    let mut parts = vec![
        scene.name.clone(),
        format!("time {}", short(scene.observer.time)),
    ];
    if observer_beta != DVec3::ZERO {
        parts.push(format!("observer β {}", vector(observer_beta)));
    }
    if scene.objects.len() <= 3 {
        parts.extend((scene.objects.iter()).map(|object| {
            let beta = object.frame.beta();
            format!("{} {}c {}", object.name, short(beta.length()), vector(beta))
        }));
    } else {
        let speeds = scene
            .objects
            .iter()
            .map(|object| object.frame.beta().length());
        let (slowest, fastest) = speeds.fold((f64::INFINITY, 0.0_f64), |(low, high), speed| {
            (low.min(speed), high.max(speed))
        });
        parts.push(format!(
            "{} objects at |β| {} to {}",
            scene.objects.len(),
            short(slowest),
            short(fastest)
        ));
    }
    parts.push(format!("{} view", view.name()));
    parts.push(scene.effects.name().to_owned());
    parts.push(renderer.to_owned());
    parts.join(" · ")
}

/// A number with at most three decimals, without trailing zeros ("0.95", "5.12", "-3").
fn short(value: f64) -> String {
    let text = format!("{:.3}", value + 0.0);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

/// A vector as "(x, y, z)" with [`short`] components.
fn vector(value: DVec3) -> String {
    format!(
        "({}, {}, {})",
        short(value.x),
        short(value.y),
        short(value.z)
    )
}

/// A caption laid out for one picture size: white letters on a darkened band at the bottom, a
/// thirtieth of the height high, smaller where the line would not fit the width.
pub struct Ink {
    /// The first row of the band.
    first_row: u32,
    /// The letters' coverage of the band, 255 = white ink.
    coverage: GrayImage,
}

impl Ink {
    /// `text` laid out for the bottom of a `width` × `height` picture.
    #[must_use]
    pub fn new(width: u32, height: u32, text: &str) -> Self {
        let font = FontRef::try_from_slice(dejavu::sans::regular())
            .expect("the DejaVu Sans font embedded by the dejavu crate parses");
        let margin = (height / 120).max(2);
        let mut size = (height as f32 / 30.0).clamp(10.0, 64.0);
        let (text_width, _) = text_size(PxScale::from(size), &font, text);
        let room = width.saturating_sub(2 * margin).max(1);
        if text_width > room {
            size *= room as f32 / text_width as f32;
        }
        let band = (size * 1.4).ceil() as u32 + margin;
        let band = band.min(height);
        let mut coverage = GrayImage::new(width, band);
        let top = (band as f32 - size * 1.2).max(0.0) as i32;
        draw_text_mut(
            &mut coverage,
            Luma([255]),
            margin as i32,
            top,
            PxScale::from(size),
            &font,
            text,
        );
        Self {
            first_row: height - band,
            coverage,
        }
    }

    /// Burns the caption into `pixels`, the rows `rows` of the picture (`width` pixels each,
    /// row-major from the top).
    pub fn burn_into_rows(&self, pixels: &mut [DVec3], width: u32, rows: std::ops::Range<u32>) {
        for (row, y) in pixels.chunks_exact_mut(width as usize).zip(rows) {
            let Some(band_row) = y.checked_sub(self.first_row) else {
                continue;
            };
            for (x, pixel) in row.iter_mut().enumerate() {
                let ink = f64::from(self.coverage.get_pixel(x as u32, band_row).0[0]) / 255.0;
                *pixel = *pixel * BAND_KEEPS * (1.0 - ink) + DVec3::ONE * ink;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig4() -> Scene {
        srt_scene::builtin::find_builtin("fig4")
            .expect("fig4")
            .build()
            .expect("builds")
            .0
    }

    #[test]
    fn the_caption_says_scene_time_velocities_view_and_renderer() {
        let text = caption_text(&fig4(), DVec3::ZERO, View::Seen, "cpu");
        assert_eq!(
            text,
            "fig4 · time 5.12 · cube 0.95c (0, 0.95, 0) · seen view · geometry · cpu"
        );
        assert_eq!(short(-0.0), "0");
        assert_eq!(short(1.0 / 3.0), "0.333");
    }

    #[test]
    fn the_caption_is_white_ink_on_a_darkened_band_at_the_bottom() {
        let (width, height) = (320, 90);
        let grey = DVec3::splat(0.5);
        let mut pixels = vec![grey; (width * height) as usize];
        Ink::new(width, height, "fig4 · time 5.12").burn_into_rows(&mut pixels, width, 0..height);
        // Burnt a band of rows at a time, the caption is the same.
        let mut banded = vec![grey; (width * height) as usize];
        for (band, first_row) in banded
            .chunks_mut((width * 16) as usize)
            .zip((0..).step_by(16))
        {
            let rows = first_row..first_row + (band.len() as u32 / width);
            Ink::new(width, height, "fig4 · time 5.12").burn_into_rows(band, width, rows);
        }
        assert_eq!(banded, pixels);
        let (above, band) = pixels.split_at((width * height / 2) as usize);
        assert!(
            above.iter().all(|p| *p == grey),
            "only the bottom band changes"
        );
        assert!(band.iter().any(|p| p.min_element() > 0.9), "white letters");
        assert!(
            band.iter().any(|p| (p.x - 0.5 * BAND_KEEPS).abs() < 1e-12),
            "dark band"
        );
        // A line too long for the width shrinks to fit instead of running off the picture.
        let long = "x".repeat(400);
        let mut pixels = vec![grey; (width * height) as usize];
        Ink::new(width, height, &long).burn_into_rows(&mut pixels, width, 0..height);
        let last_column_inked = pixels
            .chunks_exact(width as usize)
            .any(|row| row[width as usize - 1].min_element() > 0.9);
        assert!(!last_column_inked);
    }
}
