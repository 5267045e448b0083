//! Helpers shared by the end-to-end tests: run `srt`, read its output, and check that a failure
//! is a clean one.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `srt` with `args` in `dir`, in the test's own environment: it finds adapters the way a
/// user's `srt` does (`WGPU_BACKEND` picks one where set), so a machine with only llvmpipe's GL
/// runs the GPU tests there instead of skipping them.
pub fn srt(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_srt"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("srt runs")
}

/// Runs `srt` in `dir`, asserts it succeeded and returns its standard output.
pub fn srt_ok(args: &[&str], dir: &Path) -> String {
    let output = srt(args, dir);
    assert!(
        output.status.success(),
        "srt {args:?}:\n{}",
        stderr(&output)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The standard error of a run, as text.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A fresh temporary folder.
pub fn folder() -> tempfile::TempDir {
    tempfile::tempdir().expect("temporary folder")
}

/// Asserts a clean user-facing failure: exit code 2, one `error:` line (bounded in length, the
/// only line besides warnings and notes) mentioning every word of `mentions`, no panic.
pub fn assert_clean_failure(output: &Output, mentions: &[&str]) {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(2), "exit code; stderr:\n{err}");
    assert!(err.contains("error:"), "no error line:\n{err}");
    assert!(!err.contains("panicked"), "panic:\n{err}");
    let message: Vec<&str> = err
        .lines()
        .filter(|line| !line.starts_with("warning:") && !line.starts_with("note:"))
        .collect();
    assert_eq!(message.len(), 1, "the error is not one line:\n{err}");
    assert!(message[0].len() <= 600, "the error is too long:\n{err}");
    for word in mentions {
        assert!(
            err.contains(word),
            "message does not mention {word:?}:\n{err}"
        );
    }
}

/// A named channel of an EXR, as f32 values row-major.
pub fn exr_channel(path: &Path, name: &str) -> Vec<f32> {
    use exr::prelude::{FlatSamples, ReadChannels as _, ReadLayers as _, read};
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .expect("srt's EXR reads back");
    let channel = (image.layer_data.channel_data.list.iter())
        .find(|channel| channel.name.to_string() == name)
        .unwrap_or_else(|| panic!("{} has no channel {name}", path.display()));
    match &channel.sample_data {
        FlatSamples::F32(values) => values.clone(),
        other => panic!("{name} is not f32: {other:?}"),
    }
}

/// The built-in scene `name`, built as `srt render NAME` builds it without options.
pub fn builtin_scene(name: &str) -> srt_scene::Scene {
    srt_scene::SceneSource::resolve(name)
        .unwrap()
        .load(None)
        .unwrap()
        .scene
}
