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

/// `--set KEY=VALUE` gives a scene file key its value: the picture is byte for byte that of the
/// scene file with the value written in it, and a key or value the file would refuse is refused
/// with the setting named, nothing written.
#[test]
fn set_gives_any_scene_key_as_the_file_would() {
    let dir = folder();
    let shown = srt(&["scenes", "--show", "fig4"], dir.path());
    let edited = String::from_utf8(shown.stdout)
        .expect("UTF-8")
        .replace("fov_y_deg = 35.0", "fov_y_deg = 60.0")
        .replace("beta = [0.0, 0.95, 0.0]", "beta = [0.0, 0.5, 0.0]");
    std::fs::write(dir.path().join("mine.toml"), edited).expect("written");
    let size = ["--backend", "cpu", "--width", "32", "--height", "18"];
    let from_file = srt(
        &[&["render", "mine.toml", "-o", "file.png"][..], &size].concat(),
        dir.path(),
    );
    assert!(from_file.status.success(), "{}", stderr(&from_file));
    let set = [
        "--set",
        "observer.fov_y_deg=60",
        "--set",
        "object.cube.beta=0,0.5,0",
    ];
    let from_set = srt(
        &[&["render", "fig4", "-o", "set.png"][..], &size, &set].concat(),
        dir.path(),
    );
    assert!(from_set.status.success(), "{}", stderr(&from_set));
    let pixels = |name: &str| {
        image::open(dir.path().join(name))
            .expect("an image")
            .to_rgb8()
    };
    assert_eq!(pixels("file.png"), pixels("set.png"));
    let plain = srt(
        &[&["render", "fig4", "-o", "plain.png"][..], &size].concat(),
        dir.path(),
    );
    assert!(plain.status.success(), "{}", stderr(&plain));
    assert_ne!(
        pixels("set.png"),
        pixels("plain.png"),
        "the settings change the picture"
    );
    for (setting, mentions) in [
        (
            "observer.fov=60",
            &["--set observer.fov=60", "unknown field `fov`"][..],
        ),
        ("observer.fov_y_deg=200", &["observer.fov_y_deg", "200"][..]),
        (
            "object.ship.beta=0,0.5,0",
            &["no element named \"ship\""][..],
        ),
    ] {
        let output = srt(
            &["render", "fig4", "--set", setting, "-o", "refused.png"],
            dir.path(),
        );
        assert_clean_failure(&output, mentions);
        assert!(!dir.path().join("refused.png").exists(), "{setting}");
    }
}
