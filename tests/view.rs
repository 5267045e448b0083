//! End to end: `srt render --view` draws the three pictures of the fig10 cube moving sideways on
//! the CPU, records the view, and rejects an unknown view cleanly.

use std::path::Path;

use crate::common;

use common::{assert_clean_failure, folder, srt, stderr};

/// Renders fig10-cube50 moving sideways at 0.6c (γ = 1.25) at ct = 8 in `view`, in a wide image
/// (400 × 90) that holds both the cube where it is now and where it is seen; returns the RGB
/// image.
fn render(view: &str, dir: &Path) -> image::RgbImage {
    let name = format!("{view}.png");
    let output = srt(
        &[
            "render",
            "fig10-cube50",
            "--backend",
            "cpu",
            "--width",
            "400",
            "--height",
            "90",
            "--beta",
            "0.6,0,0",
            "--time",
            "8",
            "--view",
            view,
            "-o",
            &name,
        ],
        dir,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    image::open(dir.join(&name)).unwrap().to_rgb8()
}

/// The columns and rows (first, last) of the cube's silhouette, if any is visible.
fn silhouette(image: &image::RgbImage) -> Option<((u32, u32), (u32, u32))> {
    let lit: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0.iter().any(|&c| c > 3))
        .map(|(x, y, _)| (x, y))
        .collect();
    let span =
        |f: fn(&(u32, u32)) -> u32| Some((lit.iter().map(f).min()?, lit.iter().map(f).max()?));
    Some((span(|p| p.0)?, span(|p| p.1)?))
}

#[test]
fn the_measured_cube_is_contracted_and_the_seen_one_lags_behind() {
    let dir = folder();
    let newtonian = render("newtonian", dir.path());
    let measured = render("measured", dir.path());
    let seen = render("seen", dir.path());
    let (n_cols, n_rows) = silhouette(&newtonian).expect("the Newtonian cube is in view");
    let (m_cols, m_rows) = silhouette(&measured).expect("the measured cube is in view");
    let width = |(a, b): (u32, u32)| f64::from(b - a + 1);
    let ratio = width(m_cols) / width(n_cols);
    // Contraction by 1/γ = 0.8 along the motion (the depth seen in perspective blurs it a bit).
    assert!(
        (0.72..0.88).contains(&ratio),
        "width ratio {ratio}: {m_cols:?} vs {n_cols:?}"
    );
    // Nothing changes across the motion, and both are centred on the same place.
    assert!(n_rows.0.abs_diff(m_rows.0) <= 1 && n_rows.1.abs_diff(m_rows.1) <= 1);
    let centre = |(a, b): (u32, u32)| f64::from(a + b) / 2.0;
    assert!((centre(m_cols) - centre(n_cols)).abs() < 4.0);
    // The light now arriving left the cube about 20 units of time ago, when it was 12 units
    // behind: the seen cube lags behind the other two (the cube moves towards smaller columns).
    let (s_cols, _) = silhouette(&seen).expect("the seen cube is in view");
    assert!(
        s_cols.0 > n_cols.1,
        "seen {s_cols:?} lags newtonian {n_cols:?}"
    );
    let info = srt(&["info", "measured.png"], dir.path());
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(
        text.lines()
            .any(|l| l.starts_with("view") && l.ends_with("measured")),
        "{text}"
    );
}

#[test]
fn an_unknown_view_is_a_clean_failure() {
    let dir = folder();
    let output = srt(&["render", "fig4", "--view", "painted"], dir.path());
    // clap's message: the bad value and the possible ones, exit code 2.
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{err}");
    assert!(err.contains("painted") && err.contains("measured") && !err.contains("panicked"));
}

#[test]
fn a_view_keeps_the_time_checks() {
    let dir = folder();
    let output = srt(
        &["render", "fig4", "--view", "measured", "--time", "1e300"],
        dir.path(),
    );
    assert_clean_failure(&output, &["--time"]);
    assert!(!dir.path().join("fig4.png").exists());
}
