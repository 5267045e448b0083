//! The 24 ColorChecker patches under a Doppler shift (issue 11): the spectral answer (reflectance
//! spectra upsampled by Jakob & Hanika 2019, light reflected with the observer's Doppler factor D,
//! `srt_color::reflected_display_rgb`) beside the paper's shortcut (the display colour of the
//! shifted black body scaled by the patch's grey value, as `srt-trace`'s `shade` does, §4.2).

use std::path::{Path, PathBuf};

use image::Rgb;
use srt_color::spectral::Reflectance;
use srt_color::{
    ToneMap, quantize_8bit, reflected_display_rgb, srgb_coefficient_table, srgb_decode,
};

use crate::plot::{BLACK, Canvas, WHITE};

/// The illuminant: a black body at the correlated colour temperature of D65 (6504 K), at rest
/// relative to the surfaces (D_in = 1).
const LIGHT_TEMPERATURE_K: f64 = 6504.0;
/// The observer's Doppler factors D_out, one row each.
const DOPPLER_FACTORS: [f64; 7] = [0.25, 0.5, 0.8, 1.0, 1.25, 2.0, 4.0];

/// The ColorChecker 24 (X-Rite, after November 2014) as 8-bit sRGB: colour-science 0.4.7's
/// `CCS_COLOURCHECKERS["ColorChecker24 - After November 2014"]` (xyY under D50), adapted to D65
/// with Bradford, clipped to the sRGB gamut (only cyan leaves it) and encoded — the values of
/// `crates/srt-color/tests/data/make_jakob_reference.py`.
const COLORCHECKER_SRGB: [[u8; 3]; 24] = [
    [116, 79, 65],   // dark skin
    [197, 144, 127], // light skin
    [91, 120, 155],  // blue sky
    [91, 108, 64],   // foliage
    [131, 127, 175], // blue flower
    [95, 189, 172],  // bluish green
    [224, 124, 48],  // orange
    [69, 90, 167],   // purplish blue
    [197, 80, 95],   // moderate red
    [93, 58, 104],   // purple
    [156, 187, 58],  // yellow green
    [227, 161, 39],  // orange yellow
    [40, 62, 145],   // blue
    [61, 147, 70],   // green
    [178, 54, 57],   // red
    [236, 200, 15],  // yellow
    [191, 79, 146],  // magenta
    [0, 133, 165],   // cyan
    [241, 242, 235], // white 9.5
    [201, 202, 201], // neutral 8
    [161, 163, 163], // neutral 6.5
    [121, 121, 121], // neutral 5
    [83, 84, 85],    // neutral 3.5
    [50, 50, 50],    // black 2
];

/// Side of one patch and the gap between patches, in pixels.
const PATCH: u32 = 34;
/// Gap between patches in pixels.
const GAP: u32 = 4;
/// Width of the label column in pixels.
const LABEL_WIDTH: f32 = 190.0;
/// Gap between the spectral and the shortcut chart in pixels.
const CHART_GAP: f32 = 40.0;
/// Vertical space of one row of charts in pixels.
const ROW_HEIGHT: f32 = 4.0 * (PATCH + GAP) as f32 + 26.0;

/// Writes `colorchecker_doppler.png` into `out_dir`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let chart_width = 6.0 * (PATCH + GAP) as f32;
    let width = LABEL_WIDTH + 2.0 * chart_width + CHART_GAP + 20.0;
    let top = 100.0;
    let height = top + (DOPPLER_FACTORS.len() + 1) as f32 * ROW_HEIGHT + 60.0;
    let mut canvas = Canvas::new(width as u32, height as u32, WHITE);
    canvas.text_centred(
        width / 2.0,
        12.0,
        19.0,
        BLACK,
        "ColorChecker under a Doppler shift: spectra vs. the paper's shortcut",
    );
    let left = (LABEL_WIDTH, LABEL_WIDTH + chart_width + CHART_GAP);
    canvas.text_centred(
        left.0 + chart_width / 2.0,
        top - 34.0,
        15.0,
        BLACK,
        "spectral (Jakob–Hanika)",
    );
    canvas.text_centred(
        left.1 + chart_width / 2.0,
        top - 34.0,
        15.0,
        BLACK,
        "shortcut ½(G+1)·C_sRGB(D·T)",
    );

    let published = COLORCHECKER_SRGB.map(Rgb);
    draw_chart(&mut canvas, (left.0, top), &published);
    canvas.text_right(
        LABEL_WIDTH - 14.0,
        top + 50.0,
        15.0,
        BLACK,
        "published sRGB",
    );

    let table = srgb_coefficient_table();
    for (row, &d) in DOPPLER_FACTORS.iter().enumerate() {
        let y = top + (row + 1) as f32 * ROW_HEIGHT;
        let mut spectral = [Rgb([0, 0, 0]); 24];
        let mut shortcut = [Rgb([0, 0, 0]); 24];
        let light = ToneMap::Luminance.display_rgb(d * LIGHT_TEMPERATURE_K);
        for (k, code) in COLORCHECKER_SRGB.iter().enumerate() {
            let encoded = code.map(|c| f64::from(c) / 255.0);
            let linear = glam::DVec3::from_array(encoded.map(srgb_decode));
            let reflectance = Reflectance::new(table.lookup(linear)?);
            let rgb = reflected_display_rgb(
                ToneMap::Luminance,
                &reflectance,
                LIGHT_TEMPERATURE_K,
                1.0,
                d,
                1.0,
            )?;
            spectral[k] = Rgb(rgb.to_array().map(quantize_8bit));
            // srt-trace's shade(): f_ar = ½(G + 1) with G = 0.3R + 0.59G + 0.11B, full light.
            let grey = 0.3 * encoded[0] + 0.59 * encoded[1] + 0.11 * encoded[2];
            let f_ar = 0.5 * (grey + 1.0);
            shortcut[k] = Rgb((f_ar * light).to_array().map(quantize_8bit));
        }
        draw_chart(&mut canvas, (left.0, y), &spectral);
        draw_chart(&mut canvas, (left.1, y), &shortcut);
        canvas.text_right(
            LABEL_WIDTH - 14.0,
            y + 40.0,
            16.0,
            BLACK,
            &format!("D = {d}"),
        );
        let apparent = d * LIGHT_TEMPERATURE_K;
        canvas.text_right(
            LABEL_WIDTH - 14.0,
            y + 64.0,
            13.0,
            BLACK,
            &format!("D·T = {apparent:.0} K"),
        );
    }
    canvas.text_centred(
        width / 2.0,
        height - 44.0,
        13.0,
        BLACK,
        "Black body 6504 K at rest with the chart; the observer sees the chart with Doppler factor D.",
    );
    canvas.text_centred(
        width / 2.0,
        height - 26.0,
        13.0,
        BLACK,
        "Luminance tone map (doppler mode). Outside 360–830 nm reflectances hold their edge values.",
    );
    let path = out_dir.join("colorchecker_doppler.png");
    canvas.save(&path)?;
    Ok(vec![path])
}

/// Draws 24 patches as the chart's 4 rows of 6, top-left corner at `origin`.
fn draw_chart(canvas: &mut Canvas, origin: (f32, f32), patches: &[Rgb<u8>; 24]) {
    for (k, &colour) in patches.iter().enumerate() {
        let (column, row) = ((k % 6) as u32, (k / 6) as u32);
        let x = origin.0 as i32 + (column * (PATCH + GAP)) as i32;
        let y = origin.1 as i32 + (row * (PATCH + GAP)) as i32;
        canvas.fill_rect(x, y, PATCH, PATCH, colour);
    }
}
