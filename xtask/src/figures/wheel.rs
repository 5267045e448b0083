//! `rolling_wheel.png`: the built-in `rolling-wheel` rolling at 0, 0.5, 0.9 and 0.99c, as seen
//! (the exact CPU reference: spokes bent, the bottom sharp, the top smeared, the wheel turned
//! towards its trailing side) beside its Newtonian picture at the moment the light seen left the
//! axle (the rest shape where it was then, turned as far as it had rolled). For each speed β the
//! wheel's frame moves at β and it spins at ω = β/r, its offset chosen so that the axle is seen
//! straight ahead at ct = 0.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::DVec3;
use image::imageops;
use srt_scene::View;
use srt_scene::builtin::find_builtin;

use super::render_panel;
use crate::plot::{BLACK, Canvas, WHITE};

/// The speeds shown, one row each.
const SPEEDS: [f64; 4] = [0.0, 0.5, 0.9, 0.99];
/// One panel's size.
const PANEL: (u32, u32) = (400, 225);
/// The wheel's axle in its rest frame and its radius.
const AXLE: DVec3 = DVec3::new(0.0, 0.0, 1.0);
const RADIUS: f64 = 1.0;

/// Writes the figure.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let builtin = find_builtin("rolling-wheel").context("rolling-wheel is a built-in scene")?;
    let (width, height) = PANEL;
    let (title, label) = (46, 24);
    let mut canvas = Canvas::new(
        2 * (width + 10) + 90,
        title + SPEEDS.len() as u32 * (height + 10) + label,
        WHITE,
    );
    canvas.text(
        10.0,
        8.0,
        17.0,
        BLACK,
        "rolling-wheel: left as seen at ct = 0 (exact); right the Newtonian picture when that light \
         left the axle",
    );
    for (column, name) in ["seen", "Newtonian"].iter().enumerate() {
        canvas.text_centred(
            90.0 + (column as u32 * (width + 10) + width / 2) as f32,
            (title - 20) as f32,
            15.0,
            BLACK,
            name,
        );
    }
    for (row, &speed) in SPEEDS.iter().enumerate() {
        let mut description = builtin.description();
        let observer = DVec3::from_array(description.observer.position);
        let distance = (observer - AXLE).length();
        for object in &mut description.objects {
            if let Some(spin) = &mut object.spin {
                spin.rate = speed / RADIUS;
                object.beta = [speed, 0.0, 0.0];
                object.offset = [speed * distance, 0.0, AXLE.z];
            }
        }
        let (scene, _) = builtin.build_description(&description)?;
        // The light seen at ct = 0 left the axle at ct = −distance, when it was at x = 0.
        description.observer.ct = -distance;
        let (then, _) = builtin.build_description(&description)?;
        let newtonian = View::Newtonian.apply(&then)?;
        let top = title + row as u32 * (height + 10);
        canvas.text(
            10.0,
            (top + height / 2 - 8) as f32,
            17.0,
            BLACK,
            &format!("{speed}c"),
        );
        for (column, picture) in [&scene, &newtonian].into_iter().enumerate() {
            let panel = render_panel(picture, width, height);
            let left = 90 + column as u32 * (width + 10);
            imageops::replace(canvas.image_mut(), &panel, i64::from(left), i64::from(top));
        }
    }
    let path = out_dir.join("rolling_wheel.png");
    canvas.save(&path)?;
    Ok(vec![path])
}
