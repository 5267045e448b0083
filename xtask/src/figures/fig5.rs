//! Fig. 5 of the paper: the Planck spectrum of a 6000 K black body and its Doppler-shifted
//! versions for a source approaching or receding at 0.2c (D = √(3/2) and 1/√(3/2); the paper's
//! text misprints them as √3/2). The visible band is shaded with the colours of the spectrum.

use std::path::{Path, PathBuf};

use glam::DVec3;
use image::Rgb;
use srt_color::{cie_1931, planck_radiance, srgb_encode, xyz_to_linear_rgb};
use srt_physics::doppler_factor;

use crate::plot::{Axes, BLACK, Canvas, GREY, WHITE};

/// Temperature of the black body at rest, in kelvin.
const REST_TEMPERATURE_K: f64 = 6000.0;
/// Speed of the source relative to the observer, in units of c.
const SPEED: f64 = 0.2;
/// Plotted wavelength range in nm.
const LAMBDA_RANGE_NM: (f64, f64) = (0.0, 2500.0);
/// Visible band shaded in the background, in nm.
const VISIBLE_NM: (f64, f64) = (380.0, 780.0);
/// Vertical unit: 1 kW·sr⁻¹·m⁻²·nm⁻¹ = 10¹² W·sr⁻¹·m⁻³.
const RADIANCE_UNIT: f64 = 1e12;

/// Writes `fig5_doppler_spectra.png` into `out_dir`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    // Light travels from the source towards the observer along −x; the source moves along ∓x.
    let towards_observer = DVec3::NEG_X;
    let approaching = doppler_factor(DVec3::new(-SPEED, 0.0, 0.0), towards_observer);
    let receding = doppler_factor(DVec3::new(SPEED, 0.0, 0.0), towards_observer);
    let expected = 1.5_f64.sqrt();
    anyhow::ensure!(
        (approaching - expected).abs() < 1e-12 && (receding - 1.0 / expected).abs() < 1e-12,
        "Doppler factors {approaching} and {receding} are not √(3/2) and its inverse"
    );

    let mut canvas = Canvas::new(1000, 620, WHITE);
    let axes = Axes {
        area: (100.0, 70.0, 960.0, 540.0),
        x_range: LAMBDA_RANGE_NM,
        y_range: (0.0, 90.0),
    };
    shade_visible_band(&mut canvas, &axes);
    for edge in [VISIBLE_NM.0, VISIBLE_NM.1] {
        let (px, top) = axes.to_px(edge, axes.y_range.1);
        let (_, bottom) = axes.to_px(edge, axes.y_range.0);
        dashed_line(&mut canvas, (px, top), (px, bottom), GREY);
    }
    let (band_centre, band_bottom) = axes.to_px(0.5 * (VISIBLE_NM.0 + VISIBLE_NM.1), 0.0);
    canvas.text_centred(band_centre, band_bottom - 24.0, 14.0, BLACK, "visible");

    // Light grid lines under the curves.
    for y in (10..=80).step_by(10) {
        let (l, py) = axes.to_px(LAMBDA_RANGE_NM.0, f64::from(y));
        let (r, _) = axes.to_px(LAMBDA_RANGE_NM.1, f64::from(y));
        dashed_line(&mut canvas, (l, py), (r, py), GREY);
    }

    let curves = [
        (
            REST_TEMPERATURE_K,
            BLACK,
            "T = 6000 K, at rest (D = 1)".to_string(),
        ),
        (
            approaching * REST_TEMPERATURE_K,
            Rgb([30, 80, 220]),
            format!(
                "approaching at 0.2c: D = √(3/2) = {approaching:.4}, seen as {:.0} K",
                approaching * REST_TEMPERATURE_K
            ),
        ),
        (
            receding * REST_TEMPERATURE_K,
            Rgb([200, 30, 30]),
            format!(
                "receding at 0.2c: D = 1/√(3/2) = {receding:.4}, seen as {:.0} K",
                receding * REST_TEMPERATURE_K
            ),
        ),
    ];
    for (temperature, colour, _) in &curves {
        let points: Vec<(f32, f32)> = (1..=1250)
            .map(|i| {
                let lambda_nm = f64::from(i) * 2.0;
                let radiance = planck_radiance(lambda_nm * 1e-9, *temperature) / RADIANCE_UNIT;
                axes.to_px(lambda_nm, radiance)
            })
            .collect();
        canvas.polyline(&points, 2.5, *colour);
        // Mark the maximum (Wien's displacement law, b / T).
        let peak_nm = 2.897_771_955e-3 / temperature * 1e9;
        let peak = axes.to_px(
            peak_nm,
            planck_radiance(peak_nm * 1e-9, *temperature) / RADIANCE_UNIT,
        );
        canvas.dot(peak, 4, *colour);
    }

    let x_ticks: Vec<(f64, String)> = (0..=5)
        .map(|i| (f64::from(i) * 500.0, format!("{}", i * 500)))
        .collect();
    let y_ticks: Vec<(f64, String)> = (0..=9)
        .map(|i| (f64::from(i) * 10.0, format!("{}", i * 10)))
        .collect();
    axes.draw(
        &mut canvas,
        &x_ticks,
        &y_ticks,
        "wavelength λ (nm)",
        "spectral radiance L(λ, T) (kW·sr⁻¹·m⁻²·nm⁻¹)",
    );
    canvas.text_centred(
        530.0,
        12.0,
        19.0,
        BLACK,
        "Planck spectra of a 6000 K black body, Doppler-shifted by a motion at 0.2c (Eq. 9, 10)",
    );

    // Legend, top right.
    let (lx, ly) = (470.0, 110.0);
    canvas.fill_rect(lx as i32 - 10, ly as i32 - 12, 480, 118, WHITE);
    canvas.rect_outline(lx as i32 - 10, ly as i32 - 12, 480, 118, GREY);
    for (k, (_, colour, label)) in curves.iter().enumerate() {
        let y = ly + 26.0 * k as f32;
        canvas.line((lx, y + 8.0), (lx + 34.0, y + 8.0), 2.5, *colour);
        canvas.text(lx + 44.0, y, 15.0, BLACK, label);
    }
    canvas.text(
        lx + 44.0,
        ly + 78.0,
        14.0,
        BLACK,
        "dots: maxima at λ = b / T (Wien); band: visible light, 380–780 nm",
    );

    let path = out_dir.join("fig5_doppler_spectra.png");
    canvas.save(&path)?;
    Ok(vec![path])
}

/// Fills the visible band with the colour of monochromatic light at each wavelength: CIE 1931
/// (x̄, ȳ, z̄) → BT.709 (Eq. 12), desaturated into the gamut, normalised to its largest channel,
/// sRGB (Eq. 13), blended with the background so that the curves stay readable; it fades out
/// towards both ends of the band as the eye's sensitivity does.
fn shade_visible_band(canvas: &mut Canvas, axes: &Axes) {
    let (_, top, _, bottom) = axes.area;
    let (x0, _) = axes.to_px(VISIBLE_NM.0, 0.0);
    let (x1, _) = axes.to_px(VISIBLE_NM.1, 0.0);
    let table = cie_1931();
    let peak = table
        .iter()
        .map(|s| xyz_to_linear_rgb(s.tristimulus()).max_element())
        .fold(0.0, f64::max);
    for px in x0.round() as i32..x1.round() as i32 {
        let lambda_nm = axes.x_range.0
            + (f64::from(px) + 0.5 - f64::from(axes.area.0)) / f64::from(axes.area.2 - axes.area.0)
                * (axes.x_range.1 - axes.x_range.0);
        let Some(sample) = table.iter().find(|s| s.wavelength_nm >= lambda_nm.round()) else {
            continue;
        };
        // Out-of-gamut spectral colours: add just enough white to make every channel
        // non-negative (keeps the hue), then normalise the largest channel to 1.
        let raw = xyz_to_linear_rgb(sample.tristimulus());
        let linear = raw - DVec3::splat(raw.min_element().min(0.0));
        let strength = (raw.max_element() / (0.25 * peak)).clamp(0.0, 1.0);
        let hue = linear / linear.max_element().max(1e-12);
        let alpha = 0.65 * strength;
        let rgb = hue
            .to_array()
            .map(|c| srt_color::quantize_8bit(alpha * srgb_encode(c) + (1.0 - alpha)));
        canvas.fill_rect(px, top as i32, 1, (bottom - top) as u32, Rgb(rgb));
    }
}

/// A dashed one-pixel line from `a` to `b`.
fn dashed_line(canvas: &mut Canvas, a: (f32, f32), b: (f32, f32), colour: Rgb<u8>) {
    let length = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let dashes = (length / 8.0).floor() as i32;
    for k in (0..dashes).step_by(2) {
        let s = k as f32 / dashes as f32;
        let e = (k + 1) as f32 / dashes as f32;
        let p = |t: f32| (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
        canvas.line(p(s), p(e), 1.0, colour);
    }
}
