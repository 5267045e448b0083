//! Fig. 6 of the paper: the colour tables of black-body temperatures 1000–26000 K (horizontal)
//! scaled by a reflection factor f ∈ [0, 1] (vertical), for the luminance tone map (left, the
//! `doppler` effect mode) and the searchlight tone map (right).

use std::path::{Path, PathBuf};

use image::Rgb;
use srt_color::{ToneMap, colour_table};

use crate::plot::{Axes, BLACK, Canvas, WHITE};

/// Temperature range of the paper's Fig. 6, in kelvin.
const RANGE_K: (f64, f64) = (1000.0, 26_000.0);
/// Size of each colour table in pixels.
const TABLE_SIZE: (u32, u32) = (500, 300);

/// Writes `fig6_colour_tables.png` into `out_dir`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let (width, height) = TABLE_SIZE;
    let panel_width = width as f32 + 130.0;
    let mut canvas = Canvas::new((2.0 * panel_width) as u32 + 20, height + 190, WHITE);
    canvas.text_centred(
        canvas.width() as f32 / 2.0,
        10.0,
        19.0,
        BLACK,
        "Colour tables of Planck spectra, 1000 K – 26000 K (Eq. 10–13)",
    );
    let panels = [
        (ToneMap::Luminance, "luminance: XYZ / Y(T)  (doppler mode)"),
        (
            ToneMap::Searchlight,
            "searchlight: XYZ / Y(1500 K), 0.6·log₁₀(C + 1)",
        ),
    ];
    for (k, (tone_map, title)) in panels.into_iter().enumerate() {
        let left = 90.0 + k as f32 * panel_width;
        let top = 90.0;
        draw_panel(&mut canvas, tone_map, (left, top), title)?;
    }
    canvas.text_centred(
        canvas.width() as f32 / 2.0,
        canvas.height() as f32 - 34.0,
        15.0,
        BLACK,
        concat!(
            "Each column is one temperature (linear in T); each row scales the display colour ",
            "by f (C_display = f · C_sRGB, §4.2)."
        ),
    );
    let path = out_dir.join("fig6_colour_tables.png");
    canvas.save(&path)?;
    Ok(vec![path])
}

/// One colour table with its axes, top-left corner of the table at `origin`.
fn draw_panel(
    canvas: &mut Canvas,
    tone_map: ToneMap,
    origin: (f32, f32),
    title: &str,
) -> anyhow::Result<()> {
    let (width, height) = TABLE_SIZE;
    let (w, h) = (width as usize, height as usize);
    let table = colour_table(tone_map, RANGE_K.0, RANGE_K.1, w, h);
    anyhow::ensure!(
        table.len() == w * h,
        "colour table has {} pixels, want {}",
        table.len(),
        w * h
    );
    let (x0, y0) = (origin.0.round() as u32, origin.1.round() as u32);
    let image = canvas.image_mut();
    for (index, pixel) in table.iter().enumerate() {
        let (i, j) = ((index % w) as u32, (index / w) as u32);
        let rgb = pixel.map(|c| srt_color::quantize_8bit(f64::from(c)));
        image.put_pixel(x0 + i, y0 + j, Rgb(rgb));
    }

    // Column i is centred on T = t_min + i · ΔT, row j on f = 1 − j · Δf: let the axes span
    // half a pixel beyond the first and last centres so that ticks land on those centres.
    let dt = (RANGE_K.1 - RANGE_K.0) / (w - 1) as f64;
    let df = 1.0 / (h - 1) as f64;
    let axes = Axes {
        area: (
            x0 as f32,
            y0 as f32,
            (x0 + width) as f32,
            (y0 + height) as f32,
        ),
        x_range: (RANGE_K.0 - 0.5 * dt, RANGE_K.1 + 0.5 * dt),
        y_range: (-0.5 * df, 1.0 + 0.5 * df),
    };
    let x_ticks: Vec<(f64, String)> = [1000.0, 5000.0, 10_000.0, 15_000.0, 20_000.0, 26_000.0]
        .into_iter()
        .map(|t| (t, format!("{t:.0}")))
        .collect();
    let y_ticks: Vec<(f64, String)> = [0.0, 0.25, 0.5, 0.75, 1.0]
        .into_iter()
        .map(|f| (f, format!("{f}")))
        .collect();
    axes.draw(
        canvas,
        &x_ticks,
        &y_ticks,
        "temperature T (K)",
        "reflection factor f",
    );
    canvas.text_centred(
        origin.0 + width as f32 / 2.0,
        origin.1 - 52.0,
        17.0,
        BLACK,
        title,
    );
    Ok(())
}
