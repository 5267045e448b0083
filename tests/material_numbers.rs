//! A material library whose colour reads as NaN (`Kd nan nan nan`, `Kd nan 0.5 0.5`): `srt`
//! says so, naming the MTL file and the line, and draws the model in the default colour instead
//! of black or dimmed.

use crate::common::{folder, srt, stderr};

/// A tetrahedron in front of the default camera with material `m` from `model.mtl`.
const MODEL: &str = "mtllib model.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl m\n\
                     f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// The mean of the picture's pixels (channels 0–255), rendered from `mtl`, with the run's
/// standard error.
fn render(mtl: &str) -> (f64, String) {
    let dir = folder();
    std::fs::write(dir.path().join("model.obj"), MODEL).unwrap();
    std::fs::write(dir.path().join("model.mtl"), mtl).unwrap();
    let out = srt(
        &[
            "render",
            "model.obj",
            "--backend",
            "cpu",
            "--width",
            "48",
            "--height",
            "32",
            "-o",
            "m.png",
        ],
        dir.path(),
    );
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let picture = image::open(dir.path().join("m.png")).unwrap().to_rgb8();
    let sum: f64 = picture.pixels().flat_map(|p| p.0).map(f64::from).sum();
    (sum / (picture.len() as f64), err)
}

#[test]
fn a_non_finite_material_colour_is_named_by_file_and_line_and_the_default_is_drawn() {
    let (white, quiet) = render("newmtl m\nKd 1 1 1\n");
    assert!(!quiet.contains("warning"), "{quiet}");
    // The model shows: a black material gives a darker picture.
    let (black, _) = render("newmtl m\nKd 0 0 0\n");
    assert!(white > black + 1.0, "white {white}, black {black}");
    for bad in ["Kd nan nan nan", "Kd nan 0.5 0.5"] {
        let (mean, err) = render(&format!("# a comment\nnewmtl m\n{bad}\n"));
        let wanted = "model.mtl:3: Kd has a non-finite value (nan); using the default colour";
        let warned =
            (err.lines()).any(|line| line.starts_with("warning:") && line.contains(wanted));
        assert!(warned, "{bad}: {err}");
        // The default colour is white: the same picture as an explicit white material.
        assert!(
            (mean - white).abs() < 1e-9,
            "{bad}: mean {mean}, white {white}"
        );
    }
}
