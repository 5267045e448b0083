//! End to end: `srt render`'s scene overrides (--effects, --colour, --exposure, --time, --beta,
//! --observer-beta) edit the scene's description and are judged by the scene file's rules; a
//! refused value is named by its option in one line, exit code 2, and nothing is written.

use crate::common;

use common::{assert_clean_failure, folder, srt, stderr};

/// `srt render fig4` on the CPU at 16×8 to `x.png`, with `extra` options.
fn render_fig4(extra: &[&str], dir: &std::path::Path) -> std::process::Output {
    let mut args = vec![
        "render",
        "fig4",
        "--backend",
        "cpu",
        "--width",
        "16",
        "--height",
        "8",
        "-o",
        "x.png",
    ];
    args.extend(extra);
    srt(&args, dir)
}

#[test]
fn refused_overrides_name_their_option() {
    let dir = folder();
    for (extra, mentions) in [
        (
            &["--exposure=-1"][..],
            &["--exposure must be a positive number, got -1.0"][..],
        ),
        (
            &["--colour", "spectral", "--exposure", "nan"],
            &["--exposure must be a positive number, got NaN"],
        ),
        (
            &["--exposure", "2"],
            &["--exposure 2.0 needs spectral colour (--colour spectral)"],
        ),
        (
            &["--observer-beta", "0,1.2,0"],
            &["--observer-beta 0.0,1.2,0.0 is not a valid velocity: speed"],
        ),
        (
            &["--beta", "0,0.5,0", "--observer-beta", "0,0.2,0"],
            &["--beta sets every object's velocity", "--observer-beta"],
        ),
        (
            &["--frames", "2", "--t0", "nan"],
            &["--t0 must be a finite number within ±1e9, got NaN"],
        ),
    ] {
        let output = render_fig4(extra, dir.path());
        assert_clean_failure(&output, mentions);
        assert!(
            stderr(&output).starts_with("error: --"),
            "{}",
            stderr(&output)
        );
    }
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}

#[test]
fn a_moving_scene_observer_refuses_beta() {
    let dir = folder();
    let output = srt(
        &["render", "flythrough", "--beta", "0,0.5,0", "-o", "x.png"],
        dir.path(),
    );
    assert_clean_failure(&output, &["--beta", "moving observer", "flythrough"]);
    assert!(!dir.path().join("x.png").exists());
}

#[test]
fn accepted_overrides_are_what_is_rendered_and_recorded() {
    let dir = folder();
    let output = render_fig4(
        &[
            "--effects",
            "searchlight",
            "--colour",
            "spectral",
            "--exposure",
            "2",
            "--beta",
            "0,0.5,0",
            "--time",
            "1",
        ],
        dir.path(),
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let info = srt(&["info", "x.png"], dir.path());
    let record = String::from_utf8_lossy(&info.stdout);
    for line in [
        "velocities         cube (0.0, 0.5, 0.0)",
        "effects            searchlight",
        "colour             spectral",
        "exposure           2.0",
        "time               1.0",
    ] {
        assert!(record.contains(line), "{line:?} missing from:\n{record}");
    }
}
