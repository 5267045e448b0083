//! End-to-end tests of the `srt` program: it renders, lists scenes, and meets bad input with one
//! clear message, exit code 2, no panic and no (half-)written or destroyed output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn srt(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_srt"))
        .args(args)
        .current_dir(dir)
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
        )
        .output()
        .expect("srt runs")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A fresh temporary folder.
fn folder() -> tempfile::TempDir {
    tempfile::tempdir().expect("temporary folder")
}

/// Asserts a clean user-facing failure: exit code 2, an `error:` line mentioning every word of
/// `mentions`, no panic.
fn assert_clean_failure(output: &Output, mentions: &[&str]) {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(2), "exit code; stderr:\n{err}");
    assert!(err.contains("error:"), "no error line:\n{err}");
    assert!(!err.contains("panicked"), "panic:\n{err}");
    for word in mentions {
        assert!(
            err.contains(word),
            "message does not mention {word:?}:\n{err}"
        );
    }
}

#[test]
fn renders_a_builtin_scene_on_the_cpu_and_says_where() {
    let dir = folder();
    let output = srt(
        &[
            "render",
            "fig4",
            "--backend",
            "cpu",
            "--width",
            "64",
            "--height",
            "36",
            "-o",
            "out.png",
        ],
        dir.path(),
    );
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(String::from_utf8_lossy(&output.stdout).contains("wrote out.png"));
    let image = image::open(dir.path().join("out.png"))
        .expect("a PNG was written")
        .to_rgb8();
    assert_eq!(image.dimensions(), (64, 36));
    assert!(
        image.pixels().any(|p| p.0 != [0, 0, 0]),
        "the cube is visible"
    );
}

#[test]
fn writes_linear_exr_and_numbered_animation_frames() {
    let dir = folder();
    let common = ["--backend", "cpu", "--width", "32", "--height", "18"];
    let output = srt(
        &[&["render", "fig4", "-o", "lin.exr"], &common[..]].concat(),
        dir.path(),
    );
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(image::open(dir.path().join("lin.exr")).is_ok());
    let output = srt(
        &[
            &[
                "render", "fig4", "-o", "anim.png", "--frames", "3", "--t0", "4.4", "--t1", "5.66",
            ],
            &common[..],
        ]
        .concat(),
        dir.path(),
    );
    assert!(output.status.success(), "{}", stderr(&output));
    for k in 0..3 {
        assert!(dir.path().join(format!("anim_{k:04}.png")).exists());
    }
}

#[test]
fn lists_builtin_scenes() {
    let output = srt(&["scenes"], Path::new("."));
    let text = String::from_utf8_lossy(&output.stdout);
    for name in ["fig10-cube50", "fig10-cube200", "fig7", "fig4", "teaser"] {
        assert!(text.contains(name), "{name} missing from:\n{text}");
    }
}

#[test]
fn superluminal_velocity_is_refused() {
    let dir = folder();
    let output = srt(
        &[
            "render",
            "fig4",
            "--backend",
            "cpu",
            "--beta",
            "0,1.2,0",
            "-o",
            "x.png",
        ],
        dir.path(),
    );
    assert_clean_failure(&output, &["--beta", "speed"]);
    assert!(!dir.path().join("x.png").exists());
}

#[test]
fn unknown_scene_names_and_bad_extensions_are_refused() {
    let dir = folder();
    assert_clean_failure(
        &srt(&["render", "no-such-scene"], dir.path()),
        &["no-such-scene", "srt scenes"],
    );
    std::fs::write(dir.path().join("model.xyz"), "1 2 3").unwrap();
    assert_clean_failure(
        &srt(&["render", "model.xyz"], dir.path()),
        &["model.xyz", ".toml"],
    );
}

#[test]
fn malformed_and_empty_models_name_the_file() {
    let dir = folder();
    std::fs::write(dir.path().join("broken.glb"), b"glTF garbage").unwrap();
    assert_clean_failure(
        &srt(
            &["render", "broken.glb", "--backend", "cpu", "-o", "o.png"],
            dir.path(),
        ),
        &["broken.glb"],
    );
    std::fs::write(dir.path().join("empty.stl"), b"").unwrap();
    assert_clean_failure(
        &srt(
            &["render", "empty.stl", "--backend", "cpu", "-o", "o.png"],
            dir.path(),
        ),
        &["empty.stl"],
    );
    std::fs::write(
        dir.path().join("nan.obj"),
        "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n",
    )
    .unwrap();
    assert_clean_failure(
        &srt(
            &["render", "nan.obj", "--backend", "cpu", "-o", "o.png"],
            dir.path(),
        ),
        &["nan.obj"],
    );
    assert!(!dir.path().join("o.png").exists());
}

#[test]
fn scene_file_errors_name_the_file_line_and_key() {
    let dir = folder();
    let path: PathBuf = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        "[observer]\nposition = [0, 0, 0]\nlook_at = [0, 1, 0]\nfov_y_deg = 40\ncolour = 3\n",
    )
    .unwrap();
    assert_clean_failure(
        &srt(&["render", "bad.toml", "--backend", "cpu"], dir.path()),
        &["bad.toml", "colour", "line 5"],
    );
    std::fs::write(&path, "[observer]\nposition = [0, 0, 0]\nlook_at = [0, 1, 0]\n[[object]]\nshape = { type = \"cube\" }\nbeta = [0.6, 0.9, 0]\n").unwrap();
    assert_clean_failure(
        &srt(&["render", "bad.toml", "--backend", "cpu"], dir.path()),
        &["bad.toml", "speed"],
    );
}

#[test]
fn unwritable_output_fails_before_rendering_and_keeps_existing_files() {
    let dir = folder();
    assert_clean_failure(
        &srt(
            &[
                "render",
                "fig4",
                "--backend",
                "cpu",
                "-o",
                "missing/folder/out.png",
            ],
            dir.path(),
        ),
        &["missing/folder/out.png"],
    );
    assert_clean_failure(
        &srt(
            &["render", "fig4", "--backend", "cpu", "-o", "out.jpg"],
            dir.path(),
        ),
        &["out.jpg", ".png"],
    );
    // A failing render leaves an existing file untouched.
    let keep = dir.path().join("keep.png");
    std::fs::write(&keep, b"precious").unwrap();
    let output = srt(
        &[
            "render",
            "fig4",
            "--backend",
            "cpu",
            "--beta",
            "2,0,0",
            "-o",
            "keep.png",
        ],
        dir.path(),
    );
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(std::fs::read(&keep).unwrap(), b"precious");
    // No temporary files are left behind.
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .filter_map(Result::ok)
        .collect();
    assert_eq!(leftovers.len(), 1, "{leftovers:?}");
}

#[test]
fn polygon_method_needs_the_gpu_backend() {
    let dir = folder();
    assert_clean_failure(
        &srt(
            &["render", "fig4", "--backend", "cpu", "--method", "polygon"],
            dir.path(),
        ),
        &["polygon", "GPU"],
    );
}
