//! The `srt` command-line program: render relativistic scenes and models to images and videos,
//! join frames into videos, tell how an image was made, list the built-in scenes, and open the
//! interactive viewer.
//!
//! Every failure the user can cause (bad files, bad numbers, unwritable paths) ends in one clear
//! message on standard error and exit code 2; nothing is written half-way.

mod caption;
mod cli;
mod encode;
mod exr_range;
mod listing;
mod output;
mod progress;
mod provenance;
mod render;
mod shard;
mod source;

use std::process::ExitCode;

use clap::Parser;

use crate::cli::{Cli, Command};

/// Runs `srt view`.
#[cfg(feature = "viewer")]
fn view(scenes: &[String]) -> anyhow::Result<()> {
    Ok(srt_viewer::run(scenes)?)
}

/// Without the `viewer` feature there is no window.
#[cfg(not(feature = "viewer"))]
fn view(_scenes: &[String]) -> anyhow::Result<()> {
    anyhow::bail!("this srt was built without the `viewer` feature; rebuild with default features")
}

/// Gives the process a private `XDG_RUNTIME_DIR` when it has no valid one (a bare container, a
/// CI job, `sudo`): Mesa's Vulkan device-selection layer connects to Wayland while listing
/// adapters, and libwayland prints "XDG_RUNTIME_DIR is invalid or not set" on every run,
/// successful ones included. The folder is private (0700), empty, and removed when the
/// returned guard drops at the end of `main`.
fn ensure_runtime_dir() -> Option<tempfile::TempDir> {
    if !cfg!(target_os = "linux") {
        return None;
    }
    // libwayland's rule: the variable must hold an absolute path; it must also exist to be
    // useful to anyone else.
    let valid = std::env::var_os("XDG_RUNTIME_DIR")
        .map(std::path::PathBuf::from)
        .is_some_and(|dir| dir.is_absolute() && dir.is_dir());
    if valid {
        return None;
    }
    let dir = tempfile::Builder::new()
        .prefix("srt-runtime-")
        .tempdir()
        .ok()?;
    // SAFETY: this runs first thing in `main`, before any other thread exists, so no other
    // thread can be reading or writing the environment at the same time.
    #[allow(unsafe_code)]
    unsafe {
        std::env::set_var("XDG_RUNTIME_DIR", dir.path());
    }
    Some(dir)
}

/// On SIGINT, SIGTERM or SIGHUP (Ctrl-C, a cluster's time limit, a closed terminal), removes
/// the temporary files of outputs not yet finished ([`srt_video::remove_partial_files`]) and the
/// private `runtime_dir` ([`ensure_runtime_dir`]), whose guard the exit does not drop, and exits
/// with the conventional status 128 + the signal's number: an interrupted render leaves no
/// half-written file and no folder. Without a handler (it cannot be installed) the signals act
/// as before.
#[cfg(unix)]
fn remove_partial_files_on_signals(runtime_dir: Option<std::path::PathBuf>) {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let removed = srt_video::remove_partial_files();
            if removed > 0 {
                eprintln!("interrupted: removed {removed} unfinished output file(s)");
            }
            if let Some(dir) = &runtime_dir {
                let _ = std::fs::remove_dir_all(dir);
            }
            std::process::exit(128 + signal);
        }
    });
}

/// Other systems end the process on their own terms.
#[cfg(not(unix))]
fn remove_partial_files_on_signals(_runtime_dir: Option<std::path::PathBuf>) {}

fn main() -> ExitCode {
    let runtime_dir = ensure_runtime_dir();
    remove_partial_files_on_signals(runtime_dir.as_ref().map(|dir| dir.path().to_owned()));
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or_default() {
        Command::Render(args) => render::run(&args),
        Command::Scenes { show } => source::print_scenes(show.as_deref()),
        Command::View { scenes } => view(&scenes),
        Command::Encode(args) => encode::run(&args),
        Command::Info { image } => provenance::print_info(&image),
    };
    match listing::ends_quietly(result) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::from(2)
        }
    }
}
