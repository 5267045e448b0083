//! The footprint of one triangle passing in front of the observer at 0.9c (§4.1, Fig. 8): its
//! apparent corners P̄_i, the tangent intersections Ḡ_ij, the rectangle and the convex hull,
//! printed and drawn.
//!
//! `cargo run -p srt-proxy --example footprint [OUT.png]` writes `footprint.png` in the current
//! folder, or OUT.png, and says where: the curved apparent triangle in blue (dense samples of
//! the rest triangle mapped to where they are seen, Eq. 5–8), its corners in dark blue, the
//! tangent intersections in green, the convex hull in red and the rectangle in grey.

use glam::dcamera::rh::proj::directx::perspective;
use glam::dcamera::rh::view::look_at_mat4;
use glam::{DVec2, DVec3};
use image::{Rgb, RgbImage};
use srt_physics::{Event, Frame};
use srt_proxy::{Viewport, footprint, project};

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
        .unwrap_or_else(|| "footprint.png".to_owned());
    // A triangle at rest in S′, which moves along +x at 0.9c; the observer is at the origin of
    // S at ct = 0 and looks at where the triangle's centre is seen.
    let frame = Frame::new(DVec3::new(0.9, 0.0, 0.0), DVec3::ZERO)?;
    let observer = Event::new(0.0, DVec3::ZERO);
    let triangle = [
        DVec3::new(-1.5, -1.0, -2.0),
        DVec3::new(1.5, -0.6, -2.6),
        DVec3::new(-0.2, 1.4, -1.6),
    ];
    let viewport = Viewport {
        width: 600.0,
        height: 600.0,
    };
    let centre = frame.apparent_position((triangle[0] + triangle[1] + triangle[2]) / 3.0, observer);
    let view_projection = perspective(40f64.to_radians(), 1.0, 0.01, 100.0)
        * look_at_mat4(observer.position, centre, DVec3::Y);

    let fp = footprint(&frame, triangle, observer, view_projection, viewport);
    println!("apparent corners P:        {:.1?}", fp.corners);
    println!("tangent intersections G:   {:.1?}", fp.tangent_points);
    println!(
        "rectangle:                 {:.1?} to {:.1?}",
        fp.rect.min, fp.rect.max
    );
    println!(
        "convex hull ({} points):    {:.1?}",
        fp.hull_len,
        fp.hull_points()
    );

    let mut image = RgbImage::from_pixel(600, 600, Rgb([255, 255, 255]));
    let mut dot = |p: DVec2, colour: [u8; 3], radius: i64| {
        for dy in -radius..=radius {
            for dx in -radius..=radius {
                let (x, y) = (p.x.floor() as i64 + dx, p.y.floor() as i64 + dy);
                if (0..600).contains(&x) && (0..600).contains(&y) {
                    image.put_pixel(x as u32, y as u32, Rgb(colour));
                }
            }
        }
    };
    // The apparent triangle: rest-frame points u, v on a 1000 × 1000 grid, seen where R maps them.
    let mut outside = 0;
    for i in 0..=1000 {
        for j in 0..=1000 - i {
            let (u, v) = (f64::from(i) / 1000.0, f64::from(j) / 1000.0);
            let rest =
                triangle[0] + u * (triangle[1] - triangle[0]) + v * (triangle[2] - triangle[0]);
            let seen = frame.apparent_position(rest, observer);
            if let Some(pixel) = project(view_projection, viewport, seen) {
                outside += usize::from(!fp.hull_contains(pixel, 1e-6));
                dot(pixel, [120, 160, 240], 0);
            }
        }
    }
    let hull = fp.hull_points();
    let rect = fp.rect.corners();
    for (points, colour) in [(&rect[..], [150, 150, 150]), (hull, [220, 40, 40])] {
        for k in 0..points.len() {
            let (a, b) = (points[k], points[(k + 1) % points.len()]);
            for s in 0..=1000 {
                dot(a.lerp(b, f64::from(s) / 1000.0), colour, 0);
            }
        }
    }
    fp.corners.iter().for_each(|&p| dot(p, [20, 40, 140], 3));
    fp.tangent_points
        .iter()
        .for_each(|&p| dot(p, [30, 150, 60], 3));
    image.save(&path)?;
    println!(
        "{outside} of the apparent triangle's samples lie outside the hull (it is conservative)"
    );
    println!("wrote {path}");
    Ok(())
}
