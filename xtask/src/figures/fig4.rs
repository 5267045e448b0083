//! Fig. 4 of the paper: photo-objects (apparent shapes, Eq. 8) of a wireframe unit cube moving
//! with β = (0, 0.95, 0), seen from (2, 5, 0.2) with a 35° pinhole camera at ct_obs = 4.4, 5.12
//! and 5.66. Each panel's camera is aimed at the apparent position of the cube's centre at that
//! instant (the paper does not give its viewing direction), with +z up.

use std::path::{Path, PathBuf};

use glam::dcamera::rh::proj::directx::perspective;
use glam::dcamera::rh::view::look_at_mat4;
use glam::{DVec2, DVec3};
use image::Rgb;
use srt_physics::{Event, Frame};
use srt_proxy::{Viewport, project};

use crate::plot::{BLACK, Canvas, GREY, WHITE};

const PANEL: u32 = 420;
const OBSERVER: DVec3 = DVec3::new(2.0, 5.0, 0.2);
const TIMES: [f64; 3] = [4.4, 5.12, 5.66];

/// The twelve edges of the unit cube centred at the origin of S′.
fn cube_edges() -> Vec<(DVec3, DVec3)> {
    let corner = |i: u32| {
        DVec3::new(
            if i & 1 == 0 { -0.5 } else { 0.5 },
            if i & 2 == 0 { -0.5 } else { 0.5 },
            if i & 4 == 0 { -0.5 } else { 0.5 },
        )
    };
    let mut edges = Vec::new();
    for i in 0..8u32 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                edges.push((corner(i), corner(i | bit)));
            }
        }
    }
    edges
}

/// Writes `fig4_photo_objects.png`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let frame = Frame::new(DVec3::new(0.0, 0.95, 0.0), DVec3::ZERO)?;
    let viewport = Viewport {
        width: f64::from(PANEL),
        height: f64::from(PANEL),
    };
    let projection = perspective(35f64.to_radians(), 1.0, 0.01, 100.0);
    let title_height = 60;
    let mut canvas = Canvas::new(3 * PANEL + 40, PANEL + title_height + 50, WHITE);
    canvas.text(
        20.0,
        12.0,
        20.0,
        BLACK,
        "Fig. 4: photo-objects of a unit cube, β = (0, 0.95, 0), observer (2, 5, 0.2), 35° FOV",
    );
    let blue = Rgb([20, 60, 170]);
    for (panel, &ct) in TIMES.iter().enumerate() {
        let observer = Event::new(ct, OBSERVER);
        let centre = frame.apparent_position(DVec3::ZERO, observer);
        let view_projection = projection * look_at_mat4(OBSERVER, centre, DVec3::Z);
        let left = 10.0 + panel as f32 * (PANEL as f32 + 10.0);
        let top = title_height as f32;
        canvas.rect_outline(left as i32, top as i32, PANEL, PANEL, GREY);
        for (a, b) in cube_edges() {
            let samples: Vec<(f32, f32)> = (0..=200)
                .filter_map(|k| {
                    let rest = a + (b - a) * (f64::from(k) / 200.0);
                    let seen = frame.apparent_position(rest, observer);
                    project(view_projection, viewport, seen)
                })
                .map(|p: DVec2| (left + p.x as f32, top + p.y as f32))
                .collect();
            canvas.polyline(&samples, 2.0, blue);
        }
        canvas.text_centred(
            left + PANEL as f32 / 2.0,
            top + PANEL as f32 + 12.0,
            18.0,
            BLACK,
            &format!("ct_obs = {ct}"),
        );
    }
    let path = out_dir.join("fig4_photo_objects.png");
    canvas.save(&path)?;
    Ok(vec![path])
}
