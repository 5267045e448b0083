//! A small drawing surface for the documentation figures: anti-aliased lines, markers, text
//! (DejaVu Sans, embedded by the `dejavu` crate) and plot axes, on top of `image` + `imageproc`.

use std::path::Path;

use ab_glyph::FontRef;
use anyhow::Context as _;
use image::{Rgb, RgbImage};
use imageproc::drawing::{
    draw_antialiased_line_segment_mut, draw_filled_circle_mut, draw_filled_rect_mut,
    draw_hollow_rect_mut, draw_text_mut, text_size,
};
use imageproc::pixelops::interpolate;
use imageproc::rect::Rect;

/// Black, for axes and text.
pub const BLACK: Rgb<u8> = Rgb([0, 0, 0]);
/// White, the usual background.
pub const WHITE: Rgb<u8> = Rgb([255, 255, 255]);
/// Light grey, for grid lines and guides.
pub const GREY: Rgb<u8> = Rgb([190, 190, 190]);

/// An RGB image with drawing helpers and an embedded font.
pub struct Canvas {
    image: RgbImage,
    font: FontRef<'static>,
}

impl Canvas {
    /// A `width` × `height` canvas filled with `background`.
    pub fn new(width: u32, height: u32, background: Rgb<u8>) -> Self {
        let font = FontRef::try_from_slice(dejavu::sans::regular())
            .expect("the DejaVu Sans font embedded by the dejavu crate parses");
        Self {
            image: RgbImage::from_pixel(width, height, background),
            font,
        }
    }

    /// The underlying image, for pixel-level drawing.
    pub fn image_mut(&mut self) -> &mut RgbImage {
        &mut self.image
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.image.width()
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.image.height()
    }

    /// An anti-aliased line `thickness` pixels wide (drawn as parallel one-pixel lines).
    pub fn line(&mut self, a: (f32, f32), b: (f32, f32), thickness: f32, color: Rgb<u8>) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let length = (dx * dx + dy * dy).sqrt().max(1e-6);
        let (nx, ny) = (-dy / length, dx / length);
        let strands = thickness.max(1.0).round() as i32;
        for k in 0..strands {
            let o = k as f32 - (strands - 1) as f32 / 2.0;
            let p = ((a.0 + o * nx).round() as i32, (a.1 + o * ny).round() as i32);
            let q = ((b.0 + o * nx).round() as i32, (b.1 + o * ny).round() as i32);
            draw_antialiased_line_segment_mut(&mut self.image, p, q, color, interpolate);
        }
    }

    /// A polyline through `points`.
    pub fn polyline(&mut self, points: &[(f32, f32)], thickness: f32, color: Rgb<u8>) {
        for pair in points.windows(2) {
            self.line(pair[0], pair[1], thickness, color);
        }
    }

    /// A closed polygon outline.
    pub fn polygon_outline(&mut self, points: &[(f32, f32)], thickness: f32, color: Rgb<u8>) {
        self.polyline(points, thickness, color);
        if let (Some(&first), Some(&last)) = (points.first(), points.last()) {
            self.line(last, first, thickness, color);
        }
    }

    /// A filled disc marker.
    pub fn dot(&mut self, centre: (f32, f32), radius: i32, color: Rgb<u8>) {
        draw_filled_circle_mut(
            &mut self.image,
            (centre.0.round() as i32, centre.1.round() as i32),
            radius,
            color,
        );
    }

    /// A filled axis-aligned rectangle.
    pub fn fill_rect(&mut self, x: i32, y: i32, width: u32, height: u32, color: Rgb<u8>) {
        draw_filled_rect_mut(
            &mut self.image,
            Rect::at(x, y).of_size(width, height),
            color,
        );
    }

    /// An axis-aligned rectangle outline.
    pub fn rect_outline(&mut self, x: i32, y: i32, width: u32, height: u32, color: Rgb<u8>) {
        draw_hollow_rect_mut(
            &mut self.image,
            Rect::at(x, y).of_size(width, height),
            color,
        );
    }

    /// Text with its top-left corner at (x, y), `size` pixels high.
    pub fn text(&mut self, x: f32, y: f32, size: f32, color: Rgb<u8>, text: &str) {
        draw_text_mut(
            &mut self.image,
            color,
            x as i32,
            y as i32,
            size,
            &self.font,
            text,
        );
    }

    /// Text centred horizontally on `x`.
    pub fn text_centred(&mut self, x: f32, y: f32, size: f32, color: Rgb<u8>, text: &str) {
        let (w, _) = text_size(size, &self.font, text);
        self.text(x - w as f32 / 2.0, y, size, color, text);
    }

    /// Text right-aligned at `x`.
    pub fn text_right(&mut self, x: f32, y: f32, size: f32, color: Rgb<u8>, text: &str) {
        let (w, _) = text_size(size, &self.font, text);
        self.text(x - w as f32, y, size, color, text);
    }

    /// Writes the canvas as a PNG, creating parent folders.
    pub fn save(&self, path: &Path) -> anyhow::Result<()> {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create folder {}", parent.display()))?;
        }
        self.image
            .save(path)
            .with_context(|| format!("cannot write {}", path.display()))
    }
}

/// A plot area: maps data coordinates to pixels inside a rectangle of the canvas.
#[derive(Clone, Copy, Debug)]
pub struct Axes {
    /// Left, top, right, bottom edges of the plot area in pixels.
    pub area: (f32, f32, f32, f32),
    /// Data range shown horizontally.
    pub x_range: (f64, f64),
    /// Data range shown vertically (first value at the bottom).
    pub y_range: (f64, f64),
}

impl Axes {
    /// Pixel position of the data point (x, y).
    pub fn to_px(self, x: f64, y: f64) -> (f32, f32) {
        let (l, t, r, b) = self.area;
        let u = (x - self.x_range.0) / (self.x_range.1 - self.x_range.0);
        let v = (y - self.y_range.0) / (self.y_range.1 - self.y_range.0);
        (l + (r - l) * u as f32, b - (b - t) * v as f32)
    }

    /// Draws the frame, tick marks with labels and the axis titles.
    pub fn draw(
        &self,
        canvas: &mut Canvas,
        x_ticks: &[(f64, String)],
        y_ticks: &[(f64, String)],
        x_title: &str,
        y_title: &str,
    ) {
        let (l, t, r, b) = self.area;
        canvas.polygon_outline(&[(l, t), (r, t), (r, b), (l, b)], 1.0, BLACK);
        for (x, label) in x_ticks {
            let (px, _) = self.to_px(*x, self.y_range.0);
            canvas.line((px, b), (px, b + 6.0), 1.0, BLACK);
            canvas.text_centred(px, b + 9.0, 15.0, BLACK, label);
        }
        for (y, label) in y_ticks {
            let (_, py) = self.to_px(self.x_range.0, *y);
            canvas.line((l - 6.0, py), (l, py), 1.0, BLACK);
            canvas.text_right(l - 9.0, py - 8.0, 15.0, BLACK, label);
        }
        canvas.text_centred((l + r) / 2.0, b + 30.0, 17.0, BLACK, x_title);
        canvas.text(l, t - 26.0, 17.0, BLACK, y_title);
    }
}
