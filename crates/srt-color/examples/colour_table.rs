//! The paper's Fig. 6 as a PNG: black-body colours from 1000 K to 26 000 K (left to right),
//! scaled by a reflection factor f from 1 to 0 (top to bottom), for the luminance tone map (left
//! table) and the searchlight tone map (right table).
//!
//! `cargo run -p srt-color --example colour_table [OUT.png]` writes `colour_table.png` in the
//! current folder, or OUT.png, and says where.

use image::{Rgb, RgbImage};
use srt_color::{ToneMap, colour_table, quantize_8bit};

/// Width and height of each table in pixels, and the gap between them.
const TABLE: (u32, u32) = (500, 300);
const GAP: u32 = 20;
/// The temperature range of Fig. 6, in kelvin.
const RANGE_K: (f64, f64) = (1000.0, 26_000.0);

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "colour_table.png".to_owned());
    let (width, height) = TABLE;
    let mut image = RgbImage::from_pixel(2 * width + GAP, height, Rgb([255, 255, 255]));
    for (k, tone_map) in ToneMap::ALL.into_iter().enumerate() {
        // Display sRGB (Eq. 10–13 and the tone map), row-major from the top.
        let table = colour_table(
            tone_map,
            RANGE_K.0,
            RANGE_K.1,
            width as usize,
            height as usize,
        );
        let left = k as u32 * (width + GAP);
        for (index, rgb) in table.iter().enumerate() {
            let (x, y) = (index as u32 % width, index as u32 / width);
            let pixel = rgb.map(|c| quantize_8bit(f64::from(c)));
            image.put_pixel(left + x, y, Rgb(pixel));
        }
        println!(
            "{} tone map: T = {} K … {} K left to right, f = 1 … 0 top to bottom",
            tone_map.name(),
            RANGE_K.0,
            RANGE_K.1
        );
    }
    image.save(&path)?;
    println!("wrote {path} (luminance left, searchlight right)");
    Ok(())
}
