//! `srt render --aov` at the fastest speeds `f64` can write, for every built-in scene whose
//! bodies spin or thrust: a point moving forward on a body at |β| = 1 − 10⁻¹⁶ moves faster
//! still (its β rounds to |β| = 1), and every channel of every pixel — radiance, display colour
//! and the per-pixel time channels — must still be a finite number.

use crate::common::{exr_channel, folder, srt, stderr};

/// Every channel `--aov` writes into the EXR.
const CHANNELS: [&str; 11] = [
    "R",
    "G",
    "B",
    "display.R",
    "display.G",
    "display.B",
    "emission_ct",
    "proper_time",
    "distance",
    "doppler",
    "object",
];

#[test]
fn spinning_and_thrusting_scenes_at_the_fastest_f64_speeds_have_finite_channels() {
    let dir = folder();
    let edge = "--beta=0.9999999999999999,0,0";
    let diagonal = "--beta=0.5773502691896256,0.5773502691896256,0.5773502691896256";
    let mut bad = Vec::new();
    for scene in ["rolling-wheel", "rocket", "bell"] {
        for beta in [edge, diagonal] {
            let out = srt(
                &[
                    "render",
                    scene,
                    beta,
                    "--backend",
                    "cpu",
                    "--aov",
                    "--width",
                    "160",
                    "--height",
                    "90",
                    "-o",
                    "x.exr",
                ],
                dir.path(),
            );
            assert!(out.status.success(), "{scene} {beta}: {}", stderr(&out));
            let exr = dir.path().join("x.exr");
            for name in CHANNELS {
                let values = exr_channel(&exr, name);
                let count = values.iter().filter(|v| !v.is_finite()).count();
                if count > 0 {
                    bad.push(format!("{scene} {beta}: {count} non-finite in {name}"));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
