//! Fig. 8 of the paper: one apparent (curved) triangle with its projected corners P̄_i, the
//! paper's chord points Q̄_ij, the tangent intersections Ḡ_ij, the window-aligned rectangle and
//! the convex hull footprint, all computed by `srt-proxy`.

use std::path::{Path, PathBuf};

use glam::dcamera::rh::proj::directx::perspective;
use glam::dcamera::rh::view::look_at_mat4;
use glam::{DMat4, DVec2, DVec3};
use image::Rgb;
use srt_physics::{Event, Frame};
use srt_proxy::{Footprint, PAPER_EPSILON, Viewport, chord_point, footprint, project};

use crate::plot::{BLACK, Canvas, GREY, WHITE};

/// The figure's triangle and camera: a triangle passing close in front of the observer at 0.9c,
/// strongly curved by aberration.
struct Setup {
    frame: Frame,
    observer: Event,
    triangle: [DVec3; 3],
    viewport: Viewport,
    view_projection: DMat4,
}

impl Setup {
    fn new() -> anyhow::Result<Self> {
        let frame = Frame::new(DVec3::new(0.9, 0.0, 0.0), DVec3::ZERO)?;
        let observer = Event::new(0.0, DVec3::ZERO);
        let triangle = [
            DVec3::new(-1.5, -1.0, -2.0),
            DVec3::new(1.5, -0.6, -2.6),
            DVec3::new(-0.2, 1.4, -1.6),
        ];
        let centroid = (triangle[0] + triangle[1] + triangle[2]) / 3.0;
        let aim = frame.apparent_position(centroid, observer);
        Ok(Self {
            frame,
            observer,
            triangle,
            viewport: Viewport {
                width: 1000.0,
                height: 1000.0,
            },
            view_projection: perspective(100f64.to_radians(), 1.0, 0.01, 100.0)
                * look_at_mat4(observer.position, aim, DVec3::Y),
        })
    }

    /// Where the rest point `rest` of the triangle is seen on the screen, if in front.
    fn seen(&self, rest: DVec3) -> Option<DVec2> {
        let apparent = self.frame.apparent_position(rest, self.observer);
        project(self.view_projection, self.viewport, apparent)
    }
}

/// Writes `fig8_footprint.png`.
pub fn write(out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let setup = Setup::new()?;
    let fp = footprint(
        &setup.frame,
        setup.triangle,
        setup.observer,
        setup.view_projection,
        setup.viewport,
    );
    anyhow::ensure!(
        !fp.whole_screen,
        "the figure's triangle must be in front of the camera"
    );

    // Fit the rectangle (plus a margin) into the canvas.
    let (width, height) = (900u32, 760u32);
    let margin = 70.0;
    let size = fp.rect.max - fp.rect.min;
    let scale = ((f64::from(width) - 2.0 * margin) / size.x)
        .min((f64::from(height) - 2.0 * margin - 40.0) / size.y);
    let to_canvas = |p: DVec2| {
        let q = (p - fp.rect.min) * scale + DVec2::new(margin, margin + 40.0);
        (q.x as f32, q.y as f32)
    };
    let mut canvas = Canvas::new(width, height, WHITE);
    canvas.text(
        20.0,
        12.0,
        20.0,
        BLACK,
        "Fig. 8: footprint of an apparent triangle (β = 0.9c along x)",
    );
    let edge_colour = Rgb([20, 60, 170]);
    draw_apparent_triangle(&mut canvas, &setup, &to_canvas, edge_colour);

    // Rectangle and hull.
    let rect = [
        fp.rect.min,
        DVec2::new(fp.rect.max.x, fp.rect.min.y),
        fp.rect.max,
        DVec2::new(fp.rect.min.x, fp.rect.max.y),
    ];
    canvas.polygon_outline(&rect.map(to_canvas), 1.0, GREY);
    let hull: Vec<(f32, f32)> = fp.hull_points().iter().map(|&p| to_canvas(p)).collect();
    let hull_colour = Rgb([200, 40, 40]);
    canvas.polygon_outline(&hull, 2.0, hull_colour);

    let tangent_colour = Rgb([40, 150, 60]);
    draw_tangents(&mut canvas, &setup, &fp, &to_canvas, tangent_colour);
    for (i, &p) in fp.corners.iter().enumerate() {
        let c = to_canvas(p);
        canvas.dot(c, 6, edge_colour);
        canvas.text(
            c.0 + 8.0,
            c.1 + 4.0,
            18.0,
            edge_colour,
            &format!("P{}", i + 1),
        );
    }
    let legend_y = height as f32 - 30.0;
    canvas.text(
        20.0,
        legend_y,
        16.0,
        edge_colour,
        "apparent triangle and corners P",
    );
    canvas.text(
        290.0,
        legend_y,
        16.0,
        tangent_colour,
        "exact tangents, intersections G",
    );
    canvas.text(560.0, legend_y, 16.0, hull_colour, "convex hull");
    canvas.text(670.0, legend_y, 16.0, GREY, "rectangle");
    canvas.text(770.0, legend_y, 16.0, BLACK, "• Q (ε=0.01)");
    let path = out_dir.join("fig8_footprint.png");
    canvas.save(&path)?;
    Ok(vec![path])
}

/// The curved triangle, filled by dense samples of the rest triangle mapped through R, and its
/// curved edges in `edge_colour`.
fn draw_apparent_triangle(
    canvas: &mut Canvas,
    setup: &Setup,
    to_canvas: &dyn Fn(DVec2) -> (f32, f32),
    edge_colour: Rgb<u8>,
) {
    let triangle = setup.triangle;
    let fill = Rgb([200, 220, 250]);
    let n = 300;
    for i in 0..=n {
        for j in 0..=n - i {
            let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            let rest =
                triangle[0] + u * (triangle[1] - triangle[0]) + v * (triangle[2] - triangle[0]);
            if let Some(p) = setup.seen(rest) {
                canvas.dot(to_canvas(p), 2, fill);
            }
        }
    }
    for k in 0..3 {
        let (a, b) = (triangle[k], triangle[(k + 1) % 3]);
        let curve: Vec<(f32, f32)> = (0..=300)
            .filter_map(|s| setup.seen(a + (b - a) * (f64::from(s) / 300.0)))
            .map(to_canvas)
            .collect();
        canvas.polyline(&curve, 2.0, edge_colour);
    }
}

/// Tangent lines P̄_i → Ḡ_ij ← P̄_j with their intersections, and the paper's chord points.
fn draw_tangents(
    canvas: &mut Canvas,
    setup: &Setup,
    fp: &Footprint,
    to_canvas: &dyn Fn(DVec2) -> (f32, f32),
    tangent_colour: Rgb<u8>,
) {
    for i in 0..3 {
        let j = (i + 1) % 3;
        let g = to_canvas(fp.tangent_points[i]);
        canvas.line(to_canvas(fp.corners[i]), g, 1.0, tangent_colour);
        canvas.line(to_canvas(fp.corners[j]), g, 1.0, tangent_colour);
        canvas.dot(g, 5, tangent_colour);
        canvas.text(
            g.0 + 8.0,
            g.1 - 20.0,
            18.0,
            tangent_colour,
            &format!("G{}{}", i + 1, j + 1),
        );
        for (from, to) in [(i, j), (j, i)] {
            let q = chord_point(
                &setup.frame,
                setup.triangle[from],
                setup.triangle[to],
                PAPER_EPSILON,
                setup.observer,
            );
            if let Some(q) = project(setup.view_projection, setup.viewport, q) {
                canvas.dot(to_canvas(q), 3, BLACK);
            }
        }
    }
}
